//! glTF 2.0 writer: one self-contained `.gltf` (JSON, buffer embedded as a base64 data
//! URI) holding triangle meshes with optional per-vertex colours and simple PBR materials.
//! glTF's unit is the metre (spec §3.4 "Coordinate System and Units"), so positions given
//! in another unit are scaled to metres as they are written, and the source unit is named
//! in `asset.extras`. They stay z up under a root node that turns them to glTF's y-up
//! convention, so Blender, three.js and every other glTF reader see the job's z as up.

use std::io::Write;

use base64::Engine;
use serde_json::{json, Value};

use crate::Result;

/// A material: base colour (linear RGBA) and whether it is see-through.
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    /// Name.
    pub name: String,
    /// Base colour, linear RGBA in [0, 1].
    pub color: [f32; 4],
    /// Alpha blending on (for translucent boxes).
    pub blend: bool,
}

impl Material {
    /// Material `name` of linear RGBA `color`, alpha-blended when `blend`.
    pub fn new(name: impl Into<String>, color: [f32; 4], blend: bool) -> Self {
        Self {
            name: name.into(),
            color,
            blend,
        }
    }
}

/// A triangle mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Name (also the node's name).
    pub name: String,
    /// Vertex positions, in the source units (written in metres as single precision; the
    /// model's bounds are computed from these, in double precision).
    pub positions: Vec<[f64; 3]>,
    /// Per-vertex linear RGBA colours (same length as `positions`), if any.
    pub colors: Option<Vec<[f32; 4]>>,
    /// Triangles as vertex indices, three per triangle.
    pub indices: Vec<u32>,
    /// Index into the materials.
    pub material: usize,
}

pub use crate::SourceUnits;

/// A position as a mesh holds it.
pub fn xyz(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

impl Mesh {
    /// A triangle mesh of `geom` with one material and no vertex colours.
    pub fn from_trimesh(name: impl Into<String>, m: &geom::mesh::TriMesh, material: usize) -> Self {
        Self {
            name: name.into(),
            positions: m.vertices().iter().map(xyz).collect(),
            colors: None,
            indices: m.faces().iter().flatten().copied().collect(),
            material,
        }
    }

    /// A closed box (the faces of [`geom::mesh::BOX_FACES`]) with min corner `o` and edges
    /// `s` along `axes` (each unit length; corner `i` adds edge `k` when bit `k` of `i` is
    /// set).
    pub fn from_box(
        name: impl Into<String>,
        o: nalgebra::Vector3<f64>,
        axes: [nalgebra::Vector3<f64>; 3],
        s: [f64; 3],
        material: usize,
    ) -> Self {
        let corner = |i: usize| {
            o + axes[0] * if i & 1 != 0 { s[0] } else { 0.0 }
                + axes[1] * if i & 2 != 0 { s[1] } else { 0.0 }
                + axes[2] * if i & 4 != 0 { s[2] } else { 0.0 }
        };
        Self {
            name: name.into(),
            positions: (0..8).map(|i| xyz(&corner(i))).collect(),
            colors: None,
            indices: geom::mesh::BOX_FACES.iter().flatten().copied().collect(),
            material,
        }
    }
}

/// The bounding box `(min, max)` of every position of `meshes`, in their own units
/// (`None` without any position, or with one that is not finite).
pub fn bounds(meshes: &[Mesh]) -> Option<([f64; 3], [f64; 3])> {
    let mut it = meshes.iter().flat_map(|m| &m.positions).copied();
    if it.clone().flatten().any(|v| !v.is_finite()) {
        return None;
    }
    let first = it.next()?;
    let (lo, hi) = it.fold((first, first), |(lo, hi), p| {
        (
            std::array::from_fn(|k| lo[k].min(p[k])),
            std::array::from_fn(|k| hi[k].max(p[k])),
        )
    });
    lo.iter()
        .chain(&hi)
        .all(|v| v.is_finite())
        .then_some((lo, hi))
}

/// Writes the scene.
///
/// ```
/// use export::gltf::{write_gltf, Material, Mesh, SourceUnits};
/// let m = Mesh { name: "tri".into(), positions: vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
///     colors: None, indices: vec![0, 1, 2], material: 0 };
/// let mat = Material { name: "grey".into(), color: [0.5, 0.5, 0.5, 1.0], blend: false };
/// let mut out = Vec::new();
/// // positions in millimetres: written in metres
/// let mm = SourceUnits { name: "Millimetre", metres: 1e-3 };
/// write_gltf("hotcut", &[m], &[mat], mm, &mut out).unwrap();
/// let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
/// assert_eq!(v["asset"]["version"], "2.0");
/// assert_eq!(v["asset"]["extras"]["source_units"], "Millimetre");
/// assert_eq!(v["accessors"][0]["max"][0].as_f64().unwrap() as f32, 0.001f32);
/// ```
///
/// # Errors
/// I/O errors of `w`; [`crate::ExportError::Data`] for a position that is not a finite
/// single-precision number in metres (glTF's accessors are `f32`).
pub fn write_gltf(
    generator: &str,
    meshes: &[Mesh],
    materials: &[Material],
    units: SourceUnits<'_>,
    mut w: impl Write,
) -> Result<()> {
    let mut buffer: Vec<u8> = Vec::new();
    let mut views: Vec<Value> = Vec::new();
    let mut accessors: Vec<Value> = Vec::new();
    let mut gl_meshes: Vec<Value> = Vec::new();
    let mut nodes: Vec<Value> = Vec::new();
    let mut children: Vec<usize> = Vec::new();
    let mut push_view = |bytes: &[u8], target: u32, buffer: &mut Vec<u8>| -> usize {
        while !buffer.len().is_multiple_of(4) {
            buffer.push(0);
        }
        let offset = buffer.len();
        buffer.extend_from_slice(bytes);
        views.push(
            json!({"buffer": 0, "byteOffset": offset, "byteLength": bytes.len(), "target": target}),
        );
        views.len() - 1
    };
    for m in meshes
        .iter()
        .filter(|m| !m.positions.is_empty() && !m.indices.is_empty())
    {
        let mut bytes = Vec::with_capacity(12 * m.positions.len());
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for p in &m.positions {
            for k in 0..3 {
                let v = (p[k] * units.metres) as f32;
                if !v.is_finite() {
                    return Err(crate::ExportError::Data(format!(
                        "glTF: mesh {:?} has a position beyond single precision ({} m): the model is too large to draw",
                        m.name,
                        p[k] * units.metres
                    )));
                }
                bytes.extend_from_slice(&v.to_le_bytes());
                lo[k] = lo[k].min(v);
                hi[k] = hi[k].max(v);
            }
        }
        let pv = push_view(&bytes, 34962, &mut buffer);
        accessors.push(
            json!({"bufferView": pv, "componentType": 5126, "count": m.positions.len(),
            "type": "VEC3", "min": lo, "max": hi}),
        );
        let pos = accessors.len() - 1;
        let mut attributes = json!({"POSITION": pos});
        if let Some(colors) = m.colors.as_ref().filter(|c| c.len() == m.positions.len()) {
            let mut bytes = Vec::with_capacity(16 * colors.len());
            for c in colors {
                for v in c {
                    bytes.extend_from_slice(&v.clamp(0.0, 1.0).to_le_bytes());
                }
            }
            let cv = push_view(&bytes, 34962, &mut buffer);
            accessors.push(json!({"bufferView": cv, "componentType": 5126, "count": colors.len(), "type": "VEC4"}));
            attributes["COLOR_0"] = json!(accessors.len() - 1);
        }
        let bytes: Vec<u8> = m.indices.iter().flat_map(|i| i.to_le_bytes()).collect();
        let iv = push_view(&bytes, 34963, &mut buffer);
        accessors.push(json!({"bufferView": iv, "componentType": 5125, "count": m.indices.len(), "type": "SCALAR"}));
        let idx = accessors.len() - 1;
        gl_meshes.push(
            json!({"name": m.name, "primitives": [{"attributes": attributes, "indices": idx,
            "material": m.material.min(materials.len().saturating_sub(1)), "mode": 4}]}),
        );
        nodes.push(json!({"name": m.name, "mesh": gl_meshes.len() - 1}));
        children.push(nodes.len() - 1);
    }
    // z-up to y-up: −90° about x
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let mut root_node = json!({"name": "z-up", "rotation": [-h, 0.0, 0.0, h]});
    if !children.is_empty() {
        root_node["children"] = json!(children);
    }
    nodes.push(root_node);
    let root = nodes.len() - 1;
    let mats: Vec<Value> = materials
        .iter()
        .map(|m| {
            let mut v = json!({"name": m.name, "pbrMetallicRoughness": {"baseColorFactor": m.color,
                "metallicFactor": 0.0, "roughnessFactor": 0.8}, "doubleSided": true});
            if m.blend {
                v["alphaMode"] = json!("BLEND");
            }
            v
        })
        .collect();
    let uri = format!(
        "data:application/octet-stream;base64,{}",
        base64::engine::general_purpose::STANDARD.encode(&buffer)
    );
    let mut doc = json!({
        "asset": {"version": "2.0", "generator": generator, "extras": {
            "source_units": units.name,
            "metres_per_source_unit": units.metres,
            "up_axis": "the source's +z, turned to glTF's +y by the root node `z-up`",
        }},
        "scene": 0,
        "scenes": [{"nodes": [root]}],
        "nodes": nodes,
        "meshes": gl_meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": buffer.len(), "uri": uri}],
    });
    if !mats.is_empty() {
        doc["materials"] = json!(mats);
    }
    if gl_meshes_is_empty(&doc) {
        // glTF forbids empty arrays
        for key in ["meshes", "accessors", "bufferViews", "buffers"] {
            if let Some(o) = doc.as_object_mut() {
                o.remove(key);
            }
        }
    }
    serde_json::to_writer(&mut w, &doc)?;
    w.write_all(b"\n")?;
    Ok(())
}

fn gl_meshes_is_empty(doc: &Value) -> bool {
    doc["meshes"].as_array().is_none_or(|a| a.is_empty())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bounds_keep_double_precision() {
        // 1.8 m as single precision reads 1.79999995: the report's bounds must not
        let m = Mesh {
            name: "box".into(),
            positions: vec![[0.1, -0.495, 0.0], [1.8, 0.495, 1234.5678]],
            colors: None,
            indices: vec![0, 1, 0],
            material: 0,
        };
        let (lo, hi) = bounds(std::slice::from_ref(&m)).unwrap();
        assert_eq!(lo, [0.1, -0.495, 0.0]);
        assert_eq!(hi, [1.8, 0.495, 1234.5678]);
        let mut bad = m;
        bad.positions[0][2] = f64::NAN;
        assert_eq!(bounds(&[bad]), None);
    }
}
