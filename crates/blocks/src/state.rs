//! A segmentation in progress: the blocks, how many blocks cover each sample, and the
//! objective E of eq. 3.3.
//!
//! Every change goes through [`State::place`](crate::state::State::place) or [`State::remove`](crate::state::State::remove), which keep the cover
//! counts exact and (in debug builds) assert that every sample the change touched is
//! still covered: the invariant "every sample covered" holds after every operation.

use nalgebra::Vector3;

use crate::cuboid::{overlap_volume, Cuboid};
use crate::samples::Samples;

/// Blocks and cover counts over a fixed sample set.
#[derive(Debug, Clone)]
pub struct State<'s> {
    samples: &'s Samples,
    /// All blocks ever placed; removed ones stay with `alive = false` so indices are stable.
    pub blocks: Vec<Cuboid>,
    /// Whether each block is still in the segmentation.
    pub alive: Vec<bool>,
    count: Vec<u16>,
    /// Exponent p of eq. 3.3.
    p: f64,
    /// ε of eq. 3.3.
    epsilon: f64,
    /// Volume V of one block.
    volume: f64,
    /// Check every sample after every operation (tests).
    pub paranoid: bool,
}

impl<'s> State<'s> {
    /// A state with the given blocks, all alive, cover counts computed.
    pub fn new(samples: &'s Samples, blocks: Vec<Cuboid>, p: f64, epsilon: f64) -> Self {
        let volume = blocks.first().map_or(0.0, Cuboid::volume);
        let mut s = Self {
            samples,
            alive: vec![true; blocks.len()],
            blocks,
            count: vec![0; samples.points.len()],
            p,
            epsilon,
            volume,
            paranoid: false,
        };
        for i in 0..s.blocks.len() {
            s.cover(i, 1);
        }
        s
    }

    /// The samples.
    pub fn samples(&self) -> &'s Samples {
        self.samples
    }

    /// Number of blocks in the segmentation.
    pub fn len(&self) -> usize {
        self.alive.iter().filter(|&&a| a).count()
    }

    /// Whether no block is left.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Indices of the blocks in the segmentation, ascending.
    pub fn alive_ids(&self) -> Vec<usize> {
        (0..self.blocks.len()).filter(|&i| self.alive[i]).collect()
    }

    /// Samples not covered by any block.
    pub fn uncovered(&self) -> usize {
        self.count.iter().filter(|&&c| c == 0).count()
    }

    /// How many blocks cover sample `id`.
    pub fn count(&self, id: usize) -> u16 {
        self.count[id]
    }

    /// Calls `f` with every sample block `b` covers (inside it shrunk by the margin).
    pub fn for_each_covered(&self, b: &Cuboid, f: impl FnMut(usize)) {
        self.samples.for_each_covered(b, f);
    }

    /// Sample ids covered by block `i` and by no other block.
    pub fn exclusive(&self, i: usize) -> Vec<usize> {
        let mut out = Vec::new();
        self.for_each_covered(&self.blocks[i], |id| {
            if self.count[id] == 1 {
                out.push(id);
            }
        });
        out
    }

    /// Whether block `i` can go: every sample it covers is covered by another block.
    pub fn removable(&self, i: usize) -> bool {
        !self
            .samples
            .any_covered(&self.blocks[i], |id| self.count[id] < 2)
    }

    /// Removes block `i` (which must be removable).
    pub fn remove(&mut self, i: usize) {
        debug_assert!(self.alive[i]);
        self.cover(i, -1);
        self.alive[i] = false;
        self.check_touched(&self.blocks[i].clone());
    }

    /// Moves block `i` to `to`; the caller guarantees that every sample only `i` covers
    /// is covered by `to`.
    pub fn place(&mut self, i: usize, to: Cuboid) {
        let from = self.blocks[i];
        self.cover(i, -1);
        self.blocks[i] = to;
        self.cover(i, 1);
        self.check_touched(&from);
    }

    /// Replaces a group of blocks: `ids` lose their cover, the first `poses.len()` of them
    /// get the new poses and cover again, the rest are removed.
    pub fn replace(&mut self, ids: &[usize], poses: &[Cuboid]) {
        let old: Vec<Cuboid> = ids.iter().map(|&i| self.blocks[i]).collect();
        for &i in ids {
            self.cover(i, -1);
        }
        for (k, &i) in ids.iter().enumerate() {
            if let Some(b) = poses.get(k) {
                self.blocks[i] = *b;
                self.cover(i, 1);
            } else {
                self.alive[i] = false;
            }
        }
        for b in &old {
            self.check_touched(b);
        }
    }

    fn cover(&mut self, i: usize, delta: i32) {
        let count = &mut self.count;
        self.samples.for_each_covered(&self.blocks[i], |id| {
            count[id] = (count[id] as i32 + delta) as u16;
        });
    }

    /// The invariant after an operation that took cover from the samples of `b`.
    fn check_touched(&self, b: &Cuboid) {
        if self.paranoid {
            assert_eq!(self.uncovered(), 0, "a sample lost its last block");
        } else if cfg!(debug_assertions) {
            self.for_each_covered(b, |id| {
                debug_assert!(self.count[id] > 0, "sample {id} lost its last block");
            });
        }
    }

    /// Σ_j (2Ω(b, b_j))^p over the blocks in the segmentation other than `skip`.
    pub fn pair_sum(&self, skip: usize, b: &Cuboid) -> f64 {
        let mut s = 0.0;
        for j in 0..self.blocks.len() {
            if j != skip && self.alive[j] {
                let o = overlap_volume(b, &self.blocks[j]);
                if o > 0.0 {
                    s += (2.0 * o).powf(self.p);
                }
            }
        }
        s
    }

    /// The objective E of eq. 3.3.
    pub fn energy(&self) -> f64 {
        let ids = self.alive_ids();
        let n = ids.len() as f64;
        if ids.is_empty() {
            return 0.0;
        }
        let mut sum = 0.0;
        for (a, &i) in ids.iter().enumerate() {
            for &j in &ids[a + 1..] {
                let o = overlap_volume(&self.blocks[i], &self.blocks[j]);
                if o > 0.0 {
                    sum += (2.0 * o).powf(self.p);
                }
            }
        }
        n - sum / (n * ((n - 1.0 + self.epsilon) * self.volume).powf(self.p))
    }

    /// The scale of one pair term, `(2V)^p`, for tolerances.
    pub fn pair_scale(&self) -> f64 {
        (2.0 * self.volume).powf(self.p)
    }

    /// Model points of the given sample ids.
    pub fn points(&self, ids: &[usize]) -> Vec<Vector3<f64>> {
        ids.iter().map(|&id| self.samples.points[id]).collect()
    }
}
