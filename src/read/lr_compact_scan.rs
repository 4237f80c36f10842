//! The well-formed open's fast path over the pairs of `LRBE` (rule V35, and the slot flags of
//! [`SlotMap`] on one ring): plain pairs, most of them, in a branch-free pass over their
//! words; extended pairs, with a record to read, in a second pass over those alone. It only
//! says whether the rules hold: when they do not, the reader's pair-by-pair loop finds the
//! first fault and names it.

use super::lr_rules::{one_ring_next_next, ring_slot_flags, BitsSet, CANONICAL, JUMPS};
use crate::lr::compact::{BLOCK_SHIFT, EXTENDED, WART_LEFT};
use crate::lr::{CompactTables, NULL};
use crate::words::{LeUnits, LeWords, Units, Words};

type Tables<'a> = CompactTables<LeWords<'a>, LeUnits<'a>>;

/// What [`scan_pairs`] finds.
pub(super) struct PairScan {
    /// Whether [V35] holds.
    pub pairs_hold: bool,
    /// On one ring (and when V35 holds), the slot flags of [`SlotMap`](super::lr_rules::SlotMap)
    /// and the number of canonical triangles they flag.
    pub flags: Option<(Vec<u8>, u64)>,
    /// When V35 holds: every opposite that a record stores, with its pair, for [V37].
    pub stored: Vec<(u32, u32)>,
}

/// Sign-extends the low 15 bits.
#[inline(always)]
fn short15(bits: u32) -> i32 {
    ((bits as i32) << 17) >> 17
}

/// [V35] on every pair, and with `one_ring` the slot flags, for tables of `m` vertices.
pub(super) fn scan_pairs(t: &Tables, m: u32, one_ring: bool) -> PairScan {
    let m_r = t.m_r;
    let mut flags = vec![0u8; if one_ring { 2 * m_r as usize } else { 0 }];
    // Plain pairs: tips in range (the left one never NULL, the right one NULL only without
    // WART), bitwise rather than short-circuit logic; extended pairs are checked below.
    let mut bad = 0u32;
    let mut canonical = 0u32;
    // Tips and WART flags of pair `v` (word `p`), and whether they break V35 when plain.
    let pair = |v: u32, p: u32| {
        let config = p >> 30;
        let plain = (config != EXTENDED) as u32;
        let d = [short15(p), short15(p >> 15)];
        let tip = d.map(|d| {
            if d == 0 {
                NULL
            } else {
                v.wrapping_add_signed(d)
            }
        });
        let wart = [config == WART_LEFT, config == WART_LEFT + 1].map(|w| w as u32);
        let ok =
            (tip[0] < m) as u32 & ((tip[1] < m) as u32 | ((tip[1] == NULL) as u32 & (1 ^ wart[1])));
        (tip, wart, plain & (1 ^ ok))
    };
    let words = t.pairs.0.chunks_exact(4).enumerate().map(|(v, word)| {
        let p = u32::from_le_bytes(word.try_into().expect("four bytes"));
        (v as u32, p)
    });
    // Zipped rather than indexed, so that the pass has no bounds checks and vectorizes.
    if one_ring {
        // A slot is redundant when its tip is `v.n.n`: `v + 2`, a delta of 2, but for the
        // last two pairs (the ring wraps), whose flags are made again below. Extended
        // pairs get no flags here (the extended pass makes them).
        for ((v, p), slot_flags) in words.zip(flags.chunks_exact_mut(2)) {
            let (fault, pair_flags, pair_canonical) = plain_flags(v, p, m);
            bad |= fault;
            canonical += pair_canonical;
            slot_flags.copy_from_slice(&pair_flags.to_le_bytes());
        }
        for v in m_r.saturating_sub(2)..m_r {
            let p = t.pairs.at(v as usize);
            if p >> 30 == EXTENDED {
                continue; // flagged by the extended pass
            }
            let (tip, wart, _) = pair(v, p);
            let nn = one_ring_next_next(v, m_r);
            for side in 0..2 {
                let slot = &mut flags[2 * v as usize + side];
                canonical -= (*slot & CANONICAL) as u32;
                *slot = ring_slot_flags(tip[side], wart[side], 0, nn);
                canonical += (*slot & CANONICAL) as u32;
            }
        }
    } else {
        for (v, p) in words {
            bad |= pair(v, p).2;
        }
    }
    // A stored opposite takes a record unit at least.
    let mut stored = Vec::with_capacity(if bad == 0 { t.records.count() } else { 0 });
    let pairs_hold = bad == 0
        && extended_pairs_hold(
            t,
            m,
            one_ring.then_some((&mut flags, &mut canonical)),
            &mut stored,
        );
    PairScan {
        pairs_hold,
        flags: one_ring.then_some((flags, canonical as u64)),
        stored,
    }
}

/// Pair `v` (word `p`) read as plain, for tables of `m` vertices on one ring: whether it
/// breaks [V35], its two slot flags (left in the low byte; none for an extended pair) and
/// how many are canonical, with `v.n.n = v + 2`: [`ring_slot_flags`] for the deltas a plain
/// pair stores (a tip is `NULL` for a delta of 0 and `v.n.n` for a delta of 2).
#[inline(always)]
fn plain_flags(v: u32, p: u32, m: u32) -> (u32, u16, u32) {
    let config = p >> 30;
    let plain = (config != EXTENDED) as u32;
    let d = [short15(p), short15(p >> 15)];
    let (mut ok, mut flags, mut canonical) = (1u32, 0u32, 0u32);
    for (side, d) in d.into_iter().enumerate() {
        let wart = (config == WART_LEFT + side as u32) as u32;
        let null = (d == 0) as u32;
        let vertex = (v.wrapping_add_signed(d) < m) as u32 & (1 ^ null);
        // Left: a vertex; right: a vertex, or NULL without WART.
        ok &= if side == 0 {
            vertex
        } else {
            vertex | (null & (1 ^ wart))
        };
        let redundant = (1 ^ wart) & (d == 2) as u32;
        let is_canonical = (1 ^ null) & (1 ^ redundant) & plain;
        let jumps = (redundant | wart) & plain;
        canonical += is_canonical;
        flags |= ((is_canonical * CANONICAL as u32) | (jumps * JUMPS as u32)) << (8 * side);
    }
    (plain & (1 ^ ok), flags as u16, canonical)
}

/// [V35] on the extended pairs, in ring order: records tile `RECORDS`, each block's record
/// start is the records before it, every record inside the units, IRREGULAR flags as the
/// heads say, tips in range; and their slot flags (`v.n.n` on one ring) and stored
/// opposites (`(pair, corner)`, in `stored`).
fn extended_pairs_hold(
    t: &Tables,
    m: u32,
    mut flags: Option<(&mut Vec<u8>, &mut u32)>,
    stored: &mut Vec<(u32, u32)>,
) -> bool {
    let (m_r, records) = (t.m_r, t.records.count());
    let blocks = m_r.div_ceil(1 << BLOCK_SHIFT) as usize;
    let (mut next_record, mut next_block) = (0usize, 0usize);
    // Every block whose first vertex comes before `v` starts at the records so far.
    let blocks_start = |upto: usize, next_block: &mut usize, next_record: usize| {
        let mut ok = true;
        while *next_block < upto {
            ok &= t.blocks.at(2 * *next_block) as usize == next_record;
            *next_block += 1;
        }
        ok
    };
    // Loops rather than a flattened iterator: its `next` was not inlined, a call per pair.
    for (k, chunk) in t.pairs.0.chunks(4 * 64).enumerate() {
        for i in BitsSet(extended_mask(chunk)) {
            let v = (64 * k) as u32 + i;
            let p = t.pairs.at(v as usize);
            if !blocks_start(
                (v >> BLOCK_SHIFT) as usize + 1,
                &mut next_block,
                next_record,
            ) {
                return false;
            }
            let Some(x) = t.decode_extended(v, p) else {
                return false;
            };
            // Tips in range: the left one never NULL, the right one NULL only without WART or
            // IRREGULAR. (The record ends inside the units: `decode_extended` read it.)
            let [left, right] = x.tips;
            let right_null = (right == NULL) & !x.wart[1] & !x.irregular[1];
            if !((x.start == next_record) & x.flags_agree & (left < m) & ((right < m) | right_null))
            {
                return false;
            }
            next_record += x.len;
            for &c in x.opposites.iter().flatten() {
                stored.push((v, c));
            }
            if let Some((flags, canonical)) = flags.as_mut() {
                // One ring (the flags are only made then). The plain pass gave the pair no
                // flags.
                let nn = one_ring_next_next(v, m_r);
                for side in [0, 1] {
                    let flag = ring_slot_flags(
                        x.tips[side],
                        x.wart[side] as u32,
                        x.irregular[side] as u32,
                        nn,
                    );
                    flags[2 * v as usize + side] = flag;
                    **canonical += (flag & CANONICAL) as u32;
                }
            }
        }
    }
    blocks_start(blocks, &mut next_block, next_record) && next_record == records
}

/// Every opposite that a record stores, with its pair, by decoding the records one by one
/// (after the reader's loop has checked V35).
pub(super) fn stored_opposites(t: &Tables) -> Vec<(u32, u32)> {
    let mut stored = Vec::new();
    for v in extended_pairs(&t.pairs) {
        if let Some(x) = t.decode_extended(v, t.pairs.at(v as usize)) {
            stored.extend(x.opposites.into_iter().flatten().map(|c| (v, c)));
        }
    }
    stored
}

/// The ring vertices whose pair is extended, in order.
fn extended_pairs<'b>(pairs: &'b LeWords) -> impl Iterator<Item = u32> + 'b {
    pairs
        .0
        .chunks(4 * 64)
        .enumerate()
        .flat_map(|(k, chunk)| BitsSet(extended_mask(chunk)).map(move |i| (64 * k) as u32 + i))
}

/// Which of (up to) 64 pair words are extended, as bits (a filter branching on every pair
/// would mispredict at each of the scattered extended pairs): a byte per pair first, in a
/// loop that vectorizes, then eight bytes at a time by [`byte_bits`].
#[inline(always)]
fn extended_mask(chunk: &[u8]) -> u64 {
    let mut extended = [0u8; 64];
    for (e, w) in extended.iter_mut().zip(chunk.chunks_exact(4)) {
        let p = u32::from_le_bytes(w.try_into().expect("four bytes"));
        *e = (p >> 30 == EXTENDED) as u8;
    }
    extended
        .chunks_exact(8)
        .enumerate()
        .fold(0u64, |mask, (i, eight)| {
            mask | byte_bits(eight.try_into().expect("eight bytes")) << (8 * i)
        })
}

/// Eight bytes, each 0 or 1, as the bits of a byte (byte `i` to bit `i`): one multiply moves
/// byte `i`'s bit to bit `56 + i`, and no two of the partial products meet.
#[inline(always)]
fn byte_bits(bytes: [u8; 8]) -> u64 {
    u64::from_le_bytes(bytes).wrapping_mul(0x0102_0408_1020_4080) >> 56
}

#[cfg(all(test, feature = "fuzz-checks"))]
mod tests {
    /// 3,000 bit-efficient LR files forged (see [`read_forged_files`]): under `cfg(test)`
    /// `lr_compact_tables` asserts that this fast pass and the pair loop agree on every one,
    /// and the fuzz targets check it under `cfg(fuzzing)`.
    ///
    /// [`read_forged_files`]: crate::read::read_forged_files
    #[test]
    fn the_fast_pass_and_the_pair_loop_agree_on_forged_files() {
        crate::read::read_forged_files(0b001, 35, 3000);
    }
}
