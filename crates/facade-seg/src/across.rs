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
    /// Interior samples that are local maxima of |curvature| (`k[i]` ≥ both neighbours),
    /// increasing.
    peaks: Vec<usize>,
    /// `argmax[l][i]`: the first sample of largest |curvature| in `i..i + 2^l` (a sparse
    /// table, so the largest on any range is found in constant time).
    argmax: Vec<Vec<u32>>,
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
        let k: Vec<f64> = signed.iter().map(|v| v.abs()).collect();
        let mut inflections: Vec<f64> = sec.inflections.iter().map(|&v| sec.point(v).x).collect();
        inflections.sort_by(f64::total_cmp);
        let peaks = (1..k.len().saturating_sub(1))
            .filter(|&i| k[i] >= k[i - 1] && k[i] >= k[i + 1])
            .collect();
        let argmax = sparse_argmax(&k);
        Ok(Self {
            u,
            s,
            k,
            signed,
            inflections,
            peaks,
            argmax,
        })
    }

    /// The first sample of largest |curvature| in `a..b` (`a < b`).
    fn largest(&self, a: usize, b: usize) -> usize {
        let level = (usize::BITS - 1 - (b - a).leading_zeros()) as usize;
        let x = self.argmax[level][a] as usize;
        let y = self.argmax[level][b - (1 << level)] as usize;
        if self.k[y] > self.k[x] {
            y
        } else {
            x
        }
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
        let first = self.inflections.partition_point(|&u| u <= start);
        let limit = self
            .inflections
            .get(first + k)
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
        let largest = self.largest(a, b);
        let Some(prev) = prev else {
            return self.u[largest];
        };
        // local maxima of |κ| inside the range (ends count when the range cuts a slope):
        // the interior peaks nearest to `prev` on either side, and the two ends
        let end_a = a + 1 == b || self.k[a] >= self.k[a + 1];
        let end_b = b - 1 == a || self.k[b - 1] >= self.k[b - 2];
        let inner_lo = self.peaks.partition_point(|&i| i <= a);
        let inner_hi = self.peaks.partition_point(|&i| i < b - 1);
        let inner = &self.peaks[inner_lo..inner_hi.max(inner_lo)];
        let at = inner.partition_point(|&i| self.u[i] < prev);
        let candidates = [
            end_a.then_some(a),
            at.checked_sub(1).map(|m| inner[m]),
            inner.get(at).copied(),
            end_b.then_some(b - 1),
        ];
        candidates
            .into_iter()
            .flatten()
            .min_by(|&i, &j| {
                (self.u[i] - prev)
                    .abs()
                    .total_cmp(&(self.u[j] - prev).abs())
                    .then(self.k[j].total_cmp(&self.k[i]))
                    .then(i.cmp(&j))
            })
            .map_or(self.u[largest], |i| self.u[i])
    }

    pub fn count(&self, lo: f64, hi: f64) -> usize {
        let a = self.inflections.partition_point(|&u| u <= lo);
        let b = self.inflections.partition_point(|&u| u < hi);
        b.saturating_sub(a)
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

/// Sparse table of range argmax over `k`: level `l` holds, for each start `i`, the first
/// index of the largest value in `i..i + 2^l`.
fn sparse_argmax(k: &[f64]) -> Vec<Vec<u32>> {
    let n = k.len();
    let mut table: Vec<Vec<u32>> = vec![(0..n as u32).collect()];
    let mut width = 1;
    while 2 * width <= n {
        let prev = &table[table.len() - 1];
        let next = (0..=n - 2 * width)
            .map(|i| {
                let (x, y) = (prev[i], prev[i + width]);
                if k[y as usize] > k[x as usize] {
                    y
                } else {
                    x
                }
            })
            .collect();
        table.push(next);
        width *= 2;
    }
    table
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sparse table agrees with a plain scan (first index of the largest) on every range.
    #[test]
    fn range_argmax_matches_a_scan() {
        let k: Vec<f64> = (0..37).map(|i| ((i * 7919) % 13) as f64).collect();
        let table = sparse_argmax(&k);
        for a in 0..k.len() {
            for b in a + 1..=k.len() {
                let level = (usize::BITS - 1 - (b - a).leading_zeros()) as usize;
                let x = table[level][a] as usize;
                let y = table[level][b - (1 << level)] as usize;
                let got = if k[y] > k[x] { y } else { x };
                let want = (a..b).fold(a, |best, i| if k[i] > k[best] { i } else { best });
                assert_eq!(got, want, "range {a}..{b}");
            }
        }
    }
}
