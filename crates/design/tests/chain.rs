//! The tangent-continuous construction over three blocks ("Designing for Robotic
//! Hot-Blade Cutting" figs. 13/14), checked independently of the solver: for every piece
//! the elastica's end points and end tangents equal the Bézier's to 1e-9 (relative to the
//! length) and its length to 1e-9 relative; across every block face the neighbouring
//! elastica share their end point to 1e-9 and their tangent to 1e-9 rad. A chain whose
//! legs are not on one line at a face is refused, naming the face.

use design::bezier::{wrap, Bezier};
use design::chain::{elastica_chain, g1_breaks};
use proptest::prelude::*;

/// Three pieces over faces at x = 600 and 1200 (block length 600), the curve's heights
/// `h`, its slopes `t` (radians) at the four faces, leg ratios `r` (fractions of the
/// block length along the tangents).
fn chain(h: [f64; 4], t: [f64; 4], r: [(f64, f64); 3]) -> Vec<Bezier> {
    (0..3)
        .map(|i| {
            let (x0, x1) = (600.0 * i as f64, 600.0 * (i + 1) as f64);
            let a = [x0, h[i]];
            let b = [x1, h[i + 1]];
            let (la, lb) = (600.0 * r[i].0, 600.0 * r[i].1);
            Bezier {
                p: [
                    a,
                    [a[0] + la * t[i].cos(), a[1] + la * t[i].sin()],
                    [b[0] - lb * t[i + 1].cos(), b[1] - lb * t[i + 1].sin()],
                    b,
                ],
            }
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 16, ..ProptestConfig::default() })]

    #[test]
    fn neighbouring_elastica_share_points_and_tangents(
        h in proptest::array::uniform4(-80.0f64..80.0),
        t in proptest::array::uniform4(-0.5f64..0.5),
        r in proptest::array::uniform3((0.25f64..0.45, 0.25f64..0.45)),
    ) {
        let pieces = chain(h, t, r);
        prop_assert!(g1_breaks(&pieces).unwrap().is_empty());
        let proxies = elastica_chain(&pieces).unwrap();
        for (b, p) in pieces.iter().zip(&proxies) {
            let e = p.elastica.evaluator().unwrap();
            let (s, z) = (e.eval(0.0), e.eval(1.0));
            let l = b.length();
            let d = |u: [f64; 2], v: [f64; 2]| (u[0] - v[0]).hypot(u[1] - v[1]);
            prop_assert!(d(s.p, b.p[0]) <= 1e-9 * l && d(z.p, b.p[3]) <= 1e-9 * l);
            prop_assert!(wrap(s.angle - b.start_angle().unwrap()).abs() <= 1e-9);
            prop_assert!(wrap(z.angle - b.end_angle().unwrap()).abs() <= 1e-9);
            prop_assert!((p.elastica.length() / l - 1.0).abs() <= 1e-9);
        }
        for w in proxies.windows(2) {
            let (a, b) = (w[0].elastica.evaluator().unwrap(), w[1].elastica.evaluator().unwrap());
            let (end, start) = (a.eval(1.0), b.eval(0.0));
            let l = w[0].length.min(w[1].length);
            prop_assert!((end.p[0] - start.p[0]).hypot(end.p[1] - start.p[1]) <= 1e-9 * l);
            prop_assert!(wrap(end.angle - start.angle).abs() <= 1e-9);
        }
    }
}

#[test]
fn a_chain_whose_legs_break_at_a_face_is_refused() {
    let mut pieces = chain(
        [0.0, 40.0, -20.0, 10.0],
        [0.2, -0.1, 0.3, 0.0],
        [(0.3, 0.3); 3],
    );
    assert!(elastica_chain(&pieces).is_ok());
    // the second piece's first leg turned by 0.05 rad at the face x = 600
    let [a, b] = [pieces[1].p[0], pieces[1].p[1]];
    let (s, c) = 0.05f64.sin_cos();
    let v = [b[0] - a[0], b[1] - a[1]];
    pieces[1].p[1] = [a[0] + c * v[0] - s * v[1], a[1] + s * v[0] + c * v[1]];
    let breaks = g1_breaks(&pieces).unwrap();
    assert_eq!(breaks.len(), 1);
    assert_eq!(breaks[0].face, 0);
    assert!((breaks[0].angle - 0.05).abs() < 1e-12);
    let e = elastica_chain(&pieces).unwrap_err().to_string();
    assert!(e.contains("between pieces 0 and 1"), "{e}");
    // a gap at the face x = 1200
    pieces[1].p[1] = [a[0] + v[0], a[1] + v[1]];
    pieces[2].p[0][1] += 0.5;
    let breaks = g1_breaks(&pieces).unwrap();
    assert_eq!(breaks.iter().map(|b| b.face).collect::<Vec<_>>(), vec![1]);
}
