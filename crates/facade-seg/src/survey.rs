//! The survey of a facade before anything is cut (thesis §5.1): every section's length,
//! inflections and curvature maxima, the production constraints it breaks, and whether
//! the surface as a whole fits the block. The `Analyze` task reports it.
//!
//! Entry point: [`survey`](crate::survey::survey).

use geom::analysis::{analyze_curve, CurveAnalysis, CurveAnalysisParams, CurvePoint};
use geom::bbox::Aabb;
use geom::slice::PlaneFrame;
use geom::surface::Section;
use rayon::prelude::*;

use crate::SegError;

/// Parameters of [`survey`].
#[derive(Debug, Clone, PartialEq)]
pub struct SurveyParams {
    /// Curve analysis of every section (its `end_margins` come from each section).
    pub curve: CurveAnalysisParams,
    /// Blade length: a longer section breaks the dimension constraint.
    pub blade_length: f64,
    /// Largest |curvature| the blade takes.
    pub max_curvature: f64,
    /// Most inflections a section may have.
    pub max_inflections: u32,
    /// The block's size and, when placed, its min corner; `None`: not checked.
    pub block: Option<([f64; 3], Option<[f64; 3]>)>,
}

/// A facade's survey.
#[derive(Debug, Clone)]
pub struct Survey {
    /// The sections with their analyses, in input order.
    pub sections: Vec<(Section, CurveAnalysis)>,
    /// Per section its measures and violations, in the same order.
    pub reports: Vec<SectionReport>,
    /// Totals and the verdict.
    pub summary: Summary,
}

/// A production constraint a section or the surface breaks.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
#[cfg_attr(
    feature = "serde",
    serde(tag = "constraint", rename_all = "snake_case")
)]
pub enum Violation {
    /// Dimension (§5.1.1): the section is longer than the blade.
    Dimension {
        /// What exceeds: `section_longer_than_blade`, `surface_larger_than_block_<axis>`, or for
        /// a block with an `origin`, `surface_below_block_<axis>` / `surface_above_block_<axis>`
        /// (the surface sticks out of the placed block).
        what: String,
        /// The measured size.
        value: f64,
        /// The limit.
        limit: f64,
    },
    /// Shape (§5.1.3): more inflections than the blade can hold.
    Shape {
        /// Inflections found.
        inflections: usize,
        /// Most allowed.
        limit: u32,
    },
    /// Blade strain (§5.1.4): curvature above what the blade takes.
    BladeStrain {
        /// Largest |curvature| on the section.
        max_abs_curvature: f64,
        /// The limit.
        limit: f64,
        /// Arc length where it occurs.
        at_s: f64,
    },
}

/// A point on a section.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SectionPoint {
    /// Arc length from the section's start.
    pub s: f64,
    /// Position in the job's frame.
    pub position: [f64; 3],
    /// Signed curvature there (left turn in the `(u, v)` plane is positive).
    pub curvature: f64,
}

/// One section piece.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct SectionReport {
    /// Plane index, from 0.
    pub index: usize,
    /// Piece within the plane, from 0 (a plane can cut the surface in several pieces).
    pub piece: usize,
    /// Plane offset along the cutting direction.
    pub offset: f64,
    /// Whether the piece is a closed loop.
    pub closed: bool,
    /// Arc length.
    pub length: f64,
    /// RMS deviation of the smoothing spline from the sectioned points (0 for exact sections).
    pub fit_rms: f64,
    /// Inflection points in order along the section.
    pub inflections: Vec<SectionPoint>,
    /// Curvature maxima, one per stretch between inflections.
    pub curvature_maxima: Vec<SectionPoint>,
    /// Largest |curvature| on the section.
    pub max_abs_curvature: f64,
    /// Inflections dropped as noise: pairs around stretches turning less than
    /// `tolerance.min_turning`, and sign changes inside the first or last segment of a
    /// polyline section.
    pub suppressed_inflections: usize,
    /// Constraints this section breaks.
    pub violations: Vec<Violation>,
}

/// Totals.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Summary {
    /// Planes that cut the surface.
    pub planes_with_sections: usize,
    /// Section pieces.
    pub pieces: usize,
    /// Longest section.
    pub max_length: f64,
    /// Inflections over all sections.
    pub total_inflections: usize,
    /// Most inflections on one section.
    pub max_inflections: usize,
    /// Largest |curvature| over all sections.
    pub max_abs_curvature: f64,
    /// Sections longer than the blade.
    pub sections_too_long: usize,
    /// Sections with too many inflections.
    pub sections_too_many_inflections: usize,
    /// Sections whose curvature strains the blade.
    pub sections_too_curved: usize,
    /// Violations of the surface as a whole (larger than the block).
    pub surface_violations: Vec<Violation>,
    /// True when nothing is violated: one block, one blade, no segmentation needed.
    pub cuttable_without_segmentation: bool,
}

fn arr(v: &nalgebra::Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// Surveys `sections` (cut by planes of `frame`) of a surface whose bounding box is
/// `bbox`; `tick` is called once per section analysed (from worker threads).
///
/// # Errors
/// [`SegError::Section`] when a section's curve cannot be analysed.
pub fn survey(
    frame: &PlaneFrame,
    sections: Vec<Section>,
    bbox: &Aabb,
    params: &SurveyParams,
    tick: &(dyn Fn() + Sync),
) -> Result<Survey, SegError> {
    let analysed: Vec<Result<(Section, CurveAnalysis), SegError>> = sections
        .into_par_iter()
        .map(|s| {
            let curve_params = s.analysis_params(&params.curve);
            let a = analyze_curve(&s.curve, &curve_params).map_err(|e| SegError::Section {
                index: s.index,
                message: format!("piece {}: {e}", s.piece),
            });
            tick();
            a.map(|a| (s, a))
        })
        .collect();
    let sections: Vec<(Section, CurveAnalysis)> = analysed.into_iter().collect::<Result<_, _>>()?;
    let reports: Vec<SectionReport> = sections
        .iter()
        .map(|(s, a)| section_report(frame, s, a, params))
        .collect();
    let summary = Summary::of(&reports, surface_violations(bbox, params));
    Ok(Survey {
        sections,
        reports,
        summary,
    })
}

/// One section's measures and the constraints it breaks.
fn section_report(
    frame: &PlaneFrame,
    s: &Section,
    a: &CurveAnalysis,
    params: &SurveyParams,
) -> SectionReport {
    let point = |p: &CurvePoint| SectionPoint {
        s: p.s,
        position: arr(&frame.to_world(s.offset, &p.point)),
        curvature: p.curvature,
    };
    let violations = violations(a, params);
    let kmax = a.max_abs_curvature.curvature.abs();
    SectionReport {
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
    }
}

/// The production constraints (§5.1.1, §5.1.3, §5.1.4) one analysed section breaks.
pub(crate) fn violations(a: &CurveAnalysis, params: &SurveyParams) -> Vec<Violation> {
    let mut violations = Vec::new();
    if a.length > params.blade_length {
        violations.push(Violation::Dimension {
            what: "section_longer_than_blade".into(),
            value: a.length,
            limit: params.blade_length,
        });
    }
    if a.inflections.len() > params.max_inflections as usize {
        violations.push(Violation::Shape {
            inflections: a.inflections.len(),
            limit: params.max_inflections,
        });
    }
    let kmax = a.max_abs_curvature.curvature.abs();
    if kmax > params.max_curvature {
        violations.push(Violation::BladeStrain {
            max_abs_curvature: kmax,
            limit: params.max_curvature,
            at_s: a.max_abs_curvature.s,
        });
    }
    violations
}

/// The surface larger than the block, or sticking out of the placed block.
fn surface_violations(bbox: &Aabb, params: &SurveyParams) -> Vec<Violation> {
    let mut out = Vec::new();
    let Some((block, origin)) = params.block else {
        return out;
    };
    let size = bbox.size();
    for (i, axis) in ["x", "y", "z"].iter().enumerate() {
        if size[i] > block[i] {
            out.push(Violation::Dimension {
                what: format!("surface_larger_than_block_{axis}"),
                value: size[i],
                limit: block[i],
            });
        } else if let Some(o) = origin {
            // a placed block must also contain the surface
            let lo = o[i];
            if bbox.min[i] < lo {
                out.push(Violation::Dimension {
                    what: format!("surface_below_block_{axis}"),
                    value: bbox.min[i],
                    limit: lo,
                });
            }
            if bbox.max[i] > lo + block[i] {
                out.push(Violation::Dimension {
                    what: format!("surface_above_block_{axis}"),
                    value: bbox.max[i],
                    limit: lo + block[i],
                });
            }
        }
    }
    out
}

impl Summary {
    /// Totals over `reports`, with the surface's own violations.
    fn of(reports: &[SectionReport], surface_violations: Vec<Violation>) -> Self {
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
        Self {
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
        }
    }
}
