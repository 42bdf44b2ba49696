//! Curve analysis: inflection points (sign change of the curvature, then the bisection of
//! eq. 5.3), the lobes between them, and the curvature maximum of each lobe.
//!
//! Entry point: [`analyze_curve`](crate::analysis::analyze_curve) with
//! [`CurveAnalysisParams`](crate::analysis::CurveAnalysisParams).
//!
//! # The false-inflection rule
//! Between two consecutive inflections the curvature has one sign; call that stretch a
//! *lobe* and its *turning* the change of the tangent angle across it (`∫κ ds`). Noise on a
//! nearly straight stretch makes lobes that barely turn, each bounded by a *pair* of false
//! inflections. The rule: while some interior lobe (one between two inflections) turns by
//! less than `min_lobe_turning` radians, take the one that turns least and remove both its
//! inflections, merging it with its neighbours (like pushing out a small dent, thesis
//! §5.1.3). Lobes that touch an end of the curve are kept: their single inflection is real
//! as far as the curve is concerned. Every removal is counted in
//! [`CurveAnalysis::suppressed_inflections`](crate::analysis::CurveAnalysis::suppressed_inflections), so the report can say so.
//!
//! On a curve fitted to a polyline, the curvature inside the first and last segment is set
//! by the spline's end condition, not by data; sign changes there
//! ([`CurveAnalysisParams::end_margins`](crate::analysis::CurveAnalysisParams::end_margins)) are dropped and counted the same way.
//!
//! # The noise floor
//! Then every lobe, those at the ends included, must depart from its chord by more than
//! the curve's noise floor (f64 rounding at its scale, the caller's `noise`, and half the
//! data's allowance around it): the rule of [`crate::significance`]. This is what gives
//! straight and planar stretches, exact or meshed, no inflections at all.

use nalgebra::Vector2;

use crate::ends::EndTrend;

/// Standard errors taken off an end trend's curvature for the lower bound of its lobe's
/// departure (see `add_end_inflections`).
const CONFIDENCE: f64 = 2.0;
use crate::error::{GeomError, Result};
use crate::planar::{signed_curvature, ArcLength, Jet2, PlanarCurve};
use crate::significance::{drop_noise_lobes, rounding_floor, Floor, LobeCurve, DATA_SHARE};

/// A planar curve seen by the noise-floor rule.
struct Lobes<'a>(&'a dyn PlanarCurve);

impl LobeCurve for Lobes<'_> {
    fn point(&self, t: f64) -> Vector2<f64> {
        self.0.jet(t).p
    }
    fn curvature(&self, t: f64) -> f64 {
        signed_curvature(&self.0.jet(t))
    }
}

/// The noise floor of the lobe `[t0, t1]` (see [`crate::significance`]): `base` (rounding
/// and the caller's floor) or [`DATA_SHARE`] × the largest precision of the data points in
/// the lobe and the two around it, whichever is larger, as a distance and a curvature. On a
/// curve fitted to points, a lobe holding fewer than [`RESOLVED_POINTS`] of them is not in
/// the data (its curvature is the spline's, set by its penalty or end condition): its floor
/// is infinite. A near-end inflection the data do show comes back through the end trends.
fn lobe_floor(params: &CurveAnalysisParams, base: f64, length: f64, t0: f64, t1: f64) -> Floor {
    let data = &params.data_params;
    let mut d = base;
    if !data.is_empty() {
        let held = data.partition_point(|&t| t < t1) - data.partition_point(|&t| t <= t0);
        if held < RESOLVED_POINTS {
            return Floor::of(f64::INFINITY, length);
        }
    }
    let precision = &params.data_precision;
    if !precision.is_empty() && precision.len() == data.len() {
        let lo = data.partition_point(|&t| t < t0).saturating_sub(1);
        let hi = (data.partition_point(|&t| t <= t1) + 1).min(data.len());
        let most = precision[lo..hi.max(lo)]
            .iter()
            .copied()
            .fold(0.0, f64::max);
        d = d.max(DATA_SHARE * most);
    }
    Floor::of(d, length)
}

/// Parameters of [`analyze_curve`].
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAnalysisParams {
    /// Number of equally spaced parameter samples at which the curvature sign is read
    /// (the `M` of eq. 5.2). At least 8.
    pub samples: usize,
    /// Bisection (eq. 5.3) stops when the bracket is shorter than this, in parameter units.
    pub bisection_tolerance: f64,
    /// Lobes that turn less than this many radians are noise; see the module docs.
    pub min_lobe_turning: f64,
    /// Parameter lengths at the start and the end of the curve in which curvature is not
    /// determined by data (the first and last segment of a fitted polyline; 0 for exact
    /// curves). Sign changes there are not reported as inflections.
    pub end_margins: (f64, f64),
    /// Parameters of the points the curve was fitted to, in order (empty for exact
    /// curves). A lobe holding at least [`RESOLVED_POINTS`] of them is determined by the
    /// data and is kept however little it turns; `min_lobe_turning` applies to the others.
    pub data_params: Vec<f64>,
    /// Curvature at the start and the end as the data show it (see [`crate::ends`]).
    /// Where the spline's end lobe has the other sign and is more than twice as long as
    /// the data window, the inflection the data show there is added.
    pub end_trends: (Option<EndTrend>, Option<EndTrend>),
    /// How far each data point is known to lie from the true curve (one per
    /// `data_params`; empty for exact curves): the data's precision, which sets the noise
    /// floor of the lobes around it ([`crate::significance`]).
    pub data_precision: Vec<f64>,
    /// A noise floor for the whole curve, in its units (≥ 0): lobes departing from their
    /// chords by less are not inflections' lobes ([`crate::significance`]). f64 rounding
    /// at the curve's scale is always a floor.
    pub noise: f64,
}

/// Curvature samples per exact curve at least (a height field's section): every sign
/// change of its curvature counts, so it is read at least this densely.
pub const EXACT_SAMPLES: usize = 8192;

impl CurveAnalysisParams {
    /// These parameters for an exact curve (no data points): no lobe is dropped for
    /// turning little (small ripples on a flat stretch are real inflections the blade must
    /// make, and only the noise floor of f64 rounding applies), and the curvature is read
    /// at least [`EXACT_SAMPLES`] times.
    pub fn for_exact(&self) -> Self {
        Self {
            samples: self.samples.max(EXACT_SAMPLES),
            min_lobe_turning: 0.0,
            ..self.clone()
        }
    }
}

/// Data points a lobe must hold to be kept whatever its turning (three points give one
/// curvature of their own).
pub const RESOLVED_POINTS: usize = 3;

impl Default for CurveAnalysisParams {
    fn default() -> Self {
        Self {
            samples: 2000,
            bisection_tolerance: 1e-9,
            min_lobe_turning: 1e-3,
            end_margins: (0.0, 0.0),
            data_params: Vec::new(),
            end_trends: (None, None),
            data_precision: Vec::new(),
            noise: 0.0,
        }
    }
}

/// A point of interest on a curve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurvePoint {
    /// Curve parameter.
    pub t: f64,
    /// Arc length from the start of the curve.
    pub s: f64,
    /// The point.
    pub point: Vector2<f64>,
    /// Signed curvature there.
    pub curvature: f64,
}

/// A stretch of one curvature sign between inflections (or curve ends).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lobe {
    /// Start parameter.
    pub t0: f64,
    /// End parameter.
    pub t1: f64,
    /// Change of tangent angle across the lobe, radians (signed).
    pub turning: f64,
}

/// What [`analyze_curve`] finds.
#[derive(Debug, Clone, PartialEq)]
pub struct CurveAnalysis {
    /// Arc length of the curve.
    pub length: f64,
    /// Inflection points in curve order, after the false-inflection rule.
    pub inflections: Vec<CurvePoint>,
    /// One curvature maximum (largest |κ|) per lobe, in curve order.
    pub curvature_maxima: Vec<CurvePoint>,
    /// The point of largest |κ| on the whole curve.
    pub max_abs_curvature: CurvePoint,
    /// Lobes between consecutive inflections, after the rule.
    pub lobes: Vec<Lobe>,
    /// Inflections removed by the false-inflection rule or found inside the end margins.
    pub suppressed_inflections: usize,
}

fn sign(k: f64) -> i8 {
    if k > 0.0 {
        1
    } else if k < 0.0 {
        -1
    } else {
        0
    }
}

/// Bisection of eq. (5.3) on a bracket `[t, t + dt]` whose ends have opposite curvature sign.
fn bisect_inflection(curve: &dyn PlanarCurve, mut t: f64, mut dt: f64, tol: f64) -> f64 {
    let s_end = sign(signed_curvature(&curve.jet(t + dt)));
    while dt > tol {
        let half = 0.5 * dt;
        let mid = sign(signed_curvature(&curve.jet(t + half)));
        if mid == s_end {
            dt = half;
        } else {
            t += half;
            dt = half;
        }
        if half == 0.0 {
            break;
        }
    }
    t + 0.5 * dt
}

fn wrap_angle(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    let mut a = a % tau;
    if a > std::f64::consts::PI {
        a -= tau;
    } else if a < -std::f64::consts::PI {
        a += tau;
    }
    a
}

fn tangent_angle(j: &Jet2) -> f64 {
    j.d1.y.atan2(j.d1.x)
}

/// Turning of the curve over `[t0, t1]`, summing wrapped angle steps at the given samples.
fn turning(curve: &dyn PlanarCurve, t0: f64, t1: f64, ts: &[f64]) -> f64 {
    let mut prev = tangent_angle(&curve.jet(t0));
    let mut sum = 0.0;
    for &t in ts
        .iter()
        .filter(|&&t| t > t0 && t < t1)
        .chain(std::iter::once(&t1))
    {
        let a = tangent_angle(&curve.jet(t));
        sum += wrap_angle(a - prev);
        prev = a;
    }
    sum
}

/// Golden-section search for the largest |κ| on `[a, b]`.
fn refine_max(curve: &dyn PlanarCurve, mut a: f64, mut b: f64, tol: f64) -> f64 {
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let f = |t: f64| signed_curvature(&curve.jet(t)).abs();
    let mut c = b - g * (b - a);
    let mut d = a + g * (b - a);
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..100 {
        if (b - a).abs() <= tol {
            break;
        }
        if fc >= fd {
            b = d;
            d = c;
            fd = fc;
            c = b - g * (b - a);
            fc = f(c);
        } else {
            a = c;
            c = d;
            fc = fd;
            d = a + g * (b - a);
            fd = f(d);
        }
    }
    0.5 * (a + b)
}

/// Parameters where the sampled curvature `ks` (at `ts`) changes sign, each refined by
/// bisection to `tolerance`; exact zeros are skipped (the last non-zero sign carries).
fn sign_changes(curve: &dyn PlanarCurve, ts: &[f64], ks: &[f64], tolerance: f64) -> Vec<f64> {
    let mut raw = Vec::new();
    let mut last: Option<(usize, i8)> = None;
    for (i, &k) in ks.iter().enumerate() {
        let s = sign(k);
        if s == 0 {
            continue;
        }
        if let Some((j, ls)) = last {
            if ls != s {
                raw.push(bisect_inflection(curve, ts[j], ts[i] - ts[j], tolerance));
            }
        }
        last = Some((i, s));
    }
    raw
}

/// The false-inflection rule: the interior lobe (between `bounds`) turning least is merged
/// with its neighbours, dropping its two inflections, while it turns less than
/// `min_turning`. Lobes holding [`RESOLVED_POINTS`] of `data` (sorted data parameters;
/// none for an exact curve) are kept. Returns the inflections dropped. End lobes have one
/// inflection, not a pair, and are kept.
fn merge_flat_lobes(
    bounds: &mut Vec<f64>,
    turns: &mut Vec<f64>,
    min_turning: f64,
    data: &[f64],
) -> usize {
    let held =
        |t0: f64, t1: f64| data.partition_point(|&t| t < t1) - data.partition_point(|&t| t <= t0);
    let mut suppressed = 0;
    // each pass removes two bounds, so at most bounds.len() / 2 passes
    while let Some((i, &tmin)) = turns
        .iter()
        .enumerate()
        .take(turns.len().saturating_sub(1))
        .skip(1)
        .filter(|(i, _)| held(bounds[*i], bounds[*i + 1]) < RESOLVED_POINTS)
        .min_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))
    {
        if tmin.abs() >= min_turning {
            break;
        }
        bounds.drain(i..=i + 1);
        let merged = turns[i - 1] + turns[i] + turns[i + 1];
        turns.splice(i - 1..=i + 1, [merged]);
        suppressed += 2;
    }
    suppressed
}

/// Adds the inflection the data show near an end (`params.end_trends`) where the spline's
/// end lobe has the other sign and is more than twice as long as the data window (so the
/// curvature varies slowly there and the window's linear trend holds). The new end lobe's
/// turning is the local fit's (curvature linear to zero). Returns the data's curvature at
/// each end where an inflection was added.
fn add_end_inflections(
    curve: &dyn PlanarCurve,
    bounds: &mut Vec<f64>,
    turns: &mut Vec<f64>,
    params: &CurveAnalysisParams,
    ts: &[f64],
    floor: f64,
) -> (Option<f64>, Option<f64>) {
    // the added end lobe, curvature falling linearly from k to 0 over z, departs from its
    // chord by 0.064·|k|·z² (the largest of k(s²/2 − s³/6z − zs/3) over [0, z]); it must
    // be above the floor (rounding, the caller's and the file's) by the trend's lower
    // confidence bound (|k| less CONFIDENCE standard errors; the trend itself is
    // SIGNIFICANCE standard errors from zero): the trend is measured against the data's
    // residuals, so their precision is in it already
    let above = |tr: &EndTrend, t0: f64, t1: f64| {
        let k = (tr.curvature.abs() - CONFIDENCE * tr.standard_error).max(0.0);
        0.064 * k * (t1 - t0).powi(2) >= floor
    };
    let mut added = (None, None);
    if let Some(tr) = params.end_trends.0 {
        let (a, next) = (bounds[0], bounds[1]);
        if sign(tr.curvature) != sign(turns[0]) && turns[0] != 0.0 && next - a > 2.0 * tr.window {
            let t = a + tr
                .zero_at
                .unwrap_or(params.end_margins.0)
                .clamp(0.0, tr.window);
            if t > a && t < next && above(&tr, a, t) {
                bounds.insert(1, t);
                let rest = turning(curve, t, next, ts);
                turns.splice(0..1, [0.5 * tr.curvature * (t - a), rest]);
                added.0 = Some(tr.curvature);
            }
        }
    }
    if let Some(tr) = params.end_trends.1 {
        let n = bounds.len();
        let (prev, b) = (bounds[n - 2], bounds[n - 1]);
        let last = turns.len() - 1;
        if sign(tr.curvature) != sign(turns[last])
            && turns[last] != 0.0
            && b - prev > 2.0 * tr.window
        {
            let t = b - tr
                .zero_at
                .unwrap_or(params.end_margins.1)
                .clamp(0.0, tr.window);
            if t > prev && t < b && above(&tr, t, b) {
                bounds.insert(n - 1, t);
                let rest = turning(curve, prev, t, ts);
                turns.splice(last..=last, [rest, 0.5 * tr.curvature * (b - t)]);
                added.1 = Some(tr.curvature);
            }
        }
    }
    added
}

/// The parameter of the largest |κ| in `lobe`: the best sample (`ks` at `ts`), refined by
/// golden section within `dt` of it; the lobe's middle when no sample falls in it.
fn lobe_maximum(
    curve: &dyn PlanarCurve,
    lobe: &Lobe,
    ts: &[f64],
    ks: &[f64],
    dt: f64,
    tolerance: f64,
) -> f64 {
    let mut best: Option<(f64, f64)> = None;
    for (&t, &k) in ts.iter().zip(ks) {
        if t < lobe.t0 || t > lobe.t1 {
            continue;
        }
        if best.is_none_or(|(_, bk)| k.abs() > bk) {
            best = Some((t, k.abs()));
        }
    }
    match best {
        Some((t, _)) => refine_max(
            curve,
            (t - dt).max(lobe.t0),
            (t + dt).min(lobe.t1),
            tolerance,
        ),
        None => 0.5 * (lobe.t0 + lobe.t1),
    }
}

/// Analyses a planar curve: length, inflections, lobes, curvature maxima, max |κ|.
///
/// # Errors
/// [`GeomError::InvalidDomain`] for an empty domain or a curve of zero length,
/// [`GeomError::NonFinite`] when the curve evaluates to NaN.
///
/// # Example
/// ```
/// use geom::analysis::{analyze_curve, CurveAnalysisParams};
/// use geom::planar::{Jet2, PlanarCurve};
/// use nalgebra::Vector2;
/// // y = sin(x) on [0.5, 7]: inflections at π and 2π.
/// struct Sine;
/// impl PlanarCurve for Sine {
///     fn domain(&self) -> (f64, f64) { (0.5, 7.0) }
///     fn jet(&self, t: f64) -> Jet2 {
///         Jet2 { p: Vector2::new(t, t.sin()), d1: Vector2::new(1.0, t.cos()), d2: Vector2::new(0.0, -t.sin()) }
///     }
/// }
/// let a = analyze_curve(&Sine, &CurveAnalysisParams::default()).unwrap();
/// assert_eq!(a.inflections.len(), 2);
/// assert!((a.inflections[0].t - std::f64::consts::PI).abs() < 1e-8);
/// ```
pub fn analyze_curve(
    curve: &dyn PlanarCurve,
    params: &CurveAnalysisParams,
) -> Result<CurveAnalysis> {
    let (a, b) = curve.domain();
    if !(b > a) || !a.is_finite() || !b.is_finite() {
        return Err(GeomError::InvalidDomain(format!(
            "curve domain [{a}, {b}] is empty"
        )));
    }
    let m = params.samples.max(8);
    let ts: Vec<f64> = (0..=m).map(|i| a + (b - a) * i as f64 / m as f64).collect();
    let jets: Vec<Jet2> = ts.iter().map(|&t| curve.jet(t)).collect();
    if jets.iter().any(|j| {
        !(j.p
            .iter()
            .chain(j.d1.iter())
            .chain(j.d2.iter())
            .all(|v| v.is_finite()))
    }) {
        return Err(GeomError::NonFinite {
            what: "the curve (or its derivatives) at some parameter".into(),
        });
    }
    let arc = ArcLength::new(curve, m.min(4000));
    let length = arc.length();
    if !(length > 0.0) {
        return Err(GeomError::InvalidDomain("the curve has zero length".into()));
    }
    let ks: Vec<f64> = jets.iter().map(signed_curvature).collect();

    // bisection never below rounding of the parameter domain, whatever its unit
    let bisection = params.bisection_tolerance.max(1e-12 * (b - a));
    let mut raw = sign_changes(curve, &ts, &ks, bisection);

    // Sign changes inside the end margins carry no information from the data.
    let before = raw.len();
    raw.retain(|&t| t > a + params.end_margins.0 && t < b - params.end_margins.1);
    let in_margins = before - raw.len();

    // Lobes between consecutive inflections, then the false-inflection rule.
    let mut bounds: Vec<f64> = std::iter::once(a)
        .chain(raw.iter().copied())
        .chain(std::iter::once(b))
        .collect();
    let mut turns: Vec<f64> = bounds
        .windows(2)
        .map(|w| turning(curve, w[0], w[1], &ts))
        .collect();
    let mut suppressed = in_margins
        + merge_flat_lobes(
            &mut bounds,
            &mut turns,
            params.min_lobe_turning,
            &params.data_params,
        );
    // the noise floor: every lobe must depart from its chord by more than it
    let reach = jets
        .iter()
        .map(|j| j.p.x.abs().max(j.p.y.abs()))
        .fold(0.0, f64::max);
    let base = rounding_floor(reach, length).max(params.noise);
    let floor = |t0: f64, t1: f64| lobe_floor(params, base, length, t0, t1);
    let dropped = drop_noise_lobes(&Lobes(curve), &mut bounds, &floor, &ts);
    if dropped > 0 {
        suppressed += dropped;
        turns = bounds
            .windows(2)
            .map(|w| turning(curve, w[0], w[1], &ts))
            .collect();
    }
    let added = add_end_inflections(curve, &mut bounds, &mut turns, params, &ts, base);

    let at = |t: f64| {
        let j = curve.jet(t);
        CurvePoint {
            t,
            s: arc.s_at(curve, t),
            point: j.p,
            curvature: signed_curvature(&j),
        }
    };
    let inflections: Vec<CurvePoint> = bounds[1..bounds.len() - 1].iter().map(|&t| at(t)).collect();
    let lobes: Vec<Lobe> = bounds
        .windows(2)
        .zip(&turns)
        .map(|(w, &turning)| Lobe {
            t0: w[0],
            t1: w[1],
            turning,
        })
        .collect();

    // One maximum of |κ| per lobe: best sample, then golden-section refinement.
    let dt = (b - a) / m as f64;
    let tolerance = bisection;
    let mut maxima: Vec<CurvePoint> = lobes
        .iter()
        .map(|lobe| at(lobe_maximum(curve, lobe, &ts, &ks, dt, tolerance)))
        .collect();
    // an added end lobe's largest |κ| is the data's, at the end
    if let (Some(k), Some(first)) = (added.0, maxima.first_mut()) {
        *first = CurvePoint {
            curvature: k,
            ..at(a)
        };
    }
    if let (Some(k), Some(last)) = (added.1, maxima.last_mut()) {
        *last = CurvePoint {
            curvature: k,
            ..at(b)
        };
    }
    let mut max_point = at(a);
    for (&t, &k) in ts.iter().zip(&ks) {
        if k.abs() > max_point.curvature.abs() {
            max_point = at(t);
        }
    }
    for p in &maxima {
        if p.curvature.abs() > max_point.curvature.abs() {
            max_point = *p;
        }
    }
    Ok(CurveAnalysis {
        length,
        inflections,
        curvature_maxima: maxima,
        max_abs_curvature: max_point,
        lobes,
        suppressed_inflections: suppressed,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    struct Circle(f64);
    impl PlanarCurve for Circle {
        fn domain(&self) -> (f64, f64) {
            (0.0, 5.0)
        }
        fn jet(&self, t: f64) -> Jet2 {
            let r = self.0;
            Jet2 {
                p: Vector2::new(r * t.cos(), r * t.sin()),
                d1: Vector2::new(-r * t.sin(), r * t.cos()),
                d2: Vector2::new(-r * t.cos(), -r * t.sin()),
            }
        }
    }

    #[test]
    fn circle_has_curvature_one_over_r_and_no_inflections() {
        let c = Circle(2.5);
        let a = analyze_curve(&c, &CurveAnalysisParams::default()).unwrap();
        assert!(a.inflections.is_empty());
        assert!((a.max_abs_curvature.curvature - 0.4).abs() < 1e-12);
        assert!((a.length - 12.5).abs() < 1e-9);
        let arc = ArcLength::new(&c, 50);
        let t = arc.t_at(&c, 5.0);
        assert!((t - 2.0).abs() < 1e-10);
    }

    struct Wiggle;
    impl PlanarCurve for Wiggle {
        fn domain(&self) -> (f64, f64) {
            (0.0, 10.0)
        }
        fn jet(&self, t: f64) -> Jet2 {
            // a gentle arc plus a tiny dent near t = 5 that makes two false inflections
            let x = t - 5.0;
            let dent = 3e-5 * (-50.0 * x * x).exp();
            Jet2 {
                p: Vector2::new(t, 0.001 * t * t + dent),
                d1: Vector2::new(1.0, 0.002 * t - 100.0 * x * dent),
                d2: Vector2::new(0.0, 0.002 + dent * (1e4 * x * x - 100.0)),
            }
        }
    }

    #[test]
    fn tiny_dent_inflections_are_suppressed() {
        let raw = analyze_curve(
            &Wiggle,
            &CurveAnalysisParams {
                min_lobe_turning: 0.0,
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(raw.inflections.len(), 2, "the dent makes two inflections");
        let a = analyze_curve(&Wiggle, &CurveAnalysisParams::default()).unwrap();
        assert!(a.inflections.is_empty());
        assert_eq!(a.suppressed_inflections, 2);
        assert_eq!(a.curvature_maxima.len(), 1);
    }

    #[test]
    fn a_dent_the_data_resolve_is_kept_one_they_do_not_is_dropped() {
        // the dent's lobe spans about t ∈ [4.86, 5.14]
        let fine: Vec<f64> = (0..=1000).map(|i| i as f64 / 100.0).collect();
        let coarse: Vec<f64> = (0..=10).map(|i| i as f64).collect();
        let with = |data: Vec<f64>| {
            analyze_curve(
                &Wiggle,
                &CurveAnalysisParams {
                    data_params: data,
                    ..Default::default()
                },
            )
            .unwrap()
        };
        assert_eq!(with(fine).inflections.len(), 2, "28 points inside the lobe");
        let a = with(coarse);
        assert!(a.inflections.is_empty());
        assert_eq!(a.suppressed_inflections, 2);
    }

    #[test]
    fn an_end_trend_of_the_other_sign_adds_one_inflection_at_its_zero() {
        // y = t²: convex throughout; the data say the curvature is negative at t = 0
        // and crosses zero 0.5 in
        let trend = EndTrend {
            curvature: -0.01,
            zero_at: Some(0.5),
            window: 1.0,
            standard_error: 1e-3,
        };
        let a = analyze_curve(
            &Wiggle,
            &CurveAnalysisParams {
                end_trends: (Some(trend), None),
                ..Default::default()
            },
        )
        .unwrap();
        assert_eq!(a.inflections.len(), 1);
        assert!((a.inflections[0].t - 0.5).abs() < 1e-12);
        assert_eq!(a.lobes.len(), 2);
        assert!(a.lobes[0].turning < 0.0 && a.lobes[1].turning > 0.0);
        assert_eq!(a.curvature_maxima[0].curvature, -0.01);
        // the same sign as the spline's lobe, or a window too long for the lobe: nothing
        for tr in [
            EndTrend {
                curvature: 0.01,
                ..trend
            },
            EndTrend {
                window: 6.0,
                ..trend
            },
        ] {
            let a = analyze_curve(
                &Wiggle,
                &CurveAnalysisParams {
                    end_trends: (None, Some(tr)),
                    ..Default::default()
                },
            )
            .unwrap();
            assert!(a.inflections.is_empty(), "{tr:?}");
        }
    }

    #[test]
    fn line_has_zero_curvature() {
        struct Line;
        impl PlanarCurve for Line {
            fn domain(&self) -> (f64, f64) {
                (0.0, 1.0)
            }
            fn jet(&self, t: f64) -> Jet2 {
                Jet2 {
                    p: Vector2::new(3.0 * t, 4.0 * t),
                    d1: Vector2::new(3.0, 4.0),
                    d2: Vector2::zeros(),
                }
            }
        }
        let a = analyze_curve(&Line, &CurveAnalysisParams::default()).unwrap();
        assert_eq!(a.max_abs_curvature.curvature, 0.0);
        assert!(a.inflections.is_empty());
        assert!((a.length - 5.0).abs() < 1e-12);
        let _ = PI;
    }
}
