//! Layer-3 checks of each task's own fields, and which outputs each task writes.

use std::path::Path;

use super::semantic;
use crate::error::JobError;
use crate::job::{FitConstraintSpec, Job, OutputSpec, SegAlgorithmSpec, SurfaceSpec, TaskSpec};

/// Checks `job.task` (pushing every problem to `errors`) and returns the names of the
/// outputs the task writes. `base` is the job file's folder.
pub(super) fn check_task(
    path: &Path,
    job: &Job,
    base: &Path,
    errors: &mut Vec<JobError>,
) -> &'static [&'static str] {
    match &job.task {
        TaskSpec::FitCurves { input, .. } => {
            match input {
                Some(rel) => {
                    if let Err(m) = crate::fit_curves::read_curves(&base.join(rel)) {
                        errors.push(semantic(path, "/task/FitCurves/input", m));
                    }
                }
                None if job.surface.is_none() => errors.push(semantic(
                    path,
                    "/task/FitCurves/input",
                    "task FitCurves needs `input` (a curves file) or a surface to section",
                )),
                None => {}
            }
            &["Report", "Svg"]
        }
        TaskSpec::Analyze { .. } => {
            if job.surface.is_none() {
                errors.push(semantic(path, "/surface", "task Analyze needs a surface"));
            }
            &["Report", "Svg", "Obj"]
        }
        TaskSpec::HotBlade {
            targets_per_block,
            constraint,
            speed,
            approach,
            max_plane_angle,
            ..
        } => {
            let ptr = "/task/HotBlade";
            require_surface_and_block(path, job, "HotBlade", "", "surface is", errors);
            if *constraint == FitConstraintSpec::Free {
                errors.push(semantic(path, &format!("{ptr}/constraint"), "HotBlade fits keep the sections' end points so that neighbouring blocks meet: use EndPoints or EndPointsAndLength"));
            }
            check_motion(path, ptr, *speed, *approach, errors);
            if !(*max_plane_angle >= 0.0 && *max_plane_angle <= std::f64::consts::FRAC_PI_2) {
                errors.push(semantic(
                    path,
                    &format!("{ptr}/max_plane_angle"),
                    format!("the plane angle must be in [0, π/2], got {max_plane_angle}"),
                ));
            }
            for (i, o) in job.outputs.iter().enumerate() {
                if let OutputSpec::RobotTargets {
                    per_block: Some(per_block),
                } = o
                {
                    if per_block != targets_per_block {
                        errors.push(semantic(path, &format!("/outputs/{i}/RobotTargets/per_block"), format!("per_block ({per_block}) must equal the task's targets_per_block ({targets_per_block})")));
                    }
                }
            }
            &[
                "Report",
                "Svg",
                "Obj",
                "Gltf",
                "Csv",
                "RobotTargets",
                "Rapid",
            ]
        }
        TaskSpec::FacadeSegmentation {
            algorithm,
            rationalize,
            constraint,
            speed,
            approach,
            ..
        } => {
            let ptr = "/task/FacadeSegmentation";
            require_surface_and_block(
                path,
                job,
                "FacadeSegmentation",
                " (the facade)",
                "pieces are",
                errors,
            );
            if *constraint == FitConstraintSpec::Free {
                errors.push(semantic(path, &format!("{ptr}/constraint"), "a piece's fits keep its parts' end points so that neighbouring pieces meet: use EndPoints or EndPointsAndLength"));
            }
            check_motion(path, ptr, *speed, *approach, errors);
            if job.blade.as_ref().is_some_and(|b| b.max_inflections == 0) {
                errors.push(semantic(path, "/blade/max_inflections", "FacadeSegmentation needs max_inflections ≥ 1: parts meet between inflections, never exactly on one, so a section with an inflection cannot be split into parts without any"));
            }
            let positive =
                |errors: &mut Vec<JobError>, field: &str, v: Option<f64>, zero_ok: bool| {
                    if let Some(v) = v {
                        let ok = v.is_finite() && (v > 0.0 || (zero_ok && v == 0.0));
                        if !ok {
                            errors.push(semantic(
                                path,
                                &format!("{ptr}/algorithm/{}/{field}", algorithm.name()),
                                format!(
                                    "{field} must be a {} number, got {v}",
                                    if zero_ok { "non-negative" } else { "positive" }
                                ),
                            ));
                        }
                    }
                };
            match algorithm {
                SegAlgorithmSpec::Inflection { .. } => {}
                SegAlgorithmSpec::Trace {
                    link_distance,
                    merge_distance,
                    ..
                } => {
                    positive(errors, "link_distance", *link_distance, false);
                    positive(errors, "merge_distance", *merge_distance, true);
                }
                SegAlgorithmSpec::LongestElastica {
                    precision,
                    max_step,
                } => {
                    positive(errors, "precision", *precision, false);
                    positive(errors, "max_step", *max_step, false);
                }
            }
            for (i, o) in job.outputs.iter().enumerate() {
                let robot = matches!(o, OutputSpec::RobotTargets { .. } | OutputSpec::Rapid);
                if robot && !rationalize {
                    errors.push(semantic(
                        path,
                        &format!("/outputs/{i}"),
                        format!(
                            "output {} needs the pieces rationalized: set `rationalize: true`",
                            o.name()
                        ),
                    ));
                }
                if let OutputSpec::RobotTargets { per_block: Some(_) } = o {
                    errors.push(semantic(path, &format!("/outputs/{i}/RobotTargets/per_block"), "FacadeSegmentation poses the blade on every section a piece crosses: leave per_block out"));
                }
            }
            &[
                "Report",
                "Svg",
                "Obj",
                "Gltf",
                "Csv",
                "RobotTargets",
                "Rapid",
            ]
        }
        TaskSpec::BlockSegmentation {
            operations,
            p,
            epsilon,
            restarts,
            max_iterations,
            time_limit,
            sample_spacing,
            ..
        } => {
            let ptr = "/task/BlockSegmentation";
            if !(1..=256).contains(restarts) {
                errors.push(semantic(
                    path,
                    &format!("{ptr}/restarts"),
                    format!("restarts must be 1–256, got {restarts}"),
                ));
            }
            if *max_iterations == 0 {
                errors.push(semantic(
                    path,
                    &format!("{ptr}/max_iterations"),
                    "max_iterations must be at least 1",
                ));
            }
            check_block_segmentation(
                path,
                job,
                operations,
                *p,
                *epsilon,
                *time_limit,
                *sample_spacing,
                errors,
            );
            &["Report", "Blocks", "Svg", "Obj", "Gltf"]
        }
        TaskSpec::PreCut {
            legs,
            directions,
            degree,
            controls,
            sections,
            samples,
            max_rounds,
        } => {
            check_pre_cut(
                path,
                job,
                (*legs, *degree, *controls, *sections, *samples, *max_rounds),
                directions,
                errors,
            );
            for (i, o) in job.outputs.iter().enumerate() {
                if matches!(o, OutputSpec::GCode | OutputSpec::Csv) && job.wire.is_none() {
                    errors.push(semantic(
                        path,
                        &format!("/outputs/{i}"),
                        format!("{} writes wire programs: the job needs `wire: Wire(tower_distance: .., kerf: ..)`", o.name()),
                    ));
                }
            }
            if let Some(w) = &job.wire {
                let positive = |v: Option<f64>| v.is_none_or(|v| v.is_finite() && v > 0.0);
                if !(w.tower_distance.is_finite() && w.tower_distance > 0.0) {
                    errors.push(semantic(
                        path,
                        "/wire/tower_distance",
                        "tower_distance must be positive",
                    ));
                }
                if !(w.kerf.is_finite() && w.kerf >= 0.0) {
                    errors.push(semantic(path, "/wire/kerf", "kerf must be at least 0"));
                }
                if !positive(w.speed) {
                    errors.push(semantic(path, "/wire/speed", "speed must be positive"));
                }
                if !w.lead.is_none_or(|v| v.is_finite() && v >= 0.0) {
                    errors.push(semantic(path, "/wire/lead", "lead must be at least 0"));
                }
                if !positive(w.clearance) {
                    errors.push(semantic(
                        path,
                        "/wire/clearance",
                        "clearance must be positive",
                    ));
                }
            }
            &["Report", "PreCut", "Svg", "GCode", "Csv", "Obj", "Gltf"]
        }
    }
}

/// The fields of a `PreCut` task: counts `(legs, degree, controls, sections, samples,
/// max_rounds)` and directions; it needs a surface and a block.
fn check_pre_cut(
    path: &Path,
    job: &Job,
    (legs, degree, controls, sections, samples, max_rounds): (u32, u32, u32, u32, u32, u32),
    directions: &[crate::job::CutDirection],
    errors: &mut Vec<JobError>,
) {
    let ptr = "/task/PreCut";
    require_surface_and_block(path, job, "PreCut", "", "cuts are", errors);
    let mut range = |field: &str, v: u32, lo: u32, hi: u32| {
        if !(lo..=hi).contains(&v) {
            errors.push(semantic(
                path,
                &format!("{ptr}/{field}"),
                format!("{field} must be {lo}–{hi}, got {v}"),
            ));
        }
    };
    range("legs", legs, 1, 32);
    range("degree", degree, 1, 5);
    range("controls", controls, degree + 1, 64);
    range("sections", sections, 2, 500);
    range("samples", samples, 2, 500);
    range("max_rounds", max_rounds, 1, 10_000);
    if directions.is_empty() {
        errors.push(semantic(
            path,
            &format!("{ptr}/directions"),
            "at least one cutting direction, e.g. [X]",
        ));
    }
    for (i, d) in directions.iter().enumerate() {
        let [x, y] = d.vector();
        if !(x.is_finite() && y.is_finite()) || x.hypot(y) < 1e-9 {
            errors.push(semantic(
                path,
                &format!("{ptr}/directions/{i}"),
                format!("{d:?} is not a direction in the xy plane (finite, not zero)"),
            ));
        } else if directions[..i].iter().any(|e| {
            let [a, b] = e.vector();
            (a * y - b * x).abs() < 1e-9 * x.hypot(y) * a.hypot(b) && a * x + b * y > 0.0
        }) {
            errors.push(semantic(
                path,
                &format!("{ptr}/directions/{i}"),
                format!("{d:?} repeats an earlier direction"),
            ));
        }
    }
}

/// The fields of a `BlockSegmentation` task, its closed mesh and its block.
#[allow(clippy::too_many_arguments)]
fn check_block_segmentation(
    path: &Path,
    job: &Job,
    operations: &[blocks::Operation],
    p: f64,
    epsilon: f64,
    time_limit: Option<f64>,
    sample_spacing: f64,
    errors: &mut Vec<JobError>,
) {
    let ptr = "/task/BlockSegmentation";
    require_surface_and_block(
        path,
        job,
        "BlockSegmentation",
        " (a closed mesh)",
        "model is",
        errors,
    );
    match &job.surface {
        Some(SurfaceSpec::Mesh { closed: true, .. }) | None => {}
        Some(SurfaceSpec::Mesh { closed: false, .. }) => errors.push(semantic(
            path,
            "/surface/Mesh/closed",
            "BlockSegmentation covers a solid: the mesh must be closed (`closed: true`)",
        )),
        Some(_) => errors.push(semantic(
            path,
            "/surface",
            "BlockSegmentation needs a closed triangle mesh: `Mesh(path: .., closed: true)`",
        )),
    }
    if job.block.as_ref().is_some_and(|b| b.origin.is_some()) {
        errors.push(semantic(
            path,
            "/block/origin",
            "BlockSegmentation places its blocks itself: leave origin out",
        ));
    }
    if operations.is_empty() {
        errors.push(semantic(
            path,
            &format!("{ptr}/operations"),
            "at least one of Translate, Rotate, Align",
        ));
    }
    for (i, o) in operations.iter().enumerate() {
        if operations[..i].contains(o) {
            errors.push(semantic(
                path,
                &format!("{ptr}/operations/{i}"),
                format!("{o:?} is listed twice"),
            ));
        }
    }
    if !(p >= 1.0) || !p.is_finite() {
        errors.push(semantic(
            path,
            &format!("{ptr}/p"),
            format!("p must be a finite number ≥ 1, got {p}"),
        ));
    }
    if !(epsilon > 0.0) || !epsilon.is_finite() {
        errors.push(semantic(
            path,
            &format!("{ptr}/epsilon"),
            format!("epsilon must be positive, got {epsilon}"),
        ));
    }
    if let Some(t) = time_limit {
        if !(t > 0.0) || !t.is_finite() {
            errors.push(semantic(
                path,
                &format!("{ptr}/time_limit"),
                format!("time_limit must be positive seconds, got {t}"),
            ));
        }
    }
    if !(sample_spacing > 0.0 && sample_spacing <= 0.25) {
        errors.push(semantic(path, &format!("{ptr}/sample_spacing"), format!("sample_spacing must be in (0, 0.25] of the shortest block edge, got {sample_spacing}")));
    }
}

/// Checks a task's cutting speed (> 0) and approach distance (≥ 0), when given.
fn check_motion(
    path: &Path,
    ptr: &str,
    speed: Option<f64>,
    approach: Option<f64>,
    errors: &mut Vec<JobError>,
) {
    if let Some(v) = speed {
        if !(v > 0.0) || !v.is_finite() {
            errors.push(semantic(
                path,
                &format!("{ptr}/speed"),
                format!("the cutting speed must be a positive number, got {v}"),
            ));
        }
    }
    if let Some(v) = approach {
        if !(v >= 0.0) || !v.is_finite() {
            errors.push(semantic(
                path,
                &format!("{ptr}/approach"),
                format!("the approach distance must be ≥ 0, got {v}"),
            ));
        }
    }
}

/// A task that cuts a surface from blocks needs both: reports each missing one. `what`
/// says what the surface is (may be empty), `cut` what is cut from the blocks, with its
/// verb ("surface is").
fn require_surface_and_block(
    path: &Path,
    job: &Job,
    task: &str,
    what: &str,
    cut: &str,
    errors: &mut Vec<JobError>,
) {
    if job.surface.is_none() {
        errors.push(semantic(
            path,
            "/surface",
            format!("task {task} needs a surface{what}"),
        ));
    }
    if job.block.is_none() {
        errors.push(semantic(
            path,
            "/block",
            format!("task {task} needs `block` (the size of the blocks the {cut} cut from)"),
        ));
    }
}
