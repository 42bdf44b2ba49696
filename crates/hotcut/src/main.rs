//! The `hotcut` command-line tool. Exit codes: 0 success, 1 invalid input or failed run,
//! 2 usage error.
//!
//! Printing never stops a run: a closed or full stdout or stderr (`hotcut run … | head`)
//! loses the messages, not the outputs.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Args, Parser, Subcommand};
use hotcut::limits::{Limits, DEFAULT_MEMORY_GB, DEFAULT_OUTPUT_MB, DEFAULT_WORK};
use hotcut::load::{load_job_with, ResolvedJob};
use hotcut::Progress;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// hotcut: from freeform designs to hot-wire and hot-blade cutting data (job files in,
/// robot programs, G-code, meshes, drawings and reports out).
#[derive(Parser)]
#[command(version)]
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
        #[command(flatten)]
        limits: LimitArgs,
    },
    /// Check job files (syntax, schema, semantics, and the work and memory a run would
    /// take) without running them.
    Validate {
        /// Job files (RON).
        #[arg(required = true)]
        jobs: Vec<PathBuf>,
        #[command(flatten)]
        limits: LimitArgs,
    },
    /// Print the JSON Schema of job files or of a task's report.json, or write every schema
    /// to a folder.
    Schema {
        /// Print the schema of TASK's report.json instead; TASK is a task's name as job files
        /// write it (default: Analyze).
        #[arg(long, value_name = "TASK", num_args = 0..=1, default_missing_value = "Analyze")]
        report: Option<String>,
        /// Same as `--report FitCurves`.
        #[arg(long, conflicts_with = "report", hide = true)]
        fit_report: bool,
        /// Write every schema into this folder: job.schema.json and one
        /// <task>-report.schema.json per task (Analyze's is report.schema.json).
        #[arg(long, value_name = "DIR", conflicts_with_all = ["report", "fit_report"])]
        write: Option<PathBuf>,
    },
}

/// The limits a job's estimated run is checked against at validation.
#[derive(Args)]
struct LimitArgs {
    /// Most memory a run may need, GB: a job whose estimate is larger is refused at
    /// validation.
    #[arg(long, value_name = "GB", default_value_t = DEFAULT_MEMORY_GB, value_parser = positive)]
    max_memory: f64,
    /// Most work a run may take, in steps (about 10⁸ per second): a job whose estimate is
    /// larger is refused at validation.
    #[arg(long, value_name = "STEPS", default_value_t = DEFAULT_WORK, value_parser = positive)]
    max_work: f64,
    /// Most files a run may write, MB: a job whose estimate is larger is refused at
    /// validation.
    #[arg(long, value_name = "MB", default_value_t = DEFAULT_OUTPUT_MB, value_parser = positive)]
    max_output: f64,
}

impl LimitArgs {
    fn limits(&self) -> Limits {
        Limits {
            memory_gb: self.max_memory,
            work: self.max_work,
            output_mb: self.max_output,
        }
    }
}

/// A positive finite number.
fn positive(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() && v > 0.0 => Ok(v),
        _ => Err(format!("expected a positive number, got {s}")),
    }
}

/// Prints a line to stdout, control characters escaped ([`geom::text::terminal`]); a closed or full stdout is not an error (the run goes on).
macro_rules! say {
    ($($t:tt)*) => {{
        use std::io::Write;
        let _ = writeln!(std::io::stdout(), "{}", geom::text::terminal(&format!($($t)*)));
    }};
}

/// Prints a line to stderr, control characters escaped, ignoring a closed stderr.
macro_rules! warn {
    ($($t:tt)*) => {{
        use std::io::Write;
        let _ = writeln!(std::io::stderr(), "{}", geom::text::terminal(&format!($($t)*)));
    }};
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

fn load_all(jobs: &[PathBuf], limits: &Limits) -> Result<Vec<ResolvedJob>, ()> {
    let mut ok: Vec<ResolvedJob> = Vec::new();
    let mut failed = false;
    for j in jobs {
        match load_job_with(j, limits) {
            Ok(r) => {
                // one output folder per name: two jobs of one name would overwrite each other
                if let Some(first) = ok.iter().find(|o| o.context.name == r.context.name) {
                    failed = true;
                    warn!(
                        "error: {}: /name: job name {:?} is also the name of {}; names must differ within one call (they name the output folders)",
                        j.display(),
                        r.context.name,
                        first.path().display()
                    );
                }
                ok.push(r);
            }
            Err(errors) => {
                failed = true;
                for e in errors {
                    warn!("error: {e}");
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

/// Lists written files, folding long runs of per-block files.
fn print_files(dir: &std::path::Path, files: &[String]) {
    if files.len() <= 12 {
        say!("  wrote {}: {}", dir.display(), files.join(", "));
    } else {
        say!(
            "  wrote {}: {} files ({}, …, {})",
            dir.display(),
            files.len(),
            files[..6].join(", "),
            files[files.len() - 2..].join(", ")
        );
    }
}

/// `hotcut schema`: prints the job schema or a report schema, or writes them all.
fn schema(report: Option<String>, fit_report: bool, write: Option<PathBuf>) -> ExitCode {
    let files = hotcut::schema_files();
    if let Some(dir) = write {
        for f in files {
            let p = dir.join(f.file);
            if let Err(e) = std::fs::create_dir_all(&dir).and_then(|_| std::fs::write(&p, f.text)) {
                warn!("error: {}: {e}", p.display());
                return ExitCode::from(1);
            }
            say!("wrote {}", p.display());
        }
        return ExitCode::SUCCESS;
    }
    let task = if fit_report {
        Some("FitCurves".to_string())
    } else {
        report
    };
    let Some(f) = files.iter().find(|f| f.task == task.as_deref()) else {
        let names: Vec<&str> = files.iter().filter_map(|f| f.task).collect();
        warn!(
            "error: no task {} (tasks: {})",
            task.unwrap_or_default(),
            names.join(", ")
        );
        return ExitCode::from(2);
    };
    {
        use std::io::Write;
        if let Err(e) = write!(std::io::stdout(), "{}", f.text) {
            warn!("error: writing the schema: {e}");
            return ExitCode::from(1);
        }
    }
    ExitCode::SUCCESS
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
        } => schema(report, fit_report, write),
        Command::Validate { jobs, limits } => match load_all(&jobs, &limits.limits()) {
            Ok(list) => {
                for j in list {
                    say!("{}: ok ({})", j.path().display(), j.estimate.summary());
                    for w in &j.context.warnings {
                        say!("  warning: {w}");
                    }
                }
                ExitCode::SUCCESS
            }
            Err(()) => ExitCode::from(1),
        },
        Command::Run { jobs, out, limits } => {
            // Ctrl-C or a TERM signal: this run's temporary folders go, the outputs in
            // place stay whole
            let _ = ctrlc::set_handler(|| {
                hotcut::run::remove_temporaries();
                std::process::exit(130);
            });
            let Ok(list) = load_all(&jobs, &limits.limits()) else {
                warn!("nothing was run: fix the errors above");
                return ExitCode::from(1);
            };
            let bars = Bars::new();
            let mut code = ExitCode::SUCCESS;
            for j in &list {
                match hotcut::run::run_job(j, &out, &bars) {
                    Ok(o) => {
                        say!("{}", o.summary);
                        print_files(&o.dir, &o.files);
                    }
                    Err(e) => {
                        warn!("error: {e}");
                        code = ExitCode::from(1);
                    }
                }
            }
            code
        }
    }
}
