//! Discrete elastica ("Designing for Robotic Hot-Blade Cutting" §3.2, after Bruckstein et
//! al. 2001): a polyline of n equal segments between given end points, end tangents and
//! length that minimises the sum of squared turning angles.
//!
//! Unknowns are the segment directions θ₀ … θ_{n−1}; the turning angles are their
//! differences, with the end tangents as ghost directions θ_s, θ_e. The first and last turn
//! happen over half a segment, so they count twice — that keeps the discrete energy a
//! second-order approximation of ∫κ² ds and the vertices converge to the closed-form
//! elastica at O(h²). The end point is imposed by two equality constraints
//! `h Σ (cos θᵢ, sin θᵢ) = p_e − p_s`; the problem is solved by Newton's method on the
//! Lagrange (KKT) system with a merit-function line search, a direct solve instead of the
//! paper's two-loop gradient descent.
//!
//! Newton on the KKT system can stall where its matrix turns singular on the way — typical
//! of nearly taut blades whose length exceeds the chord by 1e-5 or less and that must
//! buckle into an S to take up the slack. Then the energy is minimised by an augmented
//! Lagrangian method instead (damped Newton on the augmented energy, which only ever goes
//! downhill, multipliers updated outside), and Newton–KKT polishes the result to full
//! accuracy. Written here rather than taken from an optimisation crate because the
//! structure (tridiagonal energy Hessian, two constraints) makes each step a small dense
//! solve and the fallback must hand its multipliers to the polishing step.

use nalgebra::{DMatrix, DVector};

/// Boundary data and resolution of a discrete elastica.
#[derive(Clone, Debug)]
pub struct DiscreteParams {
    /// Number of equal segments (≥ 2).
    pub segments: usize,
    /// Start point.
    pub start: [f64; 2],
    /// Tangent angle at the start (radians).
    pub start_angle: f64,
    /// End point.
    pub end: [f64; 2],
    /// Tangent angle at the end (radians, unwrapped relative to the start).
    pub end_angle: f64,
    /// Curve length (> distance between the end points).
    pub length: f64,
    /// Newton iterations at most.
    pub max_iterations: usize,
}

/// A solved discrete elastica.
#[derive(Clone, Debug)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct DiscreteElastica {
    /// The n + 1 vertices.
    pub points: Vec<[f64; 2]>,
    /// Direction of each segment.
    pub angles: Vec<f64>,
    /// Bending energy Σα²/h (approximates ∫κ² ds).
    pub energy: f64,
    /// Distance between the last vertex and the requested end point.
    pub end_error: f64,
    /// Newton iterations used (all stages).
    pub iterations: usize,
    /// Whether Newton–KKT alone stalled and the augmented-Lagrangian fallback was used.
    pub fallback: bool,
}

/// Why no discrete elastica was found.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DiscreteError {
    /// Bad input.
    #[error("invalid discrete elastica input: {0}")]
    Invalid(String),
    /// Newton's method did not reach the end point.
    #[error("no discrete elastica found: end point missed by {0}")]
    NotConverged(f64),
}

/// Solve for the discrete elastica.
///
/// ```
/// use elastica::discrete::{discrete_elastica, DiscreteParams};
/// // a symmetric arch: 1 unit wide, 1.2 long, leaving at +30° and arriving at −30°
/// let a = 30f64.to_radians();
/// let d = discrete_elastica(&DiscreteParams {
///     segments: 32, start: [0.0, 0.0], start_angle: a, end: [1.0, 0.0], end_angle: -a,
///     length: 1.2, max_iterations: 50,
/// }).unwrap();
/// assert!(d.end_error < 1e-12);
/// assert!((d.points[16][0] - 0.5).abs() < 1e-12); // symmetric
/// ```
pub fn discrete_elastica(p: &DiscreteParams) -> Result<DiscreteElastica, DiscreteError> {
    let n = p.segments;
    let finite = p.start.iter().chain(&p.end).all(|v| v.is_finite())
        && p.start_angle.is_finite()
        && p.end_angle.is_finite()
        && p.length.is_finite();
    if !finite {
        return Err(DiscreteError::Invalid("inputs must be finite".into()));
    }
    if n < 2 {
        return Err(DiscreteError::Invalid(format!(
            "need ≥ 2 segments, got {n}"
        )));
    }
    let dx = p.end[0] - p.start[0];
    let dy = p.end[1] - p.start[1];
    let chord = dx.hypot(dy);
    if !(p.length > chord) {
        return Err(DiscreteError::Invalid(format!(
            "length {} must exceed the chord {chord}",
            p.length
        )));
    }
    let pb = Problem {
        n,
        h: p.length / n as f64,
        ts: p.start_angle,
        te: p.end_angle,
        d: [dx, dy],
    };
    // start: a quadratic angle profile whose mean direction points along the chord
    let (ts, te) = (p.start_angle, p.end_angle);
    let chord_angle = ts
        + (dy.atan2(dx) - ts + std::f64::consts::PI).rem_euclid(2.0 * std::f64::consts::PI)
        - std::f64::consts::PI;
    let theta: Vec<f64> = (0..n)
        .map(|i| {
            let u = (i as f64 + 0.5) / n as f64;
            // Bernstein blend: ts, 3·mid-correction, te so the average is the chord angle
            let mid = (4.0 * chord_angle - ts - te) / 2.0;
            ts * (1.0 - u).powi(2) + 2.0 * mid * u * (1.0 - u) + te * u * u
        })
        .collect();
    let tolerance = 1e-9 * p.length;
    let mut sol = pb.newton_kkt(theta.clone(), [0.0; 2], p.max_iterations);
    let fallback = !(sol.end_error < tolerance);
    if fallback {
        // Newton stalled: minimise the energy from the same start, then polish
        let (th, mu, used) = pb.augmented_lagrangian(theta, p.max_iterations);
        let polished = pb.newton_kkt(th, mu, p.max_iterations);
        sol = Solution {
            iterations: sol.iterations + used + polished.iterations,
            ..polished
        };
    }
    if !(sol.end_error < tolerance) {
        return Err(DiscreteError::NotConverged(sol.end_error));
    }
    let h = pb.h;
    let mut points = Vec::with_capacity(n + 1);
    let mut q = p.start;
    points.push(q);
    for t in &sol.theta {
        q = [q[0] + h * t.cos(), q[1] + h * t.sin()];
        points.push(q);
    }
    let energy = pb.energy(&sol.theta) / h;
    Ok(DiscreteElastica {
        points,
        angles: sol.theta,
        energy,
        end_error: sol.end_error,
        iterations: sol.iterations,
        fallback,
    })
}

/// The discrete problem: n directions θ between the ghost end directions ts, te, each
/// segment h long, the segments summing to the chord vector d.
struct Problem {
    n: usize,
    h: f64,
    ts: f64,
    te: f64,
    d: [f64; 2],
}

/// Where an iteration ended.
struct Solution {
    theta: Vec<f64>,
    end_error: f64,
    iterations: usize,
}

impl Problem {
    /// Weight of turning angle i: the two half-segment end turns count twice.
    fn weight(&self, i: usize) -> f64 {
        if i == 0 || i == self.n {
            2.0
        } else {
            1.0
        }
    }

    /// Turning angles α₀ = θ₀ − θs, αᵢ = θᵢ − θᵢ₋₁, αₙ = θe − θₙ₋₁.
    fn alphas(&self, th: &[f64]) -> Vec<f64> {
        let n = self.n;
        (0..=n)
            .map(|i| {
                if i == 0 {
                    th[0] - self.ts
                } else if i == n {
                    self.te - th[n - 1]
                } else {
                    th[i] - th[i - 1]
                }
            })
            .collect()
    }

    /// E·h = Σ wᵢ αᵢ².
    fn energy(&self, th: &[f64]) -> f64 {
        let a = self.alphas(th);
        (0..=self.n).map(|i| self.weight(i) * a[i] * a[i]).sum()
    }

    /// ∂(E·h)/∂θᵢ: from αᵢ (+) and αᵢ₊₁ (−).
    fn energy_gradient(&self, th: &[f64]) -> Vec<f64> {
        let a = self.alphas(th);
        (0..self.n)
            .map(|i| 2.0 * (self.weight(i) * a[i] - self.weight(i + 1) * a[i + 1]))
            .collect()
    }

    /// The energy's (tridiagonal) Hessian written into `k`.
    fn add_energy_hessian(&self, k: &mut DMatrix<f64>) {
        for i in 0..self.n {
            k[(i, i)] += 2.0 * (self.weight(i) + self.weight(i + 1));
            if i + 1 < self.n {
                let w = 2.0 * self.weight(i + 1);
                k[(i, i + 1)] -= w;
                k[(i + 1, i)] -= w;
            }
        }
    }

    /// End-point constraint h Σ (cos θ, sin θ) − d.
    fn constraint(&self, th: &[f64]) -> [f64; 2] {
        let cx: f64 = th.iter().map(|t| self.h * t.cos()).sum::<f64>() - self.d[0];
        let cy: f64 = th.iter().map(|t| self.h * t.sin()).sum::<f64>() - self.d[1];
        [cx, cy]
    }

    /// KKT residual of the Lagrangian E·h + μ·c, and the end error |c|.
    fn kkt_residual(&self, th: &[f64], mu: &[f64; 2]) -> (DVector<f64>, f64) {
        let n = self.n;
        let g = self.energy_gradient(th);
        let mut r = DVector::zeros(n + 2);
        for i in 0..n {
            let (s, c) = th[i].sin_cos();
            r[i] = g[i] - mu[0] * self.h * s + mu[1] * self.h * c;
        }
        let c = self.constraint(th);
        r[n] = c[0];
        r[n + 1] = c[1];
        (r, c[0].hypot(c[1]))
    }

    /// Newton's method on the KKT system with backtracking on the residual norm.
    fn newton_kkt(&self, mut theta: Vec<f64>, mut mu: [f64; 2], max_iter: usize) -> Solution {
        let (n, h) = (self.n, self.h);
        let length = h * n as f64;
        let mut iterations = 0;
        let (mut r, mut end_err) = self.kkt_residual(&theta, &mu);
        for it in 0..max_iter {
            iterations = it;
            let rn = r.norm();
            if rn < 1e-13 * (1.0 + length) {
                break;
            }
            let Some(step) = self.kkt_step(&theta, &mu, &r) else {
                break;
            };
            let mut lambda = 1.0;
            let mut improved = false;
            for _ in 0..30 {
                let th: Vec<f64> = (0..n).map(|i| theta[i] + lambda * step[i]).collect();
                let m = [mu[0] + lambda * step[n], mu[1] + lambda * step[n + 1]];
                let (rt, et) = self.kkt_residual(&th, &m);
                if rt.norm() < (1.0 - 1e-4 * lambda) * rn || rt.norm() < 1e-13 {
                    theta = th;
                    mu = m;
                    r = rt;
                    end_err = et;
                    improved = true;
                    break;
                }
                lambda *= 0.5;
            }
            if !improved {
                break;
            }
            iterations = it + 1;
        }
        Solution {
            theta,
            end_error: end_err,
            iterations,
        }
    }

    /// The Newton step of the KKT system at `(theta, mu)` with residual `r`: the
    /// tridiagonal Hessian bordered by the two constraint rows, solved in O(n)
    /// ([`crate::stability::pencil`]'s bordered solve) and, where the Hessian alone is
    /// singular, by a dense LU of the whole matrix.
    fn kkt_step(&self, theta: &[f64], mu: &[f64; 2], r: &DVector<f64>) -> Option<DVector<f64>> {
        let (n, h) = (self.n, self.h);
        let trig: Vec<(f64, f64)> = theta.iter().map(|t| t.sin_cos()).collect();
        let diag: Vec<f64> = (0..n)
            .map(|i| {
                let (s, c) = trig[i];
                2.0 * (self.weight(i) + self.weight(i + 1)) - mu[0] * h * c - mu[1] * h * s
            })
            .collect();
        let off: Vec<f64> = (1..n).map(|i| -2.0 * self.weight(i)).collect();
        let rows = [
            trig.iter().map(|&(s, _)| -h * s).collect::<Vec<f64>>(),
            trig.iter().map(|&(_, c)| h * c).collect::<Vec<f64>>(),
        ];
        let f: Vec<f64> = (0..n).map(|i| -r[i]).collect();
        if let Some((x, y)) = crate::stability::pencil::bordered_solve(
            &diag,
            &off,
            [&rows[0], &rows[1]],
            &f,
            [-r[n], -r[n + 1]],
        ) {
            return Some(DVector::from_iterator(n + 2, x.into_iter().chain(y)));
        }
        let mut k = DMatrix::<f64>::zeros(n + 2, n + 2);
        for i in 0..n {
            k[(i, i)] = diag[i];
            if i + 1 < n {
                k[(i, i + 1)] = off[i];
                k[(i + 1, i)] = off[i];
            }
            for (j, row) in rows.iter().enumerate() {
                k[(i, n + j)] = row[i];
                k[(n + j, i)] = row[i];
            }
        }
        k.lu().solve(&(-r))
    }

    /// Augmented Lagrangian minimisation of E·h subject to c = 0, with the constraint
    /// measured relative to the length: Φ = E·h − λ·c/L + ρ/2 |c/L|². Each inner step is a
    /// Levenberg–Marquardt-damped Newton step on Φ (the damping makes the matrix positive
    /// definite, so every accepted step lowers Φ). Returns the directions, the multipliers
    /// in the convention of [`Problem::kkt_residual`] and the iterations used.
    fn augmented_lagrangian(
        &self,
        mut theta: Vec<f64>,
        max_iter: usize,
    ) -> (Vec<f64>, [f64; 2], usize) {
        let (n, h) = (self.n, self.h);
        let length = h * n as f64;
        let mut lambda = [0.0f64; 2];
        let mut rho = 10.0 * n as f64;
        let mut used = 0;
        let rel = |th: &[f64]| {
            let c = self.constraint(th);
            [c[0] / length, c[1] / length]
        };
        let merit = |th: &[f64], lambda: &[f64; 2], rho: f64| {
            let c = rel(th);
            self.energy(th) - lambda[0] * c[0] - lambda[1] * c[1]
                + 0.5 * rho * (c[0] * c[0] + c[1] * c[1])
        };
        let mut c_prev = f64::INFINITY;
        for _outer in 0..60 {
            let mut nu = 0.0f64;
            for _inner in 0..200 {
                if used >= max_iter {
                    break;
                }
                used += 1;
                let c = rel(&theta);
                let sigma = [lambda[0] - rho * c[0], lambda[1] - rho * c[1]];
                // ∂c/∂θᵢ relative: (−h sin θᵢ, h cos θᵢ)/L
                let grad_e = self.energy_gradient(&theta);
                let mut g = DVector::zeros(n);
                let mut jac = DMatrix::<f64>::zeros(2, n);
                let mut k = DMatrix::<f64>::zeros(n, n);
                self.add_energy_hessian(&mut k);
                for i in 0..n {
                    let (s, co) = theta[i].sin_cos();
                    jac[(0, i)] = -h * s / length;
                    jac[(1, i)] = h * co / length;
                    g[i] = grad_e[i] - sigma[0] * jac[(0, i)] - sigma[1] * jac[(1, i)];
                    // −σ·∂²c: ∂²cx/∂θᵢ² = −h cos θᵢ / L, ∂²cy/∂θᵢ² = −h sin θᵢ / L
                    k[(i, i)] += (sigma[0] * co + sigma[1] * s) * h / length;
                }
                k += rho * jac.transpose() * &jac;
                let phi = merit(&theta, &lambda, rho);
                if g.amax() < 1e-15 {
                    // stationary: a minimum, or a saddle such as a straight start between
                    // aligned ends that must buckle one way or the other
                    match escape_saddle(&k, &theta, |th| merit(th, &lambda, rho), phi) {
                        Some(th) => {
                            theta = th;
                            continue;
                        }
                        None => break,
                    }
                }
                let mut accepted = false;
                for _ in 0..40 {
                    let mut kd = k.clone();
                    for i in 0..n {
                        kd[(i, i)] += nu;
                    }
                    if let Some(ch) = kd.cholesky() {
                        let step = ch.solve(&(-&g));
                        let th: Vec<f64> = (0..n).map(|i| theta[i] + step[i]).collect();
                        let decrease = -0.5 * g.dot(&step);
                        let phit = merit(&th, &lambda, rho);
                        if phit <= phi - 1e-4 * decrease {
                            theta = th;
                            nu /= 10.0;
                            accepted = step.amax() > 1e-14;
                            break;
                        }
                    }
                    nu = if nu == 0.0 { 1e-10 } else { nu * 10.0 };
                }
                if !accepted {
                    break;
                }
            }
            let c = rel(&theta);
            let cn = c[0].hypot(c[1]);
            lambda = [lambda[0] - rho * c[0], lambda[1] - rho * c[1]];
            if cn * length < 1e-7 * length.max(1.0) || used >= max_iter {
                break;
            }
            if cn > 0.25 * c_prev {
                rho *= 10.0;
            }
            c_prev = cn;
        }
        // E·h − λ·c/L has ∇ = ∇E − (λ/L)·∇c; kkt_residual uses ∇E + μ·∇c
        (theta, [-lambda[0] / length, -lambda[1] / length], used)
    }
}

/// From a stationary point with an indefinite Hessian `k`, step along the direction of most
/// negative curvature (to the side of positive first component, for determinism) far
/// enough to lower `merit`; `None` at a minimum.
fn escape_saddle(
    k: &DMatrix<f64>,
    theta: &[f64],
    merit: impl Fn(&[f64]) -> f64,
    phi: f64,
) -> Option<Vec<f64>> {
    if k.clone().cholesky().is_some() {
        return None;
    }
    let eig = k.clone().symmetric_eigen();
    let (imin, lmin) =
        eig.eigenvalues
            .iter()
            .enumerate()
            .fold(
                (0, f64::INFINITY),
                |(bi, bl), (i, &l)| {
                    if l < bl {
                        (i, l)
                    } else {
                        (bi, bl)
                    }
                },
            );
    if !(lmin < 0.0) {
        return None;
    }
    let mut v = eig.eigenvectors.column(imin).into_owned();
    if v.iter().find(|x| x.abs() > 1e-12).is_some_and(|x| *x < 0.0) {
        v = -v;
    }
    let mut t = 1.0;
    for _ in 0..60 {
        let th: Vec<f64> = theta.iter().zip(v.iter()).map(|(a, b)| a + t * b).collect();
        if merit(&th) < phi {
            return Some(th);
        }
        t *= 0.5;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Clamped at both ends along the chord with slack: the straight start is a saddle of
    /// the energy, the solver must buckle it into the symmetric first mode.
    #[test]
    fn clamped_ends_with_slack_buckle_symmetrically() {
        for chord in [0.5, 0.99, 0.99999] {
            let d = discrete_elastica(&DiscreteParams {
                segments: 64,
                start: [0.0, 0.0],
                start_angle: 0.0,
                end: [chord, 0.0],
                end_angle: 0.0,
                length: 1.0,
                max_iterations: 500,
            })
            .unwrap();
            assert!(
                d.fallback && d.end_error < 1e-12,
                "{chord}: {}",
                d.end_error
            );
            let n = d.points.len() - 1;
            for i in 0..=n {
                let (a, b) = (d.points[i], d.points[n - i]);
                assert!(
                    (a[0] + b[0] - chord).abs() < 1e-9,
                    "{chord}: x symmetry at {i}"
                );
                assert!((a[1] - b[1]).abs() < 1e-9, "{chord}: y symmetry at {i}");
            }
            assert!(d.points[n / 2][1].abs() > 0.0);
        }
    }

    #[test]
    fn bad_input_is_rejected() {
        let ok = DiscreteParams {
            segments: 8,
            start: [0.0, 0.0],
            start_angle: 0.0,
            end: [1.0, 0.0],
            end_angle: 0.0,
            length: 1.5,
            max_iterations: 50,
        };
        for bad in [
            DiscreteParams {
                length: 1.0,
                ..ok.clone()
            },
            DiscreteParams {
                segments: 1,
                ..ok.clone()
            },
            DiscreteParams {
                start_angle: f64::NAN,
                ..ok.clone()
            },
        ] {
            assert!(matches!(
                discrete_elastica(&bad),
                Err(DiscreteError::Invalid(_))
            ));
        }
    }
}
