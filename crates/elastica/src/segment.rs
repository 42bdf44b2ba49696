//! Elastica segments in the plane: the closed-form families in the papers' standard
//! parameters `(k, s₀, ℓ, S, φ, x₀, y₀)`,
//! `p(t) = S·R(φ)·f(s₀ + ℓt) + (x₀, y₀)`, t ∈ [0, 1], f = ζ or γ ([`crate::unit`]),
//! plus explicit straight lines and circular arcs (the λ = 0 elastica, common in facades and
//! badly conditioned as limits k → 0, S → ∞). Arc length is `S·|ℓ|·t`; ℓ < 0 traverses f
//! backwards, which mirrors the turning direction.

use crate::elliptic::EllipticError;
use crate::unit::{Family, UnitElastica};
use geom::significance::{drop_noise_lobes, rounding_floor, Floor, LobeCurve};
use nalgebra::Vector2;

/// The standard parameters of a closed-form elastica segment.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct ElasticaParams {
    /// Inflectional or non-inflectional.
    pub family: Family,
    /// Modulus k (m = k²).
    pub k: f64,
    /// Start on the normalized curve.
    pub s0: f64,
    /// Length on the normalized curve, signed (ℓ < 0 runs backwards).
    pub l: f64,
    /// Scale S > 0.
    #[cfg_attr(feature = "serde", serde(rename = "S"))]
    pub scale: f64,
    /// Rotation φ (radians).
    pub phi: f64,
    /// Translation x₀.
    pub x0: f64,
    /// Translation y₀.
    pub y0: f64,
    /// `1 − k` to full precision, for shapes whose modulus is too close to 1 for `k` in
    /// `f64` (under strong tension 1 − k falls to 10⁻²⁰ and below); when given, it defines
    /// the modulus and `k` is its rounded value.
    #[cfg_attr(
        feature = "serde",
        serde(default, skip_serializing_if = "Option::is_none")
    )]
    pub one_minus_k: Option<f64>,
}

impl ElasticaParams {
    /// The normalized curve of these parameters (its modulus from
    /// [`ElasticaParams::one_minus_k`] when given, else from `k`).
    pub fn unit(&self) -> Result<UnitElastica, EllipticError> {
        match self.one_minus_k {
            Some(c) => UnitElastica::with_complement(self.family, c),
            None => UnitElastica::new(self.family, self.k),
        }
    }
}

/// Names of the seven parameters in the order of [`ElasticaSegment::point_gradient`].
pub const PARAM_NAMES: [&str; 7] = ["k", "s0", "l", "S", "phi", "x0", "y0"];

/// A planar segment a hot blade can take: a closed-form elastica, a line or a circular arc.
/// All are parameterized by t ∈ [0, 1] at constant speed (t outside [0, 1] extends the same
/// curve).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(tag = "type", rename_all = "lowercase"))]
pub enum Segment {
    /// A closed-form elastica segment.
    Elastica(ElasticaParams),
    /// A straight segment from (x₀, y₀) in direction φ.
    Line {
        /// Start x.
        x0: f64,
        /// Start y.
        y0: f64,
        /// Direction angle (radians).
        phi: f64,
        /// Length ≥ 0.
        length: f64,
    },
    /// A circular arc from (x₀, y₀) with start tangent angle φ and signed curvature
    /// (positive turns left).
    Arc {
        /// Start x.
        x0: f64,
        /// Start y.
        y0: f64,
        /// Start tangent angle (radians).
        phi: f64,
        /// Signed curvature (1/length).
        curvature: f64,
        /// Length ≥ 0.
        length: f64,
    },
}

impl Segment {
    /// The segment under the similarity `p ↦ factor·p + offset` (`factor > 0`): lengths
    /// scale by `factor`, curvatures by `1/factor`, angles and shape are kept.
    pub fn similar(&self, factor: f64, offset: [f64; 2]) -> Segment {
        self.mapped([factor, 0.0], offset)
    }

    /// The segment under the similarity `p ↦ a·p + b` of the complex plane (`a`, `b` as
    /// `[re, im]`, `a ≠ 0`): turned by arg a, lengths scaled by |a|, curvatures by 1/|a|,
    /// then moved by `b`; the shape is kept.
    pub fn mapped(&self, a: [f64; 2], b: [f64; 2]) -> Segment {
        let (k, turn) = (a[0].hypot(a[1]), a[1].atan2(a[0]));
        let map = |x: f64, y: f64| (a[0] * x - a[1] * y + b[0], a[1] * x + a[0] * y + b[1]);
        match *self {
            Segment::Elastica(p) => {
                let (x0, y0) = map(p.x0, p.y0);
                Segment::Elastica(ElasticaParams {
                    scale: p.scale * k,
                    phi: p.phi + turn,
                    x0,
                    y0,
                    ..p
                })
            }
            Segment::Line {
                x0,
                y0,
                phi,
                length,
            } => {
                let (x0, y0) = map(x0, y0);
                Segment::Line {
                    x0,
                    y0,
                    phi: phi + turn,
                    length: length * k,
                }
            }
            Segment::Arc {
                x0,
                y0,
                phi,
                curvature,
                length,
            } => {
                let (x0, y0) = map(x0, y0);
                Segment::Arc {
                    x0,
                    y0,
                    phi: phi + turn,
                    curvature: curvature / k,
                    length: length * k,
                }
            }
        }
    }
}

/// Point, unit tangent, tangent angle and signed curvature of a segment at one parameter.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct SegmentPoint {
    /// Position.
    pub p: [f64; 2],
    /// Unit tangent in the direction of increasing t.
    pub tangent: [f64; 2],
    /// Tangent angle (radians), continuous in t.
    pub angle: f64,
    /// Signed curvature with respect to arc length (left turn positive).
    pub curvature: f64,
}

/// sin(x)/x without the 0/0.
pub(crate) fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-4 {
        1.0 - x * x / 6.0
    } else {
        x.sin() / x
    }
}

/// (1 − cos x)/x without cancellation.
pub(crate) fn cosc(x: f64) -> f64 {
    let h = 0.5 * x;
    h.sin() * sinc(h)
}

fn rot(phi: f64, v: [f64; 2]) -> [f64; 2] {
    let (s, c) = phi.sin_cos();
    [c * v[0] - s * v[1], s * v[0] + c * v[1]]
}

/// An elastica segment with its normalized curve prepared for repeated evaluation.
#[derive(Clone, Debug)]
pub struct ElasticaSegment {
    /// The parameters.
    pub params: ElasticaParams,
    unit: UnitElastica,
}

impl ElasticaSegment {
    /// Prepare `params` (checks k's range and S > 0).
    pub fn new(params: ElasticaParams) -> Result<Self, EllipticError> {
        if !(params.scale > 0.0) || !params.scale.is_finite() {
            return Err(EllipticError::Parameter(f64::NAN));
        }
        Ok(ElasticaSegment {
            unit: params.unit()?,
            params,
        })
    }

    /// The normalized curve.
    pub fn unit(&self) -> &UnitElastica {
        &self.unit
    }

    /// Point, tangent, angle and curvature at t.
    pub fn eval(&self, t: f64) -> SegmentPoint {
        let p = &self.params;
        let u = self.unit.eval(p.s0 + p.l * t);
        let f = rot(p.phi, u.p);
        let dir = if p.l < 0.0 { -1.0 } else { 1.0 };
        let tan = rot(p.phi, u.t);
        SegmentPoint {
            p: [p.scale * f[0] + p.x0, p.scale * f[1] + p.y0],
            tangent: [dir * tan[0], dir * tan[1]],
            angle: p.phi + u.theta + if p.l < 0.0 { std::f64::consts::PI } else { 0.0 },
            curvature: dir * u.kappa / p.scale,
        }
    }

    /// The point at t and its derivatives with respect to `(k, s₀, ℓ, S, φ, x₀, y₀)`.
    pub fn point_gradient(&self, t: f64) -> ([f64; 2], [[f64; 2]; 7]) {
        let p = &self.params;
        let (u, dk) = self.unit.eval_dk(p.s0 + p.l * t);
        let f = rot(p.phi, u.p);
        let tan = rot(p.phi, u.t);
        let s = p.scale;
        let point = [s * f[0] + p.x0, s * f[1] + p.y0];
        let dk = rot(p.phi, dk);
        let grad = [
            [s * dk[0], s * dk[1]],
            [s * tan[0], s * tan[1]],
            [t * s * tan[0], t * s * tan[1]],
            f,
            [-s * f[1], s * f[0]],
            [1.0, 0.0],
            [0.0, 1.0],
        ];
        (point, grad)
    }
}

impl Segment {
    /// Arc length of the segment (t from 0 to 1).
    pub fn length(&self) -> f64 {
        match *self {
            Segment::Elastica(p) => p.scale * p.l.abs(),
            Segment::Line { length, .. } | Segment::Arc { length, .. } => length,
        }
    }

    /// A short name of the kind: `inflectional`, `noninflectional`, `line` or `arc`.
    pub fn kind(&self) -> &'static str {
        match self {
            Segment::Elastica(p) => match p.family {
                Family::Inflectional => "inflectional",
                Family::NonInflectional => "noninflectional",
            },
            Segment::Line { .. } => "line",
            Segment::Arc { .. } => "arc",
        }
    }

    /// Prepare for evaluation (validates the parameters).
    pub fn evaluator(&self) -> Result<SegmentEval, EllipticError> {
        Ok(match *self {
            Segment::Elastica(p) => SegmentEval::Elastica(Box::new(ElasticaSegment::new(p)?)),
            other => SegmentEval::Simple(other),
        })
    }

    /// Evaluate at one t (convenience; prefer [`Segment::evaluator`] in loops).
    pub fn eval(&self, t: f64) -> Result<SegmentPoint, EllipticError> {
        Ok(self.evaluator()?.eval(t))
    }

    /// `n ≥ 2` points at equal arc-length spacing from t = 0 to t = 1.
    ///
    /// ```
    /// use elastica::Segment;
    /// // half a circle of radius 2 about (0, 2), from the origin turning left
    /// let arc = Segment::Arc { x0: 0.0, y0: 0.0, phi: 0.0, curvature: 0.5, length: 2.0 * std::f64::consts::PI };
    /// let pts = arc.sample(9)?;
    /// assert_eq!(pts.len(), 9);
    /// assert!(pts.iter().all(|p| (p[0].hypot(p[1] - 2.0) - 2.0).abs() < 1e-12));
    /// // the far end, heading back (−x) with curvature 1/2
    /// let end = arc.eval(1.0)?;
    /// assert!(end.p[0].abs() < 1e-12 && (end.p[1] - 4.0).abs() < 1e-12);
    /// assert!((end.tangent[0] + 1.0).abs() < 1e-12 && end.curvature == 0.5);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn sample(&self, n: usize) -> Result<Vec<[f64; 2]>, EllipticError> {
        let e = self.evaluator()?;
        let n = n.max(2);
        Ok((0..n)
            .map(|i| e.eval(i as f64 / (n - 1) as f64).p)
            .collect())
    }

    /// Parameters t ∈ (0, 1) of the inflection points (none for lines, arcs and
    /// non-inflectional elastica): the zeros of the closed form's curvature whose lobes
    /// depart from their chords by more than f64 rounding at the segment's scale — the
    /// noise-floor rule every inflection count of hotcut follows
    /// ([`geom::significance`]; an exact curve's floor is rounding). A zero a hair from
    /// an end, or a lobe of a nearly straight segment that no evaluation can tell from
    /// its chord, is not an inflection.
    ///
    /// ```
    /// use elastica::{ElasticaParams, Elliptic, Family, Segment};
    /// // the inflectional elastica over one full period 4K: κ = 2k·cn vanishes at K and 3K
    /// let k = 0.5;
    /// let quarter = Elliptic::from_modulus(k)?.k();
    /// let s = Segment::Elastica(ElasticaParams {
    ///     family: Family::Inflectional, k, s0: 0.0, l: 4.0 * quarter,
    ///     scale: 1.0, phi: 0.0, x0: 0.0, y0: 0.0, one_minus_k: None,
    /// });
    /// let t = s.inflections()?;
    /// assert_eq!(t.len(), 2);
    /// assert!((t[0] - 0.25).abs() < 1e-12 && (t[1] - 0.75).abs() < 1e-12);
    /// assert!(s.eval(t[0])?.curvature.abs() < 1e-12);
    /// // |κ| peaks at σ = 0 with 2k
    /// assert!((s.max_abs_curvature()? - 2.0 * k).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn inflections(&self) -> Result<Vec<f64>, EllipticError> {
        let mut ts = self.curvature_zeros()?;
        if ts.is_empty() {
            return Ok(ts);
        }
        let eval = self.evaluator()?;
        let reach = (0..=16)
            .map(|i| {
                let p = eval.eval(i as f64 / 16.0).p;
                p[0].abs().max(p[1].abs())
            })
            .fold(0.0, f64::max);
        let length = self.length();
        let floor = Floor::of(rounding_floor(reach, length), length);
        let mut bounds: Vec<f64> = std::iter::once(0.0)
            .chain(ts.iter().copied())
            .chain(std::iter::once(1.0))
            .collect();
        drop_noise_lobes(&eval, &mut bounds, &|_, _| floor, &[]);
        ts = bounds[1..bounds.len() - 1].to_vec();
        Ok(ts)
    }

    /// Every zero of the closed form's curvature in t ∈ (0, 1), increasing (before the
    /// noise floor of [`Segment::inflections`]).
    pub fn curvature_zeros(&self) -> Result<Vec<f64>, EllipticError> {
        match *self {
            Segment::Elastica(p) => {
                let u = p.unit()?;
                let mut ts: Vec<f64> = u
                    .inflections_between(p.s0, p.s0 + p.l)
                    .into_iter()
                    .map(|s| (s - p.s0) / p.l)
                    .filter(|t| *t > 0.0 && *t < 1.0)
                    .collect();
                ts.sort_by(f64::total_cmp);
                Ok(ts)
            }
            _ => Ok(Vec::new()),
        }
    }

    /// The largest |curvature| on the segment.
    pub fn max_abs_curvature(&self) -> Result<f64, EllipticError> {
        Ok(match *self {
            Segment::Elastica(p) => {
                let u = p.unit()?;
                u.max_abs_curvature_between(p.s0, p.s0 + p.l) / p.scale
            }
            Segment::Line { .. } => 0.0,
            Segment::Arc { curvature, .. } => curvature.abs(),
        })
    }

    /// The elastica of shape `(family, k, s₀, ℓ)` scaled, rotated and moved so that it runs
    /// from `p0` (t = 0) to `p1` (t = 1); `None` when the shape's ends coincide or `k` is out
    /// of range.
    ///
    /// ```
    /// use elastica::segment::Segment;
    /// use elastica::unit::Family;
    /// let s = Segment::elastica_between(Family::Inflectional, 0.5, 0.3, 1.2, [1.0, 2.0], [4.0, 6.0]).unwrap();
    /// let (a, b) = (s.eval(0.0).unwrap().p, s.eval(1.0).unwrap().p);
    /// assert!((a[0] - 1.0).abs() < 1e-12 && (a[1] - 2.0).abs() < 1e-12);
    /// assert!((b[0] - 4.0).abs() < 1e-12 && (b[1] - 6.0).abs() < 1e-12);
    /// ```
    pub fn elastica_between(
        family: Family,
        k: f64,
        s0: f64,
        l: f64,
        p0: [f64; 2],
        p1: [f64; 2],
    ) -> Option<Segment> {
        let unit = Segment::Elastica(ElasticaParams {
            one_minus_k: None,
            family,
            k,
            s0,
            l,
            scale: 1.0,
            phi: 0.0,
            x0: 0.0,
            y0: 0.0,
        });
        let e = unit.evaluator().ok()?;
        let (z0, z1) = (e.eval(0.0).p, e.eval(1.0).p);
        let (dzx, dzy) = (z1[0] - z0[0], z1[1] - z0[1]);
        let dz2 = dzx * dzx + dzy * dzy;
        if !(dz2 > 0.0) {
            return None;
        }
        // a = (p1 − p0)/(z1 − z0) as complex numbers, b = p0 − a·z0
        let (dpx, dpy) = (p1[0] - p0[0], p1[1] - p0[1]);
        let ax = (dpx * dzx + dpy * dzy) / dz2;
        let ay = (dpy * dzx - dpx * dzy) / dz2;
        let scale = ax.hypot(ay);
        if !(scale > 0.0) || !scale.is_finite() {
            return None;
        }
        Some(Segment::Elastica(ElasticaParams {
            one_minus_k: None,
            family,
            k,
            s0,
            l,
            scale,
            phi: ay.atan2(ax),
            x0: p0[0] - (ax * z0[0] - ay * z0[1]),
            y0: p0[1] - (ax * z0[1] + ay * z0[0]),
        }))
    }

    /// The segment moved by the similarity that puts its ends (t = 0, 1) on `p0` and `p1`
    /// (a turn, a scale and a shift: the shape is kept); `None` when its ends coincide.
    ///
    /// ```
    /// use elastica::segment::Segment;
    /// let arc = Segment::Arc { x0: 0.0, y0: 0.0, phi: 0.5, curvature: 1.0, length: 1.0 };
    /// let moved = arc.with_ends([2.0, 1.0], [2.0, 3.0]).unwrap();
    /// let (a, b) = (moved.eval(0.0).unwrap().p, moved.eval(1.0).unwrap().p);
    /// assert!((a[0] - 2.0).abs() < 1e-12 && (a[1] - 1.0).abs() < 1e-12);
    /// assert!((b[0] - 2.0).abs() < 1e-12 && (b[1] - 3.0).abs() < 1e-12);
    /// ```
    pub fn with_ends(&self, p0: [f64; 2], p1: [f64; 2]) -> Option<Segment> {
        let e = self.evaluator().ok()?;
        let (z0, z1) = (e.eval(0.0).p, e.eval(1.0).p);
        let (dzx, dzy) = (z1[0] - z0[0], z1[1] - z0[1]);
        let dz2 = dzx * dzx + dzy * dzy;
        if !(dz2 > 0.0) || !dz2.is_finite() {
            return None;
        }
        // a = (p1 − p0)/(z1 − z0) as complex numbers, b = p0 − a·z0
        let (dpx, dpy) = (p1[0] - p0[0], p1[1] - p0[1]);
        let a = [(dpx * dzx + dpy * dzy) / dz2, (dpy * dzx - dpx * dzy) / dz2];
        let scale = a[0].hypot(a[1]);
        if !(scale > 0.0) || !scale.is_finite() {
            return None;
        }
        let b = [
            p0[0] - (a[0] * z0[0] - a[1] * z0[1]),
            p0[1] - (a[0] * z0[1] + a[1] * z0[0]),
        ];
        Some(self.mapped(a, b))
    }

    /// The same curve continued by `before` length units before t = 0 and `after` beyond
    /// t = 1 (negative values shorten it); the result is again parameterized on [0, 1].
    pub fn extended(&self, before: f64, after: f64) -> Segment {
        let len = self.length();
        match *self {
            Segment::Elastica(mut p) => {
                if len > 0.0 {
                    let per_len = p.l / len;
                    p.s0 -= per_len * before;
                    p.l = per_len * (len + before + after);
                }
                Segment::Elastica(p)
            }
            Segment::Line {
                x0,
                y0,
                phi,
                length,
            } => Segment::Line {
                x0: x0 - before * phi.cos(),
                y0: y0 - before * phi.sin(),
                phi,
                length: length + before + after,
            },
            Segment::Arc {
                x0,
                y0,
                phi,
                curvature,
                length,
            } => {
                let [dx, dy] = arc_offset(phi, curvature, -before);
                Segment::Arc {
                    x0: x0 + dx,
                    y0: y0 + dy,
                    phi: phi - curvature * before,
                    curvature,
                    length: length + before + after,
                }
            }
        }
    }
}

/// Displacement along a circle of signed curvature κ after arc length s from tangent angle
/// φ: e^{iφ}·(e^{iκs} − 1)/(iκ), exact as κ → 0.
pub(crate) fn arc_offset(phi: f64, kappa: f64, s: f64) -> [f64; 2] {
    let th = kappa * s;
    rot(phi, [s * sinc(th), s * cosc(th)])
}

/// A segment prepared for evaluation.
#[derive(Clone, Debug)]
pub enum SegmentEval {
    /// Closed-form elastica with its elliptic data.
    Elastica(Box<ElasticaSegment>),
    /// Line or arc.
    Simple(Segment),
}

impl LobeCurve for SegmentEval {
    fn point(&self, t: f64) -> Vector2<f64> {
        let p = self.eval(t).p;
        Vector2::new(p[0], p[1])
    }
    fn curvature(&self, t: f64) -> f64 {
        self.eval(t).curvature
    }
}

impl SegmentEval {
    /// Point, tangent, angle and curvature at t.
    pub fn eval(&self, t: f64) -> SegmentPoint {
        match self {
            SegmentEval::Elastica(e) => e.eval(t),
            SegmentEval::Simple(Segment::Line {
                x0,
                y0,
                phi,
                length,
            }) => {
                let (s, c) = phi.sin_cos();
                SegmentPoint {
                    p: [x0 + length * t * c, y0 + length * t * s],
                    tangent: [c, s],
                    angle: *phi,
                    curvature: 0.0,
                }
            }
            SegmentEval::Simple(Segment::Arc {
                x0,
                y0,
                phi,
                curvature,
                length,
            }) => {
                let s = length * t;
                let [dx, dy] = arc_offset(*phi, *curvature, s);
                let a = phi + curvature * s;
                SegmentPoint {
                    p: [x0 + dx, y0 + dy],
                    tangent: [a.cos(), a.sin()],
                    angle: a,
                    curvature: *curvature,
                }
            }
            // `Segment::evaluator` never wraps an elastica in `Simple`.
            SegmentEval::Simple(Segment::Elastica(_)) => SegmentPoint {
                p: [f64::NAN; 2],
                tangent: [f64::NAN; 2],
                angle: f64::NAN,
                curvature: f64::NAN,
            },
        }
    }
}
