//! The job's `cell:` in millimetres and frames ([`cell::layout::CellSettings`]); the
//! default cell where the job leaves parts out is [`cell::layout`]'s.

use cell::layout::{Carry, CellSettings, HolderSettings, Robot};
use cell::model::{Opw, RobotModel};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::spec::{CellSpec, FrameSpec, ModelSpec};

/// A frame of the job (origin in job units) in mm.
pub fn frame(f: &FrameSpec, mm: f64) -> Isometry3<f64> {
    let (a, b, c) = f.rotation;
    Isometry3::from_parts(
        Translation3::new(f.origin.0 * mm, f.origin.1 * mm, f.origin.2 * mm),
        UnitQuaternion::from_euler_angles(c.to_radians(), b.to_radians(), a.to_radians()),
    )
}

/// The robot model of a spec (custom lengths in job units, `mm` per unit).
pub fn model(m: &ModelSpec, mm: f64) -> RobotModel {
    match m {
        ModelSpec::Irb1600 => RobotModel::irb1600_6_145(),
        ModelSpec::Irb2600 => RobotModel::irb2600_12_165(),
        ModelSpec::Irb4600 => RobotModel::irb4600_60_205(),
        ModelSpec::Custom(c) => RobotModel {
            name: c.name.clone(),
            opw: Opw {
                a1: c.a1 * mm,
                a2: c.a2 * mm,
                b: c.b * mm,
                c1: c.c1 * mm,
                c2: c.c2 * mm,
                c3: c.c3 * mm,
                c4: c.c4 * mm,
                // lengths are checked at validation; a short list reads as its defaults
                offsets: std::array::from_fn(|i| {
                    let abb = [0.0, 0.0, -90.0, 0.0, 0.0, 0.0];
                    c.offsets
                        .as_ref()
                        .and_then(|o| o.get(i))
                        .copied()
                        .unwrap_or(abb[i])
                        .to_radians()
                }),
                signs: std::array::from_fn(|i| {
                    c.signs
                        .as_ref()
                        .and_then(|s| s.get(i))
                        .copied()
                        .unwrap_or(1)
                }),
            },
            limits: std::array::from_fn(|i| {
                let (lo, hi) = c.limits.get(i).copied().unwrap_or((f64::NAN, f64::NAN));
                (lo.to_radians(), hi.to_radians())
            }),
        },
    }
}

/// An end's tool frame in job coordinates, mm.
pub fn end_frame(e: &export::robot::EndPose, mm: f64) -> Isometry3<f64> {
    let q = e.rotation;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(e.position) * mm),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3])),
    )
}

/// A block's frame in job coordinates, mm.
pub fn block_frame(b: &export::robot::TargetsBlock, mm: f64) -> Isometry3<f64> {
    let q = b.rotation;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(b.origin) * mm),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3])),
    )
}

/// The job's `cell:` (or the default cell) in mm (`mm` per job unit): what it gives, the
/// rest left to [`cell::layout::resolve`].
pub fn settings(spec: Option<&CellSpec>, mm: f64) -> CellSettings {
    let default = CellSpec::default();
    let s = spec.unwrap_or(&default);
    CellSettings {
        robots: s.robots.as_ref().map(|r| {
            r.iter()
                .map(|r| Robot {
                    model: model(&r.model, mm),
                    base: frame(&r.base, mm),
                })
                .collect()
        }),
        holders: s.blade_holders.as_ref().map(|hs| {
            hs.iter()
                .map(|h| HolderSettings {
                    robot: h.robot,
                    tcp: h.tcp.as_ref().map(|f| frame(f, mm)),
                    mass: h.mass,
                    cog: h.cog.map(|c| [c.0 * mm, c.1 * mm, c.2 * mm]),
                })
                .collect()
        }),
        fixture: s.fixture.as_ref().map(|f| frame(f, mm)),
        carrier: s.block_carrier.as_ref().map(|k| Carry {
            robot: k.robot,
            grip: frame(&k.grip, mm),
            mass: k.mass,
            station: frame(&k.station, mm),
        }),
        air_speed: s.air_speed.map(|v| v * mm),
        clearance: s.clearance.map(|v| v * mm),
        heat: (s.heat.signal.clone(), s.heat.preheat_s),
        strict: s.strict,
    }
}
