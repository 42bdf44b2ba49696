//! The three operations of §3.3 as proposals: each takes the samples a block (or a group)
//! alone covers and returns new poses under which those samples stay covered.
//!
//! "Covered" uses the block shrunk by the sampling margin, so every proposal works with
//! the shrunk half sizes `h' = h − margin`, less a rounding guard of [`GUARD`](crate::moves::GUARD) × h so that
//! points placed on a face stay inside after the transform is rounded. Callers still
//! verify every proposal on the points ([`keeps`](crate::moves::keeps)).

use nalgebra::{Matrix3, Rotation3, UnitQuaternion, Vector3};

use crate::cuboid::Cuboid;
use crate::obb::{box_in_frame, min_box, BoxFit};

/// The six permutations of three axes, identity first.
const PERMUTATIONS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

/// Relative guard subtracted from the shrunk half sizes.
pub const GUARD: f64 = 1e-9;

/// The half sizes proposals work with: `h − margin − GUARD·h`.
fn shrunk_half(half: &Vector3<f64>, margin: f64) -> Vector3<f64> {
    half.map(|h| h - margin - GUARD * h)
}

/// Whether every point lies in one of `blocks` shrunk by `margin`.
pub fn keeps(blocks: &[Cuboid], pts: &[Vector3<f64>], margin: f64) -> bool {
    pts.iter()
        .all(|p| blocks.iter().any(|b| b.contains(p, margin)))
}

/// §3.3.2: the translation `(x⁺ − x⁻, y⁺ − y⁻, z⁺ − z⁻)` in the block's frame, where
/// `x⁺` (`x⁻`) is the most the block can move along +x (−x) with `exclusive` still inside
/// it. `None` when there is nothing to keep or the move is negligible.
pub fn translation(b: &Cuboid, exclusive: &[Vector3<f64>], margin: f64) -> Option<Cuboid> {
    let (lo, hi) = local_bounds(b, exclusive)?;
    let shrunk = shrunk_half(&b.half, margin);
    // x⁺ = lo + h', x⁻ = h' − hi, so x⁺ − x⁻ = lo + hi.
    let t = Vector3::from_fn(|k, _| {
        let plus = lo[k] + shrunk[k];
        let minus = shrunk[k] - hi[k];
        plus.max(0.0) - minus.max(0.0)
    });
    if t.norm() <= 1e-9 * b.half.norm() {
        return None;
    }
    Some(Cuboid::new(b.center + b.axes() * t, b.rotation, b.half))
}

/// §3.3.3: the block turned onto the minimal box of `exclusive`, that box in each of its
/// eight corners. Empty when the box does not fit in the (shrunk) block.
pub fn rotations(b: &Cuboid, exclusive: &[Vector3<f64>], margin: f64) -> Vec<Cuboid> {
    let Some(fit) = min_box(exclusive) else {
        return Vec::new();
    };
    let shrunk = shrunk_half(&b.half, margin);
    let Some((axes, size)) = fit_axes(&fit, &shrunk) else {
        return Vec::new();
    };
    let rotation = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(axes));
    (0..8)
        .map(|corner| {
            let offset = Vector3::from_fn(|k, _| {
                let slack = shrunk[k] - size[k] / 2.0;
                if corner & (1 << k) == 0 {
                    -slack
                } else {
                    slack
                }
            });
            Cuboid::new(fit.center + axes * offset, rotation, b.half)
        })
        .collect()
}

/// §3.3.4: a regular grid of blocks over the minimal box of `group_exclusive`, keeping
/// only the grid blocks that cover some of those points, or `None` when that needs more
/// than `available` blocks. The grid is centred on the box; its shrunk blocks tile it
/// exactly.
///
/// Two refinements of the thesis, which counts every cell of a grid over the minimal box:
/// cells holding none of the points are not counted (they would be removed at once), and
/// besides the minimal box, the boxes of the points in the orientations `frames` (the
/// group's blocks) are tried, the grid needing the fewest blocks winning (ties: the
/// minimal box, then `frames` in order) — the box of least volume is not always the one
/// of fewest cells, and an aligned neighbourhood can stay aligned.
pub fn alignment(
    half: &Vector3<f64>,
    group_exclusive: &[Vector3<f64>],
    margin: f64,
    available: usize,
    frames: &[UnitQuaternion<f64>],
) -> Option<Vec<Cuboid>> {
    let min = min_box(group_exclusive)?;
    // Candidate orientations, each once (aligned neighbourhoods share them).
    let mut candidates = vec![min.rotation];
    for r in frames {
        if candidates.iter().all(|t| t.angle_to(r) >= 1e-9) {
            candidates.push(*r);
        }
    }
    // The orientation is chosen on an evenly thinned subset (the choice is a heuristic;
    // the grid of the chosen one is then built and counted on every point).
    let stride = group_exclusive.len().div_ceil(SELECTION_POINTS).max(1);
    let subset: Vec<Vector3<f64>> = group_exclusive.iter().step_by(stride).copied().collect();
    let grid_in = |pts: &[Vector3<f64>], k: usize| {
        let fit = if k == 0 && pts.len() == group_exclusive.len() {
            min
        } else {
            box_in_frame(pts, candidates[k])
        };
        Grid::over(&fit, half, margin).occupied(pts)
    };
    let mut best = (usize::MAX, 0);
    for k in 0..candidates.len() {
        let n = grid_in(&subset, k).len();
        if n < best.0 {
            best = (n, k);
        }
    }
    let grid = grid_in(group_exclusive, best.1);
    (grid.len() <= available).then_some(grid)
}

/// Most points the alignment's choice of orientation looks at.
const SELECTION_POINTS: usize = 4096;

/// A regular grid of blocks over a box, centred on it, whose blocks shrunk by the margin
/// tile it exactly.
#[derive(Debug, Clone, Copy)]
pub struct Grid {
    center: Vector3<f64>,
    axes: Matrix3<f64>,
    rotation: UnitQuaternion<f64>,
    cells: [usize; 3],
    half: Vector3<f64>,
    shrunk: Vector3<f64>,
}

impl Grid {
    /// The grid over `fit` with the block axes assigned to the box's axes so it needs the
    /// fewest blocks (ties: the first permutation).
    pub fn over(fit: &BoxFit, half: &Vector3<f64>, margin: f64) -> Self {
        let shrunk = shrunk_half(half, margin);
        let fax = fit.axes();
        let mut best: Option<(usize, [usize; 3], [usize; 3])> = None;
        for perm in PERMUTATIONS {
            let n = [0, 1, 2].map(|k| cells(fit.size[perm[k]], 2.0 * shrunk[k]));
            let total = n[0] * n[1] * n[2];
            if best.as_ref().is_none_or(|(t, ..)| total < *t) {
                best = Some((total, n, perm));
            }
        }
        let (_, cells, perm) = best.unwrap_or((1, [1; 3], PERMUTATIONS[0]));
        let axes = permuted(&fax, perm);
        Self {
            center: fit.center,
            axes,
            rotation: UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(axes)),
            cells,
            half: *half,
            shrunk,
        }
    }

    /// The block of cell `idx`.
    fn block(&self, idx: [usize; 3]) -> Cuboid {
        let offset = Vector3::from_fn(|a, _| {
            (2.0 * idx[a] as f64 + 1.0 - self.cells[a] as f64) * self.shrunk[a]
        });
        Cuboid::new(self.center + self.axes * offset, self.rotation, self.half)
    }

    /// Every block of the grid.
    pub fn blocks(&self) -> Vec<Cuboid> {
        let n = self.cells;
        let mut out = Vec::with_capacity(n[0] * n[1] * n[2]);
        for i in 0..n[0] {
            for j in 0..n[1] {
                for k in 0..n[2] {
                    out.push(self.block([i, j, k]));
                }
            }
        }
        out
    }

    /// The blocks of the cells holding some of `pts` (each point in the cell its
    /// coordinates fall in, clamped to the grid), in cell order.
    pub fn occupied(&self, pts: &[Vector3<f64>]) -> Vec<Cuboid> {
        let n = self.cells;
        let mut used = vec![false; n[0] * n[1] * n[2]];
        let scale = self.shrunk.map(|s| 0.5 / s);
        let shift = Vector3::new(n[0] as f64, n[1] as f64, n[2] as f64) / 2.0;
        let cell = |x: f64, a: usize| (x.max(0.0) as usize).min(n[a] - 1);
        for p in pts {
            let f = (self.axes.tr_mul(&(p - self.center))).component_mul(&scale) + shift;
            used[(cell(f.x, 0) * n[1] + cell(f.y, 1)) * n[2] + cell(f.z, 2)] = true;
        }
        let mut out = Vec::new();
        for i in 0..n[0] {
            for j in 0..n[1] {
                for k in 0..n[2] {
                    if used[(i * n[1] + j) * n[2] + k] {
                        out.push(self.block([i, j, k]));
                    }
                }
            }
        }
        out
    }
}

/// Blocks of pitch `pitch` needed to span `length` (at least one).
pub(crate) fn cells(length: f64, pitch: f64) -> usize {
    ((length / pitch) * (1.0 - 1e-12)).ceil().max(1.0) as usize
}

/// The box's axes assigned to the block's axes so the box fits in the shrunk block, and
/// the box's sizes along the block's axes; `None` if no assignment fits.
fn fit_axes(fit: &BoxFit, shrunk: &Vector3<f64>) -> Option<(Matrix3<f64>, Vector3<f64>)> {
    let fax = fit.axes();
    PERMUTATIONS.iter().find_map(|&perm| {
        let size = Vector3::from_fn(|k, _| fit.size[perm[k]]);
        (0..3)
            .all(|k| size[k] <= 2.0 * shrunk[k])
            .then(|| (permuted(&fax, perm), size))
    })
}

/// Columns of `m` in the order `perm`, the last negated if needed to stay a rotation.
fn permuted(m: &Matrix3<f64>, perm: [usize; 3]) -> Matrix3<f64> {
    let mut r = Matrix3::from_columns(&[m.column(perm[0]), m.column(perm[1]), m.column(perm[2])]);
    if r.determinant() < 0.0 {
        let c = -r.column(2);
        r.set_column(2, &c);
    }
    r
}

/// Bounds of the points in the block's frame.
fn local_bounds(b: &Cuboid, pts: &[Vector3<f64>]) -> Option<(Vector3<f64>, Vector3<f64>)> {
    if pts.is_empty() {
        return None;
    }
    Some(pts.iter().fold(
        (Vector3::repeat(f64::MAX), Vector3::repeat(f64::MIN)),
        |(lo, hi), p| {
            let l = b.to_local(p);
            (lo.inf(&l), hi.sup(&l))
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn arb_block() -> impl Strategy<Value = Cuboid> {
        (
            prop::array::uniform3(-2.0..2.0f64),
            prop::array::uniform3(-3.0..3.0f64),
        )
            .prop_map(|(c, r)| {
                Cuboid::new(
                    Vector3::from(c),
                    UnitQuaternion::from_scaled_axis(Vector3::from(r)),
                    Vector3::new(0.5, 0.6, 0.7),
                )
            })
    }

    /// Points strictly inside the block shrunk by `margin`, from unit-cube fractions.
    fn inside(b: &Cuboid, fr: &[[f64; 3]], margin: f64) -> Vec<Vector3<f64>> {
        fr.iter()
            .map(|f| {
                let l = Vector3::from_fn(|k, _| (2.0 * f[k] - 1.0) * (b.half[k] - margin));
                b.to_model(&l)
            })
            .collect()
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// Translation keeps the points covered and mirrors their range in the block.
        #[test]
        fn translation_keeps_exclusive_points(b in arb_block(), fr in prop::collection::vec(prop::array::uniform3(0.0..1.0f64), 1..30)) {
            let m = 0.05;
            let pts = inside(&b, &fr, m);
            if let Some(t) = translation(&b, &pts, m) {
                for p in &pts { prop_assert!(t.contains(p, m - 1e-9)); }
                prop_assert_eq!(t.rotation, b.rotation);
            }
        }

        /// Every rotation proposal covers the points it was made for.
        #[test]
        fn rotations_keep_exclusive_points(b in arb_block(), fr in prop::collection::vec(prop::array::uniform3(0.3..0.7f64), 4..30)) {
            let m = 0.05;
            let pts = inside(&b, &fr, m);
            let props = rotations(&b, &pts, m);
            prop_assert_eq!(props.len(), 8);
            for r in &props {
                for p in &pts { prop_assert!(r.contains(p, m - 1e-9)); }
            }
        }

        /// An alignment grid covers its points.
        #[test]
        fn alignment_grid_covers(fr in prop::collection::vec(prop::array::uniform3(0.0..1.0f64), 4..60), ext in prop::array::uniform3(0.2..3.0f64)) {
            let half = Vector3::new(0.5, 0.5, 0.5);
            let m = 0.05;
            let pts: Vec<Vector3<f64>> = fr.iter().map(|f| Vector3::new(f[0] * ext[0], f[1] * ext[1] - f[0], f[2] * ext[2])).collect();
            let grid = alignment(&half, &pts, m, usize::MAX, &[]).unwrap();
            for p in &pts {
                prop_assert!(grid.iter().any(|g| g.contains(p, m - 1e-9)));
            }
            prop_assert!(alignment(&half, &pts, m, grid.len() - 1, &[]).is_none());
        }
    }

    /// Cells holding no point are not counted: an L of points over a 2 × 2 grid needs 3.
    #[test]
    fn alignment_counts_occupied_cells_only() {
        let half = Vector3::repeat(0.5);
        let mut pts = Vec::new();
        for (x, y) in [(0.1, 0.1), (1.9, 0.1), (0.1, 1.9), (0.9, 0.2), (0.2, 0.9)] {
            pts.push(Vector3::new(x, y, 0.0));
            pts.push(Vector3::new(x, y, 0.9));
        }
        let frame = UnitQuaternion::identity();
        let grid = alignment(&half, &pts, 0.0, 3, &[frame]).unwrap();
        assert_eq!(grid.len(), 3);
        assert!(keeps(&grid, &pts, 0.0));
        assert!(alignment(&half, &pts, 0.0, 2, &[frame]).is_none());
    }

    /// A block-aligned orientation among the frames wins over a tilted minimal box when
    /// it needs fewer blocks.
    #[test]
    fn alignment_tries_the_given_frames() {
        let half = Vector3::repeat(0.5);
        // A 2 × 1 × 1 slab of points (exactly two blocks axis-aligned).
        let mut pts = Vec::new();
        for i in 0..=20 {
            for j in 0..=10 {
                for k in 0..=10 {
                    pts.push(Vector3::new(i as f64, j as f64, k as f64) * 0.0999);
                }
            }
        }
        let grid = alignment(&half, &pts, 0.0, usize::MAX, &[UnitQuaternion::identity()]).unwrap();
        assert_eq!(grid.len(), 2);
        assert!(keeps(&grid, &pts, 0.0));
    }

    #[test]
    fn translation_exact_value() {
        let b = Cuboid::new(
            Vector3::zeros(),
            UnitQuaternion::identity(),
            Vector3::repeat(1.0),
        );
        // Exclusive points in x ∈ [0.2, 0.9] (shrunk half 1.0): x⁺ = 1.2, x⁻ = 0.1 → +1.1.
        let pts = vec![Vector3::new(0.2, 0.0, 0.0), Vector3::new(0.9, 0.0, 0.0)];
        let t = translation(&b, &pts, 0.0).unwrap();
        assert!((t.center - Vector3::new(1.1, 0.0, 0.0)).norm() < 1e-12);
    }
}
