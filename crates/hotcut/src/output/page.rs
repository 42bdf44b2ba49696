//! `report.html`: the task's [`Body`](export::html::Body) (from
//! [`Task::page`](crate::task::Task::page)) with the drawings inlined, links to every other
//! file of the run, the run time and the job; rendered by [`export::html`]. Also the number
//! formats the tasks' pages share.

use export::html::{Drawing, Page};

use crate::context::Context;
use crate::output::Files;
use crate::spec::{OutputKind, OutputSpec};
use crate::task::{Finished, Task};

/// The page's file name.
pub const NAME: &str = "report.html";

/// Writes `report.html` of a finished run into `files`, after every other file: the
/// drawings are rendered again into memory through the task's `Svg` writer (so the page
/// has them whether or not the job writes `Svg`), followed by any other drawing the run
/// wrote (PreCut's G-code previews); the files listed are the ones in `files`.
///
/// # Errors
/// The drawing writer's, or the file system's.
pub fn write<T: Task>(
    done: &Finished<'_, T>,
    files: &mut Files,
    elapsed: std::time::Duration,
) -> export::Result<()> {
    let mut drawings = Vec::new();
    if let Some(w) = T::OUTPUTS.iter().find(|w| w.kind == OutputKind::Svg) {
        let mut memory = Files::in_memory();
        (w.write)(done, &OutputSpec::Svg, &mut memory)?;
        drawings = memory
            .into_kept()
            .into_iter()
            .map(|(name, svg)| Drawing { name, svg })
            .collect();
    }
    // drawings other outputs wrote (PreCut's G-code previews)
    for name in files.names().iter().filter(|n| n.ends_with(".svg")) {
        if drawings.iter().any(|d| &d.name == name) {
            continue;
        }
        if let Some(dir) = files.dir() {
            let svg = std::fs::read(dir.join(name))?;
            drawings.push(Drawing {
                name: name.clone(),
                svg,
            });
        }
    }
    let listed = files
        .names()
        .iter()
        .map(|name| {
            let bytes = files
                .dir()
                .and_then(|d| std::fs::metadata(d.join(name)).ok())
                .map_or(0, |m| m.len());
            (name.clone(), bytes)
        })
        .collect();
    let job = done.job;
    let page = Page {
        title: job.name.clone(),
        subtitle: format!(
            "{} · units {} · hotcut {} · job file {}",
            T::NAME,
            job.units.name(),
            crate::report::VERSION,
            job.path.file_name().map_or_else(
                || job.path.display().to_string(),
                |f| f.to_string_lossy().into_owned()
            )
        ),
        body: T::page(done.report, job),
        drawings,
        files: listed,
        run_time: format!("{:.2} s", elapsed.as_secs_f64()),
        job: job.job_ron.clone(),
        job_as_written: job.job_file.clone(),
    };
    files.text(NAME, export::html::render(&page))
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
    use super::num;

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
