//! The whole chain on closed models.

mod common;

use ruled_blocks::{run, Params};

fn params(tol: f64, block: f64) -> Params {
    Params {
        axis: [1.0, 0.0, 0.0],
        sections: 24,
        tolerance: tol,
        max_strips: 48,
        blocks: blocks::Params {
            block_size: [block; 3],
            max_iterations: 10,
            sample_spacing: 0.1,
            seed: 1,
            ..blocks::Params::default()
        },
        kerf: 0.0,
        lead: 20.0,
    }
}

#[test]
fn half_sphere_report() {
    let m = common::half_sphere(500.0, 64);
    let r = run(&m, &params(5.0, 600.0), &|_| {}).unwrap();
    eprintln!("regions {}", r.regions.len());
    for g in &r.regions {
        eprintln!(
            "  strips {} sides {:?} controls {} fit max {:.3} dev {:?}",
            g.region.strips, g.region.side_strips, g.region.controls, g.region.fit_max, g.deviation
        );
    }
    eprintln!("dev {:?} diag {}", r.deviation, r.diagonal);
    eprintln!(
        "solid volume {} model {}",
        r.solid.mesh.volume(),
        m.volume()
    );
    for b in &r.blocks {
        eprintln!(
            "block cuttable {} cuts {} deepest {:.3} added {:.0} depth {:.2} reason {:?}",
            b.cuttable,
            b.cuts.len(),
            b.deepest,
            b.added_volume,
            b.added_depth,
            b.reason
        );
    }
}

#[test]
fn torus_report() {
    let m = common::torus(1000.0, 350.0, 48, 24);
    let r = run(&m, &params(10.0, 550.0), &|_| {}).unwrap();
    eprintln!("regions {}", r.regions.len());
    for g in &r.regions {
        eprintln!(
            "  first {} n {} strips {} sides {:?} controls {} fit max {:.3} dev {:?}",
            g.region.first,
            g.region.offsets.len(),
            g.region.strips,
            g.region.side_strips,
            g.region.controls,
            g.region.fit_max,
            g.deviation
        );
    }
    eprintln!("dev {:?} diag {}", r.deviation, r.diagonal);
    eprintln!(
        "solid volume {} model {}",
        r.solid.mesh.volume(),
        m.volume()
    );
    for b in &r.blocks {
        eprintln!(
            "block cuttable {} cuts {} deepest {:.3} added {:.0} depth {:.2} reason {:?}",
            b.cuttable,
            b.cuts.len(),
            b.deepest,
            b.added_volume,
            b.added_depth,
            b.reason
        );
    }
}
