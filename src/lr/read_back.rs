//! Any LR layout read back as standard LR tables: every slot's tip and flags, and the
//! opposites of irregular slots and T0 corners (stored or inferred) resolved once. The
//! standard tables' operators then answer as the layout's do, each a few reads: a verifying
//! reader checks the semantic rules on them (FORMAT.md §5.1 asks the same answers of both).
//! The Zipper has a faster pass of its own ([`ZipperTables::to_lr_tables`](super::ZipperTables)).

use super::open_fans::OpenFans;
use super::tables::{LrLayout, LrTables, IRREGULAR, LEFT, RIGHT, WART};

/// The opposite of transversal corner `k` of slot `(v, side)`: stored or inferred.
pub(crate) fn opposite<T: LrLayout>(t: &T, v: u32, side: usize, k: usize) -> u32 {
    t.stored_opposite(v, side, k)
        .unwrap_or_else(|| t.inferred_opposite(v, 4 * side as u32 + 2 * k as u32))
}

/// The slot entry of the standard tables for a slot with `tip`, WART flag `wart` and, when
/// irregular, the record `(tip, both opposites)` pushed onto `vo_star`.
pub(crate) fn push_slot<T: LrLayout>(
    t: &T,
    (v, side): (u32, usize),
    (tip, wart, irregular): (u32, bool, bool),
    lr: &mut Vec<u32>,
    vo_star: &mut Vec<u32>,
) {
    let flags = if wart { WART } else { 0 };
    if irregular {
        lr.push(IRREGULAR | flags | (vo_star.len() / 3) as u32);
        vo_star.extend([tip, opposite(t, v, side, 0), opposite(t, v, side, 1)]);
    } else {
        lr.push(flags | tip);
    }
}

/// The standard tables of `t` with `lr` and `vo_star` as given (every slot's entry, in slot
/// order, and the records): the rings, T0 rows (opposites resolved) and C read from `t`.
pub(crate) fn with_slots<T: LrLayout>(
    t: &T,
    lr: Vec<u32>,
    vo_star: Vec<u32>,
) -> LrTables<Vec<u32>> {
    let ring_starts: Vec<u32> = (0..t.ring_count() + 1).map(|r| t.ring_start(r)).collect();
    // The ring-end bits and ranks from the starts (a layout may not store them), only read
    // with several rings.
    let (ring_last, ring_rank) = match t.ring_count() {
        0 | 1 => (Vec::new(), Vec::new()),
        _ => crate::lr::ring_bits(&ring_starts),
    };
    LrTables {
        lr,
        vo_v: (0..3 * t.t0_count()).map(|k| t.t0_vertex(k)).collect(),
        vo_o: (0..3 * t.t0_count()).map(|k| t.t0_opposite(k)).collect(),
        vo_star,
        c: (0..t.vertex_count() - t.ring_vertices())
            .map(|i| t.isolated_corner(i))
            .collect(),
        ring_starts,
        ring_last,
        ring_rank,
        m_r: t.ring_vertices(),
        m: t.vertex_count(),
        boundaries_on_ring: t.boundaries_on_ring(),
        open_fans: t
            .listed_fans()
            .map(|pairs| OpenFans::from_pairs(&pairs, t.ring_vertices())),
    }
}

/// The standard tables whose every answer is `t`'s, slot by slot through its operators.
pub(crate) fn standard_tables<T: LrLayout>(t: &T) -> LrTables<Vec<u32>> {
    let m_r = t.ring_vertices();
    let mut lr = Vec::with_capacity(2 * m_r as usize);
    let mut vo_star = Vec::new();
    for v in 0..m_r {
        for side in [LEFT, RIGHT] {
            let (tip, wart) = t.tip_and_wart(v, side);
            let slot = (tip, wart, t.irregular(v, side));
            push_slot(t, (v, side), slot, &mut lr, &mut vo_star);
        }
    }
    with_slots(t, lr, vo_star)
}

/// Whether `lr` answers every operator as `t` does: the same corners, each one's vertex and
/// opposite, and each vertex's corner. The check of a read-back in tests and fuzzing.
#[cfg(any(test, fuzzing))]
pub(crate) fn answers_agree<T: LrLayout>(t: &T, lr: &LrTables<Vec<u32>>) -> bool {
    use crate::ids::{Corner, Vertex};
    use crate::ops::CornerOps;
    let corners = 8 * t.ring_vertices() + 4 * t.t0_count();
    let slots_agree = (0..t.ring_vertices()).all(|v| {
        [LEFT, RIGHT].into_iter().all(|side| {
            (t.tip_and_wart(v, side), t.irregular(v, side))
                == (lr.tip_and_wart(v, side), lr.irregular(v, side))
        })
    });
    let corners_agree = (0..corners).map(Corner).all(|c| match t.is_corner(c) {
        true => lr.is_corner(c) && (t.vertex(c), t.opposite(c)) == (lr.vertex(c), lr.opposite(c)),
        false => !lr.is_corner(c),
    });
    let vertices_agree = (0..t.vertex_count())
        .map(Vertex)
        .all(|v| t.vertex_corner(v) == lr.vertex_corner(v));
    slots_agree && corners_agree && vertices_agree
}
