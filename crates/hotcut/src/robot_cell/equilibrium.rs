//! The report's `cell.equilibrium` section: the blade's equilibrium followed through every
//! move of the program ([`cell::equilibrium`]) — its stability margin along the program,
//! per block, and every move that snaps the blade to another shape.

use cell::equilibrium::{ProgramShapes, SnapKind};
use cell::fixture::{Phase, Step};
use schemars::JsonSchema;
use serde::Serialize;

/// A move that snaps the blade.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct SnapReport {
    /// The move (1-based, as `cell.csv` numbers them).
    pub r#move: usize,
    /// Its robtarget (`pB<block>_<phase><n>`).
    pub target: String,
    /// The block it belongs to.
    pub block: usize,
    /// What the move does.
    pub phase: Phase,
    /// How the blade left the planned shape.
    pub kind: SnapKind,
    /// Where along the move it happened (0–1; `null` when it arrived on another shape).
    pub at: Option<f64>,
}

/// The least margin over one block's moves.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct BlockMargin {
    /// The block.
    pub block: usize,
    /// The least margin over the moves that belong to it.
    pub min_margin: f64,
    /// Its moves that snap.
    pub snaps: usize,
}

/// The `cell.equilibrium` section.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct EquilibriumReport {
    /// Moves along which the blade's equilibrium was followed (every move after the
    /// blade is mounted straight).
    pub transitions: usize,
    /// Of those, the moves that snap it: a fold on the way, no equilibrium to follow, or an
    /// arrival on another shape than planned.
    pub snaps: usize,
    /// The least stability margin along the whole program.
    pub min_margin: f64,
    /// The least margin a pose keeps (the job's `blade.min_margin`): below it a pose is
    /// marginal.
    pub marginal: f64,
    /// Cutting poses that hold the blade nearly taut: its slack (length less chord) below
    /// [`TAUT_SLACK_MM`]. Such a blade's shape and stability hang on less than the robots'
    /// path accuracy and the blade's heating (a steel blade grows ~0.4 % at 350 °C): they
    /// are flagged, not refused.
    pub taut_poses: usize,
    /// The least slack of a cutting pose, mm.
    pub min_slack_mm: f64,
    /// Per block.
    pub blocks: Vec<BlockMargin>,
    /// Every move that snaps.
    pub snap_moves: Vec<SnapReport>,
    /// The least margin along each move, in order (`null` where the blade is not
    /// followed: the mount, and a move from a taut blade).
    pub margins: Vec<Option<f64>>,
}

/// The robtarget names of the steps: `pB<block>_<phase letter><n>`.
pub fn target_names(steps: &[Step]) -> Vec<String> {
    let mut count = std::collections::HashMap::new();
    steps
        .iter()
        .map(|s| {
            let n = count.entry((s.block, letter(s.phase))).or_insert(0);
            *n += 1;
            format!("pB{}_{}{}", s.block, letter(s.phase), n)
        })
        .collect()
}

/// The robtarget letter of a phase.
pub fn letter(p: Phase) -> &'static str {
    match p {
        Phase::Load => "L",
        Phase::Bend => "B",
        Phase::Start => "S",
        Phase::Descend => "D",
        Phase::Cut => "C",
        Phase::Retreat => "R",
        Phase::Rise => "U",
        Phase::Travel => "T",
    }
}

/// The section of a program's `steps` and the blade followed through them.
/// Slack below which a cutting pose holds the blade nearly taut, mm.
pub const TAUT_SLACK_MM: f64 = 0.5;

/// The section of a program's `steps` and the blade followed through them; `slacks` are
/// the cutting poses' slacks, mm.
pub fn report(
    steps: &[Step],
    shapes: &ProgramShapes,
    marginal: f64,
    slacks: &[f64],
) -> EquilibriumReport {
    let names = target_names(steps);
    let mut blocks: Vec<BlockMargin> = Vec::new();
    let mut snap_moves = Vec::new();
    for (k, (s, m)) in steps.iter().zip(&shapes.moves).enumerate() {
        let Some(m) = m else { continue };
        let entry = match blocks.iter_mut().find(|b| b.block == s.block) {
            Some(b) => b,
            None => {
                blocks.push(BlockMargin {
                    block: s.block,
                    min_margin: f64::INFINITY,
                    snaps: 0,
                });
                blocks.last_mut().expect("just pushed")
            }
        };
        entry.min_margin = entry.min_margin.min(m.min_margin);
        if let Some(kind) = m.snap {
            entry.snaps += 1;
            snap_moves.push(SnapReport {
                r#move: k + 1,
                target: names[k].clone(),
                block: s.block,
                phase: s.phase,
                kind,
                at: m.snap_at,
            });
        }
    }
    EquilibriumReport {
        transitions: shapes.transitions,
        snaps: shapes.snaps,
        min_margin: shapes.min_margin,
        marginal,
        taut_poses: slacks.iter().filter(|s| **s < TAUT_SLACK_MM).count(),
        min_slack_mm: slacks
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min)
            .min(1e6),
        blocks,
        snap_moves,
        margins: shapes
            .moves
            .iter()
            .map(|m| m.as_ref().map(|m| m.min_margin).filter(|v| v.is_finite()))
            .collect(),
    }
}

impl EquilibriumReport {
    /// What is wrong: every snap, one line each (the first 12).
    pub fn problems(&self) -> Vec<String> {
        let mut out: Vec<String> = self
            .snap_moves
            .iter()
            .take(12)
            .map(|s| {
                let how = match s.kind {
                    SnapKind::Fold => "the blade's shape folds (its margin reaches 0)",
                    SnapKind::Lost => "no equilibrium of the blade can be followed",
                    SnapKind::OtherShape => "the blade arrives on another shape than planned",
                };
                format!("move {} ({}, block {}): {how}", s.r#move, s.target, s.block)
            })
            .collect();
        if self.snap_moves.len() > 12 {
            out.push(format!("… {} snaps in all", self.snap_moves.len()));
        }
        out
    }

    /// The warning about nearly taut poses, if any.
    pub fn taut_warning(&self) -> Option<String> {
        (self.taut_poses > 0).then(|| {
            format!(
                "{} cutting pose(s) hold the blade nearly taut (slack down to {:.4} mm, below {TAUT_SLACK_MM} mm): its shape and stability there hang on less than the robots' path accuracy and the blade's heating",
                self.taut_poses, self.min_slack_mm
            )
        })
    }
}
