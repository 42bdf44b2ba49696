//! The runner: maps a resolved job to its task and writes the outputs atomically.
//!
//! Outputs are written into a temporary folder inside the output directory and renamed to
//! `<out>/<job name>/` only when everything succeeded, so a failed run leaves no partial
//! output folder.
//!
//! Entry point: [`run_job`](crate::run::run_job).

use std::path::{Path, PathBuf};

use export::json::{to_json_string, REPORT_DIGITS};
use export::obj::ObjWriter;

use crate::analyze::{analyze, sample_world, AnalyzeParams};
use crate::draw::{fit_svg, sections_svg};
use crate::error::{HotcutError, Result};
use crate::fit_curves::{fit_curves, FitCurvesParams};
use crate::hot_blade::{hot_blade, HotBladeParams};
use crate::job::{OutputSpec, TaskSpec};
use crate::load::ResolvedJob;
use crate::report::TaskReport;
use crate::segmentation::{segment_facade, SegmentationParams};
use crate::Progress;

/// What a run produced.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The output folder, `<out>/<job name>`.
    pub dir: PathBuf,
    /// Files written, relative to `dir`, in order.
    pub files: Vec<String>,
    /// The report.
    pub report: TaskReport,
}

/// How a task renders its own output files (all but `report.json`); an output kind may
/// give several files.
type TaskFiles = Box<dyn Fn(&OutputSpec) -> Vec<Render<'static>>>;

/// One output file: its name and how to render it.
pub(crate) type Render<'a> = (String, Box<dyn Fn(&mut Vec<u8>) -> export::Result<()> + 'a>);

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> HotcutError + '_ {
    move |source| HotcutError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Runs a resolved job and writes its outputs to `<out>/<name>/`, replacing an earlier
/// run's folder.
///
/// # Errors
/// Geometry failures of the task; I/O failures writing the outputs.
pub fn run_job(job: &ResolvedJob, out: &Path, progress: &dyn Progress) -> Result<RunOutcome> {
    let units = job.job.units.symbol();
    // run the task; `render` makes the task's own files (validation rejected the rest)
    let (report, render): (TaskReport, TaskFiles) = match &job.job.task {
        TaskSpec::Analyze { .. } => {
            let params = AnalyzeParams::from_job(job);
            let a = std::rc::Rc::new(analyze(job, &params, progress)?);
            let report = TaskReport::Analyze(Box::new(a.report.clone()));
            let render = move |o: &OutputSpec| -> Vec<Render<'static>> {
                let a = a.clone();
                match o {
                    OutputSpec::Svg => vec![(
                        "sections.svg".into(),
                        Box::new(move |buf| sections_svg(&a, units).write(buf)),
                    )],
                    OutputSpec::Obj => vec![(
                        "sections.obj".into(),
                        Box::new(move |buf| {
                            let mut w = ObjWriter::new(REPORT_DIGITS);
                            for (s, _) in &a.sections {
                                w.polyline(
                                    &format!("section_{}_{}", s.index, s.piece),
                                    &sample_world(&a.frame, s, 400),
                                );
                            }
                            w.write(buf)
                        }),
                    )],
                    _ => Vec::new(),
                }
            };
            (report, Box::new(render))
        }
        TaskSpec::FitCurves {
            constraint,
            samples,
            ..
        } => {
            let params = FitCurvesParams {
                constraint: *constraint,
                samples: *samples as usize,
            };
            let f = std::rc::Rc::new(fit_curves(job, &params, progress)?);
            let report = TaskReport::FitCurves(f.report.clone());
            let render = move |o: &OutputSpec| -> Vec<Render<'static>> {
                let f = f.clone();
                match o {
                    OutputSpec::Svg => vec![(
                        "fit.svg".into(),
                        Box::new(move |buf| fit_svg(&f, units).write(buf)),
                    )],
                    _ => Vec::new(),
                }
            };
            (report, Box::new(render))
        }
        TaskSpec::HotBlade { .. } => {
            let params = HotBladeParams::from_job(job).ok_or_else(|| HotcutError::Task {
                path: job.path.clone(),
                message: "not a HotBlade job".into(),
            })?;
            let h = std::rc::Rc::new(hot_blade(job, &params, progress)?);
            let report = TaskReport::HotBlade(Box::new(h.report.clone()));
            let units = job.job.units;
            let name = job.job.name.clone();
            let render =
                move |o: &OutputSpec| crate::hot_blade::outputs::render(&h, o, units, &name);
            (report, Box::new(render))
        }
        TaskSpec::FacadeSegmentation { .. } => {
            let params = SegmentationParams::from_job(job).ok_or_else(|| HotcutError::Task {
                path: job.path.clone(),
                message: "not a FacadeSegmentation job with a block".into(),
            })?;
            let s = std::rc::Rc::new(segment_facade(job, &params, progress)?);
            let report = TaskReport::FacadeSegmentation(Box::new(s.report.clone()));
            let units = job.job.units;
            let name = job.job.name.clone();
            let render =
                move |o: &OutputSpec| crate::segmentation::outputs::render(&s, o, units, &name);
            (report, Box::new(render))
        }
        TaskSpec::BlockSegmentation { .. } => {
            let b = std::rc::Rc::new(crate::block_seg::block_segmentation(job, progress)?);
            let report = TaskReport::BlockSegmentation(Box::new(b.report.clone()));
            let render = move |o: &OutputSpec| crate::block_seg::outputs::render(&b, o);
            (report, Box::new(render))
        }
        TaskSpec::PreCut { .. } => {
            let c = std::rc::Rc::new(crate::pre_cut::pre_cut(job, progress)?);
            let report = TaskReport::PreCut(Box::new(c.report.clone()));
            let render = move |o: &OutputSpec| crate::pre_cut::outputs::render(&c, o);
            (report, Box::new(render))
        }
    };
    let mut renders: Vec<Render<'_>> = Vec::new();
    for o in &job.job.outputs {
        match o {
            OutputSpec::Report => renders.push((
                "report.json".into(),
                Box::new(|buf| {
                    buf.extend(to_json_string(&report, REPORT_DIGITS)?.into_bytes());
                    Ok(())
                }),
            )),
            other => renders.extend(render(other)),
        }
    }

    std::fs::create_dir_all(out).map_err(io(out))?;
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".{}.tmp-", job.job.name))
        .tempdir_in(out)
        .map_err(io(out))?;
    let mut files = Vec::new();
    // renders each output into memory, then writes it into the temporary folder
    for (name, render) in renders {
        let p = tmp.path().join(&name);
        let mut buf = Vec::new();
        render(&mut buf).map_err(|source| HotcutError::Export {
            path: p.clone(),
            source,
        })?;
        std::fs::write(&p, buf).map_err(io(&p))?;
        files.push(name);
    }
    let dir = out.join(&job.job.name);
    if dir.exists() {
        std::fs::remove_dir_all(&dir).map_err(io(&dir))?;
    }
    let kept = tmp.keep();
    std::fs::rename(&kept, &dir).map_err(|e| {
        let _ = std::fs::remove_dir_all(&kept);
        HotcutError::Io {
            path: dir.clone(),
            source: e,
        }
    })?;
    Ok(RunOutcome { dir, files, report })
}
