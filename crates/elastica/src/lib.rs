//! # elastica — the mathematical heart of hot-blade cutting
//!
//! A hot blade held by two robots takes the shape of a planar Euler elastica. This crate
//! evaluates elastica exactly (Jacobi elliptic functions), fits them to section curves,
//! computes discrete elastica from boundary data, and extends a fitted segment to the
//! blade's length to give the robots their targets.

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
/// Elastica segments (closed form, line, arc): evaluation, derivatives, inflections.
pub mod segment;
/// Elastica-swept patches: parameter interpolation between sections, 3D blade poses.
pub mod sweep;
/// The normalized inflectional and non-inflectional elastica.
pub mod unit;
