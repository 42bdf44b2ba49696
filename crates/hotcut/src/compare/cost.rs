//! From a process's measured figures to time and cost, and how the ranking of the
//! processes answers each rate's change: plain arithmetic on the rates, no geometry.
//!
//! - Material: the EPS bought (m³) × `eps_per_m3`.
//! - Machine time: heated path ÷ `wire_speed` or `blade_speed`; milling volume ÷ removal
//!   rate + milled area ÷ (stepover × feed).
//! - Set-up: `setup_minutes` per block and per machine the block goes to.
//! - Cost: machine hours × the machine's rate; labour: the operator through set-up and
//!   machine time.

use schemars::JsonSchema;
use serde::Serialize;

use crate::process::{Deviation, ProcessFigures};
use crate::spec::compare::RATE_DEFAULTS;

/// Index of each rate in [`Rates::values`] (the order of [`RATE_DEFAULTS`]).
pub mod rate {
    /// EPS price per m³.
    pub const EPS: usize = 0;
    /// Milling machine per hour.
    pub const MILLING: usize = 1;
    /// Wire machine per hour.
    pub const WIRE: usize = 2;
    /// Blade cell per hour.
    pub const BLADE: usize = 3;
    /// Operator per hour.
    pub const OPERATOR: usize = 4;
    /// Set-up minutes per block and machine.
    pub const SETUP: usize = 5;
    /// Removal rate, job units³ per minute.
    pub const REMOVAL: usize = 6;
    /// Finishing feed, job units per minute.
    pub const FEED: usize = 7;
    /// Wire speed, job units per second.
    pub const WIRE_SPEED: usize = 8;
    /// Blade speed, job units per second.
    pub const BLADE_SPEED: usize = 9;
}

/// The rates of a run, in job units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rates {
    /// Values in the order of [`RATE_DEFAULTS`].
    pub values: [f64; 10],
    /// The defaults, converted (what `values` holds for a rate the job leaves out, until
    /// the sensitivity scales it).
    pub nominal: [f64; 10],
    /// Whether the job set each rate.
    pub written: [bool; 10],
    /// Cubic metres per cubic job unit.
    pub m3_per_unit3: f64,
}

impl Rates {
    /// The rates as written, defaults (converted by `per_mm`, job units per mm) where
    /// left out.
    pub fn resolve(written: [Option<f64>; 10], per_mm: f64) -> Self {
        let mut values = [0.0; 10];
        let mut nominal = [0.0; 10];
        for (k, d) in RATE_DEFAULTS.iter().enumerate() {
            nominal[k] = d.value * per_mm.powi(d.length_power);
            values[k] = written[k].unwrap_or(nominal[k]);
        }
        let m = 1e-3 / per_mm;
        Self {
            values,
            nominal,
            written: written.map(|w| w.is_some()),
            m3_per_unit3: m * m * m,
        }
    }

    /// The cutting speed of a process whose programs cut at `own` (0: none given): the
    /// job's rate when it sets one, else the programs' own speed (scaled as the
    /// sensitivity scales the rate), else the rate's default.
    pub fn speed(&self, k: usize, own: f64) -> f64 {
        if !self.written[k] && own > 0.0 {
            own * self.values[k] / self.nominal[k]
        } else {
            self.values[k]
        }
    }

    /// These rates with rate `k` multiplied by `factor`.
    pub fn scaled(&self, k: usize, factor: f64) -> Self {
        let mut r = *self;
        r.values[k] *= factor;
        r
    }
}

/// A ball-nose milling tool, job units (feeds per minute; `None`: the rates').
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Tool {
    /// Diameter.
    pub diameter: f64,
    /// Stepover between finishing passes.
    pub stepover: f64,
    /// Finishing feed per minute, when the process sets its own.
    pub feed: Option<f64>,
    /// Removal rate per minute, when the process sets its own.
    pub removal_rate: Option<f64>,
}

/// The scallop a ball-nose tool leaves between passes on a flat surface: its height
/// `r − √(r² − (s/2)²)` and its RMS over one stepover, job units.
pub fn scallop(tool: &Tool) -> Deviation {
    let r = 0.5 * tool.diameter;
    let half = (0.5 * tool.stepover).min(r);
    let depth = |x: f64| r - (r * r - x * x).max(0.0).sqrt();
    // midpoint rule over one stepover (the profile is smooth and even: 256 cells give
    // the RMS to ~1e-5 of itself)
    let n = 256;
    let mut sum = 0.0;
    for i in 0..n {
        let x = -half + (i as f64 + 0.5) * (2.0 * half / n as f64);
        sum += depth(x).powi(2);
    }
    Deviation {
        rms: (sum / n as f64).sqrt(),
        max: depth(half),
    }
}

/// The hours a process takes, per machine.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Hours {
    /// Hot wire cutting.
    pub wire: f64,
    /// Hot blade cutting.
    pub blade: f64,
    /// Milling: roughing (volume ÷ removal rate).
    pub roughing: f64,
    /// Milling: finishing (area ÷ (stepover × feed)).
    pub finishing: f64,
    /// Handling and set-up.
    pub setup: f64,
    /// Every machine's time and the set-up.
    pub total: f64,
}

/// What a process costs, split.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Cost {
    /// EPS bought.
    pub material: f64,
    /// Machine hours × machine rates.
    pub machine: f64,
    /// The operator's hours.
    pub labour: f64,
    /// The sum.
    pub total: f64,
}

/// The hours of a process with `figures`, milled with `tool` (processes that mill).
pub fn hours(f: &ProcessFigures, tool: Option<&Tool>, r: &Rates) -> Hours {
    let v = &r.values;
    let mut h = Hours::default();
    if f.cut_length > 0.0 {
        let speed = match f.cutter {
            crate::process::Cutter::Blade => r.speed(rate::BLADE_SPEED, f.cut_speed),
            _ => r.speed(rate::WIRE_SPEED, f.cut_speed),
        };
        let t = (f.cut_length / speed + f.dwell_s) / 3600.0;
        match f.cutter {
            crate::process::Cutter::Blade => h.blade = t,
            _ => h.wire = t,
        }
    }
    let mut setups = f.setups;
    if let Some(tool) = tool {
        // a tool's own feed and removal rate are scaled as the rates are (sensitivity)
        let own = |k: usize, x: Option<f64>| x.map_or(v[k], |x| x * v[k] / r.nominal[k]);
        let removal = own(rate::REMOVAL, tool.removal_rate);
        let feed = own(rate::FEED, tool.feed);
        h.roughing = f.milling_volume / removal / 60.0;
        h.finishing = f.milled_area / (tool.stepover * feed) / 60.0;
        // every block mounted on the milling machine once
        setups += f.blocks;
    }
    h.setup = setups as f64 * v[rate::SETUP] / 60.0;
    h.total = h.wire + h.blade + h.roughing + h.finishing + h.setup;
    h
}

/// The cost of a process with `figures` taking `hours`.
pub fn cost(f: &ProcessFigures, h: &Hours, r: &Rates) -> Cost {
    let v = &r.values;
    let material = f.stock_volume * r.m3_per_unit3 * v[rate::EPS];
    let machine = h.wire * v[rate::WIRE]
        + h.blade * v[rate::BLADE]
        + (h.roughing + h.finishing) * v[rate::MILLING];
    let labour = h.total * v[rate::OPERATOR];
    Cost {
        material,
        machine,
        labour,
        total: material + machine + labour,
    }
}

/// A process as the ranking sees it: its figures and tool (feasible processes only).
#[derive(Debug, Clone, Copy)]
pub struct Costed<'a> {
    /// Its figures.
    pub figures: &'a ProcessFigures,
    /// Its milling tool.
    pub tool: Option<&'a Tool>,
}

/// Indices of `processes` cheapest first at rates `r`; costs equal to 9 significant
/// digits are ties, which keep the listed order (sums in another order differ in the
/// last bits).
pub fn ranking(processes: &[Costed<'_>], r: &Rates) -> Vec<usize> {
    let totals: Vec<f64> = processes
        .iter()
        .map(|p| sig9(cost(p.figures, &hours(p.figures, p.tool, r), r).total))
        .collect();
    let mut order: Vec<usize> = (0..processes.len()).collect();
    order.sort_by(|&a, &b| totals[a].total_cmp(&totals[b]).then(a.cmp(&b)));
    order
}

/// `v` rounded to 9 significant digits.
fn sig9(v: f64) -> f64 {
    if v == 0.0 || !v.is_finite() {
        return v;
    }
    let e = 8 - v.abs().log10().floor() as i32;
    let f = 10f64.powi(e.clamp(-300, 300));
    (v * f).round() / f
}

/// Factors tried when looking for the change of one rate that flips the winner: a log
/// grid from 1/`FLIP_RANGE` to `FLIP_RANGE`.
pub const FLIP_RANGE: f64 = 100.0;
/// Steps of that grid on each side of 1.
const FLIP_STEPS: usize = 200;
/// Bisection steps that refine a flip found on the grid.
const FLIP_BISECTIONS: usize = 40;

/// The factors nearest to 1, below and above, by which rate `k` must be multiplied for
/// the cheapest process to change (`None`: not within 1/100–100×).
pub fn flip_factors(processes: &[Costed<'_>], r: &Rates, k: usize) -> (Option<f64>, Option<f64>) {
    let winner = |f: f64| ranking(processes, &r.scaled(k, f)).first().copied();
    let w0 = winner(1.0);
    let search = |up: bool| -> Option<f64> {
        let step = FLIP_RANGE.ln() / FLIP_STEPS as f64;
        let at = |i: usize| (if up { 1.0 } else { -1.0 } * step * i as f64).exp();
        let mut prev: f64 = 1.0;
        for i in 1..=FLIP_STEPS {
            let f = at(i);
            if winner(f) != w0 {
                // bisect in log between prev (same winner) and f (another)
                let (mut a, mut b) = (prev.ln(), f.ln());
                for _ in 0..FLIP_BISECTIONS {
                    let m = 0.5 * (a + b);
                    if winner(m.exp()) == w0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                return Some(b.exp());
            }
            prev = f;
        }
        None
    };
    (search(false), search(true))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::process::Cutter;

    fn figures(cutter: Cutter, cut: f64, mill: f64, area: f64) -> ProcessFigures {
        ProcessFigures {
            why_not: None,
            blocks: 2,
            stock_volume: 1e9,
            part_volume: 5e8,
            milling_volume: mill,
            milled_area: area,
            cutter,
            cut_length: cut,
            cut_speed: 0.0,
            dwell_s: 0.0,
            setups: if cut > 0.0 { 2 } else { 0 },
            programs: 1,
            deviation: None,
        }
    }

    #[test]
    fn scallop_matches_the_circle() {
        // r = 10, s = 4: h = 10 − √96
        let d = scallop(&Tool {
            diameter: 20.0,
            stepover: 4.0,
            feed: None,
            removal_rate: None,
        });
        assert!((d.max - (10.0 - 96f64.sqrt())).abs() < 1e-12);
        // for s ≪ r the profile is x²/2r: RMS = s²/(√320 r)
        let small = scallop(&Tool {
            diameter: 2000.0,
            stepover: 4.0,
            feed: None,
            removal_rate: None,
        });
        let want = 16.0 / (320f64.sqrt() * 1000.0);
        assert!(
            (small.rms - want).abs() < 1e-4 * want,
            "{} {want}",
            small.rms
        );
    }

    #[test]
    fn hours_and_cost_add_up_exactly() {
        let r = Rates::resolve([None; 10], 1.0);
        let f = figures(Cutter::Wire, 36_000.0, 2.0e6 * 60.0, 0.0);
        let tool = Tool {
            diameter: 20.0,
            stepover: 4.0,
            feed: None,
            removal_rate: None,
        };
        let h = hours(&f, Some(&tool), &r);
        // 36 m at 5 mm/s: 2 h; 120 L at 2 L/min: 1 h; 2 blocks × 2 machines × 10 min
        assert!((h.wire - 2.0).abs() < 1e-12);
        assert!((h.roughing - 1.0).abs() < 1e-12);
        assert!((h.setup - 40.0 / 60.0).abs() < 1e-12);
        let c = cost(&f, &h, &r);
        // 1 m³ at 60; wire 2 h × 40, milling 1 h × 80; operator 3.667 h × 45
        assert!((c.material - 60.0).abs() < 1e-9);
        assert!((c.machine - 160.0).abs() < 1e-9);
        assert!((c.labour - h.total * 45.0).abs() < 1e-9);
        assert!((c.total - (c.material + c.machine + c.labour)).abs() < 1e-9);
    }

    #[test]
    fn costs_do_not_depend_on_the_unit() {
        let mm = Rates::resolve([None; 10], 1.0);
        let m = Rates::resolve([None; 10], 1e-3);
        let f_mm = figures(Cutter::Blade, 5000.0, 3e8, 2e6);
        let f_m = ProcessFigures {
            stock_volume: 1e9 * 1e-9,
            part_volume: 5e8 * 1e-9,
            milling_volume: 3e8 * 1e-9,
            milled_area: 2e6 * 1e-6,
            cut_length: 5.0,
            ..f_mm.clone()
        };
        let t_mm = Tool {
            diameter: 20.0,
            stepover: 4.0,
            feed: None,
            removal_rate: None,
        };
        let t_m = Tool {
            diameter: 0.02,
            stepover: 0.004,
            ..t_mm
        };
        let a = cost(&f_mm, &hours(&f_mm, Some(&t_mm), &mm), &mm);
        let b = cost(&f_m, &hours(&f_m, Some(&t_m), &m), &m);
        assert!((a.total - b.total).abs() < 1e-9 * a.total);
    }

    #[test]
    fn a_flip_factor_is_where_the_winner_changes() {
        let r = Rates::resolve([None; 10], 1.0);
        let blade = figures(Cutter::Blade, 36_000.0, 0.0, 0.0);
        let mill = figures(Cutter::None, 0.0, 4e8, 1e6);
        let tool = Tool {
            diameter: 20.0,
            stepover: 4.0,
            feed: None,
            removal_rate: None,
        };
        let p = [
            Costed {
                figures: &blade,
                tool: None,
            },
            Costed {
                figures: &mill,
                tool: Some(&tool),
            },
        ];
        let w = ranking(&p, &r)[0];
        let (_, up) = flip_factors(&p, &r, rate::BLADE);
        assert_eq!(w, 0, "the blade is cheaper at the default rates");
        let f = up.expect("a dearer blade cell flips it within 100×");
        assert!(f > 1.0);
        assert_ne!(ranking(&p, &r.scaled(rate::BLADE, f * 1.001))[0], w);
        assert_eq!(ranking(&p, &r.scaled(rate::BLADE, f / 1.001))[0], w);
    }
}
