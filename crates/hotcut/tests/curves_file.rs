//! Reading curves files (`FitCurves(input: ..)`): JSON and CSV give the same curves, and
//! every malformed file is rejected with a reason naming the line or curve.

use std::path::Path;

use hotcut::fit_curves::curves::read_curves;

fn write(name: &str, text: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join(name);
    std::fs::write(&p, text).unwrap();
    (dir, p)
}

#[test]
fn json_and_csv_give_the_same_curves() {
    let (_a, json) = write(
        "c.json",
        r#"{"curves": [{"id": "a", "class": "x", "points": [[0, 0], [1, 0.5], [2, 0]]},
                       {"id": 7, "points": [[0, 1], [1, 1], [2, 1.5]]}]}"#,
    );
    let (_b, csv) = write(
        "c.csv",
        "id,x,y\na,0,0\na,1,0.5\na,2,0\n\n7,0,1\n7,1,1\n7,2,1.5\n",
    );
    let (j, c) = (read_curves(&json).unwrap(), read_curves(&csv).unwrap());
    assert_eq!(j, c);
    assert_eq!(j.len(), 2);
    assert_eq!(j[1].id, "7");
    assert_eq!(j[0].points[1], [1.0, 0.5]);
}

#[test]
fn bad_curve_files_are_rejected_with_a_reason() {
    let cases = [
        ("a.json", "{\"curves\": []}", "no curves"),
        (
            "b.json",
            "{\"curves\": [{\"id\": \"a\"}]}",
            "missing field `points`",
        ),
        ("c.json", "{\"curves\": [", "EOF"),
        (
            "d.json",
            "{\"curves\": [{\"id\": \"a\", \"points\": [[0, 0], [1, 1]]}]}",
            "at least 3",
        ),
        (
            "e.json",
            "{\"curves\": [{\"id\": \"a\", \"points\": [[0, 0], [1, 1], [1, 1]]}]}",
            "coincide",
        ),
        ("f.csv", "x,y\n0,0\n", "header"),
        ("g.csv", "id,x,y\na,0,0\na,1,nan\na,2,0\n", "not finite"),
        ("h.csv", "id,x,y\na,0,zero\n", "line 2"),
        ("i.csv", "id,x,y\na,0,0,1\n", "3 fields"),
        (
            "j.csv",
            "id,x,y\na,0,0\na,1,1\na,2,0\nb,0,0\nb,1,1\nb,2,0\na,5,5\n",
            "twice",
        ),
    ];
    for (name, text, expect) in cases {
        let (_d, p) = write(name, text);
        let e = read_curves(&p).unwrap_err();
        assert!(e.contains(expect), "{name}: `{e}` lacks `{expect}`");
    }
    let missing = read_curves(Path::new("/nonexistent/curves.json")).unwrap_err();
    assert!(missing.contains("curves.json"));
}
