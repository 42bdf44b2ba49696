//! `wire: Wire(..)`: a 4-axis hot-wire machine, its controller profile, travel, heat and
//! kerf. Every length is in the job's units; programs are written in millimetres.

use ruled::wire::{DwellUnit, FeedMode};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A 4-axis hot-wire machine: two towers `tower_distance` apart across the block, each
/// moving the wire's end along the cut and up. Tower A stands on the block's side towards
/// −across (the cutting direction turned 90° clockwise seen from above), tower B towards
/// +across.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Wire")]
pub struct WireSpec {
    /// The controller profile: `LinuxCncXyuv`, `Grbl4Axis`, `FluidNc(XYZA)`,
    /// `FluidNc(XYAB)`, `Mach3` or `Custom(..)`. Default: `LinuxCncXyuv`.
    #[serde(default)]
    pub machine: MachineSpec,
    /// Distance between the tower planes (> the block's width across the cut).
    #[schemars(extend("exclusiveMinimum" = 0))]
    pub tower_distance: f64,
    /// Kerf width (≥ 0): the wire's cut is offset by half of it into the removed material.
    /// Required unless `kerf_table` is given.
    #[serde(default)]
    #[schemars(range(min = 0))]
    pub kerf: Option<f64>,
    /// Kerf by wire speed, `[(speed, kerf), ..]` with speeds increasing (job units per
    /// minute, job units), 1–64 rows: interpolated linearly, held beyond the ends. Each
    /// side of the block gets the kerf of the wire's speed there (a tapered cut's slower
    /// side burns wider). Default: none (`kerf` everywhere).
    #[serde(default)]
    pub kerf_table: Option<Vec<(f64, f64)>>,
    /// Cutting speed: the speed of the faster tower's wire end, job units per minute
    /// (> 0). Default: 300 mm/min.
    #[serde(default)]
    pub speed: Option<f64>,
    /// Lead-in and lead-out along the cut outside the block (≥ 0). Default: 20 mm.
    #[serde(default)]
    pub lead: Option<f64>,
    /// Clearance above the block for rapid moves (> 0). Default: 50 mm.
    #[serde(default)]
    pub clearance: Option<f64>,
    /// Machine coordinates `(along, up)` of the block's start corner at its floor, job
    /// units: where the block stands on the machine. Default: `(lead, 0)`, so the lead-in
    /// starts at along = 0 and the floor is up = 0.
    #[serde(default)]
    pub origin: Option<(f64, f64)>,
    /// The machine's travel, job units. Every program is checked against it before it is
    /// written. Default: not checked.
    #[serde(default)]
    pub travel: Option<TravelSpec>,
    /// Fastest feed of the machine's axes, job units per minute: `speed` must not exceed
    /// it. Default: 60 000 mm/min.
    #[serde(default)]
    pub max_speed: Option<f64>,
    /// The value of `{power}` in the heat-on command (`M3 S{power}`): spindle or PWM units
    /// as the controller is set up. Default: 1000 (GRBL's and FluidNC's default maximum,
    /// full output; the wire's supply sets its temperature).
    #[serde(default)]
    pub power: Option<f64>,
    /// Dwell after heat on, before the lead-in, seconds (0–600). Default: 2 s (a
    /// `Custom` profile may give its own).
    #[serde(default)]
    pub preheat_s: Option<f64>,
}

/// A controller profile: axis letters, setup lines, heat commands, feed and number
/// format. The built-in ones are documented in the README with their sources.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum MachineSpec {
    /// LinuxCNC 2.9 set up like its `sim/axis/foam` sample (`trivkins coordinates=xyuv`):
    /// tower A on X/Y, tower B on U/V; `%` wrappers, `G17 G21 G90 G94 G61 G54`, `G93`,
    /// heat `M3 S{power}` / `M5`, `M2`.
    #[default]
    LinuxCncXyuv,
    /// A 4-axis GRBL 1.1 fork (grbl-Mega-5X): tower A on X/Y, tower B on Z/A; no `%`,
    /// `G17 G21 G90 G94 G61`, `G93`, heat `M3 S{power}` / `M5` with `$32=0`, `M2`.
    Grbl4Axis,
    /// FluidNC with four linear axes: tower B on Z/A (`FluidNc(XYZA)`) or A/B
    /// (`FluidNc(XYAB)`); otherwise as `Grbl4Axis`.
    FluidNc(FluidNcAxes),
    /// Mach3 with a linear fourth axis: tower A on X/Y, tower B on Z/A; `G17 G21 G90 G94
    /// G61`, `G93`, heat `M3` / `M5`, `G4 P` in seconds, `M30`.
    Mach3,
    /// Any controller: write `Custom(axes: "XYUV", header: ["G17 G21 G90 G94"], heat_on:
    /// "M3 S{power}", heat_off: "M5", preheat_s: 2.0, feed_mode: InverseTime, decimals:
    /// 3)`.
    Custom {
        /// Four different letters of `XYZABCUVW`: tower A along, tower A up, tower B
        /// along, tower B up.
        #[schemars(length(min = 4, max = 4))]
        axes: String,
        /// Setup lines after the header comments, at most 70 characters each: modal
        /// words that cannot move the machine or change its offsets or feed mode (`G17
        /// G21 G40 G49 G54`–`G59.3 G61 G61.1 G64 G90 G94`, `P`/`Q` with `G64`), comments
        /// and the heat-off words; they must set `G21` and `G90` (the program is in
        /// absolute millimetres). Default: `["G17 G21 G90 G94 G61"]`.
        #[serde(default = "default_header")]
        header: Vec<String>,
        /// Lines after the last move, before `end`: the same words as `header` (no
        /// moves: every program already ends with the towers raised). Default: none.
        #[serde(default)]
        footer: Vec<String>,
        /// Heat on, `{power}` replaced by `wire.power`: one switch-on of one output and
        /// nothing else — `M3`/`M4` with an optional `S`, `M7`/`M8`, `M62`/`M64 P<n>` or
        /// `M67`/`M68 E<n> Q<v>`. Default: `M3 S{power}`.
        #[serde(default = "default_heat_on")]
        heat_on: String,
        /// Heat off: the switch-off of what `heat_on` switches on — `M5`, `M9`,
        /// `M63`/`M65 P<n>` (the same `n`) or `M67`/`M68 E<n> Q0`. Default: `M5`.
        #[serde(default = "default_heat_off")]
        heat_off: String,
        /// Preheat dwell, seconds (0–600). Default: `wire.preheat_s`, else 2 s.
        #[serde(default)]
        preheat_s: Option<f64>,
        /// `InverseTime` (`G93`); `UnitsPerMinute` (`G94`, `F` along all four axes, as
        /// GRBL and FluidNC read it); or `UnitsPerMinuteXyz` (`G94`, `F` along X/Y/Z when
        /// they move, else U/V/W, else A/B/C, as LinuxCNC reads it). `F` is computed per
        /// move. Default: `InverseTime`.
        #[serde(default)]
        feed_mode: FeedMode,
        /// Decimals of coordinates, 2–6. Default: 4.
        #[serde(default = "default_decimals")]
        #[schemars(range(min = 2, max = 6))]
        decimals: u32,
        /// Wrap the program in `%` lines. Default: `false`.
        #[serde(default)]
        percent: bool,
        /// The program end: `M2` or `M30`, with modal words as `header` at most.
        /// Default: `M2`.
        #[serde(default = "default_end")]
        end: String,
        /// The unit of `G4 P`: `Seconds` or `Milliseconds`. Default: `Seconds`.
        #[serde(default)]
        dwell: DwellUnit,
    },
}

/// The axes of a FluidNC foam cutter's tower B.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum FluidNcAxes {
    /// Tower B on Z (along) and A (up).
    XYZA,
    /// Tower B on A (along) and B (up).
    XYAB,
}

/// The travel of the towers' axes, `(min, max)` in the machine's coordinates (job units).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Travel")]
pub struct TravelSpec {
    /// Along the cut, both towers (tower A's only when `b_along` is given).
    pub along: (f64, f64),
    /// Up, both towers (tower A's only when `b_up` is given).
    pub up: (f64, f64),
    /// Tower B along the cut, when it differs. Default: `along`.
    #[serde(default)]
    pub b_along: Option<(f64, f64)>,
    /// Tower B up, when it differs. Default: `up`.
    #[serde(default)]
    pub b_up: Option<(f64, f64)>,
}

fn default_header() -> Vec<String> {
    vec!["G17 G21 G90 G94 G61".into()]
}
fn default_heat_on() -> String {
    "M3 S{power}".into()
}
fn default_heat_off() -> String {
    "M5".into()
}
fn default_decimals() -> u32 {
    4
}
fn default_end() -> String {
    "M2".into()
}

impl MachineSpec {
    /// The profile's name as written in job files.
    pub fn name(&self) -> &'static str {
        match self {
            Self::LinuxCncXyuv => "LinuxCncXyuv",
            Self::Grbl4Axis => "Grbl4Axis",
            Self::FluidNc(_) => "FluidNc",
            Self::Mach3 => "Mach3",
            Self::Custom { .. } => "Custom",
        }
    }
}
