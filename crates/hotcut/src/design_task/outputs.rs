//! The files of a `Design` run: an SVG per block (design curves, control polygons and
//! their elastica dashed, like the paper's figs. 12/14/15), `model.gltf` (the blocks, the
//! design surface and the elastica surface coloured by its deviation), and the robot files
//! ([`crate::output::robot`]).

use design::cut::CutResult;
use elastica::sweep::frame_quaternion;
use export::gltf::{write_gltf, xyz, Material, Mesh};
use export::robot::{Targets, TargetsBlock};
use nalgebra::{Vector2, Vector3};

use design::assembly::{Block, ResolvedCut};

use super::file::DesignFile;
use super::Design;
use crate::output::robot;
use crate::output::{block_material, deviation_color, Files};
use crate::spec::{OutputSpec, Units};
use crate::task::Finished;

type Done<'a> = Finished<'a, Design>;

/// The targets of a run: per (cut, block) pair in the robots' `order`
/// ([`design::assembly::robot_order`]; numbered 1, 2, … in it) the poses on every cutting plane,
/// the block's frame having its x-axis along the cut; and the blocks' sizes in those
/// frames.
pub(super) fn targets(
    blocks: &[Block],
    cuts: &[(ResolvedCut, CutResult)],
    order: &[(usize, usize)],
    blade_length: f64,
    units: Units,
    stiffness: &elastica::Stiffness,
) -> (Targets, Vec<[f64; 3]>) {
    let (mut out, mut sizes) = (Vec::new(), Vec::new());
    for (number, &(c, piece)) in order.iter().enumerate() {
        let (r, res) = &cuts[c];
        let f = &r.frame;
        let b = &blocks[r.blocks[piece]];
        let (lo, hi) = (r.faces[piece], r.faces[piece + 1]);
        let origin = f.to_world(r.span.0, &Vector2::new(lo, b.min.z));
        out.push(TargetsBlock {
            block: number + 1,
            origin: origin.into(),
            rotation: frame_quaternion(&f.normal, &f.v),
            poses: res
                .planes
                .iter()
                .map(|p| robot::pose(&p.pieces[piece].pose, &p.pieces[piece].blade, stiffness))
                .collect(),
        });
        sizes.push([r.span.1 - r.span.0, hi - lo, b.max.z - b.min.z]);
    }
    (robot::targets(units, blade_length, out), sizes)
}

/// `targets.json` and `targets.csv`, or the RAPID modules.
pub(super) fn robot(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let (t, _) = targets(
        &done.run.blocks,
        &done.run.cuts,
        &done.run.order,
        done.params.blade.length,
        done.job.units,
        &done.job.stiffness,
    );
    robot::write(files, &t, done.run.cell.as_ref(), &done.job.name, o.kind())
}

/// `block_<id>.svg` (`block_<id>_<cut>.svg` for a block cut several times): the cut's
/// piece in the block at every station: design curve (black), control polygon (grey),
/// elastica (red, dashed), blade extension (light grey), over the block's outline.
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let units = done.job.units.symbol();
    let n = done.params.points;
    for (r, res) in &done.run.cuts {
        for (piece, &k) in r.blocks.iter().enumerate() {
            let b = &done.run.blocks[k];
            let doc = super::drawing::block_svg(b, r, res, piece, n, &done.job.name, units);
            let name = drawing_name(&b.id, &r.id, done.run.multi[k].cuts.len());
            files.add(name, |buf| doc.write(buf))?;
        }
    }
    Ok(())
}

/// The drawing of block `block` in cut `cut`, the block lying in `cuts` cuts: a block cut
/// several times gets one drawing per cut.
fn drawing_name(block: &str, cut: &str, cuts: usize) -> String {
    if cuts > 1 {
        format!("block_{}_{}.svg", file_name(block), file_name(cut))
    } else {
        format!("block_{}.svg", file_name(block))
    }
}

/// Every drawing [`svg`] writes for design `d` with blocks `blocks`, in cut order.
pub(super) fn drawing_names(d: &DesignFile, blocks: &[Block]) -> Vec<String> {
    let mut through: std::collections::HashMap<&str, usize> = std::collections::HashMap::new();
    for c in &d.cuts {
        for b in &c.blocks {
            *through.entry(b.as_str()).or_default() += 1;
        }
    }
    let known: std::collections::HashSet<&str> = blocks.iter().map(|b| b.id.as_str()).collect();
    let mut out = Vec::new();
    for c in &d.cuts {
        for b in c.blocks.iter().filter(|b| known.contains(b.as_str())) {
            out.push(drawing_name(b, &c.id, through[b.as_str()]));
        }
    }
    out
}

/// A block id as a file name: letters, digits, `-` and `_` kept, anything else `_`.
fn file_name(id: &str) -> String {
    id.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

/// A grid mesh of `rows × cols` points (row-major).
fn grid_indices(rows: usize, cols: usize) -> Vec<u32> {
    let mut out = Vec::with_capacity(6 * rows * cols);
    for i in 0..rows.saturating_sub(1) {
        for j in 0..cols.saturating_sub(1) {
            let a = (i * cols + j) as u32;
            let (b, c, d) = (a + 1, a + cols as u32, a + cols as u32 + 1);
            out.extend([a, b, d, a, d, c]);
        }
    }
    out
}

/// `model.gltf`: the blocks as translucent boxes; per cut and block the design surface
/// (grey) and the elastica surface coloured by its distance to the design at equal arc
/// length (blue 0, green half the job's `tolerance.max`, red at or beyond it); a block cut
/// several times shows its top instead, the lower envelope of its cuts (design grey,
/// elastica coloured by the height difference).
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let materials = vec![
        block_material(),
        Material::new("design", [0.8, 0.8, 0.8, 1.0], false),
        Material::new("elastica", [1.0, 1.0, 1.0, 1.0], false),
    ];
    let meshes = scene(done.run, done.params.points, done.job.tolerance.max);
    files.add("model.gltf", |buf| {
        write_gltf(
            "hotcut",
            &meshes,
            &materials,
            crate::output::source_units(done.job.units),
            buf,
        )
    })
}

/// The meshes of `model.gltf` (see [`gltf`]), `n` points per curve, deviations coloured
/// red at `tol`.
pub(super) fn scene(run: &super::DesignRun, n: usize, tol: f64) -> Vec<Mesh> {
    let mut meshes = Vec::new();
    for b in &run.blocks {
        meshes.push(Mesh::from_box(
            format!("block_{}", b.id),
            b.min,
            [Vector3::x(), Vector3::y(), Vector3::z()],
            (b.max - b.min).into(),
            0,
        ));
    }
    for m in &run.multi {
        let Some(e) = &m.envelope else { continue };
        let id = &run.blocks[m.block].id;
        let at = |k: usize, z: f64| [e.points[k][0], e.points[k][1], z];
        meshes.push(Mesh {
            name: format!("envelope_design_{id}"),
            positions: (0..e.points.len()).map(|k| at(k, e.design[k])).collect(),
            colors: None,
            indices: grid_indices(e.grid, e.grid),
            material: 1,
        });
        meshes.push(Mesh {
            name: format!("envelope_elastica_{id}"),
            positions: (0..e.points.len()).map(|k| at(k, e.elastica[k])).collect(),
            colors: Some(
                e.design
                    .iter()
                    .zip(&e.elastica)
                    .map(|(d, h)| deviation_color((d - h).abs(), tol))
                    .collect(),
            ),
            indices: grid_indices(e.grid, e.grid),
            material: 2,
        });
    }
    for (r, res) in &run.cuts {
        for (piece, &k) in r.blocks.iter().enumerate() {
            if run.multi[k].envelope.is_some() {
                // a block cut several times shows its top: the envelope above
                continue;
            }
            let (mut design, mut elastica, mut colors) = (Vec::new(), Vec::new(), Vec::new());
            for c in &res.planes {
                let (d, e) = c.sampled(piece, n);
                for (p, q) in d.iter().zip(&e) {
                    let w = |v: &[f64; 2]| r.frame.to_world(c.offset, &Vector2::new(v[0], v[1]));
                    design.push(xyz(&w(p)));
                    elastica.push(xyz(&w(q)));
                    colors.push(deviation_color((p[0] - q[0]).hypot(p[1] - q[1]), tol));
                }
            }
            let indices = grid_indices(res.planes.len(), n);
            let id = &run.blocks[k].id;
            meshes.push(Mesh {
                name: format!("design_{id}"),
                positions: design,
                colors: None,
                indices: indices.clone(),
                material: 1,
            });
            meshes.push(Mesh {
                name: format!("elastica_{id}"),
                positions: elastica,
                colors: Some(colors),
                indices,
                material: 2,
            });
        }
    }
    meshes
}
