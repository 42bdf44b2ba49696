//! The files of a `FacadeSegmentation` run: `segmentation.svg` (after thesis figs. 5.11,
//! 5.14, 5.17), `model.gltf` (pieces in colours, their blocks), `segmentation.obj` (the
//! section parts of every piece), `sections.csv` (one row per part) and the robot files
//! shared with `HotBlade`.

use export::csv::Table;
use export::gltf::{write_gltf, xyz, Material, Mesh, SourceUnits};
use export::obj::ObjWriter;
use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};
use facade_seg::Piece;
use nalgebra::Vector3;

use super::report::SegmentationReport;
use super::{FacadeSegmentation, SegmentationRun};
use crate::output::robot;
use crate::output::{block_material, Files};
use crate::spec::{OutputSpec, Units};
use crate::task::Finished;
use export::robot::{Targets, TargetsBlock};

/// Piece colours, cycled by piece id (a qualitative palette readable in print).
const PALETTE: [[f32; 3]; 10] = [
    [0.55, 0.76, 0.96],
    [0.99, 0.75, 0.44],
    [0.60, 0.87, 0.54],
    [0.98, 0.60, 0.60],
    [0.79, 0.70, 0.84],
    [0.99, 0.99, 0.60],
    [0.69, 0.87, 0.90],
    [0.90, 0.75, 0.60],
    [0.80, 0.92, 0.77],
    [0.99, 0.80, 0.90],
];

/// Points each section part is sampled at in the drawings and meshes.
const DRAW_SAMPLES: usize = 24;

fn colour(id: usize) -> [f32; 3] {
    PALETTE[(id + PALETTE.len() - 1) % PALETTE.len()]
}

fn hex(c: [f32; 3]) -> String {
    let b = |v: f32| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", b(c[0]), b(c[1]), b(c[2]))
}

type Done<'a> = Finished<'a, FacadeSegmentation>;

/// The robot targets: one "block" per posed piece, its poses in cutting order; and the
/// pieces' block sizes.
pub(super) fn targets(
    run: &SegmentationRun,
    blade_length: f64,
    units: Units,
    stiffness: &elastica::Stiffness,
) -> export::Result<(Targets, Vec<[f64; 3]>)> {
    let mut blocks = Vec::new();
    let mut sizes = Vec::new();
    for p in run.posed.iter().filter(|p| !p.parts.is_empty()) {
        let Some(piece) = run.segmentation.pieces.iter().find(|q| q.id == p.id) else {
            return Err(export::ExportError::Data(format!(
                "posed piece {} is not in the segmentation",
                p.id
            )));
        };
        sizes.push(piece.block.size);
        blocks.push(TargetsBlock {
            block: p.id,
            origin: piece.block.origin,
            rotation: p.rotation,
            poses: p
                .parts
                .iter()
                .map(|q| robot::pose(&q.pose, &q.blade, stiffness))
                .collect(),
        });
    }
    Ok((robot::targets(units, blade_length, blocks), sizes))
}

/// `targets.json` and `targets.csv`, or the RAPID modules `<job>_T_ROB<n>.mod/.pgf`.
pub(super) fn robot(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let (t, _) = targets(
        done.run,
        done.params.blade.length,
        done.job.units,
        &done.job.stiffness,
    )?;
    robot::write(files, &t, done.run.cell.as_ref(), &done.job.name, o.kind())
}

/// `segmentation.svg`.
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let units = done.job.units.symbol();
    files.add("segmentation.svg", |buf| {
        plan_svg(done.run, done.report, units).write(buf)
    })
}

/// `model.gltf`.
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("model.gltf", |buf| {
        model(done.run, crate::output::source_units(done.job.units), buf)
    })
}

/// `segmentation.obj`.
pub(super) fn obj(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("segmentation.obj", |buf| {
        parts_obj(
            done.run,
            crate::output::obj_writer(6, done.job.units, o),
            buf,
        )
    })
}

/// `sections.csv`.
pub(super) fn csv(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.text("sections.csv", parts_csv(done.report))
}

/// Plan view in the facade frame: x along the cut, y across it (`u`); for a horizontal
/// cut through a facade lying in plan this is the view from above. Pieces filled in
/// colours (each reaching half a section spacing beyond its first and last section, where
/// its row's neighbour takes over), sections grey, inflection points red, seams black,
/// blocks dashed.
fn plan_svg(run: &SegmentationRun, r: &SegmentationReport, units: &str) -> SvgDoc {
    const W: f64 = 1000.0;
    const M: f64 = 40.0;
    let f = &run.facade.frame;
    let plan = |p: &Vector3<f64>| (f.normal.dot(p), f.u.dot(p));
    let half = 0.5 * run.facade.spacing();
    let sections: Vec<Vec<(f64, f64)>> = (0..run.facade.sections.len())
        .map(|j| {
            let sec = &run.facade.sections[j];
            (0..=200)
                .map(|m| plan(&run.facade.world(j, sec.length * m as f64 / 200.0)))
                .collect()
        })
        .collect();
    // the viewport holds everything drawn: sections, pieces half a spacing beyond their
    // sections, and the blocks' outlines
    let corners = run.segmentation.pieces.iter().flat_map(|piece| {
        let (d0, u0) = plan(&Vector3::from(piece.block.origin));
        let s = piece.block.size;
        [(d0, u0), (d0 + s[0], u0 + s[1])]
    });
    let (mut lo, mut hi) = bounds(sections.iter().flatten().copied().chain(corners));
    lo.0 -= half;
    hi.0 += half;
    let inner = W - 2.0 * M;
    let h = (inner * (hi.1 - lo.1) / (hi.0 - lo.0).max(1e-9)).clamp(200.0, 1400.0);
    // header: title, counts and verdict, legend; then the plan
    const TOP: f64 = 90.0;
    let mut doc = SvgDoc::new(W, TOP + h + M + 16.0);
    doc.text(
        (M, 22.0),
        16.0,
        "black",
        &format!("{} — {}", r.job, r.settings.algorithm.name()),
    );
    doc.text(
        (M, 42.0),
        12.0,
        "black",
        &format!(
            "{} pieces in {} blocks, {} bands × {} rows: {}",
            r.counts.pieces,
            r.counts.blocks,
            r.counts.bands,
            r.counts.rows,
            if r.counts.all_ok {
                "every constraint met"
            } else {
                "some constraints broken (see report)"
            }
        ),
    );
    doc.legend(
        (M, 50.0),
        inner,
        &[
            Legend::new(Mark::Swatch, "#a6cee3", "piece (one colour each)"),
            Legend::new(Mark::Line, "#777777", "section"),
            Legend::new(Mark::Dot, "#e01010", "inflection"),
            Legend::new(Mark::Line, "#000000", "seam"),
            Legend::new(Mark::Line, "#3050a0", "block"),
            Legend::new(Mark::Line, "#d00000", "piece breaking a constraint"),
        ],
    );
    doc.axes_key(
        (W - M - 150.0, TOP + h + 48.0),
        "along the cut",
        "across the cut",
    );
    let page = (M, TOP, inner, h);
    let vp = Viewport::fit(lo, hi, page);
    doc.scale_bar(&vp, (M, TOP + h + 30.0), inner, units);
    let map = |p: (f64, f64)| vp.map(p.0, p.1);
    for piece in &run.segmentation.pieces {
        // the report's verdicts: the blade fits' approximation included
        let broken = r
            .pieces
            .iter()
            .find(|p| p.id == piece.id)
            .map(|p| broken_constraints(&p.verdicts))
            .unwrap_or_default();
        draw_piece(&mut doc, piece, &broken, &plan, &map, half);
    }
    for (j, pts) in sections.iter().enumerate() {
        let page: Vec<(f64, f64)> = pts.iter().copied().map(map).collect();
        doc.polyline(&page, "#777", 0.5, Some(&format!("section {j}")));
    }
    for (j, sec) in run.facade.sections.iter().enumerate() {
        for &s in &sec.inflections {
            doc.circle(map(plan(&run.facade.world(j, s))), 2.2, "#e01010", None);
        }
    }
    for piece in &run.segmentation.pieces {
        let o = Vector3::from(piece.block.origin);
        let s = piece.block.size;
        let (d0, u0) = plan(&o);
        let corners = [
            (d0, u0),
            (d0 + s[0], u0),
            (d0 + s[0], u0 + s[1]),
            (d0, u0 + s[1]),
            (d0, u0),
        ];
        let pts: Vec<(f64, f64)> = corners.into_iter().map(map).collect();
        doc.polyline(
            &pts,
            "#3050a0",
            0.6,
            Some(&format!("block of piece {}", piece.id)),
        );
    }
    doc
}

/// The constraints a piece's report verdicts break.
fn broken_constraints(v: &facade_seg::constraints::Verdicts) -> Vec<&'static str> {
    [
        (v.dimension, "dimension"),
        (v.approximation != Some(false), "approximation"),
        (v.shape, "shape"),
        (v.blade_strain, "blade strain"),
    ]
    .into_iter()
    .filter_map(|(ok, what)| (!ok).then_some(what))
    .collect()
}

/// A piece in the plan: its region filled in its colour (outlined red when it breaks a
/// constraint), reaching `half` beyond its first and last section, and its part
/// boundaries as seams.
fn draw_piece(
    doc: &mut SvgDoc,
    piece: &Piece,
    broken: &[&str],
    plan: &dyn Fn(&Vector3<f64>) -> (f64, f64),
    map: &dyn Fn((f64, f64)) -> (f64, f64),
    half: f64,
) {
    let n = piece.parts.len();
    if n == 0 {
        return;
    }
    let starts: Vec<(f64, f64)> = piece
        .parts
        .iter()
        .map(|p| plan(&Vector3::from(p.start)))
        .collect();
    let ends: Vec<(f64, f64)> = piece
        .parts
        .iter()
        .map(|p| plan(&Vector3::from(p.end)))
        .collect();
    let shift = |p: (f64, f64), d: f64| (p.0 + d, p.1);
    let mut poly = vec![shift(starts[0], -half)];
    poly.extend(starts.iter().copied());
    poly.push(shift(starts[n - 1], half));
    poly.push(shift(ends[n - 1], half));
    poly.extend(ends.iter().rev().copied());
    poly.push(shift(ends[0], -half));
    let title = format!(
        "piece {} (band {}, row {}): {} sections, {}",
        piece.id,
        piece.band,
        piece.row,
        n,
        if broken.is_empty() {
            "every constraint met".to_string()
        } else {
            format!("breaks {}", broken.join(", "))
        }
    );
    let pts: Vec<(f64, f64)> = poly.into_iter().map(map).collect();
    let stroke = if broken.is_empty() { "none" } else { "#d00000" };
    doc.polygon(&pts, &hex(colour(piece.id)), stroke, 1.5, Some(&title));
    // the part boundaries of the piece, as seams
    for side in [&starts, &ends] {
        let pts: Vec<(f64, f64)> = side.iter().copied().map(map).collect();
        doc.polyline(&pts, "black", 1.2, None);
    }
}

/// Pieces as coloured triangle strips between their consecutive section parts, and their
/// blocks as translucent boxes.
fn model(run: &SegmentationRun, units: SourceUnits<'_>, buf: &mut Vec<u8>) -> export::Result<()> {
    let mut materials = vec![block_material()];
    for (k, c) in PALETTE.iter().enumerate() {
        materials.push(Material {
            name: format!("piece_{k}"),
            color: [c[0], c[1], c[2], 1.0],
            blend: false,
        });
    }
    write_gltf("hotcut", &scene(run), &materials, units, buf)
}

/// The meshes of `model.gltf`: per piece its block and its strip.
pub(super) fn scene(run: &SegmentationRun) -> Vec<Mesh> {
    let mut meshes = Vec::new();
    let n = DRAW_SAMPLES;
    for piece in &run.segmentation.pieces {
        let f = &run.facade.frame;
        meshes.push(Mesh::from_box(
            format!("block_{}", piece.id),
            Vector3::from(piece.block.origin),
            [f.normal, f.u, f.v],
            piece.block.size,
            0,
        ));
        let Some((positions, indices)) = run.facade.piece_strip(piece, n) else {
            continue;
        };
        meshes.push(Mesh {
            name: format!("piece_{}", piece.id),
            positions: positions.iter().map(xyz).collect(),
            colors: None,
            indices,
            material: 1 + (piece.id + PALETTE.len() - 1) % PALETTE.len(),
        });
    }
    meshes
}

/// Every piece's section parts as 3D polylines.
fn parts_obj(run: &SegmentationRun, mut w: ObjWriter, buf: &mut Vec<u8>) -> export::Result<()> {
    for piece in &run.segmentation.pieces {
        for part in &piece.parts {
            w.polyline(
                &format!("piece_{}_section_{}", piece.id, part.plane),
                &run.facade.part_points(part, 4 * DRAW_SAMPLES),
            );
        }
    }
    w.write(buf)
}

/// One row per section part of a piece.
fn parts_csv(report: &SegmentationReport) -> String {
    let mut t = Table::new(
        "piece,row,band,plane,offset,s0,s1,length,inflections,max_abs_curvature,start_x,start_y,start_z,end_x,end_y,end_z,blade_fit_rms,blade_fit_max",
    );
    let f = Table::num;
    for p in &report.pieces {
        for sec in &p.sections {
            let mut row = vec![
                p.id.to_string(),
                p.row.to_string(),
                p.band.to_string(),
                sec.plane.to_string(),
                f(sec.offset),
                f(sec.s[0]),
                f(sec.s[1]),
                f(sec.length),
                sec.inflections.to_string(),
                f(sec.max_abs_curvature),
            ];
            row.extend(sec.start.iter().chain(&sec.end).map(|v| f(*v)));
            match &sec.blade_fit {
                Some(b) => row.extend([f(b.rms), f(b.max)]),
                None => row.extend([String::new(), String::new()]),
            }
            t.row(&row);
        }
    }
    t.finish()
}
