//! # elastica — the mathematical heart of hot-blade cutting
//!
//! A hot blade held by two robots takes the shape of a planar Euler elastica. This crate
//! evaluates elastica exactly (Jacobi elliptic functions), fits them to section curves,
//! computes discrete elastica from boundary data, and extends a fitted segment to the
//! blade's length to give the robots their targets.
//!
//! ```
//! use elastica::{fit_points, jacobi, ElasticaParams, Family, FitParams, Segment};
//!
//! // Jacobi elliptic functions at u = 0.8, m = 0.36: sn² + cn² = 1 and dn² + m·sn² = 1
//! let m = 0.36;
//! let v = jacobi(0.8, m)?;
//! assert!((v.sn * v.sn + v.cn * v.cn - 1.0).abs() < 1e-15);
//! assert!((v.dn * v.dn + m * v.sn * v.sn - 1.0).abs() < 1e-15);
//!
//! // 40 points on an inflectional elastica (k = 0.6, about 250 mm long)...
//! let truth = Segment::Elastica(ElasticaParams {
//!     family: Family::Inflectional,
//!     k: 0.6,
//!     s0: 0.3,
//!     l: 2.5,
//!     scale: 100.0,
//!     phi: 0.2,
//!     x0: 10.0,
//!     y0: -5.0,
//!     one_minus_k: None,
//! });
//! let points = truth.sample(40)?;
//!
//! // ...are fitted back by the same elastica, to rounding
//! let fit = fit_points(&points, &FitParams::default())?;
//! assert!(fit.max < 1e-6, "max distance {}", fit.max);
//! let Segment::Elastica(p) = fit.segment else {
//!     panic!("expected an elastica, got a {}", fit.segment.kind());
//! };
//! assert_eq!(p.family, Family::Inflectional);
//! assert!((p.k - 0.6).abs() < 1e-6);
//! assert!((fit.segment.length() - truth.length()).abs() < 1e-6);
//! // and it has the original's one inflection
//! assert_eq!(fit.segment.inflections()?.len(), 1);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

/// Extension of a fitted segment to the blade length; robot end data and blade checks.
pub mod blade;
/// Carlson's symmetric elliptic integrals R_F, R_D.
pub mod carlson;
/// The blade outside its cut against the block: gouges into kept material, holder clearance.
pub mod clearance;
/// Double-double arithmetic for the quarter period.
mod dd;
/// Discrete elastica from boundary data (turning-angle energy, Newton–KKT, augmented-Lagrangian fallback).
pub mod discrete;
/// Jacobi elliptic functions, epsilon function, complete integrals.
pub mod elliptic;
/// Fitting curves by elastica segments (variable projection + Levenberg–Marquardt).
pub mod fit;
/// Process-wide memos of costly functions of blades, keyed by their exact bits.
pub(crate) mod memo;
/// Where along the blade a piece sits: clear of its block, stable, without snapping.
pub mod place;
/// Elastica segments (closed form, line, arc): evaluation, derivatives, inflections.
pub mod segment;
/// Whether a held blade keeps its shape: second variation, margin, end forces, continuation.
pub mod stability;
/// Elastica-swept patches: parameter interpolation between sections, 3D blade poses.
pub mod sweep;
/// The normalized inflectional and non-inflectional elastica.
pub mod unit;

pub use blade::{extend_to_blade, Blade, BladeEnd, BladeError, BladeParams};
pub use clearance::{place, Clearance, Section};
pub use discrete::{discrete_elastica, DiscreteElastica, DiscreteError, DiscreteParams};
pub use elliptic::{ellip_e, ellip_k, jacobi, Elliptic, EllipticError, JacobiValues};
pub use fit::{
    fit_curve, fit_points, fit_points_with_arclength, fit_with_end_tangents, polish, FitConstraint,
    FitError, FitParams, FitResult,
};
pub use segment::{ElasticaParams, Segment, SegmentPoint};
pub use stability::{
    stability, BladeSection, Class, HolderLoads, Stability, StabilityParams, Stiffness,
};
pub use sweep::{blade_pose, interpolate, BladePose};
pub use unit::{Family, UnitElastica};
