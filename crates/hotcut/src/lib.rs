//! # hotcut — job files, validation, the task runner and the `hotcut` CLI
//!
//! The edge of the workspace: a job file (RON) is read in three layers ([`load`]), its
//! task — one of the task modules below, each implementing [`task::Task`] — turns the
//! resolved job into parameters for an algorithm crate, runs it, makes its report and
//! writes its files, and [`run`] writes them into a folder that replaces the previous run's
//! as a whole.
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
//! assert_eq!(out.report["sections"][0]["inflections"].as_array().unwrap().len(), 2);
//! assert!(out.dir.join("report.json").is_file());
//! ```

/// The `Analyze` task: every section checked against the production constraints.
pub mod analyze;
/// The `BlockSegmentation` task: a closed mesh covered by few freely placed blocks.
pub mod block_segmentation;
/// The `Compare` task: one design made by several processes, set side by side (thesis ch. 6).
pub mod compare;
/// What a task sees of its job: the common fields as written and resolved.
pub mod context;
/// The `Design` task: designs made for the hot blade, their elastica, robot data.
pub mod design_task;
/// Error types.
pub mod error;
/// The `FacadeSegmentation` task: facade-seg algorithms, pieces rationalized, robot data.
pub mod facade_segmentation;
/// The `FitCurves` task: curves or sections fitted by elastica.
pub mod fit_curves;
/// The `HotBlade` task: the hotblade pipeline, its report and robot files.
pub mod hot_blade;
/// Input files: regular files of bounded size, checked before they are opened.
pub mod input;
/// The job file: the [`job::Job`] struct and [`job::TaskSpec`], the list of every task.
pub mod job;
/// Work and memory estimates of a run, and the limits they are checked against.
pub mod limits;
/// Reading, validating and resolving job files.
pub mod load;
/// Writers shared by the tasks: the rendered files and the robot files.
pub mod output;
/// The `PreCut` task: hot-wire cuts removing the bulk above a design surface.
pub mod pre_cut;
/// A task's run measured as a production process: the figures `Compare` sets side by side.
pub mod process;
/// Progress of long steps.
pub mod progress;
/// Rendering a finished run's files, into a folder or into memory.
pub mod render;
/// What reports share.
pub mod report;
/// The robot cell of the blade-posing tasks: `cell:` checked and resolved, the program planned.
pub mod robot_cell;
/// The `RuledBlocks` task: a model rationalized by ruled strips, then cut into blocks.
pub mod ruled_blocks;
/// Running a job and writing its outputs as a whole.
pub mod run;
/// Job-file types shared by every task (units, surface, block, blade, outputs, ...).
pub mod spec;
/// The `Task` trait, output declarations, and visiting a job's task.
pub mod task;
/// The job's `wire` as the wire-cutting tasks' machine: path settings, controller, checks.
pub mod wire_machine;

pub use error::{HotcutError, JobError, Result};
pub use progress::{NoProgress, Progress};

use task::{Task, VisitType};

/// Pretty JSON with a final newline, as the files in `schemas/` hold it.
fn pretty(v: &serde_json::Value) -> String {
    let mut s = serde_json::to_string_pretty(v).unwrap_or_default();
    s.push('\n');
    s
}

/// The JSON Schema of job files, as written to `schemas/job.schema.json`.
pub fn job_schema_json() -> String {
    pretty(&load::job_schema())
}

/// One schema file of `schemas/`.
#[derive(Debug, Clone, PartialEq)]
pub struct SchemaFile {
    /// The task whose report it describes (`None`: an input file, the job file or the
    /// design file).
    pub task: Option<&'static str>,
    /// File name.
    pub file: &'static str,
    /// Contents.
    pub text: String,
}

/// Makes a schema of a file hotcut writes strict: every object schema that lists its
/// properties gets `additionalProperties: false` (maps, which give their own
/// `additionalProperties`, stay as they are), so a reader's validator rejects unknown keys.
pub fn strict(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(o) => {
            if o.contains_key("properties") && !o.contains_key("additionalProperties") {
                o.insert("additionalProperties".into(), false.into());
            }
            o.values_mut().for_each(strict);
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(strict),
        _ => {}
    }
}

/// The schema of task `T`'s `report.json`.
fn report_schema<T: Task>() -> SchemaFile {
    let mut v = serde_json::to_value(schemars::schema_for!(T::Report)).unwrap_or_default();
    strict(&mut v);
    SchemaFile {
        task: Some(T::NAME),
        file: T::REPORT_SCHEMA,
        text: pretty(&v),
    }
}

/// Every schema file of `schemas/`: the job file's, the design file's, then one per task's report, in the
/// order of [`job::TaskSpec`].
pub fn schema_files() -> Vec<SchemaFile> {
    struct Reports(Vec<SchemaFile>);
    impl VisitType for Reports {
        fn visit<T: Task>(&mut self) {
            self.0.push(report_schema::<T>());
        }
    }
    let mut files = Reports(vec![SchemaFile {
        task: None,
        file: "job.schema.json",
        text: job_schema_json(),
    }]);
    files.0.push(SchemaFile {
        task: None,
        file: "design.schema.json",
        text: pretty(&design_task::file::design_schema()),
    });
    job::TaskSpec::each(&mut files);
    files.0.extend([
        output_schema::<export::robot::Targets>("targets.schema.json"),
        output_schema::<block_segmentation::BlocksFile<'static>>("blocks.schema.json"),
        output_schema::<pre_cut::PreCutFile<'static>>("precut.schema.json"),
    ]);
    files.0
}

/// The strict schema of a JSON file other than a report.
fn output_schema<T: schemars::JsonSchema>(file: &'static str) -> SchemaFile {
    let mut v = serde_json::to_value(schemars::schema_for!(T)).unwrap_or_default();
    strict(&mut v);
    SchemaFile {
        task: None,
        file,
        text: pretty(&v),
    }
}
