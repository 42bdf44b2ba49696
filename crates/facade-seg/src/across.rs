//! A section seen across the facade: `u` (the plane coordinate across) against arc length,
//! sampled densely, with its |curvature| and its inflections in `u`. Shared by the
//! algorithms that place seams by `u` (inflection points, trace).

use geom::planar::{signed_curvature, PlanarCurve};

use crate::section::{Facade, PreparedSection};
use crate::SegError;

/// A section seen across the facade: `u` (plane coordinate across) against arc length,
/// sampled densely, and where its inflections lie in `u`.
pub(crate) struct Across {
    pub u: Vec<f64>,
    pub s: Vec<f64>,
    pub k: Vec<f64>,
    pub signed: Vec<f64>,
    pub inflections: Vec<f64>,
}

const ACROSS_SAMPLES: usize = 2048;

impl Across {
    pub fn new(facade: &Facade, j: usize) -> Result<Self, SegError> {
        let sec = &facade.sections[j];
        let n = ACROSS_SAMPLES;
        let s: Vec<f64> = (0..=n).map(|i| sec.length * i as f64 / n as f64).collect();
        let u: Vec<f64> = s.iter().map(|&v| sec.point(v).x).collect();
        if u.windows(2).any(|w| !(w[1] > w[0])) {
            return Err(SegError::Section {
                index: sec.index,
                message: "the inflection-points algorithm needs sections that run steadily across the facade (u increasing along the curve)".into(),
            });
        }
        let signed: Vec<f64> = s
            .iter()
            .map(|&v| signed_curvature(&sec.curve.jet(sec.t_at(v))))
            .collect();
        let k = signed.iter().map(|v| v.abs()).collect();
        let inflections = sec.inflections.iter().map(|&v| sec.point(v).x).collect();
        Ok(Self {
            u,
            s,
            k,
            signed,
            inflections,
        })
    }

    /// Arc length at `u` (clamped to the section): bisection on `u(s)` inside the bracketing
    /// samples, so the part ends exactly at the seam.
    pub fn s_at(&self, sec: &PreparedSection, u: f64) -> f64 {
        let i = self.u.partition_point(|&x| x < u);
        if i == 0 {
            return self.s[0];
        }
        if i >= self.u.len() {
            return self.s[self.s.len() - 1];
        }
        let (mut lo, mut hi) = (self.s[i - 1], self.s[i]);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if sec.point(mid).x < u {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// The seam in the overlap `[lo, hi]` after a part that starts at `start`, among the
    /// points that leave that part at most `k` inflections: the local maximum of |curvature|
    /// nearest to `prev` (the same seam on the previous section), or without `prev` the
    /// largest |curvature| — so the seam runs along one ridge or valley of the surface
    /// from section to section and never sits on an inflection; `lo` when there is none.
    pub fn seam(&self, lo: f64, hi: f64, start: f64, k: usize, prev: Option<f64>) -> f64 {
        let lo = lo.max(start);
        // the (k+1)-th inflection after `start` bounds the part
        let limit = self
            .inflections
            .iter()
            .filter(|&&u| u > start)
            .nth(k)
            .copied()
            .unwrap_or(f64::INFINITY);
        let hi = hi.min(limit);
        if !(hi > lo) {
            return lo;
        }
        let a = self.u.partition_point(|&x| x < lo);
        let b = self.u.partition_point(|&x| x < hi);
        if a >= b {
            return lo;
        }
        let largest = (a..b).fold(a, |best, i| if self.k[i] > self.k[best] { i } else { best });
        let Some(prev) = prev else {
            return self.u[largest];
        };
        // local maxima of |κ| inside the range (ends count when the range cuts a slope)
        let peak = |i: usize| {
            (i == a || self.k[i] >= self.k[i - 1]) && (i + 1 == b || self.k[i] >= self.k[i + 1])
        };
        (a..b)
            .filter(|&i| peak(i))
            .min_by(|&i, &j| {
                (self.u[i] - prev)
                    .abs()
                    .total_cmp(&(self.u[j] - prev).abs())
                    .then(self.k[j].total_cmp(&self.k[i]))
            })
            .map_or(self.u[largest], |i| self.u[i])
    }

    pub fn count(&self, lo: f64, hi: f64) -> usize {
        self.inflections
            .iter()
            .filter(|&&u| u > lo && u < hi)
            .count()
    }

    /// The sample of largest |curvature| strictly between `lo` and `hi`: its `u` and signed
    /// curvature.
    pub fn max_between(&self, lo: f64, hi: f64) -> Option<(f64, f64)> {
        let a = self.u.partition_point(|&x| x <= lo);
        let b = self.u.partition_point(|&x| x < hi);
        (a..b)
            .fold(None, |best: Option<usize>, i| match best {
                Some(j) if self.k[j] >= self.k[i] => best,
                _ => Some(i),
            })
            .map(|i| (self.u[i], self.signed[i]))
    }

    /// First and last `u` of the section.
    pub fn u_range(&self) -> (f64, f64) {
        (self.u[0], self.u[self.u.len() - 1])
    }

    /// Every section of the facade seen across it, `tick` called once per section.
    pub fn all(facade: &Facade, tick: &dyn Fn()) -> Result<Vec<Self>, SegError> {
        (0..facade.sections.len())
            .map(|j| {
                let a = Self::new(facade, j);
                tick();
                a
            })
            .collect()
    }
}
