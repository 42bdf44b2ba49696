//! The job's `wire` as the algorithm's parameters: the path settings
//! ([`ruled::wire::WireParams`]) and the controller ([`ruled::wire::Machine`]), and the
//! checks of the fields that need no geometry.

use ruled::wire::{Machine, WireParams};

use crate::context::{Context, JobFields};
use crate::error::JobError;
use crate::spec::{defaults, FluidNcAxes, MachineSpec, WireSpec};

/// The wire machine's path settings of a job, in job units (`None` without `wire`;
/// `steps` left 0 for the task to set).
pub fn wire_params(job: &Context) -> Option<WireParams> {
    let w = job.wire.as_ref()?;
    let unit = job.per_mm();
    let lead = w.lead.unwrap_or(defaults::WIRE_LEAD_MM * unit);
    Some(WireParams {
        tower_distance: w.tower_distance,
        kerf: w.kerf.unwrap_or(0.0),
        kerf_table: w.kerf_table.clone().unwrap_or_default(),
        speed: w.speed.unwrap_or(defaults::WIRE_SPEED_MM_PER_MIN * unit),
        lead,
        clearance: w.clearance.unwrap_or(defaults::WIRE_CLEARANCE_MM * unit),
        origin: w.origin.map_or([lead, 0.0], |o| [o.0, o.1]),
        steps: 0,
        mm_per_unit: 1.0 / unit,
    })
}

/// The controller of a job's wire, lengths converted to millimetres (`None` without
/// `wire`). A `Custom` profile with other than four axis letters gets `?` for the missing
/// ones, which [`Machine::check`] rejects (validation names the field first).
pub fn machine(job: &Context) -> Option<Machine> {
    let w = job.wire.as_ref()?;
    let mm = 1.0 / job.per_mm();
    let mut m = match &w.machine {
        MachineSpec::LinuxCncXyuv => Machine::linuxcnc_xyuv(),
        MachineSpec::Grbl4Axis => Machine::grbl_4axis(),
        MachineSpec::FluidNc(a) => Machine::fluidnc(*a == FluidNcAxes::XYZA),
        MachineSpec::Mach3 => Machine::mach3(),
        MachineSpec::Custom {
            axes,
            header,
            footer,
            heat_on,
            heat_off,
            preheat_s,
            feed_mode,
            decimals,
            percent,
            end,
            dwell,
        } => {
            let mut letters = axes.chars().map(|c| c.to_ascii_uppercase());
            Machine {
                profile: "Custom".into(),
                axes: std::array::from_fn(|_| letters.next().unwrap_or('?')),
                percent: *percent,
                header: header.clone(),
                footer: footer.clone(),
                end: end.clone(),
                heat_on: heat_on.clone(),
                heat_off: heat_off.clone(),
                preheat_s: preheat_s.unwrap_or(defaults::WIRE_PREHEAT_S),
                dwell: *dwell,
                feed: *feed_mode,
                decimals: *decimals as usize,
                notes: Vec::new(),
                ..Machine::linuxcnc_xyuv()
            }
        }
    };
    m.power = w.power.unwrap_or(defaults::WIRE_POWER);
    if let Some(p) = w.preheat_s {
        m.preheat_s = p;
    }
    m.travel = w.travel.as_ref().map(|t| {
        [
            t.along,
            t.up,
            t.b_along.unwrap_or(t.along),
            t.b_up.unwrap_or(t.up),
        ]
        .map(|(lo, hi)| (lo * mm, hi * mm))
    });
    if let Some(v) = w.max_speed {
        m.max_speed = v * mm;
    }
    Some(m)
}

/// The JSON pointer of a [`ruled::wire`] setting's name.
pub fn pointer(name: &str) -> String {
    match name {
        "axes" | "header" | "footer" | "heat_on" | "heat_off" | "decimals" | "end" => {
            "/wire/machine".into()
        }
        "mm_per_unit" => "/units".into(),
        other => format!("/wire/{other}"),
    }
}

/// The checks of `wire` that need neither the block nor the units: signs, the kerf given
/// once, a `Custom` profile's axes. The dialect's own checks ([`Machine::check`]) and the
/// machine's fit come with the block, in the task's estimate.
pub fn check(job: &JobFields<'_>, w: &WireSpec, errors: &mut Vec<JobError>) {
    let positive = |v: Option<f64>| v.is_none_or(|v| v.is_finite() && v > 0.0);
    let mut bad = |field: &str, message: String| {
        errors.push(job.error(&format!("/wire/{field}"), message));
    };
    if !(w.tower_distance.is_finite() && w.tower_distance > 0.0) {
        bad("tower_distance", "tower_distance must be positive".into());
    }
    match (w.kerf, &w.kerf_table) {
        (Some(k), None) if !(k.is_finite() && k >= 0.0) => {
            bad("kerf", "kerf must be at least 0".into());
        }
        (Some(_), None) => {}
        (None, Some(t)) if t.is_empty() => {
            bad("kerf_table", "kerf_table needs at least one row".into());
        }
        (None, Some(_)) => {}
        (Some(_), Some(_)) => bad(
            "kerf",
            "give kerf or kerf_table, not both (the table sets the kerf at every speed)".into(),
        ),
        (None, None) => bad(
            "kerf",
            "the wire needs its kerf: `kerf: 1.5` or `kerf_table: [(speed, kerf), ..]`".into(),
        ),
    }
    if !positive(w.speed) {
        bad("speed", "speed must be positive".into());
    }
    if !w.lead.is_none_or(|v| v.is_finite() && v >= 0.0) {
        bad("lead", "lead must be at least 0".into());
    }
    if !positive(w.clearance) {
        bad("clearance", "clearance must be positive".into());
    }
    if !positive(w.max_speed) {
        bad("max_speed", "max_speed must be positive".into());
    }
    if let MachineSpec::Custom {
        axes, preheat_s, ..
    } = &w.machine
    {
        if axes.chars().count() != 4 {
            bad(
                "machine",
                format!("Custom axes {axes:?} must be four letters: tower A along, A up, tower B along, B up, e.g. \"XYUV\""),
            );
        }
        if preheat_s.is_some() && w.preheat_s.is_some() {
            bad(
                "preheat_s",
                "give preheat_s once: in Custom(..) or in Wire(..)".into(),
            );
        }
    }
}
