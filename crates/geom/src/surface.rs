//! The surfaces hotcut works on, behind one interface: triangle meshes, height fields and
//! B-spline surfaces; and their sections by a family of parallel planes.
//!
//! Entry points: [`Surface`](crate::surface::Surface), [`Surface::sections`](crate::surface::Surface::sections) with [`SectionParams`](crate::surface::SectionParams), [`Section`](crate::surface::Section).
//!
//! Height fields are sectioned exactly ([`GraphCurve`](crate::heightfield::GraphCurve)). Mesh sections are noisy polylines,
//! so each is replaced by the smoothing spline of [`crate::fit::fit_smoothing`] with the
//! caller's explicit tolerance, widened where needed to the polyline's own chordal error
//! (`chordal: true`), before any curvature is taken. B-spline surfaces are sampled
//! on a parameter grid, sliced like a mesh, and every crossing is then moved onto the exact
//! surface by bisection along its grid edge, so their section points are exact.

use nalgebra::{Vector2, Vector3};
#[cfg(feature = "parallel")]
use rayon::prelude::*;

use crate::analysis::CurveAnalysisParams;
use crate::bbox::Aabb;
use crate::ends::end_trends;
use crate::error::{GeomError, Result};
use crate::fit::{chord_length_params, fit_smoothing_allowing, SmoothingParams};
use crate::heightfield::{GraphCurve, HeightField};
use crate::mesh::TriMesh;
use crate::planar::{Jet2, PlanarCurve, SplineCurve2};
use crate::slice::{slab_centres, slice_mesh, Chain, PlaneFrame};
use crate::surface_spline::BSplineSurface;

/// A surface to be cut.
#[derive(Debug, Clone)]
pub enum Surface {
    /// A triangle mesh.
    Mesh(TriMesh),
    /// `z = f(x, y)` over a rectangle.
    HeightField(HeightField),
    /// A tensor-product B-spline surface.
    Spline(BSplineSurface),
}

/// Parameters of [`Surface::sections`].
#[derive(Debug, Clone, PartialEq)]
pub struct SectionParams {
    /// Cutting direction (normal of the section planes); need not be unit length.
    pub direction: Vector3<f64>,
    /// Number of planes (at the centres of equal slabs of the surface's extent).
    pub count: usize,
    /// Smoothing of polyline sections (meshes, B-spline surfaces).
    pub smoothing: SmoothingParams,
    /// Parameter samples per side when slicing a B-spline surface.
    pub spline_grid: usize,
    /// Every section curve moved this far along its left normal, towards `+v` (up, for a
    /// horizontal cutting direction): a hot blade's path half its kerf off the design, on
    /// the side it removes. 0 leaves the sections as they are.
    pub offset: f64,
}

impl Default for SectionParams {
    fn default() -> Self {
        Self {
            direction: Vector3::x(),
            count: 26,
            smoothing: SmoothingParams::default(),
            spline_grid: 200,
            offset: 0.0,
        }
    }
}

/// The exact or fitted curve of a section, in plane coordinates.
#[derive(Debug, Clone)]
pub enum SectionCurve {
    /// Exact section of a height field.
    Graph(GraphCurve),
    /// Smoothing spline through a polyline section.
    Spline(SplineCurve2),
    /// Another section curve moved along its left normal ([`SectionParams::offset`]).
    Offset(Box<OffsetCurve<SectionCurve>>),
}

impl SectionCurve {
    /// Whether the curve is exact (a height field's section, or its offset) rather than
    /// fitted to points.
    pub fn is_exact(&self) -> bool {
        match self {
            Self::Graph(_) => true,
            Self::Spline(_) => false,
            Self::Offset(o) => o.base.is_exact(),
        }
    }
}

impl PlanarCurve for SectionCurve {
    fn domain(&self) -> (f64, f64) {
        match self {
            Self::Graph(g) => g.domain(),
            Self::Spline(s) => s.domain(),
            Self::Offset(o) => o.domain(),
        }
    }
    fn jet(&self, t: f64) -> Jet2 {
        match self {
            Self::Graph(g) => g.jet(t),
            Self::Spline(s) => s.jet(t),
            Self::Offset(o) => o.jet(t),
        }
    }
    fn velocity(&self, t: f64) -> Vector2<f64> {
        match self {
            Self::Spline(s) => s.velocity(t),
            other => other.jet(t).d1,
        }
    }
}

/// A planar curve moved by `distance` along its left unit normal `n` (`+90°` from the
/// tangent): `q = p + d·n`, so `q' = (1 − dκ)·p'` and its curvature is `κ / (1 − dκ)`, of
/// the same sign while `dκ < 1` (the offset has no cusp). `q''` is exact across the
/// tangent (what curvature needs); along it, the derivative of `κ` is a central
/// difference (it only sets how the speed changes).
#[derive(Debug, Clone)]
pub struct OffsetCurve<C> {
    /// The curve moved.
    pub base: C,
    /// How far, along the left normal (negative: to the right).
    pub distance: f64,
}

impl<C: PlanarCurve> PlanarCurve for OffsetCurve<C> {
    fn domain(&self) -> (f64, f64) {
        self.base.domain()
    }
    fn jet(&self, t: f64) -> Jet2 {
        let j = self.base.jet(t);
        let speed = j.d1.norm();
        if !(speed > 0.0) {
            return j;
        }
        let d = self.distance;
        let n = Vector2::new(-j.d1.y, j.d1.x) / speed;
        let k = crate::planar::signed_curvature(&j);
        let (a, b) = self.base.domain();
        let h = 1e-6 * (b - a);
        let (t0, t1) = ((t - h).max(a), (t + h).min(b));
        let kt = if t1 > t0 {
            (crate::planar::signed_curvature(&self.base.jet(t1))
                - crate::planar::signed_curvature(&self.base.jet(t0)))
                / (t1 - t0)
        } else {
            0.0
        };
        let f = 1.0 - d * k;
        Jet2 {
            p: j.p + n * d,
            d1: j.d1 * f,
            d2: j.d2 * f - j.d1 * (d * kt),
        }
    }
}

/// Samples per section at which an offset is checked against the curvature.
const OFFSET_CHECK_SAMPLES: usize = 2048;

/// `section` with its curve moved by `offset` along the left normal, or an error where the
/// design bends tighter than the offset allows (`offset · κ ≥ 1/2`: the offset curve would
/// come within a factor of two of a cusp).
fn offset_section(mut section: Section, offset: f64, frame: &PlaneFrame) -> Result<Section> {
    if offset == 0.0 {
        return Ok(section);
    }
    let (a, b) = section.curve.domain();
    for i in 0..=OFFSET_CHECK_SAMPLES {
        let t = a + (b - a) * i as f64 / OFFSET_CHECK_SAMPLES as f64;
        let j = section.curve.jet(t);
        let k = crate::planar::signed_curvature(&j);
        if !(offset * k < 0.5) {
            let p = frame.to_world(section.offset, &j.p);
            return Err(GeomError::InvalidDomain(format!(
                "an offset of {offset} is too wide where the section bends with radius {:.6} (at ({:.6}, {:.6}, {:.6})): at most half the radius",
                1.0 / k.abs(),
                p.x,
                p.y,
                p.z
            )));
        }
    }
    section.curve = SectionCurve::Offset(Box::new(OffsetCurve {
        base: section.curve,
        distance: offset,
    }));
    Ok(section)
}

/// One connected piece of the surface's section by one plane.
#[derive(Debug, Clone)]
pub struct Section {
    /// Plane index (0-based, in the order of increasing offset).
    pub index: usize,
    /// Piece index within the plane (in order of increasing `u`).
    pub piece: usize,
    /// Plane offset along the unit cutting direction.
    pub offset: f64,
    /// Whether the piece is a closed loop.
    pub closed: bool,
    /// The section curve in plane coordinates (`frame.u`, `frame.v`).
    pub curve: SectionCurve,
    /// The sectioned points in plane coordinates (empty for exact sections).
    pub points: Vec<Vector2<f64>>,
    /// RMS residual of the smoothing fit (0 for exact sections).
    pub fit_rms: f64,
    /// Parameter length of the first and last polyline segment, where the fitted curve's
    /// curvature is not determined by data (0 for exact sections).
    pub end_margins: (f64, f64),
    /// How far each point is known to lie from the true section (one per point; empty
    /// for exact sections): a mesh facet's distance from the surface, the polyline's
    /// sagitta ([`crate::fit::SplineFit::precision`]).
    pub precision: Vec<f64>,
    /// How far any point may lie from where the input put it, however exact the rest:
    /// half the step the mesh file's coordinates were written with
    /// ([`TriMesh::quantum`]); 0 for exact sections.
    pub quantization: f64,
}

impl Section {
    /// `base` with what this section's data say: its end margins, the parameters of its
    /// points (so lobes the points resolve are kept), their precision and the file's
    /// quantization (the noise floor around them) and the curvature at its ends from local fits to them (for an open
    /// piece). An exact section counts every sign change above f64 rounding
    /// ([`CurveAnalysisParams::for_exact`]).
    pub fn analysis_params(&self, base: &CurveAnalysisParams) -> CurveAnalysisParams {
        if self.points.is_empty() {
            return base.for_exact();
        }
        let data_params = chord_length_params(&self.points);
        let end_trends = if self.closed {
            (None, None)
        } else {
            end_trends(&self.points, &data_params)
        };
        CurveAnalysisParams {
            end_margins: self.end_margins,
            data_params,
            end_trends,
            data_precision: self.precision.clone(),
            noise: base.noise.max(self.quantization),
            ..base.clone()
        }
    }
}

impl Surface {
    /// Bounding box (height-field and spline heights are sampled).
    pub fn aabb(&self) -> Aabb {
        match self {
            Self::Mesh(m) => m.aabb(),
            Self::HeightField(h) => h.aabb(),
            Self::Spline(s) => Aabb::from_points(&spline_grid_points(s, 65).0).unwrap_or(Aabb {
                min: Vector3::zeros(),
                max: Vector3::zeros(),
            }),
        }
    }

    /// Range of `d · p` over the surface for a unit direction `d`.
    pub fn extent_along(&self, d: &Vector3<f64>) -> (f64, f64) {
        let range = |pts: &[Vector3<f64>]| {
            pts.iter()
                .map(|p| d.dot(p))
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                    (a.min(v), b.max(v))
                })
        };
        match self {
            Self::Mesh(m) => range(m.vertices()),
            Self::HeightField(h) => h.aabb().project(d),
            Self::Spline(s) => range(&spline_grid_points(s, 129).0),
        }
    }

    /// Sections by `params.count` planes normal to the cutting direction, at the centres of
    /// equal slabs of the surface's extent along it. `progress` is called once per plane
    /// (from worker threads). Results are in plane order, then piece order, whatever the
    /// number of threads.
    ///
    /// # Errors
    /// [`GeomError::ZeroDirection`]; [`GeomError::InvalidDomain`] for zero planes;
    /// [`GeomError::Unsupported`] for a tilted direction on a height field;
    /// fit errors for unusable sections.
    ///
    /// ```
    /// use geom::{Expr, HeightField, SectionParams, Surface};
    /// // a wave across y over a 300 × 600 rectangle, cut by planes normal to x (the default)
    /// let hf = HeightField::try_new(Expr::parse("50*sin(y/100)")?, (0.0, 300.0), (0.0, 600.0))?;
    /// let params = SectionParams { count: 3, ..SectionParams::default() };
    /// let (frame, sections) = Surface::HeightField(hf).sections(&params, &|| {})?;
    /// assert_eq!(frame.normal, nalgebra::Vector3::x());
    /// // one exact piece per plane, at the centres of three equal slabs of [0, 300]
    /// assert_eq!(sections.len(), 3);
    /// for (s, x) in sections.iter().zip([50.0, 150.0, 250.0]) {
    ///     assert!((s.offset - x).abs() < 1e-9);
    ///     assert!(s.curve.is_exact() && !s.closed);
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn sections(
        &self,
        params: &SectionParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<(PlaneFrame, Vec<Section>)> {
        let frame = PlaneFrame::from_direction(params.direction)?;
        if params.count == 0 {
            return Err(GeomError::InvalidDomain(
                "the number of sections must be at least 1".into(),
            ));
        }
        let (lo, hi) = self.extent_along(&frame.normal);
        let planes: Vec<(PlaneFrame, f64)> = slab_centres(lo, hi, params.count)
            .into_iter()
            .map(|o| (frame, o))
            .collect();
        Ok((frame, self.sections_at(&planes, params, progress)?))
    }

    /// Sections by arbitrary planes, each given by its frame and its offset along the frame's
    /// normal (planes need not be parallel: cutting planes that follow a curve, thesis
    /// eq. 5.4). `params.direction` and `params.count` are not used. A section's `index` is
    /// the index of its plane in `planes`; results are in plane order, then piece order.
    ///
    /// # Errors
    /// As [`Surface::sections`].
    ///
    /// ```
    /// use geom::planar::PlanarCurve;
    /// use geom::slice::PlaneFrame;
    /// use geom::{Expr, HeightField, SectionParams, Surface};
    /// use nalgebra::Vector3;
    /// // the plane z = x + 2y, cut by the planes x = 1 and x = 2
    /// let plane = HeightField::try_new(Expr::parse("x + 2*y")?, (0.0, 3.0), (0.0, 1.0))?;
    /// let frame = PlaneFrame::from_direction(Vector3::x())?;
    /// let sections = Surface::HeightField(plane)
    ///     .sections_at(&[(frame, 1.0), (frame, 2.0)], &SectionParams::default(), &|| {})?;
    /// assert_eq!(sections.len(), 2);
    /// // in plane coordinates (u, v) = (y, z) each section is the line v = x + 2u
    /// for (s, x) in sections.iter().zip([1.0, 2.0]) {
    ///     let (a, b) = s.curve.domain();
    ///     for t in [a, 0.5 * (a + b), b] {
    ///         let p = s.curve.point(t);
    ///         assert!((p.y - (x + 2.0 * p.x)).abs() < 1e-12);
    ///     }
    /// }
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn sections_at(
        &self,
        planes: &[(PlaneFrame, f64)],
        params: &SectionParams,
        progress: &(dyn Fn() + Sync),
    ) -> Result<Vec<Section>> {
        let spline_mesh = match self {
            Self::Spline(s) => Some(spline_grid_mesh(s, params.spline_grid.max(8))?),
            _ => None,
        };
        let normals = match self {
            Self::Mesh(m) => m.vertex_normals(),
            _ => Vec::new(),
        };
        let quantization = match self {
            Self::Mesh(m) => 0.5 * m.quantum(),
            _ => 0.0,
        };
        // Planes are independent: in parallel with the `parallel` feature, in order without.
        #[cfg(feature = "parallel")]
        let planes_iter = planes.par_iter();
        #[cfg(not(feature = "parallel"))]
        let planes_iter = planes.iter();
        let per_plane: Vec<Result<Vec<Section>>> = planes_iter
            .enumerate()
            .map(|(index, &(frame, offset))| {
                let r = match self {
                    Self::HeightField(h) => Ok(h
                        .section(&frame, offset)?
                        .map(|g| Section {
                            index,
                            piece: 0,
                            offset,
                            closed: false,
                            curve: SectionCurve::Graph(g),
                            points: Vec::new(),
                            fit_rms: 0.0,
                            end_margins: (0.0, 0.0),
                            precision: Vec::new(),
                            quantization: 0.0,
                        })
                        .into_iter()
                        .collect()),
                    Self::Mesh(m) => {
                        let chains = slice_mesh(m, &frame.normal, offset);
                        let polys = chains
                            .iter()
                            .map(|c| Polyline {
                                points: c.points(m),
                                deviation: Some(c.facet_deviation(m, &normals)),
                                closed: c.closed,
                            })
                            .collect();
                        let chordal = SmoothingParams {
                            chordal: true,
                            ..params.smoothing.clone()
                        };
                        fit_pieces(&frame, index, offset, polys, &chordal, quantization)
                    }
                    Self::Spline(s) => {
                        let (mesh, uv) = spline_mesh
                            .as_ref()
                            .ok_or(GeomError::Unsupported("spline mesh".into()))?;
                        let chains = slice_mesh(mesh, &frame.normal, offset);
                        let polys = chains
                            .iter()
                            .map(|c| Polyline {
                                points: refine_on_spline(s, uv, c, &frame.normal, offset),
                                deviation: None,
                                closed: c.closed,
                            })
                            .collect();
                        fit_pieces(&frame, index, offset, polys, &params.smoothing, 0.0)
                    }
                };
                progress();
                r.and_then(|pieces: Vec<Section>| {
                    pieces
                        .into_iter()
                        .map(|s| offset_section(s, params.offset, &frame))
                        .collect()
                })
            })
            .collect();
        let mut out = Vec::new();
        for r in per_plane {
            out.extend(r?);
        }
        Ok(out)
    }
}

/// One piece of a plane's section as sliced: its points, how far each may lie from the
/// true surface (mesh facets), and whether it closes.
struct Polyline {
    points: Vec<Vector3<f64>>,
    deviation: Option<Vec<f64>>,
    closed: bool,
}

/// A cleaned piece in plane coordinates.
struct Piece {
    points: Vec<Vector2<f64>>,
    deviation: Option<Vec<f64>>,
    closed: bool,
}

/// Orders, cleans and fits the polyline pieces of one plane.
fn fit_pieces(
    frame: &PlaneFrame,
    index: usize,
    offset: f64,
    polys: Vec<Polyline>,
    smoothing: &SmoothingParams,
    quantization: f64,
) -> Result<Vec<Section>> {
    let mut pieces: Vec<Piece> = Vec::new();
    for poly in polys {
        let mut q: Vec<Vector2<f64>> = Vec::with_capacity(poly.points.len() + 1);
        let mut dev: Vec<f64> = Vec::with_capacity(poly.points.len() + 1);
        for (k, p) in poly.points.iter().enumerate() {
            let x = frame.to_plane(p);
            let d = poly.deviation.as_ref().map_or(0.0, |d| d[k]);
            match q.last() {
                Some(l) if (l - x).norm() <= 1e-9 * (1.0 + x.norm()) => {
                    // one point: the larger allowance
                    if let Some(last) = dev.last_mut() {
                        *last = last.max(d);
                    }
                }
                _ => {
                    q.push(x);
                    dev.push(d);
                }
            }
        }
        if poly.closed {
            // start at the point of smallest u, and close the loop explicitly
            if let Some(k) = (0..q.len()).min_by(|&a, &b| q[a].x.total_cmp(&q[b].x).then(a.cmp(&b)))
            {
                q.rotate_left(k);
                dev.rotate_left(k);
            }
            if let (Some(&f), Some(&d)) = (q.first(), dev.first()) {
                q.push(f);
                dev.push(d);
            }
        } else if q.len() >= 2 && q[q.len() - 1].x < q[0].x {
            q.reverse();
            dev.reverse();
        }
        if q.len() >= 2 {
            pieces.push(Piece {
                points: q,
                deviation: poly.deviation.is_some().then_some(dev),
                closed: poly.closed,
            });
        }
    }
    pieces.sort_by(|a, b| {
        let ma = a.points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        let mb = b.points.iter().map(|p| p.x).fold(f64::INFINITY, f64::min);
        ma.total_cmp(&mb)
    });
    pieces
        .into_iter()
        .enumerate()
        .map(
            |(
                piece,
                Piece {
                    points,
                    deviation,
                    closed,
                },
            )| {
                let mut s = Section::from_points(points, deviation.as_deref(), closed, smoothing)?;
                s.index = index;
                s.piece = piece;
                s.offset = offset;
                s.quantization = quantization;
                Ok(s)
            },
        )
        .collect()
}

impl Section {
    /// A section given as points of its plane, as a sectioned polyline is: a smoothing
    /// spline through them (`smoothing`), its end margins and the points' precision, so
    /// that [`Section::analysis_params`] reads it as it reads a mesh's sections. `deviation`:
    /// how far each point may lie from the true curve (`None`: exact points). Index, piece
    /// and offset are 0.
    ///
    /// ```
    /// use geom::fit::SmoothingParams;
    /// use geom::surface::Section;
    /// use nalgebra::Vector2;
    /// let pts: Vec<Vector2<f64>> = (0..50).map(|i| {
    ///     let x = i as f64 * 10.0;
    ///     Vector2::new(x, 30.0 * (x / 80.0).sin())
    /// }).collect();
    /// let s = Section::from_points(pts, None, false, &SmoothingParams::default())?;
    /// assert!(s.fit_rms < 0.05 && !s.closed);
    /// # Ok::<(), geom::GeomError>(())
    /// ```
    ///
    /// # Errors
    /// [`GeomError::InvalidFit`] for fewer than 2 points, or the smoothing fit's.
    pub fn from_points(
        points: Vec<Vector2<f64>>,
        deviation: Option<&[f64]>,
        closed: bool,
        smoothing: &SmoothingParams,
    ) -> Result<Section> {
        let n = points.len();
        if n < 2 {
            return Err(GeomError::InvalidFit(format!(
                "a section needs at least 2 points, got {n}"
            )));
        }
        let fit = fit_smoothing_allowing(&points, None, smoothing, deviation)?;
        let end_margins = (
            (points[1] - points[0]).norm(),
            (points[n - 1] - points[n - 2]).norm(),
        );
        Ok(Section {
            end_margins,
            index: 0,
            piece: 0,
            offset: 0.0,
            closed,
            curve: SectionCurve::Spline(SplineCurve2::new(fit.curve)),
            points,
            fit_rms: fit.rms,
            precision: fit.precision,
            quantization: 0.0,
        })
    }
}

/// Surface points on an `n × n` parameter grid, with their parameters.
fn spline_grid_points(s: &BSplineSurface, n: usize) -> (Vec<Vector3<f64>>, Vec<(f64, f64)>) {
    let ((u0, u1), (v0, v1)) = s.domain();
    let mut pts = Vec::with_capacity(n * n);
    let mut uv = Vec::with_capacity(n * n);
    for i in 0..n {
        for j in 0..n {
            let u = u0 + (u1 - u0) * i as f64 / (n - 1) as f64;
            let v = v0 + (v1 - v0) * j as f64 / (n - 1) as f64;
            pts.push(s.eval(u, v));
            uv.push((u, v));
        }
    }
    (pts, uv)
}

impl Surface {
    /// The surface as a triangle mesh: a mesh as it is, a height field on `n × n` cells of
    /// its rectangle, a B-spline surface at `n × n` samples of its parameter domain.
    ///
    /// # Errors
    /// [`GeomError::InvalidDomain`] for `n < 2`; mesh errors for a degenerate grid.
    ///
    /// ```
    /// use geom::{Expr, HeightField, Surface};
    /// // a tilted plane z = x over the unit square: every tessellation has the area √2
    /// let hf = HeightField::try_new(Expr::parse("x")?, (0.0, 1.0), (0.0, 1.0))?;
    /// let mesh = Surface::HeightField(hf).to_mesh(4)?;
    /// assert_eq!(mesh.faces().len(), 2 * 4 * 4);
    /// assert!((mesh.area() - 2f64.sqrt()).abs() < 1e-12);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_mesh(&self, n: usize) -> Result<TriMesh> {
        match self {
            Surface::Mesh(m) => Ok(m.clone()),
            Surface::HeightField(h) => h.to_mesh(n, n),
            Surface::Spline(s) => s.to_mesh(n),
        }
    }
}

impl BSplineSurface {
    /// The surface tessellated on an `n × n` grid of its parameter domain (`n ≥ 2`).
    ///
    /// # Errors
    /// [`GeomError::InvalidDomain`] for `n < 2`; mesh errors for a degenerate grid.
    pub fn to_mesh(&self, n: usize) -> Result<TriMesh> {
        if n < 2 {
            return Err(GeomError::InvalidDomain(format!(
                "a tessellation needs at least 2 samples per side, got {n}"
            )));
        }
        Ok(spline_grid_mesh(self, n)?.0)
    }
}

pub(crate) fn spline_grid_mesh(s: &BSplineSurface, n: usize) -> Result<(TriMesh, Vec<(f64, f64)>)> {
    let (pts, uv) = spline_grid_points(s, n);
    let mut faces = Vec::with_capacity(2 * (n - 1) * (n - 1));
    let w = n as u32;
    for i in 0..w - 1 {
        for j in 0..w - 1 {
            let a = i * w + j;
            faces.push([a, a + w, a + w + 1]);
            faces.push([a, a + w + 1, a + 1]);
        }
    }
    Ok((TriMesh::try_new(pts, faces)?, uv))
}

/// Moves each crossing of a chain on the sampled spline mesh onto the exact surface by
/// bisection of `n · S(u, v) − offset` along the crossing's parameter-space edge.
fn refine_on_spline(
    s: &BSplineSurface,
    uv: &[(f64, f64)],
    chain: &Chain,
    n: &Vector3<f64>,
    offset: f64,
) -> Vec<Vector3<f64>> {
    chain
        .crossings
        .iter()
        .map(|c| {
            let (pa, pb) = (uv[c.a as usize], uv[c.b as usize]);
            let at = |t: f64| s.eval(pa.0 + (pb.0 - pa.0) * t, pa.1 + (pb.1 - pa.1) * t);
            let g = |t: f64| n.dot(&at(t)) - offset;
            let (mut lo, mut hi) = (0.0, 1.0);
            let glo = g(lo);
            if glo == 0.0 {
                return at(0.0);
            }
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                let gm = g(mid);
                if (gm >= 0.0) == (glo >= 0.0) {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            at(0.5 * (lo + hi))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analysis::{analyze_curve, CurveAnalysisParams};

    #[test]
    fn spline_surface_sections_are_on_the_surface() {
        let (nu, nv) = (6, 5);
        let mut c = Vec::new();
        for i in 0..nu {
            for j in 0..nv {
                c.push(Vector3::new(
                    i as f64 * 100.0,
                    j as f64 * 100.0,
                    ((i + 2 * j) % 3) as f64 * 30.0,
                ));
            }
        }
        let s = BSplineSurface::clamped_uniform((3, 3), (nu, nv), c).unwrap();
        let surf = Surface::Spline(s.clone());
        let params = SectionParams {
            count: 5,
            smoothing: SmoothingParams {
                tolerance: 1e-4,
                ..Default::default()
            },
            ..Default::default()
        };
        let (frame, secs) = surf.sections(&params, &|| {}).unwrap();
        assert_eq!(secs.len(), 5);
        for sec in &secs {
            // every sectioned point lies in its plane and on the surface (checked via v-line search)
            for q in &sec.points {
                let p = frame.to_world(sec.offset, q);
                assert!((frame.normal.dot(&p) - sec.offset).abs() < 1e-9);
            }
            let a = analyze_curve(&sec.curve, &CurveAnalysisParams::default()).unwrap();
            assert!(a.length > 300.0);
        }
    }
}
