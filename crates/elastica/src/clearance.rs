//! The blade outside its cut against the block (issue 37): on a cutting plane, the blade
//! runs past the piece it cuts on both sides to its holders. Wherever that extension
//! enters material the block keeps it melts it (a gouge); a holder inside the block
//! collides with it.
//!
//! The kept material of a block's section is what lies inside the block's rectangle and
//! on the kept side of the piece: the polygon of the piece closed through the block's two
//! corners on that side. The blade is sampled outside the piece; a sample inside that
//! region gouges, as deep as its distance to the region's boundary.

use crate::blade::Blade;
use crate::elliptic::EllipticError;

/// Samples along the whole blade (the extension's samples are those outside the piece).
pub const SAMPLES: usize = 1000;

/// The blade outside its piece against the block on one cutting plane.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Clearance {
    /// How deep the blade outside the piece runs into kept material (0: not at all).
    pub gouge_depth: f64,
    /// How much of the blade outside the piece lies in kept material.
    pub gouge_length: f64,
    /// The smaller distance of the blade's two held ends from the block's rectangle;
    /// negative when an end lies inside it.
    pub holder_clearance: f64,
    /// Both held ends at least [`HOLDER_MARGIN`] of the blade's length from the block: a
    /// holder closer than that touches it (a holder has a size; an end exactly on a face
    /// is a collision, whatever the sign of its rounding).
    pub holders_clear: bool,
}

/// How far, as a share of the blade's length, a held end must stay from the block.
pub const HOLDER_MARGIN: f64 = 0.01;

impl Clearance {
    /// The worst of `items` that is not clean: the deepest gouge, then the smallest holder
    /// clearance; the first of equals. `None` when every one is clean.
    ///
    /// ```
    /// use elastica::clearance::Clearance;
    /// let clean = Clearance { holders_clear: true, holder_clearance: 50.0, ..Clearance::default() };
    /// let touching = Clearance { holders_clear: false, holder_clearance: 1.0, ..clean };
    /// let gouging = Clearance { gouge_depth: 2.0, gouge_length: 30.0, ..clean };
    /// let items = [("a", clean), ("b", touching), ("c", gouging)];
    /// assert_eq!(Clearance::worst(items).map(|w| w.0), Some("c"));
    /// assert_eq!(Clearance::worst([("a", clean)]), None);
    /// ```
    pub fn worst<T>(items: impl IntoIterator<Item = (T, Clearance)>) -> Option<(T, Clearance)> {
        let mut worst: Option<(T, Clearance)> = None;
        for (item, c) in items.into_iter().filter(|(_, c)| !c.is_clean()) {
            let worse = worst.as_ref().is_none_or(|(_, w)| {
                c.gouge_depth > w.gouge_depth
                    || (c.gouge_depth == w.gouge_depth && c.holder_clearance < w.holder_clearance)
            });
            if worse {
                worst = Some((item, c));
            }
        }
        worst
    }

    /// No gouge and both held ends clear of the block.
    pub fn is_clean(&self) -> bool {
        self.gouge_depth == 0.0 && self.holders_clear
    }

    /// How bad a placement is: the gouge's depth plus how far a held end falls short of
    /// `margin` (0: clean).
    pub(crate) fn badness(&self, margin: f64) -> f64 {
        self.gouge_depth + (margin - self.holder_clearance).max(0.0)
    }
}

/// A block's section on the cutting plane: its rectangle `[[u_min, v_min], [u_max, v_max]]`
/// and the side of the piece it keeps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Section {
    /// The rectangle of material the piece shapes (where the kept region is sought).
    pub rect: [[f64; 2]; 2],
    /// The whole block's rectangle, which the held ends must keep out of (wider than
    /// `rect` where the design covers only part of the block).
    pub block: [[f64; 2]; 2],
    /// `true`: the block keeps what lies below the piece (towards `v_min`), as when a cut
    /// shapes a block's top; `false`: above it.
    pub keeps_below: bool,
}

/// Distance from `p` to the segment `a`–`b`.
fn to_segment(p: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
    let len2 = dx * dx + dy * dy;
    let t = if len2 > 0.0 {
        (((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p[0] - a[0] - t * dx).hypot(p[1] - a[1] - t * dy)
}

/// Whether `p` lies inside the closed polygon `poly` (even–odd rule).
fn inside(p: [f64; 2], poly: &[[f64; 2]]) -> bool {
    let mut odd = false;
    let n = poly.len();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        if (a[1] > p[1]) != (b[1] > p[1]) {
            let x = a[0] + (p[1] - a[1]) / (b[1] - a[1]) * (b[0] - a[0]);
            if p[0] < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// Signed distance from `p` to the rectangle `r = [min, max]`: positive outside, negative
/// inside.
pub fn to_rect(p: [f64; 2], r: [[f64; 2]; 2]) -> f64 {
    let dx = (r[0][0] - p[0]).max(p[0] - r[1][0]);
    let dy = (r[0][1] - p[1]).max(p[1] - r[1][1]);
    if dx <= 0.0 && dy <= 0.0 {
        dx.max(dy)
    } else {
        dx.max(0.0).hypot(dy.max(0.0))
    }
}

/// The blade's extension beyond its piece against `section` ([`Clearance`]). The piece is
/// the part of `blade.segment` from `blade.lead_in` to `lead_in + (length − lead_in −
/// lead_out)`; points within `tolerance` of the kept region's boundary do not count
/// (the piece itself lies on it).
///
/// ```
/// use elastica::blade::{extend_to_blade, BladeParams};
/// use elastica::clearance::{clearance, Section};
/// use elastica::segment::Segment;
/// // a flat top at v = 1 across a block [0, 2] × [0, 1], cut by a straight blade 4 long:
/// // its extensions run outside the block, its ends 1 away from it
/// let piece = Segment::Line { x0: 0.0, y0: 1.0, phi: 0.0, length: 2.0 };
/// let blade = extend_to_blade(&piece, &BladeParams::new(4.0)).unwrap();
/// let r = [[0.0, 0.0], [2.0, 1.0]];
/// let section = Section { rect: r, block: r, keeps_below: true };
/// let c = clearance(&blade, &section, 1e-9).unwrap();
/// assert_eq!(c.gouge_depth, 0.0);
/// assert!((c.holder_clearance - 1.0).abs() < 1e-12);
/// ```
///
/// # Errors
/// The segment cannot be evaluated.
pub fn clearance(
    blade: &Blade,
    section: &Section,
    tolerance: f64,
) -> Result<Clearance, EllipticError> {
    let eval = blade.segment.evaluator()?;
    let length = blade.segment.length();
    let holder_clearance = blade
        .ends
        .iter()
        .map(|e| to_rect(e.position, section.block))
        .fold(f64::INFINITY, f64::min);
    if !(length > 0.0) || !holder_clearance.is_finite() {
        return Err(EllipticError::Parameter(length));
    }
    let holders_clear = holder_clearance > HOLDER_MARGIN * length;
    let (a, b) = (blade.lead_in / length, 1.0 - blade.lead_out / length);
    // the kept region: the piece, then the block's corners on the kept side
    let [lo, hi] = section.rect;
    let v = if section.keeps_below { lo[1] } else { hi[1] };
    let mut region: Vec<[f64; 2]> = (0..=SAMPLES / 4)
        .map(|i| eval.eval(a + (b - a) * i as f64 / (SAMPLES / 4) as f64).p)
        .collect();
    let (first, last) = (region[0], region[region.len() - 1]);
    // the corner below (or above) the piece's end first, then its start's
    let (end_u, start_u) = if last[0] >= first[0] {
        (hi[0], lo[0])
    } else {
        (lo[0], hi[0])
    };
    region.push([end_u, v]);
    region.push([start_u, v]);
    let depth_at = |p: [f64; 2]| -> f64 {
        if to_rect(p, section.rect) >= 0.0 || !inside(p, &region) {
            return 0.0;
        }
        let n = region.len();
        let edge = (0..n)
            .map(|i| to_segment(p, region[i], region[(i + 1) % n]))
            .fold(f64::INFINITY, f64::min);
        let depth = edge.min(-to_rect(p, section.rect));
        if depth > tolerance {
            depth
        } else {
            0.0
        }
    };
    let step = 1.0 / SAMPLES as f64;
    let (mut gouge_depth, mut gouge_length) = (0.0f64, 0.0);
    for i in 0..SAMPLES {
        // the midpoint of each step, outside the piece
        let t = (i as f64 + 0.5) * step;
        if t > a && t < b {
            continue;
        }
        let p = eval.eval(t).p;
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err(EllipticError::Parameter(t));
        }
        let d = depth_at(p);
        if d > 0.0 {
            gouge_depth = gouge_depth.max(d);
            gouge_length += step * length;
        }
    }
    Ok(Clearance {
        gouge_depth,
        gouge_length,
        holder_clearance,
        holders_clear,
    })
}

pub use crate::place::{
    place, place_all, place_all_by, snapping_moves, FINE_SHARES, LEAD_IN_SHARES,
};

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_and_rectangle_distances() {
        let square = [[0.0, 0.0], [2.0, 0.0], [2.0, 2.0], [0.0, 2.0]];
        assert!(inside([1.0, 1.0], &square) && !inside([3.0, 1.0], &square));
        assert_eq!(to_rect([1.0, 0.5], [[0.0, 0.0], [2.0, 2.0]]), -0.5);
        assert_eq!(to_rect([5.0, 6.0], [[0.0, 0.0], [2.0, 2.0]]), 5.0);
        assert_eq!(to_segment([1.0, 1.0], [0.0, 0.0], [2.0, 0.0]), 1.0);
    }
}
