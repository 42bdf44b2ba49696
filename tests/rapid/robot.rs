//! What the replay needs besides the modules, rebuilt independently of hotcut's planner:
//! a robot from the report's OPW parameters with its forward kinematics and ABB's
//! configuration data, and the blade's shape from its two held ends (the discrete
//! elastica of the length between them).

use elastica::discrete::{discrete_elastica, DiscreteParams};
use nalgebra::{Isometry3, Point3, Quaternion, Rotation3, Translation3, UnitQuaternion, Vector3};

/// A robot as the report states it.
#[derive(Debug, Clone)]
pub struct Robot {
    /// `[a1, a2, b, c1, c2, c3, c4]`, mm.
    pub opw: [f64; 7],
    /// Offsets, radians.
    pub offsets: [f64; 6],
    /// Signs.
    pub signs: [f64; 6],
    /// Limits, degrees.
    pub limits: [(f64, f64); 6],
    /// Base frame in the world.
    pub base: Isometry3<f64>,
}

/// A frame of the report: `origin_mm` and `rotation` `[w, x, y, z]`.
pub fn frame(v: &serde_json::Value) -> Isometry3<f64> {
    let o: Vec<f64> = v["origin_mm"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    let q: Vec<f64> = v["rotation"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    Isometry3::from_parts(
        Translation3::new(o[0], o[1], o[2]),
        UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3])),
    )
}

fn six(v: &serde_json::Value) -> [f64; 6] {
    std::array::from_fn(|i| v[i].as_f64().unwrap())
}

impl Robot {
    /// The robot of `report["cell"]["robots"][i]`.
    pub fn from_report(r: &serde_json::Value) -> Robot {
        let opw = r["opw_mm"].as_array().unwrap();
        Robot {
            opw: std::array::from_fn(|i| opw[i].as_f64().unwrap()),
            offsets: six(&r["offsets_deg"]).map(f64::to_radians),
            signs: six(&r["signs"]),
            limits: std::array::from_fn(|i| {
                let l = &r["limits_deg"][i];
                (l[0].as_f64().unwrap(), l[1].as_f64().unwrap())
            }),
            base: frame(&r["base"]),
        }
    }

    /// The paper's angles of joints in degrees.
    fn paper(&self, j: &[f64; 6]) -> [f64; 6] {
        std::array::from_fn(|i| j[i].to_radians() * self.signs[i] - self.offsets[i])
    }

    /// The flange in the world, and the wrist centre in the base frame: the arm plane
    /// turned by axis 1, the wrist from axes 2 and 3, the wrist's Z-Y-Z turns.
    pub fn flange(&self, j: &[f64; 6]) -> (Isometry3<f64>, Vector3<f64>) {
        let [a1, a2, b, c1, c2, c3, c4] = self.opw;
        let q = self.paper(j);
        let (psi3, k) = (a2.atan2(c3), a2.hypot(c3));
        let x = a1 + c2 * q[1].sin() + k * (q[1] + q[2] + psi3).sin();
        let z = c1 + c2 * q[1].cos() + k * (q[1] + q[2] + psi3).cos();
        let (s1, co1) = q[0].sin_cos();
        let wrist = Vector3::new(x * co1 - b * s1, x * s1 + b * co1, z);
        let r = Rotation3::from_axis_angle(&Vector3::z_axis(), q[0])
            * Rotation3::from_axis_angle(&Vector3::y_axis(), q[1] + q[2])
            * Rotation3::from_axis_angle(&Vector3::z_axis(), q[3])
            * Rotation3::from_axis_angle(&Vector3::y_axis(), q[4])
            * Rotation3::from_axis_angle(&Vector3::z_axis(), q[5]);
        let flange = Isometry3::from_parts(
            Translation3::from(wrist + r * Vector3::new(0.0, 0.0, c4)),
            UnitQuaternion::from_rotation_matrix(&r),
        );
        (self.base * flange, wrist)
    }

    /// ABB's `[cf1, cf4, cf6, cfx]` of joints (degrees): quarter turns of axes 1, 4, 6; cfx = 4·(wrist centre behind axis 1) + 2·(behind the lower arm)
    /// + (axis 5 negative).
    pub fn conf(&self, j: &[f64; 6]) -> [i32; 4] {
        let [a1, _, _, c1, _, _, _] = self.opw;
        let q = self.paper(j);
        let (_, wrist) = self.flange(j);
        let forward = Vector3::new(q[0].cos(), q[0].sin(), 0.0);
        let along = wrist.dot(&forward);
        // lower arm from axis 2 (a1 forward, c1 up) along (sin q2, cos q2)
        let (u, w) = ((q[1].sin(), q[1].cos()), (along - a1, wrist.z - c1));
        let behind_arm = u.0 * w.1 - u.1 * w.0 > 0.0;
        // the RAPID manual: int(a / 90°) for a ≥ 0, int(a / 90° − 1) below (int truncates)
        let quarter = |a: f64| {
            if a >= 0.0 {
                (a / 90.0).trunc() as i32
            } else {
                (a / 90.0 - 1.0).trunc() as i32
            }
        };
        let cfx = 4 * i32::from(along < 0.0) + 2 * i32::from(behind_arm) + i32::from(j[4] < 0.0);
        [quarter(j[0]), quarter(j[3]), quarter(j[5]), cfx]
    }
}

/// The blade of `length` held by two TCP frames (x along the blade, z the plane's
/// normal): points along it, in the world.
pub fn blade(ends: [&Isometry3<f64>; 2], length: f64) -> Result<Vec<Vector3<f64>>, String> {
    blade_turned(ends, length, 32, 0.0)
}

/// The blade of `length` held by two TCP frames as [`blade`] takes it, but on `segments`
/// chords and with its total turning `turns` whole turns off the shortest (a held tangent
/// says nothing of whole turns: a blade far longer than its chord may loop).
pub fn blade_turned(
    ends: [&Isometry3<f64>; 2],
    length: f64,
    segments: usize,
    turns: f64,
) -> Result<Vec<Vector3<f64>>, String> {
    let (p0, p1) = (ends[0].translation.vector, ends[1].translation.vector);
    let chord = (p1 - p0).norm();
    if !(chord < length) {
        return Err(format!("ends {chord:.3} mm apart, blade {length:.3} mm"));
    }
    let x = (p1 - p0) / chord;
    let n = ends[0].rotation * Vector3::z();
    let z = (n - x * n.dot(&x)).normalize();
    let y = z.cross(&x);
    let angle = |e: usize| {
        let t = ends[e].rotation * Vector3::x();
        t.dot(&y).atan2(t.dot(&x))
    };
    let (a0, a1) = (angle(0), angle(1));
    let tau = std::f64::consts::TAU;
    let turn = (a1 - a0 + std::f64::consts::PI).rem_euclid(tau) - std::f64::consts::PI;
    let d = discrete_elastica(&DiscreteParams {
        segments,
        start: [0.0, 0.0],
        start_angle: a0,
        end: [chord, 0.0],
        end_angle: a0 + turn + turns * tau,
        length,
        max_iterations: 200,
    })
    .map_err(|e| e.to_string())?;
    Ok(d.points.iter().map(|v| p0 + x * v[0] + y * v[1]).collect())
}

/// How deep `p` (world) is inside the box `[0, size]` of frame `f` (negative: outside).
pub fn depth(f: &Isometry3<f64>, size: &[f64; 3], p: &Vector3<f64>) -> f64 {
    let l = f.inverse() * Point3::from(*p);
    (0..3)
        .map(|i| l[i].min(size[i] - l[i]))
        .fold(f64::INFINITY, f64::min)
}

/// Whether the plane of the tool frame `end` (its z the normal) passes through the box
/// `[0, size]` of frame `f`.
pub fn crosses(f: &Isometry3<f64>, size: &[f64; 3], end: &Isometry3<f64>) -> bool {
    let n = end.rotation * Vector3::z();
    let at = end.translation.vector;
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for corner in 0..8 {
        let c = Vector3::from_fn(|i, _| if corner & (1 << i) != 0 { size[i] } else { 0.0 });
        let d = ((f * Point3::from(c)).coords - at).dot(&n);
        lo = lo.min(d);
        hi = hi.max(d);
    }
    lo < 0.0 && hi > 0.0
}
