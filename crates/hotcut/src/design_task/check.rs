//! The design's checks beyond its schema: blocks, cuts, their constructions and the
//! drawings' file names. Validation and run both call [`check_design`], so they refuse
//! alike.

use design::cut::CutParams;
use elastica::blade::BladeParams;

use design::assembly::{resolve_cut, Block, ResolvedCut};

use super::file::{self, DesignFile};
use super::outputs;

/// Largest design coordinate, mm (as the cell's frames): a kilometre.
const MAX_COORDINATE_MM: f64 = 1e6;
/// Smallest block edge, mm.
const MIN_BLOCK_MM: f64 = 1.0;

/// The design's problems beyond its schema: blocks (finite, bounded, at least
/// [`MIN_BLOCK_MM`], named once, drawings' file names distinct), cuts, each construction
/// and everything [`design::cut::solve`] checks before solving, the blade's length, as
/// `(pointer, message)`; and the resolved cuts when there are none. Validation and run
/// both call it, so they refuse alike. `mm` is millimetres per job unit.
pub(super) fn check_design(
    d: &DesignFile,
    blade: f64,
    planes: usize,
    mm: f64,
) -> (Vec<(String, String)>, Vec<ResolvedCut>) {
    let blocks = d.blocks();
    let far = MAX_COORDINATE_MM / mm;
    let mut errors = check_blocks(d, &blocks, far, MIN_BLOCK_MM / mm);
    let mut cuts = Vec::new();
    for i in 0..d.cuts.len() {
        if let Some(r) = check_cut(d, i, &blocks, blade, planes, far, &mut errors) {
            cuts.push(r);
        }
    }
    if errors.is_empty() {
        errors.extend(check_drawing_names(d, &blocks));
    }
    (errors, cuts)
}

/// An id as it may appear in a message: clipped, control characters escaped.
fn shown(s: &str) -> String {
    geom::text::terminal(&geom::text::clip(s, 40))
}

/// The blocks' problems: beyond `far` of the origin, an edge under `small`, a name twice.
/// A grid stops at its first problem (every block of it shares the cause).
fn check_blocks(d: &DesignFile, blocks: &[Block], far: f64, small: f64) -> Vec<(String, String)> {
    let mut errors = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for (i, b) in blocks.iter().enumerate() {
        let at = match d.blocks {
            file::BlocksSpec::List(_) => format!("/blocks/List/{i}"),
            file::BlocksSpec::Grid(_) => "/blocks/Grid".to_string(),
        };
        if b.min.iter().chain(b.max.iter()).any(|v| !(v.abs() <= far)) {
            errors.push((
                at.clone(),
                format!(
                    "block `{}` must lie within ±{far} (a kilometre) of the origin",
                    shown(&b.id)
                ),
            ));
        } else if (0..3).any(|k| !(b.max[k] - b.min[k] >= small)) {
            errors.push((
                at.clone(),
                format!(
                    "block `{}` must have max > min by at least {small} ({MIN_BLOCK_MM} mm) on every axis",
                    shown(&b.id)
                ),
            ));
        }
        if !seen.insert(b.id.as_str()) {
            errors.push((at, format!("block `{}` is named twice", shown(&b.id))));
        }
        if matches!(d.blocks, file::BlocksSpec::Grid(_)) && !errors.is_empty() {
            break;
        }
    }
    errors
}

/// Cut `i`'s problems, pushed onto `errors`: its name, its control points' bounds, its
/// construction, its pieces against the blade and everything [`design::cut::problems`]
/// checks. Returns the resolved cut unless it could not be resolved (or earlier
/// problems make resolving pointless).
fn check_cut(
    d: &DesignFile,
    i: usize,
    blocks: &[Block],
    blade: f64,
    planes: usize,
    far: f64,
    errors: &mut Vec<(String, String)>,
) -> Option<ResolvedCut> {
    let c = &d.cuts[i];
    if d.cuts[..i].iter().any(|o| o.id == c.id) {
        errors.push((
            format!("/cuts/{i}/id"),
            format!("cut `{}` is named twice", shown(&c.id)),
        ));
    }
    for (s, st) in c.stations.iter().enumerate() {
        let points: Vec<[f64; 2]> = match &st.curve {
            file::CurveSpec::Bezier(p) => p.iter().flatten().copied().collect(),
            file::CurveSpec::Spline(p) => p.clone(),
        };
        if points.iter().flatten().any(|v| !(v.abs() <= far)) {
            errors.push((
                format!("/cuts/{i}/stations/{s}/curve"),
                format!(
                    "cut `{}`: a control point lies beyond ±{far} (a kilometre)",
                    shown(&c.id)
                ),
            ));
        }
    }
    if !errors.is_empty() {
        return None;
    }
    let r = match resolve_cut(&c.input(), blocks) {
        Ok(r) => r,
        Err(list) => {
            errors.extend(list.into_iter().map(|(p, m)| {
                (
                    format!("/cuts/{i}{p}"),
                    format!("cut `{}`: {m}", shown(&c.id)),
                )
            }));
            return None;
        }
    };
    for (s, st) in r.stations.iter().enumerate() {
        for (k, piece) in st.curve.pieces().iter().enumerate() {
            let length = piece.length();
            if length > blade {
                errors.push((
                    format!("/cuts/{i}/stations/{s}/curve"),
                    format!("the piece in block `{}` is {length:.3} long, longer than the blade ({blade:.3}): shorten it or lengthen blade.length", shown(&c.blocks[k])),
                ));
            }
        }
    }
    let cp = CutParams {
        frame: r.frame,
        faces: r.faces.clone(),
        stations: r.stations.clone(),
        blade: BladeParams {
            length: blade,
            lead_in_share: 0.5,
            max_curvature: None,
            max_inflections: None,
            stability: elastica::StabilityParams::default(),
        },
        planes,
        offset: 0.0,
        // the blade's place along it is a verdict of the run, not a check of the file
        heights: Vec::new(),
    };
    for m in design::cut::problems(&cp) {
        errors.push((format!("/cuts/{i}"), format!("cut `{}`: {m}", shown(&c.id))));
    }
    Some(r)
}

/// Two drawings whose file names would collide (case ignored).
fn check_drawing_names(d: &DesignFile, blocks: &[Block]) -> Vec<(String, String)> {
    let mut names: Vec<(String, String)> = outputs::drawing_names(d, blocks)
        .into_iter()
        .map(|n| (n.to_lowercase(), n))
        .collect();
    names.sort();
    names
        .windows(2)
        .filter(|w| w[0].0 == w[1].0)
        .map(|w| {
            (
                "/blocks".into(),
                format!(
                    "two drawings would both be written as {} (block and cut ids become file names: letters, digits, - and _ kept, anything else _, case ignored): rename a block or a cut",
                    w[1].1
                ),
            )
        })
        .collect()
}
