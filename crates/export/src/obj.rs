//! Wavefront OBJ writer: triangle meshes and polylines, floats with a fixed number of
//! decimals, 1-based indices, `o` groups in the order given. OBJ has no units and no up
//! axis, so the header says both: the coordinates are the job's, in its unit, z up.
//! Importers differ: Blender's OBJ import assumes y up unless told "Up Axis: Z"; Rhino
//! reads z up as written; three.js and most game engines assume y up.
//!
//! Entry points: [`ObjWriter`](crate::obj::ObjWriter), [`write_mesh`](crate::obj::write_mesh).

use std::io::Write;

use geom::mesh::TriMesh;
use nalgebra::Vector3;

use crate::{fmt_float, Result, SourceUnits};

/// Which axis of the file is up.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub enum UpAxis {
    /// As hotcut computes: x, y, z with +z up (Rhino, most CAD).
    #[default]
    Z,
    /// Turned for y-up readers (Blender's OBJ import default, three.js): a point
    /// (x, y, z) is written as (x, z, −y), the turn glTF's `z-up` root node makes.
    Y,
}

/// Accumulates named objects and writes them as one OBJ file.
#[derive(Debug, Default, Clone)]
pub struct ObjWriter {
    decimals: usize,
    up: UpAxis,
    text: String,
    next_vertex: usize,
}

impl ObjWriter {
    /// A writer printing coordinates in `units` with `decimals` digits, z up.
    pub fn new(decimals: usize, units: SourceUnits<'_>) -> Self {
        Self::with_up(decimals, units, UpAxis::Z)
    }

    /// A writer printing coordinates in `units` with `decimals` digits, `up` up.
    pub fn with_up(decimals: usize, units: SourceUnits<'_>, up: UpAxis) -> Self {
        let axes = match up {
            UpAxis::Z => "right-handed, +z up as computed (Blender: import with Up Axis Z, Forward Axis Y)",
            UpAxis::Y => "right-handed, +y up: a computed (x, y, z) is written (x, z, -y) (Blender's and three.js's default)",
        };
        Self {
            decimals,
            up,
            text: format!(
                "# written by hotcut\n# units: {} (1 unit = {} m)\n# axes: {axes}\n",
                units.name, units.metres
            ),
            next_vertex: 1,
        }
    }

    fn vertex(&mut self, p: &Vector3<f64>) {
        let d = self.decimals;
        let p = match self.up {
            UpAxis::Z => *p,
            UpAxis::Y => Vector3::new(p.x, p.z, -p.y),
        };
        self.text.push_str(&format!(
            "v {} {} {}\n",
            fmt_float(p.x, d),
            fmt_float(p.y, d),
            fmt_float(p.z, d)
        ));
        self.next_vertex += 1;
    }

    /// Adds a triangle mesh as object `name`.
    pub fn mesh(&mut self, name: &str, mesh: &TriMesh) -> &mut Self {
        self.text.push_str(&format!("o {name}\n"));
        let base = self.next_vertex;
        for v in mesh.vertices() {
            self.vertex(v);
        }
        for f in mesh.faces() {
            self.text.push_str(&format!(
                "f {} {} {}\n",
                base + f[0] as usize,
                base + f[1] as usize,
                base + f[2] as usize
            ));
        }
        self
    }

    /// Adds a polyline (an `l` element) as object `name`.
    pub fn polyline(&mut self, name: &str, points: &[Vector3<f64>]) -> &mut Self {
        if points.len() < 2 {
            return self;
        }
        self.text.push_str(&format!("o {name}\n"));
        let base = self.next_vertex;
        for p in points {
            self.vertex(p);
        }
        let idx: Vec<String> = (0..points.len()).map(|i| (base + i).to_string()).collect();
        self.text.push_str(&format!("l {}\n", idx.join(" ")));
        self
    }

    /// Writes everything added so far.
    ///
    /// # Errors
    /// I/O failures.
    pub fn write(&self, mut w: impl Write) -> Result<()> {
        w.write_all(self.text.as_bytes())?;
        Ok(())
    }
}

/// Writes one mesh in `units` as an OBJ file.
///
/// # Errors
/// I/O failures.
pub fn write_mesh(
    w: impl Write,
    mesh: &TriMesh,
    decimals: usize,
    units: SourceUnits<'_>,
) -> Result<()> {
    let mut o = ObjWriter::new(decimals, units);
    o.mesh("mesh", mesh);
    o.write(w)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn y_up_turns_points_as_gltf_does() {
        let mut o = ObjWriter::with_up(3, SourceUnits::METRE, UpAxis::Y);
        o.polyline("p", &[Vector3::new(1.0, 2.0, 3.0), Vector3::zeros()]);
        let mut buf = Vec::new();
        o.write(&mut buf).unwrap();
        let s = String::from_utf8(buf).unwrap();
        assert!(s.contains("+y up"), "{s}");
        assert!(s.contains("\nv 1 3 -2\n"), "{s}");
    }

    #[test]
    fn writes_mesh_and_polyline() {
        let m = TriMesh::try_new(
            vec![Vector3::zeros(), Vector3::x(), Vector3::new(0.0, 1.0, 0.5)],
            vec![[0, 1, 2]],
        )
        .unwrap();
        let mut o = ObjWriter::new(3, SourceUnits::METRE);
        o.mesh("m", &m)
            .polyline("p", &[Vector3::zeros(), Vector3::new(1.0 / 3.0, 0.0, 0.0)]);
        let mut buf = Vec::new();
        o.write(&mut buf).unwrap();
        let s = String::from_utf8(buf).unwrap();
        assert_eq!(
            s,
            "# written by hotcut\n# units: Metre (1 unit = 1 m)\n# axes: right-handed, +z up as computed (Blender: import with Up Axis Z, Forward Axis Y)\no m\nv 0 0 0\nv 1 0 0\nv 0 1 0.5\nf 1 2 3\no p\nv 0 0 0\nv 0.333 0 0\nl 4 5\n"
        );
        // the written mesh reads back
        let dir = std::env::temp_dir().join(format!("hotcut-obj-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("m.obj");
        let mut f = std::fs::File::create(&path).unwrap();
        write_mesh(&mut f, &m, 6, SourceUnits::METRE).unwrap();
        drop(f);
        let back = TriMesh::load_obj(&path).unwrap();
        assert_eq!(back.faces().len(), 1);
        std::fs::remove_dir_all(&dir).ok();
    }
}
