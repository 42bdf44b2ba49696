//! The job-file types of the `Compare` task that hold no other task: the `rates:` table
//! and a milling tool. Every default is stated once here ([`RATE_DEFAULTS`](crate::spec::compare::RATE_DEFAULTS)) with its
//! source, in millimetres, and converted by the job's units.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Prices, rates and speeds that turn a process's measured figures into time and cost.
/// Every field may be left out: its default and the default's source are in
/// [`RATE_DEFAULTS`] (README, "Which process?"). Money is in one currency of your choice
/// (the defaults: euros); lengths in job units.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Rates")]
pub struct RatesSpec {
    /// EPS bought, per cubic metre (always m³, whatever the job units).
    #[serde(default)]
    pub eps_per_m3: Option<f64>,
    /// CNC milling machine, per hour.
    #[serde(default)]
    pub milling_per_hour: Option<f64>,
    /// Hot-wire machine (or robot with a wire), per hour.
    #[serde(default)]
    pub wire_per_hour: Option<f64>,
    /// Hot-blade robot cell, per hour.
    #[serde(default)]
    pub blade_per_hour: Option<f64>,
    /// Operator, per hour (present through set-up and machine time).
    #[serde(default)]
    pub operator_per_hour: Option<f64>,
    /// Handling and set-up per block and machine, minutes.
    #[serde(default)]
    pub setup_minutes: Option<f64>,
    /// Milling removal rate (roughing), job units³ per minute.
    #[serde(default)]
    pub removal_rate: Option<f64>,
    /// Milling finishing feed, job units per minute.
    #[serde(default)]
    pub finishing_feed: Option<f64>,
    /// Hot-wire cutting speed, job units per second. Default: each process's own
    /// programs' speed (`wire.speed`).
    #[serde(default)]
    pub wire_speed: Option<f64>,
    /// Hot-blade cutting speed, job units per second. Default: each process's own robot
    /// program's speed (its task's `speed`).
    #[serde(default)]
    pub blade_speed: Option<f64>,
}

/// One rate's default: its field, value (mm-based, per unit of its own), how a length
/// unit enters it, and its source.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RateDefault {
    /// The field in `rates:`.
    pub field: &'static str,
    /// Default value, in millimetres where it has a length.
    pub value: f64,
    /// The power of length in its unit (mm³/min: 3; mm/s: 1; a price: 0).
    pub length_power: i32,
    /// Its unit, mm-based.
    pub unit: &'static str,
    /// Whether no published source was found (the report says so).
    pub assumed: bool,
    /// Where it comes from.
    pub source: &'static str,
}

/// The default of every rate, in the order of [`RatesSpec`]'s fields.
pub const RATE_DEFAULTS: [RateDefault; 10] = [
    RateDefault {
        field: "eps_per_m3",
        value: 60.0,
        length_power: 0,
        unit: "per m³",
        assumed: true,
        source: "assumed: mould-grade EPS blocks delivered; epsole.com (2016) puts the raw material alone at USD 18 per m³ for 15 kg/m³ EPS, a delivered block costs a few times that",
    },
    RateDefault {
        field: "milling_per_hour",
        value: 80.0,
        length_power: 0,
        unit: "per hour",
        assumed: true,
        source: "assumed: a large 3- or 5-axis CNC router with its running costs",
    },
    RateDefault {
        field: "wire_per_hour",
        value: 40.0,
        length_power: 0,
        unit: "per hour",
        assumed: true,
        source: "assumed: a 4-axis hot-wire foam cutter or a robot with a wire bow",
    },
    RateDefault {
        field: "blade_per_hour",
        value: 120.0,
        length_power: 0,
        unit: "per hour",
        assumed: true,
        source: "assumed: a two- or three-robot hot-blade cell (three industrial robots, the seed's 18-axis cell)",
    },
    RateDefault {
        field: "operator_per_hour",
        value: 45.0,
        length_power: 0,
        unit: "per hour",
        assumed: true,
        source: "assumed: one skilled operator",
    },
    RateDefault {
        field: "setup_minutes",
        value: 10.0,
        length_power: 0,
        unit: "minutes per block and machine",
        assumed: true,
        source: "assumed: placing, fixing and zeroing one block on one machine",
    },
    RateDefault {
        field: "removal_rate",
        value: 2.0e6,
        length_power: 3,
        unit: "mm³ per minute",
        assumed: false,
        source: "vendor EPS router settings (ypmfg.com, \"CNC milling foam\": EPS at 150–300 in/min, 0.2–0.5 in deep): 7.6 m/min × 12.7 mm deep × 20 mm wide passes (a 25 mm tool) ≈ 2 L/min",
    },
    RateDefault {
        field: "finishing_feed",
        value: 5000.0,
        length_power: 1,
        unit: "mm per minute",
        assumed: false,
        source: "vendor EPS router feeds (ypmfg.com, \"CNC milling foam\": EPS at 150–300 in/min, 3.8–7.6 m/min); the middle, 5 m/min, for a ball-nose finishing pass",
    },
    RateDefault {
        field: "wire_speed",
        value: 5.0,
        length_power: 1,
        unit: "mm per second",
        assumed: true,
        source: "left out: each wire process's own programs' speed (`wire.speed`, default 300 mm/min); this value only where a program gives none (assumed: that default)",
    },
    RateDefault {
        field: "blade_speed",
        value: 7.0,
        length_power: 1,
        unit: "mm per second",
        assumed: false,
        source: "left out: each blade process's own robot program's speed (its task's `speed`, default 7 mm/s: the seed, \"Robotic Hot-Blade Cutting\", good surface quality at 7 mm/s in a 600 mm block)",
    },
];

impl RatesSpec {
    /// The values as written, in the order of [`RATE_DEFAULTS`].
    pub fn values(&self) -> [Option<f64>; 10] {
        [
            self.eps_per_m3,
            self.milling_per_hour,
            self.wire_per_hour,
            self.blade_per_hour,
            self.operator_per_hour,
            self.setup_minutes,
            self.removal_rate,
            self.finishing_feed,
            self.wire_speed,
            self.blade_speed,
        ]
    }
}

/// A milling tool and how it finishes: a ball-nose tool of `diameter` stepping `stepover`
/// between passes (the scallop height follows from the two). Lengths in job units.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, rename = "Tool")]
pub struct ToolSpec {
    /// Ball-nose tool diameter. Default: 20 mm.
    #[serde(default)]
    pub diameter: Option<f64>,
    /// Distance between finishing passes. Default: 4 mm.
    #[serde(default)]
    pub stepover: Option<f64>,
    /// Finishing feed, job units per minute. Default: `rates.finishing_feed`.
    #[serde(default)]
    pub feed: Option<f64>,
    /// Removal rate, job units³ per minute. Default: `rates.removal_rate`.
    #[serde(default)]
    pub removal_rate: Option<f64>,
}

/// Default ball-nose tool diameter, mm.
pub const TOOL_DIAMETER_MM: f64 = 20.0;
/// Default finishing stepover, mm.
pub const STEPOVER_MM: f64 = 4.0;
