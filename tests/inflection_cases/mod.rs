//! The analytic surfaces of the inflection tests and their exact inflection counts.
//!
//! Each surface is `z = f(x, y)` in millimetres, written once as an expression for hotcut
//! (with `X` and `Y` for the coordinates, so it can be restated in metres) and once as
//! hand-written Rust closures for its gradient and Hessian: the reference never goes
//! through hotcut's parser, derivatives, meshes or curve analysis.
//!
//! The reference count of a section by the plane `d · p = o` is the number of sign changes
//! of the section's curvature. With the plane's frame `u = normalize(ẑ × d)`, `v = d × u`
//! (hotcut's), the section is the curve `p(a) = o d + a u + b(a) v` with
//! `g(a, b) = p_z − f(p_x, p_y) = 0`; implicit differentiation gives
//! `b'' = (wᵀ H w) / g_b` with `w = (u + b' v)_xy`, and `g_b` keeps its sign along a
//! section that is a graph over `u`. So the curvature changes sign where the quadratic
//! form `Q(a) = wᵀ H w` does; for vertical planes `w = u_xy` and `Q` is the second
//! derivative along the section. `Q` is exactly 0 on planes and along rulings, so those
//! count 0.

/// Which acceptance class a surface belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// A plane: every section straight.
    Plane,
    /// A ruled surface (cylinder, cone, hyperbolic paraboloid): sections are conics or
    /// straight lines.
    Ruled,
    /// Ripples with 10–20 inflections per section.
    Rippled,
    /// Sections with 15 or more inflections.
    Dense,
}

/// `(f, f_x, f_y, f_xx, f_xy, f_yy)` at a point.
pub type Jet = (f64, f64, f64, f64, f64, f64);

/// An analytic surface over a rectangle, in millimetres.
pub struct Analytic {
    /// Its name.
    pub name: &'static str,
    /// Its class.
    pub class: Class,
    /// `z` as hotcut reads it, `X` and `Y` standing for the coordinates in millimetres.
    pub expr: &'static str,
    /// Value, gradient and Hessian.
    pub jet: fn(f64, f64) -> Jet,
    /// `x` range.
    pub x: (f64, f64),
    /// `y` range.
    pub y: (f64, f64),
}

const R_CYL: f64 = 1500.0;

/// Every surface of the test.
pub const SURFACES: &[Analytic] = &[
    // --- planes at several tilts
    Analytic {
        name: "plane-flat",
        class: Class::Plane,
        expr: "250",
        jet: |_, _| (250.0, 0.0, 0.0, 0.0, 0.0, 0.0),
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        // the facade: tilted 11° about one axis and 6° about the other
        name: "plane-11-6",
        class: Class::Plane,
        expr: "0.194380309*X + 0.105104235*Y + 40",
        jet: |x, y| {
            let (a, b) = (0.194380309, 0.105104235);
            (a * x + b * y + 40.0, a, b, 0.0, 0.0, 0.0)
        },
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        name: "plane-steep",
        class: Class::Plane,
        expr: "0.7*Y - 0.45*X + 2000",
        jet: |x, y| (0.7 * y - 0.45 * x + 2000.0, -0.45, 0.7, 0.0, 0.0, 0.0),
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    // --- ruled surfaces
    Analytic {
        // rulings along x: sections x = const are circular arcs
        name: "cylinder-across",
        class: Class::Ruled,
        expr: "sqrt(2250000 - (Y - 1000)^2)",
        jet: |_, y| {
            let t = y - 1000.0;
            let r2 = R_CYL * R_CYL - t * t;
            let r = r2.sqrt();
            (r, 0.0, -t / r, 0.0, 0.0, -R_CYL * R_CYL / (r2 * r))
        },
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        // rulings along y: sections x = const are straight
        name: "cylinder-along",
        class: Class::Ruled,
        expr: "sqrt(2250000 - (X - 1500)^2)",
        jet: |x, _| {
            let t = x - 1500.0;
            let r2 = R_CYL * R_CYL - t * t;
            let r = r2.sqrt();
            (r, -t / r, 0.0, -R_CYL * R_CYL / (r2 * r), 0.0, 0.0)
        },
        x: (500.0, 2500.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        // a wavy cylinder: across its rulings the sine's inflections, along them none
        name: "wave-cylinder",
        class: Class::Ruled,
        expr: "60*sin(Y/250)",
        jet: |_, y| {
            let s = (y / 250.0).sin();
            let c = (y / 250.0).cos();
            (
                60.0 * s,
                0.0,
                60.0 / 250.0 * c,
                0.0,
                0.0,
                -60.0 / 62500.0 * s,
            )
        },
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        // a cone with its apex outside the rectangle: every section a conic
        name: "cone",
        class: Class::Ruled,
        expr: "1800 - 0.6*sqrt((X + 800)^2 + (Y - 1000)^2)",
        jet: |x, y| {
            let (p, q) = (x + 800.0, y - 1000.0);
            let r = (p * p + q * q).sqrt();
            let r3 = r * r * r;
            (
                1800.0 - 0.6 * r,
                -0.6 * p / r,
                -0.6 * q / r,
                -0.6 * q * q / r3,
                0.6 * p * q / r3,
                -0.6 * p * p / r3,
            )
        },
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    Analytic {
        // doubly ruled: straight along x and along y, a conic in any other plane
        name: "hypar",
        class: Class::Ruled,
        expr: "(X - 1500)*(Y - 1000)/4000",
        jet: |x, y| {
            let (p, q) = (x - 1500.0, y - 1000.0);
            (
                p * q / 4000.0,
                q / 4000.0,
                p / 4000.0,
                0.0,
                1.0 / 4000.0,
                0.0,
            )
        },
        x: (0.0, 3000.0),
        y: (0.0, 2000.0),
    },
    // --- rippled facades, 10–20 inflections per section (issue 19's held-out class)
    Analytic {
        name: "tilted-crests",
        class: Class::Rippled,
        expr: "12*sin(Y/45 + X/400)",
        jet: |x, y| wave(12.0, 1.0 / 400.0, 1.0 / 45.0, 0.0, x, y),
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Analytic {
        name: "two-waves",
        class: Class::Rippled,
        expr: "8*sin(Y/50) + 1.5*sin(Y/23 + X/300)",
        jet: |x, y| {
            add(
                wave(8.0, 0.0, 1.0 / 50.0, 0.0, x, y),
                wave(1.5, 1.0 / 300.0, 1.0 / 23.0, 0.0, x, y),
            )
        },
        x: (0.0, 1200.0),
        y: (0.0, 1500.0),
    },
    Analytic {
        name: "chirp",
        class: Class::Rippled,
        expr: "10*sin(1.5*(Y/300)^2 + X/700)",
        jet: |x, y| {
            // 10 sin(φ), φ = 1.5 y²/90000 + x/700
            let phi = 1.5 * y * y / 90000.0 + x / 700.0;
            let (px, py, pyy) = (1.0 / 700.0, 3.0 * y / 90000.0, 3.0 / 90000.0);
            sine_of(10.0, phi, (px, py, pyy))
        },
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Analytic {
        name: "decaying",
        class: Class::Rippled,
        expr: "15*exp(-Y/900)*sin(Y/55 + X/500)",
        jet: |x, y| {
            // e(y) · w(x, y), e = 15 exp(−y/900), w = sin(y/55 + x/500)
            let e = 15.0 * (-y / 900.0).exp();
            let (ey, eyy) = (-e / 900.0, e / 810000.0);
            let (_, wx, wy, wxx, wxy, wyy) = wave(1.0, 1.0 / 500.0, 1.0 / 55.0, 0.0, x, y);
            let w = (y / 55.0 + x / 500.0).sin();
            (
                e * w,
                e * wx,
                ey * w + e * wy,
                e * wxx,
                ey * wx + e * wxy,
                eyy * w + 2.0 * ey * wy + e * wyy,
            )
        },
        x: (0.0, 1000.0),
        y: (0.0, 1800.0),
    },
    Analytic {
        name: "vault-ripples",
        class: Class::Rippled,
        expr: "(Y - 750)^2/4000 + 4*sin(Y/40 + X/250)",
        jet: |x, y| {
            let q = y - 750.0;
            add(
                (q * q / 4000.0, 0.0, q / 2000.0, 0.0, 0.0, 1.0 / 2000.0),
                wave(4.0, 1.0 / 250.0, 1.0 / 40.0, 0.0, x, y),
            )
        },
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    Analytic {
        name: "oblique-wave",
        class: Class::Rippled,
        expr: "10*sin(X/120 + Y/75)",
        jet: |x, y| wave(10.0, 1.0 / 120.0, 1.0 / 75.0, 0.0, x, y),
        x: (0.0, 1500.0),
        y: (0.0, 2400.0),
    },
    Analytic {
        name: "egg-crate",
        class: Class::Rippled,
        expr: "6*sin(X/80)*sin(Y/45) + X/20",
        jet: |x, y| {
            let (sx, cx) = ((x / 80.0).sin(), (x / 80.0).cos());
            let (sy, cy) = ((y / 45.0).sin(), (y / 45.0).cos());
            (
                6.0 * sx * sy + x / 20.0,
                6.0 / 80.0 * cx * sy + 1.0 / 20.0,
                6.0 / 45.0 * sx * cy,
                -6.0 / 6400.0 * sx * sy,
                6.0 / 3600.0 * cx * cy,
                -6.0 / 2025.0 * sx * sy,
            )
        },
        x: (0.0, 1000.0),
        y: (0.0, 1600.0),
    },
    Analytic {
        name: "shallow",
        class: Class::Rippled,
        expr: "2*sin(Y/35 + X/600) + Y/10",
        jet: |x, y| {
            add(
                wave(2.0, 1.0 / 600.0, 1.0 / 35.0, 0.0, x, y),
                (y / 10.0, 0.0, 0.1, 0.0, 0.0, 0.0),
            )
        },
        x: (0.0, 1000.0),
        y: (0.0, 1500.0),
    },
    // --- sections with 15+ inflections
    Analytic {
        // a wave whose wavelength wanders: 15–20 inflections per section
        name: "dense",
        class: Class::Dense,
        expr: "5*sin(Y/30 + X/300 + 0.3*sin(Y/200))",
        jet: |x, y| {
            let phi = y / 30.0 + x / 300.0 + 0.3 * (y / 200.0).sin();
            let (px, py, pyy) = (
                1.0 / 300.0,
                1.0 / 30.0 + 0.3 / 200.0 * (y / 200.0).cos(),
                -0.3 / 40000.0 * (y / 200.0).sin(),
            );
            sine_of(5.0, phi, (px, py, pyy))
        },
        x: (0.0, 1000.0),
        y: (0.0, 1600.0),
    },
    Analytic {
        name: "dense-beat",
        class: Class::Dense,
        expr: "5*sin(Y/33)*cos(Y/410 + X/900)",
        jet: |x, y| {
            // 5 s(y) c(x, y), s = sin(y/33), c = cos(y/410 + x/900)
            let (s, sy, syy) = (
                (y / 33.0).sin(),
                (y / 33.0).cos() / 33.0,
                -(y / 33.0).sin() / 1089.0,
            );
            let phi = y / 410.0 + x / 900.0;
            let (c, cs) = (phi.cos(), phi.sin());
            let (cx, cy) = (-cs / 900.0, -cs / 410.0);
            let (cxx, cxy, cyy) = (-c / 810000.0, -c / 369000.0, -c / 168100.0);
            (
                5.0 * s * c,
                5.0 * s * cx,
                5.0 * (sy * c + s * cy),
                5.0 * s * cxx,
                5.0 * (sy * cx + s * cxy),
                5.0 * (syy * c + 2.0 * sy * cy + s * cyy),
            )
        },
        x: (0.0, 1000.0),
        y: (0.0, 1600.0),
    },
];

/// `amp · sin(kx·x + ky·y + phase)` with its derivatives.
fn wave(amp: f64, kx: f64, ky: f64, phase: f64, x: f64, y: f64) -> Jet {
    let p = kx * x + ky * y + phase;
    let (s, c) = (p.sin(), p.cos());
    (
        amp * s,
        amp * c * kx,
        amp * c * ky,
        -amp * s * kx * kx,
        -amp * s * kx * ky,
        -amp * s * ky * ky,
    )
}

/// The jet of `amp · sin(φ)` for a phase `φ` linear in x: its value `phi` and its
/// derivatives `(φx, φy, φyy)` (φxx = φxy = 0).
fn sine_of(amp: f64, phi: f64, (px, py, pyy): (f64, f64, f64)) -> Jet {
    let (s, c) = (phi.sin(), phi.cos());
    (
        amp * s,
        amp * c * px,
        amp * c * py,
        -amp * s * px * px,
        -amp * s * px * py,
        -amp * s * py * py + amp * c * pyy,
    )
}

fn add(a: Jet, b: Jet) -> Jet {
    (
        a.0 + b.0,
        a.1 + b.1,
        a.2 + b.2,
        a.3 + b.3,
        a.4 + b.4,
        a.5 + b.5,
    )
}

/// The surface's expression in `scale` job units per millimetre.
pub fn expr_in(s: &Analytic, scale: f64) -> String {
    let body = s
        .expr
        .replace('X', &format!("(x/{scale})"))
        .replace('Y', &format!("(y/{scale})"));
    format!("{scale}*({body})")
}

/// A cutting plane's frame as hotcut makes it: `d` unit, `u = normalize(ẑ × d)`,
/// `v = d × u`.
pub fn frame(d: [f64; 3]) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let n = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    let d = [d[0] / n, d[1] / n, d[2] / n];
    let u = [-d[1], d[0], 0.0];
    let nu = (u[0] * u[0] + u[1] * u[1]).sqrt();
    let u = [u[0] / nu, u[1] / nu, 0.0];
    let v = [
        d[1] * u[2] - d[2] * u[1],
        d[2] * u[0] - d[0] * u[2],
        d[0] * u[1] - d[1] * u[0],
    ];
    (d, u, v)
}

/// The inflections of the section of `s` by `d · p = offset` (millimetres), over the part
/// of the plane whose points lie over the rectangle: the positions (the `a` coordinate
/// along `u`) of the sign changes, and the section's span of `a`.
pub fn reference(s: &Analytic, d: [f64; 3], offset: f64) -> (Vec<f64>, (f64, f64)) {
    let (d, u, v) = frame(d);
    // a = p · u (u is horizontal and d ⟂ u): the rectangle's corners seen along u
    let diag = ((s.x.1 - s.x.0).powi(2) + (s.y.1 - s.y.0).powi(2)).sqrt();
    let along: Vec<f64> = [
        (s.x.0, s.y.0),
        (s.x.1, s.y.0),
        (s.x.0, s.y.1),
        (s.x.1, s.y.1),
    ]
    .iter()
    .map(|c| c.0 * u[0] + c.1 * u[1])
    .collect();
    let lo = along.iter().copied().fold(f64::INFINITY, f64::min) - 0.01 * diag;
    let hi = along.iter().copied().fold(f64::NEG_INFINITY, f64::max) + 0.01 * diag;
    // 0.05 mm steps: every lobe of these surfaces spans hundreds
    let n = ((hi - lo) / 0.05) as usize;
    let inside = |x: f64, y: f64| x >= s.x.0 && x <= s.x.1 && y >= s.y.0 && y <= s.y.1;
    // b at a, by Newton on g(b) = o d_z + b v_z − f(p_xy) from `b0`
    let solve = |a: f64, b0: f64| -> Option<(f64, f64, f64)> {
        let mut b = b0;
        for _ in 0..60 {
            let (x, y) = (
                offset * d[0] + a * u[0] + b * v[0],
                offset * d[1] + a * u[1] + b * v[1],
            );
            let j = (s.jet)(x, y);
            let g = offset * d[2] + b * v[2] - j.0;
            let gb = v[2] - (j.1 * v[0] + j.2 * v[1]);
            if gb == 0.0 || !gb.is_finite() {
                return None;
            }
            let step = g / gb;
            b -= step;
            if step.abs() <= 1e-13 * (1.0 + b.abs()) {
                let (x, y) = (
                    offset * d[0] + a * u[0] + b * v[0],
                    offset * d[1] + a * u[1] + b * v[1],
                );
                return Some((b, x, y));
            }
        }
        None
    };
    let mut at: Vec<f64> = Vec::new();
    let mut last = 0i8;
    let mut span: Option<(f64, f64)> = None;
    let mut b = if v[2].abs() > 1e-12 {
        // start from the surface's height at the plane's foot
        let j = (s.jet)(offset * d[0], offset * d[1]);
        (j.0 - offset * d[2]) / v[2]
    } else {
        0.0
    };
    for i in 0..=n {
        let a = lo + (hi - lo) * i as f64 / n as f64;
        let Some((bb, x, y)) = solve(a, b) else {
            continue;
        };
        b = bb;
        if !inside(x, y) {
            continue;
        }
        span = Some(span.map_or((a, a), |(s0, _)| (s0, a)));
        let j = (s.jet)(x, y);
        let (ga, gb) = (-(j.1 * u[0] + j.2 * u[1]), v[2] - (j.1 * v[0] + j.2 * v[1]));
        let bp = -ga / gb;
        let w = [u[0] + bp * v[0], u[1] + bp * v[1]];
        let q = j.3 * w[0] * w[0] + 2.0 * j.4 * w[0] * w[1] + j.5 * w[1] * w[1];
        let sgn = if q > 0.0 {
            1
        } else if q < 0.0 {
            -1
        } else {
            0
        };
        if sgn != 0 {
            if last != 0 && sgn != last {
                at.push(a);
            }
            last = sgn;
        }
    }
    // a sign change within END_GUARD of an end bounds a lobe that departs from its chord
    // by less than 10⁻⁶ mm on these surfaces: below any floor, counted by nobody
    let (s0, s1) = span.unwrap_or_default();
    at.retain(|&a| a > s0 + END_GUARD && a < s1 - END_GUARD);
    (at, (s0, s1))
}

/// Sign changes this close to a section's end (mm) are not counted.
pub const END_GUARD: f64 = 0.5;
