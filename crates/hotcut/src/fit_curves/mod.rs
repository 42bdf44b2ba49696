//! The `FitCurves` task: fit every curve of an input file, or every section of the
//! surface, by one elastica, line or arc ([`elastica::fit`]), in parallel and in input
//! order.

/// Reading the curves file.
pub mod curves;
/// Its file: `fit.svg`.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// Its report.
pub mod report;

use std::path::Path;

use elastica::fit::{fit_points_with_arclength, FitError, FitParams, FitResult};
use geom::planar::{ArcLength, PlanarCurve};
use geom::surface::Section;
use rayon::prelude::*;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::{section_cost, Estimate};
use crate::progress::Progress;
use crate::report::surface_kind;
use crate::spec::{FitConstraintSpec, OutputKind};
use crate::task::{Output, Task};
use curves::{read_curves, InputCurve};
use design::numerical::{numerical_spline, NumericalParams, NumericalResult};
use elastica::fit::describe::{CurveFit, FitSummary};
use report::{input_length, FitCurvesReport, NumericalCurve};

/// Fit every curve of `input` (or, without `input`, every section of the surface) by
/// one elastica, line or arc — the shapes a hot blade takes ("Hot Blade Cuttings" §5.1).
/// Writes `report.json` (per curve the segment, its distances to the curve and the
/// fitted curve sampled at 400 points) and `fit.svg` (input and fit overlaid). Write
/// `FitCurves(input: "curves.json", constraint: Free)`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FitCurves {
    /// Curves file, relative to the job file: JSON
    /// `{"curves": [{"id": "a", "points": [[x, y], ...]}, ...]}` (other fields are
    /// ignored) or CSV with a header `id,x,y` and one row per point, a curve's rows
    /// consecutive. Coordinates in job units. Default: the sections of `surface`.
    #[serde(default)]
    #[schemars(length(min = 1))]
    pub input: Option<String>,
    /// What the fitted segment must reproduce exactly. Default: `Free`.
    #[serde(default)]
    pub constraint: FitConstraintSpec,
    /// Points each surface section is sampled at, equally spaced in arc length (≥ 3;
    /// unused with `input`). Default: 200.
    #[serde(default = "default_fit_samples")]
    #[schemars(range(min = 3, max = 100000))]
    pub samples: u32,
    /// `Analytic` (the closed-form elastica fit, always made) or additionally
    /// `NumericalSpline(epsilon: ..)`: "Hot Blade Cuttings" §5.2, eq. (13). Default:
    /// `Analytic`.
    #[serde(default)]
    pub method: FitMethod,
}

/// How `FitCurves` approximates each curve by an elastica.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum FitMethod {
    /// The closed-form elastica fit.
    #[default]
    Analytic,
    /// Also the numerical spline approach ("Hot Blade Cuttings" §5.2, eq. 13): the curve
    /// as a cubic B-spline of `control_points` control points, and the spline of least
    /// bending energy whose control points stay within `epsilon` of those; the end points
    /// are kept, and with `fix_tangents` / `fix_length` the end tangents and the length.
    /// Reported per curve beside the analytic fit (`numerical` in the report), drawn in
    /// `fit.svg` in orange.
    NumericalSpline {
        /// Largest distance of a control point from the input spline's (> 0), job units.
        epsilon: f64,
        /// Control points of the refined spline, 6 to the curve's number of points.
        /// Default: 24 (or the number of points, if fewer).
        #[serde(default)]
        #[schemars(range(min = 6, max = 10000))]
        control_points: Option<u32>,
        /// Keep the end tangents. Default: false.
        #[serde(default)]
        fix_tangents: bool,
        /// Keep the length. Default: false.
        #[serde(default)]
        fix_length: bool,
    },
}

fn default_fit_samples() -> u32 {
    200
}

const INPUT: &str = "/task/FitCurves/input";

/// Parameters of a `FitCurves` run.
#[derive(Debug, Clone, PartialEq)]
pub struct FitCurvesParams {
    /// The curves file (resolved path, and as written), or `None` for the sections.
    pub input: Option<(std::path::PathBuf, String)>,
    /// The boundary constraint.
    pub constraint: FitConstraintSpec,
    /// Points per surface section.
    pub samples: usize,
    /// The method.
    pub method: FitMethod,
}

/// Curves and fits of a `FitCurves` run.
#[derive(Debug, Clone)]
pub struct FitRun {
    /// Where the curves came from: `file <path>` or `sections of the <kind> surface`.
    pub source: String,
    /// The curves, in report order.
    pub curves: Vec<InputCurve>,
    /// Their fits (segment and matched parameters), or why not.
    pub fits: Vec<std::result::Result<FitResult, FitError>>,
    /// With `NumericalSpline`: per curve its result, or why not.
    pub numerical: Option<Vec<std::result::Result<NumericalResult, String>>>,
}

impl Task for FitCurves {
    const NAME: &'static str = "FitCurves";
    const REPORT_SCHEMA: &'static str = "fit-curves-report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[Output::new(OutputKind::Svg, outputs::svg)];
    type Params = FitCurvesParams;
    type Run = FitRun;
    type Report = FitCurvesReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        let numerical = match self.method {
            FitMethod::Analytic => None,
            FitMethod::NumericalSpline {
                epsilon,
                control_points,
                ..
            } => {
                if !(epsilon > 0.0) || !epsilon.is_finite() {
                    errors.push(job.error(
                        "/task/FitCurves/method/NumericalSpline/epsilon",
                        format!("epsilon must be a positive length, got {epsilon:?}"),
                    ));
                }
                let n = control_points.map_or(6, |n| n as usize);
                if n > design::numerical::MAX_CONTROL_POINTS {
                    errors.push(job.error(
                        "/task/FitCurves/method/NumericalSpline/control_points",
                        format!(
                            "control_points must be at most {} (the solver's work grows with their cube), got {n}",
                            design::numerical::MAX_CONTROL_POINTS
                        ),
                    ));
                }
                Some(n)
            }
        };
        match &self.input {
            Some(rel) => match read_curves(&job.base.join(rel)) {
                Err(m) => errors.push(job.error(INPUT, m)),
                Ok(curves) => {
                    let n = numerical.unwrap_or(0);
                    if let Some(c) = curves.iter().find(|c| c.points.len() < n.max(4)) {
                        errors.push(job.error(
                            "/task/FitCurves/method/NumericalSpline/control_points",
                            format!(
                                "curve `{}` has {} points: the numerical spline needs at least 4, and at least control_points ({n})",
                                c.id,
                                c.points.len()
                            ),
                        ));
                    }
                }
            },
            None if job.surface.is_none() => errors.push(job.error(
                INPUT,
                "task FitCurves needs `input` (a curves file) or a surface to section",
            )),
            None => {
                if numerical.is_some_and(|n| n > self.samples as usize) {
                    errors.push(job.error(
                        "/task/FitCurves/method/NumericalSpline/control_points",
                        "control_points must not exceed the task's samples",
                    ));
                }
            }
        }
    }

    fn params(&self, job: &Context) -> Result<FitCurvesParams> {
        let base = job.path.parent().unwrap_or(Path::new("."));
        Ok(FitCurvesParams {
            input: self.input.as_ref().map(|rel| (base.join(rel), rel.clone())),
            constraint: self.constraint,
            samples: self.samples as usize,
            method: self.method,
        })
    }

    fn estimate(p: &FitCurvesParams, job: &Context) -> Estimate {
        // the curves and their points: the file's, or the sections'
        let (section, curves, points, sectioning) = match &p.input {
            Some((file, _)) => {
                let (c, n) = read_curves(file).map_or((1, 3), |c| {
                    (c.len(), c.iter().map(|c| c.points.len()).sum::<usize>())
                });
                (0.0, c as f64, n as f64, 0.0)
            }
            None => {
                let (cost, points) = section_cost(job.surface.as_ref());
                let n = f64::from(job.cutting.sections);
                (points, n, n * p.samples as f64, n * (cost + 1e3 * points))
            }
        };
        let per_curve = points / curves.max(1.0);
        // the numerical spline: a bending-energy solve whose work grows with the cube of
        // its control points (measured: 0.8 s at 48 and 3 s at 96 per curve, one core)
        let numerical = match p.method {
            FitMethod::Analytic => 0.0,
            FitMethod::NumericalSpline { control_points, .. } => {
                let n = control_points.map_or(24.0_f64.min(per_curve), f64::from);
                1e3 * n.powi(3) + 2e4 * per_curve
            }
        };
        // measured per curve: ~135 kB of memory, and ~45 kB of files (report.json's
        // fitted samples ~27 kB, the page ~11 kB, the drawing ~8 kB)
        Estimate::new(
            curves * (2e5 + 200.0 * section) + points * 200.0 + 1e7,
            sectioning + curves * (2e5 + numerical) + points * 2e3,
            if p.input.is_some() {
                INPUT
            } else {
                "/task/FitCurves/samples"
            },
            if p.input.is_some() {
                "fit fewer curves per job (split the curves file), or fewer control_points"
            } else {
                "lower the task's samples or cutting.sections, or fewer control_points"
            },
        )
        .with_output(curves * 5e4 + points * 120.0 + 1e4)
    }

    fn run(params: &FitCurvesParams, job: &Context, progress: &dyn Progress) -> Result<FitRun> {
        let (curves, source) = match &params.input {
            Some((file, rel)) => {
                let curves = read_curves(file)
                    .map_err(|message| JobError::semantic(&job.path, INPUT, message))?;
                (curves, format!("file {rel}"))
            }
            None => {
                let surface = job.surface(Self::NAME)?;
                progress.start("sectioning", job.cutting.sections as u64);
                let (_, sections) = surface
                    .sections(&job.sectioning(), &|| progress.tick())
                    .map_err(job.geom_err("sectioning the surface"))?;
                progress.finish();
                let samples = params.samples.max(3);
                (
                    sections.iter().map(|s| section_curve(s, samples)).collect(),
                    format!("sections of the {} surface", surface_kind(surface)),
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
        let numerical = match params.method {
            FitMethod::Analytic => None,
            FitMethod::NumericalSpline {
                epsilon,
                control_points,
                fix_tangents,
                fix_length,
            } => {
                progress.start("numerical splines", curves.len() as u64);
                let out = curves
                    .par_iter()
                    .map(|c| {
                        let n = control_points.map_or(24.min(c.points.len()), |n| n as usize);
                        let p = NumericalParams {
                            epsilon,
                            control_points: n,
                            fix_tangents,
                            fix_length,
                        };
                        let r = numerical_spline(&c.points, &p).map_err(|e| e.to_string());
                        progress.tick();
                        r
                    })
                    .collect();
                progress.finish();
                Some(out)
            }
        };
        Ok(FitRun {
            source,
            curves,
            fits,
            numerical,
        })
    }

    fn report(params: &FitCurvesParams, run: &FitRun, job: &Context) -> FitCurvesReport {
        let entries: Vec<CurveFit> = run
            .curves
            .iter()
            .zip(&run.fits)
            .map(|(c, f)| CurveFit::new(&c.id, c.points.len(), input_length(c), f))
            .collect();
        let numerical = run.numerical.as_ref().map(|list| {
            run.curves
                .iter()
                .zip(&run.fits)
                .zip(list)
                .map(|((c, f), r)| NumericalCurve::new(&c.id, r, f.as_ref().ok()))
                .collect()
        });
        FitCurvesReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            source: run.source.clone(),
            constraint: params.constraint,
            method: params.method,
            summary: FitSummary::of(&entries),
            curves: entries,
            numerical,
        }
    }

    fn page(r: &FitCurvesReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &FitCurvesReport, job: &Context) -> String {
        let units = job.units.symbol();
        let s = &r.summary;
        let mut out = format!(
            "{} (FitCurves, {:?}, {}):\n  {} curve(s): {} inflectional, {} non-inflectional elastica, {} arc(s), {} line(s)\n  RMS distance: median {:.3e} {units}, max {:.3e} {units}; largest distance {:.3e} {units}",
            r.job, r.constraint, r.source,
            s.curves, s.inflectional, s.noninflectional, s.arcs, s.lines,
            s.median_rms, s.max_rms, s.max_distance
        );
        if let Some(list) = &r.numerical {
            let active = list.iter().filter(|n| n.constraint_active).count();
            let worst = list.iter().map(|n| n.eq11_residual).fold(0.0, f64::max);
            let far = list
                .iter()
                .filter_map(|n| n.distance_to_analytic)
                .fold(0.0, f64::max);
            out.push_str(&format!(
                "\n  numerical spline: {active} of {} curve(s) with an active ε constraint; eq. (11) residual ≤ {worst:.3}; ≤ {far:.3e} {units} from the analytic fit",
                list.len()
            ));
            for n in list {
                if let Some(e) = &n.error {
                    out.push_str(&format!(
                        "\n  warning: curve `{}`: numerical spline failed: {e}",
                        n.id
                    ));
                }
            }
        }
        for c in &r.curves {
            if let Some(e) = &c.error {
                out.push_str(&format!(
                    "\n  warning: curve `{}` was not fitted: {e}",
                    c.id
                ));
            }
        }
        out
    }
}

/// A section as a curve sampled at `samples` points of equal arc length.
fn section_curve(s: &Section, samples: usize) -> InputCurve {
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
}
