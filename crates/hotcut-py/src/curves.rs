//! `hotcut.elastica`: the closed-form elastica of the `elastica` crate from Python — the
//! `Elastica` class, `fit` (points of a plane, 2-D or 3-D), `between` (the boundary-value
//! elastica of `design::bvp`) and `Elliptic` (Jacobi functions of one parameter).

use elastica::{Elliptic as RustElliptic, FitConstraint, FitParams, Segment, SegmentPoint};
use geom::slice::PlaneFrame;
use nalgebra::{Vector2, Vector3};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert::{floats, json_to_py, points as read_points, row, rows, vector};
use crate::guard::guarded;

/// The plane a 3-D curve lies in: its frame and offset along the normal.
#[derive(Clone, Copy)]
pub struct Plane {
    frame: PlaneFrame,
    offset: f64,
}

impl Plane {
    fn world(&self, q: [f64; 2]) -> [f64; 3] {
        let w = self.frame.to_world(self.offset, &Vector2::new(q[0], q[1]));
        [w.x, w.y, w.z]
    }
    fn world_vector(&self, v: [f64; 2]) -> [f64; 3] {
        let w = self.frame.u * v[0] + self.frame.v * v[1];
        [w.x, w.y, w.z]
    }
}

/// A point of a curve's plane in the caller's coordinates: in 3-D when the curve has a
/// plane.
pub fn to_caller(plane: &Option<Plane>, q: [f64; 2]) -> Vec<f64> {
    match plane {
        Some(p) => p.world(q).to_vec(),
        None => q.to_vec(),
    }
}

/// A planar elastica (or its limits, a line or a circular arc), parameterized by
/// t ∈ [0, 1] at constant speed; in 3-D when it was fitted to 3-D points.
#[pyclass(module = "hotcut.elastica", name = "Elastica", frozen)]
pub struct Elastica {
    segment: Segment,
    plane: Option<Plane>,
    fit: Option<elastica::FitResult>,
    residuals: Option<[f64; 3]>,
}

impl Elastica {
    /// A segment in the plane, or in `plane` when given.
    pub fn new(segment: Segment, plane: Option<Plane>) -> Self {
        Self {
            segment,
            plane,
            fit: None,
            residuals: None,
        }
    }

    fn dim(&self) -> usize {
        if self.plane.is_some() {
            3
        } else {
            2
        }
    }

    fn at(&self, t: f64) -> PyResult<SegmentPoint> {
        self.segment
            .eval(t)
            .map_err(|e| PyValueError::new_err(e.to_string()))
    }

    fn point(&self, q: [f64; 2]) -> Vec<f64> {
        to_caller(&self.plane, q)
    }

    fn direction(&self, v: [f64; 2]) -> Vec<f64> {
        match &self.plane {
            Some(p) => p.world_vector(v).to_vec(),
            None => v.to_vec(),
        }
    }

    /// `f` at one t (a row) or at each of several (rows).
    fn map_t(
        &self,
        py: Python<'_>,
        t: &Bound<'_, PyAny>,
        f: impl Fn(&SegmentPoint) -> Vec<f64>,
    ) -> PyResult<Py<PyAny>> {
        guarded(|| match floats(t)? {
            Err(t) => row(py, &f(&self.at(t)?)),
            Ok(ts) => {
                let eval = self
                    .segment
                    .evaluator()
                    .map_err(|e| PyValueError::new_err(e.to_string()))?;
                let mut flat = Vec::with_capacity(ts.len() * self.dim());
                let mut width = self.dim();
                for t in ts {
                    let v = f(&eval.eval(t));
                    width = v.len();
                    flat.extend(v);
                }
                rows(py, &flat, width)
            }
        })
    }
}

#[pymethods]
impl Elastica {
    /// `"inflectional"`, `"noninflectional"`, `"line"` or `"arc"`.
    #[getter]
    fn family(&self) -> &'static str {
        self.segment.kind()
    }

    /// The parameters as the reports write them: for an elastica `k, s0, l, S, phi, x0, y0`
    /// (in its plane's coordinates), for a line `x0, y0, phi, length`, for an arc also
    /// `curvature`.
    #[getter]
    fn params(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        guarded(|| {
            let v = serde_json::to_value(self.segment).unwrap_or_default();
            json_to_py(py, &v)
        })
    }

    /// 2, or 3 for a curve fitted to 3-D points.
    #[getter(dim)]
    fn get_dim(&self) -> usize {
        self.dim()
    }

    /// The plane of a 3-D curve, `{"origin", "u", "v", "normal"}` (its 2-D coordinates are
    /// along `u` and `v` from the origin), or `None`.
    #[getter]
    fn plane(&self, py: Python<'_>) -> PyResult<Option<Py<PyAny>>> {
        let Some(p) = &self.plane else {
            return Ok(None);
        };
        let d = PyDict::new(py);
        let v = |w: Vector3<f64>| row(py, &[w.x, w.y, w.z]);
        d.set_item("origin", v(p.frame.normal * p.offset)?)?;
        d.set_item("u", v(p.frame.u)?)?;
        d.set_item("v", v(p.frame.v)?)?;
        d.set_item("normal", v(p.frame.normal)?)?;
        Ok(Some(d.into_any().unbind()))
    }

    /// Arc length.
    #[getter]
    fn length(&self) -> f64 {
        self.segment.length()
    }

    /// RMS distance from the fitted points over arc length (`None` unless fitted).
    #[getter]
    fn rms(&self) -> Option<f64> {
        self.fit.as_ref().map(|f| f.rms)
    }

    /// Largest distance of a fitted point (`None` unless fitted).
    #[getter]
    fn max(&self) -> Option<f64> {
        self.fit.as_ref().map(|f| f.max)
    }

    /// Whether the fit's last solve converged (`None` unless fitted).
    #[getter]
    fn converged(&self) -> Option<bool> {
        self.fit.as_ref().map(|f| f.converged)
    }

    /// Residuals of `between`: start angle (rad), turning (rad), length (relative).
    #[getter]
    fn residuals(&self) -> Option<[f64; 3]> {
        self.residuals
    }

    /// The point at t = 0.
    #[getter]
    fn start(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        guarded(|| row(py, &self.point(self.at(0.0)?.p)))
    }

    /// The point at t = 1.
    #[getter]
    fn end(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        guarded(|| row(py, &self.point(self.at(1.0)?.p)))
    }

    /// Unit tangent at t = 0.
    #[getter]
    fn start_tangent(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        guarded(|| row(py, &self.direction(self.at(0.0)?.tangent)))
    }

    /// Unit tangent at t = 1.
    #[getter]
    fn end_tangent(&self, py: Python<'_>) -> PyResult<Py<PyAny>> {
        guarded(|| row(py, &self.direction(self.at(1.0)?.tangent)))
    }

    /// The point at `t` (a number), or the points at every t of a sequence, (n, dim).
    fn evaluate(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.map_t(py, t, |s| self.point(s.p))
    }

    /// The unit tangent at `t` (a number or a sequence).
    fn tangent(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.map_t(py, t, |s| self.direction(s.tangent))
    }

    /// The signed curvature at `t` (left turn positive in its plane), a number or a
    /// sequence of them.
    fn curvature(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        guarded(|| match floats(t)? {
            Err(t) => Ok(self.at(t)?.curvature.into_pyobject(py)?.into_any().unbind()),
            Ok(ts) => {
                let mut k = Vec::with_capacity(ts.len());
                for t in ts {
                    k.push(self.at(t)?.curvature);
                }
                row(py, &k)
            }
        })
    }

    /// `n ≥ 2` points at equal arc length from t = 0 to t = 1, (n, dim).
    fn sample(&self, py: Python<'_>, n: i64) -> PyResult<Py<PyAny>> {
        guarded(|| {
            if !(2..=10_000_000).contains(&n) {
                return Err(PyValueError::new_err(format!(
                    "sample: n must be between 2 and 10⁷, got {n}"
                )));
            }
            let n = n as usize;
            let pts = self
                .segment
                .sample(n)
                .map_err(|e| PyValueError::new_err(e.to_string()))?;
            let flat: Vec<f64> = pts.into_iter().flat_map(|q| self.point(q)).collect();
            rows(py, &flat, self.dim())
        })
    }

    /// The t of its inflections inside (0, 1).
    fn inflections(&self) -> PyResult<Vec<f64>> {
        guarded(|| {
            self.segment
                .inflections()
                .map_err(|e| PyValueError::new_err(e.to_string()))
        })
    }

    /// Its largest |curvature|.
    fn max_curvature(&self) -> PyResult<f64> {
        guarded(|| {
            self.segment
                .max_abs_curvature()
                .map_err(|e| PyValueError::new_err(e.to_string()))
        })
    }

    fn __repr__(&self) -> String {
        let fit = self
            .fit
            .as_ref()
            .map(|f| format!(", rms={:.3e}, max={:.3e}", f.rms, f.max))
            .unwrap_or_default();
        format!(
            "Elastica({}, length={:.6}, dim={}{fit})",
            self.segment.kind(),
            self.segment.length(),
            self.dim()
        )
    }
}

/// The constraint named in Python (snake case or as job files write it).
fn constraint_of(name: &str) -> PyResult<FitConstraint> {
    match name {
        "free" | "Free" => Ok(FitConstraint::Free),
        "end_points" | "EndPoints" => Ok(FitConstraint::EndPoints),
        "end_points_and_length" | "EndPointsAndLength" => Ok(FitConstraint::EndPointsAndLength),
        other => Err(PyValueError::new_err(format!(
            "constraint: expected \"free\", \"end_points\" or \"end_points_and_length\", got {other:?}"
        ))),
    }
}

/// Points of a plane in 2-D: 3-D points are projected into their best plane, which must
/// hold them to `plane_tolerance` (default 10⁻⁶ of their extent).
pub fn planar(
    pts: &crate::convert::Points,
    plane_tolerance: Option<f64>,
) -> PyResult<(Vec<[f64; 2]>, Option<Plane>)> {
    if pts.dim == 2 {
        return Ok((pts.xy(), None));
    }
    let v: Vec<Vector3<f64>> = pts.xyz.iter().map(|p| Vector3::from(*p)).collect();
    let (frame, offset, off) = PlaneFrame::fit_points(&v)
        .map_err(|_| PyValueError::new_err("points: they do not span a line, so no plane"))?;
    // by coordinates: no overflow where the points are finite
    let extent = v.iter().map(|p| (p - v[0]).amax()).fold(0.0, f64::max);
    if let Some(t) = plane_tolerance {
        crate::checks::positive("plane_tolerance", t, true)?;
    }
    let tol = plane_tolerance.unwrap_or(1e-6 * extent);
    if !(off <= tol) {
        return Err(PyValueError::new_err(format!(
            "points: not planar: a point lies {off:.3e} from their best plane, more than plane_tolerance = {tol:.3e}"
        )));
    }
    let xy = v
        .iter()
        .map(|p| {
            let q = frame.to_plane(p);
            [q.x, q.y]
        })
        .collect();
    Ok((xy, Some(Plane { frame, offset })))
}

/// `fit(points, constraint="free", *, plane_tolerance=None)`.
#[pyfunction]
#[pyo3(signature = (points, constraint="free", *, arc_length=None, polish=true, plane_tolerance=None))]
fn fit(
    points: &Bound<'_, PyAny>,
    constraint: &str,
    arc_length: Option<&Bound<'_, PyAny>>,
    polish: bool,
    plane_tolerance: Option<f64>,
) -> PyResult<Elastica> {
    guarded(|| {
        let c = constraint_of(constraint)?;
        let pts = read_points(points, "points", 3)?;
        let (xy, plane) = planar(&pts, plane_tolerance)?;
        let params = FitParams {
            constraint: c,
            ..FitParams::default()
        };
        let s = match arc_length {
            None => geom::polyline::chord_lengths(&xy),
            Some(s) => {
                let s = match floats(s)? {
                    Ok(s) => s,
                    Err(_) => {
                        return Err(PyValueError::new_err(
                            "arc_length: expected one number per point",
                        ))
                    }
                };
                if s.len() != xy.len() {
                    return Err(PyValueError::new_err(format!(
                        "arc_length: {} numbers for {} points",
                        s.len(),
                        xy.len()
                    )));
                }
                if !s.iter().all(|v| v.is_finite()) || s.windows(2).any(|w| !(w[1] > w[0])) {
                    return Err(PyValueError::new_err(
                        "arc_length: must be finite and strictly increasing",
                    ));
                }
                s
            }
        };
        let error = |e: elastica::FitError| PyValueError::new_err(format!("fit: {e}"));
        let mut f = elastica::fit_points_with_arclength(&xy, &s, &params).map_err(error)?;
        if polish {
            f = elastica::polish(&xy, &s, &f, &params).map_err(error)?;
        }
        Ok(Elastica {
            segment: f.segment,
            plane,
            fit: Some(f),
            residuals: None,
        })
    })
}

/// A tangent given as an angle (radians) or a 2-vector.
fn angle_of(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<(f64, bool)> {
    if let Ok(a) = obj.extract::<f64>() {
        if !a.is_finite() {
            return Err(PyValueError::new_err(format!("{what}: not finite")));
        }
        return Ok((a, true));
    }
    let v = vector(obj, what)?;
    if v.len() != 2 || !(v[0].hypot(v[1]) > 0.0) {
        return Err(PyValueError::new_err(format!(
            "{what}: expected an angle or a non-zero 2-vector"
        )));
    }
    Ok((v[1].atan2(v[0]), false))
}

/// `between(p0, t0, p1, t1, length)`.
#[pyfunction]
fn between(
    p0: &Bound<'_, PyAny>,
    t0: &Bound<'_, PyAny>,
    p1: &Bound<'_, PyAny>,
    t1: &Bound<'_, PyAny>,
    length: f64,
) -> PyResult<Elastica> {
    guarded(|| {
        let (a, b) = (vector(p0, "p0")?, vector(p1, "p1")?);
        if a.len() != 2 || b.len() != 2 {
            return Err(PyValueError::new_err(
                "between: p0 and p1 must be 2-D points",
            ));
        }
        let chord = (b[0] - a[0]).hypot(b[1] - a[1]);
        if !(chord.is_normal() && chord.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "between: p0 and p1 must be distinct points a normal float apart, got a distance of {chord:e}"
            )));
        }
        crate::checks::positive("length", length, false)?;
        let (start_angle, _) = angle_of(t0, "t0")?;
        let (mut end_angle, given) = angle_of(t1, "t1")?;
        if !given {
            // a direction: the turning within (−π, π]
            let pi = std::f64::consts::PI;
            let d = (end_angle - start_angle + pi).rem_euclid(2.0 * pi) - pi;
            end_angle = start_angle + d;
        }
        let d = design::EndData {
            start: [a[0], a[1]],
            start_angle,
            end: [b[0], b[1]],
            end_angle,
            length,
        };
        let s = design::solve(&d).map_err(|e| PyValueError::new_err(format!("between: {e}")))?;
        let l = s.segment.length();
        if !(l.is_normal() && l.is_finite()) || s.segment.evaluator().is_err() {
            return Err(PyValueError::new_err(format!(
                "between: no usable elastica for these end data (length {l:e})"
            )));
        }
        Ok(Elastica {
            residuals: Some(s.residuals),
            ..Elastica::new(s.segment, None)
        })
    })
}

/// Jacobi elliptic functions and integrals of one parameter m ∈ [0, 1].
#[pyclass(module = "hotcut.elastica", name = "Elliptic", frozen)]
struct Elliptic {
    e: RustElliptic,
}

impl Elliptic {
    fn each(
        &self,
        py: Python<'_>,
        u: &Bound<'_, PyAny>,
        f: impl Fn(&elastica::JacobiValues) -> f64,
    ) -> PyResult<Py<PyAny>> {
        guarded(|| match floats(u)? {
            Err(u) => Ok(f(&self.e.eval(u)).into_pyobject(py)?.into_any().unbind()),
            Ok(us) => {
                let v: Vec<f64> = us.iter().map(|&u| f(&self.e.eval(u))).collect();
                row(py, &v)
            }
        })
    }
}

#[pymethods]
impl Elliptic {
    #[new]
    fn py_new(m: f64) -> PyResult<Self> {
        guarded(|| {
            RustElliptic::new(m)
                .map(|e| Self { e })
                .map_err(|e| PyValueError::new_err(format!("Elliptic: {e}")))
        })
    }

    /// The parameter m = k².
    #[getter]
    fn m(&self) -> f64 {
        self.e.m()
    }

    /// The complete integral of the first kind K(m), the quarter period.
    #[allow(non_snake_case)]
    fn K(&self) -> f64 {
        self.e.k()
    }

    /// `E()`: the complete integral of the second kind E(m); `E(u)`: Jacobi's epsilon
    /// function E(u|m) = ∫₀ᵘ dn²(t|m) dt (= E(am u | m)), a number or a sequence.
    #[allow(non_snake_case)]
    #[pyo3(signature = (u=None))]
    fn E(&self, py: Python<'_>, u: Option<&Bound<'_, PyAny>>) -> PyResult<Py<PyAny>> {
        match u {
            None => Ok(self.e.e().into_pyobject(py)?.into_any().unbind()),
            Some(u) => self.each(py, u, |v| v.eps),
        }
    }

    /// sn(u|m), for a number or a sequence.
    fn sn(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.each(py, u, |v| v.sn)
    }

    /// cn(u|m).
    fn cn(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.each(py, u, |v| v.cn)
    }

    /// dn(u|m).
    fn dn(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.each(py, u, |v| v.dn)
    }

    /// The amplitude am(u|m), continuous and increasing in u.
    fn am(&self, py: Python<'_>, u: &Bound<'_, PyAny>) -> PyResult<Py<PyAny>> {
        self.each(py, u, |v| v.am)
    }

    fn __repr__(&self) -> String {
        format!("Elliptic(m={})", self.e.m())
    }
}

/// Adds `Elastica`, `Elliptic`, `fit` and `between`.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Elastica>()?;
    m.add_class::<Elliptic>()?;
    m.add_function(wrap_pyfunction!(fit, m)?)?;
    m.add_function(wrap_pyfunction!(between, m)?)
}

/// The elastica of a check, as a Python object.
pub fn elastica_object(
    py: Python<'_>,
    segment: Segment,
    plane: Option<Plane>,
    fit: Option<elastica::FitResult>,
) -> PyResult<Py<Elastica>> {
    Py::new(
        py,
        Elastica {
            fit,
            ..Elastica::new(segment, plane)
        },
    )
}
