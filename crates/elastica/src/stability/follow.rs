//! The blade as the robots move it: `n` equal straight segments of directions `θᵢ`
//! between the two held ends (the discrete elastica of "Designing for Robotic Hot-Blade
//! Cutting" §3.2, the end turns over half a segment), its equilibrium found by Newton's
//! method on the KKT system, its stability by the reduced Hessian, and its equilibrium
//! followed by continuation while the ends move.
//!
//! The blade is described in its chord frame: the first end at `(−c/2, 0)`, the second
//! at `(c/2, 0)`, the end tangents at angles `a₀`, `a₁` against the chord
//! ([`HeldEnds`](crate::stability::follow::HeldEnds)). The energy is `½ Σ wᵢ αᵢ²/h` (`αᵢ` the turning angles, `w = 2` for the
//! two half-segment end turns), the constraint `h Σ (cos θᵢ, sin θᵢ) = (c, 0)`, and the
//! multipliers are the papers' `λ` (as [`multipliers`](crate::stability::multipliers)). Every Newton step solves
//! a tridiagonal system bordered by two rows, in O(n) (the module `pencil`); the reduced
//! Hessian's smallest eigenvalue is found by Sturm counts, also in O(n) per count. The
//! margin converges to the closed form's at O(1/n²): the two differ by less than
//! `6(π/n)²(1 + |m| + P)²`, `P = |λ|L²/4π²` the load over the buckling load, away from
//! margin 0 (|m| > 0.05) and from nearly straight waves, where the shape itself converges
//! more slowly (measured in the tests; about 0.03 for a blade pose at [`SEGMENTS`](crate::stability::follow::SEGMENTS)
//! segments).

use super::pencil::{bordered_solve, Pencil};
use super::{nu_straight, StabilityError};

/// Segments of the discrete blade the robot programs are followed with.
pub const SEGMENTS: usize = 128;

/// The held ends in the blade's chord frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HeldEnds {
    /// Distance between the ends.
    pub chord: f64,
    /// Tangent angle of the first and the second end against the chord (radians,
    /// continuous along a move).
    pub angles: [f64; 2],
}

/// A discrete blade at an equilibrium.
#[derive(Clone, Debug, PartialEq)]
pub struct DiscreteBlade {
    /// Length.
    pub length: f64,
    /// Where it is held.
    pub ends: HeldEnds,
    /// Direction of each segment against the chord.
    pub theta: Vec<f64>,
    /// The multipliers `(λ₁, λ₂)` in the chord frame.
    pub load: [f64; 2],
}

/// The energy, gradient and constraints of a discrete blade.
struct Model<'a> {
    h: f64,
    ends: &'a HeldEnds,
}

impl Model<'_> {
    fn weight(&self, i: usize, n: usize) -> f64 {
        if i == 0 || i == n {
            2.0
        } else {
            1.0
        }
    }

    /// Turning angles α₀ … αₙ.
    fn alphas(&self, th: &[f64]) -> Vec<f64> {
        let n = th.len();
        (0..=n)
            .map(|i| match i {
                0 => th[0] - self.ends.angles[0],
                i if i == n => self.ends.angles[1] - th[n - 1],
                i => th[i] - th[i - 1],
            })
            .collect()
    }

    /// The Lagrangian's gradient and the constraint residual.
    fn residual(&self, th: &[f64], load: [f64; 2]) -> (Vec<f64>, [f64; 2]) {
        self.residual_at(th, &Trig::of(th), load)
    }

    /// [`Model::residual`] with the directions' sines and cosines given.
    fn residual_at(&self, th: &[f64], t: &Trig, load: [f64; 2]) -> (Vec<f64>, [f64; 2]) {
        let n = th.len();
        let a = self.alphas(th);
        let h = self.h;
        let g = (0..n)
            .map(|i| {
                (self.weight(i, n) * a[i] - self.weight(i + 1, n) * a[i + 1]) / h
                    + h * (-load[0] * t.sin[i] + load[1] * t.cos[i])
            })
            .collect();
        let cx = h * t.cos.iter().sum::<f64>() - self.ends.chord;
        let cy = h * t.sin.iter().sum::<f64>();
        (g, [cx, cy])
    }

    /// The Lagrangian's tridiagonal Hessian `(diag, off)` and the constraint rows.
    fn hessian(&self, th: &[f64], load: [f64; 2]) -> (Vec<f64>, Vec<f64>, [Vec<f64>; 2]) {
        self.hessian_at(&Trig::of(th), load)
    }

    /// [`Model::hessian`] with the directions' sines and cosines given.
    fn hessian_at(&self, t: &Trig, load: [f64; 2]) -> (Vec<f64>, Vec<f64>, [Vec<f64>; 2]) {
        let n = t.sin.len();
        let h = self.h;
        let diag = (0..n)
            .map(|i| {
                (self.weight(i, n) + self.weight(i + 1, n)) / h
                    - h * (load[0] * t.cos[i] + load[1] * t.sin[i])
            })
            .collect();
        let off = vec![-1.0 / h; n.saturating_sub(1)];
        let rows = [
            t.sin.iter().map(|v| -h * v).collect(),
            t.cos.iter().map(|v| h * v).collect(),
        ];
        (diag, off, rows)
    }
}

/// The sines and cosines of a blade's segment directions, computed once per iterate.
struct Trig {
    sin: Vec<f64>,
    cos: Vec<f64>,
}

impl Trig {
    fn of(th: &[f64]) -> Self {
        let (sin, cos) = th.iter().map(|t| t.sin_cos()).unzip();
        Trig { sin, cos }
    }
}

/// Scaled size of a residual: the gradient times the length, the constraint over it.
fn size(g: &[f64], c: [f64; 2], length: f64) -> f64 {
    let gm = g.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (gm * length).max(c[0].abs().max(c[1].abs()) / length)
}

/// Residual size at which Newton's method stops.
const CONVERGED: f64 = 1e-11;

fn check_ends(length: f64, ends: &HeldEnds) -> Result<(), StabilityError> {
    if !(length > 0.0 && length.is_finite()) {
        return Err(StabilityError::Invalid(format!(
            "the length must be positive, got {length}"
        )));
    }
    if !(ends.chord >= 0.0 && ends.chord < length && ends.angles.iter().all(|a| a.is_finite())) {
        return Err(StabilityError::Invalid(format!(
            "the ends must be finite and less than the blade's length {length} apart, got {}",
            ends.chord
        )));
    }
    Ok(())
}

impl DiscreteBlade {
    /// The equilibrium nearest `guess` (segment directions) for a blade of `length` held
    /// at `ends`, by Newton's method on the KKT system from `guess` and the multipliers
    /// `load` (`None`: those that fit `guess` best).
    ///
    /// ```
    /// use elastica::stability::follow::{DiscreteBlade, HeldEnds};
    /// // a blade of 1000 held 990 apart, its ends turned up and down by 0.15 rad: an arch
    /// let ends = HeldEnds { chord: 990.0, angles: [0.15, -0.15] };
    /// let guess: Vec<f64> = (0..64).map(|i| 0.15 - 0.3 * (i as f64 + 0.5) / 64.0).collect();
    /// let b = DiscreteBlade::settle(1000.0, ends, &guess, None)?;
    /// assert!(b.margin()? > 0.9);
    /// // its last point on the second end
    /// let end = b.points()[64];
    /// assert!((end[0] - 495.0).abs() < 1e-8 && end[1].abs() < 1e-8);
    /// # Ok::<(), elastica::stability::StabilityError>(())
    /// ```
    ///
    /// # Errors
    /// [`StabilityError::Invalid`] for bad input or when Newton's method does not
    /// converge.
    pub fn settle(
        length: f64,
        ends: HeldEnds,
        guess: &[f64],
        load: Option<[f64; 2]>,
    ) -> Result<DiscreteBlade, StabilityError> {
        check_ends(length, &ends)?;
        let n = guess.len();
        if n < 4 || !guess.iter().all(|t| t.is_finite()) {
            return Err(StabilityError::Invalid(format!(
                "the guess needs ≥ 4 finite segment directions, got {n}"
            )));
        }
        let model = Model {
            h: length / n as f64,
            ends: &ends,
        };
        let load = load.unwrap_or_else(|| fitted_load(&model, guess));
        let (theta, load) = newton(&model, guess.to_vec(), load, length, (40, 20))
            .ok_or_else(|| StabilityError::Invalid("no equilibrium near the guess".into()))?;
        Ok(DiscreteBlade {
            length,
            ends,
            theta,
            load,
        })
    }

    /// The blade held at `ends` whose shape is nearest the tangent angle `angle(u)` (u ∈
    /// [0, 1] along the blade, against the chord), on `segments` segments.
    ///
    /// # Errors
    /// As [`DiscreteBlade::settle`].
    pub fn settle_like(
        length: f64,
        ends: HeldEnds,
        angle: impl Fn(f64) -> f64,
        segments: usize,
        load: Option<[f64; 2]>,
    ) -> Result<DiscreteBlade, StabilityError> {
        let guess: Vec<f64> = (0..segments)
            .map(|i| angle((i as f64 + 0.5) / segments as f64))
            .collect();
        Self::settle(length, ends, &guess, load)
    }

    /// The points of the blade, first end to second, in the chord frame.
    pub fn points(&self) -> Vec<[f64; 2]> {
        let h = self.length / self.theta.len() as f64;
        let mut p = [-0.5 * self.ends.chord, 0.0];
        let mut out = Vec::with_capacity(self.theta.len() + 1);
        out.push(p);
        for t in &self.theta {
            p = [p[0] + h * t.cos(), p[1] + h * t.sin()];
            out.push(p);
        }
        out
    }

    /// The largest distance between the two blades' points at equal arc length (both of
    /// as many segments; `f64::INFINITY` otherwise).
    pub fn distance(&self, other: &DiscreteBlade) -> f64 {
        if self.theta.len() != other.theta.len() {
            return f64::INFINITY;
        }
        self.points()
            .iter()
            .zip(other.points())
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max)
    }

    /// The reduced Hessian of the Lagrangian (mass `h` per segment).
    fn pencil(&self) -> Pencil {
        let model = Model {
            h: self.length / self.theta.len() as f64,
            ends: &self.ends,
        };
        let (diag, off, rows) = model.hessian(&self.theta, self.load);
        let h = model.h;
        Pencil::new(
            diag.iter().map(|d| d / h).collect(),
            off.iter().map(|o| o / h).collect(),
            rows,
        )
    }

    /// The margin of the discrete equilibrium: the reduced Hessian's smallest eigenvalue
    /// over `4π²/L²` (as [`super::margin_of`], to O(1/n²)).
    ///
    /// # Errors
    /// [`StabilityError::Invalid`] when the Hessian is not finite.
    pub fn margin(&self) -> Result<f64, StabilityError> {
        let nu0 = nu_straight(self.length);
        self.pencil()
            .smallest(1e-9 * nu0)
            .map(|v| v / nu0)
            .ok_or_else(|| StabilityError::Invalid("the Hessian is not finite".into()))
    }

    /// Whether the reduced Hessian is positive definite (one Sturm count).
    pub fn is_stable(&self) -> bool {
        self.pencil().count_below(0.0) == 0
    }
}

/// The multipliers that best balance the shape `th`: the gradient's least-squares fit.
fn fitted_load(model: &Model<'_>, th: &[f64]) -> [f64; 2] {
    let (g0, _) = model.residual(th, [0.0, 0.0]);
    let h = model.h;
    // g0 + λ₁ a + λ₂ b = 0 with a = −h sin θ, b = h cos θ
    let (mut aa, mut ab, mut bb, mut ag, mut bg) = (0.0, 0.0, 0.0, 0.0, 0.0);
    for (t, g) in th.iter().zip(&g0) {
        let (a, b) = (-h * t.sin(), h * t.cos());
        aa += a * a;
        ab += a * b;
        bb += b * b;
        ag += a * g;
        bg += b * g;
    }
    let det = aa * bb - ab * ab;
    if !(det.abs() > 1e-300) {
        return [0.0, 0.0];
    }
    [(-ag * bb + bg * ab) / det, (-bg * aa + ag * ab) / det]
}

/// Newton's method on the KKT system with step halving on the residual, at most
/// `halvings` times per iteration; `None` when it does not converge in `iterations`.
fn newton(
    model: &Model<'_>,
    mut th: Vec<f64>,
    mut load: [f64; 2],
    length: f64,
    (iterations, halvings): (usize, usize),
) -> Option<(Vec<f64>, [f64; 2])> {
    let mut trig = Trig::of(&th);
    let (mut g, mut c) = model.residual_at(&th, &trig, load);
    let mut r = size(&g, c, length);
    for _ in 0..iterations {
        if r < CONVERGED {
            return Some((th, load));
        }
        let (diag, off, rows) = model.hessian_at(&trig, load);
        let f: Vec<f64> = g.iter().map(|v| -v).collect();
        let (dx, dy) = bordered_solve(&diag, &off, [&rows[0], &rows[1]], &f, [-c[0], -c[1]])?;
        let mut step = 1.0;
        let mut improved = false;
        for _ in 0..halvings {
            let t: Vec<f64> = th.iter().zip(&dx).map(|(a, d)| a + step * d).collect();
            let l = [load[0] + step * dy[0], load[1] + step * dy[1]];
            let tt = Trig::of(&t);
            let (gt, ct) = model.residual_at(&t, &tt, l);
            let rt = size(&gt, ct, length);
            if rt.is_finite() && rt < (1.0 - 1e-4 * step) * r {
                (th, load, g, c, r, trig) = (t, l, gt, ct, rt, tt);
                improved = true;
                break;
            }
            step *= 0.5;
        }
        if !improved {
            break;
        }
    }
    (r < CONVERGED).then_some((th, load))
}

/// How [`follow`] steps.
#[derive(Clone, Debug, PartialEq)]
pub struct FollowParams {
    /// Largest change of a segment's direction in one step (radians): a larger change
    /// would risk jumping to another equilibrium unseen.
    pub max_turn: f64,
    /// Smallest step, as a fraction of the move: a blade that cannot be followed by a
    /// step this small has no equilibrium nearby (it snaps).
    pub min_step: f64,
    /// Whether to measure the margin at every step (else stability is only checked, by
    /// one Sturm count, and every margin recorded is 1 while stable).
    pub margins: bool,
}

impl Default for FollowParams {
    fn default() -> Self {
        FollowParams {
            max_turn: 0.05,
            min_step: 1e-5,
            margins: true,
        }
    }
}

/// The largest change of a segment's direction between two blades.
fn max_turn_between(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

/// The share of [`FollowParams::max_turn`] a step of [`follow`] aims to turn.
const TURN_AIM: f64 = 0.8;

/// How a followed equilibrium was lost.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Snap {
    /// The equilibrium lost its stability (a fold or a bifurcation: the margin reached
    /// 0) at this fraction of the move: the blade jumps to another shape.
    Fold {
        /// Fraction of the move.
        at: f64,
        /// The last margin seen before it.
        margin: f64,
    },
    /// No equilibrium could be followed past this fraction of the move (the blade
    /// stretched taut, or jumped): the blade leaves the shape.
    Lost {
        /// Fraction of the move.
        at: f64,
        /// The last margin seen before it.
        margin: f64,
    },
}

/// The equilibrium followed along a move.
#[derive(Clone, Debug, PartialEq)]
pub struct Followed {
    /// The last equilibrium reached (at the move's end unless it snapped).
    pub blade: DiscreteBlade,
    /// The margin at the move's start and at its end (where it got there): `(fraction of
    /// the move, margin)`. Between them stability is checked at every step.
    pub margins: Vec<(f64, f64)>,
    /// How it snapped, if it did.
    pub snap: Option<Snap>,
}

impl Followed {
    /// The smaller margin of the move's start and end.
    pub fn min_margin(&self) -> f64 {
        self.margins
            .iter()
            .map(|m| m.1)
            .fold(f64::INFINITY, f64::min)
    }
}

/// Follows the equilibrium `start` while the ends move along `path` (w ∈ [0, 1] ↦ held
/// ends; `path(0)` is `start`'s): natural-parameter continuation with a secant
/// predictor, Newton's method as corrector, steps halved where the corrector fails or a
/// segment would turn more than [`FollowParams::max_turn`], doubled after a success. A
/// step that lands on an unstable equilibrium, or steps that cannot be made smaller than
/// [`FollowParams::min_step`], end the move with a [`Snap`].
///
/// ```
/// use elastica::stability::follow::{follow, DiscreteBlade, FollowParams, HeldEnds};
/// // an arch whose ends turn further while the ends close in: it follows smoothly
/// let at = |w: f64| HeldEnds { chord: 990.0 - 40.0 * w, angles: [0.15 + 0.2 * w, -0.15 - 0.2 * w] };
/// let start = DiscreteBlade::settle_like(1000.0, at(0.0), |u| 0.15 - 0.3 * u, 64, None)?;
/// let f = follow(&start, &at, &FollowParams::default());
/// assert!(f.snap.is_none());
/// assert_eq!(f.blade.ends, at(1.0));
/// assert!(f.min_margin() > 0.5);
/// # Ok::<(), elastica::stability::StabilityError>(())
/// ```
pub fn follow(
    start: &DiscreteBlade,
    path: &dyn Fn(f64) -> HeldEnds,
    params: &FollowParams,
) -> Followed {
    let length = start.length;
    let n = start.theta.len();
    let h = length / n as f64;
    // the margin where it is reported (the move's start and end, with `margins`, and
    // where it snaps); elsewhere stability is checked by one Sturm count
    let margin = |b: &DiscreteBlade| {
        if params.margins {
            b.margin().unwrap_or(f64::NAN)
        } else if b.is_stable() {
            1.0
        } else {
            -1.0
        }
    };
    let first = margin(start);
    let mut out = Followed {
        blade: start.clone(),
        margins: vec![(0.0, first)],
        snap: None,
    };
    if !(first >= 0.0) {
        out.snap = Some(Snap::Fold {
            at: 0.0,
            margin: first,
        });
        return out;
    }
    let min_step = params.min_step.clamp(1e-12, 1.0);
    let (mut w, mut dw) = (0.0f64, 1.0f64);
    let mut last = first;
    // the previous accepted state and its step, for the secant predictor
    let mut previous: Option<(Vec<f64>, [f64; 2], f64)> = None;
    // every attempt shortens the step by at least TURN_AIM or advances by it, and an
    // advance at most doubles it: bounded by the steps of min_step
    let attempts = (8.0 / min_step).min(8.0e6) as usize + 64;
    for _ in 0..attempts {
        if w >= 1.0 {
            break;
        }
        let to = (w + dw).min(1.0);
        let ends = path(to);
        let reach = (to - w) / dw.max(f64::MIN_POSITIVE);
        let ok = check_ends(length, &ends).is_ok();
        let cur = &out.blade;
        let (guess, load_guess) = match &previous {
            Some((th, l, step)) if *step > 0.0 => {
                let f = (to - w) / step;
                (
                    cur.theta
                        .iter()
                        .zip(th)
                        .map(|(a, b)| a + f * (a - b))
                        .collect::<Vec<f64>>(),
                    [
                        cur.load[0] + f * (cur.load[0] - l[0]),
                        cur.load[1] + f * (cur.load[1] - l[1]),
                    ],
                )
            }
            _ => (cur.theta.clone(), cur.load),
        };
        // a secant predictor turning a segment further than a step may: a shorter step,
        // to about 0.8 of that (the predictor's turn scales with the step)
        let predicted = max_turn_between(&guess, &cur.theta);
        if predicted > params.max_turn && dw > min_step {
            dw = (dw * TURN_AIM * params.max_turn / predicted).max(min_step);
            continue;
        }
        let model = Model { h, ends: &ends };
        let solved = if ok {
            // from the predictor, a step of the path converges at once or is too long:
            // Newton's steps damped below 1/32 mean a shorter step of the path
            newton(&model, guess, load_guess, length, (12, 6))
        } else {
            None
        };
        // the step taken, or why not: `Err(Some(turn))` converged but turned too far
        let accepted = match solved {
            Some((theta, load)) => {
                let turn = max_turn_between(&theta, &cur.theta);
                if turn <= params.max_turn {
                    Ok((
                        DiscreteBlade {
                            length,
                            ends,
                            theta,
                            load,
                        },
                        turn,
                    ))
                } else {
                    Err(Some(turn))
                }
            }
            None => Err(None),
        };
        match accepted {
            Ok((b, turn)) => {
                if !b.is_stable() {
                    // stability lost between w and to: a fold or a bifurcation, unless a
                    // smaller step finds the stable side still reaching on
                    if dw > min_step {
                        dw *= 0.5;
                        continue;
                    }
                    out.snap = Some(Snap::Fold {
                        at: w,
                        margin: margin(&out.blade),
                    });
                    return out;
                }
                previous = Some((out.blade.theta.clone(), out.blade.load, to - w));
                if to >= 1.0 {
                    let m = margin(&b);
                    out.margins.push((to, m));
                    last = m;
                }
                out.blade = b;
                w = to;
                // the next step aimed at turning about 0.8 of the most, at most doubled
                let grow = if turn > 0.0 {
                    (TURN_AIM * params.max_turn / turn).min(2.0)
                } else {
                    2.0
                };
                dw = (grow * dw * reach.min(1.0)).clamp(min_step, 1.0);
            }
            Err(turned) => {
                if dw <= min_step {
                    let last = margin(&out.blade);
                    out.snap = Some(if last < 2.0 * super::MARGINAL {
                        Snap::Fold {
                            at: w,
                            margin: last,
                        }
                    } else {
                        Snap::Lost {
                            at: w,
                            margin: last,
                        }
                    });
                    return out;
                }
                // turned too far: the step that would have turned about 0.8 of the
                // most; else (no equilibrium found) half the step
                dw *= turned.map_or(0.5, |t| (TURN_AIM * params.max_turn / t).min(0.5));
                dw = dw.max(min_step);
            }
        }
    }
    if w < 1.0 {
        out.snap = Some(Snap::Lost {
            at: w,
            margin: last,
        });
    }
    out
}

/// How a move lost the planned shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize, schemars::JsonSchema)
)]
pub enum SnapKind {
    /// The equilibrium lost its stability on the way (a fold or a bifurcation).
    Fold,
    /// No equilibrium could be followed on the way.
    Lost,
    /// The move arrived on another equilibrium than the planned shape.
    OtherShape,
}

impl From<Snap> for SnapKind {
    fn from(s: Snap) -> Self {
        match s {
            Snap::Fold { .. } => SnapKind::Fold,
            Snap::Lost { .. } => SnapKind::Lost,
        }
    }
}

/// A blade of the same length carried from one shape to another.
#[derive(Clone, Debug, PartialEq)]
pub struct Transition {
    /// How it snapped, if it did.
    pub snap: Option<SnapKind>,
}

/// The blade held as `a` (a whole blade, both ends held) carried to `b` (the same
/// length) while its ends move as robots move them between two poses on parallel planes:
/// both end points linearly, both end tangents turning at a constant rate. Whether it
/// arrives on `b` without snapping ([`follow`] on [`SEGMENTS`] segments; `b` is reached
/// when the discrete blade settled from it is the one followed). A move into or out of a
/// taut, straight blade passes through straight, where the blade may go either way: it
/// counts as a snap ([`SnapKind::Lost`]); from straight to straight it does not.
///
/// ```
/// use elastica::stability::follow::transition;
/// use elastica::Segment;
/// // an arch flattening a little: it follows; turned over at once: it snaps
/// let arc = |c: f64| Segment::Arc { x0: 0.0, y0: 0.0, phi: 0.5 * c * 1000.0, curvature: -c, length: 1000.0 };
/// let t = transition(&arc(4e-4), &arc(3e-4))?;
/// assert!(t.snap.is_none());
/// let flip = transition(&arc(4e-4), &arc(-4e-4))?;
/// assert!(flip.snap.is_some());
/// # Ok::<(), elastica::stability::StabilityError>(())
/// ```
///
/// # Errors
/// [`StabilityError`] when the blades differ in length, cannot be evaluated or `a` is not
/// an equilibrium the discrete blade finds.
pub fn transition(a: &crate::Segment, b: &crate::Segment) -> Result<Transition, StabilityError> {
    let length = a.length();
    if !((b.length() - length).abs() <= 1e-9 * length) {
        return Err(StabilityError::Invalid(format!(
            "the blades differ in length: {length} and {}",
            b.length()
        )));
    }
    let (ea, eb) = (a.evaluator()?, b.evaluator()?);
    let (a0, a1, b0, b1) = (ea.eval(0.0), ea.eval(1.0), eb.eval(0.0), eb.eval(1.0));
    // a blade held taut and straight: its tension undetermined, it goes either way from
    // there; into or out of such a pose the blade passes through straight (flagged), two
    // straight poses in a row keep it straight
    let taut = |p: [f64; 2], q: [f64; 2]| (q[0] - p[0]).hypot(q[1] - p[1]) >= length * (1.0 - 1e-9);
    match (taut(a0.p, a1.p), taut(b0.p, b1.p)) {
        (true, true) => return Ok(Transition { snap: None }),
        (true, false) | (false, true) => {
            return Ok(Transition {
                snap: Some(SnapKind::Lost),
            })
        }
        (false, false) => {}
    }
    let chord_of = |p: [f64; 2], q: [f64; 2]| (q[1] - p[1]).atan2(q[0] - p[0]);
    let start_chord = chord_of(a0.p, a1.p);
    let turn = |x: f64, y: f64| {
        let pi = std::f64::consts::PI;
        pi - (pi - (y - x)).rem_euclid(2.0 * pi)
    };
    let (d0, d1) = (turn(a0.angle, b0.angle), turn(a1.angle, b1.angle));
    let path = |w: f64| {
        let lerp = |p: [f64; 2], q: [f64; 2]| [p[0] + w * (q[0] - p[0]), p[1] + w * (q[1] - p[1])];
        let (p, q) = (lerp(a0.p, b0.p), lerp(a1.p, b1.p));
        let c = start_chord + turn(start_chord, chord_of(p, q));
        HeldEnds {
            chord: (q[0] - p[0]).hypot(q[1] - p[1]),
            angles: [a0.angle + w * d0 - c, a1.angle + w * d1 - c],
        }
    };
    let start = DiscreteBlade::settle_like(
        length,
        path(0.0),
        |u| ea.eval(u).angle - start_chord,
        SEGMENTS,
        None,
    )?;
    // whether it snaps, not where: the fold located to a thousandth of the move (steps
    // turning a segment twice the default 0.05 rad step over folds: one of seg-wavy-45-
    // inflection's pieces then passes, which fails at 0.05 and at 0.025)
    let quick = FollowParams {
        margins: false,
        min_step: 1e-3,
        ..FollowParams::default()
    };
    let f = follow(&start, &path, &quick);
    let mut snap = f.snap.map(SnapKind::from);
    if snap.is_none() {
        let end = path(1.0);
        let c = start_chord + turn(start_chord, chord_of(b0.p, b1.p));
        // b's own angles moved by the whole turns the path took
        let shift = end.angles[0] - (b0.angle - c);
        let planned = DiscreteBlade::settle_like(
            length,
            end,
            |u| eb.eval(u).angle - c + shift,
            SEGMENTS,
            None,
        );
        let same = planned.is_ok_and(|p| p.distance(&f.blade) <= 1e-6 * length);
        if !same {
            snap = Some(SnapKind::OtherShape);
        }
    }
    Ok(Transition { snap })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The Hessian and the constraint rows are the derivatives of the residual (central
    /// differences, step 1e-6: agreement to ~1e-8).
    #[test]
    fn derivatives_match_finite_differences() {
        let ends = HeldEnds {
            chord: 11.0,
            angles: [1.2, -1.1],
        };
        let n = 16;
        let model = Model {
            h: 16.8 / n as f64,
            ends: &ends,
        };
        let th: Vec<f64> = (0..n).map(|i| 1.2 * ((i as f64) * 0.7).cos()).collect();
        let load = [0.9, 0.3];
        let (diag, off, rows) = model.hessian(&th, load);
        let e = 1e-6;
        for j in 0..n {
            let mut p = th.clone();
            let mut m = th.clone();
            p[j] += e;
            m[j] -= e;
            let (gp, cp) = model.residual(&p, load);
            let (gm, cm) = model.residual(&m, load);
            for i in 0..n {
                let fd = (gp[i] - gm[i]) / (2.0 * e);
                let want = if i == j {
                    diag[i]
                } else if i + 1 == j {
                    off[i]
                } else if j + 1 == i {
                    off[j]
                } else {
                    0.0
                };
                assert!((fd - want).abs() < 1e-6, "H[{i},{j}] {fd} vs {want}");
            }
            for k in 0..2 {
                let fd = (cp[k] - cm[k]) / (2.0 * e);
                assert!(
                    (fd - rows[k][j]).abs() < 1e-6,
                    "J[{k},{j}] {fd} vs {}",
                    rows[k][j]
                );
            }
        }
        // and ∂g/∂λ are the rows
        for k in 0..2 {
            let mut lp = load;
            lp[k] += e;
            let mut lm = load;
            lm[k] -= e;
            let (gp, _) = model.residual(&th, lp);
            let (gm, _) = model.residual(&th, lm);
            for i in 0..n {
                let fd = (gp[i] - gm[i]) / (2.0 * e);
                assert!((fd - rows[k][i]).abs() < 1e-6, "dg/dλ{k}");
            }
        }
    }
}
