//! The files of a `BlockSegmentation` run: `blocks.json` (the placed blocks),
//! `blocks.obj` (blocks as boxes), `model.gltf` (model and translucent blocks) and
//! `progress.svg` (blocks and E per iteration, after thesis fig. 3.6).

use std::rc::Rc;

use blocks::{Phase, Placement};
use export::gltf::{write_gltf, Material, Mesh};
use export::json::{to_json_string, REPORT_DIGITS};
use export::obj::ObjWriter;
use export::svg::SvgDoc;
use geom::mesh::TriMesh;
use serde::Serialize;

use super::BlockSegRun;
use crate::hot_blade::outputs::{f32s, file};
use crate::job::OutputSpec;
use crate::run::Render;

/// The files of output `o`.
pub fn render(run: &Rc<BlockSegRun>, o: &OutputSpec) -> Vec<Render<'static>> {
    let r = run.clone();
    match o {
        OutputSpec::Blocks => vec![file(
            "blocks.json",
            Box::new(move |buf| {
                #[derive(Serialize)]
                struct BlocksFile<'a> {
                    blocks: &'a [Placement],
                }
                let f = BlocksFile {
                    blocks: &r.report.segmentation.blocks,
                };
                buf.extend(to_json_string(&f, REPORT_DIGITS)?.into_bytes());
                Ok(())
            }),
        )],
        OutputSpec::Obj => vec![file("blocks.obj", Box::new(move |buf| obj(&r, buf)))],
        OutputSpec::Gltf => vec![file("model.gltf", Box::new(move |buf| gltf(&r, buf)))],
        OutputSpec::Svg => vec![file(
            "progress.svg",
            Box::new(move |buf| progress_svg(&r).write(buf)),
        )],
        _ => Vec::new(),
    }
}

/// A block as a closed box mesh.
pub(crate) fn block_mesh(p: &Placement) -> export::Result<TriMesh> {
    TriMesh::try_new(
        p.cuboid().corners().to_vec(),
        geom::mesh::BOX_FACES.to_vec(),
    )
    .map_err(|e| export::ExportError::Io(std::io::Error::other(e.to_string())))
}

fn obj(run: &BlockSegRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let mut w = ObjWriter::new(6);
    for (i, b) in run.report.segmentation.blocks.iter().enumerate() {
        w.mesh(&format!("block_{i}"), &block_mesh(b)?);
    }
    w.write(buf)
}

/// A mesh for the glTF writer with one material.
pub(crate) fn gltf_mesh(name: String, m: &TriMesh, material: usize) -> Mesh {
    Mesh {
        name,
        positions: m.vertices().iter().map(f32s).collect(),
        colors: None,
        indices: m.faces().iter().flatten().copied().collect(),
        material,
    }
}

fn gltf(run: &BlockSegRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let materials = vec![
        Material {
            name: "model".into(),
            color: [0.8, 0.8, 0.82, 1.0],
            blend: false,
        },
        Material {
            name: "block".into(),
            color: [0.95, 0.6, 0.2, 0.25],
            blend: true,
        },
    ];
    let mut meshes = vec![gltf_mesh("model".into(), &run.mesh, 0)];
    for (i, b) in run.report.segmentation.blocks.iter().enumerate() {
        meshes.push(gltf_mesh(format!("block_{i}"), &block_mesh(b)?, 1));
    }
    write_gltf("hotcut BlockSegmentation", &meshes, &materials, buf)
}

/// Blocks per iteration as a step line, alignment passes marked, the lower bound dashed.
fn progress_svg(run: &BlockSegRun) -> SvgDoc {
    let seg = &run.report.segmentation;
    let (w, h) = (640.0, 360.0);
    let mut doc = SvgDoc::new(w, h);
    let last = seg.history.last().map_or(1, |r| r.iteration.max(1)) as f64;
    let top = seg.initial_blocks.max(1) as f64;
    let bottom = (seg.lower_bound as f64).min(seg.final_blocks as f64);
    // Independent scales on the two axes (a chart, not a drawing).
    let span = (top - bottom).max(1.0);
    let map = |it: f64, n: f64| {
        (
            60.0 + it / last * (w - 80.0),
            30.0 + (top - n) / span * (h - 80.0),
        )
    };
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
    doc.rect((60.0, 30.0, w - 80.0, h - 80.0), "#999999", "none");
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
    let lb = seg.lower_bound as f64;
    doc.polyline(
        &[map(0.0, lb), map(last, lb)],
        "#888888",
        1.0,
        Some("lower bound"),
    );
    doc.text(
        (60.0, 20.0),
        12.0,
        "#000000",
        &format!(
            "blocks per iteration: {} → {} ({:.1} % fewer); lower bound {}",
            seg.initial_blocks, seg.final_blocks, seg.reduction_percent, seg.lower_bound
        ),
    );
    doc.text(
        (60.0, h - 30.0),
        11.0,
        "#000000",
        &format!("iteration (0 – {last}); orange: alignment passes"),
    );
    doc.text(
        (6.0, map(0.0, top).1 + 4.0),
        11.0,
        "#000000",
        &format!("{}", seg.initial_blocks),
    );
    doc.text(
        (6.0, map(0.0, bottom).1 + 4.0),
        11.0,
        "#000000",
        &format!("{}", bottom),
    );
    doc
}
