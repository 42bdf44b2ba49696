use geom::analysis::{analyze_curve, CurveAnalysisParams};
use geom::planar::{signed_curvature, ArcLength, PlanarCurve};
use geom::slice::PlaneFrame;
use geom::surface::{Section, SectionCurve};
use nalgebra::{Vector2, Vector3};

use crate::SegError;

/// One section of the facade, ready for segmentation: its curve with an arc-length table
/// and its inflections. Positions along it are arc lengths `s ∈ [0, length]` from the
/// curve's start, which lies on the facade's edge along the cut.
#[derive(Debug, Clone)]
pub struct PreparedSection {
    /// Plane index in the input.
    pub index: usize,
    /// Plane offset along the cutting direction.
    pub offset: f64,
    /// The section curve in plane coordinates.
    pub curve: SectionCurve,
    arc: ArcLength,
    /// Arc length of the curve.
    pub length: f64,
    /// Arc lengths of its inflections, increasing.
    pub inflections: Vec<f64>,
    /// Arc lengths of its curvature maxima (by absolute value), increasing.
    pub curvature_maxima: Vec<f64>,
}

/// The facade: the frame of its (parallel) section planes and one prepared section per
/// plane, in plane order.
#[derive(Debug, Clone)]
pub struct Facade {
    /// Frame of the section planes: `normal` is the cutting direction, `u` runs across the
    /// facade, `v` completes the frame.
    pub frame: PlaneFrame,
    /// One section per plane (the longest piece where a plane cuts the surface in several).
    pub sections: Vec<PreparedSection>,
}

impl Facade {
    /// Prepares the output of [`geom::surface::Surface::sections`].
    ///
    /// # Errors
    /// [`SegError::NoSections`] for no sections; [`SegError::Section`] when a curve cannot
    /// be analysed.
    pub fn new(frame: PlaneFrame, sections: &[Section]) -> Result<Self, SegError> {
        Self::with_analysis(frame, sections, &CurveAnalysisParams::default())
    }

    /// [`Facade::new`] with the inflections of every section found by `analysis` (the
    /// job's bisection tolerance and least lobe turning).
    ///
    /// # Errors
    /// As [`Facade::new`].
    pub fn with_analysis(
        frame: PlaneFrame,
        sections: &[Section],
        analysis: &CurveAnalysisParams,
    ) -> Result<Self, SegError> {
        let mut best: Vec<(usize, &Section, f64)> = Vec::new();
        for s in sections {
            let arc = ArcLength::new(&s.curve, 64);
            let len = arc.length();
            match best.iter_mut().find(|b| b.0 == s.index) {
                Some(b) if b.2 >= len => {}
                Some(b) => *b = (s.index, s, len),
                None => best.push((s.index, s, len)),
            }
        }
        best.sort_by_key(|b| b.0);
        let prepared: Result<Vec<_>, _> = best
            .into_iter()
            .map(|(index, s, _)| {
                PreparedSection::with_analysis(
                    index,
                    s.offset,
                    s.curve.clone(),
                    &s.analysis_params(analysis),
                )
            })
            .collect();
        let sections = prepared?;
        if sections.is_empty() {
            return Err(SegError::NoSections);
        }
        Ok(Self { frame, sections })
    }

    /// Mean spacing between consecutive section planes (0 for one section).
    pub fn spacing(&self) -> f64 {
        let n = self.sections.len();
        if n < 2 {
            return 0.0;
        }
        (self.sections[n - 1].offset - self.sections[0].offset).abs() / (n - 1) as f64
    }

    /// World point of section `j` at arc length `s`.
    pub fn world(&self, j: usize, s: f64) -> Vector3<f64> {
        let sec = &self.sections[j];
        self.frame.to_world(sec.offset, &sec.point(s))
    }

    /// `n + 1` world points of a piece's part, equally spaced in arc length (`n ≥ 1`; none
    /// when its section is not in the facade or `n = 0`).
    pub fn part_points(&self, part: &crate::PiecePart, n: usize) -> Vec<Vector3<f64>> {
        let Some(j) = self.sections.iter().position(|s| s.index == part.plane) else {
            return Vec::new();
        };
        if n == 0 {
            return Vec::new();
        }
        (0..=n)
            .map(|m| {
                let s = part.s[0] + (part.s[1] - part.s[0]) * m as f64 / n as f64;
                self.world(j, s)
            })
            .collect()
    }

    /// A piece as a triangle strip between its consecutive parts, each sampled at `n + 1`
    /// points (`n ≥ 1`): the positions (part after part) and the triangles' vertex indices.
    /// `None` for a piece of fewer than two parts, `n = 0`, or a part whose section is not
    /// in the facade.
    pub fn piece_strip(
        &self,
        piece: &crate::Piece,
        n: usize,
    ) -> Option<(Vec<Vector3<f64>>, Vec<u32>)> {
        if piece.parts.len() < 2 || n == 0 {
            return None;
        }
        let mut positions = Vec::with_capacity(piece.parts.len() * (n + 1));
        for part in &piece.parts {
            let points = self.part_points(part, n);
            if points.len() != n + 1 {
                return None;
            }
            positions.extend(points);
        }
        let row = (n + 1) as u32;
        let mut indices = Vec::new();
        for k in 0..piece.parts.len() as u32 - 1 {
            for m in 0..n as u32 {
                let a = k * row + m;
                let b = a + row;
                indices.extend([a, b, a + 1, a + 1, b, b + 1]);
            }
        }
        Some((positions, indices))
    }
}

/// Curvature samples per exact section for its inflections, at least.
pub use geom::analysis::EXACT_SAMPLES;

impl PreparedSection {
    /// Tabulates the arc length and finds the inflections of one section curve.
    ///
    /// # Errors
    /// [`SegError::Section`] when the curve cannot be analysed.
    pub fn new(index: usize, offset: f64, curve: SectionCurve) -> Result<Self, SegError> {
        Self::with_analysis(index, offset, curve, &CurveAnalysisParams::default())
    }

    /// [`PreparedSection::new`] with the inflections found by `params`.
    ///
    /// The inflections count against `max_inflections` (the blade's shape), so on an
    /// exact section (a height field's) every sign change of the curvature above f64
    /// rounding counts, as a dense count of the exact second derivative finds them
    /// ([`CurveAnalysisParams::for_exact`]). `min_lobe_turning` applies to smoothed
    /// polyline sections only; the noise floor of [`geom::significance`] to every section.
    ///
    /// # Errors
    /// As [`PreparedSection::new`].
    pub fn with_analysis(
        index: usize,
        offset: f64,
        curve: SectionCurve,
        params: &CurveAnalysisParams,
    ) -> Result<Self, SegError> {
        let exact;
        let params = if curve.is_exact() {
            exact = params.for_exact();
            &exact
        } else {
            params
        };
        let analysis = analyze_curve(&curve, params).map_err(|e| SegError::Section {
            index,
            message: e.to_string(),
        })?;
        let arc = ArcLength::new(&curve, 512);
        Ok(Self {
            index,
            offset,
            length: arc.length(),
            inflections: analysis.inflections.iter().map(|p| p.s).collect(),
            curvature_maxima: analysis.curvature_maxima.iter().map(|p| p.s).collect(),
            arc,
            curve,
        })
    }

    /// Curve parameter at arc length `s`.
    pub fn t_at(&self, s: f64) -> f64 {
        self.arc.t_at(&self.curve, s)
    }

    /// Point (plane coordinates) at arc length `s`.
    pub fn point(&self, s: f64) -> Vector2<f64> {
        self.curve.point(self.t_at(s))
    }

    /// `n ≥ 2` points equally spaced in arc length on `[s0, s1]`, and their arc lengths
    /// from `s0`.
    pub fn samples(&self, s0: f64, s1: f64, n: usize) -> (Vec<[f64; 2]>, Vec<f64>) {
        let n = n.max(2);
        let mut pts = Vec::with_capacity(n);
        let mut ss = Vec::with_capacity(n);
        for i in 0..n {
            let s = s0 + (s1 - s0) * i as f64 / (n - 1) as f64;
            let q = self.point(s);
            pts.push([q.x, q.y]);
            ss.push(s - s0);
        }
        (pts, ss)
    }

    /// Inflections strictly inside `(s0, s1)`.
    pub fn inflections_in(&self, s0: f64, s1: f64) -> usize {
        self.inflections
            .iter()
            .filter(|&&s| s > s0 && s < s1)
            .count()
    }

    /// Largest |curvature| of the design on `[s0, s1]`, sampled at `n` points.
    pub fn max_abs_curvature(&self, s0: f64, s1: f64, n: usize) -> f64 {
        let n = n.max(2);
        (0..n)
            .map(|i| {
                let s = s0 + (s1 - s0) * i as f64 / (n - 1) as f64;
                signed_curvature(&self.curve.jet(self.t_at(s))).abs()
            })
            .fold(0.0, f64::max)
    }
}
