//! # export — deterministic writers of hotcut
//!
//! Every writer takes `impl Write` (or returns the text) and formats floats to a fixed,
//! documented precision, so the same data always gives the same bytes.
//!
//! ```
//! let mut out = Vec::new();
//! export::json::write_json(&mut out, &serde_json::json!({"length": 1.0 / 3.0}), 6).unwrap();
//! assert_eq!(String::from_utf8(out).unwrap(), "{\n  \"length\": 0.333333\n}\n");
//! ```

/// CSV tables with fixed-decimal numbers.
pub mod csv;
/// glTF 2.0 (JSON with an embedded buffer) for meshes with colours.
pub mod gltf;
/// A self-contained HTML report page (no script, no network).
pub mod html;
/// Deterministic JSON with rounded floats.
pub mod json;
/// Wavefront OBJ writer for meshes and polylines.
pub mod obj;
/// ABB RAPID modules and program files for a MultiMove hot-blade cell (two robots hold
/// the blade; a third may carry the block).
pub mod rapid;
/// The identifiers a user may give a RAPID program: not reserved, predefined or ours.
pub mod rapid_names;
/// Robot files of a hot-blade cell: targets (JSON, CSV) and one RAPID module per robot.
pub mod robot;
/// A small SVG builder with a world-to-page viewport.
pub mod svg;

/// Errors of the writers.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// Writing failed.
    #[error("write failed: {0}")]
    Io(#[from] std::io::Error),
    /// The value could not be serialised.
    #[error("cannot serialise: {0}")]
    Serialize(#[from] serde_json::Error),
    /// The data cannot be written as asked (what is wrong).
    #[error("{0}")]
    Data(String),
    /// The geometry to write could not be made (e.g. a degenerate mesh).
    #[error("geometry: {0}")]
    Geom(#[from] geom::GeomError),
}

/// The length unit of the coordinates handed to a writer: glTF scales them to metres, OBJ
/// names it in its header.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SourceUnits<'a> {
    /// Its name, e.g. `Millimetre`.
    pub name: &'a str,
    /// Metres per unit (`0.001` for millimetres).
    pub metres: f64,
}

impl SourceUnits<'static> {
    /// Coordinates in metres.
    pub const METRE: Self = Self {
        name: "Metre",
        metres: 1.0,
    };
}

/// Result alias of this crate.
pub type Result<T, E = ExportError> = std::result::Result<T, E>;

/// Formats `x` with `decimals` digits after the point, trimming trailing zeros, and printing
/// `-0` as `0`. Non-finite values print as `nan`, `inf` or `-inf`.
pub fn fmt_float(x: f64, decimals: usize) -> String {
    if !x.is_finite() {
        return if x.is_nan() {
            "nan".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let mut s = format!("{x:.decimals$}");
    if s.contains('.') {
        while s.ends_with('0') {
            s.pop();
        }
        if s.ends_with('.') {
            s.pop();
        }
    }
    if s == "-0" {
        s = "0".into();
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_formatting() {
        assert_eq!(fmt_float(1.0, 3), "1");
        assert_eq!(fmt_float(-0.0001, 3), "0");
        assert_eq!(fmt_float(2.5, 3), "2.5");
        assert_eq!(fmt_float(1.0 / 3.0, 4), "0.3333");
        assert_eq!(fmt_float(f64::NAN, 2), "nan");
    }
}
