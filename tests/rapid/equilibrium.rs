//! The blade held by two TCP frames, as the replays rebuild it with a solver of their own
//! (not hotcut's): `N` equal segments, the equilibrium by Newton's method on the dense KKT
//! system (nalgebra's LU), the stability by the eigenvalues of the Hessian projected on
//! the constraints' null space (nalgebra's symmetric eigen-decomposition), and a move
//! followed as the controller executes it (both TCPs linearly, their orientations by
//! spherical interpolation) in fixed sub-steps, halved where Newton's method fails.

#![allow(dead_code)]

use nalgebra::{DMatrix, DVector, Isometry3, UnitQuaternion, Vector3};

/// Segments of the replay's blade along the moves.
pub const N: usize = 64;

/// The held ends in the blade's plane: chord and the end tangents' angles against it.
#[derive(Debug, Clone, Copy)]
pub struct Ends {
    pub chord: f64,
    pub angles: [f64; 2],
}

/// The plane of two tool frames: the first's z made perpendicular to the chord; the end
/// tangents (the tools' x) measured against the chord about that normal.
pub fn ends_of(p: &Isometry3<f64>, q: &Isometry3<f64>) -> Ends {
    let d = q.translation.vector - p.translation.vector;
    let chord = d.norm();
    let x = d / chord;
    let z = p.rotation * Vector3::z();
    let z = (z - x * z.dot(&x)).normalize();
    let y = z.cross(&x);
    let angle = |r: &UnitQuaternion<f64>| {
        let t = r * Vector3::x();
        t.dot(&y).atan2(t.dot(&x))
    };
    Ends {
        chord,
        angles: [angle(&p.rotation), angle(&q.rotation)],
    }
}

/// The angle `a` moved by whole turns to within half a turn of `near`.
pub fn near(a: f64, near: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    a - ((a - near) / tau).round() * tau
}

/// A discrete blade: `n` segments of directions `theta`, multipliers `lambda`.
#[derive(Debug, Clone)]
pub struct Blade {
    pub length: f64,
    pub ends: Ends,
    pub theta: DVector<f64>,
    pub lambda: [f64; 2],
}

/// The Lagrangian's gradient and constraints (size n + 2) and its Hessian blocks of a
/// blade of `length` held at `ends`: energy ½Σwα²/h with the end turns over half a
/// segment (w = 2), constraints hΣ(cos θ, sin θ) = (chord, 0).
pub fn kkt(
    length: f64,
    ends: &Ends,
    theta: &DVector<f64>,
    l: [f64; 2],
) -> (DVector<f64>, DMatrix<f64>) {
    let n = theta.len();
    let h = length / n as f64;
    let alpha = |i: usize| -> f64 {
        if i == 0 {
            theta[0] - ends.angles[0]
        } else if i == n {
            ends.angles[1] - theta[n - 1]
        } else {
            theta[i] - theta[i - 1]
        }
    };
    let w = |i: usize| if i == 0 || i == n { 2.0 } else { 1.0 };
    let mut r = DVector::zeros(n + 2);
    let mut k = DMatrix::zeros(n + 2, n + 2);
    for i in 0..n {
        let (s, c) = theta[i].sin_cos();
        r[i] = (w(i) * alpha(i) - w(i + 1) * alpha(i + 1)) / h + h * (-l[0] * s + l[1] * c);
        k[(i, i)] = (w(i) + w(i + 1)) / h - h * (l[0] * c + l[1] * s);
        if i + 1 < n {
            k[(i, i + 1)] = -1.0 / h;
            k[(i + 1, i)] = -1.0 / h;
        }
        k[(i, n)] = -h * s;
        k[(n, i)] = -h * s;
        k[(i, n + 1)] = h * c;
        k[(n + 1, i)] = h * c;
        r[n] += h * c;
        r[n + 1] += h * s;
    }
    r[n] -= ends.chord;
    (r, k)
}

/// Newton's method from `theta`, `lambda`: the equilibrium, if it converges.
pub fn solve(length: f64, ends: Ends, mut theta: DVector<f64>, mut l: [f64; 2]) -> Option<Blade> {
    let n = theta.len();
    let size = |r: &DVector<f64>| {
        let g = r.rows(0, n).amax() * length;
        let c = r.rows(n, 2).amax() / length;
        g.max(c)
    };
    let (mut r, mut k) = kkt(length, &ends, &theta, l);
    for _ in 0..30 {
        if size(&r) < 1e-10 {
            return Some(Blade {
                length,
                ends,
                theta,
                lambda: l,
            });
        }
        let step = k.clone().lu().solve(&(-&r))?;
        let mut t = 1.0;
        let mut moved = false;
        for _ in 0..20 {
            let th = &theta + step.rows(0, n) * t;
            let ll = [l[0] + t * step[n], l[1] + t * step[n + 1]];
            let (r2, k2) = kkt(length, &ends, &th, ll);
            if size(&r2) < (1.0 - 1e-4 * t) * size(&r) {
                (theta, l, r, k) = (th, ll, r2, k2);
                moved = true;
                break;
            }
            t *= 0.5;
        }
        if !moved {
            return None;
        }
    }
    None
}

impl Blade {
    /// The eigenvalues of the Hessian on the constraints' null space, over the mass `h`.
    pub fn reduced(&self) -> Vec<f64> {
        let n = self.theta.len();
        let h = self.length / n as f64;
        let (_, k) = kkt(self.length, &self.ends, &self.theta, self.lambda);
        let hess = k.view((0, 0), (n, n)).into_owned();
        // an orthonormal basis of the constraint rows, and the projector off them
        let mut q: Vec<DVector<f64>> = Vec::new();
        for row in [n, n + 1] {
            let mut v: DVector<f64> = DVector::from_fn(n, |i, _| k[(row, i)]);
            for u in &q {
                v -= u * u.dot(&v);
            }
            if v.norm() > 1e-12 {
                q.push(v.normalize());
            }
        }
        let mut p = DMatrix::<f64>::identity(n, n);
        for u in &q {
            p -= u * u.transpose();
        }
        // the constraint directions pushed far above every eigenvalue of interest
        let big = 10.0 * hess.amax() + 1.0;
        let mut m = &p * &hess * &p;
        for u in &q {
            m += u * u.transpose() * big;
        }
        let mut e: Vec<f64> = m
            .symmetric_eigen()
            .eigenvalues
            .iter()
            .map(|v| v / h)
            .collect();
        e.sort_by(f64::total_cmp);
        e.truncate(n - q.len());
        e
    }

    /// Whether the Hessian on the constraints' null space is positive definite (a
    /// Cholesky factorisation of it, the constraint directions pushed far up).
    pub fn is_stable(&self) -> bool {
        let (p, hess, q, big) = self.projected();
        let mut m = &p * &hess * &p;
        for u in &q {
            m += u * u.transpose() * big;
        }
        m.cholesky().is_some()
    }

    /// The projector off the constraint rows, the Hessian, the rows' orthonormal basis
    /// and a value above every eigenvalue of interest.
    fn projected(&self) -> (DMatrix<f64>, DMatrix<f64>, Vec<DVector<f64>>, f64) {
        let n = self.theta.len();
        let (_, k) = kkt(self.length, &self.ends, &self.theta, self.lambda);
        let hess = k.view((0, 0), (n, n)).into_owned();
        let mut q: Vec<DVector<f64>> = Vec::new();
        for row in [n, n + 1] {
            let mut v: DVector<f64> = DVector::from_fn(n, |i, _| k[(row, i)]);
            for u in &q {
                v -= u * u.dot(&v);
            }
            if v.norm() > 1e-12 {
                q.push(v.normalize());
            }
        }
        let mut p = DMatrix::<f64>::identity(n, n);
        for u in &q {
            p -= u * u.transpose();
        }
        let big = 10.0 * hess.amax() + 1.0;
        (p, hess, q, big)
    }

    /// The margin: the smallest reduced eigenvalue over 4π²/L².
    pub fn margin(&self) -> f64 {
        let nu0 = (2.0 * std::f64::consts::PI / self.length).powi(2);
        self.reduced()[0] / nu0
    }

    pub fn points(&self) -> Vec<[f64; 2]> {
        let h = self.length / self.theta.len() as f64;
        let mut p = [-0.5 * self.ends.chord, 0.0];
        let mut out = vec![p];
        for t in self.theta.iter() {
            p = [p[0] + h * t.cos(), p[1] + h * t.sin()];
            out.push(p);
        }
        out
    }

    pub fn distance(&self, other: &Blade) -> f64 {
        self.points()
            .iter()
            .zip(other.points())
            .map(|(a, b)| (a[0] - b[0]).hypot(a[1] - b[1]))
            .fold(0.0, f64::max)
    }
}

/// The blade settled from a shape given at 17 stations (linear between them).
pub fn settle_like(length: f64, ends: Ends, shape: &[f64], n: usize) -> Option<Blade> {
    let m = shape.len() - 1;
    let turn = near(shape[0], ends.angles[0]) - shape[0];
    let theta = DVector::from_fn(n, |i, _| {
        let x = (i as f64 + 0.5) / n as f64 * m as f64;
        let k = (x.floor() as usize).min(m - 1);
        let f = x - k as f64;
        shape[k] * (1.0 - f) + shape[k + 1] * f + turn
    });
    solve(length, ends, theta, [0.0, 0.0])
}

/// The ends a fraction `w` along the move from `a` to `b` (both ends), as the controller
/// moves them.
pub fn between(a: &[Isometry3<f64>; 2], b: &[Isometry3<f64>; 2], w: f64) -> [Isometry3<f64>; 2] {
    let at = |e: usize| {
        Isometry3::from_parts(
            a[e].translation
                .vector
                .lerp(&b[e].translation.vector, w)
                .into(),
            a[e].rotation.slerp(&b[e].rotation, w),
        )
    };
    [at(0), at(1)]
}

/// Follows `from` through the move from `a` to `b`: steps of at most a quarter of the move,
/// each accepted when Newton's method converges, no segment turns by more than 0.02 rad
/// and the blade stays stable, else halved; a move that cannot be followed by steps of
/// 1e-4 snaps. `Err` names how.
pub fn follow(
    from: &Blade,
    a: &[Isometry3<f64>; 2],
    b: &[Isometry3<f64>; 2],
) -> Result<Blade, String> {
    let length = from.length;
    let at = |w: f64, prev: &Ends| {
        let p = between(a, b, w);
        let e = ends_of(&p[0], &p[1]);
        Ends {
            chord: e.chord,
            angles: [
                near(e.angles[0], prev.angles[0]),
                near(e.angles[1], prev.angles[1]),
            ],
        }
    };
    let mut blade = from.clone();
    let (mut w, mut dw) = (0.0f64, 0.25f64);
    for _ in 0..100_000 {
        if w >= 1.0 - 1e-12 {
            return Ok(blade);
        }
        let to = (w + dw).min(1.0);
        let ends = at(to, &blade.ends);
        let next = if ends.chord < length {
            solve(length, ends, blade.theta.clone(), blade.lambda)
                .filter(|b| (&b.theta - &blade.theta).amax() <= 0.02)
        } else {
            None
        };
        match next {
            Some(b) if b.is_stable() => {
                blade = b;
                w = to;
                dw = (2.0 * dw).min(0.25);
            }
            other => {
                let unstable = other.is_some();
                dw *= 0.5;
                if dw < 1e-4 {
                    return Err(if unstable {
                        format!("a fold at {w:.4} of the move (the blade loses its stability)")
                    } else {
                        format!("no equilibrium to follow past {w:.4} of the move")
                    });
                }
            }
        }
    }
    Err("the move was not followed to its end".into())
}

/// The points of the blade of `length` held by the TCP frames `ends` in the planned shape
/// `shape` (its tangent angle against the chord at equal stations): the discrete
/// equilibrium settled from it on `n` segments, in the TCPs' frame.
pub fn planned_points(
    ends: [&Isometry3<f64>; 2],
    length: f64,
    shape: &[f64],
    n: usize,
) -> Option<Vec<Vector3<f64>>> {
    let (p0, p1) = (ends[0].translation.vector, ends[1].translation.vector);
    let e = ends_of(ends[0], ends[1]);
    if !(e.chord < length) {
        return None;
    }
    let x = (p1 - p0) / e.chord;
    let z = ends[0].rotation * Vector3::z();
    let z = (z - x * z.dot(&x)).normalize();
    let y = z.cross(&x);
    let mid = 0.5 * (p0 + p1);
    let blade = settle_like(length, e, shape, n)?;
    Some(
        blade
            .points()
            .iter()
            .map(|q| mid + x * q[0] + y * q[1])
            .collect(),
    )
}
