//! Construction of the Zipper tables from a standard LR: each slot's symbol is chosen the
//! way the decoder reads it back, then every slot and T0 opposite is decoded and compared
//! with the standard LR's.

use super::packed::{list_fields, ring_block_field, Field, FieldKind, Packed};
use super::slots::{four_sides, last_vertex_bits, plane_array_words, row_corner, slot_edges, Slot};
use super::tables::ZipperTables;
use super::{
    below, BLOCK_SHIFT, BY_LEFT_RULE, BY_RIGHT_RULE, COMPACT_SUPER_SHIFT, DELTAS, EXCEPTION,
    EXPLICIT, EXPLICIT_SHIFT, FOUR, IRREGULAR_SLOT, LEFT_SLOTS, NEXT_NEXT_OR_NULL, NO_OPPOSITE,
    PREVIOUS, RECORD_WORDS, STATE_SHIFT, STORES_BOTH, STORES_FIRST, STORES_NONE, STORES_SECOND,
};
use crate::corner_table::NONE;
use crate::error::{Error, Result};
use crate::format::layout::{ZIPPER_IMPLIED_WARTS, ZIPPER_PACKED_LISTS, ZIPPER_ROW_RECORDS};
use crate::lr::read_back::opposite;
use crate::lr::tables::{LrLayout, LrTables, IRREGULAR, LEFT, NULL, RIGHT, VALUE, WART};

/// Whether slot `(v, side)` of `t` is a canonical T2 (symbol [`PREVIOUS`]).
fn is_canonical_t2(t: &LrTables<Vec<u32>>, v: u32, side: usize) -> bool {
    t.entry(v, side) & (IRREGULAR | WART) == 0 && t.tip(v, side) == t.ring_prev(v)
}

/// Whether slot `(v, side)` of `t` is followed on its side by a canonical T2. Such a slot
/// holds the T2's redundant copy or a wart (the T2 is the triangle on that side of the
/// slot's ring edge), and with `WART_DELTAS` its symbols read so (OPERATORS.md §8.1).
fn before_t2(t: &LrTables<Vec<u32>>, v: u32, side: usize) -> bool {
    is_canonical_t2(t, t.ring_next(v), side)
}

/// What slot `(v, side)` of `t` stores after chain value `chain`: its symbol, the chain
/// value after it, and the word (WART flag and tip) it adds to the exception or record list,
/// if any. A slot `before_t2` a canonical T2 is coded for the `WART_DELTAS` reading: a wart
/// as a delta when its tip is a small decrement of the chain, the redundant copy as symbol 5
/// on either side, anything else as an exception. On a side with fours, `fours` says whether
/// the slot is the last ring vertex's or the next vertex's slot in the block is a canonical
/// T2: then symbol 5
/// reads the T2's redundant copy, otherwise a four (FORMAT.md §3.5e.4), and the slot takes
/// symbol 5 only when that reading gives its tip and WART flag.
fn symbol(
    t: &LrTables<Vec<u32>>,
    v: u32,
    side: usize,
    chain: u32,
    before_t2: bool,
    fours: Option<bool>,
) -> (u32, u32, Option<u32>) {
    let entry = t.entry(v, side);
    let tip = t.tip(v, side);
    let stored = (entry & WART) | tip;
    if entry & IRREGULAR != 0 {
        return (IRREGULAR_SLOT, tip, Some(stored));
    }
    let delta = chain.wrapping_sub(tip);
    let next_next = t.ring_next_next(v);
    let wart = entry & WART != 0;
    if fours == Some(true) && !wart && tip == next_next {
        return (NEXT_NEXT_OR_NULL, chain, None);
    }
    // Symbol 5 as a four, or as the ring rules read it (without fours on this side).
    let four = fours == Some(false) && delta == FOUR;
    let rule_5 = fours.is_none();
    if before_t2 {
        return match delta {
            0..=3 if wart => (delta, tip, None),
            _ if four && wart => (NEXT_NEXT_OR_NULL, tip, None),
            _ if rule_5 && !wart && tip == next_next => (NEXT_NEXT_OR_NULL, chain, None),
            _ => (EXCEPTION, tip, Some(stored)),
        };
    }
    if wart {
        return (EXCEPTION, tip, Some(stored));
    }
    if tip == t.ring_prev(v) {
        return (PREVIOUS, chain, None);
    }
    if rule_5 && tip == if side == LEFT { next_next } else { NULL } {
        return (NEXT_NEXT_OR_NULL, chain, None);
    }
    match delta {
        0..=3 => (delta, tip, None),
        _ if four => (NEXT_NEXT_OR_NULL, tip, None),
        _ => (EXCEPTION, tip, Some(stored)),
    }
}

/// Record word 1 of irregular slot `(v, side)`: the opposites the ring rules cannot infer
/// (pushing both to `pairs` when one is not enough). With `ROW_RECORDS` a single T0 corner
/// is stored as its row, when the decoder finds that corner in the row by the slot's edges
/// (FORMAT.md §3.5e.5); a pair otherwise.
fn stored_opposites(
    t: &LrTables<Vec<u32>>,
    (v, side): (u32, usize),
    pairs: &mut Vec<u32>,
    row_records: bool,
) -> Result<u32> {
    let stored = [0, 1].map(|k| t.stored_opposite(v, side, k).unwrap_or(NONE));
    let needed =
        [0, 1].map(|k| stored[k] != t.inferred_opposite(v, 4 * side as u32 + 2 * k as u32));
    let t0_offset = |c: u32| {
        (c != NONE && c >= 8 * t.m_r && c - 8 * t.m_r < 1 << STATE_SHIFT).then(|| c - 8 * t.m_r)
    };
    // With ROW_RECORDS: the row of T0 corner `c`, if the decoder finds `c` for corner `k`.
    let row_of = |k: usize, c: u32| {
        let offset = c - 8 * t.m_r;
        let (row, i) = (offset / 4, offset % 4);
        let edges = slot_edges(v, side, t.tip(v, side), t.far(v, side));
        let vertices = [0, 1, 2].map(|i| t.vo_v[3 * row as usize + i]);
        (row_corner(edges, vertices) == Some((k, i))).then_some(STORES_FIRST << STATE_SHIFT | row)
    };
    let word = match needed {
        _ if row_records => {
            let single = match needed {
                [true, false] => t0_offset(stored[0]).and_then(|_| row_of(0, stored[0])),
                [false, true] => t0_offset(stored[1]).and_then(|_| row_of(1, stored[1])),
                _ => None,
            };
            match single {
                Some(word) => word,
                None => push_pair(pairs, stored)?,
            }
        }
        [false, false] => STORES_NONE << STATE_SHIFT,
        [true, false] if t0_offset(stored[0]).is_some() => {
            STORES_FIRST << STATE_SHIFT | t0_offset(stored[0]).unwrap_or(0)
        }
        [false, true] if t0_offset(stored[1]).is_some() => {
            STORES_SECOND << STATE_SHIFT | t0_offset(stored[1]).unwrap_or(0)
        }
        _ => push_pair(pairs, stored)?,
    };
    Ok(word)
}

/// Record word 1 storing both opposites in `pairs`.
fn push_pair(pairs: &mut Vec<u32>, stored: [u32; 2]) -> Result<u32> {
    let index = pairs.len() as u32 / 2;
    if index >= 1 << STATE_SHIFT {
        return Err(Error::Unsupported(
            "zipper: more than 2^30 opposite pairs".into(),
        ));
    }
    pairs.extend(stored);
    Ok(STORES_BOTH << STATE_SHIFT | index)
}

/// The Zipper tables of a standard LR (the same ids and flags), in the compact form. Each
/// side's chain runs on from the block before when a delta slot reads it before the side's
/// first stored slot and its offset from the block's first vertex fits 16 bits (otherwise
/// it restarts there, its first slot then taking an exception word unless a delta reaches
/// its tip); the anchors take the bits the largest offset needs, 0 for those no slot reads.
/// Restarting every chain (anchors of 0 bits) makes files 0–1% smaller but slows every
/// tip read at a block's start through an exception word (the Zipper's valence loop
/// 5.9 → 7.7 times the corner table's on bunny00).
pub(super) fn encode(t: &LrTables<Vec<u32>>) -> Result<ZipperTables<Vec<u32>>> {
    let m_r = t.m_r;
    let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);
    let mut planes = Vec::with_capacity(plane_array_words(m_r));
    let mut counts_before = Vec::with_capacity(2 * blocks);
    let mut anchors = Vec::with_capacity(2 * blocks);
    // Each side's chain starts at its first slot's tip (any value would do: the decoder
    // reads the anchors).
    let mut chain = [0, 1].map(|side| if m_r > 0 { t.tip(0, side) } else { 0 });
    let (mut exceptions, mut records, mut pairs) = (Vec::new(), Vec::new(), Vec::new());
    // Whether some slot needs the WART_DELTAS reading: only then is the flag set (and the
    // file version 1.8).
    let mut wart_deltas = false;
    let mut implied_warts = true;
    // Fours on the left always; on the right when no right slot is NULL, for symbol 5 stands
    // for NULL there otherwise.
    let sides = four_sides(true, (0..m_r).all(|v| t.tip(v, RIGHT) != NULL));
    for block in 0..blocks {
        let first = (block << BLOCK_SHIFT) as u32;
        // An anchor more than 16 bits from the block's first vertex is not stored: the chain
        // restarts at that vertex instead.
        let mut offsets = [0u32; 2];
        for (side, chain) in chain.iter_mut().enumerate() {
            let offset = i64::from(*chain) - i64::from(first);
            match i16::try_from(offset) {
                Ok(offset) => offsets[side] = offset as i32 as u32,
                Err(_) => *chain = first,
            }
        }
        counts_before.extend([exceptions.len(), records.len() / RECORD_WORDS].map(|n| n as u32));
        let mut p = [0u128; 3];
        let end = m_r.min(first + (1 << BLOCK_SHIFT));
        for v in first..end {
            for (side, chain) in chain.iter_mut().enumerate() {
                let before_t2 = before_t2(t, v, side);
                let fours = (sides & LEFT_SLOTS << side != 0)
                    .then(|| v + 1 == m_r || v + 1 < end && is_canonical_t2(t, v + 1, side));
                let (s, next, word) = symbol(t, v, side, *chain, before_t2, fours);
                *chain = next;
                // A delta, a four or a right symbol 5 of the ring rules before a canonical
                // T2 reads differently without the flag.
                let four = s == NEXT_NEXT_OR_NULL && fours == Some(false);
                let right_rule_5 = s == NEXT_NEXT_OR_NULL && side != LEFT && fours.is_none();
                wart_deltas |= before_t2 && (s < DELTAS || four || right_rule_5);
                if let Some(word) = word {
                    // IMPLIED_WARTS holds when every stored slot's flag is what it implies.
                    let next_next = t.ring_next_next(v);
                    implied_warts &= (word & WART != 0) == (before_t2 && word & VALUE != next_next);
                }
                match s {
                    EXCEPTION => exceptions.extend(word),
                    IRREGULAR_SLOT => {
                        records.extend(word);
                        records.push(stored_opposites(t, (v, side), &mut pairs, true)?);
                    }
                    _ => {}
                }
                let bit = 2 * (v - first) + side as u32;
                for (k, plane) in p.iter_mut().enumerate() {
                    *plane |= (((s >> k) & 1) as u128) << bit;
                }
            }
        }
        // An anchor is read by the delta slots of its side before the side's first stored
        // slot; with none, it is stored as 0 (so that it does not widen the field).
        let slots = 2 * (m_r - first).min(1 << BLOCK_SHIFT);
        let real = u128::MAX.checked_shr(128 - slots).unwrap_or(0);
        let fours = Slot { block, bit: 0, p }.fours(sides, last_vertex_bits(m_r, block));
        let (stored, deltas) = (p[1] & p[2], (!p[2] | fours) & real);
        for (side, offset) in offsets.iter_mut().enumerate() {
            let mine = LEFT_SLOTS << side;
            let before_stored = below((stored & mine).trailing_zeros() as usize);
            if deltas & mine & before_stored == 0 {
                *offset = 0;
            }
        }
        anchors.extend(offsets);
        // Group by group (32 slots), the three planes' words of each.
        let groups = (plane_array_words(m_r) / 3 - 4 * block).min(4);
        for q in 0..groups {
            planes.extend(p.map(|plane| (plane >> (32 * q)) as u32));
        }
    }

    let n0 = t.t0_count();
    let mut t0_codes = Vec::with_capacity(n0 as usize);
    let mut t0_explicit = Vec::new();
    for j in 0..n0 {
        if t0_explicit.len() >= 1 << (32 - EXPLICIT_SHIFT) {
            return Err(Error::Unsupported(
                "zipper: more explicit T0 opposites than 2^26".into(),
            ));
        }
        let mut word = (t0_explicit.len() as u32) << EXPLICIT_SHIFT;
        for i in 0..3 {
            let o = t.vo_o[3 * j as usize + i];
            let x = t.vo_v[3 * j as usize + (i + 1) % 3];
            let y = t.vo_v[3 * j as usize + (i + 2) % 3];
            let code = if o == NONE {
                NO_OPPOSITE
            } else if t.find_left(x, y) == o {
                BY_LEFT_RULE
            } else if t.find_right(x, y) == o {
                BY_RIGHT_RULE
            } else {
                t0_explicit.push(o);
                EXPLICIT
            };
            word |= code << (2 * i);
        }
        t0_codes.push(word);
    }

    // With several rings, the ring of each block's first vertex (RING_BLOCKS) stands for
    // the ring-end bits and ranks.
    let rings = t.ring_count() as u32;
    let ring_blocks = ring_blocks(&t.ring_starts);
    let ring_blocks = Packed::pack(&ring_blocks, [ring_block_field(rings); 2])
        .ok_or_else(|| Error::Internal("zipper: a ring index wider than its field".into()))?;
    // Every list in as many bits as the counts call for (PACKED_LISTS).
    let flags = ZIPPER_PACKED_LISTS
        | ZIPPER_ROW_RECORDS
        | if implied_warts {
            ZIPPER_IMPLIED_WARTS
        } else {
            0
        };
    if implied_warts {
        // The tips alone: the readers imply the flags.
        for word in exceptions
            .iter_mut()
            .chain(records.iter_mut().step_by(RECORD_WORDS))
        {
            *word &= VALUE;
        }
    }
    let fields = list_fields(
        flags,
        t.m,
        m_r,
        n0,
        (pairs.len() / 2) as u32,
        t0_explicit.len() as u32,
    );
    let lists = [
        &exceptions,
        &records,
        &pairs,
        &t.vo_v,
        &t0_codes,
        &t0_explicit,
        &t.c,
    ];
    let mut packed = Vec::with_capacity(lists.len());
    for (k, (words, fields)) in lists.into_iter().zip(fields).enumerate() {
        // Every word is in the range its field was sized for (the rules require it).
        packed.push(Packed::pack(words, fields).ok_or_else(|| {
            Error::Internal(format!("zipper: list {k} has a word wider than its field"))
        })?);
    }
    let mut packed = packed.into_iter();
    let mut list = || packed.next().expect("seven lists");
    // The starts of rings 1 to R − 1 (INNER_RING_STARTS): all but the first and the last.
    let inner = match t.ring_starts.len() {
        n if n > 2 => t.ring_starts[1..n - 1].to_vec(),
        _ => Vec::new(),
    };
    let (head_counts, super_counts) = compact_counts(&counts_before);
    let anchor_field = Field {
        width: signed_width(&anchors),
        kind: FieldKind::Signed,
    };
    let anchors = Packed::pack(&anchors, [anchor_field; 2])
        .ok_or_else(|| Error::Internal("zipper: an anchor wider than its field".into()))?;
    let z = ZipperTables {
        ring_starts: inner,
        rings,
        ring_last: Vec::new(),
        ring_rank: Vec::new(),
        ring_blocks,
        planes,
        heads: Vec::new(),
        anchors,
        head_counts,
        super_counts,
        exceptions: list(),
        records: list(),
        pairs: list(),
        t0_v: list(),
        t0_codes: list(),
        t0_explicit: list(),
        c: list(),
        m_r,
        m: t.m,
        boundaries_on_ring: t.boundaries_on_ring,
        wart_deltas,
        short_heads: false,
        compact: true,
        packed_lists: true,
        inner_ring_starts: true,
        ring_blocks_flag: true,
        four_sides: sides,
        row_records: true,
        implied_warts,
        joined_lists: true,
    };
    same_as_standard(&z, t)?;
    Ok(z)
}

/// The fewest bits that hold every one of `words` (two's complement) as a signed field.
fn signed_width(words: &[u32]) -> u8 {
    let width = |word: u32| match word as i32 {
        0 => 0,
        x if x < 0 => 33 - (!x).leading_zeros(),
        x => 33 - x.leading_zeros(),
    };
    words.iter().map(|&w| width(w)).max().unwrap_or(0) as u8
}

/// The compact heads' counts (FORMAT.md §3.5e.3) from each block's exceptions and records
/// before it (`before`, two per block): each as an offset from its superblock's, in the
/// fewest bits that hold the largest, and `SUPER`, the counts before each superblock from
/// the second.
fn compact_counts(before: &[u32]) -> (Packed<Vec<u32>>, Vec<u32>) {
    let per_superblock = 2 << COMPACT_SUPER_SHIFT;
    let mut offsets = Vec::with_capacity(before.len());
    let mut super_counts = Vec::new();
    for (s, superblock) in before.chunks(per_superblock).enumerate() {
        let base = [superblock[0], superblock[1]];
        if s > 0 {
            super_counts.extend(base);
        }
        for (i, &count) in superblock.iter().enumerate() {
            offsets.push(count - base[i % 2]);
        }
    }
    let width = |k: usize| {
        let largest = offsets
            .iter()
            .skip(k)
            .step_by(2)
            .copied()
            .max()
            .unwrap_or(0);
        Field {
            width: (32 - largest.leading_zeros()) as u8,
            kind: FieldKind::Plain,
        }
    };
    let fields = [width(0), width(1)];
    let packed = Packed::pack(&offsets, fields).expect("every offset fits its width");
    (packed, super_counts)
}

/// Checks that every slot and T0 opposite of `z` decodes to what `t` holds, as the decoder
/// reads them ([`ZipperTables::each_slot`]: each block's planes read once, the chains
/// followed slot by slot). The operators read the tables through tips, WART and IRREGULAR
/// flags, stored and T0 opposites (rings, `C` and T0 vertices are copied): when the first
/// three agree on every slot, every inferred opposite agrees, so only irregular slots'
/// opposites need comparing (they may be stored in one and inferred in the other).
fn same_as_standard(z: &ZipperTables<Vec<u32>>, t: &LrTables<Vec<u32>>) -> Result<()> {
    let mut first_fault = None;
    z.each_slot(|(v, side), (tip, wart, irregular)| {
        if first_fault.is_some() {
            return;
        }
        let same = (tip, wart) == t.tip_and_wart(v, side)
            && irregular == t.irregular(v, side)
            && (!irregular || (0..2).all(|k| opposite(z, v, side, k) == opposite(t, v, side, k)));
        if !same {
            first_fault = Some((v, side));
        }
    });
    if let Some((v, side)) = first_fault {
        return Err(Error::Internal(format!(
            "zipper slot ({v}, {side}) does not decode to the LR's"
        )));
    }
    for k in 0..3 * t.t0_count() {
        if z.t0_opposite(k) != t.t0_opposite(k) {
            return Err(Error::Internal(format!(
                "zipper T0 corner row {k} does not decode to the LR's opposite"
            )));
        }
    }
    Ok(())
}

/// `RING_BLOCKS` (FORMAT.md §3.5e) of the rings starting at `starts` (ring 0 at 0, then `m_r`
/// last): for each block of 64 ring vertices, the ring of its first vertex, the number of
/// ring starts after 0 at or below it; empty with fewer than two rings.
pub(crate) fn ring_blocks(starts: &[u32]) -> Vec<u32> {
    if starts.len() <= 2 {
        return Vec::new();
    }
    let m_r = starts[starts.len() - 1];
    let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);
    let mut ring = 0usize;
    (0..blocks)
        .map(|b| {
            let first = (b << BLOCK_SHIFT) as u32;
            while ring + 2 < starts.len() && starts[ring + 1] <= first {
                ring += 1;
            }
            ring as u32
        })
        .collect()
}
