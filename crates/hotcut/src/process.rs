//! What a task's run says about it as a production process ([`ProcessFigures`](crate::process::ProcessFigures)): the
//! blocks bought, the material cut away and left for milling, the heated path of its
//! programs and how close it comes to the design. Each task that is a process measures its
//! own run ([`crate::task::Task::figures`]); the `Compare` task sets them side by side, so
//! the numbers it compares are the ones each task's own report gives.
//!
//! The geometry helpers here (a design's solid inside a box, a surface's area over a
//! footprint) are shared by the tasks and `Compare`, so every process measures the design
//! the same way.

use geom::surface::Surface;
use nalgebra::Vector3;
use schemars::JsonSchema;
use serde::Serialize;

/// The tool that cuts a process's programs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, JsonSchema)]
pub enum Cutter {
    /// A hot wire (ruled cuts).
    Wire,
    /// A bent hot blade (elastica sweeps).
    Blade,
    /// No thermal cut: the stock goes to the milling machine as bought.
    None,
}

/// RMS and largest deviation of a process's result from the design, job units.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct Deviation {
    /// Root mean square.
    pub rms: f64,
    /// Largest.
    pub max: f64,
}

/// A task's run measured as a production process (thesis ch. 6): what `Compare` reads.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
#[schemars(deny_unknown_fields)]
pub struct ProcessFigures {
    /// Why the run does not make the design within the tolerance (the constraint that
    /// fails and where), or `None` when it does.
    pub why_not: Option<String>,
    /// Blocks bought.
    pub blocks: usize,
    /// EPS bought: the blocks' volume, job units³.
    pub stock_volume: f64,
    /// The design's solid inside the blocks, job units³: what stays.
    pub part_volume: f64,
    /// Material the thermal cuts leave for milling (roughing), job units³; the whole
    /// `stock_volume − part_volume` for stock that is milled as bought, 0 when the cuts
    /// finish the surface.
    pub milling_volume: f64,
    /// Area of the design surface that milling finishes, job units² (0 when no milling).
    pub milled_area: f64,
    /// Which tool makes the thermal cuts.
    pub cutter: Cutter,
    /// The heated path of every program, summed, job units (0 without thermal cuts).
    pub cut_length: f64,
    /// The speed its programs cut at (their heated path over their cutting time), job
    /// units per second (0 without thermal cuts).
    pub cut_speed: f64,
    /// Heated dwells the programs make besides cutting (preheat before each cut),
    /// seconds in all.
    pub dwell_s: f64,
    /// Times a block is mounted for the thermal cuts (a block turned between two cuts
    /// counts again; 0 without thermal cuts).
    pub setups: usize,
    /// Machine programs (wire cuts, robot programs).
    pub programs: usize,
    /// Deviation of the thermally cut surface from the design (`None` when milling
    /// finishes the surface: its fidelity is the tool's scallop).
    pub deviation: Option<Deviation>,
}

impl ProcessFigures {
    /// Stock milled as bought: `blocks` of `stock` volume in all, the design's `part`
    /// kept, everything else milled away, `area` finished (job units).
    pub fn milled(
        blocks: usize,
        stock: f64,
        part: f64,
        area: f64,
        why_not: Option<String>,
    ) -> Self {
        Self {
            why_not,
            blocks,
            stock_volume: stock,
            part_volume: part,
            milling_volume: (stock - part).max(0.0),
            milled_area: area,
            cutter: Cutter::None,
            cut_length: 0.0,
            cut_speed: 0.0,
            dwell_s: 0.0,
            setups: 0,
            programs: 0,
            deviation: None,
        }
    }

    /// Whether the run makes the design within the tolerance.
    pub fn feasible(&self) -> bool {
        self.why_not.is_none()
    }
}

/// Grid cells per side of the midpoint rule that measures a design's solid in a box.
pub const VOLUME_GRID: usize = 200;

/// The design's solid inside the box `[min, max]`: the volume between the box's floor and
/// the design surface (its upper envelope, clipped to the box), by the midpoint rule on a
/// `grid × grid` lattice of the box's footprint (`ruled::volumes`, the measure of thesis
/// Table 2.1), job units³. A surface that is not over a cell counts nothing there.
///
/// # Errors
/// When the surface cannot be turned into a height function.
pub fn solid_in_box(
    surface: &Surface,
    min: [f64; 3],
    max: [f64; 3],
    grid: usize,
) -> Result<f64, String> {
    let height = ruled::Height::new(surface).map_err(|e| e.to_string())?;
    solid_under(&height, min, max, grid)
}

/// [`solid_in_box`] with the height function made once.
///
/// # Errors
/// When the box is empty.
pub fn solid_under(
    height: &ruled::Height,
    min: [f64; 3],
    max: [f64; 3],
    grid: usize,
) -> Result<f64, String> {
    let size: Vec<f64> = (0..3).map(|i| max[i] - min[i]).collect();
    if size.iter().any(|s| !(*s > 0.0)) || grid == 0 {
        return Err(format!("empty box {min:?}–{max:?}"));
    }
    let (dx, dy) = (size[0] / grid as f64, size[1] / grid as f64);
    let mut sum = 0.0;
    for i in 0..grid {
        let x = min[0] + (i as f64 + 0.5) * dx;
        for j in 0..grid {
            let y = min[1] + (j as f64 + 0.5) * dy;
            if let Some(z) = height.at(x, y) {
                sum += (z.clamp(min[2], max[2]) - min[2]) * dx * dy;
            }
        }
    }
    Ok(sum)
}

/// Area of the surface's triangles (its mesh, or `n × n` cells of a height field or
/// spline) whose centroid lies over the footprint `[min, max]` (x and y), job units².
///
/// # Errors
/// When the surface cannot be meshed.
pub fn area_over(surface: &Surface, min: [f64; 2], max: [f64; 2], n: usize) -> Result<f64, String> {
    let mesh = match surface {
        Surface::Mesh(m) => m.clone(),
        other => other.to_mesh(n).map_err(|e| e.to_string())?,
    };
    let inside =
        |c: &Vector3<f64>| c.x >= min[0] && c.x <= max[0] && c.y >= min[1] && c.y <= max[1];
    let mut area = 0.0;
    for f in 0..mesh.faces().len() {
        let [a, b, c] = mesh.triangle(f);
        if inside(&((a + b + c) / 3.0)) {
            area += 0.5 * (b - a).cross(&(c - a)).norm();
        }
    }
    Ok(area)
}

/// The design's solid inside an oriented block: `origin` its corner, `axes` its unit edge
/// directions (the first two horizontal, the third up), `size` its edges. By the midpoint
/// rule on a `grid × grid` lattice of its two horizontal edges, each column from the
/// block's floor to the surface (clipped to the block), job units³.
///
/// # Errors
/// When the block's third axis is not up (a tilted block).
pub fn solid_in_block(
    height: &ruled::Height,
    origin: [f64; 3],
    axes: [Vector3<f64>; 3],
    size: [f64; 3],
    grid: usize,
) -> Result<f64, String> {
    if !(axes[2].z > 0.5) || grid == 0 {
        return Err(format!("the block's up axis {:?} is not vertical", axes[2]));
    }
    let o = Vector3::from(origin);
    let (da, db) = (size[0] / grid as f64, size[1] / grid as f64);
    let mut sum = 0.0;
    for i in 0..grid {
        for j in 0..grid {
            let p = o + axes[0] * ((i as f64 + 0.5) * da) + axes[1] * ((j as f64 + 0.5) * db);
            if let Some(z) = height.at(p.x, p.y) {
                sum += ((z - p.z) / axes[2].z).clamp(0.0, size[2]);
            }
        }
    }
    Ok(sum * da * db)
}

/// The fields of a count table that are not 0, as `name n, name n` (`none` when all are).
pub fn nonzero(counts: &impl Serialize) -> String {
    let v = serde_json::to_value(counts).unwrap_or_default();
    let list: Vec<String> = v
        .as_object()
        .into_iter()
        .flatten()
        .filter(|(_, n)| n.as_u64().is_some_and(|n| n > 0))
        .map(|(k, n)| format!("{k} {n}"))
        .collect();
    if list.is_empty() {
        "none".into()
    } else {
        list.join(", ")
    }
}
