//! The `hotcut` command-line tool. Exit codes: 0 success, 1 invalid input or failed run,
//! 2 usage error.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use hotcut::load::{load_job, ResolvedJob};
use hotcut::report::{AnalyzeReport, FitCurvesReport, TaskReport, Violation};
use hotcut::Progress;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// hotcut: from freeform designs to hot-wire and hot-blade cutting data.
#[derive(Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run job files; outputs go to <OUT>/<job name>/.
    Run {
        /// Job files (RON).
        #[arg(required = true)]
        jobs: Vec<PathBuf>,
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
    /// Check job files (syntax, schema, semantics) without running them.
    Validate {
        /// Job files (RON).
        #[arg(required = true)]
        jobs: Vec<PathBuf>,
    },
    /// Print the JSON Schema of job files (or of a report.json), or write all schemas to a folder.
    Schema {
        /// Print the schema of an Analyze run's report.json instead.
        #[arg(long)]
        report: bool,
        /// Print the schema of a FitCurves run's report.json instead.
        #[arg(long, conflicts_with = "report")]
        fit_report: bool,
        /// Write job.schema.json, report.schema.json and fit-curves-report.schema.json into
        /// this folder.
        #[arg(long, value_name = "DIR")]
        write: Option<PathBuf>,
    },
}

/// indicatif bars, hidden when stdout is not a terminal.
struct Bars {
    bar: ProgressBar,
}

impl Bars {
    fn new() -> Self {
        let bar = ProgressBar::hidden();
        Self { bar }
    }
}

impl Progress for Bars {
    fn start(&self, label: &str, total: u64) {
        if std::io::stdout().is_terminal() {
            self.bar.set_draw_target(ProgressDrawTarget::stderr());
        }
        self.bar.reset();
        self.bar.set_length(total);
        self.bar.set_position(0);
        self.bar.set_style(
            ProgressStyle::with_template("{msg:>20} [{bar:40}] {pos}/{len} {elapsed}")
                .unwrap_or_else(|_| ProgressStyle::default_bar())
                .progress_chars("=> "),
        );
        self.bar.set_message(label.to_string());
    }
    fn tick(&self) {
        self.bar.inc(1);
    }
    fn message(&self, status: &str) {
        self.bar.set_message(status.to_string());
    }
    fn finish(&self) {
        self.bar.finish_and_clear();
        self.bar.set_draw_target(ProgressDrawTarget::hidden());
    }
}

fn load_all(jobs: &[PathBuf]) -> Result<Vec<ResolvedJob>, ()> {
    let mut ok = Vec::new();
    let mut failed = false;
    for j in jobs {
        match load_job(j) {
            Ok(r) => ok.push(r),
            Err(errors) => {
                failed = true;
                for e in errors {
                    eprintln!("error: {e}");
                }
            }
        }
    }
    if failed {
        Err(())
    } else {
        Ok(ok)
    }
}

fn print_summary(r: &AnalyzeReport, units: &str) {
    let s = &r.summary;
    println!(
        "{}: {} section(s) on {} plane(s), longest {:.1} {units}, {} inflection(s) (at most {} on one), max |curvature| {:.5} /{units}",
        r.job, s.pieces, s.planes_with_sections, s.max_length, s.total_inflections, s.max_inflections, s.max_abs_curvature
    );
    let c = &r.constraints;
    println!(
        "  dimension:    {} section(s) longer than the blade ({} {units})",
        s.sections_too_long, c.blade_length
    );
    for v in &s.surface_violations {
        if let Violation::Dimension { what, value, limit } = v {
            println!(
                "                surface {:.1} {units} > block {limit} {units} ({what})",
                value
            );
        }
    }
    if c.block_size.is_none() {
        println!("                no block given: block size not checked");
    }
    println!(
        "  shape:        {} section(s) with more than {} inflection(s)",
        s.sections_too_many_inflections, c.max_inflections
    );
    println!(
        "  blade strain: {} section(s) above |curvature| {} /{units}",
        s.sections_too_curved, c.max_curvature
    );
    for w in &r.surface.warnings {
        println!("  warning: {w}");
    }
    println!(
        "  verdict: {}",
        if s.cuttable_without_segmentation {
            "cuttable with one blade from one block"
        } else {
            "needs segmentation or another tool (see report.json)"
        }
    );
}

fn print_fit_summary(r: &FitCurvesReport, units: &str) {
    let s = &r.summary;
    println!("{} (FitCurves, {:?}, {}):", r.job, r.constraint, r.source);
    println!(
        "  {} curve(s): {} inflectional, {} non-inflectional elastica, {} arc(s), {} line(s)",
        s.curves, s.inflectional, s.noninflectional, s.arcs, s.lines
    );
    println!(
        "  RMS distance: median {:.3e} {units}, max {:.3e} {units}; largest distance {:.3e} {units}",
        s.median_rms, s.max_rms, s.max_distance
    );
    for c in &r.curves {
        if let Some(e) = &c.error {
            println!("  warning: curve `{}` was not fitted: {e}", c.id);
        }
    }
}

fn print_hot_blade_summary(r: &hotcut::hot_blade::report::HotBladeReport, units: &str) {
    let s = &r.summary;
    println!(
        "{} (HotBlade, {:?}, {:?}): {} block(s) in {} row(s) × {} column(s), {} split(s)",
        r.job,
        r.settings.constraint,
        r.settings.continuity,
        s.blocks,
        r.grid.rows,
        r.grid.columns,
        r.splits.len()
    );
    println!(
        "  {} section(s): L2 min {:.4}, max {:.4}, avg {:.4}; largest fit distance {:.4} {units}, deviation {:.4} {units}",
        s.sections, s.l2.min, s.l2.max, s.l2.avg, s.max_fit_distance, s.max_deviation
    );
    println!(
        "  blade: max |κ| {:.4e} /{units}, ≤ {} inflection(s); plane angle ≤ {:.1}°; face gap {:.1e} {units}, angle {:.1e} rad",
        s.max_abs_curvature,
        s.max_inflections,
        s.max_plane_angle.to_degrees(),
        s.max_face_gap,
        s.max_face_angle
    );
    let f = &s.flagged;
    if s.all_ok {
        println!("  every block meets every constraint");
    } else {
        println!(
            "  warning: blocks breaking a constraint — approximation {}, blade strain {}, shape {}, blade length {}, flat blade {}, block height {}, overlap {}",
            f.approximation, f.blade_strain, f.shape, f.blade_length, f.flat_blade, f.block_height, f.overlap
        );
    }
}

fn print_pre_cut_summary(name: &str, r: &hotcut::pre_cut::PreCutReport) {
    let v = &r.volumes;
    println!(
        "{name} (PreCut): {} direction(s) × {} cut(s); left for milling {:.4} of the block (convex hull {:.4}, block {:.4}): {:.0} % more removed than the hull, {:.0} % more than the block; model {:.4}",
        r.directions.len(),
        r.params.legs,
        v.ruled,
        v.convex_hull,
        v.bounding_box,
        v.more_than_hull_percent,
        v.more_than_box_percent,
        v.model
    );
}

fn print_block_summary(name: &str, r: &hotcut::block_seg::BlockSegReport) {
    let s = &r.segmentation;
    println!(
        "{name} (BlockSegmentation): {} → {} block(s), {:.1} % fewer (lower bound {}); best of {} run(s), {} iteration(s); accepted {} translation(s), {} rotation(s), {} alignment(s)",
        s.initial_blocks,
        s.final_blocks,
        s.reduction_percent,
        s.lower_bound,
        s.restarts.len(),
        s.history.last().map_or(0, |h| h.iteration),
        s.accepted.translations,
        s.accepted.rotations,
        s.accepted.alignments
    );
}

fn print_segmentation_summary(r: &hotcut::segmentation::report::SegmentationReport, units: &str) {
    let c = &r.counts;
    println!(
        "{} (FacadeSegmentation, {}): {} piece(s) from {} block(s), {} band(s) × {} row(s), {} section part(s)",
        r.job,
        r.settings.algorithm.name(),
        c.pieces,
        c.blocks,
        c.bands,
        c.rows,
        c.parts
    );
    if r.settings.rationalized {
        let worst = r
            .pieces
            .iter()
            .filter_map(|p| p.max_blade_fit)
            .fold(0.0, f64::max);
        println!(
            "  {} blade pose(s), {} sliver(s) unposed; largest blade fit distance {:.4} {units}",
            c.poses, c.unposed, worst
        );
    }
    let f = &c.failing;
    if c.all_ok {
        println!("  every piece meets every constraint");
    } else {
        println!(
            "  warning: pieces breaking a constraint — dimension {}, approximation {}, shape {}, blade strain {}",
            f.dimension, f.approximation, f.shape, f.blade_strain
        );
    }
}

/// Lists written files, folding long runs of per-block files.
fn print_files(dir: &std::path::Path, files: &[String]) {
    if files.len() <= 12 {
        println!("  wrote {}: {}", dir.display(), files.join(", "));
    } else {
        println!(
            "  wrote {}: {} files ({}, …, {})",
            dir.display(),
            files.len(),
            files[..6].join(", "),
            files[files.len() - 2..].join(", ")
        );
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(c) => c,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match cli.command {
        Command::Schema {
            report,
            fit_report,
            write,
        } => {
            if let Some(dir) = write {
                for (name, text) in hotcut::schema_files() {
                    let p = dir.join(name);
                    if let Err(e) =
                        std::fs::create_dir_all(&dir).and_then(|_| std::fs::write(&p, text))
                    {
                        eprintln!("error: {}: {e}", p.display());
                        return ExitCode::from(1);
                    }
                    println!("wrote {}", p.display());
                }
            } else if report {
                print!("{}", hotcut::report_schema_json());
            } else if fit_report {
                print!("{}", hotcut::fit_curves_report_schema_json());
            } else {
                print!("{}", hotcut::job_schema_json());
            }
            ExitCode::SUCCESS
        }
        Command::Validate { jobs } => match load_all(&jobs) {
            Ok(list) => {
                for j in list {
                    println!("{}: ok", j.path.display());
                    for w in &j.warnings {
                        println!("  warning: {w}");
                    }
                }
                ExitCode::SUCCESS
            }
            Err(()) => ExitCode::from(1),
        },
        Command::Run { jobs, out } => {
            let Ok(list) = load_all(&jobs) else {
                eprintln!("nothing was run: fix the errors above");
                return ExitCode::from(1);
            };
            let bars = Bars::new();
            let mut code = ExitCode::SUCCESS;
            for j in &list {
                match hotcut::run::run_job(j, &out, &bars) {
                    Ok(o) => {
                        match &o.report {
                            TaskReport::Analyze(r) => print_summary(r, j.job.units.symbol()),
                            TaskReport::FitCurves(r) => print_fit_summary(r, j.job.units.symbol()),
                            TaskReport::HotBlade(r) => {
                                print_hot_blade_summary(r, j.job.units.symbol())
                            }
                            TaskReport::FacadeSegmentation(r) => {
                                print_segmentation_summary(r, j.job.units.symbol())
                            }
                            TaskReport::BlockSegmentation(r) => print_block_summary(&j.job.name, r),
                            TaskReport::PreCut(r) => print_pre_cut_summary(&j.job.name, r),
                        }
                        print_files(&o.dir, &o.files);
                    }
                    Err(e) => {
                        eprintln!("error: {e}");
                        code = ExitCode::from(1);
                    }
                }
            }
            code
        }
    }
}
