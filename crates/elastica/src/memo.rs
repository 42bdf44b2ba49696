//! Process-wide memos of pure, costly functions of blades: the same move is judged, and
//! the same blade's stability assessed, again and again — at each place tried, for the
//! halves of refined pieces, for the verdicts and again when the pieces are posed. Keys
//! are the exact bits of the blades, so results are the same with or without a memo, on
//! any number of threads. Written here because a cache crate would bring more than this
//! needs (a map behind a lock, emptied when full).

use crate::segment::Segment;
use std::collections::HashMap;
use std::hash::Hash;
use std::sync::Mutex;

/// A blade's exact bits: its variant, then its numbers. Equal keys are equal blades.
pub(crate) type Key = [u64; 10];

/// The key of blade `s`.
pub(crate) fn key(s: &Segment) -> Key {
    let mut k = [0u64; 10];
    let put = |k: &mut Key, tag: u64, v: &[f64]| {
        k[0] = tag;
        for (slot, x) in k[1..].iter_mut().zip(v) {
            *slot = x.to_bits();
        }
    };
    match *s {
        Segment::Line {
            x0,
            y0,
            phi,
            length,
        } => put(&mut k, 0, &[x0, y0, phi, length]),
        Segment::Arc {
            x0,
            y0,
            phi,
            curvature,
            length,
        } => put(&mut k, 1, &[x0, y0, phi, curvature, length]),
        Segment::Elastica(e) => put(
            &mut k,
            2 + e.family as u64 + 2 * u64::from(e.one_minus_k.is_some()),
            &[
                e.k,
                e.s0,
                e.l,
                e.scale,
                e.phi,
                e.x0,
                e.y0,
                e.one_minus_k.unwrap_or(0.0),
            ],
        ),
    }
    k
}

/// Values remembered by key, at most `cap` of them (when full, all are forgotten).
pub(crate) struct Memo<K, V> {
    map: Mutex<Option<HashMap<K, V>>>,
    cap: usize,
}

impl<K: Eq + Hash, V: Clone> Memo<K, V> {
    /// An empty memo of at most `cap` values.
    pub(crate) const fn new(cap: usize) -> Self {
        Memo {
            map: Mutex::new(None),
            cap,
        }
    }

    /// The value remembered for `k`, else `f()`, remembered when it is `Ok`.
    pub(crate) fn get_or<E>(&self, k: K, f: impl FnOnce() -> Result<V, E>) -> Result<V, E> {
        let known = self
            .map
            .lock()
            .ok()
            .and_then(|m| m.as_ref().and_then(|m| m.get(&k).cloned()));
        if let Some(v) = known {
            return Ok(v);
        }
        let v = f()?;
        if let Ok(mut m) = self.map.lock() {
            let m = m.get_or_insert_with(HashMap::new);
            if m.len() >= self.cap {
                m.clear();
            }
            m.insert(k, v.clone());
        }
        Ok(v)
    }
}
