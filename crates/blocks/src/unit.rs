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

pub use geom::unit::{UnitFrame, UNIT_GRID};

/// The frame of `mesh` with blocks of `params.block_size`: its lower corner, the block's
/// longest edge.
pub fn frame(mesh: &TriMesh, params: &Params) -> UnitFrame {
    UnitFrame {
        origin: mesh.aabb().min,
        scale: params.block_size.iter().copied().fold(0.0, f64::max),
    }
}

/// The mesh in `frame`, its vertices rounded.
///
/// # Errors
/// [`BlockError::Model`] when the mapped mesh is not a valid mesh.
pub fn mesh(frame: &UnitFrame, mesh: &TriMesh) -> Result<TriMesh> {
    let v = mesh.vertices().iter().map(|&p| frame.point(p)).collect();
    TriMesh::try_new(v, mesh.faces().to_vec()).map_err(|e| BlockError::Model(e.to_string()))
}

/// The parameters in `frame`: the block's size over its longest edge.
pub fn params(frame: &UnitFrame, params: &Params) -> Params {
    Params {
        block_size: params.block_size.map(|s| frame.length(s)),
        ..params.clone()
    }
}

/// A segmentation computed in `frame`, in model units (energies and counts are free of
/// units).
pub fn result(frame: &UnitFrame, seg: Segmentation) -> Segmentation {
    let (o, l) = (frame.origin, frame.scale);
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
