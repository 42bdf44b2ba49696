//! User text (block, cut and curve ids, job and profile names, file names) made safe for
//! each place hotcut writes it: one function per sink, used by every writer.
//!
//! | sink | function | what it guarantees |
//! |---|---|---|
//! | XML, SVG, HTML | [`xml`](crate::text::xml) | escaped markup, no character XML 1.0 forbids |
//! | terminal | [`terminal`](crate::text::terminal) | no control or bidi character: `{:?}`-style escapes |
//! | G-code comment | [`gcode_comment`](crate::text::gcode_comment) | printable ASCII, no parentheses, ≤ 70 characters |
//! | RAPID comment | [`rapid_comment`](crate::text::rapid_comment) | printable ASCII, ≤ 80 characters |
//! | any message quoting input | [`clip`](crate::text::clip) | at most a given number of characters |
//!
//! ```
//! use geom::text;
//! assert_eq!(text::xml("a<b \u{1}"), "a&lt;b \\u{1}");
//! assert_eq!(text::terminal("\u{1b}[2Jx\n"), "\\u{1b}[2Jx\n");
//! assert_eq!(text::gcode_comment("cut (1)"), "(cut [1])");
//! assert_eq!(text::rapid_comment("é\r\nx"), "___x");
//! ```

/// A character no writer passes on as is: C0 and C1 controls, DEL, the bidirectional
/// overrides and isolates (which reorder what a terminal or a browser shows), and the
/// non-characters U+FFFE and U+FFFF.
fn is_hazard(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{200e}' | '\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
        || matches!(c, '\u{fffe}' | '\u{ffff}')
}

/// `\u{..}`, the escape Rust's `{:?}` writes.
fn escaped(c: char, out: &mut String) {
    out.push_str(&format!("\\u{{{:x}}}", c as u32));
}

/// Text for XML element content and attribute values (SVG, HTML): `& < > " '` escaped, and
/// every character XML 1.0 forbids (controls but tab and newline) and every bidi control
/// written as a visible `\u{..}`.
pub fn xml(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            '\t' | '\n' => out.push(c),
            c if is_hazard(c) => escaped(c, &mut out),
            c => out.push(c),
        }
    }
    out
}

/// Text for a terminal: every control character but newline and tab, and every bidi
/// control, written as a visible `\u{..}`, so that an escape sequence in an id cannot
/// clear the screen or move the cursor.
pub fn terminal(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '\t' | '\n' => out.push(c),
            c if is_hazard(c) => escaped(c, &mut out),
            c => out.push(c),
        }
    }
    out
}

/// A G-code comment in parentheses: printable ASCII (others become `_`), parentheses
/// turned into brackets, at most 70 characters inside (GRBL's line buffer holds 80).
pub fn gcode_comment(text: &str) -> String {
    let t: String = text
        .chars()
        .map(|c| match c {
            '(' => '[',
            ')' => ']',
            c if (' '..='~').contains(&c) => c,
            _ => '_',
        })
        .take(70)
        .collect();
    format!("({})", t.trim_end())
}

/// The text of a RAPID `!` comment: printable ASCII (others, line breaks included, become
/// `_`), at most 80 characters (a line of the FlexPendant's program editor).
pub fn rapid_comment(text: &str) -> String {
    text.chars()
        .map(|c| if (' '..='~').contains(&c) { c } else { '_' })
        .take(80)
        .collect::<String>()
        .trim_end()
        .to_string()
}

/// At most `max` characters of `text`, then `…` and how many were left out, for messages
/// that quote input.
pub fn clip(text: &str, max: usize) -> String {
    let n = text.chars().count();
    if n <= max {
        return text.to_string();
    }
    let head: String = text.chars().take(max).collect();
    format!("{head}… ({} more characters)", n - max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_sink_drops_controls() {
        let hostile = "a\u{0}b\u{1b}[2J\u{7f}\u{85}\u{202e}c\u{ffff}";
        for s in [xml(hostile), terminal(hostile)] {
            assert!(!s.chars().any(is_hazard), "{s:?}");
            assert!(s.contains("\\u{1b}") && s.contains("\\u{202e}"), "{s:?}");
        }
        for s in [gcode_comment(hostile), rapid_comment(hostile)] {
            assert!(s.chars().all(|c| (' '..='~').contains(&c)), "{s:?}");
        }
        assert_eq!(xml("x & \"y\"\n"), "x &amp; &quot;y&quot;\n");
        assert_eq!(gcode_comment(&"x".repeat(100)).len(), 72);
        assert_eq!(rapid_comment(&"x".repeat(100)).len(), 80);
        assert_eq!(clip("abcdef", 3), "abc… (3 more characters)");
        assert_eq!(clip("abc", 3), "abc");
    }
}
