//! Design curves over several blocks as one planar cubic B-spline ("Designing for Robotic
//! Hot-Blade Cutting" §4, fig. 15): the knots are the block faces across the cut,
//! `u₀ < u₁ < … < uₙ` (clamped: the ends fourfold), so there is one polynomial piece per
//! block and the curve is C² where pieces meet. The construction asks that the knot
//! images, the curve's points at the knots, lie on the faces: their first coordinate is
//! the face's. Control points whose first coordinates are the Greville abscissae of the
//! knots ([`greville`](crate::spline::greville)) meet it exactly, whatever their heights.
//!
//! Each piece, a cubic polynomial, is handed on as the Bézier with the same points
//! ([`BSpline::pieces`](crate::spline::BSpline::pieces), by blossoming), so that the Bézier tools — its elastica, its
//! proxy measures — serve both constructions.

use crate::bezier::Bezier;
use crate::error::{DesignError, Result};

/// A clamped planar cubic B-spline whose interior knots are the block faces.
///
/// ```
/// use design::spline::{greville, BSpline};
/// // three blocks between the faces 0, 300, 700, 1000; control points at the Greville
/// // abscissae, so the knot images lie on the faces whatever the heights
/// let faces = vec![0.0, 300.0, 700.0, 1000.0];
/// let heights = [0.0, 80.0, -40.0, 120.0, 60.0, 10.0];
/// let control = greville(&faces).into_iter().zip(heights).map(|(u, h)| [u, h]).collect();
/// let s = BSpline::new(faces, control)?;
/// assert_eq!(s.pieces_len(), 3);
/// assert!(s.off_faces(1e-9).is_empty());
/// // one Bézier per block, joined end to end on the faces
/// let pieces = s.pieces();
/// assert_eq!(pieces.len(), 3);
/// assert_eq!(pieces[0].p[0], [0.0, 0.0]);
/// for (a, b) in pieces.iter().zip(&pieces[1..]) {
///     assert!((a.p[3][0] - b.p[0][0]).abs() < 1e-9 && (a.p[3][1] - b.p[0][1]).abs() < 1e-9);
/// }
/// # Ok::<(), design::DesignError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BSpline {
    /// The faces `u₀ < … < uₙ` (n ≥ 1 pieces).
    pub faces: Vec<f64>,
    /// n + 3 control points.
    pub control: Vec<[f64; 2]>,
}

/// The Greville abscissae of the clamped cubic knot vector on `faces`: control points
/// there make the spline's first coordinate equal its parameter, so that every knot image
/// lies on its face.
///
/// ```
/// use design::spline::greville;
/// let g = greville(&[0.0, 300.0, 700.0, 1000.0]);
/// assert_eq!(g.len(), 6); // one per control point: faces + 2
/// assert_eq!((g[0], g[1], g[4], g[5]), (0.0, 100.0, 900.0, 1000.0));
/// assert!((g[2] - 1000.0 / 3.0).abs() < 1e-12); // (0 + 300 + 700) / 3
/// ```
pub fn greville(faces: &[f64]) -> Vec<f64> {
    let t = knots(faces);
    (0..faces.len() + 2)
        .map(|j| (t[j + 1] + t[j + 2] + t[j + 3]) / 3.0)
        .collect()
}

/// The clamped knot vector `[u₀ ×4, u₁, …, uₙ₋₁, uₙ ×4]`.
fn knots(faces: &[f64]) -> Vec<f64> {
    let (Some(&first), Some(&last)) = (faces.first(), faces.last()) else {
        return Vec::new();
    };
    let inner = &faces[1..faces.len().saturating_sub(1).max(1)];
    let mut t = vec![first; 4];
    t.extend_from_slice(inner);
    t.extend([last; 4]);
    t
}

impl BSpline {
    /// A spline on `faces` with `control` points.
    ///
    /// ```
    /// use design::spline::BSpline;
    /// // one block: the spline is one cubic, its control points the Bézier's
    /// let p = vec![[0.0, 0.0], [1.0, 2.0], [3.0, 2.0], [4.0, 0.0]];
    /// let s = BSpline::new(vec![0.0, 4.0], p.clone())?;
    /// assert_eq!(s.pieces()[0].p.to_vec(), p);
    /// assert!(BSpline::new(vec![0.0, 4.0], p[..3].to_vec()).is_err()); // one point short
    /// assert!(BSpline::new(vec![4.0, 0.0], p).is_err()); // faces decreasing
    /// # Ok::<(), design::DesignError>(())
    /// ```
    ///
    /// # Errors
    /// [`DesignError::Invalid`] unless there are at least two faces, strictly increasing
    /// and finite, and exactly `faces.len() + 2` finite control points.
    pub fn new(faces: Vec<f64>, control: Vec<[f64; 2]>) -> Result<Self> {
        if faces.len() < 2 {
            return Err(DesignError::Invalid(
                "a spline needs at least two faces (one block)".into(),
            ));
        }
        if faces.iter().any(|u| !u.is_finite()) || faces.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(DesignError::Invalid(format!(
                "the faces must increase strictly: {faces:?}"
            )));
        }
        if control.len() != faces.len() + 2 {
            return Err(DesignError::Invalid(format!(
                "a spline over {} block(s) needs {} control points, not {}",
                faces.len() - 1,
                faces.len() + 2,
                control.len()
            )));
        }
        if control.iter().flatten().any(|v| !v.is_finite()) {
            return Err(DesignError::Invalid(
                "the control points must be finite".into(),
            ));
        }
        Ok(Self { faces, control })
    }

    /// The blossom of piece `i` at `(x₁, x₂, x₃)` (de Boor's algorithm with one argument
    /// per level): `f(t, t, t)` is the point at `t`, and the Bézier points of the piece
    /// are `f(uᵢ, uᵢ, uᵢ)`, `f(uᵢ, uᵢ, uᵢ₊₁)`, `f(uᵢ, uᵢ₊₁, uᵢ₊₁)`, `f(uᵢ₊₁, uᵢ₊₁, uᵢ₊₁)`.
    fn blossom(&self, i: usize, x: [f64; 3]) -> [f64; 2] {
        let t = knots(&self.faces);
        let span = i + 3;
        let mut d: Vec<[f64; 2]> = self.control[i..i + 4].to_vec();
        for (r, xr) in x.iter().enumerate() {
            let level = r + 1;
            // d[k] holds the point for control index span − 3 + k; update from the top
            for k in (level..4).rev() {
                let j = span - 3 + k;
                let a = (xr - t[j]) / (t[j + 4 - level] - t[j]);
                d[k] = [
                    (1.0 - a) * d[k - 1][0] + a * d[k][0],
                    (1.0 - a) * d[k - 1][1] + a * d[k][1],
                ];
            }
        }
        d[3]
    }

    /// Number of pieces (blocks).
    ///
    /// ```
    /// use design::spline::BSpline;
    /// let s = BSpline::new(vec![0.0, 1.0, 2.0], vec![[0.0, 0.0]; 5])?;
    /// assert_eq!(s.pieces_len(), 2);
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn pieces_len(&self) -> usize {
        self.faces.len() - 1
    }

    /// The point at parameter `u` in piece `i`.
    ///
    /// ```
    /// use design::spline::{greville, BSpline};
    /// let faces = vec![0.0, 300.0, 700.0, 1000.0];
    /// let control = greville(&faces).into_iter().map(|u| [u, 0.5 * u]).collect();
    /// let s = BSpline::new(faces, control)?;
    /// // control points on a line give that line, at the parameter's abscissa
    /// let p = s.point(1, 500.0);
    /// assert!((p[0] - 500.0).abs() < 1e-9 && (p[1] - 250.0).abs() < 1e-9);
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn point(&self, i: usize, u: f64) -> [f64; 2] {
        self.blossom(i, [u, u, u])
    }

    /// The knot images `S(uᵢ)`, one per face.
    ///
    /// ```
    /// use design::spline::{greville, BSpline};
    /// let faces = vec![0.0, 300.0, 700.0, 1000.0];
    /// let heights = [0.0, 80.0, -40.0, 120.0, 60.0, 10.0];
    /// let control = greville(&faces).into_iter().zip(heights).map(|(u, h)| [u, h]).collect();
    /// let s = BSpline::new(faces.clone(), control)?;
    /// let images = s.knot_images();
    /// assert_eq!(images.len(), 4);
    /// assert!(images.iter().zip(&faces).all(|(p, u)| (p[0] - u).abs() < 1e-9));
    /// assert_eq!(images[3], [1000.0, 10.0]); // clamped: the last control point
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn knot_images(&self) -> Vec<[f64; 2]> {
        let n = self.pieces_len();
        (0..=n)
            .map(|k| {
                let (i, u) = if k < n {
                    (k, self.faces[k])
                } else {
                    (n - 1, self.faces[n])
                };
                self.point(i, u)
            })
            .collect()
    }

    /// Every piece as the Bézier with the same points.
    ///
    /// ```
    /// use design::spline::{greville, BSpline};
    /// let faces = vec![0.0, 300.0, 700.0, 1000.0];
    /// let heights = [0.0, 80.0, -40.0, 120.0, 60.0, 10.0];
    /// let control = greville(&faces).into_iter().zip(heights).map(|(u, h)| [u, h]).collect();
    /// let s = BSpline::new(faces, control)?;
    /// let pieces = s.pieces();
    /// // each piece has the spline's points: here at a quarter of the second block
    /// let (u, t) = (300.0 + 0.25 * 400.0, 0.25);
    /// let (a, b) = (s.point(1, u), pieces[1].point(t));
    /// assert!((a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn pieces(&self) -> Vec<Bezier> {
        (0..self.pieces_len())
            .map(|i| {
                let (a, b) = (self.faces[i], self.faces[i + 1]);
                Bezier {
                    p: [
                        self.blossom(i, [a, a, a]),
                        self.blossom(i, [a, a, b]),
                        self.blossom(i, [a, b, b]),
                        self.blossom(i, [b, b, b]),
                    ],
                }
            })
            .collect()
    }

    /// Faces whose knot image is off the face by more than `tolerance` across (first
    /// coordinate): `(face, offset)`.
    ///
    /// ```
    /// use design::spline::{greville, BSpline};
    /// let faces = vec![0.0, 300.0, 700.0, 1000.0];
    /// let control = greville(&faces).into_iter().map(|u| [u, 0.0]).collect();
    /// let mut s = BSpline::new(faces, control)?;
    /// assert!(s.off_faces(1e-9).is_empty());
    /// s.control[2][0] += 30.0; // off its Greville abscissa: the inner knot images move
    /// let off = s.off_faces(1e-9);
    /// assert!(!off.is_empty() && off.iter().all(|&(face, _)| face == 1 || face == 2));
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn off_faces(&self, tolerance: f64) -> Vec<(usize, f64)> {
        self.knot_images()
            .iter()
            .zip(&self.faces)
            .enumerate()
            .filter_map(|(k, (p, u))| {
                let off = p[0] - u;
                (off.abs() > tolerance).then_some((k, off))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spline() -> BSpline {
        let faces = vec![0.0, 300.0, 700.0, 1000.0];
        let heights = [0.0, 80.0, -40.0, 120.0, 60.0, 10.0];
        let control = greville(&faces)
            .into_iter()
            .zip(heights)
            .map(|(a, h)| [a, h])
            .collect();
        BSpline::new(faces, control).unwrap()
    }

    #[test]
    fn greville_control_points_put_knot_images_on_the_faces() {
        let s = spline();
        assert!(s.off_faces(1e-12).is_empty());
        let g = greville(&s.faces);
        assert_eq!(g[0], 0.0);
        assert_eq!(g[1], 100.0);
        assert_eq!(*g.last().unwrap(), 1000.0);
    }

    #[test]
    fn pieces_meet_c2() {
        let s = spline();
        let p = s.pieces();
        assert_eq!(p.len(), 3);
        for w in p.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            // derivatives in the spline's parameter: Bézier t-derivatives over the width
            let (wa, wb) = (a.p[3][0] - a.p[0][0], b.p[3][0] - b.p[0][0]);
            for k in 0..2 {
                assert!((a.p[3][k] - b.p[0][k]).abs() < 1e-9);
                assert!((a.d1(1.0)[k] / wa - b.d1(0.0)[k] / wb).abs() < 1e-9);
                assert!((a.d2(1.0)[k] / (wa * wa) - b.d2(0.0)[k] / (wb * wb)).abs() < 1e-9);
            }
        }
        // the first and last pieces start and end at the end control points
        assert_eq!(p[0].p[0], s.control[0]);
        assert_eq!(p[2].p[3], s.control[5]);
    }

    #[test]
    fn moving_a_control_point_off_greville_moves_knot_images() {
        let mut s = spline();
        s.control[2][0] += 30.0;
        let off = s.off_faces(1e-9);
        assert!(off.iter().any(|(k, _)| *k == 1 || *k == 2), "{off:?}");
    }

    #[test]
    fn bad_splines_are_refused() {
        assert!(BSpline::new(vec![0.0], vec![]).is_err());
        assert!(BSpline::new(vec![0.0, 0.0], vec![[0.0, 0.0]; 4]).is_err());
        assert!(BSpline::new(vec![0.0, 1.0], vec![[0.0, 0.0]; 3]).is_err());
        assert!(BSpline::new(vec![0.0, 1.0], vec![[0.0, 0.0]; 4]).is_ok());
        assert!(BSpline::new(vec![0.0, 1.0], vec![[f64::NAN, 0.0]; 4]).is_err());
    }
}
