//! When a curvature sign change is an inflection: the noise floor.
//!
//! A sign change of the curvature counts as an inflection only if the curve really turns
//! there: each of the two stretches of one curvature sign it separates (its *lobes*)
//! departs from its chord by more than a **noise floor**, and bends by more than the
//! curvature a bulge of that floor over the whole curve would need. Below the floor a lobe
//! is not in the data: a straight or planar stretch computed in floating point, or smoothed
//! within the precision of a mesh, has curvature of random sign whose lobes depart from
//! their chords by nothing one could cut, measure or see.
//!
//! The floor of a lobe is the largest of
//! - the rounding of f64 at the curve's scale, [`ROUNDING`](crate::significance::ROUNDING) × (largest coordinate +
//!   length), for every curve;
//! - a floor the caller states for the whole curve (`noise`: e.g. the precision an
//!   elastica fit was asked for);
//! - for a curve fitted to points, [`DATA_SHARE`](crate::significance::DATA_SHARE) × the largest allowance of the points
//!   in and around the lobe: how far each point was allowed to lie from the fitted curve
//!   (the job's smoothing tolerance, a mesh facet's distance from the surface, a
//!   polyline's chordal sagitta — [`SplineFit::precision`](crate::fit::SplineFit::precision)). A smoothing
//!   spline is the smoothest curve within its allowances, so it only wiggles by less than
//!   them where the data force nothing.
//!
//! The curvature floor of a lobe is `8 · floor / L²` (`L` the curve's length): the
//! curvature of an arc as long as the whole curve whose bulge is the floor.
//!
//! The rule ([`drop_noise_lobes`](crate::significance::drop_noise_lobes)): while some lobe is below its floor, take the one
//! furthest below (smallest departure over floor) and remove the inflections that bound
//! it — both for an interior lobe, which merges it with its two neighbours (whose signs
//! agree), the inner one for a lobe at an end of the curve. Each removal takes one or two
//! inflections away, so the rule ends after at most as many steps as there were
//! inflections. Every task that counts inflections (`Analyze`, the three segmentations,
//! the production checks, `FitCurves`' descriptions, `Design`'s verdicts) counts them
//! through this rule.

use nalgebra::Vector2;

/// f64 rounding at a curve's scale: a lobe departing from its chord by less than this
/// share of (largest coordinate + length) is rounding noise (section points, spline
/// solves and curve evaluations carry errors of 10⁻¹⁵–10⁻¹² of the coordinates).
pub const ROUNDING: f64 = 1e-10;

/// The share of the data's allowance a lobe of a fitted curve must depart from its chord
/// by.
pub const DATA_SHARE: f64 = 0.1;

/// Points sampled inside a lobe to measure it, at least.
const LOBE_SAMPLES: usize = 16;

/// What [`drop_noise_lobes`] needs of a curve: points and curvature by parameter.
pub trait LobeCurve {
    /// The point at parameter `t`.
    fn point(&self, t: f64) -> Vector2<f64>;
    /// The signed curvature at parameter `t`.
    fn curvature(&self, t: f64) -> f64;
}

/// A lobe's measures: how far it departs from its chord, and its largest |κ|.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LobeShape {
    /// Largest distance of the lobe from the chord between its ends.
    pub departure: f64,
    /// Largest |curvature| inside it.
    pub max_abs_curvature: f64,
}

/// Measures the lobe `[t0, t1]` of `curve` at `LOBE_SAMPLES` points spread evenly in it
/// plus the given `samples` that fall inside.
pub fn lobe_shape(curve: &dyn LobeCurve, t0: f64, t1: f64, samples: &[f64]) -> LobeShape {
    let (a, b) = (curve.point(t0), curve.point(t1));
    let chord = b - a;
    let len = chord.norm();
    let dist = |p: Vector2<f64>| {
        if len > 0.0 {
            ((p - a).perp(&chord) / len).abs()
        } else {
            (p - a).norm()
        }
    };
    let mut shape = LobeShape {
        departure: 0.0,
        max_abs_curvature: curve.curvature(t0).abs().max(curve.curvature(t1).abs()),
    };
    let lo = samples.partition_point(|&t| t <= t0);
    let hi = samples.partition_point(|&t| t < t1);
    let even = (1..LOBE_SAMPLES).map(|i| t0 + (t1 - t0) * i as f64 / LOBE_SAMPLES as f64);
    for t in even.chain(samples[lo..hi.max(lo)].iter().copied()) {
        shape.departure = shape.departure.max(dist(curve.point(t)));
        shape.max_abs_curvature = shape.max_abs_curvature.max(curve.curvature(t).abs());
    }
    shape
}

/// The floor of a lobe; see the module docs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Floor {
    /// Distance floor.
    pub distance: f64,
    /// Curvature floor.
    pub curvature: f64,
}

impl Floor {
    /// The floor of a distance `distance` on a curve of length `length`: curvature
    /// `8 · distance / length²`.
    pub fn of(distance: f64, length: f64) -> Self {
        let curvature = if length > 0.0 {
            8.0 * distance / (length * length)
        } else {
            0.0
        };
        Self {
            distance,
            curvature,
        }
    }

    /// How far above its floor a lobe is (< 1: below, noise).
    pub fn ratio(&self, shape: &LobeShape) -> f64 {
        let d = if self.distance > 0.0 {
            shape.departure / self.distance
        } else {
            f64::INFINITY
        };
        let k = if self.curvature > 0.0 {
            shape.max_abs_curvature / self.curvature
        } else {
            f64::INFINITY
        };
        d.min(k)
    }
}

/// The rounding floor of a curve whose largest coordinate is `reach` and length `length`.
pub fn rounding_floor(reach: f64, length: f64) -> f64 {
    ROUNDING * (reach.abs() + length.abs())
}

/// Applies the rule of the module docs to the lobes between consecutive `bounds` (the
/// curve's two ends and its inflections, increasing): `floor(t0, t1)` gives a lobe's
/// floor, `samples` the parameters at which lobes are measured besides their own even
/// spread. Returns how many inflections it dropped.
pub fn drop_noise_lobes(
    curve: &dyn LobeCurve,
    bounds: &mut Vec<f64>,
    floor: &dyn Fn(f64, f64) -> Floor,
    samples: &[f64],
) -> usize {
    use std::cmp::Reverse;
    use std::collections::BinaryHeap;

    /// A lobe's ratio in the queue: least ratio first, then the leftmost lobe.
    #[derive(PartialEq)]
    struct Key(f64, usize, u32);
    impl Eq for Key {}
    impl PartialOrd for Key {
        fn partial_cmp(&self, o: &Self) -> Option<std::cmp::Ordering> {
            Some(self.cmp(o))
        }
    }
    impl Ord for Key {
        fn cmp(&self, o: &Self) -> std::cmp::Ordering {
            self.0.total_cmp(&o.0).then(self.1.cmp(&o.1))
        }
    }

    let n = bounds.len();
    if n < 3 {
        return 0;
    }
    let b = bounds.clone();
    let ratio = |t0: f64, t1: f64| floor(t0, t1).ratio(&lobe_shape(curve, t0, t1, samples));
    // the bounds still there, linked both ways; a lobe is named by its left bound, and
    // merging lobes changes the version of the lobe that takes their place (a queued
    // entry of an older version is stale). Each merge removes a bound, so there are at
    // most n − 2 of them, each O(log n): the whole is O(n log n) lobe measures.
    let (mut next, mut prev): (Vec<usize>, Vec<usize>) = (
        (1..=n).collect(),
        (0..n).map(|k| k.wrapping_sub(1)).collect(),
    );
    let mut alive = vec![true; n];
    let mut version = vec![0u32; n];
    let mut heap = BinaryHeap::with_capacity(n);
    for k in 0..n - 1 {
        heap.push(Reverse(Key(ratio(b[k], b[k + 1]), k, 0)));
    }
    let (first, last) = (0, n - 1);
    let mut lobes = n - 1;
    let mut dropped = 0;
    while lobes > 1 {
        let Some(Reverse(Key(r, left, v))) = heap.pop() else {
            break;
        };
        if !alive[left] || v != version[left] || left == last {
            continue;
        }
        if r >= 1.0 {
            break;
        }
        let (right, before) = (next[left], prev[left]);
        let mut unlink = |k: usize, alive: &mut Vec<bool>| {
            alive[k] = false;
            let (p, q) = (prev[k], next[k]);
            if p < n {
                next[p] = q;
            }
            if q < n {
                prev[q] = p;
            }
        };
        let renewed = if left == first {
            // the first lobe joins the second: its inner inflection goes
            unlink(right, &mut alive);
            dropped += 1;
            lobes -= 1;
            left
        } else if right == last {
            // the last lobe joins the one before: its inner inflection goes
            unlink(left, &mut alive);
            dropped += 1;
            lobes -= 1;
            before
        } else {
            // an interior lobe joins both neighbours: both its inflections go
            unlink(left, &mut alive);
            unlink(right, &mut alive);
            dropped += 2;
            lobes -= 2;
            before
        };
        version[renewed] += 1;
        let q = next[renewed];
        heap.push(Reverse(Key(
            ratio(b[renewed], b[q]),
            renewed,
            version[renewed],
        )));
    }
    *bounds = (0..n).filter(|&k| alive[k]).map(|k| b[k]).collect();
    dropped
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `y = a · sin(t)` for `t ∈ [0, len]`, with curvature of the graph.
    struct Sine(f64);
    impl LobeCurve for Sine {
        fn point(&self, t: f64) -> Vector2<f64> {
            Vector2::new(t, self.0 * t.sin())
        }
        fn curvature(&self, t: f64) -> f64 {
            let (d1, d2) = (self.0 * t.cos(), -self.0 * t.sin());
            d2 / (1.0 + d1 * d1).powf(1.5)
        }
    }

    fn bounds(len: f64) -> Vec<f64> {
        let mut b = vec![0.0];
        let mut k = 1.0;
        while k * std::f64::consts::PI < len {
            b.push(k * std::f64::consts::PI);
            k += 1.0;
        }
        b.push(len);
        b
    }

    #[test]
    fn a_sine_lobe_departs_by_its_amplitude() {
        let s = lobe_shape(&Sine(0.3), 0.0, std::f64::consts::PI, &[]);
        assert!((s.departure - 0.3).abs() < 1e-12, "{s:?}");
        assert!((s.max_abs_curvature - 0.3).abs() < 1e-12);
    }

    #[test]
    fn lobes_above_the_floor_stay_below_it_go() {
        let len = 20.0;
        // floor 0.01: an amplitude of 0.3 keeps all six inflections
        let mut b = bounds(len);
        let n = b.len();
        let floor = |_: f64, _: f64| Floor::of(0.01, len);
        assert_eq!(drop_noise_lobes(&Sine(0.3), &mut b, &floor, &[]), 0);
        assert_eq!(b.len(), n);
        // an amplitude of 1e-3 is noise: every inflection goes, one lobe is left
        let mut b = bounds(len);
        let dropped = drop_noise_lobes(&Sine(1e-3), &mut b, &floor, &[]);
        assert_eq!(dropped, n - 2);
        assert_eq!(b, vec![0.0, len]);
    }

    #[test]
    fn a_flat_interior_lobe_takes_both_its_inflections() {
        // lobes of amplitude 1, 1e-4, 1: the middle one is below a floor of 1e-2
        struct Three;
        impl LobeCurve for Three {
            fn point(&self, t: f64) -> Vector2<f64> {
                Vector2::new(t, self.amp(t) * t.sin())
            }
            fn curvature(&self, t: f64) -> f64 {
                -self.amp(t) * t.sin()
            }
        }
        impl Three {
            fn amp(&self, t: f64) -> f64 {
                if (std::f64::consts::PI..2.0 * std::f64::consts::PI).contains(&t) {
                    1e-4
                } else {
                    1.0
                }
            }
        }
        let pi = std::f64::consts::PI;
        let mut b = vec![0.0, pi, 2.0 * pi, 3.0 * pi];
        let floor = |_: f64, _: f64| Floor::of(1e-2, 3.0 * pi);
        assert_eq!(drop_noise_lobes(&Three, &mut b, &floor, &[]), 2);
        assert_eq!(b, vec![0.0, 3.0 * pi]);
    }
}
