//! Acceptance: for analytic height fields the inflection count of each section equals the
//! number of sign changes of ∂²z/∂y² along it; the same surfaces as fine OBJ meshes
//! (vertex spacing ≤ 0.2 % of the extent) agree on at least 90 % of the sections; on
//! fine meshes of rippled surfaces (10–20 inflections per section), in millimetres and in
//! metres, at least 95 % of the sections are exact.
//!
//! The reference counts come from hand-written Rust closures for z, evaluated with central
//! second differences on a dense grid: independent of hotcut's expression parser, its
//! exact derivatives and its curve analysis.

use std::path::Path;

use hotcut::job::TaskSpec;
use hotcut::load::load_job;
use hotcut::task::Task;
use hotcut::NoProgress;

struct Case {
    name: &'static str,
    expr: &'static str,
    f: fn(f64, f64) -> f64,
    x: (f64, f64),
    y: (f64, f64),
}

const CASES: &[Case] = &[
    Case {
        name: "ripples",
        expr: "40*sin(y/70)*(1 + x/2000)",
        f: |x, y| 40.0 * (y / 70.0).sin() * (1.0 + x / 2000.0),
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Case {
        name: "oblique",
        expr: "30*sin(x/150 + y/90) + 20*cos(y/60)",
        f: |x, y| 30.0 * (x / 150.0 + y / 90.0).sin() + 20.0 * (y / 60.0).cos(),
        x: (0.0, 1200.0),
        y: (0.0, 1200.0),
    },
    Case {
        name: "design-tool",
        expr: "20*cos(2*(pi/2 - y/1000)^4)*sin(x/1000)*exp(-0.1*(x/1000)^2)",
        f: |x, y| {
            let (u, v) = (x / 1000.0, y / 1000.0);
            20.0 * (2.0 * (std::f64::consts::FRAC_PI_2 - v).powi(4)).cos()
                * u.sin()
                * (-0.1 * u * u).exp()
        },
        x: (-1570.796327, 1570.796327),
        y: (-750.0, 750.0),
    },
];

/// Sign changes of ∂²z/∂y² along x = const, sampled densely (zeros skipped).
fn reference_count(c: &Case, x: f64) -> usize {
    let n = 60_000;
    let h = 1e-2;
    let mut last = 0i8;
    let mut count = 0;
    for i in 0..=n {
        let y = c.y.0 + (c.y.1 - c.y.0) * i as f64 / n as f64;
        let d2 = ((c.f)(x, y + h) - 2.0 * (c.f)(x, y) + (c.f)(x, y - h)) / (h * h);
        let s = if d2 > 1e-12 {
            1
        } else if d2 < -1e-12 {
            -1
        } else {
            0
        };
        if s != 0 {
            if last != 0 && s != last {
                count += 1;
            }
            last = s;
        }
    }
    count
}

fn job_text(name: &str, surface: &str) -> String {
    format!(
        "Job(name: \"{name}\", surface: {surface}, cutting: Cutting(sections: 26), task: Analyze(samples: 6000), outputs: [Report])"
    )
}

fn counts(path: &Path) -> Vec<(f64, usize)> {
    positions(path)
        .into_iter()
        .map(|(o, p)| (o, p.len()))
        .collect()
}

/// Each section's offset and the y (world) of its inflections.
fn positions(path: &Path) -> Vec<(f64, Vec<f64>)> {
    let job = load_job(path).unwrap_or_else(|e| panic!("{e:?}"));
    let TaskSpec::Analyze(task) = &job.task else {
        panic!("not an Analyze job");
    };
    let params = task.params(&job.context).unwrap();
    let a = hotcut::analyze::Analyze::run(&params, &job.context, &NoProgress).unwrap();
    a.survey
        .reports
        .iter()
        .map(|s| {
            (
                s.offset,
                s.inflections.iter().map(|p| p.position[1]).collect(),
            )
        })
        .collect()
}

#[test]
fn analytic_sections_count_sign_changes_of_fyy() {
    let dir = tempfile::tempdir().unwrap();
    for c in CASES {
        let surface = format!(
            "HeightField(z: \"{}\", x: ({}, {}), y: ({}, {}))",
            c.expr, c.x.0, c.x.1, c.y.0, c.y.1
        );
        let path = dir.path().join(format!("{}.ron", c.name));
        std::fs::write(&path, job_text(c.name, &surface)).unwrap();
        let got = counts(&path);
        assert_eq!(got.len(), 26, "{}", c.name);
        let total: usize = got.iter().map(|g| g.1).sum();
        assert!(
            total >= 26 * 4,
            "{}: want many inflections, got {total}",
            c.name
        );
        for (x, n) in got {
            assert_eq!(n, reference_count(c, x), "{} at x = {x}", c.name);
        }
    }
}

#[test]
fn fine_meshes_agree_with_the_analytic_counts() {
    let dir = tempfile::tempdir().unwrap();
    for c in CASES {
        // 500 × 500 cells: spacing ≤ extent / 500 = 0.2 % of the extent
        let hf = geom::heightfield::HeightField::try_new(
            geom::expr::Expr::parse(c.expr).unwrap(),
            c.x,
            c.y,
        )
        .unwrap();
        let mesh = hf.to_mesh(500, 500).unwrap();
        let spacing = ((c.x.1 - c.x.0) / 500.0).max((c.y.1 - c.y.0) / 500.0);
        let extent = (c.x.1 - c.x.0).max(c.y.1 - c.y.0);
        assert!(spacing <= 0.002 * extent + 1e-9);
        let obj = dir.path().join(format!("{}.obj", c.name));
        let mut f = std::io::BufWriter::new(std::fs::File::create(&obj).unwrap());
        export::obj::write_mesh(&mut f, &mesh, 6, export::SourceUnits::METRE).unwrap();
        drop(f);
        let path = dir.path().join(format!("{}-mesh.ron", c.name));
        std::fs::write(
            &path,
            job_text(c.name, &format!("Mesh(path: \"{}.obj\")", c.name)),
        )
        .unwrap();
        let got = counts(&path);
        assert_eq!(got.len(), 26, "{}", c.name);
        let agree = got
            .iter()
            .filter(|(x, n)| *n == reference_count(c, *x))
            .count();
        let misses: Vec<String> = got
            .iter()
            .filter(|(x, n)| *n != reference_count(c, *x))
            .map(|(x, n)| format!("x={x:.1}: {n} vs {}", reference_count(c, *x)))
            .collect();
        assert!(
            agree * 10 >= got.len() * 9,
            "{}: {agree}/{} agree; {misses:?}",
            c.name,
            got.len()
        );
        eprintln!("{}: mesh agrees on {agree}/{} sections", c.name, got.len());
    }
}

/// The mesh facade of the jobs (`jobs/models/facade.obj`: the height field below on a
/// 20 mm grid) cut at 45° in plan: the sections cross the triangles' edges at every angle,
/// so the facets' chordal error alternates along a section. Smoothing within the facets'
/// own error (their edges' bending, from the vertex normals) keeps that from becoming
/// inflections: the mesh's counts equal the exact height field's on at least 10 of the 12
/// sections, and never exceed them by more than one.
#[test]
fn a_mesh_cut_at_45_degrees_agrees_with_its_height_field() {
    let dir = tempfile::tempdir().unwrap();
    let models = Path::new(env!("CARGO_MANIFEST_DIR")).join("jobs/models");
    let text = |name: &str, surface: &str| {
        format!(
            "Job(name: \"{name}\", surface: {surface}, cutting: Cutting(direction: (1, 1, 0), sections: 12), tolerance: Tolerance(smoothing: 0.05), task: Analyze(samples: 6000), outputs: [Report])"
        )
    };
    let exact = dir.path().join("exact.ron");
    std::fs::write(
        &exact,
        text(
            "exact",
            "HeightField(z: \"90*sin(x/380)*cos(y/330) + 35*cos(x/260)\", x: (0, 1800), y: (0, 1200))",
        ),
    )
    .unwrap();
    let mesh = dir.path().join("mesh.ron");
    let obj = models.join("facade.obj");
    std::fs::write(
        &mesh,
        text(
            "mesh",
            &format!("Mesh(path: {:?})", obj.display().to_string()),
        ),
    )
    .unwrap();
    let (a, b) = (counts(&exact), counts(&mesh));
    assert_eq!(a.len(), b.len());
    let agree = a.iter().zip(&b).filter(|(p, q)| p.1 == q.1).count();
    println!(
        "45°: exact {:?}, mesh {:?}: {agree} of {} agree",
        a.iter().map(|p| p.1).collect::<Vec<_>>(),
        b.iter().map(|p| p.1).collect::<Vec<_>>(),
        a.len()
    );
    assert!(agree >= 10, "{agree} of {}", a.len());
    assert!(a.iter().zip(&b).all(|(p, q)| q.1 <= p.1 + 1));
}

/// Rippled surfaces of the held-out class of issue 19 (10–20 inflections per section,
/// amplitudes of 0.1–1 % of the section, meshes at 0.2 % of the extent). Their `expr` is
/// in millimetres with `X` and `Y` for the coordinates, so the same surface can be stated
/// in metres (`ripple_expr`).
const RIPPLES: &[Case] = &[
    Case {
        name: "tilted-crests",
        expr: "12*sin(Y/45 + X/400)",
        f: |x, y| 12.0 * (y / 45.0 + x / 400.0).sin(),
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Case {
        name: "two-waves",
        expr: "8*sin(Y/50) + 1.5*sin(Y/23 + X/300)",
        f: |x, y| 8.0 * (y / 50.0).sin() + 1.5 * (y / 23.0 + x / 300.0).sin(),
        x: (0.0, 1200.0),
        y: (0.0, 1500.0),
    },
    Case {
        name: "chirp",
        expr: "10*sin(1.5*(Y/300)^2 + X/700)",
        f: |x, y| 10.0 * (1.5 * (y / 300.0).powi(2) + x / 700.0).sin(),
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Case {
        name: "decaying",
        expr: "15*exp(-Y/900)*sin(Y/55 + X/500)",
        f: |x, y| 15.0 * (-y / 900.0).exp() * (y / 55.0 + x / 500.0).sin(),
        x: (0.0, 1000.0),
        y: (0.0, 1800.0),
    },
    Case {
        name: "vault-ripples",
        expr: "(Y - 750)^2/4000 + 4*sin(Y/40 + X/250)",
        f: |x, y| (y - 750.0).powi(2) / 4000.0 + 4.0 * (y / 40.0 + x / 250.0).sin(),
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Case {
        name: "oblique-wave",
        expr: "10*sin(X/120 + Y/75)",
        f: |x, y| 10.0 * (x / 120.0 + y / 75.0).sin(),
        x: (0.0, 1500.0),
        y: (0.0, 2400.0),
    },
    Case {
        name: "egg-crate",
        expr: "6*sin(X/80)*sin(Y/45) + X/20",
        f: |x, y| 6.0 * (x / 80.0).sin() * (y / 45.0).sin() + x / 20.0,
        x: (0.0, 1000.0),
        y: (0.0, 1600.0),
    },
    Case {
        name: "shallow",
        expr: "2*sin(Y/35 + X/600) + Y/10",
        f: |x, y| 2.0 * (y / 35.0 + x / 600.0).sin() + y / 10.0,
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
];

/// Where the second derivative of z along the section changes sign (zeros skipped): the
/// section by the plane `d · p = offset`, `d = (cos θ, sin θ)`, inside the rectangle, as
/// the coordinate along `t = (−sin θ, cos θ)` (y for θ = 0).
fn ripple_reference_along(r: &Case, theta: f64, offset: f64) -> Vec<f64> {
    let (d, t) = ((theta.cos(), theta.sin()), (-theta.sin(), theta.cos()));
    let (mut s0, mut s1) = (f64::NEG_INFINITY, f64::INFINITY);
    for (o, dir, (lo, hi)) in [(offset * d.0, t.0, r.x), (offset * d.1, t.1, r.y)] {
        if dir.abs() > 1e-12 {
            let (a, b) = ((lo - o) / dir, (hi - o) / dir);
            s0 = s0.max(a.min(b));
            s1 = s1.min(a.max(b));
        }
    }
    let f = |s: f64| (r.f)(offset * d.0 + s * t.0, offset * d.1 + s * t.1);
    let mut at = Vec::new();
    let n = 200_000;
    let h = 1e-2;
    let mut last = 0i8;
    for i in 0..=n {
        let u = s0 + (s1 - s0) * i as f64 / n as f64;
        let d2 = (f(u + h) - 2.0 * f(u) + f(u - h)) / (h * h);
        let s = if d2 > 1e-12 {
            1
        } else if d2 < -1e-12 {
            -1
        } else {
            0
        };
        if s != 0 {
            if last != 0 && s != last {
                at.push(u);
            }
            last = s;
        }
    }
    at
}

/// The surface's expression in units of `scale` job units per millimetre.
fn ripple_expr(r: &Case, scale: f64) -> String {
    let body = r
        .expr
        .replace('X', &format!("(x/{scale})"))
        .replace('Y', &format!("(y/{scale})"));
    format!("{scale}*({body})")
}

/// Issue 19 item 4: on fine meshes of rippled surfaces at least 95 % of the sections count
/// exactly the sign changes of the exact second derivative along the section, in
/// millimetres and in metres, for sections along x and oblique ones (direction (1, 0.5)). The
/// failures this guards against: inflections a few millimetres from a section's end (the
/// smoothing spline's end condition hides them; the local end fits of `geom::ends`
/// restore them) and pairs of inflections around a lobe that barely turns (dropped as
/// noise although the mesh's points resolve them). Before the fix: 154 of 192.
#[test]
fn fine_meshes_of_rippled_surfaces_count_95_percent_of_sections_exactly() {
    let dir = tempfile::tempdir().unwrap();
    let sections = 12;
    let mut total = 0;
    let mut exact = 0;
    let mut report = Vec::new();
    let mut counts_seen = Vec::new();
    for (units, scale) in [("Millimetre", 1.0), ("Metre", 1e-3)] {
        for r in RIPPLES {
            let (x, y) = (
                (r.x.0 * scale, r.x.1 * scale),
                (r.y.0 * scale, r.y.1 * scale),
            );
            let hf = geom::heightfield::HeightField::try_new(
                geom::expr::Expr::parse(&ripple_expr(r, scale)).unwrap(),
                x,
                y,
            )
            .unwrap();
            let mesh = hf.to_mesh(500, 500).unwrap();
            let obj = dir.path().join(format!("{}-{units}.obj", r.name));
            let mut f = std::io::BufWriter::new(std::fs::File::create(&obj).unwrap());
            export::obj::write_mesh(&mut f, &mesh, 9, export::SourceUnits::METRE).unwrap();
            drop(f);
            // along x (sections x = const, the class's axis-aligned case) and oblique
            for (tag, theta, direction) in [
                ("x", 0.0, "(1, 0, 0)"),
                ("oblique", 0.5f64.atan(), "(1, 0.5, 0)"),
            ] {
                let path = dir.path().join(format!("{}-{units}-{tag}.ron", r.name));
                std::fs::write(
                    &path,
                    format!(
                        "Job(name: \"{}\", units: {units}, surface: Mesh(path: \"{}-{units}.obj\"), cutting: Cutting(direction: {direction}, sections: {sections}), task: Analyze(samples: 6000), outputs: [Report])",
                        r.name, r.name
                    ),
                )
                .unwrap();
                let got = positions(&path);
                assert_eq!(got.len(), sections, "{}", r.name);
                for (offset, at) in got {
                    let n = at.len();
                    let want_at = ripple_reference_along(r, theta, offset / scale);
                    let want = want_at.len();
                    total += 1;
                    if n == want {
                        exact += 1;
                    } else {
                        report.push(format!(
                            "{units} {} {tag} offset {:.1}: {n} vs {want} at {:?}",
                            r.name,
                            offset / scale,
                            want_at.iter().map(|v| v.round()).collect::<Vec<_>>()
                        ));
                    }
                    if tag == "x" {
                        counts_seen.push(want);
                    }
                }
            }
        }
    }
    // the class: 10–20 inflections per section on average, none trivial
    let mean = counts_seen.iter().sum::<usize>() as f64 / counts_seen.len() as f64;
    assert!((10.0..=20.0).contains(&mean), "mean {mean}");
    assert!(
        counts_seen.iter().all(|&c| (8..=22).contains(&c)),
        "{counts_seen:?}"
    );
    eprintln!("{exact}/{total} sections exact; misses: {report:#?}");
    assert!(exact * 100 >= total * 95, "{exact}/{total}: {report:#?}");
}
