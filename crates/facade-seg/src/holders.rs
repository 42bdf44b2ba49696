//! A piece's block against its blades (issue 37): the block's section on a plane (what
//! the blade outside a part may not enter), and the block slid across the cut, within
//! the room the piece leaves it, so that the blades' held ends clear it.

use elastica::blade::Blade;
use elastica::clearance::{to_rect, Section, HOLDER_MARGIN};
use hotblade::Clipped;

use crate::piece::Block;
use crate::Facade;

/// Places tried across the room the piece leaves in its block (besides those that put a
/// held end just clear of a face).
pub const SLIDES: usize = 128;

/// The block's `[min, max]` across the cut and up, in plane coordinates.
fn extent(facade: &Facade, block: &Block) -> [[f64; 2]; 2] {
    let f = &facade.frame;
    let o = nalgebra::Vector3::from(block.origin);
    let (u0, v0) = (f.u.dot(&o), f.v.dot(&o));
    [[u0, v0], [u0 + block.size[1], v0 + block.size[2]]]
}

/// The piece's block on a part's plane, in plane coordinates (the facade's planes are
/// parallel, so the block's section is one rectangle). Kept material is sought only
/// across the part itself (the rest of the block's width holds no design of this piece);
/// the held ends must keep out of the whole block. The block keeps what lies below the
/// design: `+v` is the side the blade removes, as the kerf offset takes it.
pub fn block_section(facade: &Facade, block: &Block, design: &Clipped) -> Section {
    let [[u0, v0], [u1, v1]] = extent(facade, block);
    let (lo, hi) = design
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), q| {
            (lo.min(q[0]), hi.max(q[0]))
        });
    Section {
        rect: [[lo.max(u0), v0], [hi.min(u1), v1]],
        block: [[u0, v0], [u1, v1]],
        keeps_below: true,
    }
}

/// `block` slid across the cut so that the held ends of `blades` (in plane coordinates)
/// clear it best: unchanged when every end already clears it by [`HOLDER_MARGIN`] of the
/// blade's `length`; else the place that maximizes the smallest distance of an end from
/// the block among those where the block still holds the piece (`piece`: its extent
/// across the cut, plane `u`) — tried at [`SLIDES`] + 1 equal steps and where an end
/// sits just clear of a face — the nearest to where it was among equals.
pub fn slide_block(
    facade: &Facade,
    block: &Block,
    piece: (f64, f64),
    blades: &[Blade],
    length: f64,
) -> Block {
    let [[u0, v0], [u1, v1]] = extent(facade, block);
    let margin = HOLDER_MARGIN * length;
    let ends: Vec<[f64; 2]> = blades
        .iter()
        .flat_map(|b| b.ends.iter().map(|e| e.position))
        .filter(|p| p[0].is_finite() && p[1].is_finite())
        .collect();
    let worst = |shift: f64| {
        let r = [[u0 + shift, v0], [u1 + shift, v1]];
        ends.iter()
            .map(|&p| to_rect(p, r))
            .fold(f64::INFINITY, f64::min)
    };
    // the shifts that keep the piece inside: the block's min face at most at the piece's
    // start, its max face at least at the piece's end
    let (lo, hi) = (piece.1 - u1, piece.0 - u0);
    if ends.is_empty() || worst(0.0) > margin || !(hi > lo) {
        return block.clone();
    }
    let steps = (0..=SLIDES).map(|i| lo + (hi - lo) * i as f64 / SLIDES as f64);
    let faces = ends.iter().flat_map(|p| {
        // the block's min face just past an end, or its max face just before one
        [p[0] + 2.0 * margin - u0, p[0] - 2.0 * margin - u1]
    });
    let best = steps
        .chain(faces.filter(|s| *s >= lo && *s <= hi))
        .map(|s| (worst(s), s))
        .fold((worst(0.0), 0.0f64), |best, c| {
            let better = c.0 > best.0 + 1e-9 * length
                || (c.0 >= best.0 - 1e-9 * length && c.1.abs() < best.1.abs());
            if better {
                c
            } else {
                best
            }
        });
    let mut moved = block.clone();
    let shift = facade.frame.u * best.1;
    for k in 0..3 {
        moved.origin[k] += shift[k];
    }
    moved
}

#[cfg(test)]
mod tests {
    use super::*;
    use elastica::blade::{extend_to_blade, BladeParams};
    use elastica::segment::Segment;
    use geom::expr::Expr;
    use geom::heightfield::HeightField;
    use geom::surface::{SectionParams, Surface};

    /// A flat facade cut along x: plane coordinates are (y, z).
    fn facade() -> Facade {
        let z = Expr::parse("0").unwrap();
        let s = Surface::HeightField(HeightField::try_new(z, (0.0, 600.0), (0.0, 1000.0)).unwrap());
        let (frame, sections) = s
            .sections(
                &SectionParams {
                    count: 2,
                    ..SectionParams::default()
                },
                &|| {},
            )
            .unwrap();
        Facade::new(frame, &sections).unwrap()
    }

    /// A straight blade `length` long over the flat part `[u0, u1]` at height 0, its
    /// extension shared `share` before the part.
    fn blade(u0: f64, u1: f64, length: f64, share: f64) -> Blade {
        let part = Segment::Line {
            x0: u0,
            y0: 0.0,
            phi: 0.0,
            length: u1 - u0,
        };
        let p = BladeParams {
            lead_in_share: share,
            ..BladeParams::new(length)
        };
        extend_to_blade(&part, &p).unwrap()
    }

    /// The block across the cut `[u, u + width]`, 400 high below the part, holding a
    /// piece `used` wide.
    fn block(u: f64, width: f64, used: f64) -> Block {
        Block {
            origin: [0.0, u, -400.0],
            size: [600.0, width, 400.0],
            used: [600.0, used, 0.0],
        }
    }

    #[test]
    fn a_block_whose_holders_clear_it_stays() {
        let f = facade();
        // a 300 wide part centred in a 600 wide block, blade 800: ends 100 out
        let b = block(0.0, 600.0, 300.0);
        let moved = slide_block(
            &f,
            &b,
            (150.0, 450.0),
            &[blade(150.0, 450.0, 800.0, 0.5)],
            800.0,
        );
        assert_eq!(moved, b);
    }

    #[test]
    fn a_block_slides_across_the_cut_to_clear_a_held_end_and_still_holds_its_piece() {
        let f = facade();
        // the part [150, 450] in the block [0, 600]; a twentieth of the extension before
        // the part: the held end at 125 lies in the block, the other at 925 far out
        let b = block(0.0, 600.0, 300.0);
        let blades = [blade(150.0, 450.0, 800.0, 0.05)];
        let moved = slide_block(&f, &b, (150.0, 450.0), &blades, 800.0);
        let u = moved.origin[1];
        // the block now starts past that end by the margin, and still holds the part
        assert!(u > 125.0 + HOLDER_MARGIN * 800.0, "{u}");
        assert!(u <= 150.0 && u + 600.0 >= 450.0, "{u}");
        assert_eq!((moved.origin[0], moved.origin[2]), (0.0, -400.0));
    }

    #[test]
    fn a_block_off_centre_slides_only_as_far_as_it_still_holds_its_piece() {
        let f = facade();
        // the part [150, 450] at the block's min face already: sliding on towards the end
        // at 125 would leave the part
        let b = block(150.0, 600.0, 300.0);
        let blades = [blade(150.0, 450.0, 800.0, 0.05)];
        let moved = slide_block(&f, &b, (150.0, 450.0), &blades, 800.0);
        let u = moved.origin[1];
        assert!(u <= 150.0 && u + 600.0 >= 450.0, "{u}");
        // and sliding twice is sliding once
        let again = slide_block(&f, &moved, (150.0, 450.0), &blades, 800.0);
        assert_eq!(again, moved);
    }

    #[test]
    fn with_no_room_to_clear_both_ends_the_block_takes_the_best_place() {
        let f = facade();
        // a 560 wide part in a 600 block, blade 580: ends 10 beyond the part each side,
        // inside the block wherever it stands; the best keeps them equally deep
        let b = block(-20.0, 600.0, 560.0);
        let blades = [blade(0.0, 560.0, 580.0, 0.5)];
        let moved = slide_block(&f, &b, (0.0, 560.0), &blades, 580.0);
        let u = moved.origin[1];
        assert!(u <= 0.0 && u + 600.0 >= 560.0);
        assert!((u + 20.0).abs() < 600.0 / SLIDES as f64, "{u}");
    }

    #[test]
    fn the_kept_section_spans_the_part_across_and_the_block_up() {
        let f = facade();
        let b = block(-100.0, 600.0, 300.0);
        let design = Clipped {
            points: vec![[0.0, 0.0], [150.0, 10.0], [300.0, 0.0]],
            s: vec![0.0, 150.3, 300.6],
            length: 300.6,
            end_angles: [0.0, 0.0],
        };
        let s = block_section(&f, &b, &design);
        assert_eq!(s.rect, [[0.0, -400.0], [300.0, 0.0]]);
        assert_eq!(s.block, [[-100.0, -400.0], [500.0, 0.0]]);
        assert!(s.keeps_below);
    }
}
