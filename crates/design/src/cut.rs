//! One designed cut through a row of blocks ("Designing for Robotic Hot-Blade Cutting"
//! §3.2–§3.4, §5): design curves across the cut at stations along it (at least the
//! entry and exit faces), one cubic piece per block — Béziers joined G¹ or one C² spline
//! — lofted along the cut ([`crate::loft`]). On every station and every cutting plane each
//! piece is replaced by its elastica ([`crate::proxy`](mod@crate::proxy)), which is extended to the blade's
//! length by its closed form and posed in 3D for the robots.
//!
//! The curves are lofted in a form that keeps their construction on every plane: a G¹
//! chain by its joints (points, tangent angles, leg lengths), a spline by its control
//! points (whose knot images then stay on the faces). So the elastica of every plane
//! still share points and tangents across the faces.

use elastica::blade::{extend_to_blade, Blade, BladeParams};
use elastica::clearance::{place, place_all, Clearance, Section};
use elastica::segment::Segment;
use elastica::sweep::{blade_pose, BladePose};
use geom::slice::PlaneFrame;
use rayon::prelude::*;

use crate::bezier::{wrap, Bezier};
use crate::chain::g1_breaks;
use crate::error::{DesignError, Result};
use crate::loft::Loft;
use crate::proxy::{proxy_offset, Proxy};
use crate::spline::BSpline;

/// Relative tolerance (to the cut's width) of a piece's end or a knot image on its face.
pub const FACE_TOLERANCE: f64 = 1e-6;

/// A design curve at one station: in plane coordinates (across, height) of the cutting
/// plane.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum DesignCurve {
    /// One cubic Bézier per block, joined G¹ on the faces (fig. 14).
    Bezier(Vec<Bezier>),
    /// One cubic B-spline with a piece per block, C² (fig. 15).
    Spline(BSpline),
}

/// Which construction a curve follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum Form {
    /// G¹ Béziers.
    Bezier,
    /// C² spline.
    Spline,
}

impl DesignCurve {
    /// The construction.
    pub fn form(&self) -> Form {
        match self {
            Self::Bezier(_) => Form::Bezier,
            Self::Spline(_) => Form::Spline,
        }
    }

    /// The pieces, one Bézier per block.
    ///
    /// ```
    /// use design::cut::{DesignCurve, Form};
    /// use design::spline::BSpline;
    /// let spline = BSpline::new(vec![0.0, 1.0, 2.0], vec![[0.0, 0.0], [0.5, 1.0], [1.0, 1.0], [1.5, 1.0], [2.0, 0.0]])?;
    /// let curve = DesignCurve::Spline(spline);
    /// assert_eq!(curve.form(), Form::Spline);
    /// let pieces = curve.pieces();
    /// assert_eq!(pieces.len(), 2);
    /// assert_eq!((pieces[0].p[0], pieces[1].p[3]), ([0.0, 0.0], [2.0, 0.0]));
    /// # Ok::<(), design::DesignError>(())
    /// ```
    pub fn pieces(&self) -> Vec<Bezier> {
        match self {
            Self::Bezier(p) => p.clone(),
            Self::Spline(s) => s.pieces(),
        }
    }

    /// Where the curve breaks its construction on `faces` (the blocks' faces across the
    /// cut, increasing): one message per problem, naming the face. Empty when it holds.
    ///
    /// ```
    /// use design::cut::DesignCurve;
    /// use design::Bezier;
    /// let first = Bezier { p: [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0]] };
    /// let second = Bezier { p: [[3.0, 1.0], [4.0, 1.0], [5.0, 0.0], [6.0, 0.0]] };
    /// let curve = DesignCurve::Bezier(vec![first, second]);
    /// assert!(curve.problems(&[0.0, 3.0, 6.0]).is_empty());
    /// assert_eq!(curve.problems(&[0.0, 2.0, 6.0]).len(), 2); // the joint is off face 1
    /// assert_eq!(curve.problems(&[0.0, 6.0]).len(), 1); // two pieces for one block
    /// ```
    pub fn problems(&self, faces: &[f64]) -> Vec<String> {
        let width = faces.last().unwrap_or(&0.0) - faces.first().unwrap_or(&0.0);
        let tol = FACE_TOLERANCE * width.abs();
        let mut out = Vec::new();
        match self {
            Self::Bezier(pieces) => {
                if pieces.len() + 1 != faces.len() {
                    out.push(format!(
                        "{} Bézier piece(s) for {} block(s): give one per block",
                        pieces.len(),
                        faces.len().saturating_sub(1)
                    ));
                    return out;
                }
                for (i, b) in pieces.iter().enumerate() {
                    for (end, point, face) in [(0, b.p[0], i), (3, b.p[3], i + 1)] {
                        let off = point[0] - faces[face];
                        if !(off.abs() <= tol) {
                            out.push(format!(
                                "piece {} point b{end} is {off:.3e} across from face {face} (at {}): the ends of a piece lie on its block's faces",
                                i, faces[face]
                            ));
                        }
                    }
                }
                match g1_breaks(pieces) {
                    Ok(breaks) => out.extend(breaks.iter().map(|b| {
                        format!(
                            "the pieces break the tangent-continuous construction at face {}: gap {:.3e}, legs at {:.3e} rad (the last leg of one piece and the first of the next must lie on one line)",
                            b.face + 1, b.gap, b.angle
                        )
                    })),
                    Err(e) => out.push(e.to_string()),
                }
            }
            Self::Spline(s) => {
                if s.faces.len() != faces.len()
                    || s.faces.iter().zip(faces).any(|(a, b)| (a - b).abs() > tol)
                {
                    out.push("the spline's knots are not the blocks' faces".into());
                    return out;
                }
                for (face, off) in s.off_faces(tol) {
                    out.push(format!(
                        "the knot image at face {face} is {off:.3e} across from the face (at {}): place the control points at the Greville abscissae, or move them so the curve meets the face",
                        faces[face]
                    ));
                }
            }
        }
        out
    }

    /// The parameters lofted along the cut (see the module's doc).
    fn loft_params(&self) -> Result<Vec<f64>> {
        match self {
            Self::Spline(s) => Ok(s.control.iter().flatten().copied().collect()),
            Self::Bezier(pieces) => {
                let n = pieces.len();
                let mut points = Vec::with_capacity(2 * n + 2);
                let mut angles = Vec::with_capacity(n + 1);
                let mut legs = Vec::with_capacity(2 * n);
                // the joints' tangent angles unwrapped along the curve by each piece's
                // true turning (∫κ ds), not by the nearest angle: a piece turning by π or
                // more (a vault's arch) keeps its turn, and lofts the short way
                for (i, b) in pieces.iter().enumerate() {
                    points.extend(b.p[0]);
                    let start = b.start_angle()?;
                    if i == 0 {
                        angles.push(start);
                    }
                    let at = angles[i];
                    angles.push(at + (b.end_angle_unwrapped()? - start));
                    legs.push((b.p[1][0] - b.p[0][0]).hypot(b.p[1][1] - b.p[0][1]));
                    legs.push((b.p[3][0] - b.p[2][0]).hypot(b.p[3][1] - b.p[2][1]));
                    if i + 1 == n {
                        points.extend(b.p[3]);
                    }
                }
                Ok(points.into_iter().chain(angles).chain(legs).collect())
            }
        }
    }

    /// The curve of this construction with lofted parameters `p` (the inverse of
    /// [`Self::loft_params`]).
    fn with_params(&self, p: &[f64]) -> Result<Self> {
        match self {
            Self::Spline(s) => BSpline::new(
                s.faces.clone(),
                p.chunks_exact(2).map(|c| [c[0], c[1]]).collect(),
            )
            .map(Self::Spline),
            Self::Bezier(pieces) => {
                let n = pieces.len();
                let point = |k: usize| [p[2 * k], p[2 * k + 1]];
                let angle = |k: usize| p[2 * n + 2 + k];
                let leg = |k: usize| p[3 * n + 3 + k];
                let dir = |a: f64| [a.cos(), a.sin()];
                Ok(Self::Bezier(
                    (0..n)
                        .map(|i| {
                            let (a, b) = (point(i), point(i + 1));
                            let (ta, tb) = (dir(angle(i)), dir(angle(i + 1)));
                            let (la, lb) = (leg(2 * i), leg(2 * i + 1));
                            Bezier {
                                p: [
                                    a,
                                    [a[0] + la * ta[0], a[1] + la * ta[1]],
                                    [b[0] - lb * tb[0], b[1] - lb * tb[1]],
                                    b,
                                ],
                            }
                        })
                        .collect(),
                ))
            }
        }
    }
}

/// A design curve at an offset along the cut.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Station {
    /// Offset of its plane along the cut (the frame's normal).
    pub offset: f64,
    /// The curve.
    pub curve: DesignCurve,
}

/// One designed cut.
#[derive(Debug, Clone)]
pub struct CutParams {
    /// The cutting planes' frame: normal = cut direction, (u, v) = (across, up).
    pub frame: PlaneFrame,
    /// The blocks' faces across the cut (u), increasing: block i lies between faces i and
    /// i + 1.
    pub faces: Vec<f64>,
    /// The stations, offsets increasing; the first at the blocks' entry face, the last at
    /// their exit face. All of one form.
    pub stations: Vec<Station>,
    /// The blade.
    pub blade: BladeParams,
    /// Cutting planes from the entry face to the exit face (≥ 2), equally spaced.
    pub planes: usize,
    /// How far the blade's path lies off the design, along each curve's left normal
    /// (`+v`, up: the side the blade removes): half its kerf. 0: on the design.
    pub offset: f64,
    /// Per block (as `faces`), its base and top in `v`: each plane's blade outside its
    /// piece is checked against what the block keeps below the piece, and placed along
    /// the blade to keep out of it ([`place_blade`]). Empty: not checked.
    pub heights: Vec<[f64; 2]>,
}

/// One piece of a curve and its elastica.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct PieceResult {
    /// The design piece.
    pub design: Bezier,
    /// How far the blade's path lies off it ([`CutParams::offset`]).
    pub offset: f64,
    /// Its elastica and how close they are.
    pub proxy: Proxy,
    /// The elastica extended to the blade's length, with its checks.
    pub blade: Blade,
    /// The blade's pose in 3D.
    pub pose: BladePose,
    /// The blade outside the piece against the block (when [`CutParams::heights`] are
    /// given).
    pub clearance: Option<Clearance>,
}

/// Where two neighbouring pieces' elastica meet on a face.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Joint {
    /// The face (1 … n − 1).
    pub face: usize,
    /// Distance between the two elastica's ends.
    pub gap: f64,
    /// Tangent angle of the next minus that of the previous, radians.
    pub tangent_jump: f64,
    /// Curvature of the next minus that of the previous.
    pub curvature_jump: f64,
}

/// A curve on one plane and the elastica of its pieces.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CurveResult {
    /// Offset along the cut.
    pub offset: f64,
    /// Per block.
    pub pieces: Vec<PieceResult>,
    /// Per interior face.
    pub joints: Vec<Joint>,
}

impl CurveResult {
    /// Piece `k`'s design curve and elastica at `n ≥ 2` points of equal arc-length
    /// fractions (empty when the elastica cannot be evaluated).
    pub fn sampled(&self, k: usize, n: usize) -> (Vec<[f64; 2]>, Vec<[f64; 2]>) {
        let p = &self.pieces[k];
        let n = n.max(2);
        let elastica = p
            .proxy
            .elastica
            .evaluator()
            .map(|e| {
                (0..n)
                    .map(|i| e.eval(i as f64 / (n - 1) as f64).p)
                    .collect()
            })
            .unwrap_or_default();
        // the design as the blade follows it (moved by the kerf's offset)
        let design = crate::proxy::moved_samples(&p.design, p.offset, n).unwrap_or_default();
        (design, elastica)
    }
}

/// A designed cut and its elastica.
#[derive(Debug, Clone)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct CutResult {
    /// The construction.
    pub form: Form,
    /// The curves at the stations.
    pub stations: Vec<CurveResult>,
    /// The curves on the cutting planes, entry to exit.
    pub planes: Vec<CurveResult>,
}

fn chord(a: &[Bezier], b: &[Bezier], ds: f64) -> f64 {
    let (mut sum, mut n) = (0.0, 0.0f64);
    for (p, q) in a.iter().zip(b) {
        for (x, y) in p.p.iter().zip(&q.p) {
            sum += (x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2);
            n += 1.0;
        }
    }
    (ds * ds + sum / n.max(1.0)).sqrt()
}

fn elastica_err(e: impl ToString) -> DesignError {
    DesignError::Elastica(e.to_string())
}

/// The elastica `section` of block `block` extended to the blade and placed along it
/// ([`elastica::clearance::place`]) so that the blade outside the piece keeps out of the
/// material the block keeps below the piece, and the held ends out of the block (issue
/// 37). Without [`CutParams::heights`], the blade as `p.blade` places it, unchecked.
///
/// # Errors
/// The blade cannot be extended or evaluated.
pub fn place_blade(
    section: &Segment,
    p: &CutParams,
    block: usize,
) -> std::result::Result<(Blade, Option<Clearance>), String> {
    let (Some(&[base, top]), Some(&u0), Some(&u1)) = (
        p.heights.get(block),
        p.faces.get(block),
        p.faces.get(block + 1),
    ) else {
        return extend_to_blade(section, &p.blade)
            .map(|b| (b, None))
            .map_err(|e| e.to_string());
    };
    let rect = [[u0.min(u1), base.min(top)], [u0.max(u1), base.max(top)]];
    let sec = Section {
        rect,
        block: rect,
        keeps_below: true,
    };
    place(section, &p.blade, &sec, 1e-6 * p.blade.length)
        .map(|(b, c)| (b, Some(c)))
        .map_err(|e| e.to_string())
}

/// Where a block's blade had to be placed off its default on some plane, one place along
/// the blade for all its planes ([`elastica::clearance::place_all`]): the robots then
/// cut the block without sliding the blade through their holders between planes.
fn one_place_per_block(planes: &mut [CurveResult], p: &CutParams) -> Result<()> {
    let blocks = planes.first().map_or(0, |c| c.pieces.len());
    for k in 0..blocks {
        let moved = planes.iter().any(|c| {
            c.pieces
                .get(k)
                .is_some_and(|x| x.clearance.is_some_and(|g| !g.is_clean()) || moved_off(x, p))
        });
        let (Some(&[base, top]), Some(&u0), Some(&u1)) =
            (p.heights.get(k), p.faces.get(k), p.faces.get(k + 1))
        else {
            continue;
        };
        if !moved {
            continue;
        }
        let rect = [[u0.min(u1), base.min(top)], [u0.max(u1), base.max(top)]];
        let sec = Section {
            rect,
            block: rect,
            keeps_below: true,
        };
        let sections: Vec<Segment> = planes.iter().map(|c| c.pieces[k].proxy.elastica).collect();
        let placed = place_all(
            &sections,
            &p.blade,
            &vec![sec; sections.len()],
            1e-6 * p.blade.length,
        )
        .map_err(|e| DesignError::Invalid(format!("block {k} of the cut: {e}")))?;
        for (c, (blade, clearance)) in planes.iter_mut().zip(placed) {
            let piece = &mut c.pieces[k];
            piece.pose = blade_pose(&p.frame, c.offset, &blade);
            piece.blade = blade;
            piece.clearance = Some(clearance);
        }
    }
    Ok(())
}

/// Whether a piece's blade sits off the blade's own share of the extension.
fn moved_off(x: &PieceResult, p: &CutParams) -> bool {
    let extra = x.blade.lead_in + x.blade.lead_out;
    extra > 0.0 && (x.blade.lead_in - p.blade.lead_in_share * extra).abs() > 1e-9 * p.blade.length
}

/// The elastica of every piece of `curve` at `offset`.
fn solve_curve(curve: &DesignCurve, offset: f64, p: &CutParams) -> Result<CurveResult> {
    let pieces = curve
        .pieces()
        .into_iter()
        .enumerate()
        .map(|(i, design)| {
            let proxy = proxy_offset(&design, p.offset)
                .map_err(|e| DesignError::Invalid(format!("block {i} of the cut: {e}")))?;
            let (blade, clearance) = place_blade(&proxy.elastica, p, i)
                .map_err(|e| DesignError::Invalid(format!("block {i} of the cut: {e}")))?;
            let pose = blade_pose(&p.frame, offset, &blade);
            Ok(PieceResult {
                design,
                offset: p.offset,
                proxy,
                blade,
                pose,
                clearance,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let mut joints = Vec::new();
    for (k, w) in pieces.windows(2).enumerate() {
        let a = w[0].proxy.elastica.evaluator().map_err(elastica_err)?;
        let b = w[1].proxy.elastica.evaluator().map_err(elastica_err)?;
        let (ea, sb) = (a.eval(1.0), b.eval(0.0));
        joints.push(Joint {
            face: k + 1,
            gap: (ea.p[0] - sb.p[0]).hypot(ea.p[1] - sb.p[1]),
            tangent_jump: wrap(sb.angle - ea.angle),
            curvature_jump: sb.curvature - ea.curvature,
        });
    }
    Ok(CurveResult {
        offset,
        pieces,
        joints,
    })
}

/// The problems of a cut's parameters, one message each: everything [`solve`] checks
/// before it solves (faces, stations, one construction, each curve, straight pieces, the
/// loft). Empty when it can be run.
///
/// ```
/// use design::cut::{CutParams, DesignCurve, Station};
/// use design::Bezier;
/// use elastica::blade::BladeParams;
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
///
/// // one block 600 across and 400 along the cut (x); an arch over it at the entry face,
/// // a higher one at the exit face
/// let arch = |h: f64| DesignCurve::Bezier(vec![Bezier {
///     p: [[0.0, 200.0], [200.0, 200.0 + h], [400.0, 200.0 + h], [600.0, 200.0]],
/// }]);
/// let params = CutParams {
///     frame: PlaneFrame::from_direction(Vector3::x())?,
///     faces: vec![0.0, 600.0],
///     stations: vec![
///         Station { offset: 0.0, curve: arch(60.0) },
///         Station { offset: 400.0, curve: arch(90.0) },
///     ],
///     blade: BladeParams::new(800.0),
///     planes: 3,
///     offset: 0.0,
///     heights: Vec::new(),
/// };
/// assert!(design::cut::problems(&params).is_empty());
/// // the exit station's arch ending off the exit face
/// let mut off = params.clone();
/// off.stations[1].curve = DesignCurve::Bezier(vec![Bezier {
///     p: [[0.0, 200.0], [200.0, 290.0], [400.0, 290.0], [590.0, 200.0]],
/// }]);
/// assert!(!design::cut::problems(&off).is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn problems(p: &CutParams) -> Vec<String> {
    let mut out = Vec::new();
    if p.planes < 2 {
        out.push(format!("a cut needs at least 2 planes, not {}", p.planes));
    }
    if p.faces.len() < 2 || p.faces.windows(2).any(|w| !(w[1] > w[0])) {
        out.push("the blocks' faces across the cut must increase".into());
        return out;
    }
    if p.stations.len() < 2 {
        out.push("a cut needs design curves at its entry and exit faces at least".into());
    }
    if let Some(first) = p.stations.first() {
        let form = first.curve.form();
        for (i, s) in p.stations.iter().enumerate() {
            if s.curve.form() != form {
                out.push(format!(
                    "station {i} is a {:?} curve but station 0 is a {form:?} curve: a cut keeps one construction",
                    s.curve.form()
                ));
            }
            out.extend(
                s.curve
                    .problems(&p.faces)
                    .into_iter()
                    .map(|m| format!("station {i}: {m}")),
            );
            out.extend(
                piece_problems(&s.curve, None)
                    .into_iter()
                    .map(|m| format!("station {i}: {m}")),
            );
        }
        if out.is_empty() {
            match loft(&p.stations) {
                Ok(loft) => out.extend(plane_problems(p, &loft)),
                Err(e) => out.push(e.to_string()),
            }
        }
    }
    out
}

/// The pieces of `curve` whose ends coincide, or longer than `blade` when given. A
/// straight piece is cut by a straight blade (issue 37).
fn piece_problems(curve: &DesignCurve, blade: Option<f64>) -> Vec<String> {
    let mut out = Vec::new();
    for (k, piece) in curve.pieces().iter().enumerate() {
        let [a, _, _, b] = piece.p;
        let chord = (b[0] - a[0]).hypot(b[1] - a[1]);
        let length = piece.length();
        if !(chord > 0.0) || !length.is_finite() {
            out.push(format!(
                "the piece in block {k} of the cut has its ends at one point: it spans no block"
            ));
        } else if let Some(b) = blade.filter(|&b| length > b) {
            out.push(format!(
                "the piece in block {k} of the cut is {length:.3} long, longer than the blade ({b:.3})"
            ));
        }
    }
    out
}

/// The design curves lofted on every cutting plane [`solve`] solves, with their offsets
/// along the cut, without solving their elastica: a preview of the loft.
///
/// ```
/// use design::cut::{CutParams, DesignCurve, Station};
/// use design::Bezier;
/// use elastica::blade::BladeParams;
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
///
/// // one block 600 across and 400 along the cut (x); an arch over it at the entry face,
/// // a higher one at the exit face
/// let arch = |h: f64| DesignCurve::Bezier(vec![Bezier {
///     p: [[0.0, 200.0], [200.0, 200.0 + h], [400.0, 200.0 + h], [600.0, 200.0]],
/// }]);
/// let params = CutParams {
///     frame: PlaneFrame::from_direction(Vector3::x())?,
///     faces: vec![0.0, 600.0],
///     stations: vec![
///         Station { offset: 0.0, curve: arch(60.0) },
///         Station { offset: 400.0, curve: arch(90.0) },
///     ],
///     blade: BladeParams::new(800.0),
///     planes: 3,
///     offset: 0.0,
///     heights: Vec::new(),
/// };
/// let curves = design::cut::plane_curves(&params)?;
/// let offsets: Vec<f64> = curves.iter().map(|c| c.0).collect();
/// assert_eq!(offsets, [0.0, 200.0, 400.0]);
/// // on the entry face, the entry station's curve (rebuilt from its lofted form)
/// let (lofted, given) = (curves[0].1.pieces(), params.stations[0].curve.pieces());
/// let near = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]) < 1e-9;
/// assert!(lofted[0].p.iter().zip(&given[0].p).all(|(a, b)| near(*a, *b)));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] with the first of [`problems`] before the loft (faces,
/// stations, constructions); a curve that cannot be built.
pub fn plane_curves(p: &CutParams) -> Result<Vec<(f64, DesignCurve)>> {
    if p.planes < 2 || p.stations.len() < 2 {
        return Err(DesignError::Invalid(
            "a cut needs at least 2 planes and 2 stations".into(),
        ));
    }
    let loft = loft(&p.stations)?;
    (0..p.planes).map(|j| plane_curve(p, &loft, j)).collect()
}

/// Cutting plane `j`'s offset along the cut (planes evenly from the first station to the
/// last; `p.planes ≥ 2` and stations present, as [`problems`] requires) and its lofted
/// design curve: what [`solve`], [`plane_curves`] and the checks all use.
fn plane_curve(p: &CutParams, loft: &Loft, j: usize) -> Result<(f64, DesignCurve)> {
    let (entry, exit) = (
        p.stations[0].offset,
        p.stations[p.stations.len() - 1].offset,
    );
    let offset = entry + (exit - entry) * j as f64 / (p.planes - 1) as f64;
    Ok((
        offset,
        p.stations[0].curve.with_params(&loft.at_offset(offset))?,
    ))
}

/// The problems of the lofted curves on the cutting planes [`solve`] solves: a curve that
/// cannot be built, a piece longer than the blade. Those of the first plane that has
/// any, and how many planes have some.
fn plane_problems(p: &CutParams, loft: &Loft) -> Vec<String> {
    if p.planes < 2 || p.stations.is_empty() {
        return Vec::new();
    }
    let mut first = Vec::new();
    let mut count = 0;
    for j in 0..p.planes {
        let found = match plane_curve(p, loft, j) {
            Ok((_, curve)) => piece_problems(&curve, Some(p.blade.length)),
            Err(e) => vec![e.to_string()],
        };
        if !found.is_empty() {
            count += 1;
            if first.is_empty() {
                first = found
                    .into_iter()
                    .map(|m| format!("plane {} of {}: {m}", j + 1, p.planes))
                    .collect();
            }
        }
    }
    if count > 1 {
        first.push(format!(
            "{count} of the {} planes have such problems (the lofted curves between stations must bend and fit the blade too)",
            p.planes
        ));
    }
    first
}

/// The loft of the stations' curves along the cut.
fn loft(stations: &[Station]) -> Result<Loft> {
    let pieces: Vec<Vec<Bezier>> = stations.iter().map(|s| s.curve.pieces()).collect();
    let mut lofted = stations
        .iter()
        .map(|s| Ok((s.offset, s.curve.loft_params()?)))
        .collect::<Result<Vec<_>>>()?;
    // each station's angles turned by whole turns to lie nearest the previous station's:
    // the tangents rotate the short way between stations
    if let Some(DesignCurve::Bezier(first)) = stations.first().map(|s| &s.curve) {
        let n = first.len();
        let angles = 2 * n + 2..3 * n + 3;
        for i in 1..lofted.len() {
            let (done, rest) = lofted.split_at_mut(i);
            let (previous, current) = (&done[i - 1].1, &mut rest[0].1);
            if current.len() < angles.end || previous.len() < angles.end {
                break;
            }
            let tau = std::f64::consts::TAU;
            let shift = tau * ((previous[angles.start] - current[angles.start]) / tau).round();
            for a in &mut current[angles.clone()] {
                *a += shift;
            }
        }
    }
    Loft::new(&lofted, |i| {
        chord(
            &pieces[i - 1],
            &pieces[i],
            stations[i].offset - stations[i - 1].offset,
        )
    })
}

/// The elastica of a designed cut on its stations and on every cutting plane, with the
/// blade poses; `tick` is called once per curve solved.
///
/// ```
/// use design::cut::{CutParams, DesignCurve, Station};
/// use design::Bezier;
/// use elastica::blade::BladeParams;
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
///
/// // one block 600 across and 400 along the cut (x); an arch over it at the entry face,
/// // a higher one at the exit face
/// let arch = |h: f64| DesignCurve::Bezier(vec![Bezier {
///     p: [[0.0, 200.0], [200.0, 200.0 + h], [400.0, 200.0 + h], [600.0, 200.0]],
/// }]);
/// let params = CutParams {
///     frame: PlaneFrame::from_direction(Vector3::x())?,
///     faces: vec![0.0, 600.0],
///     stations: vec![
///         Station { offset: 0.0, curve: arch(60.0) },
///         Station { offset: 400.0, curve: arch(90.0) },
///     ],
///     blade: BladeParams::new(800.0),
///     planes: 3,
///     offset: 0.0,
///     heights: Vec::new(),
/// };
/// let r = design::cut::solve(&params, &|| {})?;
/// assert_eq!((r.stations.len(), r.planes.len()), (2, 3));
/// for curve in r.stations.iter().chain(&r.planes) {
///     let x = &curve.pieces[0].proxy;
///     assert!(x.end_point_error < 1e-9 * x.length && x.end_angle_error < 1e-9);
///     assert!(x.max_deviation < 0.01 * x.length);
/// }
/// // the middle plane's arch lies between the stations'
/// let top = |k: usize| r.planes[k].pieces[0].design.p[1][1];
/// assert_eq!(r.planes[1].offset, 200.0);
/// assert!(top(0) < top(1) && top(1) < top(2));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] with the first of [`problems`], or naming the station or
/// plane and block whose elastica cannot be found or is longer than the blade.
pub fn solve(p: &CutParams, tick: &(dyn Fn() + Sync)) -> Result<CutResult> {
    if let Some(m) = problems(p).into_iter().next() {
        return Err(DesignError::Invalid(m));
    }
    let form = p.stations[0].curve.form();
    let loft = loft(&p.stations)?;
    let stations = p
        .stations
        .iter()
        .enumerate()
        .map(|(i, s)| {
            tick();
            solve_curve(&s.curve, s.offset, p)
                .map_err(|e| DesignError::Invalid(format!("station {i}: {e}")))
        })
        .collect::<Result<Vec<_>>>()?;
    let mut planes = (0..p.planes)
        .into_par_iter()
        .map(|j| {
            tick();
            let (offset, curve) = plane_curve(p, &loft, j)?;
            solve_curve(&curve, offset, p)
                .map_err(|e| DesignError::Invalid(format!("plane {} of {}: {e}", j + 1, p.planes)))
        })
        .collect::<Result<Vec<_>>>()?;
    one_place_per_block(&mut planes, p)?;
    Ok(CutResult {
        form,
        stations,
        planes,
    })
}
