//! Nearly straight Béziers against their elastica (issue 37): random cubic Béziers from
//! (0, 0) to (1, 0) whose length is within 10⁻¹² … 10⁻² of the chord (log-uniform), legs
//! from `min_leg` to 0.6 of the chord, inner control points 0.2–1 (scaled) off it, C- or
//! S-shaped; counts those whose elastica misses the end data by more than 10⁻⁹ (end points
//! relative to the length, tangents in radians, length relative) or is not found.
//!
//! `cargo run --release -p hotcut-design --example near_straight_sweep -- [count] [min_leg]`
//! (defaults 10 000 and 0.15). A fixed-seed generator: the same pieces every run.

use design::bezier::Bezier;
use design::proxy::proxy;

fn flat(a: f64, b: f64, h: [f64; 2], r: f64) -> Bezier {
    Bezier {
        p: [[0.0, 0.0], [a, r * h[0]], [1.0 - b, r * h[1]], [1.0, 0.0]],
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count: usize = args.first().and_then(|a| a.parse().ok()).unwrap_or(10_000);
    let min_leg: f64 = args.get(1).and_then(|a| a.parse().ok()).unwrap_or(0.15);
    let mut seed = 12345u64;
    let mut rnd = || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let (mut missed, mut failed, mut worst) = (0, 0, [0.0f64; 3]);
    let t0 = std::time::Instant::now();
    for _ in 0..count {
        let target = 10f64.powf(-12.0 + 10.0 * rnd());
        let a = min_leg + (0.6 - min_leg) * rnd();
        let b = min_leg + (0.6 - min_leg) * rnd();
        let h0 = 0.2 + 0.8 * rnd();
        let h1 = 0.2 + 0.8 * rnd();
        let s = if rnd() < 0.5 { -1.0 } else { 1.0 };
        let h = [h0, s * h1];
        // the slack grows like r²: a fixed-point iteration on that
        let mut r = target.sqrt();
        for _ in 0..60 {
            let slack = flat(a, b, h, r).length() - 1.0;
            if (slack / target - 1.0).abs() < 1e-6 {
                break;
            }
            r *= (target / slack).sqrt();
        }
        let piece = flat(a, b, h, r);
        match proxy(&piece) {
            Ok(p) => {
                let e = [
                    p.end_point_error / p.length,
                    p.end_angle_error,
                    p.relative_length_error.abs(),
                ];
                for i in 0..3 {
                    worst[i] = worst[i].max(e[i]);
                }
                if e.iter().any(|v| *v > 1e-9) {
                    missed += 1;
                    println!(
                        "missed by {:.1e} {:.1e} {:.1e}: {piece:?}",
                        e[0], e[1], e[2]
                    );
                }
            }
            Err(err) => {
                failed += 1;
                println!("failed: {err}: {piece:?}");
            }
        }
    }
    println!(
        "{count} pieces, legs {min_leg}–0.6: {failed} not solved, {missed} beyond 1e-9; worst end point {:.1e}, tangent {:.1e}, length {:.1e}; {:.1} s",
        worst[0],
        worst[1],
        worst[2],
        t0.elapsed().as_secs_f64()
    );
}
