//! The `Analyze` task (thesis §5.1): section the surface and, for every section, report
//! its length, inflections, curvature maxima and the production constraints it breaks
//! ([`facade_seg::survey`]).
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("wave.ron");
//! std::fs::write(&path, r#"Job(
//!     name: "wave",
//!     surface: HeightField(z: "100*sin(y/200)", x: (0, 400), y: (0, 1500)),
//!     cutting: Cutting(sections: 4),
//!     task: Analyze(),
//! )"#).unwrap();
//! let job = hotcut::load::load_job(&path).unwrap();
//! let hotcut::job::TaskSpec::Analyze(task) = &job.task else { unreachable!() };
//! let out = hotcut::run::run_task(task, &job.context, &job.outputs, dir.path(), &hotcut::NoProgress)
//!     .unwrap();
//! // sin(y/200) changes sign at y = 200π and 400π inside (0, 1500)
//! assert_eq!(out.report.sections[0].inflections.len(), 2);
//! assert!(out.dir.join("sections.svg").is_file());
//! ```

/// Its files: `sections.svg`, `sections.obj`.
mod outputs;
/// What `report.html` shows of it.
mod page;
/// Its report.
pub mod report;

use facade_seg::survey::Violation;
use facade_seg::survey::{survey, Survey, SurveyParams};
use geom::analysis::CurveAnalysisParams;
use geom::slice::PlaneFrame;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::context::{Context, JobFields};
use crate::error::{JobError, Result};
use crate::limits::{section_cost, Estimate};
use crate::progress::Progress;
use crate::report::SurfaceInfo;
use crate::spec::OutputKind;
use crate::task::{Output, Task};
use report::{AnalyzeReport, ConstraintsInfo, CuttingInfo};

/// Section the surface and report, per section, its length, inflections, curvature
/// maxima and the production constraints it breaks (thesis §5.1). Write `Analyze()`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Analyze {
    /// Curvature samples per section for the sign test of eq. (5.2) (≥ 8). Default: 2000.
    #[serde(default = "default_samples")]
    #[schemars(range(min = 8, max = 1000000))]
    pub samples: u32,
}

fn default_samples() -> u32 {
    2000
}

/// Parameters of an `Analyze` run.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyzeParams {
    /// Sectioning.
    pub sections: geom::surface::SectionParams,
    /// The survey.
    pub survey: SurveyParams,
}

/// Geometry of an `Analyze` run.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// The section plane frame.
    pub frame: PlaneFrame,
    /// The sections, their analyses and reports.
    pub survey: Survey,
    /// Extent of the surface along the cutting direction.
    pub extent: [f64; 2],
    /// The surface as loaded.
    pub surface: SurfaceInfo,
}

impl Task for Analyze {
    const NAME: &'static str = "Analyze";
    const REPORT_SCHEMA: &'static str = "report.schema.json";
    const OUTPUTS: &'static [Output<Self>] = &[
        Output::new(OutputKind::Svg, outputs::svg),
        Output::new(OutputKind::Obj, outputs::obj),
    ];
    type Params = AnalyzeParams;
    type Run = Analysis;
    type Report = AnalyzeReport;

    fn check(&self, job: &JobFields<'_>, errors: &mut Vec<JobError>) {
        if job.surface.is_none() {
            errors.push(job.error("/surface", "task Analyze needs a surface"));
        }
    }

    fn params(&self, job: &Context) -> Result<AnalyzeParams> {
        let t = &job.tolerance;
        Ok(AnalyzeParams {
            sections: job.sectioning(),
            survey: SurveyParams {
                curve: CurveAnalysisParams {
                    samples: self.samples as usize,
                    bisection_tolerance: t.bisection,
                    min_lobe_turning: t.min_turning,
                    ..Default::default()
                },
                blade_length: job.blade.length,
                max_curvature: job.blade.max_curvature,
                max_inflections: job.blade.max_inflections,
                block: job.block.as_ref().map(|b| {
                    let size = [b.size.0, b.size.1, b.size.2];
                    (size, b.origin.map(|o| [o.0, o.1, o.2]))
                }),
            },
        })
    }

    fn estimate(p: &AnalyzeParams, job: &Context) -> Estimate {
        let (cost, points) = section_cost(job.surface.as_ref());
        let n = p.sections.count as f64;
        let s = p.survey.curve.samples as f64;
        Estimate::new(
            n * (64.0 * s + 200.0 * points) + 1e7,
            n * (cost + 100.0 * s + 1e3 * points),
            "/task/Analyze/samples",
            "lower the task's samples or cutting.sections",
        )
        // report, drawing and page: each section's samples, some tens of bytes each
        .with_output(n * (s * 60.0 + points * 40.0) + 2e5)
    }

    fn run(params: &AnalyzeParams, job: &Context, progress: &dyn Progress) -> Result<Analysis> {
        let surface = job.surface(Self::NAME)?;
        progress.start("sectioning", params.sections.count as u64);
        let (frame, sections) = surface
            .sections(&params.sections, &|| progress.tick())
            .map_err(job.geom_err("sectioning the surface"))?;
        progress.finish();
        progress.start("analysing sections", sections.len() as u64);
        let survey = survey(&frame, sections, &surface.aabb(), &params.survey, &|| {
            progress.tick()
        })
        .map_err(|e| job.fail(e.to_string()))?;
        progress.finish();
        let (lo, hi) = surface.extent_along(&frame.normal);
        Ok(Analysis {
            frame,
            survey,
            extent: [lo, hi],
            surface: SurfaceInfo::of(job, surface),
        })
    }

    fn report(params: &AnalyzeParams, run: &Analysis, job: &Context) -> AnalyzeReport {
        let arr = |v: &nalgebra::Vector3<f64>| [v.x, v.y, v.z];
        let f = &run.frame;
        let s = &params.survey;
        AnalyzeReport {
            job: job.name.clone(),
            task: Self::NAME.into(),
            units: job.units,
            hotcut_version: crate::report::VERSION.into(),
            surface: run.surface.clone(),
            cutting: CuttingInfo {
                direction: arr(&f.normal),
                plane_u: arr(&f.u),
                plane_v: arr(&f.v),
                planes: params.sections.count,
                extent: run.extent,
            },
            constraints: ConstraintsInfo {
                blade_length: s.blade_length,
                max_curvature: s.max_curvature,
                max_inflections: s.max_inflections,
                block_size: s.block.map(|b| b.0),
            },
            summary: run.survey.summary.clone(),
            sections: run.survey.reports.clone(),
        }
    }

    fn page(r: &AnalyzeReport, job: &Context) -> export::html::Body {
        page::body(r, job)
    }

    fn summary(r: &AnalyzeReport, job: &Context) -> String {
        let units = job.units.symbol();
        let s = &r.summary;
        let c = &r.constraints;
        let mut out = format!(
            "{}: {} section(s) on {} plane(s), longest {:.1} {units}, {} inflection(s) (at most {} on one), max |curvature| {:.5} /{units}",
            r.job, s.pieces, s.planes_with_sections, s.max_length, s.total_inflections, s.max_inflections, s.max_abs_curvature
        );
        let mut line = |l: String| {
            out.push('\n');
            out.push_str(&l);
        };
        line(format!(
            "  dimension:    {} section(s) longer than the blade ({} {units})",
            s.sections_too_long, c.blade_length
        ));
        for v in &s.surface_violations {
            if let Violation::Dimension { what, value, limit } = v {
                line(format!(
                    "                surface {value:.1} {units} > block {limit} {units} ({what})"
                ));
            }
        }
        if c.block_size.is_none() {
            line("                no block given: block size not checked".into());
        }
        line(format!(
            "  shape:        {} section(s) with more than {} inflection(s)",
            s.sections_too_many_inflections, c.max_inflections
        ));
        line(format!(
            "  blade strain: {} section(s) above |curvature| {} /{units}",
            s.sections_too_curved, c.max_curvature
        ));
        for w in &r.surface.warnings {
            line(format!("  warning: {w}"));
        }
        out
    }
}
