//! The `Compare` jobs of `jobs/` agree with the processes' own tasks: each process that
//! runs a task is run again as that task's own job (the same fields, the task swapped in)
//! and its `report.json` must equal the one in the comparison's folder; the numbers the
//! comparison sets side by side (blocks, deviation, cut lengths, volumes) are re-read
//! from that report here, by this test's own reading, and must be the ones compared.
//! Milling the job's blocks runs no task: on the mould its volumes are checked against
//! the pre-cut's own Table 2.1 volumes of the same block.

use std::path::Path;

use hotcut::job::{Job, MillingStock, Process, TaskSpec};
use hotcut::load::{parse_job, resolve};
use hotcut::run::run_job;
use hotcut::spec::OutputSpec;
use hotcut::NoProgress;
use hotcut_workspace_tests::root;
use serde_json::Value;

fn read(path: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

/// The task a process runs, as a job's task.
fn own_task(p: &Process) -> Option<TaskSpec> {
    Some(match p {
        Process::Milling(m) => match &m.stock {
            MillingStock::Blocks => return None,
            MillingStock::BlockSegmentation(b) => TaskSpec::BlockSegmentation(b.clone()),
        },
        Process::PreCutThenMilling(c) => TaskSpec::PreCut(c.pre_cut.clone()),
        Process::HotWireRuled(r) => TaskSpec::RuledBlocks(r.clone()),
        Process::HotBlade(h) => TaskSpec::HotBlade(h.clone()),
        Process::FacadeSegmentation(s) => TaskSpec::FacadeSegmentation(s.clone()),
    })
}

/// `v` without its `job` name (the own job has another name).
fn unnamed(mut v: Value) -> Value {
    if let Some(o) = v.as_object_mut() {
        o.remove("job");
    }
    v
}

/// The figures a process's own report gives, read here: (blocks, cut length in job units,
/// deviation RMS and max).
fn own_numbers(task: &TaskSpec, r: &Value, per_mm: f64) -> (usize, f64, Option<(f64, f64)>) {
    let f = |v: &Value| v.as_f64().unwrap();
    match task {
        TaskSpec::PreCut(_) => {
            let cut: f64 = r["programs"]
                .as_array()
                .unwrap()
                .iter()
                .map(|p| f(&p["cut_length_mm"]))
                .sum();
            (1, cut * per_mm, None)
        }
        TaskSpec::BlockSegmentation(_) => (
            r["segmentation"]["blocks"].as_array().unwrap().len(),
            0.0,
            None,
        ),
        TaskSpec::RuledBlocks(_) => {
            let blocks = r["blocks"].as_array().unwrap();
            let cut: f64 = blocks
                .iter()
                .flat_map(|b| b["cuts"].as_array().unwrap())
                .map(|c| f(&c["cut_length_mm"]))
                .sum();
            let dev = (
                f(&r["deviation"]["rms"]),
                f(&r["deviation"]["max"]).max(f(&r["totals"]["added_depth"])),
            );
            (blocks.len(), cut * per_mm, Some(dev))
        }
        TaskSpec::HotBlade(_) => {
            let blocks = r["blocks"].as_array().unwrap();
            let rms = blocks.iter().map(|b| f(&b["max_rms"])).fold(0.0, f64::max);
            (
                blocks.len(),
                f64::NAN,
                Some((rms, f(&r["summary"]["max_deviation"]))),
            )
        }
        TaskSpec::FacadeSegmentation(_) => {
            // every piece's blade fits: RMS over the fits, largest distance
            let fits: Vec<&Value> = r["pieces"]
                .as_array()
                .unwrap()
                .iter()
                .flat_map(|p| p["sections"].as_array().unwrap())
                .map(|s| &s["blade_fit"])
                .filter(|b| !b.is_null())
                .collect();
            let sq: f64 = fits.iter().map(|b| f(&b["rms"]).powi(2)).sum();
            let max = fits.iter().map(|b| f(&b["max"])).fold(0.0, f64::max);
            (
                r["counts"]["blocks"].as_u64().unwrap() as usize,
                f64::NAN,
                Some(((sq / fits.len() as f64).sqrt(), max)),
            )
        }
        _ => unreachable!(),
    }
}

/// Relative agreement to the report's 9 significant digits.
fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-8 * a.abs().max(b.abs()) + 1e-12
}

#[test]
fn every_compare_job_agrees_with_each_process_run_as_its_own_task() {
    let mut checked = 0;
    // the jobs, and the facade with its segmentation for the blade too (the jobs leave
    // it out: it ties with the grid of blocks there)
    let facade = std::fs::read_to_string(root().join("jobs/compare-facade.ron")).unwrap();
    let segmented = facade.replace(
        "            HotWireRuled(",
        "            FacadeSegmentation(algorithm: Inflection()),\n            HotWireRuled(",
    );
    assert_ne!(segmented, facade);
    let jobs = [
        ("compare-closed", None),
        ("compare-facade", None),
        ("compare-mould", None),
        ("compare-facade", Some(segmented)),
    ];
    for (name, variant) in jobs {
        let path = root().join("jobs").join(format!("{name}.ron"));
        let text = variant.unwrap_or_else(|| std::fs::read_to_string(&path).unwrap());
        let job: Job = parse_job(&path, &text).unwrap();
        let out = tempfile::tempdir().unwrap();
        let resolved = resolve(&path, job.clone()).unwrap();
        let run = run_job(&resolved, out.path(), &NoProgress).unwrap();
        let report = read(&run.dir.join("report.json"));
        let per_mm = job.units.per_mm();
        let TaskSpec::Compare(c) = &job.task else {
            panic!("{name}: not a Compare job")
        };
        for (i, p) in c.processes.iter().enumerate() {
            let row = &report["processes"][i];
            if row["status"] == "NotApplicable" {
                continue;
            }
            let Some(task) = own_task(p) else { continue };
            let folder = row["folder"].as_str().unwrap();
            let mut own = job.clone();
            own.name = format!("{name}-own-{i}");
            own.task = task.clone();
            own.outputs = vec![OutputSpec::Report];
            let mut own = resolve(&path, own).unwrap();
            // the comparison plans the blade's robot program (its cut path is measured
            // there), as a job that writes RAPID does; its files need not be written here
            own.context.rapid = matches!(
                task,
                TaskSpec::HotBlade(_) | TaskSpec::FacadeSegmentation(_)
            );
            // a task that refuses (nothing to cut) still writes its report: it is compared too
            let dir = out.path().join(&own.context.name);
            if let Err(e) = run_job(&own, out.path(), &NoProgress) {
                assert!(
                    e.to_string().contains("nothing to cut"),
                    "{name} {folder}: {e}"
                );
            }
            let mine = unnamed(read(&dir.join("report.json")));
            let theirs = unnamed(read(&run.dir.join(folder).join("report.json")));
            assert!(
                mine == theirs,
                "{name}: {folder}/report.json differs from its own task's run"
            );
            // the numbers compared are the task's own
            let (blocks, cut, dev) = own_numbers(&task, &mine, per_mm);
            let fig = &row["figures"];
            assert_eq!(
                fig["blocks"].as_u64().unwrap() as usize,
                blocks,
                "{name} {folder}: blocks"
            );
            if cut.is_finite() {
                assert!(
                    close(fig["cut_length"].as_f64().unwrap(), cut),
                    "{name} {folder}: cut length {} vs {cut}",
                    fig["cut_length"]
                );
            }
            if let Some((rms, max)) = dev {
                assert!(
                    close(fig["deviation"]["rms"].as_f64().unwrap(), rms),
                    "{name} {folder}: rms"
                );
                assert!(
                    close(fig["deviation"]["max"].as_f64().unwrap(), max),
                    "{name} {folder}: max"
                );
            }
            checked += 1;
        }
        // milling the job's blocks against the pre-cut's own volumes of the same block
        if name == "compare-mould" {
            let rows = report["processes"].as_array().unwrap();
            let mill = rows.iter().find(|r| r["id"] == "milling").unwrap();
            let pre = read(&run.dir.join("precut_milling/report.json"));
            let b = &pre["block"];
            let v: f64 = (0..3)
                .map(|k| b["max"][k].as_f64().unwrap() - b["min"][k].as_f64().unwrap())
                .product();
            let vol = |k: &str| pre["volumes"][k].as_f64().unwrap() * v;
            let part = mill["figures"]["part_volume"].as_f64().unwrap();
            let milled = mill["figures"]["milling_volume"].as_f64().unwrap();
            assert!(
                (part - vol("model")).abs() <= 1e-6 * v,
                "model {part} vs {}",
                vol("model")
            );
            assert!(
                (milled - vol("bounding_box")).abs() <= 1e-6 * v,
                "box {milled} vs {}",
                vol("bounding_box")
            );
            let pc = rows.iter().find(|r| r["id"] == "precut_milling").unwrap();
            assert!(close(
                pc["figures"]["milling_volume"].as_f64().unwrap(),
                vol("ruled")
            ));
        }
    }
    assert!(checked >= 8, "only {checked} processes checked");
}

/// The cost of every feasible process, recomputed here from its figures and the report's
/// rates by the formulas the README states, and the ranking from those costs.
#[test]
fn costs_and_ranking_follow_from_the_figures_and_rates() {
    for name in ["compare-closed", "compare-facade", "compare-mould"] {
        let path = root().join("jobs").join(format!("{name}.ron"));
        let job = hotcut::load::load_job(&path).unwrap();
        let out = tempfile::tempdir().unwrap();
        let run = run_job(&job, out.path(), &NoProgress).unwrap();
        let r = read(&run.dir.join("report.json"));
        let rate = |f: &str| {
            r["rates"]
                .as_array()
                .unwrap()
                .iter()
                .find(|x| x["field"] == f)
                .unwrap()["value"]
                .as_f64()
                .unwrap()
        };
        let per_mm = match r["units"].as_str().unwrap() {
            "Metre" => 1e-3_f64,
            _ => 1.0,
        };
        let m3 = (1e-3_f64 / per_mm).powi(3);
        let mut ranked: Vec<(f64, String)> = Vec::new();
        for p in r["processes"].as_array().unwrap() {
            let Some(c) = p["cost"].as_object() else {
                continue;
            };
            let f = &p["figures"];
            let g = |k: &str| f[k].as_f64().unwrap();
            let blade = f["cutter"] == "Blade";
            let field = if blade { "blade_speed" } else { "wire_speed" };
            let rates = r["rates"].as_array().unwrap();
            let row = rates.iter().find(|x| x["field"] == field).unwrap();
            // a speed the job leaves out is the programs' own
            let speed = if row["set_by_job"] == false && g("cut_speed") > 0.0 {
                g("cut_speed")
            } else {
                rate(field)
            };
            // the heated path at its speed, and the preheat dwells
            let cut_h = (g("cut_length") / speed + g("dwell_s")) / 3600.0;
            // the thermal cuts' set-ups, and each block once on the milling machine
            let (mut mill_h, mut setups) = (0.0, g("setups"));
            if let Some(t) = p["tool"].as_object() {
                let feed = t["feed"].as_f64().unwrap_or(rate("finishing_feed"));
                let removal = t["removal_rate"].as_f64().unwrap_or(rate("removal_rate"));
                mill_h = g("milling_volume") / removal / 60.0
                    + g("milled_area") / (t["stepover"].as_f64().unwrap() * feed) / 60.0;
                setups += g("blocks");
            }
            let setup_h = setups * rate("setup_minutes") / 60.0;
            let machine = cut_h
                * rate(if blade {
                    "blade_per_hour"
                } else {
                    "wire_per_hour"
                })
                + mill_h * rate("milling_per_hour");
            let labour = (cut_h + mill_h + setup_h) * rate("operator_per_hour");
            let total = g("stock_volume") * m3 * rate("eps_per_m3") + machine + labour;
            let want = c["total"].as_f64().unwrap();
            assert!(
                (total - want).abs() <= 1e-6 * want,
                "{name} {}: {total} vs {want}",
                p["id"]
            );
            if p["status"] == "Feasible" {
                ranked.push((total, p["id"].as_str().unwrap().to_string()));
            }
        }
        ranked.sort_by(|a, b| a.0.total_cmp(&b.0));
        let ids: Vec<&str> = r["ranking"]
            .as_array()
            .unwrap()
            .iter()
            .map(|v| v.as_str().unwrap())
            .collect();
        let mine: Vec<&str> = ranked.iter().map(|(_, id)| id.as_str()).collect();
        assert_eq!(ids, mine, "{name}");
    }
}
