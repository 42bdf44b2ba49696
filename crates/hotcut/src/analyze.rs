//! The `Analyze` task (thesis §5.1): section the surface and, for every section, report
//! its length, inflections, curvature maxima and the production constraints it breaks.
//!
//! Entry point: [`analyze`](crate::analyze::analyze) with [`AnalyzeParams`](crate::analyze::AnalyzeParams); the result keeps the geometry
//! ([`Analysis`](crate::analyze::Analysis)) for drawing, and [`Analysis::report`](crate::analyze::Analysis::report) is what `report.json` holds.

use geom::analysis::{analyze_curve, CurveAnalysis, CurveAnalysisParams, CurvePoint};
use geom::fit::SmoothingParams;
use geom::planar::PlanarCurve;
use geom::slice::PlaneFrame;
use geom::surface::{Section, SectionParams, Surface};
use rayon::prelude::*;

use crate::error::{HotcutError, Result};
use crate::load::ResolvedJob;
use crate::report::*;
use crate::Progress;

/// Parameters of [`analyze`], taken from the job.
#[derive(Debug, Clone, PartialEq)]
pub struct AnalyzeParams {
    /// Sectioning.
    pub sections: SectionParams,
    /// Curve analysis.
    pub curve: CurveAnalysisParams,
}

/// The job's name for a surface kind: `HeightField`, `Mesh` or `Spline`.
pub fn surface_kind(surface: &Surface) -> &'static str {
    match surface {
        Surface::Mesh(_) => "Mesh",
        Surface::HeightField(_) => "HeightField",
        Surface::Spline(_) => "Spline",
    }
}

impl AnalyzeParams {
    /// How the job's `cutting` and `tolerance` section the surface (shared by the tasks
    /// that work on sections).
    pub fn sectioning(job: &ResolvedJob) -> SectionParams {
        SectionParams {
            direction: job.direction,
            count: job.job.cutting.sections as usize,
            smoothing: SmoothingParams {
                degree: 3,
                tolerance: job.job.tolerance.smoothing,
                max_control: 400,
                chordal: false,
            },
            spline_grid: 200,
        }
    }

    /// The parameters a resolved job asks for (the default curve sampling for tasks other
    /// than `Analyze`).
    pub fn from_job(job: &ResolvedJob) -> Self {
        let samples = match job.job.task {
            crate::job::TaskSpec::Analyze { samples } => samples,
            _ => 2000,
        };
        let t = &job.job.tolerance;
        Self {
            sections: Self::sectioning(job),
            curve: CurveAnalysisParams {
                samples: samples as usize,
                bisection_tolerance: t.bisection,
                min_lobe_turning: t.min_turning,
                end_margins: (0.0, 0.0),
            },
        }
    }
}

/// Geometry and report of an `Analyze` run.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// The section plane frame.
    pub frame: PlaneFrame,
    /// Sections with their analyses, in report order.
    pub sections: Vec<(Section, CurveAnalysis)>,
    /// The report.
    pub report: AnalyzeReport,
}

fn arr(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Runs the task on a resolved job.
///
/// # Errors
/// [`HotcutError::Geom`] when sectioning or a curve analysis fails.
pub fn analyze(
    job: &ResolvedJob,
    params: &AnalyzeParams,
    progress: &dyn Progress,
) -> Result<Analysis> {
    let geom_err = |context: String| {
        let path = job.path.clone();
        move |source| HotcutError::Geom {
            path,
            context,
            source,
        }
    };
    let surface = job.surface.as_ref().ok_or_else(|| {
        HotcutError::Invalid(vec![crate::error::JobError::Semantic {
            path: job.path.clone(),
            pointer: "/surface".into(),
            message: "task Analyze needs a surface".into(),
        }])
    })?;
    progress.start("sectioning", params.sections.count as u64);
    let (frame, sections) = surface
        .sections(&params.sections, &|| progress.tick())
        .map_err(geom_err("sectioning the surface".into()))?;
    progress.finish();

    progress.start("analysing sections", sections.len() as u64);
    let analysed: Vec<Result<(Section, CurveAnalysis)>> = sections
        .into_par_iter()
        .map(|s| {
            let curve_params = CurveAnalysisParams {
                end_margins: s.end_margins,
                ..params.curve.clone()
            };
            let a = analyze_curve(&s.curve, &curve_params)
                .map_err(geom_err(format!("section {} piece {}", s.index, s.piece)));
            progress.tick();
            a.map(|a| (s, a))
        })
        .collect();
    progress.finish();
    let sections: Vec<(Section, CurveAnalysis)> = analysed.into_iter().collect::<Result<_>>()?;

    let blade = &job.blade;
    let mut reports = Vec::with_capacity(sections.len());
    for (s, a) in &sections {
        let point = |p: &CurvePoint| SectionPoint {
            s: p.s,
            position: arr(&frame.to_world(s.offset, &p.point)),
            curvature: p.curvature,
        };
        let mut violations = Vec::new();
        if a.length > blade.length {
            violations.push(Violation::Dimension {
                what: "section_longer_than_blade".into(),
                value: a.length,
                limit: blade.length,
            });
        }
        if a.inflections.len() > blade.max_inflections as usize {
            violations.push(Violation::Shape {
                inflections: a.inflections.len(),
                limit: blade.max_inflections,
            });
        }
        let kmax = a.max_abs_curvature.curvature.abs();
        if kmax > blade.max_curvature {
            violations.push(Violation::BladeStrain {
                max_abs_curvature: kmax,
                limit: blade.max_curvature,
                at_s: a.max_abs_curvature.s,
            });
        }
        reports.push(SectionReport {
            index: s.index,
            piece: s.piece,
            offset: s.offset,
            closed: s.closed,
            length: a.length,
            fit_rms: s.fit_rms,
            inflections: a.inflections.iter().map(point).collect(),
            curvature_maxima: a.curvature_maxima.iter().map(point).collect(),
            max_abs_curvature: kmax,
            suppressed_inflections: a.suppressed_inflections,
            violations,
        });
    }

    let bbox = surface.aabb();
    let size = bbox.size();
    let mut surface_violations = Vec::new();
    if let Some(b) = &job.job.block {
        let block = [b.size.0, b.size.1, b.size.2];
        for (i, axis) in ["x", "y", "z"].iter().enumerate() {
            if size[i] > block[i] {
                surface_violations.push(Violation::Dimension {
                    what: format!("surface_larger_than_block_{axis}"),
                    value: size[i],
                    limit: block[i],
                });
            } else if let Some(o) = b.origin {
                // a placed block must also contain the surface
                let lo = [o.0, o.1, o.2][i];
                if bbox.min[i] < lo {
                    surface_violations.push(Violation::Dimension {
                        what: format!("surface_below_block_{axis}"),
                        value: bbox.min[i],
                        limit: lo,
                    });
                }
                if bbox.max[i] > lo + block[i] {
                    surface_violations.push(Violation::Dimension {
                        what: format!("surface_above_block_{axis}"),
                        value: bbox.max[i],
                        limit: lo + block[i],
                    });
                }
            }
        }
    }
    let count = |f: &dyn Fn(&Violation) -> bool| {
        reports
            .iter()
            .filter(|r| r.violations.iter().any(f))
            .count()
    };
    let sections_too_long = count(&|v| matches!(v, Violation::Dimension { .. }));
    let sections_too_many_inflections = count(&|v| matches!(v, Violation::Shape { .. }));
    let sections_too_curved = count(&|v| matches!(v, Violation::BladeStrain { .. }));
    let mut planes: Vec<usize> = reports.iter().map(|r| r.index).collect();
    planes.dedup();
    let summary = Summary {
        planes_with_sections: planes.len(),
        pieces: reports.len(),
        max_length: reports.iter().map(|r| r.length).fold(0.0, f64::max),
        total_inflections: reports.iter().map(|r| r.inflections.len()).sum(),
        max_inflections: reports
            .iter()
            .map(|r| r.inflections.len())
            .max()
            .unwrap_or(0),
        max_abs_curvature: reports
            .iter()
            .map(|r| r.max_abs_curvature)
            .fold(0.0, f64::max),
        sections_too_long,
        sections_too_many_inflections,
        sections_too_curved,
        cuttable_without_segmentation: surface_violations.is_empty()
            && sections_too_long + sections_too_many_inflections + sections_too_curved == 0,
        surface_violations,
    };
    let (lo, hi) = surface.extent_along(&frame.normal);
    let report = AnalyzeReport {
        job: job.job.name.clone(),
        task: "Analyze".into(),
        units: job.job.units,
        surface: SurfaceInfo::of(job, surface),
        cutting: CuttingInfo {
            direction: arr(&frame.normal),
            plane_u: arr(&frame.u),
            plane_v: arr(&frame.v),
            planes: params.sections.count,
            extent: [lo, hi],
        },
        constraints: ConstraintsInfo {
            blade_length: blade.length,
            max_curvature: blade.max_curvature,
            max_inflections: blade.max_inflections,
            block_size: job
                .job
                .block
                .as_ref()
                .map(|b| [b.size.0, b.size.1, b.size.2]),
        },
        summary,
        sections: reports,
    };
    Ok(Analysis {
        frame,
        sections,
        report,
    })
}

/// Points along a section in world coordinates, `n + 1` equally spaced in parameter.
pub fn sample_world(frame: &PlaneFrame, s: &Section, n: usize) -> Vec<nalgebra::Vector3<f64>> {
    let (a, b) = s.curve.domain();
    (0..=n)
        .map(|i| frame.to_world(s.offset, &s.curve.point(a + (b - a) * i as f64 / n as f64)))
        .collect()
}
