//! The design file of a `Design` job (JSON, schema `schemas/design.schema.json`): the
//! blocks, and per cut its direction, its blocks across the cut and its design curves at
//! stations along it. Coordinates are in the job's units.

use std::path::Path;

use geom::slice::PlaneFrame;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use design::assembly::{Block, CurveInput, CutInput, StationInput};

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

impl CutSpec {
    /// The cut as [`design::assembly::resolve_cut`] takes it.
    pub fn input(&self) -> CutInput {
        CutInput {
            id: self.id.clone(),
            frame: self.direction.frame(),
            blocks: self.blocks.clone(),
            stations: self
                .stations
                .iter()
                .map(|s| StationInput {
                    at: s.at,
                    curve: match &s.curve {
                        CurveSpec::Bezier(p) => CurveInput::Bezier(p.clone()),
                        CurveSpec::Spline(p) => CurveInput::Spline(p.clone()),
                    },
                })
                .collect(),
        }
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
