//! Layer 2: the parsed job, as JSON, validated against the job's JSON Schema
//! (`jsonschema`), which carries the value ranges (positive lengths, at least one section,
//! …); errors carry the JSON pointer. NaN and infinities fail here.

use std::path::Path;

use crate::error::JobError;
use crate::job::Job;

/// The JSON Schema of job files.
pub fn job_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(Job)).unwrap_or(serde_json::Value::Null)
}

/// Layer 2: validates a parsed job against the job schema.
///
/// # Errors
/// Every schema violation, each with its JSON pointer.
pub fn validate_schema(path: &Path, job: &Job) -> Result<(), Vec<JobError>> {
    let schema = job_schema();
    let instance = serde_json::to_value(job).map_err(|e| {
        vec![JobError::Schema {
            path: path.to_path_buf(),
            pointer: "/".into(),
            message: e.to_string(),
        }]
    })?;
    let validator = jsonschema::validator_for(&schema).map_err(|e| {
        vec![JobError::Schema {
            path: path.to_path_buf(),
            pointer: "/".into(),
            message: format!("invalid job schema: {e}"),
        }]
    })?;
    let mut found = Vec::new();
    for e in validator.iter_errors(&instance) {
        leaf_errors(&e, &mut found);
    }
    let mut errors: Vec<JobError> = Vec::new();
    for (pointer, message) in found {
        let e = JobError::Schema {
            path: path.to_path_buf(),
            pointer,
            message,
        };
        if !errors.contains(&e) {
            errors.push(e);
        }
    }
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors)
    }
}

/// The most specific errors under a schema error: for `anyOf`/`oneOf` (optional fields,
/// enum variants) the branch whose errors reach deepest into the instance is the one the
/// user meant, so its errors are reported instead of "not valid under any of the schemas".
fn leaf_errors(e: &jsonschema::ValidationError<'_>, out: &mut Vec<(String, String)>) {
    if let Some(branches) = branches_of(e) {
        if let Some(best) = branches
            .iter()
            .max_by_key(|b| b.iter().map(depth).max().unwrap_or(0))
        {
            if best.iter().map(depth).max().unwrap_or(0) > e.instance_path().to_string().len() {
                for x in best {
                    leaf_errors(x, out);
                }
                return;
            }
        }
    }
    let pointer = e.instance_path().to_string();
    let pointer = if pointer.is_empty() {
        "/".to_string()
    } else {
        pointer
    };
    // serde_json turns NaN and infinities into null; say what really happened
    let message = if e.instance().is_null() {
        "must be a finite number (NaN or infinity given)".to_string()
    } else {
        e.to_string()
    };
    out.push((pointer, message));
}

type Branches = Vec<Vec<jsonschema::ValidationError<'static>>>;

fn branches_of<'e>(e: &'e jsonschema::ValidationError<'_>) -> Option<&'e Branches> {
    use jsonschema::error::ValidationErrorKind as K;
    match e.kind() {
        K::AnyOf { context } | K::OneOfNotValid { context } => Some(context),
        _ => None,
    }
}

/// Length of the deepest instance path among an error and its branches.
fn depth(e: &jsonschema::ValidationError<'_>) -> usize {
    let own = e.instance_path().to_string().len();
    branches_of(e)
        .map(|bs| bs.iter().flatten().map(depth).max().unwrap_or(0))
        .unwrap_or(0)
        .max(own)
}
