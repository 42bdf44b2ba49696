//! The architecture invariants of `crates/hotcut/src` (ARCHITECTURE.md), checked on the
//! source text:
//! - no task module imports another task's module;
//! - `report` and `load` import no task module;
//! - no module imports one that imports it back, directly or through others (the graph of
//!   top-level modules has no cycle), and nothing imports through the crate root;
//! - no function is longer than [`MAX_FN_LINES`] lines.
//!
//! A task module is a top-level module whose source implements `Task`. Imports are every
//! `crate::<module>` path and every `super::` path that leaves its top-level module, in
//! code (comments and string literals are skipped), inline modules (`mod tests { .. }`)
//! taken into account, and every `"crate::<module>…"` string of an attribute line
//! (`#[serde(default = "crate::spec::keep_length")]`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Longest function allowed in hotcut, in lines (signature to closing brace).
const MAX_FN_LINES: usize = 120;

/// Rust source reduced to code: comments and the contents of string and char literals
/// are replaced by spaces (newlines kept), so that line numbers and braces stay right.
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(b.len());
    let mut i = 0;
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
        } else if c == 'r' && (next == Some('"') || next == Some('#')) && !ident_before(&b, i) {
            // raw string r"..." or r#"..."#
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            out.push('"');
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                out.push(blank(b[j]));
                j += 1;
            }
            out.push('"');
            i = j;
        } else if c == '"' {
            out.push('"');
            i += 1;
            while i < b.len() && b[i] != '"' {
                if b[i] == '\\' {
                    out.push(' ');
                    i += 1;
                }
                if i < b.len() {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
            out.push('"');
            i += 1;
        } else if c == '\'' {
            // a char literal ('x', '\n', '\u{..}'), not a lifetime
            let close = if next == Some('\\') {
                (i + 2..b.len().min(i + 12)).find(|&k| b[k] == '\'')
            } else if b.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match close {
                Some(k) => {
                    out.push_str(&" ".repeat(k - i + 1));
                    i = k + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_before(b: &[char], i: usize) -> bool {
    i > 0 && (b[i - 1].is_alphanumeric() || b[i - 1] == '_')
}

/// The identifier starting at byte `i` of `s`.
fn ident_at(s: &str, i: usize) -> &str {
    let rest = &s[i..];
    let end = rest
        .find(|c: char| !(c.is_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    &rest[..end]
}

/// One source file: its module path (`["hot_blade", "outputs"]`) and its code.
struct Source {
    path: PathBuf,
    module: Vec<String>,
    code: String,
    /// The text as written (for paths in string attributes such as `serde(default = "..")`).
    raw: String,
}

fn sources(src: &Path) -> Vec<Source> {
    let mut out = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for e in std::fs::read_dir(&dir).unwrap().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p.extension().is_some_and(|x| x == "rs") {
                let rel = p.strip_prefix(src).unwrap();
                let mut module: Vec<String> = rel
                    .iter()
                    .map(|c| c.to_string_lossy().trim_end_matches(".rs").to_string())
                    .collect();
                if module.last().is_some_and(|m| m == "mod") {
                    module.pop();
                }
                if module == ["lib"] || module == ["main"] {
                    module.clear();
                }
                let raw = std::fs::read_to_string(&p).unwrap();
                let code = code_only(&raw);
                out.push(Source {
                    path: p,
                    module,
                    code,
                    raw,
                });
            }
        }
    }
    out.sort_by(|a, b| a.path.cmp(&b.path));
    out
}

/// Every top-level module the code of `s` refers to, with the line; `"<root>"` for a path
/// through the crate root (`crate::Thing`).
fn references(s: &Source, top_level: &BTreeSet<String>) -> Vec<(String, usize)> {
    let code = &s.code;
    let mut refs = Vec::new();
    // inline modules: (name, brace depth at which it closes)
    let mut inline: Vec<(String, i32)> = Vec::new();
    let mut depth = 0i32;
    let line_of = |i: usize| code[..i].matches('\n').count() + 1;
    let bytes = code.as_bytes();
    let mut i = 0;
    while i < code.len() {
        let c = bytes[i];
        if c == b'{' {
            depth += 1;
        } else if c == b'}' {
            depth -= 1;
            if inline.last().is_some_and(|m| m.1 == depth) {
                inline.pop();
            }
        }
        let word_start = i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'_');
        if word_start && code[i..].starts_with("mod ") {
            let name = ident_at(code, i + 4);
            let after = code[i + 4 + name.len()..].trim_start();
            if after.starts_with('{') {
                inline.push((name.to_string(), depth));
            }
        }
        if word_start && code[i..].starts_with("crate::") {
            let name = ident_at(code, i + 7);
            if name.is_empty() {
                panic!(
                    "{}:{}: write one `use crate::module::...` per module, not `crate::{{..}}`",
                    s.path.display(),
                    line_of(i)
                );
            }
            let target = if top_level.contains(name) {
                name.to_string()
            } else {
                "<root>".to_string()
            };
            refs.push((target, line_of(i)));
        }
        if word_start && code[i..].starts_with("super::") {
            let mut module: Vec<String> = s.module.clone();
            module.extend(inline.iter().map(|m| m.0.clone()));
            let mut j = i;
            while code[j..].starts_with("super::") {
                module.pop();
                j += 7;
            }
            if module.is_empty() {
                let name = ident_at(code, j);
                if top_level.contains(name) {
                    refs.push((name.to_string(), line_of(i)));
                } else {
                    refs.push(("<root>".to_string(), line_of(i)));
                }
            }
            i = j;
            continue;
        }
        i += 1;
    }
    // paths in string attributes: `#[serde(default = "crate::spec::keep_length")]`
    for (n, line) in s.raw.lines().enumerate() {
        if !line.trim_start().starts_with("#[") {
            continue;
        }
        for (k, _) in line.match_indices("\"crate::") {
            let name = ident_at(line, k + 8);
            let target = if top_level.contains(name) {
                name.to_string()
            } else {
                "<root>".to_string()
            };
            refs.push((target, n + 1));
        }
    }
    refs
}

/// A cycle in `graph`, if any (depth-first search).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit(
        n: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        state: &mut BTreeMap<String, u8>,
        path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(n.to_string(), 1);
        path.push(n.to_string());
        for m in graph.get(n).into_iter().flatten() {
            match state.get(m.as_str()).copied().unwrap_or(0) {
                1 => {
                    let start = path.iter().position(|p| p == m).unwrap_or(0);
                    let mut cycle = path[start..].to_vec();
                    cycle.push(m.clone());
                    return Some(cycle);
                }
                0 => {
                    if let Some(c) = visit(m, graph, state, path) {
                        return Some(c);
                    }
                }
                _ => {}
            }
        }
        path.pop();
        state.insert(n.to_string(), 2);
        None
    }
    let mut state = BTreeMap::new();
    for n in graph.keys() {
        if state.get(n.as_str()).copied().unwrap_or(0) == 0 {
            if let Some(c) = visit(n, graph, &mut state, &mut Vec::new()) {
                return Some(c);
            }
        }
    }
    None
}

fn src_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The import graph of top-level modules, and the task modules.
fn graph() -> (
    BTreeMap<String, BTreeSet<String>>,
    BTreeSet<String>,
    Vec<String>,
) {
    let files = sources(&src_dir());
    let top_level: BTreeSet<String> = files
        .iter()
        .filter_map(|s| s.module.first().cloned())
        .collect();
    let implements_task = |code: &str| {
        code.split("impl").skip(1).any(|rest| {
            let head = rest.split('{').next().unwrap_or("");
            // `impl<P> Task for Compare<P>`: the generics first
            let head = match head.trim_start().strip_prefix('<') {
                Some(generic) => generic.split_once('>').map_or("", |(_, r)| r),
                None => head,
            };
            let mut words = head.split_whitespace();
            let trait_path = words.next().unwrap_or("");
            (trait_path == "Task" || trait_path.ends_with("::Task")) && words.next() == Some("for")
        })
    };
    let tasks: BTreeSet<String> = files
        .iter()
        .filter(|s| implements_task(&s.code))
        .filter_map(|s| s.module.first().cloned())
        .collect();
    let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let mut problems = Vec::new();
    for s in &files {
        let Some(from) = s.module.first() else {
            continue; // lib.rs and main.rs: the root may use every module
        };
        for (to, line) in references(s, &top_level) {
            let at = format!("{}:{line}", s.path.display());
            if to == "<root>" {
                problems.push(format!("{at}: `{from}` imports through the crate root"));
            } else if &to != from {
                graph.entry(from.clone()).or_default().insert(to);
            }
        }
    }
    (graph, tasks, problems)
}

#[test]
fn no_task_imports_another_and_report_and_load_import_none() {
    let (graph, tasks, problems) = graph();
    assert!(problems.is_empty(), "{}", problems.join("\n"));
    assert!(tasks.len() >= 6, "task modules found: {tasks:?}");
    let mut bad = Vec::new();
    for (from, tos) in &graph {
        // `job` holds the list of tasks; nothing else names one
        if from != "job" {
            bad.extend(tos.intersection(&tasks).map(|to| format!("{from} → {to}")));
        }
    }
    assert!(
        bad.is_empty(),
        "modules importing a task module (only `job`, the task list, may): {bad:?}"
    );
    for m in ["report", "load"] {
        let tos = graph.get(m).cloned().unwrap_or_default();
        assert!(tos.is_disjoint(&tasks), "{m} imports {tos:?}");
    }
}

#[test]
fn the_job_module_names_exactly_the_tasks_and_only_it_dispatches() {
    let (graph, tasks, _) = graph();
    let from_job: BTreeSet<String> = graph.get("job").cloned().unwrap_or_default();
    let expected: BTreeSet<String> = tasks
        .iter()
        .cloned()
        .chain(["spec".to_string(), "task".to_string()])
        .collect();
    assert_eq!(
        from_job, expected,
        "job must import every task module and only them"
    );
    // `TaskSpec::visit` is the one dispatch on the task: no other module names a variant
    for s in sources(&src_dir()) {
        if s.module == ["job"] {
            continue;
        }
        for (i, _) in s.code.match_indices("TaskSpec::") {
            let rest = ident_at(&s.code, i + "TaskSpec::".len());
            assert!(
                rest == "each" || rest == "visit",
                "{}: matches on TaskSpec::{rest}; dispatch through TaskSpec::visit",
                s.path.display()
            );
        }
    }
}

#[test]
fn task_names_are_the_job_file_variants() {
    // the variants of `TaskSpec` as the job schema has them, and the tasks' `NAME`s
    let schema: serde_json::Value = serde_json::from_str(&hotcut::job_schema_json()).unwrap();
    let variants: Vec<String> = schema["$defs"]["TaskSpec"]["oneOf"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v["required"][0].as_str().unwrap().to_string())
        .collect();
    let names: Vec<String> = hotcut::schema_files()
        .iter()
        .filter_map(|f| f.task.map(str::to_string))
        .collect();
    assert_eq!(variants, names);
    assert!(names.len() >= 6);
}

#[test]
fn modules_import_each_other_without_circles() {
    let (graph, _, _) = graph();
    for (from, tos) in &graph {
        println!(
            "{from} → {}",
            tos.iter().cloned().collect::<Vec<_>>().join(", ")
        );
    }
    assert!(graph.len() > 10, "{graph:?}");
    if let Some(cycle) = find_cycle(&graph) {
        panic!("import circle: {}", cycle.join(" → "));
    }
}

#[test]
fn the_checker_sees_imports_and_circles() {
    let top: BTreeSet<String> = ["a", "b", "c"].iter().map(|s| s.to_string()).collect();
    let s = Source {
        path: "x/b/inner.rs".into(),
        module: vec!["b".into(), "inner".into()],
        code: code_only(
            "use crate::a::X; // crate::c::Y in a comment\nlet s = \"crate::c::Z\";\n\
             fn f() { super::super::c::go(); super::local(); }\n\
             mod tests { use super::super::*; fn t() { crate::Top; } }\n",
        ),
        raw: String::new(),
    };
    let refs = references(&s, &top);
    assert_eq!(
        refs,
        vec![
            ("a".to_string(), 1),
            ("c".to_string(), 3),
            ("<root>".to_string(), 4)
        ]
    );
    // a path in a string attribute is an import too
    let raw = "#[serde(default = \"crate::c::f\")]\nx: u8,\n";
    let attr = Source {
        path: "x/a.rs".into(),
        module: vec!["a".into()],
        code: code_only(raw),
        raw: raw.to_string(),
    };
    assert_eq!(references(&attr, &top), vec![("c".to_string(), 1)]);
    let g: BTreeMap<String, BTreeSet<String>> = [("a", "b"), ("b", "c"), ("c", "a")]
        .iter()
        .map(|(x, y)| (x.to_string(), [y.to_string()].into()))
        .collect();
    assert_eq!(find_cycle(&g).map(|c| c.len()), Some(4));
    let dag: BTreeMap<String, BTreeSet<String>> = [("a", "b"), ("b", "c")]
        .iter()
        .map(|(x, y)| (x.to_string(), [y.to_string()].into()))
        .collect();
    assert_eq!(find_cycle(&dag), None);
}

/// `(name, first line, lines)` of every function in `code`.
fn functions(code: &str) -> Vec<(String, usize, usize)> {
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while let Some(k) = code[i..].find("fn ") {
        let at = i + k;
        i = at + 3;
        if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_') {
            continue;
        }
        let name = ident_at(code, at + 3);
        if name.is_empty() {
            continue;
        }
        // the body starts at the first `{` before any `;` (a declaration has none)
        let Some(open) = code[at..].find(['{', ';']).map(|o| at + o) else {
            break;
        };
        if bytes[open] == b';' {
            continue;
        }
        let mut depth = 0;
        let mut end = open;
        for (j, &c) in bytes.iter().enumerate().skip(open) {
            if c == b'{' {
                depth += 1;
            } else if c == b'}' {
                depth -= 1;
                if depth == 0 {
                    end = j;
                    break;
                }
            }
        }
        let first = code[..at].matches('\n').count() + 1;
        let last = code[..end].matches('\n').count() + 1;
        out.push((name.to_string(), first, last - first + 1));
    }
    out
}

#[test]
fn no_function_is_longer_than_the_limit() {
    let mut long = Vec::new();
    let mut count = 0;
    for s in sources(&src_dir()) {
        for (name, line, lines) in functions(&s.code) {
            count += 1;
            if lines > MAX_FN_LINES {
                long.push(format!(
                    "{}:{line}: {name} ({lines} lines)",
                    s.path.display()
                ));
            }
        }
    }
    assert!(count > 100, "only {count} functions found");
    assert!(
        long.is_empty(),
        "functions over {MAX_FN_LINES} lines:\n{}",
        long.join("\n")
    );
    // the counter measures what it should
    let f = functions(&code_only(
        "fn a() {\n    let s = \"}\"; // }\n}\nfn b(x: u8) -> u8;\nfn c() { { } }\n",
    ));
    assert_eq!(f, vec![("a".to_string(), 1, 3), ("c".to_string(), 5, 1)]);
}
