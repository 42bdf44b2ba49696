//! Whether a blade held by its two ends keeps the planned shape: the second variation of
//! its bending energy at the equilibrium, and the forces and moments the holders carry.
//!
//! A blade of length `L` clamped at both ends (position and tangent) takes an equilibrium
//! of `½∫κ² ds` under the chord constraint `∫(cos θ, sin θ) ds = d`. With the papers'
//! multipliers `λ = (λ₁, λ₂)` its angle satisfies `θ'' + λ₁ sin θ − λ₂ cos θ = 0`
//! ("Hot Blade Cuttings" eq. 3). The equilibrium is stable when the second variation
//!
//! `Q[ψ] = ∫ ψ'² − q ψ² ds`, `q(s) = λ₁ cos θ + λ₂ sin θ`,
//!
//! is positive for every variation `ψ` of the angle with `ψ(0) = ψ(L) = 0` (the clamped
//! end tangents) and `∫ ψ (−sin θ, cos θ) ds = 0` (the chord, to first order). The
//! **margin** is the smallest eigenvalue `ν` of `Q` on that space (against `∫ψ²`) divided by
//! `4π²/L²`, the same eigenvalue of a straight, unloaded blade: 1 for a straight blade,
//! `1 − P/P_cr` for one compressed by `P` (`P_cr = 4π²EI/L²`, the first clamped–clamped
//! buckling load), 0 where the blade buckles, negative when the blade would leave the
//! shape at the slightest disturbance. It is unit-free: the same in millimetres and in
//! metres, and under rigid motion.
//!
//! [`stability`](crate::stability::stability()) computes it along the closed form: `Q` discretised by finite differences
//! on `n` and `2n` cells, its smallest restricted eigenvalue found by Sturm counts in O(n)
//! (the module `pencil`), the two combined by Richardson extrapolation (the error expands in even
//! powers of the cell size), so the margin is accurate to ~1e-7 for smooth shapes. The
//! tests cross-check it with Jacobi's conjugate-point test along the closed form.
//! [`follow`](crate::stability::follow) gives the discrete blade the robots move through, its equilibrium followed
//! by continuation as the ends move, with its own reduced Hessian.
//!
//! The loads follow from the multipliers: the blade carries the constant internal force
//! `n = −EI·λ` (the part beyond a point pulls the part before it with `n`), so each holder
//! feels a force of magnitude `EI·|λ|`, the blade's tension at an end is `−EI·λ·t` and
//! the bending moment there `EI·κ`.

/// The discrete blade between held ends, and continuation of its equilibrium.
pub mod follow;
/// Sturm counts and bordered solves for the second variation.
pub(crate) mod pencil;

use crate::elliptic::EllipticError;
use crate::segment::Segment;

use pencil::Pencil;

/// Margin below which a stable equilibrium is called marginal: 5 % of a straight blade's
/// stiffness against its first buckling mode. A blade this close to buckling is moved to
/// another shape by disturbances the model leaves out — the foam's drag, gravity, the
/// blade's heating — so a plan keeps its poses above it.
pub const MARGINAL: f64 = 0.05;

/// Finite-difference cells [`stability`] takes at least per radian of the blade's
/// sharpest bend times its length (the cells then turn by under 0.15 rad each).
const RESOLUTION: f64 = 7.0;

/// The most cells [`stability`] takes for one blade.
const MAX_CELLS: usize = 1 << 16;

/// How [`stability`] works.
#[derive(Clone, Debug, PartialEq)]
pub struct StabilityParams {
    /// Margins below this (and ≥ 0) are [`Class::Marginal`].
    pub marginal: f64,
    /// Cells of the coarser finite-difference grid (the finer has twice as many; ≥ 8);
    /// more where the blade bends sharply.
    pub cells: usize,
}

impl Default for StabilityParams {
    fn default() -> Self {
        StabilityParams {
            marginal: MARGINAL,
            cells: 64,
        }
    }
}

/// Stable, marginal or unstable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum Class {
    /// The margin is at least the stated one.
    Stable,
    /// Stable, but by less than the stated margin.
    Marginal,
    /// The blade leaves this shape (negative margin).
    Unstable,
}

impl Class {
    /// The class of `margin` with `marginal` the least margin called stable.
    ///
    /// ```
    /// use elastica::stability::Class;
    /// assert_eq!(Class::of(0.3, 0.05), Class::Stable);
    /// assert_eq!(Class::of(0.01, 0.05), Class::Marginal);
    /// assert_eq!(Class::of(-0.2, 0.05), Class::Unstable);
    /// ```
    pub fn of(margin: f64, marginal: f64) -> Class {
        if !(margin >= 0.0) {
            Class::Unstable
        } else if margin < marginal {
            Class::Marginal
        } else {
            Class::Stable
        }
    }
}

/// The loads of an equilibrium per unit bending stiffness `EI` (multiply by `EI` for
/// forces and moments: [`Loads::scaled`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Loads {
    /// The multipliers `(λ₁, λ₂)` (1/length²): the internal force is `−EI·λ`.
    pub multipliers: [f64; 2],
    /// `|λ|`: the force on either holder over `EI`.
    pub force: f64,
    /// The tension at the first and the second end over `EI` (`−λ·t`; positive pulls the
    /// holder in along the blade, negative pushes it out).
    pub tension: [f64; 2],
    /// The curvature at the first and the second end (1/length): the bending moment the
    /// holder carries over `EI` (positive turns the blade left, as the curvature).
    pub moment: [f64; 2],
}

impl Loads {
    /// The loads of an equilibrium with multipliers `multipliers`, end tangent angles
    /// `angles` and end curvatures `curvatures`.
    pub fn new(multipliers: [f64; 2], angles: [f64; 2], curvatures: [f64; 2]) -> Loads {
        let [l1, l2] = multipliers;
        let tension = |a: f64| -(l1 * a.cos() + l2 * a.sin());
        Loads {
            multipliers,
            force: l1.hypot(l2),
            tension: [tension(angles[0]), tension(angles[1])],
            moment: curvatures,
        }
    }

    /// Forces (`EI`'s force unit) and moments (force × length) of a blade of bending
    /// stiffness `ei` (force × length²).
    ///
    /// ```
    /// use elastica::stability::Loads;
    /// // a circular arc of radius 500 mm: no force, the moment EI/R at both ends
    /// let arc = Loads::new([0.0, 0.0], [0.3, -0.3], [1.0 / 500.0; 2]);
    /// let ei = 5.0e5; // N·mm²
    /// let [force, _, moments] = arc.scaled(ei);
    /// assert_eq!(force, [0.0, 0.0]);
    /// assert!((moments[0] - 1000.0).abs() < 1e-9); // N·mm
    /// ```
    /// Returns `[[force, force], tension, moment]`.
    pub fn scaled(&self, ei: f64) -> [[f64; 2]; 3] {
        [
            [ei * self.force; 2],
            self.tension.map(|t| ei * t),
            self.moment.map(|m| ei * m),
        ]
    }
}

/// A blade's bending stiffness and the length unit its shapes are in: what turns
/// [`Loads`] (per unit `EI`, in that unit) into newtons and newton-metres.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stiffness {
    /// `EI`, N·m².
    pub ei: f64,
    /// Metres per length unit of the shapes (1e-3 for millimetres).
    pub metres_per_unit: f64,
}

impl Stiffness {
    /// The stiffness of `section` (thickness and width in the unit of `metres_per_unit`,
    /// Young's modulus in pascals).
    ///
    /// ```
    /// use elastica::stability::{BladeSection, Stiffness};
    /// // 1 mm × 25 mm of spring steel (200 GPa), the shapes in millimetres
    /// let mm = BladeSection { thickness: 1.0, width: 25.0, youngs_modulus: 200e9 };
    /// let s = Stiffness::of(&mm, 1e-3);
    /// assert!((s.ei - 200e9 * 0.025 * 1e-9 / 12.0).abs() < 1e-15);
    /// // the same blade with the shapes in metres: the same stiffness
    /// let m = BladeSection { thickness: 1e-3, width: 0.025, youngs_modulus: 200e9 };
    /// assert!((Stiffness::of(&m, 1.0).ei / s.ei - 1.0).abs() < 1e-12);
    /// ```
    pub fn of(section: &BladeSection, metres_per_unit: f64) -> Stiffness {
        let m = metres_per_unit;
        Stiffness {
            ei: section.youngs_modulus * (section.width * m) * (section.thickness * m).powi(3)
                / 12.0,
            metres_per_unit,
        }
    }
}

/// What the holders carry, in newtons and newton-metres.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub struct HolderLoads {
    /// The force on either holder, N (`EI·|λ|`).
    pub force_n: f64,
    /// The blade's tension at the first and the second end, N (positive pulls the holder
    /// in along the blade, negative pushes it out).
    pub tension_n: [f64; 2],
    /// The bending moment at the first and the second end, N·m (positive turns the blade
    /// left, as its curvature).
    pub moment_nm: [f64; 2],
}

impl Loads {
    /// The loads in newtons and newton-metres for a blade of stiffness `s`.
    ///
    /// ```
    /// use elastica::stability::{Loads, Stiffness};
    /// // an arc of radius 0.5 m, in millimetres, EI = 0.4 N·m²: 0.8 N·m at the clamps
    /// let arc = Loads::new([0.0, 0.0], [0.3, -0.3], [1.0 / 500.0; 2]);
    /// let held = arc.held(&Stiffness { ei: 0.4, metres_per_unit: 1e-3 });
    /// assert_eq!(held.force_n, 0.0);
    /// assert!((held.moment_nm[0] - 0.8).abs() < 1e-12);
    /// ```
    pub fn held(&self, s: &Stiffness) -> HolderLoads {
        let per_m2 = 1.0 / (s.metres_per_unit * s.metres_per_unit);
        let per_m = 1.0 / s.metres_per_unit;
        HolderLoads {
            force_n: s.ei * self.force * per_m2,
            tension_n: self.tension.map(|t| s.ei * t * per_m2),
            moment_nm: self.moment.map(|m| s.ei * m * per_m),
        }
    }
}

/// The stability of a held blade and what its holders carry.
#[derive(Clone, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Stability {
    /// Smallest eigenvalue of the second variation over `4π²/L²` (unit-free).
    pub margin: f64,
    /// Stable, marginal or unstable.
    pub class: Class,
    /// Inflections of the whole blade ([`Segment::inflections`]).
    pub inflections: usize,
    /// Total turning of the blade, `θ(L) − θ(0)` (radians).
    pub turning: f64,
    /// End loads per unit `EI`.
    pub loads: Loads,
}

/// Why stability could not be assessed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum StabilityError {
    /// A parameter is not finite or out of range.
    #[error("invalid stability input: {0}")]
    Invalid(String),
    /// The segment's parameters are invalid.
    #[error(transparent)]
    Segment(#[from] EllipticError),
}

/// The multipliers `(λ₁, λ₂)` of a closed-form blade (1/length²): a closed-form elastica
/// satisfies the pendulum equation `θ'' = −sin(θ − φ)/S²` in its own scale `S` and
/// rotation `φ` (`φ + π` traversed backwards); lines and arcs carry no force (`λ = 0`).
///
/// ```
/// use elastica::{ElasticaParams, Family, Segment};
/// use elastica::stability::multipliers;
/// let s = Segment::Elastica(ElasticaParams {
///     family: Family::Inflectional, k: 0.4, s0: 0.2, l: 2.0, scale: 100.0, phi: 0.3,
///     x0: 0.0, y0: 0.0, one_minus_k: None,
/// });
/// let l = multipliers(&s);
/// // |λ| = 1/S², along φ
/// assert!((l[0].hypot(l[1]) - 1e-4).abs() < 1e-18);
/// assert!((l[1].atan2(l[0]) - 0.3).abs() < 1e-12);
/// ```
pub fn multipliers(segment: &Segment) -> [f64; 2] {
    match *segment {
        Segment::Elastica(p) => {
            let dir = if p.l < 0.0 {
                p.phi + std::f64::consts::PI
            } else {
                p.phi
            };
            let m = 1.0 / (p.scale * p.scale);
            [m * dir.cos(), m * dir.sin()]
        }
        Segment::Line { .. } | Segment::Arc { .. } => [0.0, 0.0],
    }
}

/// The margin of a blade of `length` whose tangent angle is `angle(s)` (s ∈ [0, length])
/// under multipliers `load`: the second variation discretised on `cells` and `2·cells`
/// finite-difference cells, Richardson-extrapolated.
///
/// ```
/// use elastica::stability::margin_of;
/// use std::f64::consts::PI;
/// // a straight blade of 2 m compressed by half its buckling load 4π²EI/L²
/// let l = 2.0;
/// let p = 0.5 * 4.0 * PI * PI / (l * l);
/// let m = margin_of(l, |_| 0.0, [p, 0.0], 256)?;
/// assert!((m - 0.5).abs() < 1e-9);
/// # Ok::<(), elastica::stability::StabilityError>(())
/// ```
///
/// # Errors
/// [`StabilityError::Invalid`] for a length that is not positive, fewer than 8 cells or a
/// shape or load that is not finite.
pub fn margin_of(
    length: f64,
    angle: impl Fn(f64) -> f64,
    load: [f64; 2],
    cells: usize,
) -> Result<f64, StabilityError> {
    if !(length > 0.0 && length.is_finite()) {
        return Err(StabilityError::Invalid(format!(
            "the length must be positive, got {length}"
        )));
    }
    if !(8..=1 << 20).contains(&cells) {
        return Err(StabilityError::Invalid(format!(
            "cells must be 8 to 2^20, got {cells}"
        )));
    }
    if !load.iter().all(|v| v.is_finite()) {
        return Err(StabilityError::Invalid("the load is not finite".into()));
    }
    let fine = 2 * cells;
    let theta: Vec<f64> = (0..=fine)
        .map(|j| angle(length * j as f64 / fine as f64))
        .collect();
    if !theta.iter().all(|t| t.is_finite()) {
        return Err(StabilityError::Invalid("the shape is not finite".into()));
    }
    let nu0 = nu_straight(length);
    let coarse: Vec<f64> = theta.iter().step_by(2).copied().collect();
    let a = smallest_fd(length, &coarse, load, nu0)?;
    let b = smallest_fd(length, &theta, load, nu0)?;
    Ok((4.0 * b - a) / 3.0 / nu0)
}

/// `4π²/L²`: the smallest eigenvalue of a straight, unloaded blade's second variation.
pub(crate) fn nu_straight(length: f64) -> f64 {
    let k = 2.0 * std::f64::consts::PI / length;
    k * k
}

/// The smallest eigenvalue of the second variation discretised at the nodes of `theta`
/// (equally spaced from 0 to `length`): the interior nodes' values of ψ, three-point
/// second differences, trapezoid constraints.
fn smallest_fd(
    length: f64,
    theta: &[f64],
    load: [f64; 2],
    nu0: f64,
) -> Result<f64, StabilityError> {
    let n = theta.len() - 1;
    let h = length / n as f64;
    let inner = &theta[1..n];
    let q = |t: f64| load[0] * t.cos() + load[1] * t.sin();
    let diag: Vec<f64> = inner.iter().map(|&t| 2.0 / (h * h) - q(t)).collect();
    let off = vec![-1.0 / (h * h); n - 2];
    let rows = [
        inner.iter().map(|t| t.sin()).collect(),
        inner.iter().map(|t| t.cos()).collect(),
    ];
    Pencil::new(diag, off, rows)
        .smallest(1e-10 * nu0)
        .ok_or_else(|| StabilityError::Invalid("the second variation is not finite".into()))
}

/// The stability of the blade `segment` (the whole held blade, t = 0 and t = 1 its held
/// ends), its inflections, total turning and end loads.
///
/// ```
/// use elastica::stability::{stability, Class, StabilityParams};
/// use elastica::{ElasticaParams, Elliptic, Family, Segment};
/// // an arch: a third of a circle, no force, stable
/// let arc = Segment::Arc { x0: 0.0, y0: 0.0, phi: 1.0, curvature: -0.002, length: 1000.0 };
/// let s = stability(&arc, &StabilityParams::default())?;
/// assert_eq!(s.class, Class::Stable);
/// assert_eq!((s.inflections, s.loads.force), (0, 0.0));
/// assert!((s.loads.moment[0] + 0.002).abs() < 1e-15);
/// // a blade buckled into its first clamped–clamped mode (one period of the pendulum,
/// // k small): it pushes on its holders with the buckling load, 4π²/L² per EI; held by
/// // its ends' positions, the buckled blade is stable (the mode itself is held by the
/// // chord), its two inflections notwithstanding
/// let k = 1e-3;
/// let quarter = Elliptic::from_modulus(k)?.k();
/// let buckled = Segment::Elastica(ElasticaParams {
///     family: Family::Inflectional, k, s0: 0.0, l: 4.0 * quarter, scale: 1000.0 / (4.0 * quarter),
///     phi: 0.0, x0: 0.0, y0: 0.0, one_minus_k: None,
/// });
/// let b = stability(&buckled, &StabilityParams::default())?;
/// let p_cr = 4.0 * std::f64::consts::PI.powi(2) / 1000f64.powi(2);
/// assert!((b.loads.force / p_cr - 1.0).abs() < 1e-5);
/// assert!(b.margin > 1.0);
/// assert!(b.loads.tension[0] < 0.0); // compressed
/// assert_eq!(b.inflections, 2);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// The segment's evaluation errors, or [`StabilityError::Invalid`] for bad parameters.
pub fn stability(segment: &Segment, params: &StabilityParams) -> Result<Stability, StabilityError> {
    // every parameter in the key (a field added to the params fails to compile here)
    let StabilityParams { marginal, cells } = *params;
    let k = (crate::memo::key(segment), marginal.to_bits(), cells);
    ASSESSED.get_or(k, || assess(segment, params))
}

/// How many assessed blades [`stability`] remembers.
const ASSESSED_CAP: usize = 1 << 14;

/// The blades assessed so far ([`crate::memo`]): a blade is assessed for its place, for
/// the refinement's verdict and again when its piece is posed.
static ASSESSED: crate::memo::Memo<(crate::memo::Key, u64, usize), Stability> =
    crate::memo::Memo::new(ASSESSED_CAP);

/// [`stability`], assessed.
fn assess(segment: &Segment, params: &StabilityParams) -> Result<Stability, StabilityError> {
    let length = segment.length();
    if !(params.marginal >= 0.0 && params.marginal.is_finite()) {
        return Err(StabilityError::Invalid(format!(
            "the marginal margin must be ≥ 0, got {}",
            params.marginal
        )));
    }
    let eval = segment.evaluator()?;
    let load = multipliers(segment);
    // at least RESOLUTION cells per radian of bending and per unit of the load's length
    // scale 1/√|λ|, so that tight bends and taut boundary layers are resolved
    let bend = length
        * segment
            .max_abs_curvature()?
            .max(load[0].hypot(load[1]).sqrt());
    let cells = params
        .cells
        .max((RESOLUTION * bend).ceil().min(MAX_CELLS as f64) as usize);
    let margin = margin_of(length, |s| eval.eval(s / length).angle, load, cells)?;
    let (a, b) = (eval.eval(0.0), eval.eval(1.0));
    Ok(Stability {
        margin,
        class: Class::of(margin, params.marginal),
        inflections: segment.inflections()?.len(),
        turning: b.angle - a.angle,
        loads: Loads::new(load, [a.angle, b.angle], [a.curvature, b.curvature]),
    })
}

/// The cross-section of a blade: a thin strip bent about its width (the cutting
/// direction), so `I = width·thickness³/12`. Any consistent units ([`Stiffness::of`]
/// takes lengths in the shapes' unit and the modulus in pascals).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BladeSection {
    /// Thickness (in the cutting plane), length.
    pub thickness: f64,
    /// Width (along the cut), length.
    pub width: f64,
    /// Young's modulus, force per length².
    pub youngs_modulus: f64,
}

impl BladeSection {
    /// `EI = E·w·t³/12` (force × length²).
    ///
    /// ```
    /// use elastica::stability::BladeSection;
    /// // 1 mm × 25 mm spring steel (200 000 N/mm²)
    /// let s = BladeSection { thickness: 1.0, width: 25.0, youngs_modulus: 2.0e5 };
    /// assert!((s.bending_stiffness() - 2.0e5 * 25.0 / 12.0).abs() < 1e-6);
    /// ```
    pub fn bending_stiffness(&self) -> f64 {
        self.youngs_modulus * self.width * self.thickness.powi(3) / 12.0
    }
}
