//! A cell in millimetres and frames, with the default cell where the user leaves parts
//! out: the robots, the blade holders, the fixture (or the block carrier), air speed,
//! clearance and heat. [`resolve`](crate::layout::resolve) places the default robots and holders for a job's
//! blade poses; [`crate::program::plan`] searches the default layouts for the best one.

use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3, Vector4};

use crate::blade::BladePose;
use crate::model::RobotModel;
use crate::plan::Holder;

/// Defaults of the cell, in millimetres (a job converts its own lengths to mm first).
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

/// A robot of the cell.
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

/// The block carrier of a cell.
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

/// A blade holder as the user gives it; what is left out is the default's.
#[derive(Debug, Clone, PartialEq)]
pub struct HolderSettings {
    /// Index of its robot.
    pub robot: usize,
    /// The TCP in the flange's frame (mm); default: the layout's holder style.
    pub tcp: Option<Isometry3<f64>>,
    /// Mass, kg; default [`defaults::HOLDER_KG`].
    pub mass: Option<f64>,
    /// Centre of gravity in the flange's frame, mm; default halfway to the TCP.
    pub cog: Option<[f64; 3]>,
}

/// The cell as the user gives it, in mm; `None` leaves a part to the default cell.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CellSettings {
    /// The robots; default two IRB 2600 facing each other across the blade.
    pub robots: Option<Vec<Robot>>,
    /// The holders of the blade's first and second end (two).
    pub holders: Option<Vec<HolderSettings>>,
    /// A block's frame at the fixture, in the cell's frame; default centred over the
    /// origin on a table of the layout's height.
    pub fixture: Option<Isometry3<f64>>,
    /// The robot that carries the block through the blade, if any.
    pub carrier: Option<Carry>,
    /// Air speed, mm/s; default [`defaults::AIR_SPEED_MM_PER_S`].
    pub air_speed: Option<f64>,
    /// Clearance above the blocks, mm; default [`defaults::CLEARANCE_MM`].
    pub clearance: Option<f64>,
    /// The heat's digital output and its preheat, s.
    pub heat: (String, f64),
    /// Whether flags fail the run.
    pub strict: bool,
}

/// The cell in millimetres, every part given.
#[derive(Debug, Clone, PartialEq)]
pub struct ResolvedCell {
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

impl ResolvedCell {
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

/// A block and the blade poses through it, in the job's coordinates (mm).
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedBlock {
    /// Its number.
    pub block: usize,
    /// Its frame (origin at a corner, axes along its edges).
    pub frame: Isometry3<f64>,
    /// Its size along its own axes.
    pub size: [f64; 3],
    /// The blade's two held ends' tool frames at every pose, in cutting order.
    pub poses: Vec<BladePose>,
    /// The shape planned at every pose (as [`crate::fixture::BlockCut::shapes`]; empty
    /// when unknown).
    pub shapes: Vec<[f64; elastica::sweep::SHAPE_STATIONS]>,
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
/// station (the frame that takes job coordinates to the cell's).
fn placement(
    b: &PlacedBlock,
    p: &BladePose,
    fixture: &Isometry3<f64>,
    station: Option<&Isometry3<f64>>,
) -> Isometry3<f64> {
    let to_block = b.frame.inverse();
    let Some(s) = station else {
        return fixture * to_block;
    };
    let ends = p.map(|e| to_block * e);
    // a pose that holds no blade is refused by the planner; here any frame will do
    crate::carrier::block_pose(s, &ends).unwrap_or(*s) * to_block
}

/// The blade's mean pose in the cell (at the fixture, or at the carrier's `station`): the
/// chords' mean midpoint, their mean horizontal direction, and each end's mean tool
/// orientation (cell frame, mm).
fn mean_pose(
    blocks: &[PlacedBlock],
    fixture: &Isometry3<f64>,
    station: Option<&Isometry3<f64>>,
) -> (Vector3<f64>, Vector3<f64>, [UnitQuaternion<f64>; 2]) {
    let (mut chord, mut mid, mut n) = (Vector3::zeros(), Vector3::zeros(), 0.0);
    let mut q = [Vector4::zeros(); 2];
    for b in blocks {
        for p in &b.poses {
            let to_cell = placement(b, p, fixture, station);
            let e = |k: usize| to_cell * Point3::from(p[k].translation.vector);
            chord += e(1) - e(0);
            mid += (e(0).coords + e(1).coords) * 0.5;
            n += 1.0;
            for (k, acc) in q.iter_mut().enumerate() {
                let c = (to_cell.rotation * p[k].rotation).as_ref().coords;
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

/// End `e`'s holder: as given, the rest from `default` (the style's TCP) and the defaults.
fn hold(h: Option<&HolderSettings>, default: Isometry3<f64>, e: usize) -> Hold {
    let tcp = h.and_then(|h| h.tcp).unwrap_or(default);
    let half = tcp.translation.vector * 0.5;
    Hold {
        robot: h.map_or(e, |h| h.robot),
        tcp,
        mass: h.and_then(|h| h.mass).unwrap_or(defaults::HOLDER_KG),
        cog: h.and_then(|h| h.cog).unwrap_or([half.x, half.y, half.z]),
    }
}

/// The default fixture: a block of `size` (mm) centred over the cell's origin, its floor
/// `table` up, its axes the cell's.
fn default_fixture(size: [f64; 3], table: f64) -> Isometry3<f64> {
    Isometry3::translation(-0.5 * size[0], -0.5 * size[1], table)
}

/// The default robots: two IRB 2600-12/1.65 on the floor (the workshop's IRB 1600 cannot
/// hold every job's blade through its travels within its wrist's ±115°), facing each
/// other along the blade's mean chord `dir` (horizontal), each `standoff` beyond the end
/// of a blade of `blade` whose middle is at `mid`.
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

/// The cell of `settings` (the default where absent, laid out by `layout`) for the
/// blade poses through `blocks`, a blade of `blade_mm`, blocks of at most `block_mm`.
///
/// ```
/// use cell::layout::{defaults, resolve, CellSettings, HolderStyle, Layout, PlacedBlock};
/// use nalgebra::{Isometry3, Vector3};
///
/// // one block 1 m wide, the blade's ends 1.2 m apart along y above it
/// let end = |y: f64| Isometry3::translation(500.0, y, 300.0);
/// let block = PlacedBlock {
///     block: 0,
///     frame: Isometry3::identity(),
///     size: [1000.0, 1000.0, 400.0],
///     poses: vec![[end(-100.0), end(1100.0)]],
///     shapes: Vec::new(),
/// };
/// let layout = Layout { table: 200.0, standoff: 800.0, style: HolderStyle::Facing };
/// let cell = resolve(&CellSettings::default(), &[block], 1200.0, [1000.0, 1000.0, 400.0], layout);
/// assert!(cell.assumed);
/// // the default robots face each other across the blade, 600 + 800 mm from its middle
/// let (a, b) = (cell.robots[0].base.translation.vector, cell.robots[1].base.translation.vector);
/// assert!(((b - a).norm() - 2.0 * (600.0 + 800.0)).abs() < 1e-9);
/// assert!((b - a).normalize().dot(&Vector3::y()) > 1.0 - 1e-12);
/// assert_eq!(cell.clearance, defaults::CLEARANCE_MM);
/// ```
pub fn resolve(
    settings: &CellSettings,
    blocks: &[PlacedBlock],
    blade_mm: f64,
    block_mm: [f64; 3],
    layout: Layout,
) -> ResolvedCell {
    let s = settings;
    let fixture = s
        .fixture
        .unwrap_or_else(|| default_fixture(block_mm, layout.table));
    let carrier = s.carrier.clone();
    let (mid, dir, mean) = mean_pose(blocks, &fixture, carrier.as_ref().map(|k| &k.station));
    let hs = s.holders.as_deref();
    let holders = [0, 1].map(|e| {
        let toward = if e == 0 { dir } else { -dir };
        hold(
            hs.and_then(|h| h.get(e)),
            default_tcp(layout.style, &mean[e], &toward),
            e,
        )
    });
    let robots = match &s.robots {
        Some(r) => r.clone(),
        None => default_robots(&mid, &dir, blade_mm, layout.standoff),
    };
    ResolvedCell {
        assumed: s.robots.is_none() || s.holders.is_none(),
        robots,
        holders,
        fixture,
        carrier,
        air_speed: s.air_speed.unwrap_or(defaults::AIR_SPEED_MM_PER_S),
        clearance: s.clearance.unwrap_or(defaults::CLEARANCE_MM),
        heat: s.heat.clone(),
        strict: s.strict,
    }
}
