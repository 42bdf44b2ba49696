//! The files of a `RuledBlocks` run: `rationalized.obj` (an open surface's slab, the
//! rationalized model and the blocks), `model.gltf` (the rationalized model coloured by its
//! deviation from the model, and the blocks), `blocks.svg` (regions, rulings and blocks in
//! plan), and one program per cut, `block_BB_cut_CC.gcode`, each read back before it is
//! written.

use export::gltf::{write_gltf, Material, Mesh};
use export::svg::{Legend, Mark, SvgDoc, Viewport};
use geom::index::TriangleIndex;
use geom::surface::Surface;
use ruled::wire::{check_program, program_labelled, Labels, Program};

use super::{RuledBlocks, RuledBlocksParams, RuledBlocksRun};
use crate::context::Context;
use crate::error::Result;
use crate::output::Files;
use crate::spec::OutputSpec;
use crate::task::Finished;

type Done<'a> = Finished<'a, RuledBlocks>;

/// The file of block `i`'s cut `k` (0-based in, 1-based in the name).
pub fn program_file(i: usize, k: usize) -> String {
    format!("block_{:02}_cut_{:02}.gcode", i + 1, k + 1)
}

/// Every cut's program (none without a wire): the block mounted in its frame, the
/// header saying how.
///
/// # Errors
/// A program out of the machine's travel or speed, naming the block and the cut.
pub fn programs(
    blocks: &[::ruled_blocks::cuts::BlockPlan],
    p: &RuledBlocksParams,
    job: &Context,
) -> Result<Vec<Vec<Program>>> {
    let (Some(w), Some(m)) = (&p.wire, &p.machine) else {
        return Ok(Vec::new());
    };
    let mut all = Vec::with_capacity(blocks.len());
    for (i, b) in blocks.iter().enumerate() {
        let mut progs = Vec::with_capacity(b.cuts.len());
        for (k, c) in b.cuts.iter().enumerate() {
            // the block stands where every tower point of this cut is at or above the
            // machine's zero: `wire.origin`, moved along and up as far as the wire's slope
            // needs (the header states where)
            let probe = ::ruled_blocks::machine::wire_path(&b.block, i, k, c, w);
            let low = |axis: usize| {
                probe
                    .steps
                    .iter()
                    .flat_map(|s| [s.a[axis], s.b[axis]])
                    .fold(f64::INFINITY, f64::min)
                    / w.mm_per_unit
            };
            let wc = ruled::wire::WireParams {
                origin: [w.origin[0] - low(0).min(0.0), w.origin[1] - low(1).min(0.0)],
                ..w.clone()
            };
            let w = &wc;
            let path = ::ruled_blocks::machine::wire_path(&b.block, i, k, c, w);
            let f = ::ruled_blocks::machine::MachineFrame::new(&b.block, &c.mount);
            let highest = path
                .steps
                .iter()
                .flat_map(|s| [s.a[1], s.b[1]])
                .fold(0.0, f64::max)
                / w.mm_per_unit
                - w.origin[1];
            let top = (2.0 * f.half[2]).max(highest);
            let labels = Labels {
                title: format!(
                    "hotcut ruled blocks {}: block {} cut {}",
                    job.name.chars().take(30).collect::<String>(),
                    i + 1,
                    k + 1
                ),
                cut: format!("block {} cut {}", i + 1, k + 1),
                frame: ::ruled_blocks::machine::mount_lines(
                    i,
                    &c.mount,
                    &b.block,
                    w.mm_per_unit,
                    w.tower_distance,
                ),
            };
            let prog = program_labelled(&path, w, m, top, 0.0, &labels)
                .map_err(|e| job.fail(e.to_string()))?;
            progs.push(prog);
        }
        all.push(progs);
    }
    Ok(all)
}

/// The programs, each read back against the machine first.
pub(super) fn gcode(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let Some(m) = &done.params.machine else {
        return Ok(());
    };
    for (i, progs) in done.run.programs.iter().enumerate() {
        for (k, p) in progs.iter().enumerate() {
            check_program(&p.text, m).map_err(|e| export::ExportError::Data(e.to_string()))?;
            files.text(program_file(i, k), p.text.clone())?;
        }
    }
    Ok(())
}

/// `rationalized.obj`: the model when the task made it (`model`: a height field or B-spline
/// surface closed into its slab; a mesh job's model is its own file), the rationalized model (`rationalized`;
/// per block: `rationalized_<block>`, each block's own), then every block as a box
/// (`block_<block>`).
pub(super) fn obj(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("rationalized.obj", |buf| {
        let mut w = crate::output::obj_writer(6, done.job.units, o);
        if !matches!(done.job.surface, Some(Surface::Mesh(_))) {
            w.mesh("model", &done.run.model);
        }
        match done.run.strategy {
            super::Strategy::WholeModel => {
                w.mesh("rationalized", &done.run.mesh);
            }
            // each block keeps its own rationalization
            super::Strategy::PerBlock => {
                for (i, r) in done.run.per_block.rational.iter().enumerate() {
                    if let Some(r) = r {
                        w.mesh(&format!("rationalized_{}", i + 1), &r.solid.mesh);
                    }
                }
            }
        }
        for (i, b) in done.run.blocks.iter().enumerate() {
            w.mesh(
                &format!("block_{}", i + 1),
                &blocks::Placement::of(&b.block).mesh()?,
            );
        }
        w.write(buf)
    })
}

/// `model.gltf`: the rationalized model coloured by deviation, the blocks.
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("model.gltf", |buf| {
        let materials = vec![
            Material::new("rationalized", [1.0, 1.0, 1.0, 1.0], false),
            Material::new("block cut by its strips", [0.2, 0.7, 0.3, 0.15], true),
            Material::new("block cut to its hull", [0.9, 0.3, 0.2, 0.2], true),
        ];
        write_gltf(
            "hotcut RuledBlocks",
            &scene(done.run)?,
            &materials,
            crate::output::source_units(done.job.units),
            buf,
        )
    })
}

/// The meshes of `model.gltf`: the rationalized model, each vertex coloured by its
/// distance to the model (blue 0 → red at the largest deviation), and every block.
pub(super) fn scene(run: &RuledBlocksRun) -> export::Result<Vec<Mesh>> {
    let r = run;
    let mut m = Mesh::from_trimesh("rationalized", &r.mesh, 0);
    let index = TriangleIndex::new(&run.model);
    let top = r.deviation.max.max(1e-300);
    m.colors = Some(
        r.mesh
            .vertices()
            .iter()
            .map(|p| {
                let d = index.closest_point(p).map_or(0.0, |c| c.distance);
                let t = (d / top).clamp(0.0, 1.0) as f32;
                [
                    0.15 + 0.8 * t,
                    0.35 * (1.0 - t) + 0.1,
                    0.9 * (1.0 - t) + 0.05,
                    1.0,
                ]
            })
            .collect(),
    );
    let mut meshes = vec![m];
    for (i, b) in r.blocks.iter().enumerate() {
        let material = if b.cuttable { 1 } else { 2 };
        meshes.push(Mesh::from_trimesh(
            format!("block_{}", i + 1),
            &blocks::Placement::of(&b.block).mesh()?,
            material,
        ));
    }
    Ok(meshes)
}

const COLOURS: [&str; 6] = [
    "#1f5fa8", "#d95f02", "#1b9e77", "#7570b3", "#e7298a", "#66a61e",
];

/// `blocks.svg`: the plan — every other ruling of every strip (one colour per region) and
/// the blocks' outlines (green: cut by their strips, red: to their hulls), with a legend,
/// the axes and a scale bar. The rulings show each strategy's directions (fig. 4.2).
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let r = done.run;
    // a plan: x right, y up
    let flat = |p: &nalgebra::Vector3<f64>| (p.x, p.y);
    let mut pts: Vec<(f64, f64)> = r.mesh.vertices().iter().map(flat).collect();
    for b in &r.blocks {
        pts.extend(b.block.corners().iter().map(flat));
    }
    let (lo, hi) = export::svg::bounds(pts.into_iter());
    let (w, h) = (760.0, 620.0);
    let vp = Viewport::fit(lo, hi, (30.0, 80.0, w - 60.0, h - 150.0));
    let mut doc = SvgDoc::new(w, h);
    doc.text(
        (10.0, 18.0),
        13.0,
        "#000",
        &format!("{} · ruled strips and blocks, plan", done.job.name),
    );
    doc.text(
        (10.0, 34.0),
        11.0,
        "#000",
        &format!(
            "{:?}: {} region(s), {} block(s); deviation max {:.4} {}",
            r.strategy,
            r.whole.regions.len(),
            r.blocks.len(),
            r.deviation.max,
            done.job.units.symbol()
        ),
    );
    for st in &r.strips {
        let colour = COLOURS[st.region % COLOURS.len()];
        for ru in st.rulings.iter().step_by(2) {
            doc.polyline(
                &[
                    vp.map(flat(&ru.a).0, flat(&ru.a).1),
                    vp.map(flat(&ru.b).0, flat(&ru.b).1),
                ],
                colour,
                0.5,
                None,
            );
        }
    }
    for (i, b) in r.blocks.iter().enumerate() {
        let colour = if b.cuttable { "#1b9e77" } else { "#d02020" };
        let c = b.block.corners();
        // the box's 12 edges
        for a in 0..8usize {
            for z in (a + 1)..8 {
                if (a ^ z).count_ones() == 1 {
                    let (p, q) = (flat(&c[a]), flat(&c[z]));
                    let title = format!("block {}", i + 1);
                    doc.polyline(
                        &[vp.map(p.0, p.1), vp.map(q.0, q.1)],
                        colour,
                        1.0,
                        Some(&title),
                    );
                }
            }
        }
    }
    let mut legend: Vec<Legend<'_>> = (0..r.whole.regions.len().min(COLOURS.len()))
        .map(|k| {
            Legend::new(
                Mark::Line,
                COLOURS[k],
                "rulings of a region (colours repeat)",
            )
        })
        .take(1)
        .collect();
    legend.push(Legend::new(
        Mark::Line,
        "#1b9e77",
        "block cut by its strips",
    ));
    legend.push(Legend::new(Mark::Line, "#d02020", "block cut to its hull"));
    doc.legend((10.0, 44.0), w - 20.0, &legend);
    doc.scale_bar(&vp, (30.0, h - 30.0), w - 60.0, done.job.units.symbol());
    doc.axes_key((w - 80.0, h - 20.0), "x", "y");
    files.add("blocks.svg", |buf| doc.write(buf))
}
