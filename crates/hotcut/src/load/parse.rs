//! Layer 1: RON text parsed straight into [`Job`] with `deny_unknown_fields`; syntax errors
//! carry `file:line:column`, structural errors (unknown field, wrong type) also the JSON
//! pointer of the field.

use std::path::Path;

use serde::Deserialize;

use crate::error::JobError;
use crate::job::Job;

/// Turns a `serde_path_to_error` path into a JSON pointer.
fn pointer_of(path: &serde_path_to_error::Path) -> String {
    let mut s = String::new();
    for seg in path.iter() {
        use serde_path_to_error::Segment;
        let part = match seg {
            Segment::Seq { index } => index.to_string(),
            Segment::Map { key } => key.clone(),
            Segment::Enum { variant } => variant.clone(),
            Segment::Unknown => continue,
        };
        s.push('/');
        s.push_str(&part.replace('~', "~0").replace('/', "~1"));
    }
    if s.is_empty() {
        s.push('/');
    }
    s
}

/// Layer 1: parses RON text into a [`Job`].
///
/// # Errors
/// [`JobError::Syntax`] or [`JobError::Structure`], with line and column.
pub fn parse_job(path: &Path, text: &str) -> Result<Job, JobError> {
    // a byte-order mark (editors on Windows write one) is not part of the job
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    // `task: Analyze` is `task: Analyze()`; error columns refer to the text as written
    let forms = super::unit_form::expand(text);
    let col = |line: usize, col: usize| forms.original_column(line, col);
    let syntax = |e: ron::error::SpannedError| JobError::Syntax {
        path: path.to_path_buf(),
        line: e.span.start.line,
        col: col(e.span.start.line, e.span.start.col),
        message: e.code.to_string(),
    };
    // a task's struct is written inside its variant's parentheses: `HotBlade(samples: 40)`
    let options = ron::Options::default().with_default_extension(
        ron::extensions::Extensions::IMPLICIT_SOME
            | ron::extensions::Extensions::UNWRAP_VARIANT_NEWTYPES,
    );
    let mut de =
        ron::de::Deserializer::from_str_with_options(&forms.text, &options).map_err(syntax)?;
    let mut track = serde_path_to_error::Track::new();
    let result = Job::deserialize(serde_path_to_error::Deserializer::new(&mut de, &mut track));
    match result {
        Ok(job) => {
            de.end().map_err(|e| syntax(de.span_error(e)))?;
            Ok(job)
        }
        Err(e) => {
            let spanned = de.span_error(e);
            let pointer = pointer_of(&track.path());
            // well-formed RON of the wrong shape or type: report the field's pointer too
            let is_syntax = !matches!(
                spanned.code,
                ron::Error::NoSuchStructField { .. }
                    | ron::Error::NoSuchEnumVariant { .. }
                    | ron::Error::MissingStructField { .. }
                    | ron::Error::DuplicateStructField { .. }
                    | ron::Error::InvalidValueForType { .. }
                    | ron::Error::ExpectedDifferentLength { .. }
                    | ron::Error::ExpectedDifferentStructName { .. }
                    | ron::Error::ExpectedBoolean
                    | ron::Error::ExpectedFloat
                    | ron::Error::ExpectedInteger
                    | ron::Error::ExpectedString
                    | ron::Error::ExpectedChar
                    | ron::Error::ExpectedUnit
                    | ron::Error::ExpectedOption
                    | ron::Error::ExpectedArray
                    | ron::Error::ExpectedMap
                    | ron::Error::ExpectedStructLike
                    | ron::Error::ExpectedNamedStructLike(_)
                    | ron::Error::IntegerOutOfBounds
                    | ron::Error::Message(_)
            );
            if is_syntax {
                return Err(syntax(spanned));
            }
            Err(JobError::Structure {
                path: path.to_path_buf(),
                line: spanned.span.start.line,
                col: col(spanned.span.start.line, spanned.span.start.col),
                pointer,
                message: spanned.code.to_string(),
            })
        }
    }
}

/// Layer 1 for a job given as data rather than as a file: its JSON form (the form of
/// `schemas/job.schema.json`: enum variants as one-key objects, `{"HeightField": {..}}`,
/// tuples as arrays). The Python bindings hand a `dict` job here.
///
/// # Errors
/// [`JobError::Schema`] with the JSON pointer of the field that does not fit (unknown
/// field, wrong type, missing field, text that is not JSON).
pub fn parse_job_json(path: &Path, text: &str) -> Result<Job, JobError> {
    let mut de = serde_json::Deserializer::from_str(text);
    let mut track = serde_path_to_error::Track::new();
    let result = Job::deserialize(serde_path_to_error::Deserializer::new(&mut de, &mut track));
    match result.and_then(|job| de.end().map(|()| job)) {
        Ok(job) => Ok(job),
        Err(e) => {
            // the JSON is made from the caller's data, not written by them: its line and
            // column mean nothing to them, the field's pointer does (a tuple with an item
            // too many is a "trailing characters" error of serde_json's, a null task an
            // "expected value": both are the shape of a field)
            let message = e.to_string();
            let message = match message.rfind(" at line ") {
                Some(i) => message[..i].to_string(),
                None => message,
            };
            let message = match message.as_str() {
                "trailing characters" => "more items than the field has".to_string(),
                "expected value" => "not a value this field takes".to_string(),
                _ => message,
            };
            Err(JobError::Schema {
                path: path.to_path_buf(),
                pointer: pointer_of(&track.path()),
                message,
            })
        }
    }
}
