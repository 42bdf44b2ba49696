//! Benchmarks of the `HotBlade` task on the multi-block facade job
//! (`jobs/hot-blade-facade.ron`: 8 blocks, 408 fitted sections):
//! - `facade_job`: the whole computation (`hotblade::rationalize`: grid, sections, fits,
//!   splits, swept surfaces, deviation grid, totals), no files written;
//! - `facade_run`: `run_job`, i.e. the above plus validation of the report and every output
//!   file written to a temporary directory (what `hotcut run` does);
//! - `section_fit`: one elastica fit of one section as the task does it
//!   (`EndPointsAndLength`, 100 design samples), cycling twice through all 408 design
//!   sections of the job, warm-started from the previous plane's final fit (`warm`) or from
//!   scratch (`cold`). The task runs both per section, plus a warm fit per backward or
//!   forward sweep that still changes something (see `hotblade::sweep_fits`).
//!
//! Run: `cargo bench -p hotcut --bench hot_blade`.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use elastica::fit::{fit_points_with_arclength, FitConstraint, FitParams};
use elastica::segment::Segment;
use hotblade::Rationalization;
use hotcut::job::TaskSpec;
use hotcut::load::{load_job, ResolvedJob};
use hotcut::run::run_job;
use hotcut::task::Task;
use hotcut::NoProgress;

fn main() {
    divan::main();
}

fn job_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../jobs/hot-blade-facade.ron")
}

fn job() -> &'static ResolvedJob {
    static J: OnceLock<ResolvedJob> = OnceLock::new();
    J.get_or_init(|| load_job(&job_path()).expect("jobs/hot-blade-facade.ron loads"))
}

/// The `hotblade` pipeline with the job's parameters.
fn rationalize(job: &ResolvedJob) -> Rationalization {
    let TaskSpec::HotBlade(task) = &job.task else {
        panic!("not a HotBlade job");
    };
    let params = task.params(&job.context).unwrap().pipeline;
    let surface = job.context.surface.as_ref().unwrap();
    hotblade::rationalize(surface, &params, &|_| {}).unwrap()
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn facade_job() -> usize {
    rationalize(job()).blocks.len()
}

#[divan::bench(sample_count = 5, sample_size = 1)]
fn facade_run() {
    let dir = tempfile::tempdir().unwrap();
    run_job(job(), dir.path(), &NoProgress).unwrap();
}

/// Every design section of the facade job with the fit of the plane before it in the same
/// block (the task's warm start).
type Section = (Vec<[f64; 2]>, Vec<f64>, Option<Segment>);

fn sections() -> &'static Vec<Section> {
    static S: OnceLock<Vec<Section>> = OnceLock::new();
    S.get_or_init(|| {
        let run = rationalize(job());
        let mut out = Vec::new();
        for b in &run.blocks {
            let mut warm = None;
            for sec in &b.sections {
                out.push((sec.design.points.clone(), sec.design.s.clone(), warm));
                warm = Some(sec.fit.segment);
            }
        }
        out
    })
}

#[divan::bench(args = ["warm", "cold"], sample_count = 816, sample_size = 1)]
fn section_fit(bencher: divan::Bencher, start: &str) {
    let sections = sections();
    let mut i = 0;
    bencher.bench_local(|| {
        let (points, s, warm) = &sections[i % sections.len()];
        i += 1;
        let params = FitParams {
            constraint: FitConstraint::EndPointsAndLength,
            warm_start: if start == "warm" { *warm } else { None },
            ..FitParams::default()
        };
        divan::black_box(fit_points_with_arclength(points, s, &params).unwrap().rms)
    });
}
