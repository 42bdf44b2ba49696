//! Acceptance checks of the `HotBlade` task on the jobs in `jobs/`, made from outside the
//! algorithm's own bookkeeping:
//! - every emitted pose rebuilds, from its two end poses and the blade length alone (the
//!   discrete elastica of `elastica::discrete`, an independent boundary-value solve), a
//!   blade that passes within the job's tolerance of the fitted section;
//! - fits with `EndPointsAndLength` keep the section's length and end points to 1e-9;
//! - neighbouring blocks share their blades' end points (≤ 1e-6 mm) and, with `C1`, end
//!   tangents (≤ 1e-6 rad), measured on the blades themselves.

use std::path::Path;

use elastica::discrete::{discrete_elastica, DiscreteParams};
use hotcut::hot_blade::{hot_blade, HotBladeParams, HotBladeRun};
use hotcut::job::{Continuity, FitConstraintSpec};
use hotcut::load::load_job;
use hotcut::NoProgress;
use nalgebra::{Vector2, Vector3};

const JOBS: [&str; 3] = ["hot-blade-facade", "hot-blade-corner", "hot-blade-saddle"];

fn run(name: &str) -> (HotBladeRun, f64) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("jobs/{name}.ron"));
    let job = load_job(&path).unwrap();
    let params = HotBladeParams::from_job(&job).unwrap();
    (
        hot_blade(&job, &params, &NoProgress).unwrap(),
        job.job.tolerance.max,
    )
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
        for b in &run.blocks {
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
                let plane = &run.planes[sec.plane];
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
        if run.params.constraint != FitConstraintSpec::EndPointsAndLength {
            continue;
        }
        let mut worst = 0.0f64;
        for b in &run.blocks {
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

#[test]
fn neighbouring_blocks_share_end_points_and_tangents() {
    for name in JOBS {
        let (run, _) = run(name);
        let c1 = run.params.continuity == Continuity::C1;
        let (mut gap, mut angle, mut pairs) = (0.0f64, 0.0f64, 0);
        for a in &run.blocks {
            for b in &run.blocks {
                // side by side across the cut: a's far face is b's near face
                let touching = a.report.row == b.report.row
                    && (a.report.origin[1] + a.report.size[1] - b.report.origin[1]).abs() < 1e-9;
                if !touching {
                    continue;
                }
                for sa in &a.sections {
                    let Some(sb) = b.sections.iter().find(|s| s.plane == sa.plane) else {
                        continue;
                    };
                    let plane = &run.planes[sa.plane];
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
            for b in &run.blocks {
                if b.report.row == a.report.row + 1 && b.report.origin[1] == a.report.origin[1] {
                    let (la, fb) = (a.sections.last().unwrap(), b.sections.first().unwrap());
                    assert_eq!(la.plane, fb.plane);
                    assert_eq!(la.pose, fb.pose);
                }
            }
        }
        println!(
            "{name}: {pairs} shared ends, gap ≤ {gap:.3e}, tangent angle ≤ {angle:.3e} (C1: {c1})"
        );
        if run.blocks.len() > 1 {
            assert!(pairs > 0, "{name}: no neighbours found");
        }
        assert!(gap <= 1e-6, "{name}: gap {gap}");
        if c1 {
            assert!(angle <= 1e-6, "{name}: angle {angle}");
        }
    }
}
