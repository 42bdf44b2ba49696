//! The number formats the tasks' `report.html` pages share (the runner assembles the page,
//! [`crate::run`]; [`export::html`] renders it).

use crate::context::Context;

/// The verdict of a task that poses the blade for the robot cell: `cuttable` (what would
/// be cut, without a final stop) when its constraints hold (`constraints_ok`) and the cell,
/// if planned (`cell = Some(clean)`), reaches every move; else `broken` when the
/// constraints fail, else the cell's problem.
pub fn blade_verdict(
    constraints_ok: bool,
    cell: Option<bool>,
    cuttable: String,
    broken: impl FnOnce() -> String,
) -> export::html::Verdict {
    let ok = constraints_ok && cell.unwrap_or(true);
    let text = if ok {
        let robots = if cell.is_some() {
            ", and the robots reach every move"
        } else {
            ""
        };
        format!("Cuttable: {cuttable}{robots}.")
    } else if !constraints_ok {
        broken()
    } else {
        format!("Not cuttable as planned: the robot cell has problems (see its rows), although {cuttable}.")
    };
    export::html::Verdict { ok, text }
}

/// The constraint row of the blade's stability over a task's poses: `failing` (what fails,
/// e.g. "2 of 9 pieces fail"), the least margin of a pose, the job's least margin.
pub fn stability_constraint(
    failing: String,
    least: f64,
    marginal: f64,
    ok: bool,
) -> export::html::Constraint {
    export::html::Constraint {
        name: "blade stability: every posed blade holds its shape".into(),
        limit: format!(
            "margin ≥ {} (1 = a straight, unloaded blade), no snap from pose to pose",
            num(marginal)
        ),
        measured: format!("{failing}; least margin {}", num(least)),
        ok,
    }
}

/// A number for people: 4 significant digits, plain notation between 1e-3 and 1e6, else
/// scientific; `—` when not finite.
pub fn num(v: f64) -> String {
    if !v.is_finite() {
        return "—".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e6).contains(&a) {
        return format!("{v:.3e}");
    }
    let decimals = (3 - a.log10().floor() as i32).clamp(0, 6) as usize;
    let s = format!("{v:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A length in the job's unit: `812.3 mm`.
pub fn len(v: f64, job: &Context) -> String {
    format!("{} {}", num(v), job.units.symbol())
}

/// A curvature in the job's unit: `0.011 /mm`.
pub fn curv(v: f64, job: &Context) -> String {
    format!("{} /{}", num(v), job.units.symbol())
}

/// An angle given in radians, shown in degrees: `12.5°`.
pub fn deg(radians: f64) -> String {
    format!("{}°", num(radians.to_degrees()))
}

#[cfg(test)]
mod tests {
    use super::{blade_verdict, num};

    #[test]
    fn blade_verdicts_name_what_fails() {
        let v = |ok, cell| blade_verdict(ok, cell, "2 blocks".into(), || "broken".into());
        assert_eq!(v(true, None).text, "Cuttable: 2 blocks.");
        assert!(v(true, None).ok);
        assert_eq!(
            v(true, Some(true)).text,
            "Cuttable: 2 blocks, and the robots reach every move."
        );
        assert_eq!(v(false, Some(true)).text, "broken");
        let cell = v(true, Some(false));
        assert!(
            !cell.ok
                && cell
                    .text
                    .starts_with("Not cuttable as planned: the robot cell")
        );
        assert!(!v(false, Some(false)).ok);
    }

    #[test]
    fn numbers_read_well() {
        assert_eq!(num(812.34567), "812.3");
        assert_eq!(num(0.011), "0.011");
        assert_eq!(num(1.0), "1");
        assert_eq!(num(-2.5), "-2.5");
        assert_eq!(num(1234.0), "1234");
        assert_eq!(num(0.000_012_34), "1.234e-5");
        assert_eq!(num(2.5e7), "2.500e7");
        assert_eq!(num(f64::NAN), "—");
        assert_eq!(num(0.0), "0");
    }
}
