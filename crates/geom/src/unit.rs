//! The unit frame a problem is solved in: `p ↦ (p − origin)/scale`, every number rounded
//! to a grid, so that the same problem in millimetres and in metres (whose inputs differ
//! by the rounding of a ÷1000) becomes the same numbers and takes the same path through
//! a search that follows near-ties. The result is mapped back with
//! [`UnitFrame::to_model`](crate::unit::UnitFrame::to_model). Used by the block
//! segmentation and the pre-cut; the elastica fit rounds its unit-length problems with
//! [`snap`](crate::unit::snap) to its own finer grid.

use nalgebra::Vector3;

/// The grid, relative to the frame's scale, that [`UnitFrame`] rounds to: 2⁻²⁸ ≈
/// 3.7·10⁻⁹ (0.6 nm on a 160 mm block, 15 nm on a 4 m one). Two inputs that differ in
/// their last bits round to the same number unless one lies within those bits of a grid
/// midpoint (a chance of ~10⁻⁷ per number).
pub const UNIT_GRID: f64 = 1.0 / (1u64 << 28) as f64;

/// `x` rounded to a multiple of `grid`.
///
/// ```
/// use geom::unit::snap;
/// assert_eq!(snap(0.3, 0.25), 0.25);
/// assert_eq!(snap(1e-3 * 1000.0, 1.0 / 1024.0), 1.0);
/// ```
pub fn snap(x: f64, grid: f64) -> f64 {
    (x / grid).round() * grid
}

/// The similarity to a unit frame: `p ↦ (p − origin)/scale`, rounded to [`UNIT_GRID`].
///
/// ```
/// use geom::unit::UnitFrame;
/// use nalgebra::Vector3;
/// // the same box corner in mm and in m lands on the same unit-frame numbers
/// let mm = UnitFrame { origin: Vector3::new(100.0, 0.0, 0.0), scale: 400.0 };
/// let m = UnitFrame { origin: mm.origin / 1000.0, scale: 0.4 };
/// let p = Vector3::new(433.3, 123.4, 56.7);
/// assert_eq!(mm.point(p), m.point(p / 1000.0));
/// assert_eq!(mm.length(200.0), 0.5);
/// assert!((mm.to_model(mm.point(p)) - p).norm() < 1e-6);
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitFrame {
    /// The point that maps to zero (model units): a block's or model's lower corner.
    pub origin: Vector3<f64>,
    /// The length that maps to one (model units): a block's longest edge.
    pub scale: f64,
}

impl UnitFrame {
    /// A model point in the frame, rounded.
    pub fn point(&self, p: Vector3<f64>) -> Vector3<f64> {
        ((p - self.origin) / self.scale).map(|v| snap(v, UNIT_GRID))
    }

    /// A model length in the frame, rounded.
    pub fn length(&self, l: f64) -> f64 {
        snap(l / self.scale, UNIT_GRID)
    }

    /// A point of the frame in model units.
    pub fn to_model(&self, p: Vector3<f64>) -> Vector3<f64> {
        self.origin + p * self.scale
    }
}
