//! A near-minimum-volume oriented bounding box of a point set.
//!
//! The exact minimum box (O'Rourke) has two faces flush with hull edges; we use the common
//! approximation that one face is flush with a face of the convex hull (plus the principal
//! axes as a fallback): for each candidate normal the points are projected to the plane and
//! the minimum-area rectangle of the projection is found over the directions of its 2D
//! hull's edges (the rotating-calipers property). Written here because no crate offers it;
//! the initialization and every rotation and alignment move need it.

use nalgebra::{Matrix3, Rotation3, SymmetricEigen, UnitQuaternion, Vector2, Vector3};

/// An oriented box around points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxFit {
    /// Centre.
    pub center: Vector3<f64>,
    /// Rotation taking the box's axes to model axes.
    pub rotation: UnitQuaternion<f64>,
    /// Full edge lengths along the box's axes (may be 0 for flat or collinear points).
    pub size: Vector3<f64>,
}

impl BoxFit {
    /// The box's axes as the columns of a matrix.
    pub fn axes(&self) -> Matrix3<f64> {
        self.rotation.to_rotation_matrix().into_inner()
    }
}

/// Most hull-face normals tried (the largest faces, after merging near-parallel ones).
const MAX_NORMALS: usize = 24;

/// A near-minimum-volume box around `points`; `None` for no points or non-finite ones.
///
/// ```
/// use blocks::min_box;
/// use nalgebra::{UnitQuaternion, Vector3};
/// // the corners of a 2 × 1 × 0.5 box turned 30° about z
/// let turn = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 30f64.to_radians());
/// let pts: Vec<_> = (0..8)
///     .map(|i| turn * Vector3::new(2.0 * (i & 1) as f64, ((i >> 1) & 1) as f64, 0.5 * ((i >> 2) & 1) as f64))
///     .collect();
/// let b = min_box(&pts).ok_or("no box")?;
/// // the box is found again, not its larger axis-aligned box
/// let mut size: Vec<f64> = b.size.iter().copied().collect();
/// size.sort_by(f64::total_cmp);
/// assert!((size[0] - 0.5).abs() < 1e-9 && (size[1] - 1.0).abs() < 1e-9 && (size[2] - 2.0).abs() < 1e-9);
/// assert!(min_box(&[]).is_none());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub fn min_box(points: &[Vector3<f64>]) -> Option<BoxFit> {
    if points.is_empty() || points.iter().any(|p| !p.iter().all(|v| v.is_finite())) {
        return None;
    }
    let mut normals = principal_axes(points);
    let reduced = extremes(points);
    let mut support: Vec<Vector3<f64>> = reduced.clone();
    if reduced.len() >= 4 {
        if let Ok(hull) = geom::hull::convex_hull(&reduced) {
            support = hull.vertices().to_vec();
            let mut faces: Vec<(f64, Vector3<f64>)> = hull
                .faces()
                .iter()
                .map(|f| {
                    let [a, b, c] = f.map(|i| hull.vertices()[i as usize]);
                    let n = (b - a).cross(&(c - a));
                    (n.norm(), n)
                })
                .filter(|(a, _)| *a > 0.0)
                .collect();
            faces.sort_by(|a, b| b.0.total_cmp(&a.0));
            let mut hull_normals: Vec<Vector3<f64>> = Vec::new();
            for (a, n) in faces {
                let n = n / a;
                if hull_normals.iter().all(|m| m.dot(&n).abs() < 0.9998) {
                    hull_normals.push(n);
                    if hull_normals.len() == MAX_NORMALS {
                        break;
                    }
                }
            }
            normals.extend(hull_normals);
        }
    }
    let extent = {
        let (lo, hi) = bounds(&support);
        (hi - lo).norm().max(f64::MIN_POSITIVE)
    };
    let eta = 1e-9 * extent;
    let mut best: Option<(f64, Matrix3<f64>)> = None;
    for n in &normals {
        let frame = frame_for(n, &support);
        let (lo, hi) = local_bounds(&frame, &support);
        let s = hi - lo;
        let measure = (s.x + eta) * (s.y + eta) * (s.z + eta);
        // a candidate replaces the best only when smaller beyond rounding (ties keep the
        // first, whatever the unit)
        if best
            .as_ref()
            .is_none_or(|(m, _)| measure < *m * (1.0 - 1e-9))
        {
            best = Some((measure, frame));
        }
    }
    let (_, frame) = best?;
    // The frame was chosen on a subset; the box bounds every point.
    let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(frame));
    Some(box_with(points, &frame, rotation))
}

/// The box around `points` with the given orientation (its axes are `rotation`'s columns).
/// Points must be non-empty and finite.
///
/// ```
/// use blocks::box_in_frame;
/// use nalgebra::{UnitQuaternion, Vector3};
/// let pts = [Vector3::new(0.0, 0.0, 0.0), Vector3::new(4.0, 1.0, 2.0), Vector3::new(1.0, 3.0, 0.0)];
/// // in the model's own axes: the axis-aligned box
/// let b = box_in_frame(&pts, UnitQuaternion::identity());
/// assert!((b.size - Vector3::new(4.0, 3.0, 2.0)).norm() < 1e-12);
/// assert!((b.center - Vector3::new(2.0, 1.5, 1.0)).norm() < 1e-12);
/// ```
pub fn box_in_frame(points: &[Vector3<f64>], rotation: UnitQuaternion<f64>) -> BoxFit {
    box_with(
        points,
        &rotation.to_rotation_matrix().into_inner(),
        rotation,
    )
}

/// The box around `points` along the columns of `frame` (`rotation` as a matrix).
fn box_with(
    points: &[Vector3<f64>],
    frame: &Matrix3<f64>,
    rotation: UnitQuaternion<f64>,
) -> BoxFit {
    let (lo, hi) = local_bounds(frame, points);
    BoxFit {
        center: frame * ((lo + hi) / 2.0),
        rotation,
        size: hi - lo,
    }
}

/// Columns per axis of the grid [`extremes`] thins points with.
const EXTREME_GRID: usize = 10;

/// A subset of the points with (nearly) the same convex hull: in every column of a
/// coarse grid, along each axis, the lowest and highest point. Sets of fewer than
/// `6·EXTREME_GRID²` points are returned whole.
fn extremes(points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let n = EXTREME_GRID;
    if points.len() < 6 * n * n {
        return points.to_vec();
    }
    let (lo, hi) = bounds(points);
    let size = (hi - lo).map(|s| s.max(f64::MIN_POSITIVE));
    let cell = |p: &Vector3<f64>, k: usize| -> usize {
        (((p[k] - lo[k]) / size[k] * n as f64) as usize).min(n - 1)
    };
    // Per axis k and column (a, b) of the other two axes: (min, max) point index along k.
    let mut best = vec![(usize::MAX, usize::MAX); 3 * n * n];
    for (i, p) in points.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = ((k + 1) % 3, (k + 2) % 3);
            let slot = &mut best[(k * n + cell(p, a)) * n + cell(p, b)];
            if slot.0 == usize::MAX || p[k] < points[slot.0][k] {
                slot.0 = i;
            }
            if slot.1 == usize::MAX || p[k] > points[slot.1][k] {
                slot.1 = i;
            }
        }
    }
    let mut ids: Vec<usize> = best
        .into_iter()
        .flat_map(|(a, b)| [a, b])
        .filter(|&i| i != usize::MAX)
        .collect();
    ids.sort_unstable();
    ids.dedup();
    ids.into_iter().map(|i| points[i]).collect()
}

/// The principal axes of the points (eigenvectors of their covariance).
fn principal_axes(points: &[Vector3<f64>]) -> Vec<Vector3<f64>> {
    let c = points.iter().sum::<Vector3<f64>>() / points.len() as f64;
    let cov = points
        .iter()
        .fold(Matrix3::zeros(), |m, p| m + (p - c) * (p - c).transpose());
    let eig = SymmetricEigen::new(cov);
    (0..3)
        .map(|k| eig.eigenvectors.column(k).into_owned())
        .filter(|v: &Vector3<f64>| v.norm() > 0.5)
        .map(|v| v.normalize())
        .collect()
}

/// A right-handed frame with third axis `n` whose first two axes bound the projection
/// of `pts` with the least area.
fn frame_for(n: &Vector3<f64>, pts: &[Vector3<f64>]) -> Matrix3<f64> {
    let n = n.normalize();
    let u = if n.x.abs() < 0.9 {
        n.cross(&Vector3::x())
    } else {
        n.cross(&Vector3::y())
    }
    .normalize();
    let v = n.cross(&u);
    let flat: Vec<Vector2<f64>> = pts
        .iter()
        .map(|p| Vector2::new(p.dot(&u), p.dot(&v)))
        .collect();
    let hull = hull_2d(flat);
    let mut best = (f64::INFINITY, Vector2::new(1.0, 0.0));
    for i in 0..hull.len() {
        let e = hull[(i + 1) % hull.len()] - hull[i];
        let len = e.norm();
        if len <= 0.0 {
            continue;
        }
        let e = e / len;
        let f = Vector2::new(-e.y, e.x);
        let (mut a0, mut a1, mut b0, mut b1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for q in &hull {
            let (a, b) = (q.dot(&e), q.dot(&f));
            a0 = a0.min(a);
            a1 = a1.max(a);
            b0 = b0.min(b);
            b1 = b1.max(b);
        }
        let area = (a1 - a0) * (b1 - b0);
        if area < best.0 * (1.0 - 1e-9) {
            best = (area, e);
        }
    }
    let e = best.1;
    let x = u * e.x + v * e.y;
    let y = n.cross(&x);
    Matrix3::from_columns(&[x, y, n])
}

/// Convex hull of 2D points, counter-clockwise (Andrew's monotone chain).
fn hull_2d(mut p: Vec<Vector2<f64>>) -> Vec<Vector2<f64>> {
    p.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    p.dedup();
    if p.len() < 3 {
        return p;
    }
    let cross = |o: &Vector2<f64>, a: &Vector2<f64>, b: &Vector2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let mut h: Vec<Vector2<f64>> = Vec::with_capacity(2 * p.len());
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &Vector2<f64>>> = if pass == 0 {
            Box::new(p.iter())
        } else {
            Box::new(p.iter().rev())
        };
        for q in iter {
            while h.len() >= start + 2 && cross(&h[h.len() - 2], &h[h.len() - 1], q) <= 0.0 {
                h.pop();
            }
            h.push(*q);
        }
        h.pop();
    }
    h
}

fn bounds(pts: &[Vector3<f64>]) -> (Vector3<f64>, Vector3<f64>) {
    pts.iter().fold(
        (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
        |(lo, hi), p| (lo.inf(p), hi.sup(p)),
    )
}

fn local_bounds(frame: &Matrix3<f64>, pts: &[Vector3<f64>]) -> (Vector3<f64>, Vector3<f64>) {
    pts.iter().fold(
        (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
        |(lo, hi), p| {
            let l = frame.tr_mul(p);
            (lo.inf(&l), hi.sup(&l))
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn box_points(
        r: &UnitQuaternion<f64>,
        size: Vector3<f64>,
        c: Vector3<f64>,
    ) -> Vec<Vector3<f64>> {
        let mut pts = Vec::new();
        for i in 0..5 {
            for j in 0..5 {
                for k in 0..5 {
                    let l = Vector3::new(
                        i as f64 / 4.0 - 0.5,
                        j as f64 / 4.0 - 0.5,
                        k as f64 / 4.0 - 0.5,
                    )
                    .component_mul(&size);
                    pts.push(c + r * l);
                }
            }
        }
        pts
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The points of a rotated box are bounded by that box: same volume, all inside.
        #[test]
        fn recovers_a_rotated_box(rv in prop::array::uniform3(-3.0..3.0f64), s in prop::array::uniform3(0.3..2.0f64)) {
            let r = UnitQuaternion::from_scaled_axis(Vector3::from(rv));
            let size = Vector3::from(s);
            let pts = box_points(&r, size, Vector3::new(1.0, -2.0, 0.5));
            let b = min_box(&pts).unwrap();
            let vol = b.size.x * b.size.y * b.size.z;
            prop_assert!((vol - size.x * size.y * size.z).abs() < 1e-6 * vol, "{vol}");
            let ax = b.axes();
            for p in &pts {
                let l = ax.tr_mul(&(p - b.center));
                for k in 0..3 { prop_assert!(l[k].abs() <= b.size[k] / 2.0 + 1e-9); }
            }
            prop_assert!((ax.determinant() - 1.0).abs() < 1e-9);
        }
    }

    #[test]
    fn flat_and_tiny_sets() {
        let pts = vec![
            Vector3::new(0.0, 0.0, 1.0),
            Vector3::new(2.0, 0.0, 1.0),
            Vector3::new(0.0, 1.0, 1.0),
        ];
        let b = min_box(&pts).unwrap();
        let mut s: Vec<f64> = b.size.iter().copied().collect();
        s.sort_by(f64::total_cmp);
        assert!(s[0].abs() < 1e-12, "{s:?}");
        assert!(min_box(&[]).is_none());
        let one = min_box(&[Vector3::new(1.0, 2.0, 3.0)]).unwrap();
        assert_eq!(one.center, Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(one.size, Vector3::zeros());
    }
}
