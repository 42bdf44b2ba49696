//! B-spline curves of any degree in any dimension (thesis eq. 1.1–1.3).
//!
//! Entry points: [`BSplineCurve::try_new`](crate::bspline::BSplineCurve::try_new), [`BSplineCurve::eval`](crate::bspline::BSplineCurve::eval),
//! [`BSplineCurve::derivative`](crate::bspline::BSplineCurve::derivative), [`BSplineCurve::insert_knot`](crate::bspline::BSplineCurve::insert_knot), and the basis functions
//! [`basis_function`](crate::bspline::basis_function) (the Cox–de Boor recursion written out) and [`BSplineCurve::basis_at`](crate::bspline::BSplineCurve::basis_at)
//! (the triangular scheme used for evaluation). Fits live in [`crate::fit`].

use nalgebra::SVector;

use crate::error::{GeomError, Result};

/// A B-spline curve `s(t) = Σ βᵢᵖ(t) cᵢ` with a non-decreasing knot vector of length
/// `n + p + 1` for `n` control points of degree `p`. The valid parameter domain is
/// `[t_p, t_n]`.
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineCurve<const D: usize> {
    degree: usize,
    knots: Vec<f64>,
    control: Vec<SVector<f64, D>>,
}

/// Checks a knot vector for a given degree and number of control points.
pub(crate) fn check_knots(degree: usize, knots: &[f64], n: usize) -> Result<()> {
    if n < degree + 1 {
        return Err(GeomError::InvalidSpline(format!(
            "degree {degree} needs at least {} control points, got {n}",
            degree + 1
        )));
    }
    if knots.len() != n + degree + 1 {
        return Err(GeomError::InvalidSpline(format!(
            "{n} control points of degree {degree} need {} knots, got {}",
            n + degree + 1,
            knots.len()
        )));
    }
    if knots.iter().any(|k| !k.is_finite()) {
        return Err(GeomError::NonFinite {
            what: "a knot".into(),
        });
    }
    if knots.windows(2).any(|w| w[1] < w[0]) {
        return Err(GeomError::InvalidSpline(
            "knots must be non-decreasing".into(),
        ));
    }
    if knots[n] <= knots[degree] {
        return Err(GeomError::InvalidSpline(
            "the parameter domain [t_p, t_n] is empty".into(),
        ));
    }
    Ok(())
}

/// Index `i` of the knot span `[t_i, t_{i+1})` containing `t`, with `p <= i < n`; the end of
/// the domain belongs to the last non-empty span. `t` outside the domain is clamped.
pub(crate) fn find_span(degree: usize, knots: &[f64], n: usize, t: f64) -> usize {
    let p = degree;
    if t >= knots[n] {
        // last non-empty span
        let mut i = n - 1;
        while i > p && knots[i] >= knots[n] {
            i -= 1;
        }
        return i;
    }
    if t <= knots[p] {
        let mut i = p;
        while i + 1 < n && knots[i + 1] <= knots[p] {
            i += 1;
        }
        return i;
    }
    // binary search for knots[i] <= t < knots[i+1]
    let (mut lo, mut hi) = (p, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if t < knots[mid] {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// The non-zero basis functions `β_{span-p..=span}^p(t)` by the triangular Cox–de Boor scheme.
pub(crate) fn basis_funs(degree: usize, knots: &[f64], span: usize, t: f64, out: &mut Vec<f64>) {
    out.clear();
    out.resize(degree + 1, 0.0);
    basis_into(degree, knots, span, t, out);
}

/// Degrees below this are evaluated without allocating (the curves of this workspace are
/// cubic; allocation was most of a section check's time).
const STACK_DEGREE: usize = 15;

/// [`basis_funs`] into `out[..=degree]`, without allocating for degrees below
/// [`STACK_DEGREE`].
fn basis_into(degree: usize, knots: &[f64], span: usize, t: f64, out: &mut [f64]) {
    if degree < STACK_DEGREE {
        let (mut left, mut right) = ([0.0; STACK_DEGREE + 1], [0.0; STACK_DEGREE + 1]);
        basis_scheme(degree, knots, span, t, out, &mut left, &mut right);
    } else {
        let (mut left, mut right) = (vec![0.0; degree + 1], vec![0.0; degree + 1]);
        basis_scheme(degree, knots, span, t, out, &mut left, &mut right);
    }
}

/// The triangular scheme itself, with its work arrays.
fn basis_scheme(
    degree: usize,
    knots: &[f64],
    span: usize,
    t: f64,
    out: &mut [f64],
    left: &mut [f64],
    right: &mut [f64],
) {
    let p = degree;
    out[..=p].fill(0.0);
    out[0] = 1.0;
    for j in 1..=p {
        left[j] = t - knots[span + 1 - j];
        right[j] = knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let denom = right[r + 1] + left[j - r];
            let temp = if denom != 0.0 { out[r] / denom } else { 0.0 };
            out[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        out[j] = saved;
    }
}

/// The `degree + 1` basis functions of a B-spline with `n_control` control points on
/// `knots` that are non-zero at `t` (clamped to the domain), and the index of the first:
/// the fast way to all of them (O(p²), against O(p·2^p) per function for
/// [`basis_function`]).
///
/// ```
/// use geom::bspline::{basis_function, clamped_uniform_knots, nonzero_basis};
/// let knots = clamped_uniform_knots(3, 8, 0.0, 1.0);
/// let (first, b) = nonzero_basis(3, &knots, 8, 0.3);
/// for (k, v) in b.iter().enumerate() {
///     assert!((v - basis_function(&knots, first + k, 3, 0.3)).abs() < 1e-15);
/// }
/// ```
pub fn nonzero_basis(degree: usize, knots: &[f64], n_control: usize, t: f64) -> (usize, Vec<f64>) {
    let t = t.clamp(knots[degree], knots[n_control]);
    let span = find_span(degree, knots, n_control, t);
    let mut out = Vec::with_capacity(degree + 1);
    basis_funs(degree, knots, span, t, &mut out);
    (span - degree, out)
}

/// The B-spline basis function `β_i^p(t)` on `knots`, computed literally by the Cox–de Boor
/// recursion of eq. (1.2)–(1.3), with `0/0 = 0`. Slow; meant for checks and small inputs.
/// Like eq. (1.2) it uses half-open spans, so it is zero at the very end of a clamped domain.
pub fn basis_function(knots: &[f64], i: usize, p: usize, t: f64) -> f64 {
    if p == 0 {
        return if knots[i] <= t && t < knots[i + 1] && knots[i] < knots[i + 1] {
            1.0
        } else {
            0.0
        };
    }
    let mut v = 0.0;
    let d1 = knots[i + p] - knots[i];
    if d1 > 0.0 {
        v += (t - knots[i]) / d1 * basis_function(knots, i, p - 1, t);
    }
    let d2 = knots[i + p + 1] - knots[i + 1];
    if d2 > 0.0 {
        v += (knots[i + p + 1] - t) / d2 * basis_function(knots, i + 1, p - 1, t);
    }
    v
}

/// A clamped knot vector with uniformly spaced interior knots on `[a, b]`.
pub fn clamped_uniform_knots(degree: usize, n_control: usize, a: f64, b: f64) -> Vec<f64> {
    let p = degree;
    let interior = n_control.saturating_sub(p + 1);
    let mut knots = Vec::with_capacity(n_control + p + 1);
    knots.extend(std::iter::repeat_n(a, p + 1));
    for k in 1..=interior {
        knots.push(a + (b - a) * k as f64 / (interior + 1) as f64);
    }
    knots.extend(std::iter::repeat_n(b, p + 1));
    knots
}

impl<const D: usize> BSplineCurve<D> {
    /// A curve of `degree` with the given knots and control points.
    ///
    /// # Errors
    /// [`GeomError::InvalidSpline`] when the counts do not match (`knots.len() = n + p + 1`),
    /// the knots decrease or the domain is empty; [`GeomError::NonFinite`] for NaN input.
    pub fn try_new(degree: usize, knots: Vec<f64>, control: Vec<SVector<f64, D>>) -> Result<Self> {
        check_knots(degree, &knots, control.len())?;
        if control.iter().any(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(GeomError::NonFinite {
                what: "a control point".into(),
            });
        }
        Ok(Self {
            degree,
            knots,
            control,
        })
    }

    /// A clamped curve with uniform interior knots on `[0, 1]` through the given control points.
    ///
    /// # Errors
    /// As [`Self::try_new`].
    ///
    /// ```
    /// use geom::BSplineCurve;
    /// use nalgebra::Vector2;
    /// let c = BSplineCurve::clamped_uniform(2, vec![
    ///     Vector2::new(0.0, 0.0), Vector2::new(1.0, 2.0), Vector2::new(2.0, 0.0),
    /// ])?;
    /// // clamped: the curve starts and ends on its end control points...
    /// assert_eq!(c.eval(0.0), Vector2::new(0.0, 0.0));
    /// assert_eq!(c.eval(1.0), Vector2::new(2.0, 0.0));
    /// // ...and this quadratic Bézier peaks at half its middle control point's height
    /// assert!((c.eval(0.5) - Vector2::new(1.0, 1.0)).norm() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn clamped_uniform(degree: usize, control: Vec<SVector<f64, D>>) -> Result<Self> {
        let knots = clamped_uniform_knots(degree, control.len(), 0.0, 1.0);
        Self::try_new(degree, knots, control)
    }

    /// Polynomial degree `p`.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knot vector.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The control points.
    pub fn control_points(&self) -> &[SVector<f64, D>] {
        &self.control
    }

    /// The parameter domain `[t_p, t_n]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.control.len()])
    }

    /// The knot span index containing `t` (clamped to the domain).
    pub fn span(&self, t: f64) -> usize {
        find_span(self.degree, &self.knots, self.control.len(), t)
    }

    /// The `p + 1` basis functions that are non-zero at `t`, with the index of the first.
    pub fn basis_at(&self, t: f64) -> (usize, Vec<f64>) {
        let span = self.span(t);
        let mut out = Vec::new();
        basis_funs(self.degree, &self.knots, span, t, &mut out);
        (span - self.degree, out)
    }

    /// The point `s(t)`; `t` outside the domain evaluates the end polynomial pieces.
    pub fn eval(&self, t: f64) -> SVector<f64, D> {
        if self.degree >= STACK_DEGREE {
            let (first, b) = self.basis_at(t);
            return self.combine(first, &b);
        }
        let span = self.span(t);
        let mut b = [0.0; STACK_DEGREE + 1];
        basis_into(self.degree, &self.knots, span, t, &mut b);
        self.combine(span - self.degree, &b[..=self.degree])
    }

    /// `Σ b[k] · control[first + k]`.
    fn combine(&self, first: usize, b: &[f64]) -> SVector<f64, D> {
        let mut p = SVector::<f64, D>::zeros();
        for (k, bk) in b.iter().enumerate() {
            p += self.control[first + k] * *bk;
        }
        p
    }

    /// The derivative curve `s'(t)`, a B-spline of degree `p - 1` (a zero curve for `p = 0`).
    pub fn derivative(&self) -> Self {
        let p = self.degree;
        let n = self.control.len();
        if p == 0 {
            return Self {
                degree: 0,
                knots: self.knots.clone(),
                control: vec![SVector::zeros(); n],
            };
        }
        let mut control = Vec::with_capacity(n - 1);
        for i in 0..n - 1 {
            let dt = self.knots[i + p + 1] - self.knots[i + 1];
            let c = if dt > 0.0 {
                (self.control[i + 1] - self.control[i]) * (p as f64 / dt)
            } else {
                SVector::zeros()
            };
            control.push(c);
        }
        Self {
            degree: p - 1,
            knots: self.knots[1..self.knots.len() - 1].to_vec(),
            control,
        }
    }

    /// Inserts the knot `t` once (Boehm's algorithm); the curve's shape is unchanged.
    ///
    /// # Errors
    /// [`GeomError::InvalidSpline`] if `t` is outside the open domain or would exceed
    /// multiplicity `p`.
    pub fn insert_knot(&self, t: f64) -> Result<Self> {
        let p = self.degree;
        let n = self.control.len();
        let (a, b) = self.domain();
        if !(t > a && t < b) {
            return Err(GeomError::InvalidSpline(format!(
                "knot {t} is not inside the domain ({a}, {b})"
            )));
        }
        let mult = self.knots.iter().filter(|&&k| k == t).count();
        if mult >= p {
            return Err(GeomError::InvalidSpline(format!(
                "knot {t} already has multiplicity {mult}; a degree-{p} curve allows at most {p}"
            )));
        }
        let k = self.span(t);
        let mut control = Vec::with_capacity(n + 1);
        for i in 0..=n {
            let c = if i + p <= k {
                self.control[i]
            } else if i > k {
                self.control[i - 1]
            } else {
                let alpha = (t - self.knots[i]) / (self.knots[i + p] - self.knots[i]);
                self.control[i - 1] * (1.0 - alpha) + self.control[i] * alpha
            };
            control.push(c);
        }
        let mut knots = self.knots.clone();
        knots.insert(k + 1, t);
        Ok(Self {
            degree: p,
            knots,
            control,
        })
    }

    /// A copy with every control point mapped by `f` (e.g. an affine transform).
    pub fn map_control<const E: usize>(
        &self,
        f: impl Fn(&SVector<f64, D>) -> SVector<f64, E>,
    ) -> BSplineCurve<E> {
        BSplineCurve {
            degree: self.degree,
            knots: self.knots.clone(),
            control: self.control.iter().map(f).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector2;

    fn thesis_knots() -> Vec<f64> {
        // Figure 1.6: u = [0,0,0,0,0.25,0.25,0.5,1,1,1,1], degree 3 -> 7 basis functions.
        vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 1.0, 1.0, 1.0, 1.0]
    }

    #[test]
    fn triangular_scheme_matches_recursion() {
        let knots = thesis_knots();
        let ctrl: Vec<_> = (0..7).map(|i| Vector2::new(i as f64, 0.0)).collect();
        let c = BSplineCurve::try_new(3, knots.clone(), ctrl).unwrap();
        for k in 0..200 {
            let t = k as f64 / 200.0;
            let (first, b) = c.basis_at(t);
            for i in 0..7 {
                let expect = basis_function(&knots, i, 3, t);
                let got = if i >= first && i <= first + 3 {
                    b[i - first]
                } else {
                    0.0
                };
                assert!((expect - got).abs() < 1e-14, "i={i} t={t}");
            }
        }
    }

    #[test]
    fn rejects_bad_input() {
        let ctrl = vec![Vector2::new(0.0, 0.0); 3];
        assert!(BSplineCurve::try_new(3, vec![0.0; 7], ctrl.clone()).is_err());
        assert!(
            BSplineCurve::try_new(2, vec![0.0, 0.0, 0.0, 1.0, 0.5, 1.0], ctrl.clone()).is_err()
        );
        let mut bad = ctrl.clone();
        bad[1].x = f64::NAN;
        assert!(BSplineCurve::try_new(2, vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], bad).is_err());
        assert!(BSplineCurve::try_new(2, vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0], ctrl).is_err());
    }

    #[test]
    fn knot_insertion_keeps_shape() {
        let ctrl: Vec<_> = [(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.0), (6.0, 1.0)]
            .iter()
            .map(|&(x, y)| Vector2::new(x, y))
            .collect();
        let c = BSplineCurve::clamped_uniform(3, ctrl).unwrap();
        let d = c.insert_knot(0.3).unwrap().insert_knot(0.3).unwrap();
        assert_eq!(d.control_points().len(), 7);
        for k in 0..=100 {
            let t = k as f64 / 100.0;
            assert!((c.eval(t) - d.eval(t)).norm() < 1e-12);
        }
        assert!(d.insert_knot(0.3).unwrap().insert_knot(0.3).is_err());
    }

    #[test]
    fn end_interpolation() {
        let ctrl: Vec<_> = [(0.0, 0.0), (1.0, 2.0), (3.0, 3.0), (4.0, 0.0)]
            .iter()
            .map(|&(x, y)| Vector2::new(x, y))
            .collect();
        let c = BSplineCurve::clamped_uniform(3, ctrl.clone()).unwrap();
        assert!((c.eval(0.0) - ctrl[0]).norm() < 1e-15);
        assert!((c.eval(1.0) - ctrl[3]).norm() < 1e-15);
    }
}
