//! The unit frame a segmentation is computed in: `p ↦ (p − min)/L`, `min` the model's
//! lower corner and `L` the block's longest edge, every input number rounded to a grid.
//!
//! The loop of §3.3.5 is a randomized local search of thousands of accept/reject
//! decisions, and a decision can turn on the last bits of its input: the same model in
//! metres and in millimetres, whose vertices differ by the rounding of a ÷1000, ended
//! with 173 and 179 blocks. In the unit frame the two are the same numbers once rounded to
//! [`UNIT_GRID`](crate::unit::UNIT_GRID), so they make the same decisions; the result is mapped back to model
//! units at the end.

use geom::mesh::TriMesh;
use nalgebra::Vector3;

use crate::error::{BlockError, Result};
use crate::{Params, Placement, Segmentation};

/// The grid, relative to the block's longest edge, every number the segmentation starts
/// from is rounded to: 2⁻²⁸ ≈ 3.7·10⁻⁹ (0.6 nm on a 160 mm block). Two inputs that differ
/// in their last bits round to the same number unless one lies within those bits of a
/// grid midpoint (a chance of ~10⁻⁷ per number).
pub const UNIT_GRID: f64 = 1.0 / (1u64 << 28) as f64;

fn round(x: f64) -> f64 {
    (x / UNIT_GRID).round() * UNIT_GRID
}

/// The similarity to a segmentation's unit frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitFrame {
    /// The model's lower corner (model units).
    pub origin: Vector3<f64>,
    /// The block's longest edge (model units).
    pub scale: f64,
}

impl UnitFrame {
    /// The frame of `mesh` with blocks of `params.block_size`.
    pub fn of(mesh: &TriMesh, params: &Params) -> Self {
        Self {
            origin: mesh.aabb().min,
            scale: params.block_size.iter().copied().fold(0.0, f64::max),
        }
    }

    /// The mesh in the frame, its vertices rounded.
    ///
    /// # Errors
    /// [`BlockError::Model`] when the mapped mesh is not a valid mesh.
    pub fn mesh(&self, mesh: &TriMesh) -> Result<TriMesh> {
        let v = mesh
            .vertices()
            .iter()
            .map(|&p| ((p - self.origin) / self.scale).map(round))
            .collect();
        TriMesh::try_new(v, mesh.faces().to_vec()).map_err(|e| BlockError::Model(e.to_string()))
    }

    /// The parameters in the frame: the block's size over its longest edge.
    pub fn params(&self, params: &Params) -> Params {
        Params {
            block_size: params.block_size.map(|s| round(s / self.scale)),
            ..params.clone()
        }
    }

    /// A segmentation computed in the frame, in model units (energies and counts are
    /// free of units).
    pub fn result(&self, seg: Segmentation) -> Segmentation {
        let (o, l) = (self.origin, self.scale);
        let place = |p: Placement| Placement {
            center: (o + Vector3::from(p.center) * l).into(),
            rotation: p.rotation,
            size: p.size.map(|s| s * l),
        };
        Segmentation {
            blocks: seg.blocks.into_iter().map(place).collect(),
            model_volume: seg.model_volume * l * l * l,
            block_volume: seg.block_volume * l * l * l,
            bounding_box: place(seg.bounding_box),
            sampling: crate::SamplingInfo {
                spacing: seg.sampling.spacing * l,
                margin: seg.sampling.margin * l,
                ..seg.sampling
            },
            ..seg
        }
    }
}
