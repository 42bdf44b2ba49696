//! A cutting direction's frame: `u` along the cut (the wire travels along it), `w` across
//! the block (the wire spans it), `z` up; and the block's footprint in `(u, w)`.

use nalgebra::{Vector2, Vector3};

use crate::error::{PreCutError, Result};

/// The block: an axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Block {
    /// Minimum corner.
    pub min: [f64; 3],
    /// Maximum corner.
    pub max: [f64; 3],
}

impl Block {
    /// Edge lengths.
    pub fn size(&self) -> Vector3<f64> {
        Vector3::from(self.max) - Vector3::from(self.min)
    }

    /// Volume.
    pub fn volume(&self) -> f64 {
        let s = self.size();
        s.x * s.y * s.z
    }

    /// The longest edge: the length tolerances are relative to.
    pub fn scale(&self) -> f64 {
        self.size().max()
    }

    /// Whether `(x, y)` lies over the block (borders included).
    pub fn covers(&self, x: f64, y: f64) -> bool {
        x >= self.min[0] && x <= self.max[0] && y >= self.min[1] && y <= self.max[1]
    }
}

/// The frame of one cutting direction over a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutFrame {
    /// Unit cutting direction in the `xy` plane.
    pub along: Vector2<f64>,
    /// Unit direction across: `z × along`.
    pub across: Vector2<f64>,
    /// Range of `u = along · (x, y)` over the block.
    pub u: (f64, f64),
    /// Range of `w = across · (x, y)` over the block.
    pub w: (f64, f64),
    block: Block,
}

impl CutFrame {
    /// The frame of `direction` (only its `x`, `y` parts count; normalised) over `block`.
    ///
    /// # Errors
    /// [`PreCutError::InvalidParameter`] for a direction with no horizontal part.
    pub fn new(direction: [f64; 2], block: &Block) -> Result<Self> {
        // a vector whose norm overflows, like (1e308, 1e308), is scaled by its largest
        // component first
        let mut d = Vector2::from(direction);
        let scale = d.amax();
        if !d.norm().is_finite() && scale.is_finite() && scale > 0.0 {
            d /= scale;
        }
        let n = d.norm();
        if !(n.is_finite() && n > 1e-12) {
            return Err(PreCutError::InvalidParameter {
                name: "directions",
                reason: format!("{direction:?} has no horizontal part"),
            });
        }
        let along = d / n;
        let across = Vector2::new(-along.y, along.x);
        let corners = [
            Vector2::new(block.min[0], block.min[1]),
            Vector2::new(block.max[0], block.min[1]),
            Vector2::new(block.max[0], block.max[1]),
            Vector2::new(block.min[0], block.max[1]),
        ];
        let range = |a: &Vector2<f64>| {
            corners
                .iter()
                .map(|c| a.dot(c))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
                    (l.min(v), h.max(v))
                })
        };
        Ok(Self {
            along,
            across,
            u: range(&along),
            w: range(&across),
            block: *block,
        })
    }

    /// The point `(x, y)` of frame coordinates `(u, w)`.
    pub fn xy(&self, u: f64, w: f64) -> Vector2<f64> {
        self.along * u + self.across * w
    }

    /// The point `(x, y)` of frame coordinates `(u, w)` when it lies on the block's
    /// footprint, moved onto it when rounding put it outside by at most 10⁻⁹ of the block
    /// (a chord's end, an end face: on the block's edge, where the constraint must hold
    /// too); `None` farther out.
    pub fn xy_on_block(&self, u: f64, w: f64) -> Option<Vector2<f64>> {
        let p = self.xy(u, w);
        let slack = 1e-9 * self.block.scale();
        let q = Vector2::new(
            p.x.clamp(self.block.min[0], self.block.max[0]),
            p.y.clamp(self.block.min[1], self.block.max[1]),
        );
        ((q - p).amax() <= slack).then_some(q)
    }

    /// Points along the edges of the block's footprint, at most `step` apart (corners
    /// included), in frame coordinates `(u, w)` with their `(x, y)`.
    pub fn perimeter(&self, step: f64) -> Vec<(f64, f64, Vector2<f64>)> {
        let b = &self.block;
        let corners = [
            Vector2::new(b.min[0], b.min[1]),
            Vector2::new(b.max[0], b.min[1]),
            Vector2::new(b.max[0], b.max[1]),
            Vector2::new(b.min[0], b.max[1]),
        ];
        let mut out = Vec::new();
        for e in 0..4 {
            let (a, c) = (corners[e], corners[(e + 1) % 4]);
            let len = (c - a).norm();
            // bounded: the block's edge over the check grid's step (validated counts)
            let n = if step > 0.0 {
                ((len / step).ceil() as usize).clamp(1, 1 << 16)
            } else {
                1
            };
            for i in 0..n {
                let q = a + (c - a) * (i as f64 / n as f64);
                out.push((self.along.dot(&q), self.across.dot(&q), q));
            }
        }
        out
    }

    /// The `w` interval of the block's footprint on the line `u` (its chord), if any.
    pub fn chord(&self, u: f64) -> Option<(f64, f64)> {
        // The line {along·u + across·t}; clip t against the rectangle's slabs.
        let p = self.along * u;
        let (mut lo, mut hi) = (f64::NEG_INFINITY, f64::INFINITY);
        for k in 0..2 {
            let (a, b) = (self.block.min[k], self.block.max[k]);
            let d = self.across[k];
            if d.abs() < 1e-15 {
                let slack = 1e-12 * self.block.scale();
                if p[k] < a - slack || p[k] > b + slack {
                    return None;
                }
            } else {
                let (t0, t1) = ((a - p[k]) / d, (b - p[k]) / d);
                lo = lo.max(t0.min(t1));
                hi = hi.min(t0.max(t1));
            }
        }
        (hi >= lo).then_some((lo, hi))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_and_diagonal_frames() {
        let block = Block {
            min: [0.0, 0.0, 0.0],
            max: [2.0, 1.0, 1.0],
        };
        let f = CutFrame::new([1.0, 0.0], &block).unwrap();
        assert_eq!(f.u, (0.0, 2.0));
        assert_eq!(f.w, (0.0, 1.0));
        assert_eq!(f.chord(0.5), Some((0.0, 1.0)));
        let g = CutFrame::new([1.0, 1.0], &block).unwrap();
        let s = 0.5f64.sqrt();
        assert!((g.u.1 - 3.0 * s).abs() < 1e-12);
        // The chord through (1, 0.5) runs from (1.5, 0) to (0.5, 1): length √2.
        let u = g.along.dot(&Vector2::new(1.0, 0.5));
        let (a, b) = g.chord(u).unwrap();
        assert!((b - a - 2f64.sqrt()).abs() < 1e-12);
        assert!((g.xy(u, a) - Vector2::new(1.5, 0.0)).norm() < 1e-12);
        assert!((g.xy(u, b) - Vector2::new(0.5, 1.0)).norm() < 1e-12);
        assert!(g.chord(g.u.1 + 0.1).is_none());
        assert!(CutFrame::new([0.0, 0.0], &block).is_err());
    }
}
