//! A cut's wire path on a 4-axis hot-wire machine, the block mounted in its own frame:
//! its `along` axis along the machine's cut, its `across` axis towards tower B, its `up`
//! axis up, its start corner at the machine's `origin`. Every wire position becomes the
//! two points where it crosses the tower planes; the lead-in and lead-out move the first
//! and last positions along the cut until the wire clears the block by `lead`.

use blocks::Cuboid;
use nalgebra::Vector3;
use ruled::wire::{WireParams, WirePath, WireStep};

use crate::cuts::{Cut, Mount, WireLine};

/// The block's frame on the machine for one cut.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MachineFrame {
    /// Model vector along the cut.
    pub along: Vector3<f64>,
    /// Model vector towards tower B.
    pub across: Vector3<f64>,
    /// Model vector up.
    pub up: Vector3<f64>,
    /// Half the block's length along, width across and height up.
    pub half: [f64; 3],
    /// The block's centre.
    pub center: Vector3<f64>,
}

impl MachineFrame {
    /// The frame of `mount` on `b`.
    pub fn new(b: &Cuboid, m: &Mount) -> Self {
        Self {
            along: Mount::vector(b, m.along),
            across: Mount::vector(b, m.across),
            up: Mount::vector(b, m.up),
            half: [b.half[m.along.0], b.half[m.across.0], b.half[m.up.0]],
            center: b.center,
        }
    }

    /// `(along, across, up)` of a model point: along from the block's start, across from
    /// its middle, up from its floor (job units).
    pub fn local(&self, q: &Vector3<f64>) -> [f64; 3] {
        let d = q - self.center;
        [
            d.dot(&self.along) + self.half[0],
            d.dot(&self.across),
            d.dot(&self.up) + self.half[2],
        ]
    }

    /// The point of the wire at `across = w`.
    pub fn at_across(&self, l: &WireLine, w: f64) -> Vector3<f64> {
        let (p, d) = (self.local(&l.point)[1], l.dir.dot(&self.across));
        l.point + l.dir * ((w - p) / d)
    }
}

/// The lead-in and lead-out: the first and last wire positions moved along the cut until
/// the wire's part between the block's sides lies `lead` before the block's start, and
/// `lead` after its end (and by `lead` at least).
pub fn leads(
    f: &MachineFrame,
    first: &WireLine,
    last: &WireLine,
    lead: f64,
) -> (WireLine, WireLine) {
    let w = f.half[1];
    let along_at = |l: &WireLine, s: f64| f.local(&f.at_across(l, s * w))[0];
    // at least `lead` away from the first and last positions, even where they already
    // clear the block
    let reach_in = (along_at(first, -1.0).max(along_at(first, 1.0)) + lead).max(lead);
    let length = 2.0 * f.half[0];
    let reach_out = (length - along_at(last, -1.0).min(along_at(last, 1.0)) + lead).max(lead);
    (
        WireLine {
            point: first.point - f.along * reach_in.max(0.0),
            dir: first.dir,
        },
        WireLine {
            point: last.point + f.along * reach_out.max(0.0),
            dir: last.dir,
        },
    )
}

/// The wire path of `cut` on block `b` (`index`: the block; `number`: the cut), its lead-in
/// and lead-out included in its lines.
pub fn wire_path(b: &Cuboid, index: usize, number: usize, cut: &Cut, p: &WireParams) -> WirePath {
    let f = MachineFrame::new(b, &cut.mount);
    let w = f.half[1];
    let lines = &cut.lines;
    let towers = (-p.tower_distance / 2.0, p.tower_distance / 2.0);
    let mm = p.mm_per_unit;
    let machine = |q: Vector3<f64>| {
        let l = f.local(&q);
        [(l[0] + p.origin[0]) * mm, (l[2] + p.origin[1]) * mm]
    };
    let steps = lines
        .iter()
        .map(|l| WireStep {
            u: f.local(&f.at_across(l, 0.0))[0],
            a: machine(f.at_across(l, towers.0)),
            b: machine(f.at_across(l, towers.1)),
            side0: f.at_across(l, -w).into(),
            side1: f.at_across(l, w).into(),
            kerf: [p.kerf; 2],
        })
        .collect();
    WirePath {
        direction: index,
        leg: number,
        steps,
        towers,
        along: [1.0, 0.0],
        across: [0.0, 1.0],
        u: (0.0, 2.0 * f.half[0]),
    }
}

/// Names of the block's axes for a mount text: `+x`, `−z`.
pub fn axis_name((k, s): (usize, f64)) -> String {
    format!("{}{}", if s < 0.0 { "-" } else { "+" }, ["x", "y", "z"][k])
}

/// How to mount the block, for a program's header.
pub fn mount_lines(
    block: usize,
    m: &Mount,
    b: &Cuboid,
    mm_per_unit: f64,
    tower_distance: f64,
) -> Vec<String> {
    let f = MachineFrame::new(b, m);
    let mm = |v: f64| format!("{:.1}", v * mm_per_unit);
    vec![
        format!(
            "mount block {}: its {} axis along the cut, {} towards tower B, {} up",
            block + 1,
            axis_name(m.along),
            axis_name(m.across),
            axis_name(m.up)
        ),
        format!(
            "block {} x {} x {} mm (along, across, up)",
            mm(2.0 * f.half[0]),
            mm(2.0 * f.half[1]),
            mm(2.0 * f.half[2])
        ),
        format!(
            "block centred between the towers, {} mm apart",
            mm(tower_distance)
        ),
    ]
}
