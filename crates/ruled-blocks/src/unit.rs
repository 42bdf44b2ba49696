//! The unit frame every step computes in: the model moved to its bounding box's low corner,
//! scaled by its diagonal and snapped to [`geom::unit::UNIT_GRID`]. A job in millimetres and
//! the same job in metres (inputs rounded when converted) are then the same numbers, so
//! every decision that compares two lengths falls the same way; results are taken back to
//! the model's frame.

use blocks::Cuboid;
use geom::unit::UnitFrame;
use geom::TriMesh;
use nalgebra::Vector3;

use crate::cuts::{BlockPlan, WireLine};
use crate::error::{Error, Result};
use crate::plan::{Deviation, Params};
use crate::regions::Region;
use crate::solid::{Ruling, Solid};

/// The frame of `model`: its box's low corner, its diagonal.
pub fn frame(model: &TriMesh) -> UnitFrame {
    let b = model.aabb();
    UnitFrame {
        origin: b.min,
        scale: b.size().norm().max(f64::MIN_POSITIVE),
    }
}

/// The checks both strategies make first — the parameters, then the mesh a closed solid —
/// and the model's frame, the model and the parameters in it.
///
/// # Errors
/// [`Error::Params`] naming the first bad field, [`Error::Model`] for a mesh that is not a
/// closed solid.
pub fn prepare(model: &TriMesh, p: &Params) -> Result<(UnitFrame, TriMesh, Params)> {
    if let Some((field, message)) = p.problems().into_iter().next() {
        return Err(Error::Params { field, message });
    }
    model
        .validate(true)
        .map_err(|e| Error::Model(e.to_string()))?;
    let f = frame(model);
    Ok((f, mesh(&f, model)?, params(&f, p)))
}

/// The model in the frame.
///
/// # Errors
/// [`Error::Model`] for a mesh that no longer is one.
pub fn mesh(f: &UnitFrame, m: &TriMesh) -> Result<TriMesh> {
    let v = m.vertices().iter().map(|p| f.point(*p)).collect();
    TriMesh::try_new(v, m.faces().to_vec()).map_err(|e| Error::Model(e.to_string()))
}

/// The parameters in the frame.
pub fn params(f: &UnitFrame, p: &Params) -> Params {
    let l = |x: f64| f.length(x);
    Params {
        tolerance: l(p.tolerance),
        kerf: l(p.kerf),
        lead: l(p.lead),
        blocks: blocks::Params {
            block_size: p.blocks.block_size.map(l),
            ..p.blocks.clone()
        },
        ..p.clone()
    }
}

/// A point back in the model's frame.
fn point(f: &UnitFrame, p: Vector3<f64>) -> Vector3<f64> {
    f.to_model(p)
}

/// A deviation back.
pub fn deviation(f: &UnitFrame, d: Deviation) -> Deviation {
    Deviation {
        rms: d.rms * f.scale,
        max: d.max * f.scale,
        ..d
    }
}

/// A solid back.
///
/// # Errors
/// [`Error::Model`] for a degenerate result.
pub fn solid(f: &UnitFrame, s: Solid) -> Result<Solid> {
    let v = s.mesh.vertices().iter().map(|p| point(f, *p)).collect();
    let mesh =
        TriMesh::try_new(v, s.mesh.faces().to_vec()).map_err(|e| Error::Model(e.to_string()))?;
    let strips = s
        .strips
        .into_iter()
        .map(|mut st| {
            for r in &mut st.rulings {
                *r = Ruling {
                    a: point(f, r.a),
                    b: point(f, r.b),
                    ..*r
                };
            }
            st
        })
        .collect();
    Ok(Solid { mesh, strips, ..s })
}

/// A region back: its offsets along the axis and its surface.
///
/// # Errors
/// [`Error::Model`] for a degenerate surface.
pub fn region(f: &UnitFrame, axis: &Vector3<f64>, r: Region) -> Result<Region> {
    let shift = axis.dot(&f.origin);
    let s = &r.surface;
    let ctrl = s.control_points().iter().map(|p| point(f, *p)).collect();
    let surface = geom::surface_spline::BSplineSurface::try_new(
        s.degrees(),
        s.knots_u().iter().map(|u| u * f.scale + shift).collect(),
        s.knots_v().to_vec(),
        s.grid_size(),
        ctrl,
    )
    .map_err(|e| Error::Model(e.to_string()))?;
    Ok(Region {
        offsets: r.offsets.iter().map(|u| u * f.scale + shift).collect(),
        surface,
        fit_rms: r.fit_rms * f.scale,
        fit_max: r.fit_max * f.scale,
        ..r
    })
}

/// A block back.
pub fn cuboid(f: &UnitFrame, b: &Cuboid) -> Cuboid {
    Cuboid::new(point(f, b.center), b.rotation, b.half * f.scale)
}

/// A block's plan back.
pub fn plan(f: &UnitFrame, p: BlockPlan) -> BlockPlan {
    let v = f.scale.powi(3);
    let cuts = p
        .cuts
        .into_iter()
        .map(|mut c| {
            c.lines = c
                .lines
                .iter()
                .map(|l| WireLine {
                    point: point(f, l.point),
                    dir: l.dir,
                })
                .collect();
            c
        })
        .collect();
    BlockPlan {
        block: cuboid(f, &p.block),
        deepest: p.deepest * f.scale,
        cuts,
        added_volume: p.added_volume * v,
        added_depth: p.added_depth * f.scale,
        kept_volume: p.kept_volume * v,
        keeps: p
            .keeps
            .iter()
            .map(|h| crate::hull::Plane {
                n: h.n,
                c: h.c * f.scale + h.n.dot(&f.origin),
            })
            .collect(),
        ..p
    }
}

/// A strategy's figures back: lengths, volumes, the deviation.
pub fn figures(f: &UnitFrame, x: crate::compare::Figures) -> crate::compare::Figures {
    crate::compare::Figures {
        max_gap: x.max_gap * f.scale,
        rms_gap: x.rms_gap * f.scale,
        deviation: deviation(f, x.deviation),
        added_volume: x.added_volume * f.scale.powi(3),
        ..x
    }
}
