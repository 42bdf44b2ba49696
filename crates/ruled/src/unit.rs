//! The block's unit frame, where a pre-cut is computed: `p ↦ (p − min)/L`, `min` the
//! block's lower corner and `L` its longest edge, every input number rounded to a grid.
//!
//! The optimization follows near-ties (which constraint points the exchange adds, where
//! the QP solver stops), so its result turns on the last bits of its input: a job in
//! metres and the same job in millimetres, whose inputs differ by the rounding of a
//! ÷1000, took different paths to cuts 8 % apart in volume. In the unit frame the two are
//! the same numbers once rounded to [`UNIT_GRID`], so they take the same path; the result
//! is mapped back to model units at the end.

use geom::mesh::TriMesh;
use geom::surface::Surface;
use nalgebra::Vector3;

use crate::error::Result;
use crate::frame::Block;
use crate::height::{Height, MeshHeight, SPLINE_GRID};
use crate::{DirectionCut, LegLine, PreCut, SectionPolygon};

/// The grid, relative to the block's longest edge, every number the optimization starts
/// from is rounded to: 2⁻²⁸ ≈ 3.7·10⁻⁹, 15 nm on a 4 m block, far below the clearance the
/// cuts keep (10⁻⁵ of the edge). Two inputs that differ in their last bits round to the
/// same number unless one lies within those bits of a grid midpoint (a chance of ~10⁻⁷
/// per number).
pub const UNIT_GRID: f64 = 1.0 / (1u64 << 28) as f64;

/// `x` rounded to [`UNIT_GRID`].
pub fn round(x: f64) -> f64 {
    (x / UNIT_GRID).round() * UNIT_GRID
}

/// The similarity to a block's unit frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitFrame {
    /// The block's lower corner (model units).
    pub origin: Vector3<f64>,
    /// The block's longest edge (model units).
    pub scale: f64,
}

impl UnitFrame {
    /// The frame of `block`.
    pub fn of(block: &Block) -> Self {
        Self {
            origin: Vector3::from(block.min),
            scale: block.scale(),
        }
    }

    /// A model point in the frame, rounded.
    pub fn point(&self, p: Vector3<f64>) -> Vector3<f64> {
        ((p - self.origin) / self.scale).map(round)
    }

    /// A model length in the frame, rounded.
    pub fn length(&self, l: f64) -> f64 {
        round(l / self.scale)
    }

    /// A point of the frame in model units.
    pub fn to_model(&self, p: Vector3<f64>) -> Vector3<f64> {
        self.origin + p * self.scale
    }

    /// The block in the frame: from the origin to its size over its longest edge.
    pub fn block(&self, block: &Block) -> Block {
        let size = block.size().map(|s| self.length(s));
        Block {
            min: [0.0; 3],
            max: size.into(),
        }
    }

    /// The design surface's height function in the frame. A height field is evaluated in
    /// model units and its heights mapped and rounded; a mesh (or a spline's tessellation)
    /// has its vertices mapped and rounded.
    ///
    /// # Errors
    /// As [`Height::new`].
    pub fn height(&self, surface: &Surface) -> Result<Height> {
        let mesh = |m: &TriMesh| -> Result<Height> {
            let v = m.vertices().iter().map(|&p| self.point(p)).collect();
            let unit = TriMesh::try_new(v, m.faces().to_vec())?;
            Ok(Height::Mesh(MeshHeight::new(&unit)?))
        };
        match surface {
            Surface::HeightField(h) => {
                let ((x0, x1), (y0, y1)) = (h.x_range(), h.y_range());
                let (lo, hi) = (
                    self.point(Vector3::new(x0, y0, 0.0)),
                    self.point(Vector3::new(x1, y1, 0.0)),
                );
                Ok(Height::FieldInFrame {
                    field: h.clone(),
                    frame: *self,
                    range: [(lo.x, hi.x), (lo.y, hi.y)],
                })
            }
            Surface::Mesh(m) => mesh(m),
            Surface::Spline(s) => mesh(&s.to_mesh(SPLINE_GRID)?),
        }
    }

    /// A pre-cut computed in the frame, in model units.
    pub fn result(&self, cut: PreCut) -> PreCut {
        PreCut {
            directions: cut
                .directions
                .into_iter()
                .map(|d| self.direction(d))
                .collect(),
            // ratios of volumes
            ..cut
        }
    }

    fn direction(&self, d: DirectionCut) -> DirectionCut {
        let (o, l) = (self.origin, self.scale);
        let u0 = d.direction[0] * o.x + d.direction[1] * o.y;
        let w0 = d.across[0] * o.x + d.across[1] * o.y;
        let height = |z: f64| o.z + l * z;
        let line = |x: LegLine| LegLine {
            a: height(x.a),
            m: l * x.m,
        };
        DirectionCut {
            u: (u0 + l * d.u.0, u0 + l * d.u.1),
            w: (w0 + l * d.w.0, w0 + l * d.w.1),
            knots: d.knots.iter().map(|k| u0 + l * k).collect(),
            w_mid: w0 + l * d.w_mid,
            w_half: l * d.w_half,
            legs: d
                .legs
                .into_iter()
                .map(|leg| crate::LegSpline {
                    a: leg.a.into_iter().map(height).collect(),
                    m: leg.m.into_iter().map(|m| l * m).collect(),
                })
                .collect(),
            sections: d
                .sections
                .into_iter()
                .map(|s| SectionPolygon {
                    offset: u0 + l * s.offset,
                    polygon: s
                        .polygon
                        .iter()
                        .map(|&p| self.to_model(Vector3::from(p)).into())
                        .collect(),
                    legs: s.legs,
                })
                .collect(),
            lines: d
                .lines
                .into_iter()
                .map(|ls| ls.into_iter().map(line).collect())
                .collect(),
            objective_history: d.objective_history.iter().map(|v| v * l * l).collect(),
            clearance: l * d.clearance,
            ..d
        }
    }
}
