//! Milling the stock as bought: the job's `block` repeated over the design's bounding
//! box, measured on the design (its solid in the blocks, the area milling finishes).

use geom::surface::Surface;

use crate::process::{self, ProcessFigures};

/// Most blocks a block grid may hold (`block.size` against the design's extent).
pub const MAX_GRID_BLOCKS: f64 = 10_000.0;

/// The grid of blocks of `size` that covers `surface`'s bounding box, starting at
/// `origin` (the box's minimum corner when `None`): blocks per axis, and the start.
pub fn grid(surface: &Surface, size: [f64; 3], origin: Option<[f64; 3]>) -> ([usize; 3], [f64; 3]) {
    let b = surface.aabb();
    let (lo, hi) = ([b.min.x, b.min.y, b.min.z], [b.max.x, b.max.y, b.max.z]);
    let start = origin.unwrap_or(lo);
    let mut n = [1usize; 3];
    for k in 0..3 {
        let cells = ((hi[k] - start[k]) / size[k]).ceil();
        n[k] = if cells.is_nan() || cells < 1.0 {
            1
        } else {
            // an infinite count (a block of no size) is capped, and refused at validation
            cells.min(MAX_GRID_BLOCKS) as usize
        };
    }
    (n, start)
}

/// How many blocks [`grid`] holds (as a float, for the estimate).
pub fn grid_blocks(surface: &Surface, size: [f64; 3], origin: Option<[f64; 3]>) -> f64 {
    let (n, _) = grid(surface, size, origin);
    n.iter().map(|&k| k as f64).product()
}

/// Milling figures of the block grid: a closed mesh is milled all round (its volume is
/// kept, its area finished); an open surface is a mould, everything above it in the blocks
/// milled away (the solid under it kept, its area over the grid finished).
///
/// # Errors
/// When the surface cannot be measured (a spline that cannot be meshed).
pub fn figures(
    surface: &Surface,
    size: [f64; 3],
    origin: Option<[f64; 3]>,
) -> Result<ProcessFigures, String> {
    let (n, start) = grid(surface, size, origin);
    let blocks = n[0] * n[1] * n[2];
    let stock = blocks as f64 * size[0] * size[1] * size[2];
    let top = |k: usize| start[k] + n[k] as f64 * size[k];
    let (part, area) = match surface {
        Surface::Mesh(m) if m.topology().boundary_edges == 0 => (m.volume().abs(), m.area()),
        _ => {
            let height = ruled::Height::new(surface).map_err(|e| e.to_string())?;
            let mut part = 0.0;
            // column by column, so each block's footprint gets its own midpoint lattice
            for i in 0..n[0] {
                for j in 0..n[1] {
                    let min = [
                        start[0] + i as f64 * size[0],
                        start[1] + j as f64 * size[1],
                        start[2],
                    ];
                    let max = [min[0] + size[0], min[1] + size[1], top(2)];
                    part += process::solid_under(&height, min, max, process::VOLUME_GRID)?;
                }
            }
            let area = process::area_over(
                surface,
                [start[0], start[1]],
                [top(0), top(1)],
                process::VOLUME_GRID,
            )?;
            (part, area)
        }
    };
    let b = surface.aabb();
    let lo = [b.min.x, b.min.y, b.min.z];
    let outside = (0..3).find(|&k| lo[k] < start[k] - 1e-9 * size[k]);
    let why_not = match outside {
        Some(k) => Some(format!(
            "the design reaches {} = {} below the blocks' origin ({}): the stock does not hold it",
            ["x", "y", "z"][k],
            lo[k],
            start[k]
        )),
        None if !(part > 0.0) => Some("the design has no solid inside the blocks".into()),
        None => None,
    };
    Ok(ProcessFigures::milled(blocks, stock, part, area, why_not))
}
