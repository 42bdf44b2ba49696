//! The closed-form kinematics of an ortho-parallel arm with a spherical wrist (Brandstötter,
//! Angerer and Hofbaur 2014, "OPW"), in the paper's joint angles.
//!
//! Our own: `rs-opw-kinematics` 3 was tried first, but it depends on `anyhow`, whose build
//! script's compiler probe left a failed target query in a fresh build's cache and broke
//! the next `cargo` command of CI. The solution below is checked against forward
//! kinematics and an independent rebuild of the chain (`tests/kinematics.rs`).
//!
//! The paper's frame: axis 1 turns the arm plane about z; in that plane the wrist centre
//! is at `x = a1 + c2 sin q2 + k sin(q2 + q3 + ψ3)`, `z = c1 + c2 cos q2 + k cos(q2 + q3 +
//! ψ3)` with `k = √(a2² + c3²)`, `ψ3 = atan2(a2, c3)`, and `y = b`; the forearm's frame is
//! `Rz(q1) Ry(q2 + q3)`, the wrist `Rz(q4) Ry(q5) Rz(q6)`, the flange `c4` along the
//! wrist's z.

use nalgebra::{Matrix3, Rotation3, Vector3};

use crate::model::Opw;

/// Paper joint angles.
pub type Angles = [f64; 6];

/// The flange's rotation and position for paper angles `q`.
///
/// ```
/// use cell::opw::forward;
/// use cell::RobotModel;
/// // the paper's zero: the arm straight up, the flange on top
/// let o = RobotModel::irb1600_6_145().opw;
/// let (r, p) = forward(&o, &[0.0; 6]);
/// assert!((p.x - o.a1).abs() < 1e-9 && p.y.abs() < 1e-9);
/// assert!((p.z - (o.c1 + o.c2 + o.c3 + o.c4)).abs() < 1e-9);
/// assert!((r.matrix() - nalgebra::Matrix3::identity()).norm() < 1e-12);
/// ```
pub fn forward(o: &Opw, q: &Angles) -> (Rotation3<f64>, Vector3<f64>) {
    let (psi3, k) = (o.a2.atan2(o.c3), o.a2.hypot(o.c3));
    let x = o.a1 + o.c2 * q[1].sin() + k * (q[1] + q[2] + psi3).sin();
    let z = o.c1 + o.c2 * q[1].cos() + k * (q[1] + q[2] + psi3).cos();
    let (s1, c1) = q[0].sin_cos();
    let wrist = Vector3::new(x * c1 - o.b * s1, x * s1 + o.b * c1, z);
    let r = arm(q[0], q[1] + q[2]) * wrist_rotation(q[3], q[4], q[5]);
    let flange = wrist + r * Vector3::new(0.0, 0.0, o.c4);
    (r, flange)
}

/// The forearm's frame: `Rz(q1) Ry(q23)`.
fn arm(q1: f64, q23: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), q1)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), q23)
}

/// The wrist: `Rz(q4) Ry(q5) Rz(q6)`.
fn wrist_rotation(q4: f64, q5: f64, q6: f64) -> Rotation3<f64> {
    Rotation3::from_axis_angle(&Vector3::z_axis(), q4)
        * Rotation3::from_axis_angle(&Vector3::y_axis(), q5)
        * Rotation3::from_axis_angle(&Vector3::z_axis(), q6)
}

/// `acos` of a cosine that rounding may have pushed just past ±1 (`None` when it is
/// truly beyond: out of reach).
fn acos(c: f64) -> Option<f64> {
    const SLACK: f64 = 1e-12;
    (c.abs() <= 1.0 + SLACK).then(|| c.clamp(-1.0, 1.0).acos())
}

/// Every candidate of paper angles for the flange pose `(r, p)`: the two turns of axis 1,
/// the two elbows of each, the two wrists of each (up to 8; fewer out of reach).
/// `hint` (paper angles) fixes what a singularity leaves free: axis 1 with the wrist centre
/// on axis 1, axis 4 with axis 5 at 0. Candidates are not verified: the caller checks each
/// by [`forward`].
///
/// ```
/// use cell::opw::{forward, inverse};
/// use cell::RobotModel;
/// let o = RobotModel::irb2600_12_165().opw;
/// let q = [0.2, 0.3, -0.4, 0.5, 0.6, 0.7];
/// let (r, p) = forward(&o, &q);
/// let candidates = inverse(&o, &r, &p, &[0.0; 6]);
/// assert_eq!(candidates.len(), 8); // two shoulders, two elbows, two wrists
/// // one of them is q (the candidates are unverified: the caller checks each)
/// let found = candidates.iter().find(|c| c.iter().zip(&q).all(|(a, b)| (a - b).abs() < 1e-9));
/// let (rc, pc) = forward(&o, found.expect("q among the candidates"));
/// assert!((pc - p).norm() < 1e-6 && rc.angle_to(&r) < 1e-9);
/// ```
pub fn inverse(o: &Opw, r: &Rotation3<f64>, p: &Vector3<f64>, hint: &Angles) -> Vec<Angles> {
    let m: Matrix3<f64> = *r.matrix();
    let c = p - m.column(2) * o.c4;
    let (psi3, k2) = (o.a2.atan2(o.c3), o.a2 * o.a2 + o.c3 * o.c3);
    let radial2 = c.x * c.x + c.y * c.y - o.b * o.b;
    if radial2 < -1e-9 * (1.0 + o.b * o.b) {
        return Vec::new();
    }
    let n = radial2.max(0.0).sqrt();
    // axis 1: towards the wrist centre, or turned away (the arm reaching back over axis 1)
    let pi = std::f64::consts::PI;
    let (towards, offset) = if c.x.hypot(c.y) < 1e-12 {
        (hint[0], 0.0)
    } else {
        (c.y.atan2(c.x), o.b.atan2(n))
    };
    let mut out = Vec::new();
    for (q1, reach) in [
        (towards - offset, n - o.a1),
        (towards + offset - pi, -n - o.a1),
    ] {
        // the wrist centre in the arm plane, from axis 2
        let (x, z) = (reach, c.z - o.c1);
        let s2 = x * x + z * z;
        let s = s2.sqrt();
        // law of cosines in the triangle axis 2 – axis 3 – wrist centre
        let (Some(at2), Some(at3)) = (
            acos((s2 + o.c2 * o.c2 - k2) / (2.0 * s * o.c2)),
            acos((s2 - o.c2 * o.c2 - k2) / (2.0 * o.c2 * k2.sqrt())),
        ) else {
            continue;
        };
        let toward = x.atan2(z);
        for (q2, q3) in [(toward - at2, at3 - psi3), (toward + at2, -at3 - psi3)] {
            let r0c = arm(q1, q2 + q3);
            let w: Matrix3<f64> = *(r0c.inverse() * r).matrix();
            let sin5 = w[(0, 2)].hypot(w[(1, 2)]);
            let q5 = sin5.atan2(w[(2, 2)]);
            if sin5 < 1e-12 {
                // axis 5 at 0 (only q4 + q6 counts) or at π (only q4 − q6): axis 4 as hinted
                let q4 = hint[3];
                if w[(2, 2)] > 0.0 {
                    out.push([q1, q2, q3, q4, 0.0, w[(1, 0)].atan2(w[(0, 0)]) - q4]);
                } else {
                    out.push([q1, q2, q3, q4, pi, q4 - (-w[(1, 0)]).atan2(-w[(0, 0)])]);
                }
                continue;
            }
            let q4 = w[(1, 2)].atan2(w[(0, 2)]);
            let q6 = w[(2, 1)].atan2(-w[(2, 0)]);
            out.push([q1, q2, q3, q4, q5, q6]);
            out.push([q1, q2, q3, q4 + pi, -q5, q6 - pi]);
        }
    }
    out
}
