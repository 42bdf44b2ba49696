//! Design curves across several blocks ("Designing for Robotic Hot-Blade Cutting" §4,
//! figs. 13/14): one cubic Bézier per block, neighbours sharing the end point on the face
//! between them and the tangent line there (the last leg of one and the first leg of the
//! next on one line, legs of any lengths: G¹). Each piece is replaced by its elastica
//! ([`crate::proxy`](mod@crate::proxy)); because the elastica keep their Bézier's end points and end
//! tangents, they join G¹ as well.

use crate::bezier::{wrap, Bezier};
use crate::error::{DesignError, Result};
use crate::proxy::{proxy, Proxy};

/// Where a chain breaks the G¹ construction between pieces `face` and `face + 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct G1Break {
    /// The face: between piece `face` and piece `face + 1`.
    pub face: usize,
    /// Distance between the first piece's end and the next piece's start.
    pub gap: f64,
    /// Angle between the first piece's last leg and the next piece's first leg, radians
    /// (0: on one line, the same way).
    pub angle: f64,
}

/// Relative tolerance of a shared end point (to the chain's length) and of a shared
/// tangent (radians) in the G¹ construction.
pub const G1_TOLERANCE: f64 = 1e-9;

/// The faces where `pieces` break the G¹ construction: a gap above [`G1_TOLERANCE`] of
/// the chain's length, or legs not on one line (angle above [`G1_TOLERANCE`]).
///
/// ```
/// use design::chain::g1_breaks;
/// use design::Bezier;
/// // two pieces meeting at (3, 1), the legs there both along x: G¹
/// let first = Bezier { p: [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0]] };
/// let second = Bezier { p: [[3.0, 1.0], [4.0, 1.0], [5.0, 0.0], [6.0, 0.0]] };
/// assert!(g1_breaks(&[first, second])?.is_empty());
/// // the second piece leaving at 45°: a kink at face 0
/// let kinked = Bezier { p: [[3.0, 1.0], [4.0, 2.0], [5.0, 0.0], [6.0, 0.0]] };
/// let breaks = g1_breaks(&[first, kinked])?;
/// assert_eq!(breaks.len(), 1);
/// assert_eq!((breaks[0].face, breaks[0].gap), (0, 0.0));
/// assert!((breaks[0].angle - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
/// # Ok::<(), design::DesignError>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] for a piece whose control points coincide.
pub fn g1_breaks(pieces: &[Bezier]) -> Result<Vec<G1Break>> {
    let total: f64 = pieces.iter().map(Bezier::length).sum();
    let mut out = Vec::new();
    for (face, w) in pieces.windows(2).enumerate() {
        let (a, b) = (&w[0], &w[1]);
        let gap = (a.p[3][0] - b.p[0][0]).hypot(a.p[3][1] - b.p[0][1]);
        let angle = wrap(b.start_angle()? - a.end_angle()?).abs();
        if gap > G1_TOLERANCE * total || angle > G1_TOLERANCE {
            out.push(G1Break { face, gap, angle });
        }
    }
    Ok(out)
}

/// The elastica of every piece of a G¹ chain, in order.
///
/// ```
/// use design::chain::elastica_chain;
/// use design::Bezier;
/// let first = Bezier { p: [[0.0, 0.0], [1.0, 1.0], [2.0, 1.0], [3.0, 1.0]] };
/// let second = Bezier { p: [[3.0, 1.0], [4.0, 1.0], [5.0, 0.0], [6.0, 0.0]] };
/// let chain = elastica_chain(&[first, second])?;
/// // the two elastica meet at the face with one tangent, as their Béziers do
/// let (end, start) = (chain[0].elastica.eval(1.0)?, chain[1].elastica.eval(0.0)?);
/// assert!((end.p[0] - start.p[0]).hypot(end.p[1] - start.p[1]) < 1e-9);
/// assert!((end.angle - start.angle).abs() < 1e-9);
/// // a kinked chain is refused
/// let kinked = Bezier { p: [[3.0, 1.0], [4.0, 2.0], [5.0, 0.0], [6.0, 0.0]] };
/// assert!(elastica_chain(&[first, kinked]).is_err());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`DesignError::Invalid`] naming the first face that breaks the construction; the
/// errors of [`proxy`].
pub fn elastica_chain(pieces: &[Bezier]) -> Result<Vec<Proxy>> {
    if let Some(b) = g1_breaks(pieces)?.first() {
        return Err(DesignError::Invalid(format!(
            "the design curve breaks the tangent-continuous construction between pieces {} and {}: gap {:.3e}, legs at {:.3e} rad",
            b.face,
            b.face + 1,
            b.gap,
            b.angle
        )));
    }
    pieces.iter().map(proxy).collect()
}
