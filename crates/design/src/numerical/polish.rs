//! The end game of the numerical road: a primal active-set Newton method.
//!
//! `clarabel` stops on its objective gap, and along the energy's nearly flat valley a gap
//! of 10⁻¹¹ still leaves the step uncertain by 10⁻³ ε. So once the SQP has found the
//! neighbourhood, the constraints that hold with equality are fixed (an active disc's
//! point moves on its circle, by angle; an active segment's point stays at its end) and
//! Newton's method on the KKT equations of what remains converges on the exact gradient —
//! quadratically, to rounding. A Newton step that would leave a disc or segment is cut
//! where it first meets it, and that constraint joins the active set; an active
//! constraint whose multiplier has the wrong sign leaves it. Every round is bounded.

use nalgebra::{DMatrix, DVector};

use super::sqp::{Freedom, Problem};

/// How one movable control point stands in the active set.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Slot {
    /// A segment's point strictly inside.
    LineFree,
    /// A segment's point held at its end (±1).
    LineAt(f64),
    /// A disc's point strictly inside.
    DiscFree,
    /// A disc's point on its circle.
    DiscEdge,
}

/// Most active-set changes.
const MAX_ROUNDS: usize = 60;
/// Most Newton steps per round.
const NEWTON_STEPS: usize = 40;
/// Newton has converged when its step is below this (units of ε or radians); rounding
/// leaves steps of 10⁻¹¹–10⁻¹⁰ at the solution.
const NEWTON_TOL: f64 = 1e-8;

struct Active<'a> {
    pb: &'a Problem<'a>,
    slots: Vec<Slot>,
}

impl Active<'_> {
    fn z(&self, w: &[f64]) -> Vec<f64> {
        let (mut z, mut j) = (Vec::new(), 0);
        for s in &self.slots {
            match *s {
                Slot::LineFree => {
                    z.push(w[j]);
                    j += 1;
                }
                Slot::LineAt(v) => z.push(v),
                Slot::DiscFree => {
                    z.extend([w[j], w[j + 1]]);
                    j += 2;
                }
                Slot::DiscEdge => {
                    z.extend([w[j].cos(), w[j].sin()]);
                    j += 1;
                }
            }
        }
        z
    }

    fn w(&self, z: &[f64]) -> Vec<f64> {
        let (mut w, mut k) = (Vec::new(), 0);
        for s in &self.slots {
            match s {
                Slot::LineFree => w.push(z[k]),
                Slot::LineAt(_) => {}
                Slot::DiscFree => w.extend([z[k], z[k + 1]]),
                Slot::DiscEdge => w.push(z[k + 1].atan2(z[k])),
            }
            k += if matches!(s, Slot::DiscFree | Slot::DiscEdge) {
                2
            } else {
                1
            };
        }
        w
    }

    /// A gradient in z pulled back to w.
    fn pull(&self, w: &[f64], gz: &[f64]) -> Vec<f64> {
        let (mut out, mut j, mut k) = (Vec::new(), 0, 0);
        for s in &self.slots {
            match s {
                Slot::LineFree => {
                    out.push(gz[k]);
                    j += 1;
                    k += 1;
                }
                Slot::LineAt(_) => k += 1,
                Slot::DiscFree => {
                    out.extend([gz[k], gz[k + 1]]);
                    j += 2;
                    k += 2;
                }
                Slot::DiscEdge => {
                    out.push(-gz[k] * w[j].sin() + gz[k + 1] * w[j].cos());
                    j += 1;
                    k += 2;
                }
            }
        }
        out
    }

    /// (f, c, ∇f, ∇c) in w.
    fn eval(&self, w: &[f64], tie: f64) -> (f64, f64, Vec<f64>, Vec<f64>) {
        let e = self.pb.eval(&self.z(w), tie);
        let (gf, gc) = (self.pull(w, &e.gf), self.pull(w, &e.gc));
        (e.f, e.c, gf, gc)
    }

    /// Newton on the KKT equations from `w`; `None` if a system is singular or the steps
    /// do not settle.
    fn newton(&self, mut w: Vec<f64>, nu: &mut f64, tie: f64) -> Option<Vec<f64>> {
        let m = w.len();
        let fix = self.pb.fix_length;
        let h = 1e-5 / self.pb.eps;
        for _ in 0..NEWTON_STEPS {
            let (_, c, gf, gc) = self.eval(&w, tie);
            let n = m + usize::from(fix);
            let mut k = DMatrix::<f64>::zeros(n, n);
            let mut ww = w.clone();
            for j in 0..m {
                ww[j] = w[j] + h;
                let (_, _, fu, cu) = self.eval(&ww, tie);
                ww[j] = w[j] - h;
                let (_, _, fd, cd) = self.eval(&ww, tie);
                ww[j] = w[j];
                for i in 0..m {
                    k[(i, j)] = ((fu[i] - fd[i]) + *nu * (cu[i] - cd[i])) / (2.0 * h);
                }
            }
            let sym = 0.5 * (&k + k.transpose());
            k = sym;
            let mut rhs = DVector::<f64>::zeros(n);
            for i in 0..m {
                rhs[i] = -gf[i];
            }
            if fix {
                for i in 0..m {
                    k[(m, i)] = gc[i];
                    k[(i, m)] = gc[i];
                }
                rhs[m] = -c;
            }
            let sol = k.lu().solve(&rhs)?;
            if sol.iter().any(|v| !v.is_finite()) {
                return None;
            }
            let step = (0..m).map(|i| sol[i].abs()).fold(0.0, f64::max);
            for i in 0..m {
                w[i] += sol[i];
            }
            if fix {
                *nu = sol[m];
            }
            if step < NEWTON_TOL {
                return Some(w);
            }
        }
        None
    }
}

/// Polish `z` (the SQP's point) to the exact KKT point with tie-break `tie`; `None` when
/// the active-set method does not settle within its bounds.
pub(super) fn polish(pb: &Problem, z: &[f64], nu0: f64, tie: f64) -> Option<Vec<f64>> {
    let mut slots = Vec::new();
    let mut k = 0;
    for f in &pb.freedom {
        match f {
            Freedom::Fixed => {}
            Freedom::Line(_) => {
                slots.push(if z[k].abs() >= 1.0 - 1e-6 {
                    Slot::LineAt(z[k].signum())
                } else {
                    Slot::LineFree
                });
                k += 1;
            }
            Freedom::Disc => {
                slots.push(if z[k].hypot(z[k + 1]) >= 1.0 - 1e-6 {
                    Slot::DiscEdge
                } else {
                    Slot::DiscFree
                });
                k += 2;
            }
        }
    }
    let mut act = Active { pb, slots };
    let mut z = z.to_vec();
    let mut nu = nu0;
    for _ in 0..(2 * act.slots.len() + 4).min(MAX_ROUNDS) {
        let w0 = act.w(&z);
        let z0 = act.z(&w0);
        let w1 = act.newton(w0.clone(), &mut nu, tie)?;
        let z1 = act.z(&w1);
        // the first free point the step carries out of its disc or segment
        let mut hit: Option<(f64, usize)> = None;
        let mut k = 0;
        for (si, s) in act.slots.iter().enumerate() {
            let alpha = match s {
                Slot::LineFree if z1[k].abs() > 1.0 => {
                    let target = z1[k].signum();
                    Some(((target - z0[k]) / (z1[k] - z0[k])).clamp(0.0, 1.0))
                }
                Slot::DiscFree if z1[k].hypot(z1[k + 1]) > 1.0 => {
                    // |a + α d| = 1 for the α in [0, 1]
                    let (a, d) = ([z0[k], z0[k + 1]], [z1[k] - z0[k], z1[k + 1] - z0[k + 1]]);
                    let (qa, qb, qc) = (
                        d[0] * d[0] + d[1] * d[1],
                        2.0 * (a[0] * d[0] + a[1] * d[1]),
                        a[0] * a[0] + a[1] * a[1] - 1.0,
                    );
                    let disc = (qb * qb - 4.0 * qa * qc).max(0.0);
                    Some(((-qb + disc.sqrt()) / (2.0 * qa)).clamp(0.0, 1.0))
                }
                _ => None,
            };
            if let Some(a) = alpha {
                if hit.is_none_or(|(b, _)| a < b) {
                    hit = Some((a, si));
                }
            }
            k += if matches!(s, Slot::DiscFree | Slot::DiscEdge) {
                2
            } else {
                1
            };
        }
        if let Some((alpha, si)) = hit {
            let w: Vec<f64> = w0
                .iter()
                .zip(&w1)
                .map(|(a, b)| a + alpha * (b - a))
                .collect();
            z = act.z(&w);
            let k = zi(&act.slots, si);
            act.slots[si] = match act.slots[si] {
                Slot::LineFree => {
                    z[k] = z[k].signum();
                    Slot::LineAt(z[k])
                }
                _ => {
                    let r = z[k].hypot(z[k + 1]);
                    z[k] /= r;
                    z[k + 1] /= r;
                    Slot::DiscEdge
                }
            };
            continue;
        }
        z = z1;
        // multipliers of the active constraints: −∂L/∂(outward)
        let e = pb.eval(&z, tie);
        let gl: Vec<f64> = e.gf.iter().zip(&e.gc).map(|(a, b)| a + nu * b).collect();
        let scale = gl.iter().fold(1e-300, |a: f64, v| a.max(v.abs()));
        let mut worst: Option<(f64, usize)> = None;
        for (si, s) in act.slots.iter().enumerate() {
            let k = zi(&act.slots, si);
            let mu = match s {
                Slot::LineAt(v) => -v * gl[k],
                Slot::DiscEdge => -(gl[k] * z[k] + gl[k + 1] * z[k + 1]),
                _ => continue,
            };
            if mu < -1e-9 * scale && worst.is_none_or(|(b, _)| mu < b) {
                worst = Some((mu, si));
            }
        }
        let Some((_, si)) = worst else {
            return Some(z);
        };
        act.slots[si] = match act.slots[si] {
            Slot::LineAt(_) => Slot::LineFree,
            _ => Slot::DiscFree,
        };
    }
    None
}

/// Where slot `si`'s offsets start in z.
fn zi(slots: &[Slot], si: usize) -> usize {
    slots[..si]
        .iter()
        .map(|s| {
            if matches!(s, Slot::DiscFree | Slot::DiscEdge) {
                2
            } else {
                1
            }
        })
        .sum()
}
