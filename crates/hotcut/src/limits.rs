//! How much work and memory a run will take, estimated from the resolved job before any
//! geometry work ([`Task::estimate`](crate::task::Task::estimate)), and the one place the
//! limits they are checked against live ([`Limits`](crate::limits::Limits); `hotcut run --max-memory GB
//! --max-work STEPS` raises them).
//!
//! The estimates are coarse on purpose — products of the counts a job sets (blocks ×
//! planes × samples, sections × samples, …) with generous constant factors — so that a
//! job whose run would take hours or more memory than a workstation has is stopped at
//! validation with the field to change, and every job that runs in minutes passes.

use std::path::Path;

use geom::surface::Surface;
use nalgebra::Vector3;

use crate::context::Context;
use crate::error::JobError;

/// Default memory limit, GB (10⁹ bytes).
pub const DEFAULT_MEMORY_GB: f64 = 4.0;
/// Default limit on the files a run writes, MB (10⁶ bytes): a report a person can open.
pub const DEFAULT_OUTPUT_MB: f64 = 256.0;
/// Default work limit, in steps (a step is about one curve or surface evaluation, some
/// tens of nanoseconds: 5·10¹⁰ steps are some tens of minutes).
pub const DEFAULT_WORK: f64 = 5e10;

/// The resources a run may take.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Limits {
    /// Memory, GB.
    pub memory_gb: f64,
    /// Work, steps.
    pub work: f64,
    /// The files written, MB.
    pub output_mb: f64,
}

impl Default for Limits {
    fn default() -> Self {
        Self {
            memory_gb: DEFAULT_MEMORY_GB,
            work: DEFAULT_WORK,
            output_mb: DEFAULT_OUTPUT_MB,
        }
    }
}

/// What a run will take, and the field that drives it.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Peak memory, bytes (roughly).
    pub memory: f64,
    /// Work, steps (roughly).
    pub work: f64,
    /// Bytes of the files written, all outputs asked for (roughly; 0: not estimated).
    pub output: f64,
    /// JSON pointer of the field that drives the estimate most.
    pub pointer: std::borrow::Cow<'static, str>,
    /// What to change to make the run smaller.
    pub change: &'static str,
    /// Problems found on the resolved job that a run would fail on (JSON pointer,
    /// message): checks that need the loaded surface.
    pub checks: Vec<(String, String)>,
}

impl Estimate {
    /// An estimate of `memory` bytes and `work` steps, driven by the field at `pointer`,
    /// with no further problem.
    pub fn new(memory: f64, work: f64, pointer: &'static str, change: &'static str) -> Self {
        Self {
            memory,
            work,
            output: 0.0,
            pointer: pointer.into(),
            change,
            checks: Vec::new(),
        }
    }

    /// This estimate, writing about `bytes` of files.
    pub fn with_output(self, bytes: f64) -> Self {
        Self {
            output: bytes,
            ..self
        }
    }

    /// One line for people: work (and the time it implies at ~10⁸ steps per second),
    /// memory, files.
    pub fn summary(&self) -> String {
        let mut s = format!(
            "about {} steps of work (~{} s at 10⁸ per second), {} GB of memory",
            round3(self.work),
            round3(self.work / STEPS_PER_SECOND),
            round3(self.memory / 1e9)
        );
        if self.output > 0.0 {
            s += &format!(", {} MB of files", round3(self.output / 1e6));
        }
        s
    }
}

/// Steps a run makes per second, roughly (one core of a current workstation): the rate
/// that turns an estimate's work into time.
pub const STEPS_PER_SECOND: f64 = 1e8;

impl Estimate {
    /// The problems of this estimate against `limits`, one per resource over its limit
    /// (a non-finite estimate is over any limit).
    pub fn problems(&self, path: &Path, task: &str, limits: &Limits) -> Vec<JobError> {
        let mut out = Vec::new();
        let gb = self.memory / 1e9;
        if !(gb <= limits.memory_gb) {
            out.push(JobError::semantic(
                path,
                &self.pointer,
                format!(
                    "{task} would need about {} GB of memory, more than the limit of {} GB: {}, or raise the limit with --max-memory",
                    round3(gb),
                    limits.memory_gb,
                    self.change
                ),
            ));
        }
        if !(self.work <= limits.work) {
            out.push(JobError::semantic(
                path,
                &self.pointer,
                format!(
                    "{task} would take about {} steps of work (at ~10⁸ steps per second), more than the limit of {:e}: {}, or raise the limit with --max-work",
                    round3(self.work),
                    limits.work,
                    self.change
                ),
            ));
        }
        let mb = self.output / 1e6;
        if !(mb <= limits.output_mb) {
            out.push(JobError::semantic(
                path,
                &self.pointer,
                format!(
                    "{task} would write about {} MB of files, more than the limit of {} MB: {}, or raise the limit with --max-output",
                    round3(mb),
                    limits.output_mb,
                    self.change
                ),
            ));
        }
        out
    }
}

/// `v` with three significant digits, for messages (`5.2e12`, `0.53`).
fn round3(v: f64) -> String {
    if !v.is_finite() {
        return "an unbounded number of".to_string();
    }
    if v != 0.0 && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:.2e}")
    } else {
        format!("{}", (v * 100.0).round() / 100.0)
    }
}

/// Steps to section the surface on one plane, and points a section holds (roughly). A
/// height field's steps grow with its expression (an evaluation runs it once; ~20 bytes
/// of source are a step).
pub fn section_cost(surface: Option<&Surface>) -> (f64, f64) {
    match surface {
        Some(Surface::Mesh(m)) => {
            let faces = m.faces().len() as f64;
            (faces + 1e3, 4.0 * faces.sqrt() + 16.0)
        }
        Some(Surface::HeightField(h)) => {
            let steps = 1.0 + h.expr().source().len() as f64 / 20.0;
            (2e4 * steps, 512.0 * steps.sqrt())
        }
        Some(Surface::Spline(_)) => (2e4, 512.0),
        None => (0.0, 0.0),
    }
}

/// Pieces of length `size` the surface spans along `d`, in `f64` (an absurd size gives a
/// huge count, not an overflow); 1 without a surface.
pub fn spanned(job: &Context, d: &Vector3<f64>, size: f64) -> f64 {
    let Some(surface) = &job.surface else {
        return 1.0;
    };
    let (lo, hi) = surface.extent_along(d);
    let n = ((hi - lo) / size).ceil();
    if n.is_nan() {
        f64::INFINITY
    } else {
        n.max(1.0)
    }
}

/// Blocks of the job's block size the surface spans along `d` and across it (`u` of the
/// section frame), and blade lengths it spans across (`f64`, see [`spanned`]); `(1, 1, 1)`
/// without a surface or a block.
pub fn blocks_spanned(job: &Context) -> (f64, f64, f64) {
    let Some(block) = &job.block else {
        return (1.0, 1.0, 1.0);
    };
    let Ok(frame) = geom::slice::PlaneFrame::from_direction(job.direction) else {
        return (1.0, 1.0, 1.0);
    };
    (
        spanned(job, &frame.normal, block.size.0),
        spanned(job, &frame.u, block.size.1),
        spanned(job, &frame.u, job.blade.length),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_estimate_over_a_limit_names_its_field_and_the_flag() {
        let e = Estimate::new(5.2e9, 1e9, "/block/size", "enlarge the block");
        let p = e.problems(Path::new("a.ron"), "HotBlade", &Limits::default());
        assert_eq!(p.len(), 1);
        let m = p[0].to_string();
        assert!(
            m.contains("/block/size") && m.contains("5.2 GB") && m.contains("--max-memory"),
            "{m}"
        );
        let big = Limits {
            memory_gb: 8.0,
            work: 1e12,
            output_mb: 1.0,
        };
        assert!(e.problems(Path::new("a.ron"), "HotBlade", &big).is_empty());
        let nan = Estimate {
            work: f64::NAN,
            ..e.clone()
        };
        assert_eq!(nan.problems(Path::new("a.ron"), "T", &big).len(), 1);
        let files = e.clone().with_output(2e6);
        let p = files.problems(Path::new("a.ron"), "T", &big);
        assert!(
            p.len() == 1 && p[0].to_string().contains("--max-output"),
            "{p:?}"
        );
        assert!(
            files.summary().contains("2 MB of files"),
            "{}",
            files.summary()
        );
    }
}
