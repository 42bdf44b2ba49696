//! # hotcut — job files, validation, the task runner and the `hotcut` CLI
//!
//! A job file (RON) is read in three layers ([`load`]), resolved into checked geometry, run
//! by its task ([`analyze`], [`fit_curves`], [`hot_blade`], [`segmentation`]) and written atomically ([`run`]). Schemas of the job file and
//! the report come from the types in [`job`] and [`report`].
//!
//! ```
//! let dir = tempfile::tempdir().unwrap();
//! let path = dir.path().join("wave.ron");
//! std::fs::write(&path, r#"Job(
//!     name: "wave",
//!     surface: HeightField(z: "100*sin(y/200)", x: (0, 400), y: (0, 1500)),
//!     cutting: Cutting(sections: 4),
//!     task: Analyze(),
//! )"#).unwrap();
//! let job = hotcut::load::load_job(&path).unwrap();
//! let out = hotcut::run::run_job(&job, &dir.path().join("out"), &hotcut::NoProgress).unwrap();
//! // sin(y/200) changes sign at y = 200π and 400π inside (0, 1500)
//! let report = out.report.analyze().unwrap();
//! assert_eq!(report.sections[0].inflections.len(), 2);
//! assert!(out.dir.join("report.json").is_file());
//! ```

/// The `Analyze` task.
pub mod analyze;
/// The `BlockSegmentation` task: a closed mesh covered by few freely placed blocks.
pub mod block_seg;
/// The `sections.svg` and `fit.svg` drawings.
pub mod draw;
/// Error types.
pub mod error;
/// The `FitCurves` task.
pub mod fit_curves;
/// The `HotBlade` task: block grid, elastica fits, swept surface, robot data.
pub mod hot_blade;
/// Job-file types (serde + JSON Schema).
pub mod job;
/// Reading, validating and resolving job files.
pub mod load;
/// The `PreCut` task: hot-wire cuts removing the bulk above a design surface.
pub mod pre_cut;
/// Report types (serde + JSON Schema).
pub mod report;
/// Running a job and writing its outputs.
pub mod run;
/// The `FacadeSegmentation` task: facade-seg algorithms, pieces rationalized, robot data.
pub mod segmentation;

pub use error::{HotcutError, JobError, Result};

/// Progress of long steps; the CLI draws bars, libraries and tests pass [`NoProgress`].
/// `tick` may be called from worker threads.
pub trait Progress: Sync {
    /// A step with `total` units of work begins.
    fn start(&self, label: &str, total: u64);
    /// One unit is done.
    fn tick(&self);
    /// The step is done.
    fn finish(&self);
    /// A status line for the current step (e.g. iteration, blocks and E). Default: ignored.
    fn message(&self, _status: &str) {}
}

/// Reports nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoProgress;

impl Progress for NoProgress {
    fn start(&self, _: &str, _: u64) {}
    fn tick(&self) {}
    fn finish(&self) {}
}

/// The JSON Schema of job files, as written to `schemas/job.schema.json`.
pub fn job_schema_json() -> String {
    let mut s = serde_json::to_string_pretty(&load::job_schema()).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of an `Analyze` run's `report.json`, as written to
/// `schemas/report.schema.json`.
pub fn report_schema_json() -> String {
    let v = serde_json::to_value(schemars::schema_for!(report::AnalyzeReport)).unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of a `FitCurves` run's `report.json`, as written to
/// `schemas/fit-curves-report.schema.json`.
pub fn fit_curves_report_schema_json() -> String {
    let v =
        serde_json::to_value(schemars::schema_for!(report::FitCurvesReport)).unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of a `HotBlade` run's `report.json`, as written to
/// `schemas/hot-blade-report.schema.json`.
pub fn hot_blade_report_schema_json() -> String {
    let v = serde_json::to_value(schemars::schema_for!(hot_blade::report::HotBladeReport))
        .unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of a `FacadeSegmentation` run's `report.json`, as written to
/// `schemas/facade-segmentation-report.schema.json`.
pub fn segmentation_report_schema_json() -> String {
    let v = serde_json::to_value(schemars::schema_for!(
        segmentation::report::SegmentationReport
    ))
    .unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of a `BlockSegmentation` run's `report.json`, as written to
/// `schemas/block-segmentation-report.schema.json`.
pub fn block_segmentation_report_schema_json() -> String {
    let v =
        serde_json::to_value(schemars::schema_for!(block_seg::BlockSegReport)).unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of a `PreCut` run's `report.json`, as written to
/// `schemas/pre-cut-report.schema.json`.
pub fn pre_cut_report_schema_json() -> String {
    let v = serde_json::to_value(schemars::schema_for!(pre_cut::PreCutReport)).unwrap_or_default();
    let mut s = serde_json::to_string_pretty(&v).unwrap_or_default();
    s.push('\n');
    s
}

/// Every schema file of `schemas/`: (file name, contents).
pub fn schema_files() -> Vec<(&'static str, String)> {
    vec![
        ("job.schema.json", job_schema_json()),
        ("report.schema.json", report_schema_json()),
        (
            "fit-curves-report.schema.json",
            fit_curves_report_schema_json(),
        ),
        (
            "hot-blade-report.schema.json",
            hot_blade_report_schema_json(),
        ),
        (
            "facade-segmentation-report.schema.json",
            segmentation_report_schema_json(),
        ),
        (
            "block-segmentation-report.schema.json",
            block_segmentation_report_schema_json(),
        ),
        ("pre-cut-report.schema.json", pre_cut_report_schema_json()),
    ]
}
