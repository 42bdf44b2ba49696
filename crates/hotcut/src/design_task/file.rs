//! The design file of a `Design` job (JSON, schema `schemas/design.schema.json`): the
//! blocks, and per cut its direction, its blocks across the cut and its design curves at
//! stations along it. Coordinates are in the job's units.

use std::path::Path;

use geom::slice::PlaneFrame;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use design::bezier::Bezier;
use design::cut::{DesignCurve, Station};
use design::spline::BSpline;

/// A design for the hot blade: blocks and the cuts through them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct DesignFile {
    /// The blocks, world-axis-aligned boxes.
    pub blocks: BlocksSpec,
    /// The cuts (at least one).
    #[schemars(length(min = 1, max = 1000))]
    #[serde(deserialize_with = "bounded::seq::<_, _, 1, 1000>")]
    pub cuts: Vec<CutSpec>,
}

/// The blocks: a list, or a grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum BlocksSpec {
    /// Blocks placed one by one.
    #[serde(deserialize_with = "bounded::seq::<_, _, 1, 10000>")]
    List(#[schemars(length(min = 1, max = 10000))] Vec<BlockSpec>),
    /// `count[0] × count[1]` blocks of one size side by side along x and y from `origin`,
    /// named `x<i>y<j>` (from 0).
    Grid(GridSpec),
}

/// One block.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Its name, unique.
    #[schemars(length(min = 1, max = 100))]
    #[serde(deserialize_with = "bounded::name")]
    pub id: String,
    /// Its smallest corner.
    pub min: [f64; 3],
    /// Its largest corner.
    pub max: [f64; 3],
}

/// A grid of equal blocks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// The smallest corner of the first block.
    pub origin: [f64; 3],
    /// Each block's size.
    pub size: [f64; 3],
    /// Blocks along x and along y.
    #[schemars(inner(range(min = 1, max = 100)))]
    #[serde(deserialize_with = "bounded::count")]
    pub count: [u32; 2],
}

/// The direction a cut runs along.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum CutDirection {
    /// Along +x: design curves in (y, z).
    X,
    /// Along +y: design curves in (−x, z) (the cutting plane's right-handed frame).
    Y,
}

impl CutDirection {
    /// The cutting planes' frame: normal the direction, u across, v = +z up.
    pub fn frame(self) -> PlaneFrame {
        let d = match self {
            Self::X => Vector3::x(),
            Self::Y => Vector3::y(),
        };
        // a horizontal direction always has a frame
        PlaneFrame::from_direction(d).unwrap_or(PlaneFrame {
            normal: d,
            u: Vector3::z().cross(&d),
            v: Vector3::z(),
        })
    }
}

/// One cut through a row of blocks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct CutSpec {
    /// Its name, unique.
    #[schemars(length(min = 1, max = 100))]
    #[serde(deserialize_with = "bounded::name")]
    pub id: String,
    /// The direction the blade travels.
    pub direction: CutDirection,
    /// The blocks it runs through, side by side across the cut, in the order of the
    /// design curves' pieces (increasing across coordinate). They share their extent
    /// along the cut.
    #[schemars(length(min = 1, max = 100), inner(length(min = 1, max = 100)))]
    #[serde(deserialize_with = "bounded::names")]
    pub blocks: Vec<String>,
    /// Design curves at stations along the cut: the first at the entry face (`at: 0`),
    /// the last at the exit face (`at: 1`), any between; all of one form.
    #[schemars(length(min = 2, max = 100))]
    #[serde(deserialize_with = "bounded::seq::<_, _, 2, 100>")]
    pub stations: Vec<StationSpec>,
}

/// A design curve at a station.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct StationSpec {
    /// Where along the blocks, as a fraction from the entry face (0) to the exit face (1).
    #[schemars(range(min = 0, max = 1))]
    #[serde(deserialize_with = "bounded::fraction")]
    pub at: f64,
    /// The curve, in plane coordinates [across, height].
    pub curve: CurveSpec,
}

/// A design curve across the cut.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub enum CurveSpec {
    /// One cubic Bézier per block, `[b0, b1, b2, b3]`, ends on the block's faces;
    /// neighbours share the end point and the tangent line (fig. 14, G¹).
    #[serde(deserialize_with = "bounded::seq::<_, _, 1, 100>")]
    Bezier(#[schemars(length(min = 1, max = 100))] Vec<[[f64; 2]; 4]>),
    /// The control points of one cubic B-spline whose knots are the blocks' faces (three
    /// more points than blocks); its knot images must lie on the faces, as they do for
    /// control points at the Greville abscissae (fig. 15, C²).
    #[serde(deserialize_with = "bounded::seq::<_, _, 4, 103>")]
    Spline(#[schemars(length(min = 4, max = 103))] Vec<[f64; 2]>),
}

/// A block, resolved.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Its name.
    pub id: String,
    /// Smallest corner.
    pub min: Vector3<f64>,
    /// Largest corner.
    pub max: Vector3<f64>,
}

/// The JSON Schema of design files (`schemas/design.schema.json`).
pub fn design_schema() -> serde_json::Value {
    serde_json::to_value(schemars::schema_for!(DesignFile)).unwrap_or(serde_json::Value::Null)
}

/// Reads the design file at `path` and parses it, typed, with every bound of
/// [`design_schema`] (list lengths, name lengths, ranges) checked while it is read: a
/// list stops at its limit, no JSON tree is built, so memory stays within a small
/// multiple of the file's size (at most [`MAX_FILE_BYTES`]).
///
/// # Errors
/// The file's first problem in one message: not a regular file, too large, not JSON, or
/// a value out of its bounds, with its path in the file and its line and column; quoted
/// input clipped to 200 characters.
pub fn read(path: &Path) -> Result<DesignFile, String> {
    let text = crate::input::read_text(path, MAX_FILE_BYTES, "design file")?;
    let name = path.display();
    let mut de = serde_json::Deserializer::from_str(&text);
    let parsed: Result<DesignFile, _> = serde_path_to_error::deserialize(&mut de);
    let file = parsed.map_err(|e| {
        let at = geom::text::clip(&e.path().to_string(), 200);
        let inner = geom::text::clip(&e.into_inner().to_string(), 200);
        format!("design file {name} at {at}: {inner} (its schema: schemas/design.schema.json)")
    })?;
    de.end().map_err(|e| {
        format!(
            "design file {name}: {} (its schema: schemas/design.schema.json)",
            geom::text::clip(&e.to_string(), 200)
        )
    })?;
    Ok(file)
}

/// Largest design file read.
pub const MAX_FILE_BYTES: u64 = 64 << 20;

impl DesignFile {
    /// The blocks, resolved.
    pub fn blocks(&self) -> Vec<Block> {
        match &self.blocks {
            BlocksSpec::List(list) => list
                .iter()
                .map(|b| Block {
                    id: b.id.clone(),
                    min: Vector3::from(b.min),
                    max: Vector3::from(b.max),
                })
                .collect(),
            BlocksSpec::Grid(g) => {
                let mut out = Vec::new();
                for j in 0..g.count[1] {
                    for i in 0..g.count[0] {
                        let min = Vector3::new(
                            g.origin[0] + f64::from(i) * g.size[0],
                            g.origin[1] + f64::from(j) * g.size[1],
                            g.origin[2],
                        );
                        out.push(Block {
                            id: format!("x{i}y{j}"),
                            min,
                            max: min + Vector3::from(g.size),
                        });
                    }
                }
                out
            }
        }
    }
}

/// A cut resolved against its blocks: what [`design::cut::solve`] needs but the blade and
/// the planes.
#[derive(Debug, Clone)]
pub struct ResolvedCut {
    /// Its name.
    pub id: String,
    /// Indices of its blocks in the design's block list, across the cut.
    pub blocks: Vec<usize>,
    /// The planes' frame.
    pub frame: PlaneFrame,
    /// Faces across the cut.
    pub faces: Vec<f64>,
    /// Entry and exit offsets along the cut.
    pub span: (f64, f64),
    /// Per block, its base and top along the planes' `v` (up).
    pub heights: Vec<[f64; 2]>,
    /// Stations.
    pub stations: Vec<Station>,
}

/// Extent of a block along `axis` (a world axis or its negative).
fn extent(b: &Block, axis: &Vector3<f64>) -> (f64, f64) {
    let (a, c) = (axis.dot(&b.min), axis.dot(&b.max));
    (a.min(c), a.max(c))
}

/// Resolves cut `c` against `blocks`: every problem as `(pointer under the cut, message)`.
pub fn resolve_cut(c: &CutSpec, blocks: &[Block]) -> Result<ResolvedCut, Vec<(String, String)>> {
    let mut errors = Vec::new();
    let frame = c.direction.frame();
    let mut idx = Vec::new();
    for (i, id) in c.blocks.iter().enumerate() {
        match blocks.iter().position(|b| &b.id == id) {
            Some(k) if idx.contains(&k) => errors.push((
                format!("/blocks/{i}"),
                format!("block `{id}` is listed twice"),
            )),
            Some(k) => idx.push(k),
            None => errors.push((format!("/blocks/{i}"), format!("no block `{id}`"))),
        }
    }
    if !errors.is_empty() {
        return Err(errors);
    }
    let across: Vec<(f64, f64)> = idx.iter().map(|&k| extent(&blocks[k], &frame.u)).collect();
    let along: Vec<(f64, f64)> = idx
        .iter()
        .map(|&k| extent(&blocks[k], &frame.normal))
        .collect();
    let span = along[0];
    let scale = (span.1 - span.0).abs() + (across[across.len() - 1].1 - across[0].0).abs();
    let tol = 1e-9 * scale;
    for (i, a) in along.iter().enumerate().skip(1) {
        if (a.0 - span.0).abs() > tol || (a.1 - span.1).abs() > tol {
            errors.push((
                format!("/blocks/{i}"),
                format!(
                    "block `{}` spans {:.6}…{:.6} along the cut, the first block {:.6}…{:.6}: a cut's blocks share their extent along it",
                    c.blocks[i], a.0, a.1, span.0, span.1
                ),
            ));
        }
    }
    for (i, w) in across.windows(2).enumerate() {
        if (w[1].0 - w[0].1).abs() > tol {
            errors.push((
                format!("/blocks/{}", i + 1),
                format!(
                    "block `{}` starts at {:.6} across the cut but `{}` ends at {:.6}: list the blocks side by side, in increasing across coordinate",
                    c.blocks[i + 1], w[1].0, c.blocks[i], w[0].1
                ),
            ));
        }
    }
    let mut faces: Vec<f64> = across.iter().map(|a| a.0).collect();
    faces.push(across[across.len() - 1].1);
    if c.stations.first().map(|s| s.at) != Some(0.0) || c.stations.last().map(|s| s.at) != Some(1.0)
    {
        errors.push((
            "/stations".into(),
            "the first station is at the entry face (at: 0) and the last at the exit face (at: 1)"
                .into(),
        ));
    }
    for (i, w) in c.stations.windows(2).enumerate() {
        if !(w[1].at > w[0].at) {
            errors.push((
                format!("/stations/{}/at", i + 1),
                "stations must be listed in increasing `at`".into(),
            ));
        }
    }
    let mut stations = Vec::new();
    for (i, s) in c.stations.iter().enumerate() {
        let curve = match &s.curve {
            CurveSpec::Bezier(p) => Ok(DesignCurve::Bezier(
                p.iter().map(|p| Bezier { p: *p }).collect(),
            )),
            CurveSpec::Spline(p) => BSpline::new(faces.clone(), p.clone())
                .map(DesignCurve::Spline)
                .map_err(|e| e.to_string()),
        };
        match curve {
            Ok(curve) => {
                for m in curve.problems(&faces) {
                    errors.push((format!("/stations/{i}/curve"), m));
                }
                stations.push(Station {
                    offset: span.0 + s.at * (span.1 - span.0),
                    curve,
                });
            }
            Err(m) => errors.push((format!("/stations/{i}/curve"), m)),
        }
    }
    if errors.is_empty() {
        let heights = idx
            .iter()
            .map(|&k| {
                let (lo, hi) = extent(&blocks[k], &frame.v);
                [lo, hi]
            })
            .collect();
        Ok(ResolvedCut {
            id: c.id.clone(),
            blocks: idx,
            frame,
            faces,
            span,
            heights,
            stations,
        })
    } else {
        Err(errors)
    }
}

/// The bounds of the design file's schema, checked while it is read (`deserialize_with`),
/// so that an oversized list fails at its first extra element.
mod bounded {
    use std::fmt;
    use std::marker::PhantomData;

    use serde::de::{Deserialize, Deserializer, Error, SeqAccess, Visitor};

    /// Longest name, characters.
    const NAME: usize = 100;

    struct Seq<T, const MIN: usize, const MAX: usize>(PhantomData<T>);

    impl<'de, T: Deserialize<'de>, const MIN: usize, const MAX: usize> Visitor<'de>
        for Seq<T, MIN, MAX>
    {
        type Value = Vec<T>;
        fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
            write!(f, "a list of {MIN}–{MAX} entries")
        }
        fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<T>, A::Error> {
            let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(MAX));
            while let Some(v) = seq.next_element()? {
                if out.len() == MAX {
                    return Err(A::Error::custom(format!(
                        "more than {MAX} entries: a list holds {MIN}–{MAX}"
                    )));
                }
                out.push(v);
            }
            if out.len() < MIN {
                return Err(A::Error::custom(format!(
                    "{} entries: a list holds {MIN}–{MAX}",
                    out.len()
                )));
            }
            Ok(out)
        }
    }

    /// A list of `MIN`–`MAX` entries.
    pub fn seq<'de, D, T, const MIN: usize, const MAX: usize>(d: D) -> Result<Vec<T>, D::Error>
    where
        D: Deserializer<'de>,
        T: Deserialize<'de>,
    {
        d.deserialize_seq(Seq::<T, MIN, MAX>(PhantomData))
    }

    fn check_name<E: Error>(s: String) -> Result<String, E> {
        let n = s.chars().count();
        if (1..=NAME).contains(&n) {
            Ok(s)
        } else {
            Err(E::custom(format!(
                "a name of {n} characters: names have 1–{NAME}"
            )))
        }
    }

    /// A name of 1–100 characters.
    pub fn name<'de, D: Deserializer<'de>>(d: D) -> Result<String, D::Error> {
        check_name(String::deserialize(d)?)
    }

    /// 1–100 names of 1–100 characters.
    pub fn names<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
        let list: Vec<Name> = seq::<D, Name, 1, 100>(d)?;
        Ok(list.into_iter().map(|n| n.0).collect())
    }

    struct Name(String);
    impl<'de> Deserialize<'de> for Name {
        fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
            name(d).map(Name)
        }
    }

    /// A grid count: 1–100 along each axis.
    pub fn count<'de, D: Deserializer<'de>>(d: D) -> Result<[u32; 2], D::Error> {
        let c = <[u32; 2]>::deserialize(d)?;
        if c.iter().all(|n| (1..=100).contains(n)) {
            Ok(c)
        } else {
            Err(D::Error::custom(format!(
                "count {c:?}: 1–100 blocks along each axis"
            )))
        }
    }

    /// A fraction within 0–1.
    pub fn fraction<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        let v = f64::deserialize(d)?;
        if (0.0..=1.0).contains(&v) {
            Ok(v)
        } else {
            Err(D::Error::custom(format!("{v} is not within 0–1")))
        }
    }
}
