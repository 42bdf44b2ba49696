//! The report an `Analyze` run writes as `report.json`; its JSON Schema is
//! `schemas/report.schema.json`. Lengths are in the job's units, curvatures in 1/unit,
//! positions in the job's frame; floats are rounded to
//! [`export::json::REPORT_DIGITS`](export::json::REPORT_DIGITS) significant digits when written.

use schemars::JsonSchema;
use serde::Serialize;

use crate::job::Units;

/// The result of the `Analyze` task.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct AnalyzeReport {
    /// Job name.
    pub job: String,
    /// Task name, `Analyze`.
    pub task: String,
    /// Length unit.
    pub units: Units,
    /// The surface as loaded.
    pub surface: SurfaceInfo,
    /// The section planes.
    pub cutting: CuttingInfo,
    /// The constraints checked.
    pub constraints: ConstraintsInfo,
    /// Totals and the verdict.
    pub summary: Summary,
    /// One entry per section piece, by plane then piece.
    pub sections: Vec<SectionReport>,
}

/// What was loaded.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SurfaceInfo {
    /// `HeightField`, `Mesh` or `Spline`.
    pub kind: String,
    /// Minimum corner of the bounding box (height-field and spline heights are sampled).
    pub bbox_min: [f64; 3],
    /// Maximum corner of the bounding box.
    pub bbox_max: [f64; 3],
    /// Non-fatal findings while loading.
    pub warnings: Vec<String>,
}

impl SurfaceInfo {
    /// What a resolved job loaded.
    pub fn of(job: &crate::load::ResolvedJob, surface: &geom::surface::Surface) -> Self {
        let b = surface.aabb();
        Self {
            kind: crate::analyze::surface_kind(surface).into(),
            bbox_min: [b.min.x, b.min.y, b.min.z],
            bbox_max: [b.max.x, b.max.y, b.max.z],
            warnings: job.warnings.clone(),
        }
    }
}

/// The plane family.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CuttingInfo {
    /// Unit cutting direction (plane normal).
    pub direction: [f64; 3],
    /// First in-plane axis: section coordinates are `(u, v)`.
    pub plane_u: [f64; 3],
    /// Second in-plane axis.
    pub plane_v: [f64; 3],
    /// Number of planes.
    pub planes: usize,
    /// Extent of the surface along the direction, `[min, max]`.
    pub extent: [f64; 2],
}

/// The production constraints checked (thesis §5.1).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ConstraintsInfo {
    /// Blade length.
    pub blade_length: f64,
    /// Largest allowed |curvature|.
    pub max_curvature: f64,
    /// Most inflections allowed per section.
    pub max_inflections: u32,
    /// Block size, if given.
    pub block_size: Option<[f64; 3]>,
}

/// A production constraint a section or the surface breaks.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[serde(tag = "constraint", rename_all = "snake_case")]
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
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SectionPoint {
    /// Arc length from the section's start.
    pub s: f64,
    /// Position in the job's frame.
    pub position: [f64; 3],
    /// Signed curvature there (left turn in the `(u, v)` plane is positive).
    pub curvature: f64,
}

/// One section piece.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
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
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
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

/// The result of the `FitCurves` task (`report.json`; schema
/// `schemas/fit-curves-report.schema.json`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FitCurvesReport {
    /// Job name.
    pub job: String,
    /// Task name, `FitCurves`.
    pub task: String,
    /// Length unit of every coordinate and length; curvatures in 1/unit.
    pub units: Units,
    /// Where the curves came from: `file <path>` or `sections of the <kind> surface`.
    pub source: String,
    /// The boundary constraint every fit honours.
    pub constraint: crate::job::FitConstraintSpec,
    /// Totals.
    pub summary: FitSummary,
    /// One entry per curve, in input order (sections: by plane, then piece).
    pub curves: Vec<CurveFit>,
}

/// Totals of a `FitCurves` run.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FitSummary {
    /// Curves read.
    pub curves: usize,
    /// Curves that could not be fitted (see their `error`).
    pub failed: usize,
    /// Fits that are straight lines.
    pub lines: usize,
    /// Fits that are circular arcs.
    pub arcs: usize,
    /// Fits that are inflectional elastica.
    pub inflectional: usize,
    /// Fits that are non-inflectional elastica.
    pub noninflectional: usize,
    /// Largest RMS distance over the curves.
    pub max_rms: f64,
    /// Median RMS distance over the curves.
    pub median_rms: f64,
    /// Largest distance between a point and its match on the fit, over all curves.
    pub max_distance: f64,
}

/// One curve and its fit.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct CurveFit {
    /// The curve's id (from the input file; `section <plane>.<piece>` for sections).
    pub id: String,
    /// Number of input points.
    pub points: usize,
    /// Length of the input polyline (sections: of the section curve).
    pub input_length: f64,
    /// Why the curve could not be fitted; absent when it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The fit; absent when the curve could not be fitted.
    #[serde(flatten)]
    pub fit: Option<FittedCurve>,
}

/// A fitted segment with its quality and geometry.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct FittedCurve {
    /// `line`, `arc`, `inflectional` or `noninflectional`.
    pub family: String,
    /// The segment's parameters. Elastica: the papers' `k`, `s0`, `l`, `S`, `phi`, `x0`,
    /// `y0` (the point at t ∈ [0, 1] is S·R(φ)·f(s₀ + ℓt) + (x₀, y₀); ℓ < 0 runs the
    /// normalized curve backwards). Line: `x0`, `y0`, `phi`, `length`. Arc: `x0`, `y0`,
    /// `phi` (start tangent angle), `curvature` (signed, left positive), `length`.
    pub parameters: std::collections::BTreeMap<String, f64>,
    /// Root-mean-square distance over arc length between the curve and the fit, √(∫|x − γ|² ds / L).
    pub rms: f64,
    /// Largest distance between an input point and its matched point on the fit.
    pub max: f64,
    /// Length of the fitted segment.
    pub length: f64,
    /// Number of inflection points of the fitted segment.
    pub inflections: usize,
    /// The inflection points of the fitted segment.
    pub inflection_points: Vec<[f64; 2]>,
    /// Largest |curvature| along the fitted segment.
    pub max_abs_curvature: f64,
    /// Solver iterations.
    pub iterations: usize,
    /// Whether the last solve met its convergence test.
    pub converged: bool,
    /// The fitted segment sampled at 400 points equally spaced in arc length.
    pub fitted: Vec<[f64; 2]>,
}

/// The report of whichever task ran.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum TaskReport {
    /// From `Analyze` (boxed: it is much larger than the other reports' headers).
    Analyze(Box<AnalyzeReport>),
    /// From `FitCurves`.
    FitCurves(FitCurvesReport),
    /// From `HotBlade`.
    HotBlade(Box<crate::hot_blade::report::HotBladeReport>),
    /// From `FacadeSegmentation`.
    FacadeSegmentation(Box<crate::segmentation::report::SegmentationReport>),
    /// From `BlockSegmentation`.
    BlockSegmentation(Box<crate::block_seg::BlockSegReport>),
    /// From `PreCut`.
    PreCut(Box<crate::pre_cut::PreCutReport>),
}

impl TaskReport {
    /// The `Analyze` report, if that task ran.
    pub fn analyze(&self) -> Option<&AnalyzeReport> {
        match self {
            Self::Analyze(r) => Some(r),
            _ => None,
        }
    }

    /// The `HotBlade` report, if that task ran.
    pub fn hot_blade(&self) -> Option<&crate::hot_blade::report::HotBladeReport> {
        match self {
            Self::HotBlade(r) => Some(r),
            _ => None,
        }
    }

    /// The `FacadeSegmentation` report, if that task ran.
    pub fn segmentation(&self) -> Option<&crate::segmentation::report::SegmentationReport> {
        match self {
            Self::FacadeSegmentation(r) => Some(r),
            _ => None,
        }
    }

    /// The `BlockSegmentation` report, if that task ran.
    pub fn block_segmentation(&self) -> Option<&crate::block_seg::BlockSegReport> {
        match self {
            Self::BlockSegmentation(r) => Some(r),
            _ => None,
        }
    }

    /// The `PreCut` report, if that task ran.
    pub fn pre_cut(&self) -> Option<&crate::pre_cut::PreCutReport> {
        match self {
            Self::PreCut(r) => Some(r),
            _ => None,
        }
    }

    /// The `FitCurves` report, if that task ran.
    pub fn fit_curves(&self) -> Option<&FitCurvesReport> {
        match self {
            Self::FitCurves(r) => Some(r),
            _ => None,
        }
    }
}
