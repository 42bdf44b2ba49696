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
use crate::draw::sections_svg;
use crate::error::{HotcutError, Result};
use crate::job::OutputSpec;
use crate::load::ResolvedJob;
use crate::report::AnalyzeReport;
use crate::Progress;

/// What a run produced.
#[derive(Debug, Clone)]
pub struct RunOutcome {
    /// The output folder, `<out>/<job name>`.
    pub dir: PathBuf,
    /// Files written, relative to `dir`, in order.
    pub files: Vec<String>,
    /// The report.
    pub report: AnalyzeReport,
}

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
    let params = AnalyzeParams::from_job(job);
    let analysis = analyze(job, &params, progress)?;
    let units = job.job.units.symbol();

    std::fs::create_dir_all(out).map_err(io(out))?;
    let tmp = tempfile::Builder::new()
        .prefix(&format!(".{}.tmp-", job.job.name))
        .tempdir_in(out)
        .map_err(io(out))?;
    let mut files = Vec::new();
    // renders one output into memory, then writes it into the temporary folder
    let mut emit =
        |name: &str, render: &dyn Fn(&mut Vec<u8>) -> export::Result<()>| -> Result<()> {
            let p = tmp.path().join(name);
            let mut buf = Vec::new();
            render(&mut buf).map_err(|source| HotcutError::Export {
                path: p.clone(),
                source,
            })?;
            std::fs::write(&p, buf).map_err(io(&p))?;
            files.push(name.to_string());
            Ok(())
        };
    for o in &job.job.outputs {
        match o {
            OutputSpec::Report => emit("report.json", &|buf| {
                buf.extend(to_json_string(&analysis.report, REPORT_DIGITS)?.into_bytes());
                Ok(())
            })?,
            OutputSpec::Svg => emit("sections.svg", &|buf| {
                sections_svg(&analysis, units).write(buf)
            })?,
            OutputSpec::Obj => emit("sections.obj", &|buf| {
                let mut w = ObjWriter::new(REPORT_DIGITS);
                for (s, _) in &analysis.sections {
                    w.polyline(
                        &format!("section_{}_{}", s.index, s.piece),
                        &sample_world(&analysis.frame, s, 400),
                    );
                }
                w.write(buf)
            })?,
            // rejected by validation for Analyze
            _ => {}
        }
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
    Ok(RunOutcome {
        dir,
        files,
        report: analysis.report,
    })
}
