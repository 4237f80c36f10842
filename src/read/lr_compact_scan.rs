//! The well-formed open's fast path over the pairs of `LRBE` (rule V35, and the slot flags of
//! [`SlotMap`] on one ring): plain pairs, most of them, in a branch-free pass over their
//! words; extended pairs, with a record to read, in a second pass over those alone. It only
//! says whether the rules hold: when they do not, the reader's pair-by-pair loop finds the
//! first fault and names it.

use super::lr_rules::{ring_slot_flags, CANONICAL, JUMPS};
use crate::lr::compact::{plain, BLOCK_SHIFT, EXTENDED, SHORT_MAX, WART_LEFT};
use crate::lr::{one_ring_next_next, CompactTables, NULL};
use crate::words::BitsSet;
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

/// [V35] on every pair, and with `one_ring` the slot flags, for tables of `m` vertices.
pub(super) fn scan_pairs(t: &Tables, m: u32, one_ring: bool) -> PairScan {
    let m_r = t.m_r;
    let mut flags = vec![0u8; if one_ring { 2 * m_r as usize } else { 0 }];
    let (bad, mut canonical) = match t.has_tip_bases() {
        true => plain_pass::<true>(t, m, &mut flags),
        false => plain_pass::<false>(t, m, &mut flags),
    };
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

/// The plain pairs (extended ones are checked by [`extended_pairs_hold`]): whether one breaks
/// [V35] (non-zero), and with `flags` as long as the slots (one ring) their slot flags and
/// how many are canonical. `BASES`: the tables have tip bases. Bitwise rather than
/// short-circuit logic, and block by block with the block's bases in hand, so that the pass
/// over the words vectorizes.
fn plain_pass<const BASES: bool>(t: &Tables, m: u32, flags: &mut [u8]) -> (u32, u32) {
    let m_r = t.m_r;
    let one_ring = !flags.is_empty();
    let (mut bad, mut canonical) = (0u32, 0u32);
    let bases = |block: usize| match BASES {
        true => [0, 1].map(|side| t.bases.at(2 * block + side) as i32),
        false => [0; 2],
    };
    let block_bytes = 4 << BLOCK_SHIFT;
    for (block, words) in t.pairs.0.chunks(block_bytes).enumerate() {
        let base = bases(block);
        let first = (block << BLOCK_SHIFT) as u32;
        let words = words.chunks_exact(4).enumerate().map(|(i, word)| {
            let p = u32::from_le_bytes(word.try_into().expect("four bytes"));
            (first + i as u32, p)
        });
        let last = (first + words.len() as u32).saturating_sub(1);
        let far_two = in_range_block::<BASES>(first, last, base, m);
        // Zipped rather than indexed, so that the pass has no bounds checks and vectorizes.
        if one_ring {
            let slots = &mut flags[2 * first as usize..];
            match far_two {
                Some(far_two) => {
                    for (word, slot_flags) in words.zip(slots.chunks_exact_mut(2)) {
                        let (fault, pair_flags, pair_canonical) = field_flags(word.1, far_two);
                        bad |= fault;
                        canonical += pair_canonical;
                        slot_flags.copy_from_slice(&pair_flags.to_le_bytes());
                    }
                }
                None => {
                    for ((v, p), slot_flags) in words.zip(slots.chunks_exact_mut(2)) {
                        let (fault, pair_flags, pair_canonical) =
                            plain_flags::<BASES>(v, p, m, base);
                        bad |= fault;
                        canonical += pair_canonical;
                        slot_flags.copy_from_slice(&pair_flags.to_le_bytes());
                    }
                }
            }
        } else {
            for (v, p) in words {
                bad |= match far_two {
                    Some(far_two) => field_flags(p, far_two).0,
                    None => plain_flags::<BASES>(v, p, m, base).0,
                };
            }
        }
    }
    if one_ring {
        // A slot is redundant when its tip is `v.n.n`: `v + 2`, a delta of 2, but for the
        // last two pairs (the ring wraps), whose flags are made again here. Extended pairs
        // got no flags (the extended pass makes them).
        for v in m_r.saturating_sub(2)..m_r {
            let p = t.pairs.at(v as usize);
            if p >> 30 == EXTENDED {
                continue;
            }
            let nn = one_ring_next_next(v, m_r);
            let config = p >> 30;
            for side in 0..2 {
                let base = || bases((v >> BLOCK_SHIFT) as usize)[side];
                let tip = plain::tip(v, p >> (15 * side), BASES, base);
                let wart = (config == WART_LEFT + side as u32) as u32;
                let slot = &mut flags[2 * v as usize + side];
                canonical -= (*slot & CANONICAL) as u32;
                *slot = ring_slot_flags(tip, wart, 0, nn);
                canonical += (*slot & CANONICAL) as u32;
            }
        }
    }
    (bad, canonical)
}

/// When every tip a field of the block of ring vertices `first..=last` can give (near, or far
/// from `base`) is a vertex of `0..m`, the far field of offset 2 of each side (the field
/// value no field can take, `u32::MAX`, when 2 is beyond the base's reach): then the block's
/// verdict and flags follow from its fields alone ([`field_flags`]); `None` otherwise.
#[inline(always)]
fn in_range_block<const BASES: bool>(
    first: u32,
    last: u32,
    base: [i32; 2],
    m: u32,
) -> Option<[u32; 2]> {
    let (lo, hi) = if BASES {
        (plain::NEAR_MIN, plain::NEAR_MAX)
    } else {
        (-SHORT_MAX - 1, SHORT_MAX)
    };
    let inside = |from: i64| first as i64 + from + lo >= 0 && last as i64 + from + hi < m as i64;
    if !inside(0) {
        return None;
    }
    let mut far_two = [u32::MAX; 2];
    if BASES {
        for (side, base) in base.into_iter().enumerate() {
            if !inside(base as i64) {
                return None;
            }
            let e = 2 - base as i64;
            if (plain::NEAR_MIN..=plain::NEAR_MAX).contains(&e) {
                far_two[side] = plain::FAR | e as u32 & 0x3FFF;
            }
        }
    }
    Some(far_two)
}

/// Pair word `p` of a block whose tips are all vertices ([`in_range_block`]), read as plain:
/// whether it breaks [V35] (a `NULL` left tip, or right one with WART), its slot flags and
/// how many are canonical, as [`plain_flags`] gives them, from the fields alone: a tip is
/// `NULL` for field 0 and `v.n.n = v + 2` for field 2 or `far_two`.
#[inline(always)]
fn field_flags(p: u32, far_two: [u32; 2]) -> (u32, u16, u32) {
    let config = p >> 30;
    let plain = (config != EXTENDED) as u32;
    let (mut fault, mut flags, mut canonical) = (0u32, 0u32, 0u32);
    for (side, far_two) in far_two.into_iter().enumerate() {
        let f = (p >> (15 * side)) & 0x7FFF;
        let wart = (config == WART_LEFT + side as u32) as u32;
        let null = (f == plain::NULL_FIELD) as u32;
        fault |= null & if side == 0 { plain } else { wart };
        let two = (f == 2) as u32 | (f == far_two) as u32;
        let (slot, is_canonical) = slot_flags(plain, wart, null, two);
        canonical += is_canonical;
        flags |= slot << (8 * side);
    }
    (fault, flags as u16, canonical)
}

/// Pair `v` (word `p`) read as plain, for tables of `m` vertices, with the bases `base` of
/// its block when `BASES`: whether it breaks [V35] (its tips in range: the left one never
/// `NULL`, the right one `NULL` only without WART), and on one ring its two slot flags
/// (left in the low byte; none for an extended pair) and how many are canonical, with
/// `v.n.n = v + 2`: [`ring_slot_flags`] for the offsets a plain pair stores (a tip is
/// `NULL` for field 0 and `v.n.n` for an offset of 2).
#[inline(always)]
fn plain_flags<const BASES: bool>(v: u32, p: u32, m: u32, base: [i32; 2]) -> (u32, u16, u32) {
    let config = p >> 30;
    let plain = (config != EXTENDED) as u32;
    let (mut ok, mut flags, mut canonical) = (1u32, 0u32, 0u32);
    for (side, base) in base.into_iter().enumerate() {
        let f = (p >> (15 * side)) & 0x7FFF;
        let d = plain::offset(f, BASES.then_some(base));
        let wart = (config == WART_LEFT + side as u32) as u32;
        let null = (f == plain::NULL_FIELD) as u32;
        let vertex = (v.wrapping_add_signed(d) < m) as u32 & (1 ^ null);
        // Left: a vertex; right: a vertex, or NULL without WART.
        ok &= if side == 0 {
            vertex
        } else {
            vertex | (null & (1 ^ wart))
        };
        let two = (1 ^ null) & (d == 2) as u32;
        let (slot, is_canonical) = slot_flags(plain, wart, null, two);
        canonical += is_canonical;
        flags |= slot << (8 * side);
    }
    (plain & (1 ^ ok), flags as u16, canonical)
}

/// The flags byte of a slot of a plain pair ([`ring_slot_flags`]'s) and whether it is
/// canonical, from 0-or-1 words: the pair is `plain`, the slot has WART, its tip is `NULL`,
/// its tip is `v.n.n` (`two`, never with `null`; a redundant T2 copy unless WART).
#[inline(always)]
fn slot_flags(plain: u32, wart: u32, null: u32, two: u32) -> (u32, u32) {
    let redundant = (1 ^ wart) & two;
    let is_canonical = (1 ^ null) & (1 ^ redundant) & plain;
    let jumps = (redundant | wart) & plain;
    (
        (is_canonical * CANONICAL as u32) | (jumps * JUMPS as u32),
        is_canonical,
    )
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

#[cfg(all(test, feature = "generate"))]
mod tip_bases_tests {
    use crate::format::layout::LrbeHeader;
    use crate::format::Tag;
    use crate::generate::{self, Rng};
    use crate::read::{open, Limits};
    use crate::words::Words;
    use crate::write::{assemble, Connectivity, EncodeOptions, SectionBytes};

    /// A bit-efficient LR file of over 100 blocks, many far enough from the ring's ends for
    /// [`in_range_block`](super::in_range_block) (the forged files of the fuzz targets are
    /// small tori): with `tip_bases`, on a depth-first ring with far fields in many plain
    /// pairs; without, on a ring of period 64. Its sections, the index of `LRBE`, where
    /// `PAIRS` and `BASES` start in it, and `m_r`.
    fn base(tip_bases: bool) -> (Vec<SectionBytes>, usize, usize, usize, usize) {
        // Without tip bases a near field reaches twice as far: a ring twice as long.
        let triangles = if tip_bases { 60_000 } else { 120_000 };
        let mut mesh = generate::irregular_torus(triangles, 3);
        generate::punch_holes(&mut mesh, 6, &mut Rng::new(3));
        let options = EncodeOptions {
            connectivity: Connectivity::LrCompact,
            periods: vec![if tip_bases { 0 } else { 64 }],
            tip_bases: Some(tip_bases),
            ..EncodeOptions::default()
        };
        let (sections, k) = crate::read::encoded_sections(&mesh, &options, Tag::LRBE);
        let header = LrbeHeader::read(&sections[k].2);
        let layout = header.layout().expect("a layout");
        let at = |name| layout.array(name).start;
        (sections, k, at("PAIRS"), at("BASES"), header.m_r as usize)
    }

    /// Pair words (and bases) overwritten by others or by random words, NULL and offset-2
    /// fields, bit 14 of fields flipped: under `cfg(test)` `open` runs the fast pass and the
    /// pair loop on each file and asserts that they agree (and the slot flags too), on
    /// blocks read from their fields alone and on the others, with and without tip bases.
    /// Both verdicts occur.
    #[test]
    fn the_fast_pass_and_the_pair_loop_agree_on_large_rings() {
        for tip_bases in [true, false] {
            agree_on_forged(tip_bases);
        }
    }

    fn agree_on_forged(tip_bases: bool) {
        let (base, k, pairs, bases, m_r) = base(tip_bases);
        let blocks = m_r.div_ceil(256);
        assert!(blocks >= 100, "{blocks} blocks");
        let word = |s: &[u8], at: usize| u32::from_le_bytes(s[at..at + 4].try_into().unwrap());
        let far = (0..m_r)
            .map(|v| word(&base[k].2, pairs + 4 * v))
            .filter(|p| p >> 30 != 3 && (p & 1 << 14 != 0 || p & 1 << 29 != 0))
            .count();
        if tip_bases {
            assert!(far > m_r / 50, "{far} pairs with a far field of {m_r}");
        }
        // Blocks whose flags come from their fields alone, and blocks that read every tip.
        let bytes = assemble(&base);
        let view = open(&bytes, &Limits::default()).expect("what we write opens");
        let t = view.lr_compact().expect("lr-compact tables");
        assert_eq!(t.has_tip_bases(), tip_bases);
        let simple = (0..blocks)
            .filter(|&b| {
                let first = (b * 256) as u32;
                let last = (first + 255).min(m_r as u32 - 1);
                match tip_bases {
                    true => {
                        let base = [0, 1].map(|side| t.bases.at(2 * b + side) as i32);
                        super::in_range_block::<true>(first, last, base, t.m).is_some()
                    }
                    false => super::in_range_block::<false>(first, last, [0; 2], t.m).is_some(),
                }
            })
            .count();
        assert!(
            simple > blocks / 4 && simple < blocks,
            "{simple} of {blocks}"
        );
        let mut rng = Rng::new(26);
        let (mut opened, mut refused) = (0, 0);
        for case in 0..2000 {
            let mut sections = base.clone();
            let section = &mut sections[k].2;
            for _ in 0..1 + rng.below(3) {
                let (at, n) = match case % 3 {
                    0 if tip_bases => (bases, 2 * blocks),
                    _ => (pairs, m_r),
                };
                let to = at + 4 * rng.below(n as u32) as usize;
                let old = word(section, to);
                let x = match rng.below(6) {
                    0 => word(section, at + 4 * rng.below(n as u32) as usize),
                    1 => old ^ 1 << (14 + 15 * rng.below(2)),
                    // A NULL tip on the left, or on the right of a WART slot.
                    2 => old & !0x7FFF,
                    3 => 2 << 30 | (old & 0x7FFF),
                    // A field of offset 2, near, or far from a base of 0.
                    4 => old & !(0x7FFF << 15) | (2 | rng.below(2) << 14) << 15,
                    _ => rng.below(u32::MAX),
                };
                section[to..to + 4].copy_from_slice(&x.to_le_bytes());
            }
            match open(&assemble(&sections), &Limits::default()) {
                Ok(_) => opened += 1,
                Err(_) => refused += 1,
            }
        }
        assert!(
            opened > 0 && refused > 0,
            "{opened} opened, {refused} refused ({tip_bases})"
        );
    }
}
