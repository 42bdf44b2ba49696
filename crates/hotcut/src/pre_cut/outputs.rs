//! The files of a `PreCut` run: `precut.json` (the polygons of rulings per section, and
//! the legs' B-splines), `sections.svg` (cross sections with the design curve, the cut
//! polygon and the convex hull, after thesis fig. 2.4), `precut.obj` and `model.gltf`
//! (design surface, each direction's cut surface, the block) and per cut the wire's
//! G-code and CSV.

use export::gltf::{write_gltf, Material, Mesh, SourceUnits};
use export::json::REPORT_DIGITS;
use export::obj::ObjWriter;
use export::svg::{Legend, Mark, SvgDoc, Viewport};
use geom::mesh::TriMesh;
use nalgebra::Vector3;

use super::preview::preview;
use super::{program_file, PreCut, PreCutRun};
use crate::output::Files;
use crate::spec::{OutputKind, OutputSpec};
use crate::task::Finished;

type Done<'a> = Finished<'a, PreCut>;

/// `precut.json`: per direction the polygons of rulings and the legs' B-splines.
pub(super) fn precut_json(
    done: &Done<'_>,
    _: &OutputSpec,
    files: &mut Files,
) -> export::Result<()> {
    let f = super::PreCutFile {
        units: done.job.units,
        directions: &done.run.cut.directions,
    };
    files.json("precut.json", &f, REPORT_DIGITS)
}

/// `sections.svg`: cross sections per direction.
pub(super) fn svg(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("sections.svg", |buf| {
        let names = (done.job.name.as_str(), done.job.units.symbol());
        sections_svg(done.run, &done.params.block, names, buf)
    })
}

/// `precut.obj`: design, cut surfaces, block.
pub(super) fn obj(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("precut.obj", |buf| {
        meshes_obj(
            done.run,
            &done.params.block,
            crate::output::obj_writer(6, done.job.units, o),
            buf,
        )
    })
}

/// `model.gltf`: design, cut surfaces, block.
pub(super) fn gltf(done: &Done<'_>, _: &OutputSpec, files: &mut Files) -> export::Result<()> {
    files.add("model.gltf", |buf| {
        model(
            done.run,
            &done.params.block,
            crate::output::source_units(done.job.units),
            buf,
        )
    })
}

/// The block as a box mesh: its centre ± half its size on each axis.
fn block_box(b: &ruled::Block) -> export::Result<TriMesh> {
    let (lo, hi) = (Vector3::from(b.min), Vector3::from(b.max));
    let (centre, half) = ((lo + hi) / 2.0, (hi - lo) / 2.0);
    let corners = std::array::from_fn(|i| {
        let side = |k: usize| if i & (1 << k) == 0 { -half[k] } else { half[k] };
        centre + Vector3::new(side(0), side(1), side(2))
    });
    Ok(TriMesh::cuboid(corners)?)
}

/// The design surface as a mesh (height fields and splines tessellated).
fn design_mesh(run: &PreCutRun) -> export::Result<TriMesh> {
    Ok(run.surface.to_mesh(DESIGN_GRID)?)
}

/// Grid cells per side of the tessellated design surface.
const DESIGN_GRID: usize = 64;
/// Points across the block per section of a cut surface mesh.
const ACROSS: usize = 40;

fn meshes_obj(
    run: &PreCutRun,
    block: &ruled::Block,
    mut w: ObjWriter,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    w.mesh("design", &design_mesh(run)?);
    for (i, d) in run.cut.directions.iter().enumerate() {
        if let Some(m) = d.surface_mesh(block.max[2], ACROSS) {
            w.mesh(&format!("cut_d{}", i + 1), &m);
        }
    }
    w.mesh("block", &block_box(block)?);
    w.write(buf)
}

/// The meshes of `model.gltf`: the design, each direction's cut surface, the block.
pub(super) fn scene(run: &PreCutRun, block: &ruled::Block) -> export::Result<Vec<Mesh>> {
    let mut meshes = vec![Mesh::from_trimesh("design", &design_mesh(run)?, 0)];
    for (i, d) in run.cut.directions.iter().enumerate() {
        if let Some(m) = d.surface_mesh(block.max[2], ACROSS) {
            meshes.push(Mesh::from_trimesh(format!("cut_d{}", i + 1), &m, 1));
        }
    }
    meshes.push(Mesh::from_trimesh("block", &block_box(block)?, 2));
    Ok(meshes)
}

fn model(
    run: &PreCutRun,
    block: &ruled::Block,
    units: SourceUnits<'_>,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let materials = vec![
        Material::new("design", [0.8, 0.8, 0.82, 1.0], false),
        Material::new("cut", [0.85, 0.2, 0.15, 0.45], true),
        Material::new("block", [0.2, 0.4, 0.9, 0.12], true),
    ];
    let meshes = scene(run, block)?;
    write_gltf("hotcut PreCut", &meshes, &materials, units, buf)
}

/// One file per cut: `wire_dD_cC.gcode` with its preview `wire_dD_cC.svg` (`GCode`), or
/// `wire_dD_cC.csv` (`Csv`), 1-based.
pub(super) fn wire(done: &Done<'_>, o: &OutputSpec, files: &mut Files) -> export::Result<()> {
    let (Some(w), Some(m)) = (&done.params.wire, &done.params.machine) else {
        return Ok(());
    };
    let block = done.params.block;
    let paths = done.run.wires.iter().flatten();
    for (path, program) in paths.zip(done.run.programs.iter().flatten()) {
        let s = &program.summary;
        if o.kind() == OutputKind::GCode {
            // read back: what the machine would do stays within bounds
            ruled::wire::check_program(&program.text, m)
                .map_err(|e| export::ExportError::Data(e.to_string()))?;
            files.text(program_file(s, "gcode"), program.text.clone())?;
            let title = format!(
                "{} · {} · direction {} cut {}",
                done.job.name,
                program_file(s, "gcode"),
                s.direction + 1,
                s.cut + 1
            );
            files.add(program_file(s, "svg"), |buf| {
                preview(
                    path,
                    program,
                    w,
                    m,
                    (block.min[2], block.max[2]),
                    &title,
                    buf,
                )
            })?;
        } else {
            files.text(program_file(s, "csv"), ruled::wire::csv(path, w))?;
        }
    }
    Ok(())
}

/// Sections drawn per direction (evenly spread along the cut).
const PANELS: usize = 5;

/// One row per direction, `PANELS` cross sections each: block outline, design curve
/// (black), convex hull (grey), the cut polygon (red); a legend, and per row the axes and
/// a scale bar in `units`.
fn sections_svg(
    run: &PreCutRun,
    block: &ruled::Block,
    (job, units): (&str, &str),
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let to_err = |e: ruled::PreCutError| export::ExportError::Data(e.to_string());
    let height = ruled::Height::new(&run.surface).map_err(to_err)?;
    let (_, hull) = ruled::volume::hull_top(&height, block, 100).map_err(to_err)?;
    let (pw, ph, pad, left, head) = (260.0, 210.0, 16.0, 70.0, 56.0);
    let rows = run.cut.directions.len();
    let width = left + PANELS as f64 * pw;
    let mut doc = SvgDoc::new(width, rows as f64 * ph + head);
    doc.text(
        (8.0, 18.0),
        13.0,
        "#000",
        &format!(
            "{job} · pre-cut cross sections: {rows} direction(s), {PANELS} sections each along the cut, at one scale"
        ),
    );
    doc.legend(
        (8.0, 28.0),
        width - 16.0,
        &[
            Legend::new(Mark::Line, "#000000", "design surface"),
            Legend::new(Mark::Line, "#909090", "convex hull"),
            Legend::new(Mark::Line, "#d02020", "wire cut (ruled surface)"),
            Legend::new(Mark::Line, "#1060e0", "block"),
        ],
    );
    let (z0, z1) = (block.min[2], block.max[2]);
    // one scale for every panel: the widest section fits its panel
    let width_of = |d: &ruled::DirectionCut, s: &ruled::SectionPolygon| {
        let across = nalgebra::Vector2::new(d.across[0], d.across[1]);
        let w_of = |p: &[f64; 3]| across.dot(&nalgebra::Vector2::new(p[0], p[1]));
        match (s.polygon.first(), s.polygon.last()) {
            (Some(a), Some(b)) => (w_of(a), w_of(b)),
            _ => (0.0, 0.0),
        }
    };
    let widest = run
        .cut
        .directions
        .iter()
        .flat_map(|d| d.sections.iter().map(move |s| (d, s)))
        .map(|(d, s)| {
            let (a, b) = width_of(d, s);
            (b - a).abs()
        })
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for (row, d) in run.cut.directions.iter().enumerate() {
        // sections of (nearly) zero width, at the ends of a turned block, are not drawn
        let shown: Vec<&ruled::SectionPolygon> = d
            .sections
            .iter()
            .filter(|s| {
                let (a, b) = width_of(d, s);
                (b - a).abs() > 1e-3 * widest
            })
            .collect();
        let n = shown.len();
        let top = head + row as f64 * ph;
        doc.axes_key((16.0, top + ph - 60.0), "across", "z");
        for k in 0..PANELS.min(n) {
            let s = shown[(k * (n - 1)) / (PANELS - 1).max(1)];
            let (w0, w1) = width_of(d, s);
            let x0 = left + k as f64 * pw;
            doc.text(
                (x0 + pad, top + 14.0),
                10.0,
                "#333",
                &format!(
                    "direction {} · u = {} {units} along it",
                    row + 1,
                    export::fmt_float(s.offset, 1)
                ),
            );
            let mid = 0.5 * (w0 + w1);
            let vp = Viewport::fit(
                (mid - 0.5 * widest, z0),
                (mid + 0.5 * widest, z1),
                (x0 + pad, top + 24.0, pw - 2.0 * pad, ph - 60.0),
            );
            if k == 0 {
                doc.scale_bar(&vp, (x0 + pad, top + ph - 14.0), 2.0 * pw, units);
            }
            let surfaces = (&height, &hull);
            draw_section(&mut doc, &vp, surfaces, d, s, (w0, w1), (z0, z1));
        }
    }
    doc.write(buf)
}

/// One cross section in its panel (viewport `vp`): the block `[w0, w1] × [z0, z1]`, the
/// design surface and its convex hull along the section, and the cut polygon.
fn draw_section(
    doc: &mut SvgDoc,
    vp: &Viewport,
    (height, hull): (&ruled::Height, &ruled::height::MeshHeight),
    d: &ruled::DirectionCut,
    s: &ruled::SectionPolygon,
    (w0, w1): (f64, f64),
    (z0, z1): (f64, f64),
) {
    let along = nalgebra::Vector2::new(d.direction[0], d.direction[1]);
    let across = nalgebra::Vector2::new(d.across[0], d.across[1]);
    let w_of = |p: &[f64; 3]| across.dot(&nalgebra::Vector2::new(p[0], p[1]));
    doc.polygon(
        &[
            vp.map(w0, z0),
            vp.map(w1, z0),
            vp.map(w1, z1),
            vp.map(w0, z1),
        ],
        "none",
        "#1060e0",
        0.8,
        Some("block"),
    );
    let samples = 200;
    let mut design = Vec::new();
    let mut hull_line = Vec::new();
    for i in 0..=samples {
        let w = w0 + (w1 - w0) * i as f64 / samples as f64;
        let p = along * s.offset + across * w;
        if let Some(f) = height.at(p.x, p.y) {
            design.push(vp.map(w, f));
        }
        if let Some(h) = hull.at(p.x, p.y) {
            hull_line.push(vp.map(w, h.min(z1)));
        }
    }
    doc.polyline(&hull_line, "#909090", 1.0, Some("convex hull"));
    doc.polyline(&design, "#000000", 1.2, Some("design surface"));
    let poly: Vec<(f64, f64)> = s
        .polygon
        .iter()
        .map(|p| vp.map(w_of(p), p[2].min(z1)))
        .collect();
    doc.polyline(&poly, "#d02020", 1.4, Some("cut polygon"));
}
