//! The `FitCurves` task: fit every curve of an input file, or every section of the
//! surface, by one elastica, line or arc ([`elastica::fit`]), in parallel and in input
//! order.
//!
//! Entry points: [`read_curves`](crate::fit_curves::read_curves) (JSON or CSV, checked when
//! the job is loaded) and [`fit_curves`](crate::fit_curves::fit_curves).

use std::path::Path;

use elastica::fit::{fit_points_with_arclength, FitError, FitParams, FitResult};
use elastica::segment::Segment;
use geom::planar::{ArcLength, PlanarCurve};
use rayon::prelude::*;
use serde::Deserialize;

use crate::error::{HotcutError, Result};
use crate::job::{FitConstraintSpec, TaskSpec};
use crate::load::ResolvedJob;
use crate::report::{CurveFit, FitCurvesReport, FitSummary, FittedCurve};
use crate::Progress;

/// Points of the fitted segment written to the report.
pub const FITTED_SAMPLES: usize = 400;

/// A planar curve to fit.
#[derive(Debug, Clone, PartialEq)]
pub struct InputCurve {
    /// Its id.
    pub id: String,
    /// The points, in job units.
    pub points: Vec<[f64; 2]>,
    /// Arc length at every point when known exactly (surface sections); `None` uses the
    /// polyline's chord lengths.
    pub arc_length: Option<Vec<f64>>,
}

#[derive(Deserialize)]
struct JsonCurves {
    curves: Vec<JsonCurve>,
}

#[derive(Deserialize)]
struct JsonCurve {
    id: serde_json::Value,
    points: Vec<[f64; 2]>,
}

/// Reads a curves file: JSON `{"curves": [{"id", "points": [[x, y], ...]}, ...]}` (other
/// fields ignored; ids may be strings or numbers) or, for a `.csv` name, CSV with the header
/// `id,x,y` and one row per point, a curve's rows consecutive.
///
/// # Errors
/// A message naming the file and, where it applies, the line or curve: unreadable file,
/// malformed JSON or CSV, no curves, a repeated id, a curve with fewer than 3 points, a
/// non-finite coordinate, or two equal consecutive points.
pub fn read_curves(path: &Path) -> std::result::Result<Vec<InputCurve>, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let csv = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"));
    let curves = if csv {
        parse_csv(&text)
    } else {
        parse_json(&text)
    }
    .map_err(|e| format!("{}: {e}", path.display()))?;
    check(&curves).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(curves)
}

fn parse_json(text: &str) -> std::result::Result<Vec<InputCurve>, String> {
    let file: JsonCurves = serde_json::from_str(text).map_err(|e| e.to_string())?;
    file.curves
        .into_iter()
        .enumerate()
        .map(|(i, c)| {
            let id = match c.id {
                serde_json::Value::String(s) => s,
                serde_json::Value::Number(n) => n.to_string(),
                other => {
                    return Err(format!(
                        "curve {i}: id must be a string or number, got {other}"
                    ))
                }
            };
            Ok(InputCurve {
                id,
                points: c.points,
                arc_length: None,
            })
        })
        .collect()
}

fn parse_csv(text: &str) -> std::result::Result<Vec<InputCurve>, String> {
    let mut lines = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty());
    let header = lines.next().map(|(_, l)| l).unwrap_or_default();
    let cols: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    if cols != ["id", "x", "y"] {
        return Err(format!(
            "the first line must be the header `id,x,y`, got `{header}`"
        ));
    }
    let mut curves: Vec<InputCurve> = Vec::new();
    for (n, line) in lines {
        let f: Vec<&str> = line.split(',').map(str::trim).collect();
        if f.len() != 3 {
            return Err(format!(
                "line {}: expected 3 fields `id,x,y`, got {}",
                n + 1,
                f.len()
            ));
        }
        let num = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("line {}: `{s}` is not a number", n + 1))
        };
        let p = [num(f[1])?, num(f[2])?];
        match curves.last_mut() {
            Some(c) if c.id == f[0] => c.points.push(p),
            _ => curves.push(InputCurve {
                id: f[0].to_string(),
                points: vec![p],
                arc_length: None,
            }),
        }
    }
    Ok(curves)
}

fn check(curves: &[InputCurve]) -> std::result::Result<(), String> {
    if curves.is_empty() {
        return Err("no curves".into());
    }
    let mut seen = std::collections::BTreeSet::new();
    for c in curves {
        if !seen.insert(c.id.as_str()) {
            return Err(format!(
                "curve `{}` appears twice (CSV rows of a curve must be consecutive)",
                c.id
            ));
        }
        if c.points.len() < 3 {
            return Err(format!(
                "curve `{}` has {} point(s); a fit needs at least 3",
                c.id,
                c.points.len()
            ));
        }
        for (i, p) in c.points.iter().enumerate() {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(format!("curve `{}`: point {i} is not finite", c.id));
            }
            if i > 0 && *p == c.points[i - 1] {
                return Err(format!(
                    "curve `{}`: points {} and {i} coincide",
                    c.id,
                    i - 1
                ));
            }
        }
    }
    Ok(())
}

/// Parameters of [`fit_curves`], taken from the job.
#[derive(Debug, Clone, PartialEq)]
pub struct FitCurvesParams {
    /// The boundary constraint.
    pub constraint: FitConstraintSpec,
    /// Points per surface section.
    pub samples: usize,
}

impl FitCurvesParams {
    /// The parameters of a `FitCurves` job (`None` for other tasks).
    pub fn from_job(job: &ResolvedJob) -> Option<Self> {
        match &job.job.task {
            TaskSpec::FitCurves {
                constraint,
                samples,
                ..
            } => Some(Self {
                constraint: *constraint,
                samples: *samples as usize,
            }),
            _ => None,
        }
    }
}

/// Curves and fits of a `FitCurves` run.
#[derive(Debug, Clone)]
pub struct FitRun {
    /// The curves, in report order.
    pub curves: Vec<InputCurve>,
    /// Their fits (segment and matched parameters), or why not.
    pub fits: Vec<std::result::Result<FitResult, FitError>>,
    /// The report.
    pub report: FitCurvesReport,
}

/// The sections of a surface as curves sampled at `samples` points of equal arc length.
fn section_curves(
    job: &ResolvedJob,
    samples: usize,
    progress: &dyn Progress,
) -> Result<Vec<InputCurve>> {
    let surface = job.surface.as_ref().ok_or_else(|| {
        HotcutError::Invalid(vec![crate::error::JobError::Semantic {
            path: job.path.clone(),
            pointer: "/task/FitCurves/input".into(),
            message: "task FitCurves needs `input` or a surface".into(),
        }])
    })?;
    let analyze = crate::analyze::AnalyzeParams::sectioning(job);
    progress.start("sectioning", analyze.count as u64);
    let (_, sections) = surface
        .sections(&analyze, &|| progress.tick())
        .map_err(|source| HotcutError::Geom {
            path: job.path.clone(),
            context: "sectioning the surface".into(),
            source,
        })?;
    progress.finish();
    Ok(sections
        .iter()
        .map(|s| {
            let arc = ArcLength::new(&s.curve, 4 * samples);
            let total = arc.length();
            let mut points = Vec::with_capacity(samples);
            let mut arc_length = Vec::with_capacity(samples);
            for i in 0..samples {
                let si = total * i as f64 / (samples - 1) as f64;
                let p = s.curve.point(arc.t_at(&s.curve, si));
                points.push([p.x, p.y]);
                arc_length.push(si);
            }
            InputCurve {
                id: format!("section {}.{}", s.index, s.piece),
                points,
                arc_length: Some(arc_length),
            }
        })
        .collect())
}

/// Runs the task: reads or sections the curves and fits each.
///
/// # Errors
/// Reading the input file, or sectioning the surface. A curve that cannot be fitted is
/// reported with its `error` instead.
pub fn fit_curves(
    job: &ResolvedJob,
    params: &FitCurvesParams,
    progress: &dyn Progress,
) -> Result<FitRun> {
    let input = match &job.job.task {
        TaskSpec::FitCurves { input, .. } => input.clone(),
        _ => None,
    };
    let (curves, source) = match input {
        Some(rel) => {
            let file = job.path.parent().unwrap_or(Path::new(".")).join(&rel);
            let curves = read_curves(&file).map_err(|message| {
                HotcutError::Invalid(vec![crate::error::JobError::Semantic {
                    path: job.path.clone(),
                    pointer: "/task/FitCurves/input".into(),
                    message,
                }])
            })?;
            (curves, format!("file {rel}"))
        }
        None => {
            let kind = job
                .surface
                .as_ref()
                .map_or("", crate::analyze::surface_kind);
            (
                section_curves(job, params.samples.max(3), progress)?,
                format!("sections of the {kind} surface"),
            )
        }
    };
    let fit_params = FitParams {
        constraint: params.constraint.to_fit(),
        ..Default::default()
    };
    progress.start("fitting curves", curves.len() as u64);
    let fits: Vec<std::result::Result<FitResult, FitError>> = curves
        .par_iter()
        .map(|c| {
            let r = match &c.arc_length {
                Some(s) => fit_points_with_arclength(&c.points, s, &fit_params),
                None => elastica::fit::fit_points(&c.points, &fit_params),
            };
            progress.tick();
            r
        })
        .collect();
    progress.finish();
    let entries: Vec<CurveFit> = curves.iter().zip(&fits).map(|(c, f)| entry(c, f)).collect();
    let report = FitCurvesReport {
        job: job.job.name.clone(),
        task: "FitCurves".into(),
        units: job.job.units,
        source,
        constraint: params.constraint,
        summary: summary(&entries),
        curves: entries,
    };
    Ok(FitRun {
        curves,
        fits,
        report,
    })
}

fn input_length(c: &InputCurve) -> f64 {
    match &c.arc_length {
        Some(s) => s[s.len() - 1] - s[0],
        None => c
            .points
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .sum(),
    }
}

/// The report entry of one curve.
fn entry(c: &InputCurve, fit: &std::result::Result<FitResult, FitError>) -> CurveFit {
    let fitted = fit
        .as_ref()
        .map_err(|e| e.to_string())
        .and_then(|f| fitted_curve(f).map_err(|e| e.to_string()));
    let (fit, error) = match fitted {
        Ok(f) => (Some(f), None),
        Err(e) => (None, Some(e)),
    };
    CurveFit {
        id: c.id.clone(),
        points: c.points.len(),
        input_length: input_length(c),
        error,
        fit,
    }
}

fn fitted_curve(
    f: &FitResult,
) -> std::result::Result<FittedCurve, elastica::elliptic::EllipticError> {
    let seg = &f.segment;
    let p = |pairs: &[(&str, f64)]| pairs.iter().map(|(k, v)| (k.to_string(), *v)).collect();
    let (family, parameters) = match *seg {
        Segment::Elastica(e) => (
            match e.family {
                elastica::unit::Family::Inflectional => "inflectional",
                elastica::unit::Family::NonInflectional => "noninflectional",
            },
            p(&[
                ("k", e.k),
                ("s0", e.s0),
                ("l", e.l),
                ("S", e.scale),
                ("phi", e.phi),
                ("x0", e.x0),
                ("y0", e.y0),
            ]),
        ),
        Segment::Line {
            x0,
            y0,
            phi,
            length,
        } => (
            "line",
            p(&[("x0", x0), ("y0", y0), ("phi", phi), ("length", length)]),
        ),
        Segment::Arc {
            x0,
            y0,
            phi,
            curvature,
            length,
        } => (
            "arc",
            p(&[
                ("x0", x0),
                ("y0", y0),
                ("phi", phi),
                ("curvature", curvature),
                ("length", length),
            ]),
        ),
    };
    let inflections = seg.inflections()?;
    let eval = seg.evaluator()?;
    Ok(FittedCurve {
        family: family.into(),
        parameters,
        rms: f.rms,
        max: f.max,
        length: seg.length(),
        inflections: inflections.len(),
        inflection_points: inflections.iter().map(|&t| eval.eval(t).p).collect(),
        max_abs_curvature: seg.max_abs_curvature()?,
        iterations: f.iterations,
        converged: f.converged,
        fitted: seg.sample(FITTED_SAMPLES)?,
    })
}

fn summary(entries: &[CurveFit]) -> FitSummary {
    let fits: Vec<&FittedCurve> = entries.iter().filter_map(|e| e.fit.as_ref()).collect();
    let count = |family: &str| fits.iter().filter(|f| f.family == family).count();
    let mut rms: Vec<f64> = fits.iter().map(|f| f.rms).collect();
    rms.sort_by(f64::total_cmp);
    let median_rms = match rms.len() {
        0 => 0.0,
        n if n % 2 == 1 => rms[n / 2],
        n => 0.5 * (rms[n / 2 - 1] + rms[n / 2]),
    };
    FitSummary {
        curves: entries.len(),
        failed: entries.len() - fits.len(),
        lines: count("line"),
        arcs: count("arc"),
        inflectional: count("inflectional"),
        noninflectional: count("noninflectional"),
        max_rms: rms.last().copied().unwrap_or(0.0),
        median_rms,
        max_distance: fits.iter().map(|f| f.max).fold(0.0, f64::max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write(name: &str, text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join(name);
        std::fs::write(&p, text).unwrap();
        (dir, p)
    }

    #[test]
    fn json_and_csv_give_the_same_curves() {
        let (_a, json) = write(
            "c.json",
            r#"{"curves": [{"id": "a", "class": "x", "points": [[0, 0], [1, 0.5], [2, 0]]},
                           {"id": 7, "points": [[0, 1], [1, 1], [2, 1.5]]}]}"#,
        );
        let (_b, csv) = write(
            "c.csv",
            "id,x,y\na,0,0\na,1,0.5\na,2,0\n\n7,0,1\n7,1,1\n7,2,1.5\n",
        );
        let (j, c) = (read_curves(&json).unwrap(), read_curves(&csv).unwrap());
        assert_eq!(j, c);
        assert_eq!(j.len(), 2);
        assert_eq!(j[1].id, "7");
        assert_eq!(j[0].points[1], [1.0, 0.5]);
    }

    #[test]
    fn bad_curve_files_are_rejected_with_a_reason() {
        let cases = [
            ("a.json", "{\"curves\": []}", "no curves"),
            (
                "b.json",
                "{\"curves\": [{\"id\": \"a\"}]}",
                "missing field `points`",
            ),
            ("c.json", "{\"curves\": [", "EOF"),
            (
                "d.json",
                "{\"curves\": [{\"id\": \"a\", \"points\": [[0, 0], [1, 1]]}]}",
                "at least 3",
            ),
            (
                "e.json",
                "{\"curves\": [{\"id\": \"a\", \"points\": [[0, 0], [1, 1], [1, 1]]}]}",
                "coincide",
            ),
            ("f.csv", "x,y\n0,0\n", "header"),
            ("g.csv", "id,x,y\na,0,0\na,1,nan\na,2,0\n", "not finite"),
            ("h.csv", "id,x,y\na,0,zero\n", "line 2"),
            ("i.csv", "id,x,y\na,0,0,1\n", "3 fields"),
            (
                "j.csv",
                "id,x,y\na,0,0\na,1,1\na,2,0\nb,0,0\nb,1,1\nb,2,0\na,5,5\n",
                "twice",
            ),
        ];
        for (name, text, expect) in cases {
            let (_d, p) = write(name, text);
            let e = read_curves(&p).unwrap_err();
            assert!(e.contains(expect), "{name}: `{e}` lacks `{expect}`");
        }
        let missing = read_curves(Path::new("/nonexistent/curves.json")).unwrap_err();
        assert!(missing.contains("curves.json"));
    }
}
