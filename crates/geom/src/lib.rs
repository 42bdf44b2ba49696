//! # geom — the geometry kernel of hotcut
//!
//! B-spline curves and surfaces, planar curve analysis (curvature, inflections), the
//! surfaces hotcut cuts (meshes, height fields, B-spline surfaces) and their sections by
//! parallel planes, boxes, convex hulls and a triangle index. No I/O beyond reading meshes;
//! no serde: the job-file layer maps these types at the edge.
//!
//! ```
//! use geom::{analyze_curve, CurveAnalysisParams, Expr, HeightField, SectionParams, Surface};
//!
//! // z = 100·sin(y/200) over a 1000 × 2000 rectangle, cut by 4 planes normal to x
//! let hf = HeightField::try_new(Expr::parse("100*sin(y/200)")?, (0.0, 1000.0), (0.0, 2000.0))?;
//! let (_frame, sections) = Surface::HeightField(hf)
//!     .sections(&SectionParams { count: 4, ..SectionParams::default() }, &|| {})?;
//! assert_eq!(sections.len(), 4);
//! let a = analyze_curve(&sections[0].curve, &CurveAnalysisParams::default())?;
//! // sin(y/200) changes sign at y = 200π·k: k = 1, 2, 3 lie inside (0, 2000)
//! assert_eq!(a.inflections.len(), 3);
//! for (p, k) in a.inflections.iter().zip(1..) {
//!     assert!((p.point.x - 200.0 * std::f64::consts::PI * k as f64).abs() < 1e-6);
//! }
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// Curve analysis: inflections, lobes, curvature maxima.
pub mod analysis;
/// Symmetric banded Cholesky solver for the spline fits.
mod banded;
/// Axis-aligned and oriented boxes.
pub mod bbox;
/// B-spline curves: evaluation, derivatives, knot insertion.
pub mod bspline;
/// Curvature at the ends of a sampled curve, from local fits to its points.
pub mod ends;
/// The error type.
pub mod error;
/// Height-field expressions with exact derivatives along lines.
pub mod expr;
/// Least-squares and smoothing B-spline fits.
pub mod fit;
/// Height fields and their exact sections.
pub mod heightfield;
/// 3D convex hull.
pub mod hull;
/// R*-tree index over mesh triangles.
pub mod index;
/// Triangle meshes: OBJ loading, validation, area, volume.
pub mod mesh;
/// Unit surface normals near points (exact for height fields).
pub mod normals;
/// Planar curves: the `PlanarCurve` trait, curvature, arc length.
pub mod planar;
/// Planar polylines: chord lengths, distance from a point, angles wrapped to one turn.
pub mod polyline;
/// When a curvature sign change is an inflection: lobes against the noise floor.
pub mod significance;
/// Plane frames, slab offsets and mesh slicing.
pub mod slice;
/// The `Surface` interface and sectioning by plane families.
pub mod surface;
/// Tensor-product B-spline, ruled and piecewise-ruled surfaces.
pub mod surface_spline;
/// User text made safe for each sink: XML, terminal, G-code and RAPID comments.
pub mod text;
/// The rounded unit frame problems are solved in, the same numbers in any unit.
pub mod unit;

pub use analysis::{analyze_curve, CurveAnalysis, CurveAnalysisParams};
pub use bspline::BSplineCurve;
pub use error::{GeomError, ParamProblem, Result};
pub use expr::Expr;
pub use fit::{fit_least_squares, fit_smoothing, SmoothingParams, SplineFit};
pub use heightfield::HeightField;
pub use hull::convex_hull;
pub use mesh::TriMesh;
pub use slice::PlaneFrame;
pub use surface::{Section, SectionCurve, SectionParams, Surface};
pub use surface_spline::BSplineSurface;
