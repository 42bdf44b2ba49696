//! The job's `cell:` in millimetres and frames, with the default cell where the job leaves
//! it out: what [`cell::fixture`] plans with and the RAPID writer writes.

use cell::model::{Opw, RobotModel};
use cell::plan::Holder;
use export::robot::Targets;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use crate::spec::{CellSpec, FrameSpec, HolderSpec, ModelSpec};

/// Defaults of the cell, in millimetres (converted by the job's units where a job gives
/// lengths).
pub mod defaults {
    /// Heights of the fixture's floor (a block's bottom) above the robots' bases tried by
    /// the default cell, mm, the likeliest first.
    pub const TABLES_MM: [f64; 4] = [200.0, 0.0, 400.0, 600.0];
    /// Horizontal distances from a default robot's axis 1 to the blade's end it holds
    /// (the blade's middle over the poses' mean chord midpoint) tried by the default
    /// cell, mm, the likeliest first.
    pub const STANDOFFS_MM: [f64; 4] = [800.0, 1000.0, 600.0, 1200.0];
    /// From the flange to the blade's end along the flange's z, mm.
    pub const HOLDER_MM: f64 = 150.0;
    /// Mass of a holder with its half of the blade, kg.
    pub const HOLDER_KG: f64 = 2.0;
    /// A layout whose least joint margin is at least this, with every move reached and no
    /// flip, ends the search, degrees.
    pub const GOOD_MARGIN_DEG: f64 = 5.0;
    /// Air speed, mm/s.
    pub const AIR_SPEED_MM_PER_S: f64 = 100.0;
    /// Height of the blade above the blocks between them, mm.
    pub const CLEARANCE_MM: f64 = 100.0;
    /// Largest step of a travelling blade end, mm.
    pub const TRAVEL_STEP_MM: f64 = 100.0;
    /// Largest turn of the blade's plane or an end between two travel moves, degrees.
    pub const TRAVEL_TURN_DEG: f64 = 5.0;
    /// The robots' start postures tried, degrees: axis 5 bent either way (the wrist
    /// keeps its side through a whole program, so both sides are tried).
    pub const STARTS_DEG: [[f64; 6]; 2] = [
        [0.0, 0.0, 0.0, 0.0, 30.0, 0.0],
        [0.0, 0.0, 0.0, 0.0, -30.0, 0.0],
    ];
}

/// A robot of the resolved cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Robot {
    /// Its model (mm, radians).
    pub model: RobotModel,
    /// Its base in the cell's frame (mm).
    pub base: Isometry3<f64>,
}

/// A blade holder of the resolved cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Hold {
    /// Index of its robot.
    pub robot: usize,
    /// The TCP in the flange's frame (mm).
    pub tcp: Isometry3<f64>,
    /// Mass, kg.
    pub mass: f64,
    /// Centre of gravity in the flange's frame, mm.
    pub cog: [f64; 3],
}

/// The block carrier of the resolved cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Carry {
    /// Index of its robot.
    pub robot: usize,
    /// The block's frame in the flange's frame (mm).
    pub grip: Isometry3<f64>,
    /// Mass of the gripper with a block, kg.
    pub mass: f64,
    /// Where the blade cuts, in the cell's frame (mm).
    pub station: Isometry3<f64>,
}

/// The cell in millimetres.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolved {
    /// Whether the default cell (or default holders) is used.
    pub assumed: bool,
    /// The robots.
    pub robots: Vec<Robot>,
    /// The holders of the blade's first and second end.
    pub holders: [Hold; 2],
    /// A block's frame at the fixture, in the cell's frame (mm); unused with a carrier.
    pub fixture: Isometry3<f64>,
    /// The robot that carries the block, if any.
    pub carrier: Option<Carry>,
    /// Air speed, mm/s.
    pub air_speed: f64,
    /// Clearance above the blocks, mm.
    pub clearance: f64,
    /// The heat's output and preheat.
    pub heat: (String, f64),
    /// Whether flags fail the run.
    pub strict: bool,
}

impl Resolved {
    /// The holder of end `e` as the planner takes it.
    pub fn holder(&self, e: usize) -> Holder {
        let h = &self.holders[e];
        self.arm(h.robot, h.tcp)
    }

    /// Robot `r` with tool `tool` as the planner takes it.
    pub fn arm(&self, r: usize, tool: Isometry3<f64>) -> Holder {
        let robot = &self.robots[r];
        Holder {
            model: robot.model.clone(),
            base: robot.base,
            tool,
        }
    }
}

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

/// How a default holder holds its end of the blade.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HolderStyle {
    /// The flange faces along the cutting plane's normal, the blade's end
    /// [`defaults::HOLDER_MM`] in front of it on the flange's axis; at the job's mean pose
    /// the flange's x points down. The blade turns in its plane about axis 6.
    Facing,
    /// A bracket hanging from a flange that points down at the job's mean pose, its x from
    /// the robot towards the blade; the blade's end [`defaults::HOLDER_MM`] below it.
    Hanging,
}

/// The default holder's TCP for an end whose mean tool orientation in the cell's frame is
/// `mean`, on a robot that reaches towards the blade along `toward` (horizontal).
fn default_tcp(
    style: HolderStyle,
    mean: &UnitQuaternion<f64>,
    toward: &Vector3<f64>,
) -> Isometry3<f64> {
    let unit = |v: Vector3<f64>, or: Vector3<f64>| if v.norm() > 1e-6 { v.normalize() } else { or };
    let (x, z) = match style {
        HolderStyle::Facing => {
            let z = mean * Vector3::z();
            let down = -Vector3::z();
            (unit(down - z * down.dot(&z), mean * Vector3::x()), z)
        }
        HolderStyle::Hanging => {
            let z = -Vector3::z();
            (unit(toward - z * toward.dot(&z), Vector3::x()), z)
        }
    };
    let flange = UnitQuaternion::from_rotation_matrix(&nalgebra::Rotation3::from_matrix_unchecked(
        nalgebra::Matrix3::from_columns(&[x, z.cross(&x), z]),
    ));
    Isometry3::from_parts(
        Translation3::new(0.0, 0.0, defaults::HOLDER_MM),
        flange.inverse() * mean,
    )
}

/// Where a blade pose of the job is in the cell: at the fixture, or at the carrier's
/// station.
fn placement(
    b: &export::robot::TargetsBlock,
    p: &export::robot::Pose,
    fixture: &Isometry3<f64>,
    station: Option<&Isometry3<f64>>,
    mm: f64,
) -> Isometry3<f64> {
    let to_block = block_frame(b, mm).inverse();
    let Some(s) = station else {
        return fixture * to_block;
    };
    let ends = p.ends.map(|e| to_block * end_frame(&e, mm));
    // a pose that holds no blade is refused by the planner; here any frame will do
    cell::carrier::block_pose(s, &ends).unwrap_or(*s) * to_block
}

/// An end's tool frame in job coordinates, mm.
pub fn end_frame(e: &export::robot::EndPose, mm: f64) -> Isometry3<f64> {
    let q = e.rotation;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(e.position) * mm),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3])),
    )
}

/// The blade's mean pose in the cell (at the fixture, or at the carrier's `station`): the
/// chords' mean midpoint, their mean horizontal direction, and each end's mean tool
/// orientation (cell frame, mm).
fn mean_pose(
    t: &Targets,
    fixture: &Isometry3<f64>,
    station: Option<&Isometry3<f64>>,
) -> (Vector3<f64>, Vector3<f64>, [UnitQuaternion<f64>; 2]) {
    let mm = 1.0 / t.per_mm;
    let (mut chord, mut mid, mut n) = (Vector3::zeros(), Vector3::zeros(), 0.0);
    let mut q = [nalgebra::Vector4::zeros(); 2];
    for b in &t.blocks {
        for p in &b.poses {
            let to_cell = placement(b, p, fixture, station, mm);
            let e =
                |k: usize| to_cell * nalgebra::Point3::from(Vector3::from(p.ends[k].position) * mm);
            chord += e(1) - e(0);
            mid += (e(0).coords + e(1).coords) * 0.5;
            n += 1.0;
            for (k, acc) in q.iter_mut().enumerate() {
                let r = p.ends[k].rotation;
                let r = to_cell.rotation
                    * UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
                        r[0], r[1], r[2], r[3],
                    ));
                let c = r.as_ref().coords;
                // one hemisphere, so that the sum is a mean
                *acc += if c.dot(acc) < 0.0 { -c } else { c };
            }
        }
    }
    let mid = if n > 0.0 { mid / n } else { Vector3::zeros() };
    let dir = Vector3::new(chord.x, chord.y, 0.0);
    let dir = if dir.norm() > 1e-9 {
        dir.normalize()
    } else {
        Vector3::y()
    };
    let mean = q.map(|c| {
        if c.norm() > 0.0 {
            UnitQuaternion::from_quaternion(nalgebra::Quaternion::from(c))
        } else {
            UnitQuaternion::identity()
        }
    });
    (mid, dir, mean)
}

fn hold(h: Option<&HolderSpec>, default: Isometry3<f64>, e: usize, mm: f64) -> Hold {
    let tcp = h
        .and_then(|h| h.tcp.as_ref())
        .map_or(default, |f| frame(f, mm));
    let half = tcp.translation.vector * 0.5;
    Hold {
        robot: h.map_or(e, |h| h.robot),
        tcp,
        mass: h.and_then(|h| h.mass).unwrap_or(defaults::HOLDER_KG),
        cog: h
            .and_then(|h| h.cog)
            .map_or([half.x, half.y, half.z], |c| [c.0 * mm, c.1 * mm, c.2 * mm]),
    }
}

/// The default fixture: a block of `size` (mm) centred over the cell's origin, its floor
/// `table` up, its axes the cell's.
fn default_fixture(size: [f64; 3], table: f64) -> Isometry3<f64> {
    Isometry3::translation(-0.5 * size[0], -0.5 * size[1], table)
}

/// The default robots: two IRB 2600-12/1.65 on the floor (the workshop's IRB 1600 cannot
/// hold every job's blade through its travels within its wrist's ±115°), facing each other along the blade's
/// mean chord `dir` (horizontal), each `standoff` beyond the end of a blade of `blade`
/// whose middle is at `mid`.
fn default_robots(mid: &Vector3<f64>, dir: &Vector3<f64>, blade: f64, standoff: f64) -> Vec<Robot> {
    let irb = RobotModel::irb2600_12_165();
    (0..2)
        .map(|e| {
            let s = if e == 0 { -1.0 } else { 1.0 };
            let at = Vector3::new(mid.x, mid.y, 0.0) + dir * (s * (0.5 * blade + standoff));
            let facing = -dir * s;
            Robot {
                model: irb.clone(),
                base: Isometry3::from_parts(
                    Translation3::from(at),
                    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), facing.y.atan2(facing.x)),
                ),
            }
        })
        .collect()
}

/// A block's frame in job coordinates, mm.
pub fn block_frame(b: &export::robot::TargetsBlock, mm: f64) -> Isometry3<f64> {
    let q = b.rotation;
    Isometry3::from_parts(
        Translation3::from(Vector3::from(b.origin) * mm),
        UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3])),
    )
}

/// How the default cell is laid out.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Height of the fixture's floor above the robots' bases, mm.
    pub table: f64,
    /// Horizontal distance from a robot's axis 1 to its end of the blade, mm.
    pub standoff: f64,
    /// How the holders hold the blade.
    pub style: HolderStyle,
}

/// The cell of `spec` (the default where absent, laid out by `layout`) for the poses `t`
/// of a blade of `blade_mm`, blocks of at most `block_mm`.
pub fn resolve(
    spec: Option<&CellSpec>,
    t: &Targets,
    blade_mm: f64,
    block_mm: [f64; 3],
    layout: Layout,
) -> Resolved {
    let mm = 1.0 / t.per_mm;
    let default = CellSpec::default();
    let s = spec.unwrap_or(&default);
    let fixture = s
        .fixture
        .as_ref()
        .map_or_else(|| default_fixture(block_mm, layout.table), |f| frame(f, mm));
    let carrier = s.block_carrier.as_ref().map(|k| Carry {
        robot: k.robot,
        grip: frame(&k.grip, mm),
        mass: k.mass,
        station: frame(&k.station, mm),
    });
    let (mid, dir, mean) = mean_pose(t, &fixture, carrier.as_ref().map(|k| &k.station));
    let hs = s.blade_holders.as_deref();
    let holders = [0, 1].map(|e| {
        let toward = if e == 0 { dir } else { -dir };
        hold(
            hs.and_then(|h| h.get(e)),
            default_tcp(layout.style, &mean[e], &toward),
            e,
            mm,
        )
    });
    let robots = match &s.robots {
        Some(r) => r
            .iter()
            .map(|r| Robot {
                model: model(&r.model, mm),
                base: frame(&r.base, mm),
            })
            .collect(),
        None => default_robots(&mid, &dir, blade_mm, layout.standoff),
    };
    Resolved {
        assumed: spec.is_none() || s.robots.is_none() || s.blade_holders.is_none(),
        robots,
        holders,
        fixture,
        carrier,
        air_speed: s.air_speed.map_or(defaults::AIR_SPEED_MM_PER_S, |v| v * mm),
        clearance: s.clearance.map_or(defaults::CLEARANCE_MM, |v| v * mm),
        heat: (s.heat.signal.clone(), s.heat.preheat_s),
        strict: s.strict,
    }
}
