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

pub use geom::unit::{UnitFrame, UNIT_GRID};

/// `x` rounded to [`UNIT_GRID`].
pub fn round(x: f64) -> f64 {
    geom::unit::snap(x, UNIT_GRID)
}

/// The frame of `block`: its lower corner, its longest edge.
pub fn frame(block: &Block) -> UnitFrame {
    UnitFrame {
        origin: Vector3::from(block.min),
        scale: block.scale(),
    }
}

/// The block in `frame`: from the origin to its size over its longest edge.
pub fn block(frame: &UnitFrame, block: &Block) -> Block {
    let size = block.size().map(|s| frame.length(s));
    Block {
        min: [0.0; 3],
        max: size.into(),
    }
}

/// The design surface's height function in `frame`. A height field is evaluated in
/// model units and its heights mapped and rounded; a mesh (or a spline's tessellation)
/// has its vertices mapped and rounded.
///
/// # Errors
/// As [`Height::new`].
pub fn height(frame: &UnitFrame, surface: &Surface) -> Result<Height> {
    let mesh = |m: &TriMesh| -> Result<Height> {
        let v = m.vertices().iter().map(|&p| frame.point(p)).collect();
        let unit = TriMesh::try_new(v, m.faces().to_vec())?;
        Ok(Height::Mesh(MeshHeight::new(&unit)?))
    };
    match surface {
        Surface::HeightField(h) => {
            let ((x0, x1), (y0, y1)) = (h.x_range(), h.y_range());
            let (lo, hi) = (
                frame.point(Vector3::new(x0, y0, 0.0)),
                frame.point(Vector3::new(x1, y1, 0.0)),
            );
            Ok(Height::FieldInFrame {
                field: h.clone(),
                frame: *frame,
                range: [(lo.x, hi.x), (lo.y, hi.y)],
            })
        }
        Surface::Mesh(m) => mesh(m),
        Surface::Spline(s) => mesh(&s.to_mesh(SPLINE_GRID)?),
    }
}

/// A pre-cut computed in `frame`, in model units.
pub fn result(frame: &UnitFrame, cut: PreCut) -> PreCut {
    PreCut {
        directions: cut
            .directions
            .into_iter()
            .map(|d| direction(frame, d))
            .collect(),
        // ratios of volumes
        ..cut
    }
}

fn direction(frame: &UnitFrame, d: DirectionCut) -> DirectionCut {
    let (o, l) = (frame.origin, frame.scale);
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
                    .map(|&p| frame.to_model(Vector3::from(p)).into())
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
