//! The volumes of thesis Table 2.1 by the midpoint rule on a grid over the block's
//! footprint: the model (the solid between the block's floor and the design surface),
//! and what is left for milling above it after our cuts, after cutting the convex hull,
//! and with the block as it is.

use geom::hull::convex_hull;
use nalgebra::Vector3;

use crate::error::Result;
use crate::frame::Block;
use crate::height::{Height, MeshHeight};

/// Volumes, all divided by the block's volume (Table 2.1's normalisation by the
/// bounding box), and the "more removed" ratios.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, schemars::JsonSchema))]
pub struct Volumes {
    /// Grid cells per side of the midpoint rule.
    pub grid: usize,
    /// The model (below the design surface, inside the block).
    pub model: f64,
    /// Left for milling after our cuts.
    pub ruled: f64,
    /// Left for milling after cutting the model's convex hull.
    pub convex_hull: f64,
    /// Left for milling from the block itself.
    pub bounding_box: f64,
    /// `(hull − ruled) / hull`, in percent: how much more our cuts remove than the hull.
    pub more_than_hull_percent: f64,
    /// `(box − ruled) / box`, in percent.
    pub more_than_box_percent: f64,
}

/// Computes the volumes; `cut(x, y)` is the height the cuts leave (the lowest of all
/// directions' cut surfaces), clipped to the block here.
///
/// # Errors
/// Hull errors for a degenerate model.
pub fn volumes(
    height: &Height,
    block: &Block,
    grid: usize,
    cut: &(dyn Fn(f64, f64) -> f64 + Sync),
) -> Result<Volumes> {
    let size = block.size();
    let (dx, dy) = (size.x / grid as f64, size.y / grid as f64);
    let (z0, z1) = (block.min[2], block.max[2]);
    let clip = |z: f64| z.clamp(z0, z1);
    let (cells, hull) = hull_top(height, block, grid)?;
    let (mut model, mut ruled, mut chull, mut bbox) = (0.0, 0.0, 0.0, 0.0);
    for &(x, y, f) in &cells {
        model += f - z0;
        ruled += (clip(cut(x, y)) - f).max(0.0);
        chull += (hull.at(x, y).map_or(z0, clip) - f).max(0.0);
        bbox += z1 - f;
    }
    let cell = dx * dy / block.volume();
    let pct = |base: f64, v: f64| {
        if base > 0.0 {
            100.0 * (base - v) / base
        } else {
            0.0
        }
    };
    Ok(Volumes {
        grid,
        model: model * cell,
        ruled: ruled * cell,
        convex_hull: chull * cell,
        bounding_box: bbox * cell,
        more_than_hull_percent: pct(chull, ruled),
        more_than_box_percent: pct(bbox, ruled),
    })
}

/// A volume-grid cell centre `(x, y)` and the design height `f` there.
pub type Cell = (f64, f64, f64);

/// The design heights on the volume grid's cell centres (`(x, y, f)`, `f` the block's
/// floor where the surface is not over the block) and the top of the model's convex
/// hull (of the solid between the floor and the surface, sampled on that grid).
///
/// # Errors
/// Hull errors for a degenerate model.
pub fn hull_top(height: &Height, block: &Block, grid: usize) -> Result<(Vec<Cell>, MeshHeight)> {
    let size = block.size();
    let (dx, dy) = (size.x / grid as f64, size.y / grid as f64);
    let (z0, z1) = (block.min[2], block.max[2]);
    let clip = |z: f64| z.clamp(z0, z1);
    let mut points = Vec::new();
    let mut cells = Vec::with_capacity(grid * grid);
    for i in 0..grid {
        for j in 0..grid {
            let (x, y) = (
                block.min[0] + (i as f64 + 0.5) * dx,
                block.min[1] + (j as f64 + 0.5) * dy,
            );
            let f = height.at(x, y).map(clip);
            if let Some(f) = f {
                points.push(Vector3::new(x, y, f));
                points.push(Vector3::new(x, y, z0));
            }
            cells.push((x, y, f.unwrap_or(z0)));
        }
    }
    let hull = MeshHeight::new(&convex_hull(&points)?)?;
    Ok((cells, hull))
}
