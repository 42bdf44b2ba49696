//! The files of a `BlockSegmentation` run: `blocks.json` (the placed blocks),
//! `blocks.obj` (blocks as boxes), `model.gltf` (model and translucent blocks) and
//! `progress.svg` (blocks and E per iteration, after thesis fig. 3.6).

use blocks::Phase;
use export::gltf::{write_gltf, Material, Mesh};
use export::json::REPORT_DIGITS;
use export::svg::{Legend, Mark, SvgDoc};

use super::BlockSegmentation;
use crate::output::Files;
use crate::spec::OutputSpec;
use crate::task::Finished;

type Done<'a> = Finished<'a, BlockSegmentation>;

/// `blocks.json`: every block's centre, rotation and size.
pub(super) fn blocks_json(
    done: &Done<'_>,
    _: &OutputSpec,
    files: &mut Files,
) -> export::Result<()> {
    let f = super::BlocksFile {
        units: done.job.units,
        blocks: &done.run.segmentation.blocks,
    };
    files.json("blocks.json", &f, REPORT_DIGITS)
}

/// `blocks.obj`: the blocks as boxes.
pub(super) fn obj(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("blocks.obj", |buf| {
        let mut w = crate::output::obj_writer(6, done.job.units, o);
        for (i, b) in done.run.segmentation.blocks.iter().enumerate() {
            w.mesh(&format!("block_{i}"), &b.mesh()?);
        }
        w.write(buf)
    })
}

/// `model.gltf`: the model and its translucent blocks.
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("model.gltf", |buf| {
        let materials = vec![
            Material::new("model", [0.8, 0.8, 0.82, 1.0], false),
            Material::new("block", [0.95, 0.6, 0.2, 0.25], true),
        ];
        let meshes = scene(done.run)?;
        write_gltf(
            "hotcut BlockSegmentation",
            &meshes,
            &materials,
            crate::output::source_units(done.job.units),
            buf,
        )
    })
}

/// The meshes of `model.gltf`: the model, then every block.
pub(super) fn scene(run: &super::BlockSegRun) -> export::Result<Vec<Mesh>> {
    let mut meshes = vec![Mesh::from_trimesh("model", &run.mesh, 0)];
    for (i, b) in run.segmentation.blocks.iter().enumerate() {
        meshes.push(Mesh::from_trimesh(format!("block_{i}"), &b.mesh()?, 1));
    }
    Ok(meshes)
}

/// `progress.svg`: blocks and E per iteration.
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("progress.svg", |buf| {
        progress_svg(&done.run.segmentation, &done.job.name).write(buf)
    })
}

/// Blocks per iteration as a step line, alignment passes marked, the lower bound dashed;
/// a chart with ticks on both axes and a legend.
fn progress_svg(seg: &blocks::Segmentation, job: &str) -> SvgDoc {
    let (w, h) = (640.0, 380.0);
    let (l, t) = (60.0, 60.0);
    let (fw, fh) = (w - 90.0, h - 120.0);
    let mut doc = SvgDoc::new(w, h);
    let last = seg.history.last().map_or(1, |r| r.iteration.max(1)) as f64;
    let top = seg.initial_blocks.max(1) as f64;
    let bottom = (seg.lower_bound as f64).min(seg.final_blocks as f64);
    // Independent scales on the two axes (a chart, not a drawing); a margin of a tenth
    // above and below so the lines do not run on the frame.
    let pad = 0.1 * (top - bottom).max(1.0);
    let (lo, hi) = (0.0, top + pad);
    let map = |it: f64, n: f64| (l + it / last * fw, t + (hi - n) / (hi - lo) * fh);
    let pts: Vec<(f64, f64)> = seg
        .history
        .windows(2)
        .flat_map(|p| {
            let (a, b) = (p[0], p[1]);
            [
                map(a.iteration as f64, a.blocks as f64),
                map(b.iteration as f64, a.blocks as f64),
                map(b.iteration as f64, b.blocks as f64),
            ]
        })
        .collect();
    doc.text(
        (l, 18.0),
        12.0,
        "#000000",
        &format!(
            "{job} · blocks per iteration: {} → {} ({:.1} % fewer); lower bound {}",
            seg.initial_blocks, seg.final_blocks, seg.reduction_percent, seg.lower_bound
        ),
    );
    doc.chart_axes((l, t, fw, fh), (0.0, last), (lo, hi), "iteration", "blocks");
    let lb = seg.lower_bound as f64;
    doc.dashed_polyline(
        &[map(0.0, lb), map(last, lb)],
        "#888888",
        1.0,
        4.0,
        Some("lower bound"),
    );
    if pts.len() >= 2 {
        doc.polyline(&pts, "#1f5fa8", 2.0, Some("blocks"));
    } else if let Some(r) = seg.history.first() {
        doc.circle(map(0.0, r.blocks as f64), 3.0, "#1f5fa8", Some("blocks"));
    }
    for r in seg.history.iter().filter(|r| r.phase == Phase::Align) {
        let title = format!("alignment, iteration {}: {} blocks", r.iteration, r.blocks);
        doc.circle(
            map(r.iteration as f64, r.blocks as f64),
            3.0,
            "#d95f02",
            Some(&title),
        );
    }
    doc.legend(
        (l, h - 26.0),
        fw,
        &[
            Legend::new(Mark::Line, "#1f5fa8", "blocks"),
            Legend::new(Mark::Dot, "#d95f02", "alignment pass"),
            Legend::new(
                Mark::Dashed,
                "#888888",
                "lower bound (model volume / block volume)",
            ),
        ],
    );
    doc
}
