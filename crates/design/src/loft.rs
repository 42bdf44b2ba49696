//! Lofting design curves along the cut ("Designing for Robotic Hot-Blade Cutting" §5.4):
//! curves given at stations along the cut are joined by the surface through them whose
//! loft parameter is spaced by the square root of the chord between neighbouring stations
//! (centripetal, the paper's "tight" loft), each curve parameter following a natural
//! cubic spline in that loft parameter. Two stations give a linear (ruled) loft.
//!
//! Every curve parameter of the stations is lofted alike, and so is the offset along the
//! cut; at one loft parameter the curve therefore lies in one cutting plane, and
//! [`Loft::at_offset`](crate::loft::Loft::at_offset) finds it for a plane.

use crate::error::{DesignError, Result};

/// Curves (as parameter vectors of one length) lofted through stations along the cut.
///
/// ```
/// use design::loft::Loft;
/// // three stations along the cut, each curve by two parameters: a height and a constant
/// let stations = [(0.0, vec![0.0, 1.0]), (100.0, vec![10.0, 1.0]), (300.0, vec![0.0, 1.0])];
/// // the distance between neighbouring stations' curves: here their offsets' difference
/// let loft = Loft::new(&stations, |i| stations[i].0 - stations[i - 1].0)?;
/// for (offset, curve) in &stations {
///     let at = loft.at_offset(*offset);
///     assert!(at.iter().zip(curve).all(|(a, b)| (a - b).abs() < 1e-9));
/// }
/// // between stations: a smooth curve through them, the constant kept
/// let mid = loft.at_offset(50.0);
/// assert!(mid[0] > 0.0 && mid[0] < 12.0 && (mid[1] - 1.0).abs() < 1e-12);
/// # Ok::<(), design::DesignError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Loft {
    /// Loft parameter of each station: 0, then growing by √chord.
    v: Vec<f64>,
    /// Per station: the offset along the cut, then the curve's parameters.
    y: Vec<Vec<f64>>,
    /// Second derivatives of the natural cubic spline, per station and coordinate.
    m: Vec<Vec<f64>>,
}

/// Samples per station interval at which the offset is checked to grow.
const MONOTONE_SAMPLES: usize = 64;

impl Loft {
    /// The loft through `stations`: per station its offset along the cut (strictly
    /// increasing) and its curve parameters (all of one length); `chord(i)` is the
    /// distance between the curves of stations `i − 1` and `i`, of which the loft's
    /// parameter steps are the square roots.
    ///
    /// ```
    /// use design::loft::Loft;
    /// // two stations: a linear (ruled) loft
    /// let stations = [(0.0, vec![1.0, 2.0]), (100.0, vec![3.0, 6.0])];
    /// let loft = Loft::new(&stations, |_| 4.0)?;
    /// let mid = loft.at_offset(50.0);
    /// assert!((mid[0] - 2.0).abs() < 1e-9 && (mid[1] - 4.0).abs() < 1e-9);
    /// // offsets that do not increase are refused
    /// assert!(Loft::new(&[(0.0, vec![1.0]), (0.0, vec![2.0])], |_| 1.0).is_err());
    /// # Ok::<(), design::DesignError>(())
    /// ```
    ///
    /// # Errors
    /// [`DesignError::Invalid`] for fewer than two stations, offsets not increasing,
    /// parameter vectors of different lengths or not finite, or a loft whose offset does
    /// not grow along the cut between two stations (stations too unevenly spaced).
    pub fn new(stations: &[(f64, Vec<f64>)], chord: impl Fn(usize) -> f64) -> Result<Self> {
        if stations.len() < 2 {
            return Err(DesignError::Invalid(
                "a loft needs at least two stations".into(),
            ));
        }
        let dim = stations[0].1.len();
        if stations.iter().any(|(_, p)| p.len() != dim) {
            return Err(DesignError::Invalid(
                "every station's curve must have the same structure".into(),
            ));
        }
        if stations.windows(2).any(|w| !(w[1].0 > w[0].0)) {
            return Err(DesignError::Invalid(
                "the stations' offsets must increase along the cut".into(),
            ));
        }
        let y: Vec<Vec<f64>> = stations
            .iter()
            .map(|(s, p)| std::iter::once(*s).chain(p.iter().copied()).collect())
            .collect();
        if y.iter().flatten().any(|v| !v.is_finite()) {
            return Err(DesignError::Invalid("a station is not finite".into()));
        }
        let mut v = vec![0.0];
        for i in 1..stations.len() {
            let step = chord(i).max(0.0).sqrt();
            if !(step > 0.0) || !step.is_finite() {
                return Err(DesignError::Invalid(format!(
                    "stations {} and {} coincide",
                    i - 1,
                    i
                )));
            }
            v.push(v[i - 1] + step);
        }
        let m = natural_second_derivatives(&v, &y);
        let loft = Self { v, y, m };
        loft.check_monotone()?;
        Ok(loft)
    }

    fn eval(&self, v: f64) -> Vec<f64> {
        let n = self.v.len();
        let i = (1..n - 1).take_while(|&i| self.v[i] <= v).count();
        let (a, b) = (self.v[i], self.v[i + 1]);
        let h = b - a;
        let t = ((v - a) / h).clamp(0.0, 1.0);
        let (p, q) = (1.0 - t, t);
        (0..self.y[0].len())
            .map(|k| {
                let lin = p * self.y[i][k] + q * self.y[i + 1][k];
                let cubic =
                    ((p * p * p - p) * self.m[i][k] + (q * q * q - q) * self.m[i + 1][k]) * h * h
                        / 6.0;
                lin + cubic
            })
            .collect()
    }

    fn check_monotone(&self) -> Result<()> {
        for i in 0..self.v.len() - 1 {
            let mut last = self.y[i][0];
            for j in 1..=MONOTONE_SAMPLES {
                let w = j as f64 / MONOTONE_SAMPLES as f64;
                let s = self.eval(self.v[i] + w * (self.v[i + 1] - self.v[i]))[0];
                if !(s > last) {
                    return Err(DesignError::Invalid(format!(
                        "the loft folds back along the cut between stations {} and {}: space the stations more evenly",
                        i,
                        i + 1
                    )));
                }
                last = s;
            }
        }
        Ok(())
    }

    /// The curve parameters on the cutting plane at `offset` (clamped to the stations'
    /// range), found by bisection of the loft's monotone offset.
    ///
    /// ```
    /// use design::loft::Loft;
    /// let stations = [(0.0, vec![1.0]), (100.0, vec![3.0])];
    /// let loft = Loft::new(&stations, |_| 4.0)?;
    /// assert!((loft.at_offset(25.0)[0] - 1.5).abs() < 1e-9);
    /// assert!((loft.at_offset(500.0)[0] - 3.0).abs() < 1e-12); // clamped to the last station
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn at_offset(&self, offset: f64) -> Vec<f64> {
        let n = self.v.len();
        let s = offset.clamp(self.y[0][0], self.y[n - 1][0]);
        let i = (1..n - 1).take_while(|&i| self.y[i][0] <= s).count();
        let (mut lo, mut hi) = (self.v[i], self.v[i + 1]);
        // 60 halvings reach the rounding of the loft parameter
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if self.eval(mid)[0] < s {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let mut out = self.eval(0.5 * (lo + hi));
        out.remove(0);
        out
    }
}

/// The natural cubic spline's second derivatives at the knots `v` for the values `y`
/// (per knot, one row of coordinates): the tridiagonal system solved by the Thomas
/// algorithm (diagonally dominant, so stable without pivoting).
fn natural_second_derivatives(v: &[f64], y: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = v.len();
    let dim = y[0].len();
    let mut m = vec![vec![0.0; dim]; n];
    if n < 3 {
        return m;
    }
    let h: Vec<f64> = v.windows(2).map(|w| w[1] - w[0]).collect();
    // unknowns m[1..n-1]; rows i = 1..n-2
    let mut c = vec![0.0; n];
    let mut d = vec![vec![0.0; dim]; n];
    for i in 1..n - 1 {
        let (a, b, cc) = (h[i - 1], 2.0 * (h[i - 1] + h[i]), h[i]);
        let rhs: Vec<f64> = (0..dim)
            .map(|k| 6.0 * ((y[i + 1][k] - y[i][k]) / h[i] - (y[i][k] - y[i - 1][k]) / h[i - 1]))
            .collect();
        let denom = b - a * c[i - 1];
        c[i] = cc / denom;
        for k in 0..dim {
            d[i][k] = (rhs[k] - a * d[i - 1][k]) / denom;
        }
    }
    for i in (1..n - 1).rev() {
        for k in 0..dim {
            m[i][k] = d[i][k] - c[i] * m[i + 1][k];
        }
    }
    m
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chord_of(st: &[(f64, Vec<f64>)]) -> impl Fn(usize) -> f64 + '_ {
        move |i| {
            let (a, b) = (&st[i - 1], &st[i]);
            let d2: f64 = std::iter::once(b.0 - a.0)
                .chain(a.1.iter().zip(&b.1).map(|(x, y)| y - x))
                .map(|d| d * d)
                .sum();
            d2.sqrt()
        }
    }

    #[test]
    fn two_stations_loft_linearly() {
        let st = vec![(0.0, vec![1.0, 2.0]), (10.0, vec![3.0, -2.0])];
        let l = Loft::new(&st, chord_of(&st)).unwrap();
        let p = l.at_offset(2.5);
        assert!((p[0] - 1.5).abs() < 1e-12 && (p[1] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_loft_passes_through_its_stations() {
        let st = vec![
            (0.0, vec![0.0, 5.0]),
            (3.0, vec![2.0, 1.0]),
            (10.0, vec![-1.0, 4.0]),
            (12.0, vec![0.5, 0.0]),
        ];
        let l = Loft::new(&st, chord_of(&st)).unwrap();
        for (s, p) in &st {
            let q = l.at_offset(*s);
            for (a, b) in p.iter().zip(&q) {
                assert!((a - b).abs() < 1e-9, "{s}: {p:?} vs {q:?}");
            }
        }
    }

    #[test]
    fn a_linear_design_lofts_linearly() {
        // parameters linear in the offset stay linear whatever the spacing of the stations
        let st: Vec<(f64, Vec<f64>)> = [0.0, 1.0, 4.0, 5.0]
            .iter()
            .map(|&s| (s, vec![2.0 * s + 1.0]))
            .collect();
        let l = Loft::new(&st, chord_of(&st)).unwrap();
        for j in 0..=50 {
            let s = 5.0 * j as f64 / 50.0;
            assert!((l.at_offset(s)[0] - (2.0 * s + 1.0)).abs() < 1e-9);
        }
    }

    #[test]
    fn bad_stations_are_refused() {
        let same = vec![(0.0, vec![1.0]), (0.0, vec![1.0])];
        assert!(Loft::new(&same, |_| 1.0).is_err());
        let ragged = vec![(0.0, vec![1.0]), (1.0, vec![1.0, 2.0])];
        assert!(Loft::new(&ragged, |_| 1.0).is_err());
        let one = vec![(0.0, vec![1.0])];
        assert!(Loft::new(&one, |_| 1.0).is_err());
    }
}
