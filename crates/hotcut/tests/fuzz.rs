//! Random corruptions of a valid job never panic: every one either loads or returns errors.

use hotcut::load::{parse_job, resolve, validate_schema};
use proptest::prelude::*;

const VALID: &str = r#"Job(name: "t", surface: HeightField(z: "50*sin(y/100)", x: (0, 300), y: (0, 900)), block: Block(size: (600, 600, 600)), blade: Blade(length: 1000, max_curvature: 0.011, max_inflections: 2), cutting: Cutting(direction: (1, 0, 0), sections: 3), tolerance: Tolerance(rms: 0.5), task: Analyze(samples: 100), outputs: [Report, Svg], seed: 1)"#;

proptest! {
    #![proptest_config(ProptestConfig { cases: 400, ..ProptestConfig::default() })]

    #[test]
    fn corrupted_jobs_do_not_panic(edits in prop::collection::vec((0usize..VALID.len(), 0usize..4, prop::sample::select(vec!["", "-", "NaN", "(", ")", ",", "\"", "0", "1e999", "x", ":", "Some(", "inf"])), 1..4)) {
        let mut text = VALID.to_string();
        for (pos, del, ins) in edits {
            let pos = pos.min(text.len());
            if !text.is_char_boundary(pos) { continue; }
            let end = (pos + del).min(text.len());
            if !text.is_char_boundary(end) { continue; }
            text.replace_range(pos..end, ins);
        }
        let path = std::path::Path::new("fuzz.ron");
        if let Ok(job) = parse_job(path, &text) {
            if validate_schema(path, &job).is_ok() {
                let _ = resolve(path, job);
            }
        }
    }
}
