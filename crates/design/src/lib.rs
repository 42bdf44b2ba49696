//! # design — designing for the hot blade
//!
//! The road of "Designing for Robotic Hot-Blade Cutting" (§4): a surface defined so that
//! it can be cut, by planar design curves with one cubic piece per block, each replaced by
//! the elastica with the same end points, end tangents and length.
//!
//! A design curve turned into its elastica, and how far apart the two lie:
//!
//! ```
//! use design::{end_data, proxy, solve, Bezier};
//!
//! // a gentle arch 600 long: the design curve over one block
//! let b = Bezier { p: [[0.0, 0.0], [200.0, 60.0], [400.0, 60.0], [600.0, 0.0]] };
//!
//! // its end data: end points, end tangent angles, length
//! let d = end_data(&b)?;
//! assert_eq!((d.start, d.end), (b.p[0], b.p[3]));
//! assert!((d.start_angle - 0.3f64.atan()).abs() < 1e-15); // the first leg: 60 up in 200
//! assert!((d.end_angle + 0.3f64.atan()).abs() < 1e-12);
//! assert_eq!(d.length, b.length());
//!
//! // the elastica with the same end data, in closed form
//! let elastica = solve(&d)?.segment;
//! let (first, last) = (elastica.eval(0.0)?, elastica.eval(1.0)?);
//! let gap = |p: [f64; 2], q: [f64; 2]| (p[0] - q[0]).hypot(p[1] - q[1]);
//! assert!(gap(first.p, d.start) < 1e-9 * d.length);
//! assert!(gap(last.p, d.end) < 1e-9 * d.length);
//! assert!((first.angle - d.start_angle).abs() < 1e-9);
//! assert!((last.angle - d.end_angle).abs() < 1e-9);
//! assert!((elastica.length() - d.length).abs() < 1e-9 * d.length);
//!
//! // how far the design lies from its elastica
//! let r = proxy(&b)?;
//! assert!(r.end_point_error < 1e-9 * r.length);
//! assert!(r.max_deviation < 0.01 * r.length); // a well-behaved polygon: close to an elastica
//! assert!(r.max_deviation > 1e-6 * r.length); // but a cubic is not one
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The modules:
//!
//! - [`assembly`]: a design's blocks and the cuts through them: each cut resolved
//!   against its blocks, per block its cuts in priority order and their envelope, and
//!   the order the robots cut them in.
//! - [`bezier`]: planar cubic Bézier curves: points, derivatives, curvature, arc length,
//!   end data, the angles of the control polygon.
//! - [`chain`]: design curves over several blocks, one Bézier per block joined G¹, and
//!   their elastica.
//! - [`bvp`]: the elastica with given end points, end tangent angles and length, in
//!   closed form, started from and cross-checked by the discrete elastica.
//! - [`spline`]: design curves over several blocks as one cubic B-spline, C², its knots
//!   on the block faces, each piece handed on as a Bézier.
//! - [`loft`]: curves at stations along the cut lofted with √chord ("tight") spacing.
//! - [`cut`]: one designed cut through a row of blocks: its curves on every station and
//!   cutting plane, their elastica, the blade extended to its length and posed in 3D.
//! - [`envelope`]: several cuts through one block: priority, cuts that touch nothing
//!   dropped, the lower envelope and how far the elastica move its crease.
//! - [`numerical`]: the numerical road ("Hot Blade Cuttings" §5.2, eq. 13): a refined
//!   spline of least bending energy whose control points stay within ε of the input's.
//! - [`proxy`](mod@proxy): how close a Bézier is to its elastica: deviation, length, curvature,
//!   inflections, and the residual of the affine curvature law κ = λ₂x − λ₁y + α
//!   ("Hot Blade Cuttings" eq. 11), which predicts the deviation cheaply.
//!
//! Like the other algorithm crates it does no I/O. It is unit-free: every result scales
//! with the input.

/// A design's blocks and cuts: resolution, per-block envelopes, cutting order.
pub mod assembly;
/// Planar cubic Bézier curves.
pub mod bezier;
/// The elastica with given end points, end tangents and length.
pub mod bvp;
/// Design curves over several blocks, joined G¹.
pub mod chain;
/// One designed cut through a row of blocks.
pub mod cut;
/// Several cuts through one block: the lower envelope and its crease.
pub mod envelope;
/// Errors of the design crate.
pub mod error;
/// Lofting design curves along the cut.
pub mod loft;
/// The numerical spline approach: least bending energy within ε of the input
/// (feature `numerical`, which brings in clarabel).
#[cfg(feature = "numerical")]
pub mod numerical;
/// How close a Bézier is to its elastica.
pub mod proxy;
/// Design curves as one C² cubic B-spline over the blocks.
pub mod spline;

pub use bezier::Bezier;
pub use bvp::{solve, EndData, Solution};
pub use error::{DesignError, Result};
pub use proxy::{end_data, proxy, Proxy};
