//! `cell: Cell(..)`: the robot cell of the hot blade — the robots (OPW models, joint
//! limits, base frames), the blade holders (tool frames, loads), where a block stands
//! while it is cut, the heat signal and the air speed. Every length is in the job's units
//! (custom OPW parameters too); angles in degrees; masses in kg.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The robot cell that cuts the blocks with the hot blade. Blocks are cut one at a time,
/// at a fixture or carried by a third robot: after each block the blade retreats, rises in
/// its cutting plane above the block (or the carrier lowers the block under it), and the
/// program waits for the operator to change blocks.
///
/// Without `cell:` the default cell is used: two IRB 2600-12/1.65 facing each other across
/// the fixture, laid out by the rule in the README ("The robot cell"), with holders 150 mm
/// long. Its placement and tool data are then assumed, and the programs say so.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Cell")]
pub struct CellSpec {
    /// The robots, `[Robot(..), ..]`; the first two are the tasks `T_ROB1` and `T_ROB2`.
    /// Default: the two IRB 2600 of the default cell.
    #[serde(default)]
    pub robots: Option<Vec<RobotSpec>>,
    /// The holders of the blade's first and second end (exactly two). Default: robot 0
    /// holds the first end, robot 1 the second, each 150 mm in front of its flange, 2 kg.
    #[serde(default)]
    pub blade_holders: Option<Vec<HolderSpec>>,
    /// A third robot that carries the block through the blade (the pilot cell of
    /// "Robotic Hot-Blade Cutting" §4). Default: none, blocks stand at the fixture.
    /// With a carrier, `robots` lists all three and `fixture` is left out.
    #[serde(default)]
    pub block_carrier: Option<CarrierSpec>,
    /// Where a block stands while it is cut: its frame (min corner; axes along the cut,
    /// across it, up) in the cell's frame. Default: the block centred over the cell's
    /// origin across and along the cut, its floor 200 mm up (with the default robots, the
    /// first of 200, 0, 400, 600 mm that the robots reach well).
    #[serde(default)]
    pub fixture: Option<FrameSpec>,
    /// The heat: output signal and preheat time.
    #[serde(default)]
    pub heat: HeatSpec,
    /// Speed of the blade's ends through the air, job units per second (> 0). Default:
    /// 100 mm/s.
    #[serde(default)]
    pub air_speed: Option<f64>,
    /// Height of the whole blade above the blocks while it moves between them (> 0).
    /// Default: 100 mm.
    #[serde(default)]
    pub clearance: Option<f64>,
    /// Whether a pose out of reach, a configuration change or a joint jump — and, for
    /// `Design`, a blade whose part outside its piece runs into what a block keeps or
    /// whose held end lies inside a block — fails the run (no robot files are written).
    /// Default: `false`, they are flagged in the report.
    #[serde(default)]
    pub strict: bool,
}

/// A frame: an origin and a rotation given as ABB's Euler angles (ZYX: about z by
/// `rotation.0`, then about the new y by `.1`, then about the new x by `.2`), degrees.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Frame")]
pub struct FrameSpec {
    /// Origin, job units.
    pub origin: (f64, f64, f64),
    /// Euler angles ZYX, degrees. Default: `(0, 0, 0)`.
    #[serde(default)]
    pub rotation: (f64, f64, f64),
}

/// A robot of the cell.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Robot")]
pub struct RobotSpec {
    /// Its kinematic model.
    pub model: ModelSpec,
    /// Its base frame in the cell's frame: axis 1 at the origin, z up along axis 1, x
    /// forward (the direction the arm points at all joints zero).
    pub base: FrameSpec,
}

/// A robot's kinematic model: a built-in ABB arm or custom OPW parameters.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum ModelSpec {
    /// ABB IRB 1600-6/1.45 (axis 2 −63…+110°, axis 3 −235…+55°: where sources differ,
    /// the narrower range).
    Irb1600,
    /// ABB IRB 2600-12/1.65.
    Irb2600,
    /// ABB IRB 4600-60/2.05.
    Irb4600,
    /// Any 6-axis arm with an ortho-parallel base and a spherical wrist, by its OPW
    /// parameters (Brandstötter et al. 2014) in job units.
    Custom(CustomModel),
}

/// OPW parameters and joint limits of a custom arm.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Custom")]
pub struct CustomModel {
    /// Name in the report and the program's comments.
    pub name: String,
    /// Offset of axis 2 from axis 1, forward.
    pub a1: f64,
    /// Offset of the forearm from axis 3, perpendicular to it (negative on ABB arms).
    pub a2: f64,
    /// Lateral offset of the arm. Default: 0.
    #[serde(default)]
    pub b: f64,
    /// Height of axis 2 above the base.
    pub c1: f64,
    /// Length of the upper arm (axis 2 to axis 3).
    pub c2: f64,
    /// Length of the forearm (axis 3 to the wrist centre).
    pub c3: f64,
    /// Wrist centre to flange.
    pub c4: f64,
    /// Joint offsets from the OPW zero (arm straight up) to the maker's zero, degrees.
    /// Default: ABB's `[0, 0, -90, 0, 0, 0]`.
    #[serde(default)]
    pub offsets: Option<Vec<f64>>,
    /// Direction of each joint against the OPW convention, `[1, 1, 1, 1, 1, 1]` with −1
    /// for a joint that turns the other way. Default: all 1.
    #[serde(default)]
    pub signs: Option<Vec<i8>>,
    /// Joint limits `[(min, max), ..]` of axes 1–6, degrees.
    pub limits: Vec<(f64, f64)>,
}

/// What holds one end of the blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Holder")]
pub struct HolderSpec {
    /// Index of the robot in `robots`.
    pub robot: usize,
    /// The blade's end (the TCP) in the flange's frame: x along the blade's tangent there
    /// (from the first end to the second), z along the cutting plane's normal. Default:
    /// 150 mm along the flange's z (a bracket hanging from the flange), turned so that at
    /// the job's mean blade pose the flange points straight down, its x from the robot
    /// towards the blade.
    #[serde(default)]
    pub tcp: Option<FrameSpec>,
    /// Mass of the holder with its half of the blade, kg (> 0). Default: 2 kg.
    #[serde(default)]
    pub mass: Option<f64>,
    /// Its centre of gravity in the flange's frame. Default: halfway to the TCP.
    #[serde(default)]
    pub cog: Option<(f64, f64, f64)>,
}

/// A robot that carries the block through the blade, which stays at a station (the
/// pilot cell of "Robotic Hot-Blade Cutting" §4): `Carrier(robot, grip, mass, station)`.
/// The cell then has three robots and no fixture; the blade's robots move in a work
/// object that the carrier holds (RAPID coordinated motion).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Carrier")]
pub struct CarrierSpec {
    /// Index of the robot in `robots` (not one that holds the blade).
    pub robot: usize,
    /// The block's frame (min corner; axes along the cut, across it, up) in the carrier's
    /// flange frame: where the gripper holds the block.
    pub grip: FrameSpec,
    /// Mass of the gripper with a block, kg (> 0); its centre of gravity is taken at the
    /// middle of the largest block.
    pub mass: f64,
    /// Where the blade cuts, in the cell's frame: origin at the blade's chord midpoint, x
    /// along the chord (from the first end to the second), z the cutting plane's normal
    /// (the way the blade advances through the block).
    pub station: FrameSpec,
}

/// The heat of the blade.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Heat")]
pub struct HeatSpec {
    /// The digital output that heats the blade (a RAPID identifier). Default:
    /// `doBladeHeat`.
    #[serde(default = "default_signal")]
    pub signal: String,
    /// Wait after heat on, before the blade enters the block, seconds (0–600). Default:
    /// 2 s.
    #[serde(default = "default_preheat")]
    pub preheat_s: f64,
}

impl Default for HeatSpec {
    fn default() -> Self {
        HeatSpec {
            signal: default_signal(),
            preheat_s: default_preheat(),
        }
    }
}

fn default_signal() -> String {
    "doBladeHeat".into()
}

fn default_preheat() -> f64 {
    2.0
}
