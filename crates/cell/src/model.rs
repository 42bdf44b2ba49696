//! Robot models: OPW kinematic parameters (Brandstötter, Angerer, Hofbaur 2014) and joint
//! limits, with the built-in ABB robots of the hot-blade cells. The sources of every
//! number are in `docs/robot-cell.md`.

use crate::error::{CellError, Result};

/// OPW parameters of a 6-axis arm with an ortho-parallel base and a spherical wrist,
/// millimetres and radians. The paper's zero has the arm straight up; `offsets` bring it
/// to the maker's zero (ABB: `[0, 0, −π/2, 0, 0, 0]`), `signs` flip axes that turn the
/// other way.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
#[cfg_attr(feature = "serde", serde(deny_unknown_fields))]
pub struct Opw {
    /// Axis 1 to axis 2 along the arm, mm.
    pub a1: f64,
    /// Elbow offset, perpendicular to the forearm, mm (negative on ABB arms).
    pub a2: f64,
    /// Lateral offset of axis 2, mm.
    pub b: f64,
    /// Height of axis 2 above the base, mm.
    pub c1: f64,
    /// Upper arm: axis 2 to axis 3, mm.
    pub c2: f64,
    /// Forearm: axis 3 to the wrist centre, mm.
    pub c3: f64,
    /// Wrist centre to the flange, mm.
    pub c4: f64,
    /// Joint offsets from the paper's zero to the maker's, radians.
    pub offsets: [f64; 6],
    /// Direction of each joint: 1 or −1.
    pub signs: [i8; 6],
}

/// A robot: its kinematics and its joint limits.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct RobotModel {
    /// Model name, e.g. `IRB 1600-6/1.45`.
    pub name: String,
    /// Kinematic parameters.
    pub opw: Opw,
    /// `(min, max)` of each joint, radians.
    pub limits: [(f64, f64); 6],
}

/// ABB's joint offsets: axis 3's zero is the forearm horizontal.
const ABB_OFFSETS: [f64; 6] = [0.0, 0.0, -std::f64::consts::FRAC_PI_2, 0.0, 0.0, 0.0];

/// Limits in degrees to radians.
fn degrees(limits: [(f64, f64); 6]) -> [(f64, f64); 6] {
    limits.map(|(lo, hi)| (lo.to_radians(), hi.to_radians()))
}

impl RobotModel {
    /// ABB IRB 1600-6/1.45 (the Rob|Arch workshop's blade robots). Joint limits: the
    /// narrower of the published ranges where the sources disagree (axes 2 and 3).
    ///
    /// ```
    /// use cell::RobotModel;
    /// let robot = RobotModel::irb1600_6_145();
    /// assert!((robot.reach() - 1450.0).abs() < 1e-9); // its nominal reach, 1.45 m
    /// assert!(robot.check().is_ok());
    /// ```
    pub fn irb1600_6_145() -> Self {
        Self {
            name: "IRB 1600-6/1.45".into(),
            opw: Opw {
                a1: 150.0,
                a2: 0.0,
                b: 0.0,
                c1: 486.5,
                c2: 700.0,
                c3: 600.0,
                c4: 65.0,
                offsets: ABB_OFFSETS,
                signs: [1; 6],
            },
            limits: degrees([
                (-180.0, 180.0),
                (-63.0, 110.0),
                (-235.0, 55.0),
                (-200.0, 200.0),
                (-115.0, 115.0),
                (-400.0, 400.0),
            ]),
        }
    }

    /// ABB IRB 2600-12/1.65 (and -20/1.65, the same arm).
    ///
    /// ```
    /// use cell::RobotModel;
    /// let robot = RobotModel::irb2600_12_165();
    /// assert!((robot.reach() - 1650.0).abs() < 5.0); // 1.65 m, nominally
    /// assert!(robot.check().is_ok());
    /// ```
    pub fn irb2600_12_165() -> Self {
        Self {
            name: "IRB 2600-12/1.65".into(),
            opw: Opw {
                a1: 150.0,
                a2: -115.0,
                b: 0.0,
                c1: 445.0,
                c2: 700.0,
                c3: 795.0,
                c4: 85.0,
                offsets: ABB_OFFSETS,
                signs: [1; 6],
            },
            limits: degrees([
                (-180.0, 180.0),
                (-95.0, 155.0),
                (-180.0, 75.0),
                (-400.0, 400.0),
                (-120.0, 120.0),
                (-400.0, 400.0),
            ]),
        }
    }

    /// ABB IRB 4600-60/2.05.
    ///
    /// ```
    /// use cell::RobotModel;
    /// let robot = RobotModel::irb4600_60_205();
    /// assert!((robot.reach() - 2050.0).abs() < 5.0); // 2.05 m, nominally
    /// assert!(robot.check().is_ok());
    /// ```
    pub fn irb4600_60_205() -> Self {
        Self {
            name: "IRB 4600-60/2.05".into(),
            opw: Opw {
                a1: 175.0,
                a2: -175.0,
                b: 0.0,
                c1: 495.0,
                c2: 900.0,
                c3: 960.0,
                c4: 135.0,
                offsets: ABB_OFFSETS,
                signs: [1; 6],
            },
            limits: degrees([
                (-180.0, 180.0),
                (-90.0, 150.0),
                (-180.0, 75.0),
                (-400.0, 400.0),
                (-125.0, 120.0),
                (-400.0, 400.0),
            ]),
        }
    }

    /// The reach of the wrist centre from axis 2's circle: `a1 + c2 + √(a2² + c3²)`, mm
    /// (ABB's nominal reach: 1450 mm for an IRB 1600-x/1.45).
    ///
    /// ```
    /// use cell::RobotModel;
    /// let o = RobotModel::irb2600_12_165().opw;
    /// assert_eq!(RobotModel::irb2600_12_165().reach(), o.a1 + o.c2 + o.a2.hypot(o.c3));
    /// ```
    pub fn reach(&self) -> f64 {
        let o = &self.opw;
        o.a1 + o.c2 + o.a2.hypot(o.c3)
    }

    /// Checks the model: finite lengths within 20 m, positive upper arm and forearm, joint
    /// offsets within a turn, signs ±1, each limit finite with min < max within ±2 turns.
    ///
    /// ```
    /// use cell::{CellError, RobotModel};
    /// let mut robot = RobotModel::irb1600_6_145();
    /// assert!(robot.check().is_ok());
    /// robot.opw.c3 = -600.0;
    /// assert!(matches!(robot.check(), Err(CellError::InvalidModel { name: "c3", .. })));
    /// robot = RobotModel::irb1600_6_145();
    /// robot.limits[0] = (1.0, -1.0);
    /// assert!(robot.check().is_err());
    /// ```
    ///
    /// # Errors
    /// [`CellError::InvalidModel`] naming the parameter.
    pub fn check(&self) -> Result<()> {
        let bad = |name, reason: String| {
            Err(CellError::InvalidModel {
                model: self.name.clone(),
                name,
                reason,
            })
        };
        let o = &self.opw;
        let lengths = [
            ("a1", o.a1),
            ("a2", o.a2),
            ("b", o.b),
            ("c1", o.c1),
            ("c2", o.c2),
            ("c3", o.c3),
            ("c4", o.c4),
        ];
        for (name, v) in lengths {
            if !(v.is_finite() && v.abs() <= 20_000.0) {
                return bad(name, format!("{v} must be finite, within ±20 000 mm"));
            }
        }
        for (name, v) in [("c2", o.c2), ("c3", o.c3)] {
            if !(v > 0.0) {
                return bad(name, format!("{v} must be positive"));
            }
        }
        let turn = std::f64::consts::TAU;
        if !o.offsets.iter().all(|v| v.is_finite() && v.abs() <= turn) {
            return bad("offsets", format!("{:?} must be within ±2π", o.offsets));
        }
        if !o.signs.iter().all(|s| matches!(s, 1 | -1)) {
            return bad("signs", format!("{:?} must be 1 or −1", o.signs));
        }
        for (i, (lo, hi)) in self.limits.iter().enumerate() {
            let ok =
                lo.is_finite() && hi.is_finite() && lo < hi && lo.abs().max(hi.abs()) <= 2.0 * turn;
            if !ok {
                return bad(
                    "limits",
                    format!(
                        "axis {}: ({:.3}°, {:.3}°) must be finite, min < max, within ±720°",
                        i + 1,
                        lo.to_degrees(),
                        hi.to_degrees()
                    ),
                );
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn built_in_models_reach_their_nominal_reach() {
        for (m, reach) in [
            (RobotModel::irb1600_6_145(), 1450.0),
            (RobotModel::irb2600_12_165(), 1653.3),
            (RobotModel::irb4600_60_205(), 2050.9),
        ] {
            m.check().unwrap();
            assert!((m.reach() - reach).abs() < 0.5, "{}: {}", m.name, m.reach());
        }
    }

    #[test]
    fn bad_models_are_named() {
        let m = RobotModel::irb1600_6_145;
        let mut a = m();
        a.opw.c2 = 0.0;
        let mut b = m();
        b.limits[2] = (1.0, -1.0);
        let mut c = m();
        c.opw.signs[0] = 0;
        let mut d = m();
        d.opw.a1 = f64::NAN;
        for (model, field) in [(a, "c2"), (b, "limits"), (c, "signs"), (d, "a1")] {
            match model.check() {
                Err(CellError::InvalidModel { name, .. }) => assert_eq!(name, field),
                other => panic!("{field}: {other:?}"),
            }
        }
    }
}
