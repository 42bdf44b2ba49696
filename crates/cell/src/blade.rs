//! The hot blade between its two held ends: a pose as the two tool frames, the same pose
//! in the blade's own plane (chord, end angles), interpolation between two poses that
//! keeps every intermediate blade an elastica of the blade's length, and the blade's shape
//! rebuilt from its ends (the discrete elastica of [`elastica::discrete`]).
//!
//! A held end's tool frame has its x-axis along the blade's tangent (from the blade's
//! first end to its second) and its z-axis along the cutting plane's normal, the
//! convention of [`elastica::sweep`].

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, UnitQuaternion, Vector3};

use elastica::discrete::{discrete_elastica, DiscreteParams};

use crate::error::{CellError, Result};

/// The tool frames of the blade's two held ends (first end, second end).
pub type BladePose = [Isometry3<f64>; 2];

/// A blade pose in the blade's own plane: where its chord lies and how the ends leave it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanarPose {
    /// Midpoint of the chord.
    pub mid: Vector3<f64>,
    /// Frame of the plane: x along the chord (first end to second), z the plane's normal.
    pub frame: UnitQuaternion<f64>,
    /// Distance between the ends.
    pub chord: f64,
    /// Tangent angle of each end against the chord, in the plane (radians, (−π, π]).
    pub angles: [f64; 2],
}

/// Segments of the discrete elastica a blade shape is rebuilt with.
pub const SHAPE_SEGMENTS: usize = 48;

/// A blade's shape rebuilt from its ends.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BladeShape {
    /// Points along the blade, first end to second.
    pub points: Vec<[f64; 3]>,
    /// Largest curvature of the discrete blade (turning angle over segment length).
    pub max_curvature: f64,
}

impl BladeShape {
    /// The lowest `z` of the blade.
    ///
    /// ```
    /// use cell::blade::{from_planar, PlanarPose};
    /// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
    /// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
    /// // and back, in the plane whose normal is x
    /// let a = 20f64.to_radians();
    /// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
    ///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
    /// ));
    /// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
    /// let pose = from_planar(&held);
    /// // a blade 714 long: nearly the circular arc with those ends (700 · θ / sin θ at
    /// // θ = 20°), an arch above its chord whose ends are lowest
    /// let s = cell::blade::shape(&pose, 714.0)?;
    /// assert!((s.lowest() - 300.0).abs() < 1e-9);
    /// assert!(s.points.iter().all(|p| p[2] >= 300.0 - 1e-9));
    /// # Ok::<(), cell::CellError>(())
    /// ```
    pub fn lowest(&self) -> f64 {
        self.points
            .iter()
            .map(|p| p[2])
            .fold(f64::INFINITY, f64::min)
    }
}

/// The pose in the blade's plane. The plane's normal is the first end's tool z-axis made
/// perpendicular to the chord.
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
/// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
/// // and back, in the plane whose normal is x
/// let a = 20f64.to_radians();
/// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
/// let pose = from_planar(&held);
/// let q = cell::blade::planar(&pose)?;
/// assert!((q.chord - 700.0).abs() < 1e-9 && (q.mid - held.mid).norm() < 1e-9);
/// assert!((q.angles[0] - a).abs() < 1e-12 && (q.angles[1] + a).abs() < 1e-12);
/// assert!(q.frame.angle_to(&frame) < 1e-9);
/// // the ends at one point: no plane
/// assert!(cell::blade::planar(&[pose[0], pose[0]]).is_err());
/// # Ok::<(), cell::CellError>(())
/// ```
///
/// # Errors
/// [`CellError::Blade`] when the two ends coincide or the normal lies along the chord.
pub fn planar(p: &BladePose) -> Result<PlanarPose> {
    let (a, b) = (p[0].translation.vector, p[1].translation.vector);
    let d = b - a;
    let chord = d.norm();
    if !(chord > 0.0) || !chord.is_finite() {
        return Err(CellError::Blade("the blade's two ends coincide".into()));
    }
    let x = d / chord;
    let n = p[0].rotation * Vector3::z();
    let z = n - x * n.dot(&x);
    if !(z.norm() > 1e-9) {
        return Err(CellError::Blade(
            "the cutting plane's normal lies along the blade's chord".into(),
        ));
    }
    let z = z.normalize();
    let y = z.cross(&x);
    let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
        Matrix3::from_columns(&[x, y, z]),
    ));
    let angle = |e: usize| {
        let t = p[e].rotation * Vector3::x();
        t.dot(&y).atan2(t.dot(&x))
    };
    Ok(PlanarPose {
        mid: (a + b) * 0.5,
        frame,
        chord,
        angles: [angle(0), angle(1)],
    })
}

/// The tool frames of a planar pose.
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
/// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
/// // and back, in the plane whose normal is x
/// let a = 20f64.to_radians();
/// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
/// let pose = from_planar(&held);
/// // the ends on the chord, 350 either side of the middle, along the frame's x (here y)
/// let (first, second) = (pose[0].translation.vector, pose[1].translation.vector);
/// assert!((first - Vector3::new(0.0, -350.0, 300.0)).norm() < 1e-9);
/// assert!((second - Vector3::new(0.0, 350.0, 300.0)).norm() < 1e-9);
/// // each tool frame: x along the blade's tangent, z the plane's normal
/// let tangent = pose[0].rotation * Vector3::x();
/// assert!((tangent - Vector3::new(0.0, a.cos(), a.sin())).norm() < 1e-12);
/// assert!((pose[1].rotation * Vector3::z() - Vector3::x()).norm() < 1e-12);
/// ```
pub fn from_planar(p: &PlanarPose) -> BladePose {
    let x = p.frame * Vector3::x();
    let y = p.frame * Vector3::y();
    let z = p.frame * Vector3::z();
    let end = |e: usize, sign: f64| {
        let t = x * p.angles[e].cos() + y * p.angles[e].sin();
        let r = Matrix3::from_columns(&[t, z.cross(&t), z]);
        Isometry3::from_parts(
            Translation3::from(p.mid + x * (sign * 0.5 * p.chord)),
            UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r)),
        )
    };
    [end(0, -1.0), end(1, 1.0)]
}

/// The pose a fraction `w ∈ [0, 1]` of the way from `a` to `b`: midpoint, chord and end
/// angles linear (each angle the short way round), plane frame by spherical
/// interpolation. Each end then moves on a smooth path, and the chord never exceeds the
/// longer of the two.
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
/// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
/// // and back, in the plane whose normal is x
/// let a = 20f64.to_radians();
/// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
/// let pose = from_planar(&held);
/// use cell::blade::interpolate;
/// let wider = PlanarPose { chord: 760.0, angles: [0.5 * a, -0.5 * a], ..held };
/// let half = interpolate(&held, &wider, 0.5);
/// assert!((half.chord - 730.0).abs() < 1e-12);
/// assert!((half.angles[0] - 0.75 * a).abs() < 1e-12);
/// assert_eq!(interpolate(&held, &wider, 0.0), held);
/// ```
pub fn interpolate(a: &PlanarPose, b: &PlanarPose, w: f64) -> PlanarPose {
    let lerp = |u: f64, v: f64| u + (v - u) * w;
    let turn = |u: f64, v: f64| u + angle_between(u, v) * w;
    PlanarPose {
        mid: a.mid + (b.mid - a.mid) * w,
        frame: a.frame.slerp(&b.frame, w),
        chord: lerp(a.chord, b.chord),
        angles: [
            turn(a.angles[0], b.angles[0]),
            turn(a.angles[1], b.angles[1]),
        ],
    }
}

/// The turn from angle `u` to angle `v` the short way round, in (−π, π].
///
/// ```
/// use cell::blade::angle_between;
/// use std::f64::consts::PI;
/// assert!((angle_between(0.1, 0.3) - 0.2).abs() < 1e-15);
/// // from just below +π to just above −π: a small turn left, not almost a whole one back
/// assert!((angle_between(PI - 0.1, -PI + 0.1) - 0.2).abs() < 1e-12);
/// assert_eq!(angle_between(0.0, PI), PI); // half a turn: in (−π, π]
/// ```
pub fn angle_between(u: f64, v: f64) -> f64 {
    let pi = std::f64::consts::PI;
    pi - (pi - (v - u)).rem_euclid(2.0 * pi)
}

/// The shape of a blade of `length` held at `p`: the discrete elastica of
/// [`SHAPE_SEGMENTS`] segments between the two ends with their tangents.
///
/// ```
/// use cell::blade::{from_planar, shape, PlanarPose};
/// use nalgebra::{UnitQuaternion, Vector3};
/// // a blade of 800 held 700 apart, both ends leaving the chord at 20° upwards and back
/// let a = 20f64.to_radians();
/// let pose = from_planar(&PlanarPose { mid: Vector3::zeros(),
///     frame: UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, 0.0),
///     chord: 700.0, angles: [a, -a] });
/// let s = shape(&pose, 800.0).unwrap();
/// assert!(s.points.iter().all(|p| p[2] >= -1e-9)); // an arch above the chord
/// ```
///
/// A blade held straight with its ends a blade length apart (as mounted) is a line.
///
/// # Errors
/// [`CellError::Blade`] when the chord is not shorter than the blade (unless the blade is
/// straight and taut) or no elastica joins the ends.
pub fn shape(p: &BladePose, length: f64) -> Result<BladeShape> {
    let q = planar(p)?;
    let (x, y) = (q.frame * Vector3::x(), q.frame * Vector3::y());
    // a blade held taut and straight, as mounted (its ends a blade length apart, the
    // tangents along the chord): a line
    let taut = (q.chord - length).abs() <= 1e-9 * length;
    if taut && q.angles.iter().all(|a| a.abs() <= 1e-9) {
        let points = (0..=SHAPE_SEGMENTS)
            .map(|i| {
                let u = i as f64 / SHAPE_SEGMENTS as f64 - 0.5;
                (q.mid + x * (u * q.chord)).into()
            })
            .collect();
        return Ok(BladeShape {
            points,
            max_curvature: 0.0,
        });
    }
    if !(q.chord < length) {
        return Err(CellError::Blade(format!(
            "the ends are {:.3} mm apart, not less than the blade's length {length:.3} mm",
            q.chord
        )));
    }
    let d = discrete_elastica(&DiscreteParams {
        segments: SHAPE_SEGMENTS,
        start: [-0.5 * q.chord, 0.0],
        start_angle: q.angles[0],
        end: [0.5 * q.chord, 0.0],
        end_angle: q.angles[1],
        length,
        max_iterations: 200,
    })
    .map_err(|e| CellError::Blade(e.to_string()))?;
    let points = d
        .points
        .iter()
        .map(|v| (q.mid + x * v[0] + y * v[1]).into())
        .collect();
    let h = length / SHAPE_SEGMENTS as f64;
    let mut turns: Vec<f64> = d.angles.windows(2).map(|w| (w[1] - w[0]) / h).collect();
    // the end turns happen over half a segment
    turns.push((d.angles[0] - q.angles[0]) / (0.5 * h));
    turns.push((q.angles[1] - d.angles[SHAPE_SEGMENTS - 1]) / (0.5 * h));
    let max_curvature = turns.iter().map(|k| k.abs()).fold(0.0, f64::max);
    Ok(BladeShape {
        points,
        max_curvature,
    })
}

/// The pose moved by `v` (both ends, orientation kept).
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
/// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
/// // and back, in the plane whose normal is x
/// let a = 20f64.to_radians();
/// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
/// let pose = from_planar(&held);
/// use cell::blade::{normal, translated};
/// let v = Vector3::new(10.0, 0.0, -5.0);
/// let moved = translated(&pose, &v);
/// assert!((moved[1].translation.vector - pose[1].translation.vector - v).norm() < 1e-12);
/// assert_eq!(moved[0].rotation, pose[0].rotation);
/// assert!((normal(&moved) - Vector3::x()).norm() < 1e-12);
/// ```
pub fn translated(p: &BladePose, v: &Vector3<f64>) -> BladePose {
    let t = Translation3::from(*v);
    [t * p[0], t * p[1]]
}

/// The cutting plane's normal of a pose (the first end's tool z-axis).
///
/// ```
/// use cell::blade::{from_planar, PlanarPose};
/// use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};
/// // a blade held 700 apart along y, 300 up, its ends leaving the chord at 20° upwards
/// // and back, in the plane whose normal is x
/// let a = 20f64.to_radians();
/// let frame = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(
///     Matrix3::from_columns(&[Vector3::y(), Vector3::z(), Vector3::x()]),
/// ));
/// let held = PlanarPose { mid: Vector3::new(0.0, 0.0, 300.0), frame, chord: 700.0, angles: [a, -a] };
/// let pose = from_planar(&held);
/// assert!((cell::blade::normal(&pose) - Vector3::x()).norm() < 1e-12);
/// ```
pub fn normal(p: &BladePose) -> Vector3<f64> {
    p[0].rotation * Vector3::z()
}
