//! The files of a `HotBlade` run: robot targets (JSON, CSV), the RAPID program, the
//! rationalized surfaces (OBJ per block, one glTF for the job), an SVG per block of its
//! worst section (hot-blade paper fig. 15) and a CSV of every fitted section.

use std::rc::Rc;

use elastica::sweep::BladePose;
use export::fmt_float;
use export::gltf::{write_gltf, Material, Mesh};
use export::json::to_json_string;
use export::obj::ObjWriter;
use export::rapid::{write_module, write_pgf, RapidBlock, RapidModule, RapidTarget};
use export::svg::{SvgDoc, Viewport};
use geom::mesh::TriMesh;
use nalgebra::{Quaternion, UnitQuaternion, Vector3};
use serde::Serialize;

use super::{BlockResult, HotBladeRun};
use crate::draw::bounds;
use crate::job::{OutputSpec, Units};
use crate::run::Render;

/// Significant digits of `targets.json` (finer than the report: robot data).
pub const TARGET_DIGITS: usize = 12;

/// `targets.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetsFile {
    /// Length unit of every position.
    pub units: Units,
    /// Physical blade length.
    pub blade_length: f64,
    /// Blocks in cutting order.
    pub blocks: Vec<TargetsBlock>,
}

/// One block of `targets.json`.
#[derive(Debug, Clone, Serialize)]
pub struct TargetsBlock {
    /// Block number.
    pub block: usize,
    /// The block's min corner, the work object's origin (job coordinates).
    pub origin: [f64; 3],
    /// Orientation `[w, x, y, z]` of the block axes (work object frame).
    pub rotation: [f64; 4],
    /// Poses in cutting order, positions in job coordinates.
    pub poses: Vec<BladePose>,
}

/// The targets of a run.
pub fn targets(run: &HotBladeRun, units: Units) -> TargetsFile {
    TargetsFile {
        units,
        blade_length: run.params.blade.length,
        blocks: run
            .blocks
            .iter()
            .map(|b| TargetsBlock {
                block: b.report.block,
                origin: b.report.origin,
                rotation: b.rotation,
                poses: b.sections.iter().map(|s| s.pose).collect(),
            })
            .collect(),
    }
}

/// How one output file is rendered.
pub(crate) type Boxed = Box<dyn Fn(&mut Vec<u8>) -> export::Result<()>>;

/// One output file: its name and renderer.
pub(crate) fn file(name: impl Into<String>, f: Boxed) -> Render<'static> {
    (name.into(), f)
}

/// The files of output `o`.
pub fn render(
    run: &Rc<HotBladeRun>,
    o: &OutputSpec,
    units: Units,
    job: &str,
) -> Vec<Render<'static>> {
    let r = run.clone();
    match o {
        OutputSpec::RobotTargets { .. } | OutputSpec::Rapid => robot_files(
            Rc::new(targets(run, units)),
            run.params.speed,
            run.params.approach,
            job,
            "HotBlade",
            o,
        ),
        OutputSpec::Obj => per_block(run, "surface_block", "obj", |b, buf| {
            let mut w = ObjWriter::new(6);
            if let Some(m) = surface_mesh(b) {
                w.mesh(&format!("block_{}", b.report.block), &m);
            }
            w.write(buf)
        }),
        OutputSpec::Gltf => vec![file("model.gltf", Box::new(move |buf| gltf(&r, buf)))],
        OutputSpec::Svg => per_block(run, "block", "svg", move |b, buf| {
            block_svg(b, units.symbol()).write(buf)
        }),
        OutputSpec::Csv => vec![file(
            "sections.csv",
            Box::new(move |buf| sections_csv(&r, buf)),
        )],
        _ => Vec::new(),
    }
}

/// The robot files of output `o` (`RobotTargets` or `Rapid`) for the poses in `t`, shared
/// by every task that poses the blade: `targets.json` and `targets.csv`, or one RAPID
/// module and `.pgf` per blade robot named `<prefix>_T_ROB<n>`.
pub(crate) fn robot_files(
    t: Rc<TargetsFile>,
    speed: f64,
    approach: f64,
    job: &str,
    prefix: &str,
    o: &OutputSpec,
) -> Vec<Render<'static>> {
    match o {
        OutputSpec::RobotTargets { .. } => {
            let t2 = t.clone();
            vec![
                file(
                    "targets.json",
                    Box::new(move |buf| {
                        buf.extend(to_json_string(&*t, TARGET_DIGITS)?.into_bytes());
                        Ok(())
                    }),
                ),
                file("targets.csv", Box::new(move |buf| targets_csv(&t2, buf))),
            ]
        }
        OutputSpec::Rapid => {
            let mut out = Vec::new();
            for robot in 0..2 {
                let module = format!("{prefix}_T_ROB{}", robot + 1);
                let (t, job, m) = (t.clone(), job.to_string(), module.clone());
                out.push(file(
                    format!("{module}.mod"),
                    Box::new(move |buf| {
                        let motion = Motion { speed, approach };
                        rapid(&t, motion, &job, robot, &m, buf)
                    }),
                ));
                let mod_file = format!("{module}.mod");
                out.push(file(
                    format!("{module}.pgf"),
                    Box::new(move |buf| write_pgf(&mod_file, buf)),
                ));
            }
            out
        }
        _ => Vec::new(),
    }
}

/// Blade motion settings of a RAPID program.
#[derive(Debug, Clone, Copy)]
struct Motion {
    /// Cutting speed, job units per second.
    speed: f64,
    /// Approach and retreat distance along the cut.
    approach: f64,
}

/// One file `<stem>_NNN.<ext>` per block, rendered by `f`.
fn per_block(
    run: &Rc<HotBladeRun>,
    stem: &str,
    ext: &str,
    f: impl Fn(&BlockResult, &mut Vec<u8>) -> export::Result<()> + Clone + 'static,
) -> Vec<Render<'static>> {
    (0..run.blocks.len())
        .map(|i| {
            let (r, f) = (run.clone(), f.clone());
            file(
                format!("{stem}_{:03}.{ext}", run.blocks[i].report.block),
                Box::new(move |buf| f(&r.blocks[i], buf)),
            )
        })
        .collect()
}

fn targets_csv(t: &TargetsFile, buf: &mut Vec<u8>) -> export::Result<()> {
    let mut s = String::from(
        "block,pose,end,x,y,z,tangent_x,tangent_y,tangent_z,q_w,q_x,q_y,q_z,normal_x,normal_y,normal_z\n",
    );
    let f = |v: f64| fmt_float(v, 9);
    for b in &t.blocks {
        for (k, pose) in b.poses.iter().enumerate() {
            for (e, end) in pose.ends.iter().enumerate() {
                let mut row = vec![
                    b.block.to_string(),
                    (k + 1).to_string(),
                    (e + 1).to_string(),
                ];
                row.extend(end.position.iter().map(|v| f(*v)));
                row.extend(end.tangent.iter().map(|v| f(*v)));
                row.extend(end.rotation.iter().map(|v| f(*v)));
                row.extend(pose.plane_normal.iter().map(|v| f(*v)));
                s.push_str(&row.join(","));
                s.push('\n');
            }
        }
    }
    buf.extend(s.into_bytes());
    Ok(())
}

fn sections_csv(run: &HotBladeRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let mut s = String::from(
        "block,pose,plane,kind,design_length,fit_length,l2,rms,max,blade_max_abs_curvature,blade_inflections,plane_angle\n",
    );
    let f = |v: f64| fmt_float(v, 9);
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
            s.push_str(&row.join(","));
            s.push('\n');
        }
    }
    buf.extend(s.into_bytes());
    Ok(())
}

fn uq(q: &[f64; 4]) -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]))
}

fn wxyz(q: &UnitQuaternion<f64>) -> [f64; 4] {
    let c = q.as_ref().coords;
    let s = if c.w < 0.0 { -1.0 } else { 1.0 };
    [s * c.w, s * c.x, s * c.y, s * c.z]
}

fn rapid(
    t: &TargetsFile,
    motion: Motion,
    job: &str,
    robot: usize,
    module: &str,
    buf: &mut Vec<u8>,
) -> export::Result<()> {
    let mm = 1.0 / t.units.per_mm();
    let approach = motion.approach;
    let blocks: Vec<RapidBlock> = t
        .blocks
        .iter()
        .filter(|b| !b.poses.is_empty())
        .map(|b| {
            let frame_q = uq(&b.rotation);
            let origin = Vector3::from(b.origin);
            let local = |p: Vector3<f64>, q: &[f64; 4]| RapidTarget {
                position: (frame_q.inverse() * (p - origin) * mm).into(),
                rotation: wxyz(&(frame_q.inverse() * uq(q))),
            };
            let at = |k: usize, shift: f64| {
                let pose = &b.poses[k];
                let e = &pose.ends[robot];
                local(
                    Vector3::from(e.position) + Vector3::from(pose.plane_normal) * shift,
                    &e.rotation,
                )
            };
            let n = b.poses.len();
            RapidBlock {
                number: b.block,
                frame: RapidTarget {
                    position: (origin * mm).into(),
                    rotation: b.rotation,
                },
                approach: at(0, -approach),
                targets: (0..n).map(|k| at(k, 0.0)).collect(),
                retreat: at(n - 1, approach),
            }
        })
        .collect();
    let comment = vec![
        format!("hotcut job \"{job}\": hot-blade cut, robot task T_ROB{} holds blade end {} ({}).", robot + 1, robot + 1, if robot == 0 { "the blade's start" } else { "the blade's end" }),
        "The cell's world frame is the job frame. Each block has a work object wBlock<n> whose user".into(),
        "frame is the block's min corner with the block axes (along the cut, across it, up).".into(),
        "Targets are in that frame, in mm; orientation [q1,q2,q3,q4] = [w,x,y,z]: tool x along the".into(),
        "blade's tangent at the held end (from the blade's start to its end), tool z normal to the".into(),
        "cutting plane. Calibrate the tool (the blade holder's TCP at the blade end) before running.".into(),
        format!("Blade length {} {}; {} block(s); both tasks must run this program's twin.", fmt_float(t.blade_length, 6), t.units.symbol(), blocks.len()),
    ];
    let m = RapidModule {
        name: module,
        comment: &comment,
        tasks: ["T_ROB1", "T_ROB2"],
        tool: &format!("tBladeEnd{}", robot + 1),
        speed: motion.speed * mm,
        air_speed: (motion.speed * mm * 5.0).max(20.0),
        blocks: &blocks,
    };
    write_module(&m, buf)
}

/// The rationalized surface of a block as a triangle mesh (consecutive grid rows of equal
/// length are joined).
fn surface_mesh(b: &BlockResult) -> Option<TriMesh> {
    let (verts, faces) = surface_grid(b);
    TriMesh::try_new(verts, faces).ok()
}

fn surface_grid(b: &BlockResult) -> (Vec<Vector3<f64>>, Vec<[u32; 3]>) {
    let mut verts = Vec::new();
    let mut faces = Vec::new();
    let mut prev: Option<(u32, usize)> = None;
    for row in &b.surface {
        let start = verts.len() as u32;
        verts.extend(row.iter().map(|v| v.position));
        if let Some((p0, len)) = prev {
            if len == row.len() {
                for i in 0..len.saturating_sub(1) as u32 {
                    let (a, bb) = (p0 + i, p0 + i + 1);
                    let (c, d) = (start + i, start + i + 1);
                    faces.push([a, c, bb]);
                    faces.push([bb, c, d]);
                }
            }
        }
        prev = Some((start, row.len()));
    }
    (verts, faces)
}

/// Deviation colour: blue at 0, green at half the tolerance, red at or beyond it.
fn deviation_color(dev: f64, tolerance: f64) -> [f32; 4] {
    let t = if tolerance > 0.0 {
        (dev / tolerance).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let r = (2.0 * t - 1.0).clamp(0.0, 1.0);
    let g = 1.0 - (2.0 * t - 1.0).abs();
    let b = (1.0 - 2.0 * t).clamp(0.0, 1.0);
    [r as f32, g as f32, b as f32, 1.0]
}

pub(crate) fn f32s(v: &Vector3<f64>) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

/// A block as a closed box mesh: min corner `o`, edges `s` along the frame's normal, `u`
/// and `v`.
pub(crate) fn box_mesh(
    frame: &geom::slice::PlaneFrame,
    o: Vector3<f64>,
    s: [f64; 3],
    name: String,
    material: usize,
) -> Mesh {
    let corner = |i: usize| {
        o + frame.normal * if i & 1 != 0 { s[0] } else { 0.0 }
            + frame.u * if i & 2 != 0 { s[1] } else { 0.0 }
            + frame.v * if i & 4 != 0 { s[2] } else { 0.0 }
    };
    let positions: Vec<[f32; 3]> = (0..8).map(|i| f32s(&corner(i))).collect();
    let indices = geom::mesh::BOX_FACES.iter().flatten().copied().collect();
    Mesh {
        name,
        positions,
        colors: None,
        indices,
        material,
    }
}

fn gltf(run: &HotBladeRun, buf: &mut Vec<u8>) -> export::Result<()> {
    let tol = run.params.tolerance_max;
    let materials = vec![
        Material {
            name: "block".into(),
            color: [0.85, 0.85, 0.8, 0.15],
            blend: true,
        },
        Material {
            name: "surface".into(),
            color: [1.0, 1.0, 1.0, 1.0],
            blend: false,
        },
    ];
    let mut meshes = Vec::new();
    let g = &run.grid;
    for b in &run.blocks {
        meshes.push(box_mesh(
            &g.frame,
            Vector3::from(b.report.origin),
            b.report.size,
            format!("block_{}", b.report.block),
            0,
        ));
        let (verts, faces) = surface_grid(b);
        let colors = b
            .surface
            .iter()
            .flatten()
            .map(|v| deviation_color(v.deviation, tol))
            .collect();
        meshes.push(Mesh {
            name: format!("surface_{}", b.report.block),
            positions: verts.iter().map(f32s).collect(),
            colors: Some(colors),
            indices: faces.iter().flatten().copied().collect(),
            material: 1,
        });
    }
    write_gltf("hotcut", &meshes, &materials, buf)
}

/// Design section and fitted elastica of the block's worst section (largest L2), with the
/// blade's extension dashed in grey.
fn block_svg(b: &BlockResult, units: &str) -> SvgDoc {
    const W: f64 = 900.0;
    const H: f64 = 560.0;
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
    let vp = Viewport::fit(lo, hi, (30.0, 70.0, W - 60.0, H - 100.0));
    let r = &b.report;
    doc.text(
        (30.0, 26.0),
        16.0,
        "black",
        &format!(
            "block {} (row {}, column {}) — worst section: pose {} of {}",
            r.block,
            r.row + 1,
            r.column + 1,
            r.worst_section + 1,
            r.sections
        ),
    );
    doc.text(
        (30.0, 48.0),
        12.0,
        "#444",
        &format!(
            "L2 {:.4} · max distance {:.4} {units} · {} · design black, fitted elastica red, blade extension grey · flags: {}",
            sec.fit.l2,
            sec.fit.max,
            sec.fit.segment.kind(),
            if r.flags.any() { "see report" } else { "none" }
        ),
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
    doc
}
