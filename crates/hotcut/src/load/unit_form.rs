//! The unit form of the task and the segmentation algorithm: `task: Analyze` and
//! `algorithm: Trace` mean "all defaults", like `Analyze()` and `Trace()`.
//!
//! RON's serde deserializer needs the parentheses for a variant that holds a struct, and a
//! serde `Deserialize` cannot look ahead to see whether they are there. So before parsing,
//! this pass finds the value of each `task:` and `algorithm:` field (outside strings and
//! comments) and, when it is a known variant name not followed by `(`, writes `()` after
//! it. Positions in error messages are mapped back to the text as the user wrote it
//! ([`UnitForms::original_column`]).

use std::borrow::Cow;

/// The fields whose value may be written in unit form, with the variants allowed there.
const UNIT_FORM_FIELDS: &[(&str, &[&str])] = &[
    (
        "task",
        &[
            "Analyze",
            "FitCurves",
            "HotBlade",
            "FacadeSegmentation",
            "BlockSegmentation",
            "PreCut",
        ],
    ),
    ("algorithm", &["Inflection", "Trace", "LongestElastica"]),
];

/// The output kinds that hold options and may be written in unit form inside `outputs:`.
const UNIT_FORM_OUTPUTS: &[&str] = &["Obj"];

/// The job text with `()` written after every unit-form variant, and where they went.
pub(crate) struct UnitForms<'a> {
    /// The text to parse.
    pub text: Cow<'a, str>,
    /// (line, column) in the original text, both 1-based, after which `()` was written.
    inserted: Vec<(usize, usize)>,
}

impl UnitForms<'_> {
    /// The column in the original text of a position at `line:col` of the parsed text.
    pub fn original_column(&self, line: usize, col: usize) -> usize {
        let shift = self
            .inserted
            .iter()
            .filter(|&&(l, c)| l == line && c < col)
            .count();
        col.saturating_sub(2 * shift).max(1)
    }
}

/// A scanner over RON text that skips whitespace, comments and strings.
struct Scanner<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Scanner<'_> {
    fn peek(&self) -> Option<u8> {
        self.bytes.get(self.pos).copied()
    }

    /// Skips whitespace and comments (`//` to the end of the line, `/* */` nested).
    fn skip_trivia(&mut self) {
        while let Some(b) = self.peek() {
            if b.is_ascii_whitespace() {
                self.pos += 1;
            } else if self.bytes[self.pos..].starts_with(b"//") {
                while self.peek().is_some_and(|b| b != b'\n') {
                    self.pos += 1;
                }
            } else if self.bytes[self.pos..].starts_with(b"/*") {
                let mut depth = 0usize;
                while self.pos < self.bytes.len() {
                    if self.bytes[self.pos..].starts_with(b"/*") {
                        depth += 1;
                        self.pos += 2;
                    } else if self.bytes[self.pos..].starts_with(b"*/") {
                        depth -= 1;
                        self.pos += 2;
                        if depth == 0 {
                            break;
                        }
                    } else {
                        self.pos += 1;
                    }
                }
            } else {
                return;
            }
        }
    }

    /// Skips a string literal starting at the cursor (`"…"` with escapes, `r#"…"#`).
    fn skip_string(&mut self) -> bool {
        let rest = &self.bytes[self.pos..];
        if rest.first() == Some(&b'"') {
            self.pos += 1;
            while let Some(b) = self.peek() {
                self.pos += 1;
                match b {
                    b'\\' => self.pos += 1,
                    b'"' => break,
                    _ => {}
                }
            }
            return true;
        }
        if rest.first() == Some(&b'r') {
            let hashes = rest[1..].iter().take_while(|&&b| b == b'#').count();
            if rest.get(1 + hashes) == Some(&b'"') {
                let close: Vec<u8> = std::iter::once(b'"')
                    .chain(std::iter::repeat_n(b'#', hashes))
                    .collect();
                self.pos += 2 + hashes;
                while self.pos < self.bytes.len() && !self.bytes[self.pos..].starts_with(&close) {
                    self.pos += 1;
                }
                self.pos = (self.pos + close.len()).min(self.bytes.len());
                return true;
            }
        }
        false
    }

    /// An identifier at the cursor, consumed.
    fn ident(&mut self) -> Option<&str> {
        let start = self.pos;
        while self
            .peek()
            .is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_')
        {
            self.pos += 1;
        }
        (self.pos > start)
            .then(|| std::str::from_utf8(&self.bytes[start..self.pos]).ok())
            .flatten()
    }
}

/// 1-based line and column of byte offset `pos` in `text` (columns count characters).
fn line_col(text: &str, pos: usize) -> (usize, usize) {
    let before = &text[..pos];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

/// After the field name `outputs`: if `: [` follows, the positions after each element of
/// [`UNIT_FORM_OUTPUTS`] not followed by `(`, up to the list's `]`. Elements with
/// parentheses are skipped whole (strings inside them included).
fn outputs_list(s: &mut Scanner<'_>, at: &mut Vec<usize>) {
    s.skip_trivia();
    if s.peek() != Some(b':') {
        return;
    }
    s.pos += 1;
    s.skip_trivia();
    if s.peek() != Some(b'[') {
        return;
    }
    s.pos += 1;
    // every iteration consumes at least one byte or stops
    while s.pos < s.bytes.len() {
        s.skip_trivia();
        match s.peek() {
            None | Some(b']') => return,
            Some(b',') => {
                s.pos += 1;
                continue;
            }
            _ => {}
        }
        let Some(word) = s.ident() else {
            // not an identifier: leave the list to the parser's error
            return;
        };
        let known = UNIT_FORM_OUTPUTS.contains(&word);
        let end = s.pos;
        s.skip_trivia();
        if s.peek() == Some(b'(') {
            let mut depth = 0usize;
            while s.pos < s.bytes.len() {
                if s.skip_string() {
                    continue;
                }
                match s.peek() {
                    Some(b'(') => depth += 1,
                    Some(b')') => {
                        depth -= 1;
                        if depth == 0 {
                            s.pos += 1;
                            break;
                        }
                    }
                    _ => {}
                }
                s.pos += 1;
            }
        } else if known {
            at.push(end);
        }
    }
}

/// Writes `()` after each unit-form variant of the fields in [`UNIT_FORM_FIELDS`], and of
/// the outputs in [`UNIT_FORM_OUTPUTS`].
pub(crate) fn expand(text: &str) -> UnitForms<'_> {
    let mut s = Scanner {
        bytes: text.as_bytes(),
        pos: 0,
    };
    let mut at = Vec::new();
    // every iteration consumes at least one byte
    while s.pos < s.bytes.len() {
        s.skip_trivia();
        if s.skip_string() {
            continue;
        }
        let Some(word) = s.ident() else {
            s.pos += 1;
            continue;
        };
        if word == "outputs" {
            outputs_list(&mut s, &mut at);
            continue;
        }
        let Some(&(_, variants)) = UNIT_FORM_FIELDS.iter().find(|(f, _)| *f == word) else {
            continue;
        };
        s.skip_trivia();
        if s.peek() != Some(b':') {
            continue;
        }
        s.pos += 1;
        s.skip_trivia();
        let Some(value) = s.ident() else { continue };
        if !variants.contains(&value) {
            continue;
        }
        let end = s.pos;
        s.skip_trivia();
        if s.peek() != Some(b'(') {
            at.push(end);
        }
    }
    if at.is_empty() {
        return UnitForms {
            text: Cow::Borrowed(text),
            inserted: Vec::new(),
        };
    }
    let mut out = String::with_capacity(text.len() + 2 * at.len());
    let mut last = 0;
    let mut inserted = Vec::with_capacity(at.len());
    for &p in &at {
        out.push_str(&text[last..p]);
        out.push_str("()");
        last = p;
        let (line, col) = line_col(text, p);
        inserted.push((line, col - 1));
    }
    out.push_str(&text[last..]);
    UnitForms {
        text: Cow::Owned(out),
        inserted,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_parentheses_after_unit_form_outputs() {
        let t = "Job(outputs: [Report, Obj, RobotTargets(per_block: 3), Obj(axes: YUp), /* Obj */ Obj ], x: Obj)";
        assert_eq!(
            expand(t).text,
            "Job(outputs: [Report, Obj(), RobotTargets(per_block: 3), Obj(axes: YUp), /* Obj */ Obj() ], x: Obj)"
        );
        // a broken list is left to the parser
        for bad in [
            "Job(outputs: [Obj",
            "Job(outputs: [(",
            "Job(outputs: [RobotTargets(\"a)\"",
            "Job(outputs:",
        ] {
            let _ = expand(bad);
        }
    }

    #[test]
    fn writes_parentheses_after_unit_forms_only() {
        let t = "Job(task: Analyze, x: \"task: PreCut\", // task: HotBlade\n algorithm: /* c */ Trace )";
        let e = expand(t);
        assert_eq!(
            e.text,
            "Job(task: Analyze(), x: \"task: PreCut\", // task: HotBlade\n algorithm: /* c */ Trace() )"
        );
        let same = "Job(task: Analyze(), algorithm: Trace (), units: Metre, task2: Analyze)";
        assert_eq!(expand(same).text, same);
        // r"…" strings and unknown variants are left alone
        let raw = r##"Job(z: r#"task: Analyze"#, task: Nonsense)"##;
        assert_eq!(expand(raw).text, raw);
    }

    #[test]
    fn error_columns_map_back() {
        let e = expand("Job(task: Analyze, bad)");
        // `bad` is at column 20 in the original, 22 after the insertion
        assert_eq!(e.original_column(1, 22), 20);
        assert_eq!(e.original_column(1, 5), 5);
        assert_eq!(e.original_column(2, 22), 22);
    }
}
