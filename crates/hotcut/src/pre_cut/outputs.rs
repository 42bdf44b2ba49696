//! The files of a `PreCut` run: `precut.json` (the polygons of rulings per section, and
//! the legs' B-splines), `sections.svg` (cross sections with the design curve, the cut
//! polygon and the convex hull, after thesis fig. 2.4), `precut.obj` and `model.gltf`
//! (design surface, each direction's cut surface, the block) and per cut the wire's
//! G-code and CSV.

use std::rc::Rc;

use export::gltf::{write_gltf, Material};
use export::json::{to_json_string, REPORT_DIGITS};
use export::obj::ObjWriter;
use export::svg::{SvgDoc, Viewport};
use geom::mesh::TriMesh;
use geom::surface::Surface;
use nalgebra::Vector3;
use serde::Serialize;

use super::PreCutRun;
use crate::block_seg::outputs::{block_mesh, gltf_mesh};
use crate::hot_blade::outputs::file;
use crate::job::OutputSpec;
use crate::run::Render;

/// The files of output `o`.
pub fn render(run: &Rc<PreCutRun>, o: &OutputSpec) -> Vec<Render<'static>> {
    let r = run.clone();
    match o {
        OutputSpec::PreCut => vec![file(
            "precut.json",
            Box::new(move |buf| {
                #[derive(Serialize)]
                struct PreCutFile<'a> {
                    directions: &'a [ruled::DirectionCut],
                }
                let f = PreCutFile {
                    directions: &r.cut.directions,
                };
                buf.extend(to_json_string(&f, REPORT_DIGITS)?.into_bytes());
                Ok(())
            }),
        )],
        OutputSpec::Svg => vec![file(
            "sections.svg",
            Box::new(move |buf| sections_svg(&r, buf)),
        )],
        OutputSpec::Obj => vec![file("precut.obj", Box::new(move |buf| obj(&r, buf)))],
        OutputSpec::Gltf => vec![file("model.gltf", Box::new(move |buf| gltf(&r, buf)))],
        OutputSpec::GCode | OutputSpec::Csv => wire_files(run, matches!(o, OutputSpec::GCode)),
        _ => Vec::new(),
    }
}

/// The block as a box mesh.
fn block_box(run: &PreCutRun) -> export::Result<TriMesh> {
    let b = run.report.block;
    let (lo, hi) = (Vector3::from(b.min), Vector3::from(b.max));
    block_mesh(&blocks::Placement {
        center: ((lo + hi) / 2.0).into(),
        rotation: [1.0, 0.0, 0.0, 0.0],
        size: (hi - lo).into(),
    })
}

/// The design surface as a mesh (height fields and splines tessellated).
fn design_mesh(run: &PreCutRun) -> export::Result<TriMesh> {
    let to_err = |e: geom::GeomError| export::ExportError::Io(std::io::Error::other(e.to_string()));
    match &run.surface {
        Surface::Mesh(m) => Ok(m.clone()),
        Surface::HeightField(h) => h.to_mesh(DESIGN_GRID, DESIGN_GRID).map_err(to_err),
        Surface::Spline(s) => s.to_mesh(DESIGN_GRID).map_err(to_err),
    }
}

/// Grid cells per side of the tessellated design surface.
const DESIGN_GRID: usize = 64;
/// Points across the block per section of a cut surface mesh.
const ACROSS: usize = 40;

/// Direction `d`'s cut surface (the lower envelope of its legs, capped at the block's
/// top) as a grid mesh over its sections and `ACROSS` points across each chord.
fn cut_mesh(d: &ruled::DirectionCut, top: f64) -> Option<TriMesh> {
    let along = nalgebra::Vector2::new(d.direction[0], d.direction[1]);
    let across = nalgebra::Vector2::new(d.across[0], d.across[1]);
    let mut v = Vec::new();
    for (s, lines) in d.sections.iter().zip(&d.lines) {
        let w_of = |p: &[f64; 3]| across.dot(&nalgebra::Vector2::new(p[0], p[1]));
        let (first, last) = (s.polygon.first()?, s.polygon.last()?);
        let (w0, w1) = (w_of(first), w_of(last));
        for k in 0..=ACROSS {
            let w = w0 + (w1 - w0) * k as f64 / ACROSS as f64;
            let t = (w - d.w_mid) / d.w_half;
            let z = lines.iter().map(|l| l.a + l.m * t).fold(top, f64::min);
            let p = along * s.offset + across * w;
            v.push(Vector3::new(p.x, p.y, z));
        }
    }
    let rows = d.sections.len();
    let n = (ACROSS + 1) as u32;
    let mut f = Vec::new();
    for i in 0..rows.saturating_sub(1) as u32 {
        for k in 0..ACROSS as u32 {
            let a = i * n + k;
            f.push([a, a + n, a + n + 1]);
            f.push([a, a + n + 1, a + 1]);
        }
    }
    TriMesh::try_new(v, f).ok()
}

fn obj(run: &PreCutRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let mut w = ObjWriter::new(6);
    w.mesh("design", &design_mesh(run)?);
    for (i, d) in run.cut.directions.iter().enumerate() {
        if let Some(m) = cut_mesh(d, run.report.block.max[2]) {
            w.mesh(&format!("cut_d{}", i + 1), &m);
        }
    }
    w.mesh("block", &block_box(run)?);
    w.write(buf)
}

fn gltf(run: &PreCutRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let materials = vec![
        Material {
            name: "design".into(),
            color: [0.8, 0.8, 0.82, 1.0],
            blend: false,
        },
        Material {
            name: "cut".into(),
            color: [0.85, 0.2, 0.15, 0.45],
            blend: true,
        },
        Material {
            name: "block".into(),
            color: [0.2, 0.4, 0.9, 0.12],
            blend: true,
        },
    ];
    let mut meshes = vec![gltf_mesh("design".into(), &design_mesh(run)?, 0)];
    for (i, d) in run.cut.directions.iter().enumerate() {
        if let Some(m) = cut_mesh(d, run.report.block.max[2]) {
            meshes.push(gltf_mesh(format!("cut_d{}", i + 1), &m, 1));
        }
    }
    meshes.push(gltf_mesh("block".into(), &block_box(run)?, 2));
    write_gltf("hotcut PreCut", &meshes, &materials, buf)
}

/// One file per cut: `wire_d{direction}_c{cut}.gcode` (or `.csv`), 1-based.
fn wire_files(run: &Rc<PreCutRun>, gcode: bool) -> Vec<Render<'static>> {
    let Some(w) = run.wire else {
        return Vec::new();
    };
    let block = run.report.block;
    let mut out = Vec::new();
    for (i, d) in run.cut.directions.iter().enumerate() {
        let Ok(paths) = ruled::wire::paths(d, i, block.min[2], &w) else {
            continue;
        };
        for path in paths {
            let name = run.name.clone();
            let ext = if gcode { "gcode" } else { "csv" };
            out.push(file(
                format!("wire_d{}_c{}.{ext}", i + 1, path.leg + 1),
                Box::new(move |buf| {
                    let text = if gcode {
                        ruled::wire::gcode(&path, &w, block.max[2], block.min[2], &name)
                    } else {
                        ruled::wire::csv(&path)
                    };
                    buf.extend(text.into_bytes());
                    Ok(())
                }),
            ));
        }
    }
    out
}

/// Sections drawn per direction (evenly spread along the cut).
const PANELS: usize = 5;

/// One row per direction, `PANELS` cross sections each: block outline, design curve
/// (black), convex hull (grey, dashed look by colour), the cut polygon (red).
fn sections_svg(run: &PreCutRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let to_err =
        |e: ruled::PreCutError| export::ExportError::Io(std::io::Error::other(e.to_string()));
    let height = ruled::Height::new(&run.surface).map_err(to_err)?;
    let block = run.report.block;
    let (_, hull) = ruled::volume::hull_top(&height, &block, 100).map_err(to_err)?;
    let (pw, ph, pad) = (260.0, 180.0, 16.0);
    let rows = run.cut.directions.len();
    let mut doc = SvgDoc::new(PANELS as f64 * pw, rows as f64 * ph + 24.0);
    doc.text(
        (8.0, 16.0),
        11.0,
        "#000",
        "pre-cut sections: design (black), convex hull (grey), cut polygon (red), block (blue)",
    );
    let (z0, z1) = (block.min[2], block.max[2]);
    for (row, d) in run.cut.directions.iter().enumerate() {
        let n = d.sections.len();
        for k in 0..PANELS.min(n) {
            let s = &d.sections[(k * (n - 1)) / (PANELS - 1).max(1)];
            let along = nalgebra::Vector2::new(d.direction[0], d.direction[1]);
            let across = nalgebra::Vector2::new(d.across[0], d.across[1]);
            let w_of = |p: &[f64; 3]| across.dot(&nalgebra::Vector2::new(p[0], p[1]));
            let (Some(first), Some(last)) = (s.polygon.first(), s.polygon.last()) else {
                continue;
            };
            let (w0, w1) = (w_of(first), w_of(last));
            let top = 24.0 + row as f64 * ph;
            let vp = Viewport::fit(
                (w0, z0),
                (w1, z1),
                (
                    k as f64 * pw + pad,
                    top + pad,
                    pw - 2.0 * pad,
                    ph - 2.0 * pad,
                ),
            );
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
            doc.text(
                (k as f64 * pw + pad, top + ph - 4.0),
                9.0,
                "#333",
                &format!("direction {} · u = {:.4}", row + 1, s.offset),
            );
        }
    }
    doc.write(buf)
}
