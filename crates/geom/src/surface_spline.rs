//! Tensor-product B-spline surfaces (thesis eq. 1.4) and ruled / piecewise-ruled surfaces
//! (eq. 1.5–1.7), which are tensor-product surfaces of degree 1 in `v`.
//!
//! Entry points: [`BSplineSurface::try_new`](crate::surface_spline::BSplineSurface::try_new), [`BSplineSurface::eval`](crate::surface_spline::BSplineSurface::eval),
//! [`BSplineSurface::partials`](crate::surface_spline::BSplineSurface::partials), [`BSplineSurface::ruled`](crate::surface_spline::BSplineSurface::ruled), [`BSplineSurface::piecewise_ruled`](crate::surface_spline::BSplineSurface::piecewise_ruled).

use nalgebra::Vector3;

use crate::bspline::{basis_funs, check_knots, clamped_uniform_knots, find_span, BSplineCurve};
use crate::error::{GeomError, Result};

/// `F(u, v) = Σᵢ Σⱼ βᵢᵖ(u) βⱼ^q(v) c_{i,j}` with control points stored row-major:
/// `control[i * nv + j]` is `c_{i,j}`.
#[derive(Debug, Clone, PartialEq)]
pub struct BSplineSurface {
    degree_u: usize,
    degree_v: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    nu: usize,
    nv: usize,
    control: Vec<Vector3<f64>>,
}

impl BSplineSurface {
    /// A surface from degrees, knot vectors and an `nu × nv` control grid (row-major).
    ///
    /// # Errors
    /// [`GeomError::InvalidSpline`] for inconsistent sizes or knots, [`GeomError::NonFinite`]
    /// for NaN control points.
    pub fn try_new(
        (degree_u, degree_v): (usize, usize),
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        (nu, nv): (usize, usize),
        control: Vec<Vector3<f64>>,
    ) -> Result<Self> {
        if control.len() != nu * nv {
            return Err(GeomError::InvalidSpline(format!(
                "control grid is {nu}×{nv} = {} points, got {}",
                nu * nv,
                control.len()
            )));
        }
        check_knots(degree_u, &knots_u, nu)?;
        check_knots(degree_v, &knots_v, nv)?;
        if control.iter().any(|c| c.iter().any(|v| !v.is_finite())) {
            return Err(GeomError::NonFinite {
                what: "a control point".into(),
            });
        }
        Ok(Self {
            degree_u,
            degree_v,
            knots_u,
            knots_v,
            nu,
            nv,
            control,
        })
    }

    /// A surface with clamped uniform knots on `[0, 1]²` (degrees are lowered when the grid is
    /// too small for them).
    ///
    /// # Errors
    /// As [`Self::try_new`].
    pub fn clamped_uniform(
        (degree_u, degree_v): (usize, usize),
        (nu, nv): (usize, usize),
        control: Vec<Vector3<f64>>,
    ) -> Result<Self> {
        let pu = degree_u.min(nu.saturating_sub(1));
        let pv = degree_v.min(nv.saturating_sub(1));
        Self::try_new(
            (pu, pv),
            clamped_uniform_knots(pu, nu, 0.0, 1.0),
            clamped_uniform_knots(pv, nv, 0.0, 1.0),
            (nu, nv),
            control,
        )
    }

    /// The ruled surface `R(u, v) = (1 − v) s₂(u) + v s₁(u)` of eq. (1.5) between two curves
    /// with the same degree and knots.
    ///
    /// # Errors
    /// [`GeomError::InvalidSpline`] when the two curves do not share degree and knots.
    ///
    /// ```
    /// use geom::{BSplineCurve, BSplineSurface};
    /// use nalgebra::Vector3;
    /// let line = |z: f64| BSplineCurve::clamped_uniform(1, vec![Vector3::new(0.0, 0.0, z), Vector3::new(1.0, 0.0, z)]);
    /// let (top, bottom) = (line(1.0)?, line(0.0)?);
    /// let r = BSplineSurface::ruled(&top, &bottom)?;
    /// // v = 0 is the second curve, v = 1 the first, straight lines between
    /// assert!((r.eval(0.3, 0.0) - bottom.eval(0.3)).norm() < 1e-15);
    /// assert!((r.eval(0.3, 1.0) - top.eval(0.3)).norm() < 1e-15);
    /// assert!((r.eval(0.3, 0.25) - Vector3::new(0.3, 0.0, 0.25)).norm() < 1e-15);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn ruled(s1: &BSplineCurve<3>, s2: &BSplineCurve<3>) -> Result<Self> {
        Self::piecewise_ruled(&[s2.clone(), s1.clone()])
    }

    /// The piecewise-ruled surface of eq. (1.7): degree 1 in `v` through the curves in order
    /// (`h` curves make `h − 1` ruled strips), with `v` running over `[0, 1]` uniformly.
    ///
    /// # Errors
    /// [`GeomError::InvalidSpline`] for fewer than two curves or curves that do not share
    /// degree and knots.
    pub fn piecewise_ruled(curves: &[BSplineCurve<3>]) -> Result<Self> {
        let Some(first) = curves.first() else {
            return Err(GeomError::InvalidSpline(
                "a ruled surface needs two curves".into(),
            ));
        };
        if curves.len() < 2 {
            return Err(GeomError::InvalidSpline(
                "a ruled surface needs two curves".into(),
            ));
        }
        if curves
            .iter()
            .any(|c| c.degree() != first.degree() || c.knots() != first.knots())
        {
            return Err(GeomError::InvalidSpline(
                "the curves of a ruled surface must share degree and knots".into(),
            ));
        }
        let nu = first.control_points().len();
        let nv = curves.len();
        let mut control = Vec::with_capacity(nu * nv);
        for i in 0..nu {
            for c in curves {
                control.push(c.control_points()[i]);
            }
        }
        Self::try_new(
            (first.degree(), 1),
            first.knots().to_vec(),
            clamped_uniform_knots(1, nv, 0.0, 1.0),
            (nu, nv),
            control,
        )
    }

    /// Knot vector along `u`.
    pub fn knots_u(&self) -> &[f64] {
        &self.knots_u
    }

    /// Knot vector along `v`.
    pub fn knots_v(&self) -> &[f64] {
        &self.knots_v
    }

    /// Degrees `(p, q)`.
    pub fn degrees(&self) -> (usize, usize) {
        (self.degree_u, self.degree_v)
    }

    /// Control-grid size `(nu, nv)`.
    pub fn grid_size(&self) -> (usize, usize) {
        (self.nu, self.nv)
    }

    /// The control points, row-major.
    pub fn control_points(&self) -> &[Vector3<f64>] {
        &self.control
    }

    /// The parameter domain `((u0, u1), (v0, v1))`.
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (
            (self.knots_u[self.degree_u], self.knots_u[self.nu]),
            (self.knots_v[self.degree_v], self.knots_v[self.nv]),
        )
    }

    /// The point `F(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> Vector3<f64> {
        self.partials(u, v).0
    }

    /// `(F, ∂F/∂u, ∂F/∂v)` at `(u, v)`, from the basis functions and their first derivatives.
    pub fn partials(&self, u: f64, v: f64) -> (Vector3<f64>, Vector3<f64>, Vector3<f64>) {
        let (su, bu, du) = basis_and_derivative(self.degree_u, &self.knots_u, self.nu, u);
        let (sv, bv, dv) = basis_and_derivative(self.degree_v, &self.knots_v, self.nv, v);
        let (fu, fv) = (su - self.degree_u, sv - self.degree_v);
        let mut p = Vector3::zeros();
        let mut pu = Vector3::zeros();
        let mut pv = Vector3::zeros();
        for (a, (ba, da)) in bu.iter().zip(&du).enumerate() {
            for (b, (bb, db)) in bv.iter().zip(&dv).enumerate() {
                let c = self.control[(fu + a) * self.nv + fv + b];
                p += c * (ba * bb);
                pu += c * (da * bb);
                pv += c * (ba * db);
            }
        }
        (p, pu, pv)
    }
}

/// Span, basis values and their first derivatives at `t`.
fn basis_and_derivative(p: usize, knots: &[f64], n: usize, t: f64) -> (usize, Vec<f64>, Vec<f64>) {
    let span = find_span(p, knots, n, t);
    let mut b = Vec::new();
    basis_funs(p, knots, span, t, &mut b);
    let mut d = vec![0.0; p + 1];
    if p > 0 {
        // derivative from the degree p-1 basis: β'_{i,p} = p (β_{i,p-1}/(t_{i+p}-t_i) - β_{i+1,p-1}/(t_{i+p+1}-t_{i+1}))
        let mut lower = Vec::new();
        basis_funs(p - 1, knots, span, t, &mut lower);
        // lower[k] is β_{span-p+1+k, p-1}, k = 0..p
        for (k, dk) in d.iter_mut().enumerate() {
            let i = span - p + k;
            let mut v = 0.0;
            if k >= 1 {
                let den = knots[i + p] - knots[i];
                if den > 0.0 {
                    v += lower[k - 1] / den;
                }
            }
            if k < p {
                let den = knots[i + p + 1] - knots[i + 1];
                if den > 0.0 {
                    v -= lower[k] / den;
                }
            }
            *dk = p as f64 * v;
        }
    }
    (span, b, d)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wavy() -> BSplineSurface {
        let (nu, nv) = (5, 4);
        let mut c = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                c.push(Vector3::new(
                    i as f64,
                    j as f64,
                    ((i * 3 + j * 5) % 4) as f64 * 0.3,
                ));
            }
        }
        BSplineSurface::clamped_uniform((3, 2), (nu, nv), c).unwrap()
    }

    #[test]
    fn partials_match_finite_differences() {
        let s = wavy();
        let h = 1e-6;
        for &(u, v) in &[(0.2, 0.3), (0.45, 0.55), (0.77, 0.12), (0.01, 0.99)] {
            let (_, pu, pv) = s.partials(u, v);
            let fu = (s.eval(u + h, v) - s.eval(u - h, v)) / (2.0 * h);
            let fv = (s.eval(u, v + h) - s.eval(u, v - h)) / (2.0 * h);
            assert!((pu - fu).norm() < 1e-6, "{pu} vs {fu}");
            assert!((pv - fv).norm() < 1e-6, "{pv} vs {fv}");
        }
    }

    #[test]
    fn ruled_surface_is_linear_in_v() {
        let a = BSplineCurve::clamped_uniform(
            2,
            vec![
                Vector3::new(0.0, 0.0, 0.0),
                Vector3::new(1.0, 0.0, 1.0),
                Vector3::new(2.0, 0.0, 0.0),
            ],
        )
        .unwrap();
        let b = a.map_control(|c| c + Vector3::new(0.0, 2.0, 0.5));
        let r = BSplineSurface::ruled(&b, &a).unwrap();
        for &u in &[0.0, 0.3, 0.8, 1.0] {
            for &v in &[0.0, 0.25, 0.6, 1.0] {
                let expect = a.eval(u) * (1.0 - v) + b.eval(u) * v;
                assert!((r.eval(u, v) - expect).norm() < 1e-12);
            }
        }
        assert!(BSplineSurface::piecewise_ruled(&[a]).is_err());
    }
}
