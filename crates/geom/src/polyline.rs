//! Planar polylines given as point lists `[[x, y], …]`: cumulative chord lengths, the
//! distance from a point, and angles brought within one turn. The one copy of these helpers
//! every crate of the workspace uses.

/// Cumulative chord lengths of `points`: `s[0] = 0`, `s[i] = s[i−1] + |pᵢ − pᵢ₋₁|` (each
/// chord by `hypot`, summed in order); empty for no points.
///
/// ```
/// use geom::polyline::chord_lengths;
/// assert_eq!(chord_lengths(&[[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]]), [0.0, 5.0, 6.0]);
/// assert!(chord_lengths(&[]).is_empty());
/// ```
pub fn chord_lengths(points: &[[f64; 2]]) -> Vec<f64> {
    let mut s = Vec::with_capacity(points.len());
    if points.is_empty() {
        return s;
    }
    s.push(0.0);
    for w in points.windows(2) {
        s.push(s[s.len() - 1] + (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]));
    }
    s
}

/// Length of the polyline `points`: the sum of its chords in order (0 for fewer than two
/// points); the last of [`chord_lengths`].
///
/// ```
/// use geom::polyline::{chord_lengths, length};
/// let p = [[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]];
/// assert_eq!(length(&p), 6.0);
/// assert_eq!(length(&p), *chord_lengths(&p).last().unwrap());
/// assert_eq!(length(&p[..1]), 0.0);
/// ```
pub fn length(points: &[[f64; 2]]) -> f64 {
    points
        .windows(2)
        .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
        .fold(0.0, |s, c| s + c)
}

/// Distance from `q` to the polyline `poly`: to its nearest segment, to its one point when
/// it has one, ∞ when it has none.
///
/// ```
/// use geom::polyline::distance_to_polyline;
/// let poly = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0]];
/// assert_eq!(distance_to_polyline([2.0, -1.5], &poly), 1.5); // foot inside the first segment
/// assert_eq!(distance_to_polyline([5.0, 2.0], &poly), 1.0); // the second
/// assert_eq!(distance_to_polyline([-3.0, 4.0], &poly), 5.0); // beyond the first vertex
/// assert_eq!(distance_to_polyline([3.0, 4.0], &[[0.0, 0.0]]), 5.0);
/// assert_eq!(distance_to_polyline([1.0, 1.0], &[]), f64::INFINITY);
/// ```
pub fn distance_to_polyline(q: [f64; 2], poly: &[[f64; 2]]) -> f64 {
    // squared distances in the loop, one square root at the end
    let mut best = f64::INFINITY;
    for w in poly.windows(2) {
        let (a, b) = (w[0], w[1]);
        let (dx, dy) = (b[0] - a[0], b[1] - a[1]);
        let (ex, ey) = (q[0] - a[0], q[1] - a[1]);
        let len2 = dx * dx + dy * dy;
        let t = if len2 > 0.0 {
            ((ex * dx + ey * dy) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let (rx, ry) = (ex - t * dx, ey - t * dy);
        best = best.min(rx * rx + ry * ry);
    }
    if poly.len() == 1 {
        let (rx, ry) = (q[0] - poly[0][0], q[1] - poly[0][1]);
        best = rx * rx + ry * ry;
    }
    best.sqrt()
}

/// Angle `a` less the whole turns nearest to it: within [−π, π] (either sign at a half
/// turn). What the elastica fits compare turning angles with.
///
/// ```
/// use geom::polyline::wrap_angle;
/// use std::f64::consts::PI;
/// assert_eq!(wrap_angle(0.25), 0.25);
/// assert!((wrap_angle(0.25 + 6.0 * PI) - 0.25).abs() < 1e-14);
/// assert!((wrap_angle(1.5 * PI) + 0.5 * PI).abs() < 1e-15);
/// ```
pub fn wrap_angle(a: f64) -> f64 {
    let tau = std::f64::consts::TAU;
    a - (a / tau).round() * tau
}

/// The principal value of angle `a`: within (−π, π], a half turn always +π. What the
/// design crate states end angles and tangent jumps in. It differs from [`wrap_angle`]
/// at a half turn and in how the last bits round; each crate keeps its own convention so
/// that its results stay what they were.
///
/// ```
/// use geom::polyline::principal_angle;
/// use std::f64::consts::PI;
/// assert!((principal_angle(0.25 + 6.0 * PI) - 0.25).abs() < 1e-14);
/// assert_eq!(principal_angle(PI), PI);
/// assert_eq!(principal_angle(-PI), PI);
/// ```
pub fn principal_angle(a: f64) -> f64 {
    let pi = std::f64::consts::PI;
    pi - (pi - a).rem_euclid(2.0 * pi)
}
