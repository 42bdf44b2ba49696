//! Acceptance checks of the `HotBlade` task on the jobs in `jobs/`, made from outside the
//! algorithm's own bookkeeping:
//! - every emitted pose rebuilds, from its two end poses and the blade length alone (the
//!   discrete elastica of `elastica::discrete`, an independent boundary-value solve), a
//!   blade that passes within the job's tolerance of the fitted section;
//! - fits with `EndPointsAndLength` keep the section's length and end points to 1e-9;
//! - neighbouring blocks share their blades' end points (≤ 1e-6 mm) and, with `C1`, end
//!   tangents (≤ 1e-6 rad), measured on the blades themselves;
//! - planes that follow a cutting-direction curve are reported as overlapping exactly
//!   where two consecutive planes meet inside the part of the surface a block cuts.

use std::path::Path;

use elastica::discrete::{discrete_elastica, DiscreteParams};
use elastica::fit::FitConstraint;
use hotblade::{Continuity, FittedSection, Rationalization};
use hotcut::job::TaskSpec;
use hotcut::load::{load_job, parse_job, resolve, ResolvedJob};
use hotcut::task::Task;
use nalgebra::{Vector2, Vector3};

const JOBS: [&str; 5] = [
    "hot-blade-facade",
    "hot-blade-corner",
    "hot-blade-saddle",
    "hot-blade-oblique",
    "hot-blade-curve",
];

/// A `HotBlade` job's pipeline run, with the parameters it ran with.
struct HotBladeRun {
    cut: Rationalization,
    params: hotblade::Params,
}

/// Runs the `hotblade` pipeline with the parameters the job's task gives.
fn rationalize(job: &ResolvedJob) -> HotBladeRun {
    let TaskSpec::HotBlade(task) = &job.task else {
        panic!("not a HotBlade job");
    };
    let params = task.params(&job.context).unwrap().pipeline;
    let surface = job.context.surface.as_ref().unwrap();
    HotBladeRun {
        cut: hotblade::rationalize(surface, &params, &|_| {}).unwrap(),
        params,
    }
}

fn run(name: &str) -> (HotBladeRun, f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("jobs/{name}.ron"));
    let job = load_job(&path).unwrap();
    (rationalize(&job), job.context.tolerance.max)
}

fn dist_to_polyline(p: &Vector3<f64>, poly: &[Vector3<f64>]) -> f64 {
    poly.windows(2)
        .map(|w| {
            let d = w[1] - w[0];
            let t = ((p - w[0]).dot(&d) / d.norm_squared()).clamp(0.0, 1.0);
            (p - (w[0] + d * t)).norm()
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn every_pose_rebuilds_a_blade_through_the_fitted_section() {
    // the facade's blades are nearly taut (length/chord − 1 ≈ 1e-5): some need the discrete
    // solver's augmented-Lagrangian fallback, counted below
    for name in JOBS {
        let (run, tolerance) = run(name);
        let length = run.params.blade.length;
        let mut worst = 0.0f64;
        let (mut poses, mut fallbacks) = (0, 0);
        for b in &run.cut.blocks {
            for sec in &b.sections {
                let pose = &sec.pose;
                // the plane from the pose alone: origin at end 1, x along its tangent, z = normal
                let n = Vector3::from(pose.plane_normal);
                let p0 = Vector3::from(pose.ends[0].position);
                let x = Vector3::from(pose.ends[0].tangent);
                let y = n.cross(&x);
                let to2 = |p: &Vector3<f64>| [(p - p0).dot(&x), (p - p0).dot(&y)];
                let p1 = Vector3::from(pose.ends[1].position);
                let t1 = Vector3::from(pose.ends[1].tangent);
                let blade = discrete_elastica(&DiscreteParams {
                    segments: 200,
                    start: [0.0, 0.0],
                    start_angle: 0.0,
                    end: to2(&p1),
                    end_angle: t1.dot(&y).atan2(t1.dot(&x)),
                    length,
                    max_iterations: 1000,
                })
                .unwrap_or_else(|e| panic!("{name} block {}: {e}", b.report.block));
                fallbacks += usize::from(blade.fallback);
                let rebuilt: Vec<Vector3<f64>> = blade
                    .points
                    .iter()
                    .map(|q| p0 + x * q[0] + y * q[1])
                    .collect();
                // the fitted section (inside the block), in 3D
                let plane = &run.cut.planes[sec.plane];
                for q in sec.fit.segment.sample(200).unwrap() {
                    let p = plane
                        .frame
                        .to_world(plane.offset, &Vector2::new(q[0], q[1]));
                    worst = worst.max(dist_to_polyline(&p, &rebuilt));
                }
                poses += 1;
            }
        }
        assert!(poses > 0);
        println!(
            "{name}: {poses} poses ({fallbacks} by the fallback), rebuilt blades within \
             {worst:.3e} of the fitted sections"
        );
        assert!(worst <= tolerance, "{name}: {worst} > {tolerance}");
    }
}

#[test]
fn same_length_and_end_points_are_kept() {
    for name in JOBS {
        let (run, _) = run(name);
        if run.params.constraint != FitConstraint::EndPointsAndLength {
            continue;
        }
        let mut worst = 0.0f64;
        for b in &run.cut.blocks {
            for sec in &b.sections {
                let d = &sec.design;
                let seg = &sec.fit.segment;
                let (a, z) = (seg.eval(0.0).unwrap().p, seg.eval(1.0).unwrap().p);
                let (da, dz) = (d.points[0], d.points[d.points.len() - 1]);
                let rel = [
                    (seg.length() - d.length).abs() / d.length,
                    (a[0] - da[0]).hypot(a[1] - da[1]) / d.length,
                    (z[0] - dz[0]).hypot(z[1] - dz[1]) / d.length,
                ];
                worst = rel.iter().copied().fold(worst, f64::max);
            }
        }
        println!("{name}: length and end points kept to {worst:.3e} relative");
        assert!(worst <= 1e-9, "{name}: {worst}");
    }
}

/// Largest end-point gap and end-tangent angle between the blades of blocks side by side
/// across the cut, measured on the blades themselves, and the number of shared ends; also
/// asserts that consecutive rows cut their shared face with the same blade.
fn shared_ends(run: &HotBladeRun) -> (f64, f64, usize) {
    let (mut gap, mut angle, mut pairs) = (0.0f64, 0.0f64, 0);
    // a block's place across the cut, in the grid's frame (the cut may be oblique)
    let across =
        |b: &hotblade::BlockResult| run.cut.grid.frame.u.dot(&Vector3::from(b.report.origin));
    let scale = 1e-9 * run.cut.grid.size[1];
    for a in &run.cut.blocks {
        for b in &run.cut.blocks {
            // side by side across the cut: a's far face is b's near face
            let touching = a.report.row == b.report.row
                && (across(a) + a.report.size[1] - across(b)).abs() < scale;
            if !touching {
                continue;
            }
            for sa in &a.sections {
                let Some(sb) = b.sections.iter().find(|s| s.plane == sa.plane) else {
                    continue;
                };
                let plane = &run.cut.planes[sa.plane];
                let ea = sa.fit.segment.eval(1.0).unwrap();
                let eb = sb.fit.segment.eval(0.0).unwrap();
                let w = |q: [f64; 2]| {
                    plane
                        .frame
                        .to_world(plane.offset, &Vector2::new(q[0], q[1]))
                };
                gap = gap.max((w(ea.p) - w(eb.p)).norm());
                let cross = ea.tangent[0] * eb.tangent[1] - ea.tangent[1] * eb.tangent[0];
                let dot = ea.tangent[0] * eb.tangent[0] + ea.tangent[1] * eb.tangent[1];
                angle = angle.max(cross.atan2(dot).abs());
                pairs += 1;
            }
        }
        // along the cut: consecutive rows cut the shared face with the same blade
        for b in &run.cut.blocks {
            if b.report.row == a.report.row + 1 && (across(b) - across(a)).abs() < scale {
                let (la, fb) = (a.sections.last().unwrap(), b.sections.first().unwrap());
                assert_eq!(la.plane, fb.plane);
                assert_eq!(la.pose, fb.pose);
            }
        }
    }
    (gap, angle, pairs)
}

#[test]
fn neighbouring_blocks_share_end_points_and_tangents() {
    // the jobs as written, and the 8-block facade asked for C¹ as well
    let facade = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron");
    let mut job = parse_job(&facade, &std::fs::read_to_string(&facade).unwrap()).unwrap();
    if let TaskSpec::HotBlade(task) = &mut job.task {
        task.continuity = hotcut::spec::Continuity::C1;
    }
    let facade_c1 = rationalize(&resolve(&facade, job).unwrap());
    let runs = JOBS
        .iter()
        .map(|name| (name.to_string(), run(name).0))
        .chain([("hot-blade-facade with C1".to_string(), facade_c1)]);
    for (name, run) in runs {
        let c1 = run.params.continuity == Continuity::C1;
        if c1 {
            assert_eq!(run.cut.summary.tangent_failures, 0, "{name}");
        }
        let (gap, angle, pairs) = shared_ends(&run);
        println!(
            "{name}: {pairs} shared ends, gap ≤ {gap:.3e}, tangent angle ≤ {angle:.3e} (C1: {c1})"
        );
        if run.cut.blocks.len() > 1 {
            assert!(pairs > 0, "{name}: no neighbours found");
        }
        assert!(gap <= 1e-6, "{name}: gap {gap}");
        if c1 {
            assert!(angle <= 1e-6, "{name}: angle {angle}");
        }
    }
}

/// With a tolerance the facade's 600 mm sections cannot meet, columns are halved along the
/// cutting direction and refitted: every block still over the tolerance is at the job's
/// split depth, the parts of each column tile it in every row alike, the split list names
/// only parts that broke the tolerance, and the halves still share their blades' ends.
#[test]
fn columns_over_tolerance_are_halved_and_refitted() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut job = parse_job(&path, &text).unwrap();
    job.tolerance.max = Some(0.01);
    job.tolerance.rms = Some(0.005);
    let run = rationalize(&resolve(&path, job).unwrap());
    let (tol_max, tol_rms, depth) = (0.01f64, 0.005f64, run.params.split_depth);
    let splits = &run.cut.splits;
    println!(
        "{} splits, {} blocks (8 unsplit)",
        splits.len(),
        run.cut.blocks.len()
    );
    assert!(!splits.is_empty());
    for s in splits {
        // split because a fit broke the rms or the max tolerance; rms ≤ max distance
        assert!(s.max_fit_distance > tol_rms.min(tol_max), "{s:?}");
        assert!(s.level as usize <= depth as usize);
    }
    let column_width = run.cut.grid.size[1];
    for b in &run.cut.blocks {
        let over = b
            .sections
            .iter()
            .any(|s| s.fit.max > tol_max || s.fit.rms > tol_rms);
        assert!(
            !over || b.report.split_level == depth,
            "block {} over tolerance at level {} < {depth}",
            b.report.block,
            b.report.split_level
        );
        // a part at level n is 2^-n of its column
        let share = b.report.size[1] / column_width;
        assert!((share - 0.5f64.powi(b.report.split_level as i32)).abs() < 1e-12);
    }
    // per row, the parts tile the surface's width without gap or overlap, alike in all rows
    let mut tilings = Vec::new();
    for row in 0..run.cut.grid.rows {
        let mut parts: Vec<(f64, f64)> = run
            .cut
            .blocks
            .iter()
            .filter(|b| b.report.row == row)
            .map(|b| (b.report.origin[1], b.report.origin[1] + b.report.size[1]))
            .collect();
        parts.sort_by(|a, b| a.0.total_cmp(&b.0));
        for w in parts.windows(2) {
            assert!((w[0].1 - w[1].0).abs() < 1e-9, "row {row}: {parts:?}");
        }
        tilings.push(parts);
    }
    assert!(tilings.windows(2).all(|w| w[0] == w[1]));
    assert!(run.cut.blocks.len() > 8);
    let (gap, _, pairs) = shared_ends(&run);
    println!("{pairs} shared ends after splitting, gap ≤ {gap:.3e}");
    assert!(gap <= 1e-6);
}

/// The blocks' overlap lists against plane geometry. Two consecutive planes a, b of a block
/// are vertical, so the signed distance to plane a varies linearly along plane b's plan
/// line (and vice versa): section b lies strictly ahead of a — no material cut twice —
/// exactly when the two plan points at the ends of its lateral extent do, and section a
/// lies strictly behind b when its two ends do. Pairs with an end within 1e-6 mm of the
/// other plane are skipped (either answer is right there). Returns (flagged, checked).
fn overlaps_against_geometry(run: &HotBladeRun) -> (usize, usize) {
    let axis_u = run.cut.grid.frame.u;
    let (mut flagged, mut pairs) = (0, 0);
    // the plan points of a section at the ends of its lateral extent
    let ends = |sec: &FittedSection| {
        let pl = &run.cut.planes[sec.plane];
        let world: Vec<Vector3<f64>> = sec
            .design
            .points
            .iter()
            .map(|q| pl.frame.to_world(pl.offset, &Vector2::new(q[0], q[1])))
            .collect();
        let by_u = |a: &&Vector3<f64>, b: &&Vector3<f64>| axis_u.dot(a).total_cmp(&axis_u.dot(b));
        let lo = *world.iter().min_by(by_u).unwrap();
        let hi = *world.iter().max_by(by_u).unwrap();
        [lo, hi]
    };
    for b in &run.cut.blocks {
        'pairs: for (k, w) in b.sections.windows(2).enumerate() {
            let (pa, pb) = (&run.cut.planes[w[0].plane], &run.cut.planes[w[1].plane]);
            let dist = |pl: &hotblade::grid::Plane, p: &Vector3<f64>| {
                let n = Vector3::new(pl.frame.normal.x, pl.frame.normal.y, 0.0);
                n.dot(&Vector3::new(p.x, p.y, 0.0)) - pl.offset
            };
            let db: Vec<f64> = ends(&w[1]).iter().map(|p| dist(pa, p)).collect();
            let da: Vec<f64> = ends(&w[0]).iter().map(|p| dist(pb, p)).collect();
            if db.iter().chain(&da).any(|d| d.abs() < 1e-6) {
                continue 'pairs;
            }
            let expected = !(db.iter().all(|d| *d > 0.0) && da.iter().all(|d| *d < 0.0));
            let reported = b.report.overlaps.contains(&[k, k + 1]);
            assert_eq!(
                reported,
                expected,
                "block {} planes {k}, {}: reported {reported}, geometry says {expected}",
                b.report.block,
                k + 1
            );
            assert_eq!(b.report.flags.overlap, !b.report.overlaps.is_empty());
            flagged += usize::from(reported);
            pairs += 1;
        }
    }
    (flagged, pairs)
}

#[test]
fn overlapping_curve_planes_are_detected() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-curve.ron");
    // the job's own gentle curve (radius ≈ 2.7 m, the panel 1.2 m wide): no overlap
    let (gentle, _) = run("hot-blade-curve");
    let (flagged, pairs) = overlaps_against_geometry(&gentle);
    println!("gentle curve: {flagged} of {pairs} consecutive plane pairs overlap");
    assert!(pairs > 0 && flagged == 0);
    // an S bending with a radius of ≈ 270 mm: planes cross inside the blocks
    let text = std::fs::read_to_string(&path).unwrap();
    let mut job = parse_job(&path, &text).unwrap();
    job.cutting.curve = Some(vec![
        (0.0, 600.0),
        (450.0, 900.0),
        (900.0, 600.0),
        (1350.0, 300.0),
        (1800.0, 600.0),
    ]);
    let sharp = rationalize(&resolve(&path, job).unwrap());
    let (flagged, pairs) = overlaps_against_geometry(&sharp);
    println!("sharp S curve: {flagged} of {pairs} consecutive plane pairs overlap");
    assert!(flagged > 0, "no overlap found on the sharp curve");
    assert!(sharp.cut.summary.flagged.overlap > 0);
}

/// Issue 35 item 5: a blade with a kerf cuts the design, not half a kerf into it. The
/// facade job with `kerf: 2.0` (and, the same at its speed, a `kerf_table`) runs end to end
/// into files; from `targets.json` alone every pose rebuilds the blade (the discrete
/// elastica between its two end poses, the blade's length), each rebuilt blade is moved
/// back by half the kerf along its in-plane normal (towards `−v`, the side kept), and
/// every point of it inside its block lies within the job's tolerance of the exact design
/// surface (the height field's expression, evaluated here). Not moved back, the blades lie
/// about half a kerf above the design: the check sees the offset.
#[test]
fn kerf_offset_blades_leave_the_design_within_tolerance() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/hot-blade-facade.ron"),
    )
    .unwrap();
    let z = "60*sin(x/400)*cos(y/450) + 0.00004*y*y";
    assert!(text.contains(z));
    for (tag, kerf_fields, kerf) in [
        ("width", "kerf: 2.0", 2.0),
        // 7 mm/s is the task's default speed: halfway between 6 and 8 mm/s
        ("table", "kerf_table: [(6, 2.4), (8, 1.6)]", 2.0),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let job = text
            .replace(
                "Blade(length: 800, max_curvature: 0.011, max_inflections: 2)",
                &format!(
                    "Blade(length: 800, max_curvature: 0.011, max_inflections: 2, {kerf_fields})"
                ),
            )
            .replace(
                "outputs: [Report, RobotTargets(per_block: 51), Rapid, Gltf, Obj, Svg, Csv, Html]",
                "outputs: [Report, RobotTargets(per_block: 51)]",
            );
        let path = dir.path().join("kerf.ron");
        std::fs::write(&path, job).unwrap();
        let job = load_job(&path).unwrap_or_else(|e| panic!("{e:?}"));
        let run = hotcut::run::run_job(&job, &dir.path().join("out"), &hotcut::NoProgress).unwrap();
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(run.dir.join("report.json")).unwrap())
                .unwrap();
        let k = &report["settings"]["kerf"];
        assert!(
            (k["kerf"].as_f64().unwrap() - kerf).abs() < 1e-12,
            "{tag}: {k}"
        );
        assert!(
            (k["offset"].as_f64().unwrap() - kerf / 2.0).abs() < 1e-12,
            "{tag}: {k}"
        );
        let tolerance = report["settings"]["tolerance_max"].as_f64().unwrap();
        let targets: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(run.dir.join("targets.json")).unwrap())
                .unwrap();
        let (back, raw) = kerf_distances(&targets, z, kerf / 2.0);
        println!(
            "kerf {tag}: moved back, the blades lie within {back:.3} mm of the design (tolerance {tolerance}); as written, {raw:.3} mm"
        );
        assert!(back <= tolerance, "{tag}: {back} > {tolerance}");
        assert!(
            raw > 0.8 * kerf / 2.0,
            "{tag}: the blades are not off the design: {raw}"
        );
    }
}

/// The largest distance from the exact surface `z` of the blades rebuilt from `targets`,
/// moved back by `offset` along their in-plane normal, over the points inside their
/// blocks; and the same without moving them back.
fn kerf_distances(targets: &serde_json::Value, z: &str, offset: f64) -> (f64, f64) {
    let expr = geom::expr::Expr::parse(z).unwrap();
    let length = targets["blade_length"].as_f64().unwrap();
    let v3 = |v: &serde_json::Value| {
        Vector3::new(
            v[0].as_f64().unwrap(),
            v[1].as_f64().unwrap(),
            v[2].as_f64().unwrap(),
        )
    };
    // distance of a point from the surface z = f(x, y): the vertical gap over the slope
    let gap = |p: &Vector3<f64>| {
        let h = 1e-3;
        let (fx, fy) = (
            (expr.eval(p.x + h, p.y) - expr.eval(p.x - h, p.y)) / (2.0 * h),
            (expr.eval(p.x, p.y + h) - expr.eval(p.x, p.y - h)) / (2.0 * h),
        );
        (p.z - expr.eval(p.x, p.y)).abs() / (1.0 + fx * fx + fy * fy).sqrt()
    };
    let (mut back, mut raw) = (0.0f64, 0.0f64);
    for b in targets["blocks"].as_array().unwrap() {
        let origin = v3(&b["origin"]);
        let r = &b["rotation"];
        let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
            r[0].as_f64().unwrap(),
            r[1].as_f64().unwrap(),
            r[2].as_f64().unwrap(),
            r[3].as_f64().unwrap(),
        ));
        // poses are in job coordinates; the block's frame says which points are inside it
        for pose in b["poses"].as_array().unwrap() {
            let n = v3(&pose["plane_normal"]);
            let ends = pose["ends"].as_array().unwrap();
            let p0 = v3(&ends[0]["position"]);
            let p1 = v3(&ends[1]["position"]);
            let (t0, t1) = (v3(&ends[0]["tangent"]), v3(&ends[1]["tangent"]));
            let y = n.cross(&t0);
            let to2 = |p: &Vector3<f64>| [(p - p0).dot(&t0), (p - p0).dot(&y)];
            let blade = discrete_elastica(&DiscreteParams {
                segments: 400,
                start: [0.0, 0.0],
                start_angle: 0.0,
                end: to2(&p1),
                end_angle: t1.dot(&y).atan2(t1.dot(&t0)),
                length,
                max_iterations: 1000,
            })
            .unwrap();
            let pts: Vec<Vector3<f64>> = blade
                .points
                .iter()
                .map(|c| p0 + t0 * c[0] + y * c[1])
                .collect();
            for i in 1..pts.len() - 1 {
                let t = (pts[i + 1] - pts[i - 1]).normalize();
                let left = n.cross(&t);
                let moved = pts[i] - left * offset;
                // inside the block: its local coordinates within the block's extent
                let local = q.inverse() * (moved - origin);
                if !(local.y >= 0.0 && local.y <= 600.0 && local.x >= 0.0 && local.x <= 600.0) {
                    continue;
                }
                back = back.max(gap(&moved));
                raw = raw.max(gap(&pts[i]));
            }
        }
    }
    (back, raw)
}
