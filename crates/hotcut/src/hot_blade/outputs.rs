//! The files of a `HotBlade` run: robot targets (JSON, CSV) and the RAPID program
//! ([`crate::output::robot`]), the rationalized surfaces (OBJ per block, one glTF for the
//! job), an SVG per block of its worst section (hot-blade paper fig. 15) and a CSV of every
//! fitted section.

use crate::output::chart::{deviation_chart, DeviationLine};
use export::csv::Table;
use export::gltf::{write_gltf, xyz, Material, Mesh, SourceUnits};
use export::svg::{bounds, Legend, Mark, SvgDoc, Viewport};
use hotblade::{BlockResult, Rationalization};
use nalgebra::Vector3;

use super::HotBlade;
use crate::output::robot;
use crate::output::{block_material, deviation_color, Files};
use crate::spec::{OutputSpec, Units};
use crate::task::Finished;
use export::robot::{Targets, TargetsBlock};

type Done<'a> = Finished<'a, HotBlade>;

/// The targets of a run: every block's poses in cutting order, and the blocks' sizes.
pub(super) fn targets(
    cut: &Rationalization,
    blade_length: f64,
    units: Units,
    stiffness: &elastica::Stiffness,
) -> (Targets, Vec<[f64; 3]>) {
    let blocks = cut
        .blocks
        .iter()
        .map(|b| TargetsBlock {
            block: b.report.block,
            origin: b.report.origin,
            rotation: b.rotation,
            poses: b
                .sections
                .iter()
                .map(|s| robot::pose(&s.pose, &s.blade, stiffness))
                .collect(),
        })
        .collect();
    let sizes = cut.blocks.iter().map(|b| b.report.size).collect();
    (robot::targets(units, blade_length, blocks), sizes)
}

/// `targets.json` and `targets.csv`, or the RAPID modules `<job>_T_ROB<n>.mod/.pgf`.
pub(super) fn robot(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let (t, _) = targets(
        &done.run.cut,
        done.params.pipeline.blade.length,
        done.job.units,
        &done.job.stiffness,
    );
    robot::write(files, &t, done.run.cell.as_ref(), &done.job.name, o.kind())
}

/// `surface_block_NNN.obj`: each block's rationalized surface.
pub(super) fn obj(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    for b in &done.run.cut.blocks {
        files.add(format!("surface_block_{:03}.obj", b.report.block), |buf| {
            let mut w = crate::output::obj_writer(6, done.job.units, o);
            if let Some(m) = b.surface_mesh() {
                w.mesh(&format!("block_{}", b.report.block), &m);
            }
            w.write(buf)
        })?;
    }
    Ok(())
}

/// `block_NNN.svg`: each block's worst section.
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let units = done.job.units.symbol();
    for b in &done.run.cut.blocks {
        files.add(format!("block_{:03}.svg", b.report.block), |buf| {
            block_svg(b, &done.job.name, units).write(buf)
        })?;
    }
    Ok(())
}

/// `model.gltf`: blocks as translucent boxes, surfaces coloured by deviation.
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let tol = done.params.pipeline.tolerance_max;
    files.add("model.gltf", |buf| {
        model(
            &done.run.cut,
            tol,
            crate::output::source_units(done.job.units),
            buf,
        )
    })
}

/// `sections.csv`: one row per fitted section.
pub(super) fn csv(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.text("sections.csv", sections_csv(&done.run.cut))
}

fn sections_csv(run: &Rationalization) -> String {
    let mut t = Table::new(
        "block,pose,plane,kind,design_length,fit_length,l2,rms,max,blade_max_abs_curvature,blade_inflections,plane_angle",
    );
    let f = Table::num;
    for b in &run.blocks {
        for (k, sec) in b.sections.iter().enumerate() {
            let row = [
                b.report.block.to_string(),
                (k + 1).to_string(),
                sec.plane.to_string(),
                sec.fit.segment.kind().to_string(),
                f(sec.design.length),
                f(sec.fit.segment.length()),
                f(sec.fit.l2),
                f(sec.fit.rms),
                f(sec.fit.max),
                f(sec.blade.max_abs_curvature),
                sec.blade.inflections.to_string(),
                f(sec.plane_angle),
            ];
            t.row(&row);
        }
    }
    t.finish()
}

fn model(
    run: &Rationalization,
    tol: f64,
    units: SourceUnits<'_>,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let materials = vec![
        block_material(),
        Material::new("surface", [1.0, 1.0, 1.0, 1.0], false),
    ];
    write_gltf("hotcut", &scene(run, tol), &materials, units, buf)
}

/// The meshes of `model.gltf`: per block its box and its rationalized surface, coloured by
/// deviation (`tol` is red).
pub(super) fn scene(run: &Rationalization, tol: f64) -> Vec<Mesh> {
    let mut meshes = Vec::new();
    let g = &run.grid;
    for b in &run.blocks {
        meshes.push(Mesh::from_box(
            format!("block_{}", b.report.block),
            Vector3::from(b.report.origin),
            [g.frame.normal, g.frame.u, g.frame.v],
            b.report.size,
            0,
        ));
        let (verts, faces) = b.surface_grid();
        let colors = b
            .surface
            .iter()
            .flatten()
            .map(|v| deviation_color(v.deviation, tol))
            .collect();
        meshes.push(Mesh {
            name: format!("surface_{}", b.report.block),
            positions: verts.iter().map(xyz).collect(),
            colors: Some(colors),
            indices: faces.iter().flatten().copied().collect(),
            material: 1,
        });
    }
    meshes
}

/// Design section and fitted elastica of the block's worst section (largest L2), with the
/// blade's extension dashed in grey and a scale bar; below, the distance from the design to
/// the fit against arc length, so deviations of hundredths of a millimetre, invisible at
/// the section's scale, can be read.
fn block_svg(b: &BlockResult, job: &str, units: &str) -> SvgDoc {
    const W: f64 = 900.0;
    const H: f64 = 760.0;
    const TOP: f64 = 76.0;
    let mut doc = SvgDoc::new(W, H);
    let Some(sec) = b.sections.get(b.report.worst_section) else {
        return doc;
    };
    let fitted = sec.fit.segment.sample(400).unwrap_or_default();
    let blade = sec.blade.segment.sample(400).unwrap_or_default();
    let (lo, hi) = bounds(
        sec.design
            .points
            .iter()
            .chain(&fitted)
            .chain(&blade)
            .map(|p| (p[0], p[1])),
    );
    let vp = Viewport::fit(lo, hi, (30.0, TOP, W - 60.0, 360.0));
    let r = &b.report;
    doc.text(
        (30.0, 24.0),
        16.0,
        "black",
        &format!(
            "{job} · block {} (row {}, column {}) — worst section: pose {} of {}",
            r.block,
            r.row + 1,
            r.column + 1,
            r.worst_section + 1,
            r.sections
        ),
    );
    doc.text(
        (30.0, 44.0),
        12.0,
        "#444",
        &format!(
            "L2 {:.4} · max distance {} {units} · {} · flags: {}",
            sec.fit.l2,
            crate::output::page::num(sec.fit.max),
            sec.fit.segment.kind(),
            if r.flags.any() { "see report" } else { "none" }
        ),
    );
    doc.legend(
        (30.0, 52.0),
        W - 60.0,
        &[
            Legend::new(Mark::Line, "black", "design section"),
            Legend::new(Mark::Line, "#e01010", "fitted elastica"),
            Legend::new(Mark::Line, "#bbbbbb", "blade extended to its length"),
            Legend::new(Mark::Dot, "#1060e0", "held blade end"),
        ],
    );
    let map = |pts: &[[f64; 2]]| pts.iter().map(|p| vp.map(p[0], p[1])).collect::<Vec<_>>();
    doc.polyline(
        &map(&blade),
        "#bbbbbb",
        1.0,
        Some("blade extended to its length"),
    );
    doc.polyline(
        &map(&sec.design.points),
        "black",
        2.4,
        Some("design section"),
    );
    doc.polyline(&map(&fitted), "#e01010", 1.2, Some("fitted elastica"));
    for e in &sec.blade.ends {
        doc.circle(
            vp.map(e.position[0], e.position[1]),
            3.0,
            "#1060e0",
            Some("held blade end"),
        );
    }
    doc.scale_bar(&vp, (30.0, TOP + 360.0 + 26.0), W - 60.0, units);
    doc.axes_key((W - 110.0, TOP + 360.0 + 44.0), "u", "v (section plane)");
    // the deviation against arc length
    // the fit sampled finely enough that its chords' sag (length² · κ / 8 per chord) stays
    // far below the deviations plotted
    let fine = sec.fit.segment.sample(8000).unwrap_or_default();
    let line = DeviationLine {
        points: &sec.design.points,
        reference: &fine,
        colour: "#e01010",
        label: "distance design → fit".into(),
    };
    let title = |top: f64| {
        format!(
            "deviation along the section, at the design's points: largest {} {units}",
            crate::output::page::num(top)
        )
    };
    deviation_chart(
        &mut doc,
        (90.0, 520.0, W - 130.0, 190.0),
        &[line],
        title,
        (
            &format!("arc length along the design section ({units})"),
            &format!("distance from the design to the fit ({units})"),
        ),
    );
    doc
}
