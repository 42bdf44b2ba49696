//! Surfaces swept by elastica ("Hot Blade Cuttings" §4, §6) and the blade poses that cut
//! them ("Robotic Hot-Blade Cutting" §4).
//!
//! A swept patch is a sequence of fitted segments, each in its own cutting plane. Between
//! two fitted planes the patch is swept by the segments whose shape parameters interpolate
//! the neighbours' linearly and whose end points move linearly ([`interpolate`](crate::sweep::interpolate)). The 3D pose of a blade ([`blade_pose`](crate::sweep::blade_pose)) gives, for both held ends,
//! the position, the unit tangent and the tool orientation as a unit quaternion whose x-axis
//! is the blade's tangent (pointing from the first end to the second) and whose z-axis is
//! the cutting plane's normal.

use geom::slice::PlaneFrame;
use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector2, Vector3};

use crate::blade::Blade;
use crate::segment::{ElasticaParams, Segment};

fn lerp(a: f64, b: f64, w: f64) -> f64 {
    a + (b - a) * w
}

/// The segment a fraction `w ∈ [0, 1]` of the way from `a` to `b`: the shape parameters
/// interpolated linearly (elastica: k, s₀, ℓ of one family; arc: the turning angle; line:
/// nothing), placed between the linearly interpolated end points (the papers interpolate
/// "end points, end tangents and lengths", §6). `None` when the two are of different
/// kinds or elastica families, or the shape degenerates: the sweep between them is then
/// not a family of one kind, and the caller decides what to do.
///
/// ```
/// use elastica::segment::Segment;
/// use elastica::sweep::interpolate;
/// let a = Segment::Line { x0: 0.0, y0: 0.0, phi: 0.0, length: 100.0 };
/// let b = Segment::Line { x0: 0.0, y0: 10.0, phi: 0.0, length: 120.0 };
/// let Some(Segment::Line { y0, length, .. }) = interpolate(&a, &b, 0.5) else { panic!() };
/// assert_eq!((y0, length), (5.0, 110.0));
/// ```
pub fn interpolate(a: &Segment, b: &Segment, w: f64) -> Option<Segment> {
    let ends = |s: &Segment| -> Option<([f64; 2], [f64; 2])> {
        let e = s.evaluator().ok()?;
        Some((e.eval(0.0).p, e.eval(1.0).p))
    };
    let ((a0, a1), (b0, b1)) = (ends(a)?, ends(b)?);
    let mix = |p: [f64; 2], q: [f64; 2]| [lerp(p[0], q[0], w), lerp(p[1], q[1], w)];
    let (p0, p1) = (mix(a0, b0), mix(a1, b1));
    let chord = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
    let dir = (p1[1] - p0[1]).atan2(p1[0] - p0[0]);
    match (*a, *b) {
        (Segment::Elastica(p), Segment::Elastica(q)) if p.family == q.family => {
            // near the separatrix the moduli are mixed by their distances from 1
            let complement = (p.one_minus_k.is_some() || q.one_minus_k.is_some()).then(|| {
                let c = |e: &ElasticaParams| e.one_minus_k.unwrap_or(1.0 - e.k);
                lerp(c(&p), c(&q), w)
            });
            let shape = ElasticaParams {
                family: p.family,
                k: complement.map_or(lerp(p.k, q.k, w), |c| 1.0 - c),
                s0: lerp(p.s0, q.s0, w),
                l: lerp(p.l, q.l, w),
                scale: 1.0,
                phi: 0.0,
                x0: 0.0,
                y0: 0.0,
                one_minus_k: complement,
            };
            Segment::Elastica(shape).with_ends(p0, p1)
        }
        (Segment::Line { .. }, Segment::Line { .. }) => Some(Segment::Line {
            x0: p0[0],
            y0: p0[1],
            phi: dir,
            length: chord,
        }),
        (
            Segment::Arc {
                curvature: ca,
                length: la,
                ..
            },
            Segment::Arc {
                curvature: cb,
                length: lb,
                ..
            },
        ) => {
            // turning angle θ; the arc over the chord turning by θ has length c·(θ/2)/sin(θ/2)
            let theta = lerp(ca * la, cb * lb, w);
            let half = 0.5 * theta;
            if !(half.abs() < std::f64::consts::PI) {
                return None;
            }
            let sinc = if half.abs() < 1e-8 {
                1.0
            } else {
                half.sin() / half
            };
            let length = chord / sinc;
            Some(Segment::Arc {
                x0: p0[0],
                y0: p0[1],
                phi: dir - half,
                curvature: if length > 0.0 { theta / length } else { 0.0 },
                length,
            })
        }
        _ => None,
    }
}

/// One held end of the blade in 3D.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct EndPose {
    /// Position.
    pub position: [f64; 3],
    /// Unit tangent of the blade there, pointing from the first end to the second.
    pub tangent: [f64; 3],
    /// Tool orientation `[w, x, y, z]`: x-axis = `tangent`, z-axis = the plane normal.
    pub rotation: [f64; 4],
}

/// Stations of a pose's planned shape ([`BladePose::shape`]): every sixteenth of the
/// blade, both ends included.
pub const SHAPE_STATIONS: usize = 17;

/// A blade pose: the cutting plane's normal, both held ends and the shape the blade is
/// planned to take between them.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct BladePose {
    /// Unit normal of the cutting plane.
    pub plane_normal: [f64; 3],
    /// The two ends, the blade's start (t = 0) first.
    pub ends: [EndPose; 2],
    /// The planned shape: the blade's tangent angle against its chord (from the first end
    /// to the second), turning positive about `plane_normal`, at [`SHAPE_STATIONS`]
    /// equally spaced stations along it (radians, continuous along the blade). The same
    /// held ends often allow several equilibria; this tells which one the pose means.
    pub shape: [f64; SHAPE_STATIONS],
}

fn arr3(v: &Vector3<f64>) -> [f64; 3] {
    [v.x, v.y, v.z]
}

/// The unit quaternion `[w, x, y, z]` of the frame with axes `x`, `z × x`, `z` (`x ⟂ z`,
/// both unit), with `w ≥ 0` (ties broken by the first non-zero component positive) so the
/// same orientation always prints the same numbers.
pub fn frame_quaternion(x: &Vector3<f64>, z: &Vector3<f64>) -> [f64; 4] {
    let y = z.cross(x);
    let m = Matrix3::from_columns(&[*x, y, *z]);
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m));
    let c = q.as_ref().coords; // (x, y, z, w)
    let mut out = [c.w, c.x, c.y, c.z];
    let first = out.iter().copied().find(|v| *v != 0.0).unwrap_or(1.0);
    if out[0] < 0.0 || (out[0] == 0.0 && first < 0.0) {
        out.iter_mut().for_each(|v| *v = -*v);
    }
    out
}

/// The 3D pose of `blade` (in plane coordinates of `frame`) on the plane at `offset`.
///
/// ```
/// use elastica::sweep::{blade_pose, rotate};
/// use elastica::{extend_to_blade, BladeParams, Segment};
/// use geom::slice::PlaneFrame;
/// use nalgebra::Vector3;
/// // cutting along +x: the planes' coordinates are (y, z)
/// let frame = PlaneFrame::from_direction(Vector3::x())?;
/// let arc = Segment::Arc { x0: 0.0, y0: 0.0, phi: 0.0, curvature: 0.001, length: 500.0 };
/// let blade = extend_to_blade(&arc, &BladeParams::new(1000.0))?;
/// let pose = blade_pose(&frame, 250.0, &blade);
/// assert_eq!(pose.plane_normal, [1.0, 0.0, 0.0]);
/// // the blade, an arc turning 1 rad: its shape against the chord runs from −0.5 to 0.5
/// // (or back, as the plane's coordinates turn about its normal)
/// assert!((pose.shape[0].abs() - 0.5).abs() < 1e-12 && (pose.shape[16] + pose.shape[0]).abs() < 1e-12);
/// assert!(pose.shape[8].abs() < 1e-12);
/// for end in &pose.ends {
///     assert_eq!(end.position[0], 250.0); // on the plane x = 250
///     // the tool's z axis is the plane normal, its x axis the blade's tangent
///     let z = rotate(&end.rotation, &[0.0, 0.0, 1.0]);
///     let x = rotate(&end.rotation, &[1.0, 0.0, 0.0]);
///     assert!((Vector3::from(z) - Vector3::x()).norm() < 1e-12);
///     assert!((Vector3::from(x) - Vector3::from(end.tangent)).norm() < 1e-12);
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn blade_pose(frame: &PlaneFrame, offset: f64, blade: &Blade) -> BladePose {
    let n = frame.normal;
    let end = |i: usize| {
        let e = &blade.ends[i];
        let p = frame.to_world(offset, &Vector2::new(e.position[0], e.position[1]));
        let t = frame.u * e.tangent[0] + frame.v * e.tangent[1];
        let t = t / t.norm();
        EndPose {
            position: arr3(&p),
            tangent: arr3(&t),
            rotation: frame_quaternion(&t, &n),
        }
    };
    let ends = [end(0), end(1)];
    BladePose {
        plane_normal: arr3(&n),
        shape: planned_shape(frame, blade, &ends),
        ends,
    }
}

/// The blade's tangent angle against its chord at [`SHAPE_STATIONS`] stations, turning
/// positive about the plane's normal.
fn planned_shape(frame: &PlaneFrame, blade: &Blade, ends: &[EndPose; 2]) -> [f64; SHAPE_STATIONS] {
    let n = frame.normal;
    let chord = Vector3::from(ends[1].position) - Vector3::from(ends[0].position);
    let x = if chord.norm() > 0.0 {
        chord.normalize()
    } else {
        frame.u
    };
    let y = n.cross(&x);
    let t0 = Vector3::from(ends[0].tangent);
    let start = t0.dot(&y).atan2(t0.dot(&x));
    // the plane's coordinates turn with or against the normal
    let sign = if frame.u.cross(&frame.v).dot(&n) < 0.0 {
        -1.0
    } else {
        1.0
    };
    let mut out = [start; SHAPE_STATIONS];
    if let Ok(eval) = blade.segment.evaluator() {
        let a0 = eval.eval(0.0).angle;
        for (k, v) in out.iter_mut().enumerate() {
            let a = eval.eval(k as f64 / (SHAPE_STATIONS - 1) as f64).angle;
            *v = start + sign * (a - a0);
        }
    }
    out
}

/// Rotates `v` by the unit quaternion `q = [w, x, y, z]`.
pub fn rotate(q: &[f64; 4], v: &[f64; 3]) -> [f64; 3] {
    let uq = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
    arr3(&(uq * Vector3::new(v[0], v[1], v[2])))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::blade::{extend_to_blade, BladeParams};
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn quaternion_axes_are_the_frame(a in -3.0f64..3.0, b in -1.5f64..1.5, c in -3.0f64..3.0) {
            let z = Vector3::new(b.cos() * a.cos(), b.cos() * a.sin(), b.sin());
            let helper = if z.x.abs() < 0.9 { Vector3::x() } else { Vector3::y() };
            let x0 = helper - z * z.dot(&helper);
            let x0 = x0.normalize();
            let x = x0 * c.cos() + z.cross(&x0) * c.sin();
            let q = frame_quaternion(&x, &z);
            let norm: f64 = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            prop_assert!((norm - 1.0).abs() < 1e-12);
            prop_assert!(q[0] >= 0.0);
            let rx = rotate(&q, &[1.0, 0.0, 0.0]);
            let rz = rotate(&q, &[0.0, 0.0, 1.0]);
            prop_assert!((Vector3::from(rx) - x).norm() < 1e-12);
            prop_assert!((Vector3::from(rz) - z).norm() < 1e-12);
        }
    }

    #[test]
    fn pose_of_an_arc_blade_in_the_default_frame() {
        // default cutting direction +x: plane coordinates are (y, z)
        let frame = PlaneFrame::from_direction(Vector3::x()).unwrap();
        let arc = Segment::Arc {
            x0: 0.0,
            y0: 0.0,
            phi: 0.0,
            curvature: 0.001,
            length: 500.0,
        };
        let blade = extend_to_blade(&arc, &BladeParams::new(1000.0)).unwrap();
        let pose = blade_pose(&frame, 250.0, &blade);
        assert_eq!(pose.plane_normal, [1.0, 0.0, 0.0]);
        for e in &pose.ends {
            assert_eq!(e.position[0], 250.0);
            let z = rotate(&e.rotation, &[0.0, 0.0, 1.0]);
            assert!((Vector3::from(z) - Vector3::x()).norm() < 1e-12);
            let x = rotate(&e.rotation, &[1.0, 0.0, 0.0]);
            assert!((Vector3::from(x) - Vector3::from(e.tangent)).norm() < 1e-12);
        }
        // the arc turns by κ·L = 1 rad over the whole blade, symmetric about the middle
        let [t0, t1] = [pose.ends[0].tangent, pose.ends[1].tangent];
        assert!((t0[1] * t1[1] + t0[2] * t1[2] - 1f64.cos()).abs() < 1e-12);
    }

    #[test]
    fn interpolation_needs_one_kind_and_unwraps_the_angle() {
        let l = Segment::Line {
            x0: 0.0,
            y0: 0.0,
            phi: 3.1,
            length: 1.0,
        };
        let m = Segment::Line {
            x0: 0.0,
            y0: 0.0,
            phi: -3.1,
            length: 1.0,
        };
        let Some(Segment::Line { phi, .. }) = interpolate(&l, &m, 0.5) else {
            panic!()
        };
        assert!((phi - std::f64::consts::PI).abs() < 1e-12);
        let a = Segment::Arc {
            x0: 0.0,
            y0: 0.0,
            phi: 0.0,
            curvature: 0.1,
            length: 1.0,
        };
        assert!(interpolate(&l, &a, 0.5).is_none());
    }
}
