//! How close a cubic Bézier is to the elastica with its end points, end tangents and
//! length ("Designing for Robotic Hot-Blade Cutting" §4, fig. 12): the deviation at equal
//! arc length, the elastica's largest curvature and inflections, and the residual of the
//! affine curvature law of an elastica, κ = λ₂x − λ₁y + α ("Hot Blade Cuttings" eq. 11),
//! fitted on the Bézier by least squares — zero for an elastica, so a cheap predictor of
//! the deviation before any elastica is solved.

use nalgebra::{Matrix3, Vector3};

use crate::bezier::Bezier;
use crate::bvp::{solve, EndData};
use crate::error::{DesignError, Result};
use elastica::segment::Segment;

/// Samples along the curve for the deviation and the eq. (11) fit.
pub const SAMPLES: usize = 200;

/// A Bézier against its elastica.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Proxy {
    /// The elastica, t ∈ [0, 1] from b₀ to b₃.
    pub elastica: Segment,
    /// The Bézier's length.
    pub length: f64,
    /// Largest distance between the two curves at the same arc length.
    pub max_deviation: f64,
    /// Root mean square of that distance over arc length.
    pub rms_deviation: f64,
    /// Distance between the elastica's ends and b₀, b₃ (the larger).
    pub end_point_error: f64,
    /// Difference of the end tangent angles (the larger), radians.
    pub end_angle_error: f64,
    /// The elastica's length against the Bézier's, relative.
    pub relative_length_error: f64,
    /// The elastica's largest |κ|.
    pub max_curvature: f64,
    /// The elastica's inflections inside (0, 1).
    pub inflections: usize,
    /// RMS residual of κ ≈ λ₂x − λ₁y + α fitted on the Bézier, times its length
    /// (dimensionless).
    pub eq11_residual: f64,
    /// The interior angles of the control polygon, degrees.
    pub polygon_angles_deg: [f64; 2],
    /// The discrete elastica's largest distance from the closed form.
    pub discrete_distance: f64,
}

/// The Bézier's end data.
///
/// ```
/// use design::{end_data, Bezier};
/// let b = Bezier { p: [[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]] }; // an arch
/// let d = end_data(&b)?;
/// assert_eq!((d.start, d.end, d.length), (b.p[0], b.p[3], b.length()));
/// assert_eq!((d.start_angle, d.end_angle), (b.start_angle()?, b.end_angle_unwrapped()?));
/// # Ok::<(), design::DesignError>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] for coincident control points.
pub fn end_data(b: &Bezier) -> Result<EndData> {
    Ok(EndData {
        start: b.p[0],
        start_angle: b.start_angle()?,
        end: b.p[3],
        end_angle: b.end_angle_unwrapped()?,
        length: b.length(),
    })
}

/// The eq. (11) residual of `b`: κ fitted by λ₂x − λ₁y + α over [`SAMPLES`] points evenly
/// spaced in arc length (coordinates about their centroid), the RMS residual times the
/// length.
///
/// ```
/// use design::proxy::eq11_residual;
/// use design::{proxy, Bezier};
/// // a gentle arch and a steep one over the same chord: the steep one is further from
/// // the curvature law of an elastica, and further from its elastica
/// let gentle = Bezier { p: [[0.0, 0.0], [200.0, 60.0], [400.0, 60.0], [600.0, 0.0]] };
/// let steep = Bezier { p: [[0.0, 0.0], [100.0, 300.0], [500.0, 300.0], [600.0, 0.0]] };
/// assert!(eq11_residual(&gentle) < eq11_residual(&steep));
/// assert!(proxy(&gentle)?.max_deviation < proxy(&steep)?.max_deviation);
/// # Ok::<(), design::DesignError>(())
/// ```
pub fn eq11_residual(b: &Bezier) -> f64 {
    let table = b.arc_table();
    let length = table.length();
    let rows: Vec<([f64; 2], f64)> = (0..=SAMPLES)
        .map(|i| {
            let t = table.at_length(length * i as f64 / SAMPLES as f64);
            (b.point(t), b.curvature(t))
        })
        .collect();
    affine_curvature_residual(&rows, length)
}

/// The eq. (11) residual of a curve of `length` sampled at `rows` (point, curvature),
/// evenly along it: κ fitted by λ₂x − λ₁y + α by least squares (coordinates about their
/// centroid), the RMS residual times the length (the least-norm fit where it is singular:
/// 0 for a straight curve). NaN only for non-finite samples.
///
/// ```
/// use design::proxy::affine_curvature_residual;
/// // a circle's curvature is constant: the law fits it exactly (α = κ)
/// let circle: Vec<([f64; 2], f64)> = (0..=40)
///     .map(|i| { let a = 0.05 * i as f64; ([2.0 * a.sin(), 2.0 - 2.0 * a.cos()], 0.5) })
///     .collect();
/// assert!(affine_curvature_residual(&circle, 4.0) < 1e-12);
/// // κ = x² along a line is not affine in the position
/// let bent: Vec<([f64; 2], f64)> =
///     (0..=40).map(|i| { let x = 0.05 * i as f64; ([x, 0.0], x * x) }).collect();
/// assert!(affine_curvature_residual(&bent, 2.0) > 0.01);
/// ```
pub fn affine_curvature_residual(rows: &[([f64; 2], f64)], length: f64) -> f64 {
    let n = rows.len() as f64;
    let c = rows
        .iter()
        .fold([0.0, 0.0], |c, (p, _)| [c[0] + p[0] / n, c[1] + p[1] / n]);
    let (mut a, mut y) = (Matrix3::zeros(), Vector3::zeros());
    for (p, k) in rows {
        let v = Vector3::new(p[0] - c[0], -(p[1] - c[1]), 1.0);
        a += v * v.transpose();
        y += v * *k;
    }
    // singular where the curve is straight (y constant): the least-squares solution of
    // least norm then, which fits κ ≡ 0 exactly
    let tiny = 1e-12 * a.amax();
    let Some(x) = a
        .lu()
        .solve(&y)
        .or_else(|| a.svd(true, true).solve(&y, tiny).ok())
    else {
        return f64::NAN;
    };
    let ss: f64 = rows
        .iter()
        .map(|(p, k)| {
            let fit = x[0] * (p[0] - c[0]) - x[1] * (p[1] - c[1]) + x[2];
            (k - fit).powi(2)
        })
        .sum();
    (ss / n).sqrt() * length
}

/// The Bézier `b` against its elastica.
///
/// ```
/// use design::{proxy, Bezier};
/// let b = Bezier { p: [[0.0, 0.0], [200.0, 60.0], [400.0, 60.0], [600.0, 0.0]] };
/// let r = proxy(&b)?;
/// assert!(r.end_point_error < 1e-9 * r.length && r.end_angle_error < 1e-9);
/// assert!(r.relative_length_error.abs() < 1e-9);
/// assert!(r.max_deviation < 0.01 * r.length && r.rms_deviation <= r.max_deviation);
/// assert_eq!(r.inflections, 0); // a symmetric arch
/// // a straight Bézier: its elastica is the line
/// let line = Bezier { p: [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.0, 0.0]] };
/// let r = proxy(&line)?;
/// assert_eq!(r.elastica.kind(), "line");
/// assert!(r.max_deviation < 1e-9);
/// // a collapsed one has none
/// assert!(proxy(&Bezier { p: [[1.0, 1.0]; 4] }).is_err());
/// # Ok::<(), design::DesignError>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] for a degenerate Bézier (collapsed: its control points coincide;
/// a straight one is fine, its elastica the line); the errors of
/// [`solve`].
pub fn proxy(b: &Bezier) -> Result<Proxy> {
    proxy_offset(b, 0.0)
}

/// The Bézier `b` moved `offset` along its left normal (towards `+v` for a curve running
/// across the cut: the blade's path half a kerf off the design), against the elastica with
/// that curve's end points, end tangents (the design's) and length (`L − offset·Δθ`, `Δθ`
/// the design's turning). Deviations are measured between the moved design and the
/// elastica at equal arc length of the moved design. `offset = 0` is [`proxy`].
///
/// ```
/// use design::proxy::proxy_offset;
/// use design::{proxy, Bezier};
/// let b = Bezier { p: [[0.0, 0.0], [200.0, 60.0], [400.0, 60.0], [600.0, 0.0]] };
/// let (on, off) = (proxy(&b)?, proxy_offset(&b, 2.0)?);
/// assert_eq!(proxy_offset(&b, 0.0)?, on);
/// // the arch turns right by Δθ = −2 atan(0.3): 2 mm to its left (above it) is longer by
/// // 2·|Δθ|
/// let turn = 2.0 * 0.3f64.atan();
/// assert!((off.length - (on.length + 2.0 * turn)).abs() < 1e-9 * on.length);
/// assert!(off.end_point_error < 1e-9 * off.length);
/// # Ok::<(), design::DesignError>(())
/// ```
///
/// # Errors
/// As [`proxy`]; [`DesignError::Invalid`] where the design bends tighter than the offset
/// allows (`offset · κ ≥ 1/2`).
pub fn proxy_offset(b: &Bezier, offset: f64) -> Result<Proxy> {
    let design = end_data(b)?;
    let moved = Moved::new(b, offset)?;
    let d = moved.end_data(&design);
    let sol = solve(&d)?;
    let e = sol
        .segment
        .evaluator()
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    let (mut max, mut ss) = (0.0f64, 0.0);
    for i in 0..=SAMPLES {
        let w = i as f64 / SAMPLES as f64;
        let p = moved.point_at_length(b, d.length * w);
        let q = e.eval(w).p;
        let dist = (p[0] - q[0]).hypot(p[1] - q[1]);
        max = max.max(dist);
        // trapezoid weights over arc length
        let weight = if i == 0 || i == SAMPLES { 0.5 } else { 1.0 };
        ss += weight * dist * dist / SAMPLES as f64;
    }
    let (a, z) = (e.eval(0.0), e.eval(1.0));
    let gap = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
    let inflections = sol
        .segment
        .inflections()
        .map_err(|e| DesignError::Elastica(e.to_string()))?
        .len();
    let max_curvature = sol
        .segment
        .max_abs_curvature()
        .map_err(|e| DesignError::Elastica(e.to_string()))?;
    Ok(Proxy {
        elastica: sol.segment,
        length: d.length,
        max_deviation: max,
        rms_deviation: ss.sqrt(),
        end_point_error: gap(a.p, d.start).max(gap(z.p, d.end)),
        end_angle_error: crate::bezier::wrap(a.angle - d.start_angle)
            .abs()
            .max(crate::bezier::wrap(z.angle - d.end_angle).abs()),
        relative_length_error: sol.segment.length() / d.length - 1.0,
        max_curvature,
        inflections,
        eq11_residual: eq11_residual(b),
        polygon_angles_deg: b.polygon_angles().map(f64::to_degrees),
        discrete_distance: sol.discrete_distance,
    })
}

/// `n ≥ 2` points of `b` moved `offset` along its left normal, at equal fractions of the
/// moved curve's arc length (the design as the blade must follow it).
///
/// ```
/// use design::proxy::moved_samples;
/// use design::Bezier;
/// let b = Bezier { p: [[0.0, 0.0], [200.0, 60.0], [400.0, 60.0], [600.0, 0.0]] };
/// let on = moved_samples(&b, 0.0, 11)?;
/// assert_eq!(on.len(), 11);
/// assert_eq!((on[0], on[10]), (b.p[0], b.p[3]));
/// assert!((on[5][0] - 300.0).abs() < 1e-9); // half the length: the middle of the arch
/// // 2 above: the start moved along the start's left normal
/// let up = moved_samples(&b, 2.0, 11)?;
/// let a = 0.3f64.atan();
/// assert!((up[0][0] + 2.0 * a.sin()).abs() < 1e-12 && (up[0][1] - 2.0 * a.cos()).abs() < 1e-12);
/// # Ok::<(), design::DesignError>(())
/// ```
///
/// # Errors
/// As [`proxy_offset`].
pub fn moved_samples(b: &Bezier, offset: f64, n: usize) -> Result<Vec<[f64; 2]>> {
    let moved = Moved::new(b, offset)?;
    let design = end_data(b)?;
    let length = moved.end_data(&design).length;
    let n = n.max(2);
    Ok((0..n)
        .map(|i| moved.point_at_length(b, length * i as f64 / (n - 1) as f64))
        .collect())
}

/// A Bézier moved along its left normal: its points, and the map from the moved curve's
/// arc length back to the Bézier's parameter (a table of Gauss–Legendre integrals of
/// `|b'|·(1 − offset·κ)`).
struct Moved {
    offset: f64,
    /// `(t, arc length of the moved curve to t)` at `MOVED_STEPS + 1` even `t`.
    table: Vec<(f64, f64)>,
    /// Without an offset: the Bézier's own arc-length table.
    arc: Option<crate::bezier::ArcTable>,
}

/// Steps of the moved curve's arc-length table.
const MOVED_STEPS: usize = 4 * SAMPLES;

impl Moved {
    fn new(b: &Bezier, offset: f64) -> Result<Self> {
        if offset == 0.0 {
            return Ok(Self {
                offset,
                table: Vec::new(),
                arc: Some(b.arc_table()),
            });
        }
        let speed = |t: f64| {
            let v = b.d1(t);
            v[0].hypot(v[1]) * (1.0 - offset * b.curvature(t))
        };
        let mut table = Vec::with_capacity(MOVED_STEPS + 1);
        let mut s = 0.0;
        table.push((0.0, 0.0));
        let h = 1.0 / MOVED_STEPS as f64;
        for i in 0..MOVED_STEPS {
            let t0 = i as f64 * h;
            let mid = t0 + 0.5 * h;
            s += 0.5
                * h
                * crate::bezier::GAUSS
                    .iter()
                    .map(|(x, w)| w * speed(mid + 0.5 * h * x))
                    .sum::<f64>();
            table.push((t0 + h, s));
        }
        for i in 0..=MOVED_STEPS {
            let t = i as f64 * h;
            if !(offset * b.curvature(t) < 0.5) {
                return Err(DesignError::Invalid(format!(
                    "a blade path {offset} off the design is too far where it bends with radius {:.6} (at {:?}): the kerf must be less than the radius",
                    1.0 / b.curvature(t).abs(),
                    b.point(t)
                )));
            }
        }
        Ok(Self {
            offset,
            table,
            arc: None,
        })
    }

    /// The moved curve's end data: the design's ends moved, its tangents, its length.
    fn end_data(&self, design: &EndData) -> EndData {
        if self.offset == 0.0 {
            return *design;
        }
        let normal = |a: f64| [-a.sin(), a.cos()];
        let (n0, n1) = (normal(design.start_angle), normal(design.end_angle));
        EndData {
            start: [
                design.start[0] + self.offset * n0[0],
                design.start[1] + self.offset * n0[1],
            ],
            end: [
                design.end[0] + self.offset * n1[0],
                design.end[1] + self.offset * n1[1],
            ],
            length: self.table.last().map_or(design.length, |l| l.1),
            ..*design
        }
    }

    /// The moved curve's point at its arc length `s`.
    fn point_at_length(&self, b: &Bezier, s: f64) -> [f64; 2] {
        if let Some(arc) = self.arc.as_ref().filter(|_| self.offset == 0.0) {
            return b.point(arc.at_length(s));
        }
        let i = self
            .table
            .partition_point(|&(_, l)| l < s)
            .clamp(1, self.table.len() - 1);
        let ((t0, s0), (t1, s1)) = (self.table[i - 1], self.table[i]);
        let t = if s1 > s0 {
            t0 + (t1 - t0) * ((s - s0) / (s1 - s0)).clamp(0.0, 1.0)
        } else {
            t0
        };
        let (p, v) = (b.point(t), b.d1(t));
        let speed = v[0].hypot(v[1]);
        [
            p[0] - self.offset * v[1] / speed,
            p[1] + self.offset * v[0] / speed,
        ]
    }
}
