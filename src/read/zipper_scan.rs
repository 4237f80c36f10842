//! The well-formed open's fast path over the Zipper's slots (rule V58, and the slot flags of
//! [`SlotMap`](super::lr_rules::SlotMap)): the exception and record words in linear passes
//! of their own, then block by block, the slots' flags as bit masks of the block's symbol
//! planes, with no branch on a symbol (the symbols follow no pattern a branch predictor
//! could learn: a mispredicted branch per slot cost more than the rest of the pass) and the
//! chains decoded only where a range test cannot clear them. It only says whether the rule
//! holds: when it does not, the reader's slot-by-slot loop (`check_slots`) finds the first
//! fault and names it.

use super::lr_rules::{slot_flag_masks, SlotBits};
use crate::lr::zipper::{
    below, implied_wart, slot_bytes, Slot, BLOCK_SHIFT, DELTAS, FOUR, LEFT_SLOTS, PREVIOUS,
    RECORD_WORDS, STATE_SHIFT, STORES_BOTH, STORES_FIRST, STORES_NONE, STORES_SECOND,
};
use crate::lr::{LrLayout, ZipperTables, VALUE, WART};
use crate::words::{Bits128, BitsSet};
use crate::words::{LeWords, Words};

type Tables<'a> = ZipperTables<LeWords<'a>>;

/// A block's 128 symbols as bytes ([`slot_bytes`] of its planes).
pub(super) fn block_symbols(slot: &Slot) -> [u8; 128] {
    slot_bytes(slot.p)
}

/// Whether an exception word or a record's first word holds only a WART flag and a vertex
/// below `m`.
#[inline(always)]
pub(super) fn tip_word_holds(word: u32, m: u32) -> bool {
    (word & !(WART | VALUE) == 0) & (word & VALUE < m)
}

/// [V58]'s rules on the exception and record words alone (`records`: both words of each
/// record, in order): every such word a WART flag and a vertex, record word 1 what
/// FORMAT.md §3.5e allows, the pairs used once each in order.
fn words_hold(t: &Tables, m: u32, exceptions: &[u32], records: &[u32]) -> bool {
    let n0 = t.t0_count() as u64;
    let exceptions_hold = exceptions
        .iter()
        .fold(true, |ok, &word| ok & tip_word_holds(word, m));
    let mut pairs = 0usize;
    let records_hold = records.chunks_exact(RECORD_WORDS).all(|record| {
        let (first, second) = (record[0], record[1]);
        let value = second & ((1 << STATE_SHIFT) - 1);
        let second_holds = match second >> STATE_SHIFT {
            // ROW_RECORDS: a T0 row or a pair.
            STORES_FIRST if t.row_records => (value as u64) < n0,
            STORES_NONE | STORES_SECOND if t.row_records => false,
            STORES_NONE => value == 0,
            STORES_FIRST | STORES_SECOND => (value as u64) < 4 * n0 && value % 4 != 3,
            STORES_BOTH => {
                pairs += 1;
                value as usize == pairs - 1
            }
            _ => false,
        };
        tip_word_holds(first, m) && second_holds
    });
    exceptions_hold
        && records_hold
        && records.len() % RECORD_WORDS == 0
        && 2 * pairs == t.pairs.count()
}

/// What the slots of one block need of the ring: whether the slot on its side of `v.n` has
/// symbol 4 (a canonical T2), and the range of the slots' `v.n.n` ([`Neighbours::nn`] gives
/// each). Arithmetic (`v + 2`, the slot two bits on) except at *special* vertices: the
/// block's first and last and those next to a ring's end, found from the ring-end bits.
struct Neighbours {
    first: u32,
    /// The special vertices, bit `k` for vertex `first + k`.
    special: u64,
    /// Bit `2k + side`: the slot on `side` of vertex `first + k`'s next has symbol 4.
    next_is_t2: u128,
    /// The least and the greatest `v.n.n` of the block's vertices.
    nn_low: u32,
    nn_high: u32,
}

impl Neighbours {
    fn of_block(t: &Tables, first: u32, used: usize, slot: &Slot) -> Neighbours {
        let [p0, p1, p2] = slot.p;
        let t2 = !p0 & !p1 & p2;
        let count = used / 2;
        let ends = ring_ends(t, first, count);
        // A vertex that ends its ring, follows or precedes one that does, the block's first
        // (which may start a ring) and last.
        let special =
            (ends | ends >> 1 | ends << 1 | 1 | 1 << (count - 1)) & (u64::MAX >> (64 - count));
        // As two words: a `u128` shift by a variable amount per slot costs a branch.
        let mut next_is_t2 = [(t2 >> 2) as u64, (t2 >> 66) as u64];
        let (mut nn_low, mut nn_high) = (first + 2, first + count as u32 + 1);
        for k in BitsSet(special) {
            let v = first + k;
            let next = t.ring_next(v);
            let nn = t.ring_next(next);
            (nn_low, nn_high) = (nn_low.min(nn), nn_high.max(nn));
            // The shift above read the next vertex's slots when they are in this block.
            if next == v + 1 && k as usize + 1 < count {
                continue;
            }
            for side in 0..2 {
                let bit = 2 * k as usize + side;
                let is_t2 = t.symbol(next, side) == PREVIOUS;
                let (word, at) = (bit / 64, bit % 64);
                next_is_t2[word] = next_is_t2[word] & !(1 << at) | (is_t2 as u64) << at;
            }
        }
        Neighbours {
            first,
            special,
            next_is_t2: next_is_t2[0] as u128 | (next_is_t2[1] as u128) << 64,
            nn_low,
            nn_high,
        }
    }

    /// Every slot's `v.n.n` (slots past the used ones read `v + 2` of their place).
    fn nn(&self, t: &Tables) -> [u32; 128] {
        let mut nn: [u32; 128] = std::array::from_fn(|bit| self.first + bit as u32 / 2 + 2);
        for k in BitsSet(self.special) {
            let v = self.first + k;
            let value = t.ring_next_next(v);
            nn[2 * k as usize] = value;
            nn[2 * k as usize + 1] = value;
        }
        nn
    }
}

/// The ring-end bits of the `count` vertices from `first` (a multiple of 64).
fn ring_ends(t: &Tables, first: u32, count: usize) -> u64 {
    if t.ring_count() == 1 {
        let last = t.m_r - 1;
        return if last - first < count as u32 {
            1 << (last - first)
        } else {
            0
        };
    }
    if t.ring_blocks.count() > 0 {
        // RING_BLOCKS: the ends of the rings from the block's first vertex's on.
        let end = first as u64 + count as u64;
        let mut bits = 0;
        let mut ring = t.ring_blocks.at((first >> BLOCK_SHIFT) as usize) as usize;
        while ring < t.ring_count() {
            let last = t.ring_start(ring + 1) as u64 - 1;
            if last >= end {
                break;
            }
            bits |= 1 << (last - first as u64);
            ring += 1;
        }
        return bits;
    }
    let word = |i: u32| {
        let i = (first / 32 + i) as usize;
        if i < t.ring_last.count() {
            t.ring_last.at(i) as u64
        } else {
            0
        }
    };
    word(0) | word(1) << 32
}

/// Each side's chain through block `block` (`used` slots): the tip of every delta slot,
/// its side's tip decremented by its symbol (a four's by 4), in runs between the stored slots (whose words
/// `chained` already holds), without a branch per slot.
fn chain_block(
    t: &Tables,
    block: usize,
    used: usize,
    symbols: &[u8; 128],
    (stored, fours): (u128, u128),
    chained: &mut [u32; 128],
) {
    let mut deltas = symbols.map(|s| if (s as u32) < DELTAS { s } else { 0 });
    for bit in Bits128(fours) {
        deltas[bit] = FOUR as u8;
    }
    for side in 0..2 {
        let mut chain = t.chain_head(block, side);
        let mut bit = side;
        let resets = Bits128(stored & LEFT_SLOTS << side);
        for end in resets.chain(std::iter::once(used)) {
            while bit < end {
                chain = chain.wrapping_sub(deltas[bit] as u32);
                chained[bit] = chain;
                bit += 2;
            }
            if let Some(&value) = chained.get(end) {
                chain = value;
            }
            bit = end + 2;
        }
    }
}

/// Whether every chained tip of the block (its delta and stored slots) is surely a vertex
/// and none is a `v.n.n` of the block, without chaining. On each side a chain runs from a
/// start `b` (the anchor, or a stored slot's word) and only decreases, by at most `d`, the
/// side's delta symbols' sum, so its tips lie in `[b − d, b]`: clear when each such interval
/// lies within `0 .. m` and misses the block's range of `v.n.n` (`n`). Most blocks pass,
/// their tips on another turn of the ring; near a turn's end, where tips come close to
/// their own slots, [`runs_clear`] looks run by run.
fn chains_clear(
    t: &Tables,
    (slot, fours): (&Slot, u128),
    block: usize,
    chained: &[u32; 128],
    n: &Neighbours,
    m: u32,
) -> bool {
    let stored = slot.stored();
    (0..2).all(|side| {
        let d = decrement(slot, fours, LEFT_SLOTS << side);
        let clear = |b: u32| interval_clear(b, d, m, n.nn_low, n.nn_high);
        clear(t.chain_head(block, side))
            && Bits128(stored & LEFT_SLOTS << side).all(|bit| clear(chained[bit]))
    })
}

/// The sum of the delta symbols of `slots` (4 for each of the `fours`): how far a chain
/// decreases over them.
fn decrement(slot: &Slot, fours: u128, slots: u128) -> u32 {
    let deltas = !slot.p[2] & slots;
    (slot.p[0] & deltas).count_ones()
        + 2 * (slot.p[1] & deltas).count_ones()
        + FOUR * (fours & slots).count_ones()
}

/// Whether tips in `[b − d, b]` are all vertices (below `m`, none below 0) and none lies in
/// `[low, high]`. Bitwise, so that `b − d` is computed when `b < d` too, but never used.
fn interval_clear(b: u32, d: u32, m: u32, low: u32, high: u32) -> bool {
    (b < m) & (b >= d) & ((b < low) | (b.wrapping_sub(d) > high))
}

/// [`chains_clear`] run by run (`nn`: each used slot's `v.n.n`), for a block whose `v.n.n`
/// increase along it (no ring ends there): a run's tips decrease while its slots' `v.n.n`
/// increase, so the tips are all below or all above them when the first is below the first
/// or the last above the last.
#[inline(never)]
fn runs_clear(
    t: &Tables,
    (slot, fours): (&Slot, u128),
    block: usize,
    chained: &[u32; 128],
    nn: &[u32],
    m: u32,
) -> bool {
    if !nn.windows(2).all(|w| w[0] <= w[1]) {
        return false;
    }
    let stored = slot.stored();
    (0..2).all(|side| {
        let mine = LEFT_SLOTS << side & below(nn.len());
        let (mut b, mut from) = (t.chain_head(block, side), 0);
        Bits128(stored & mine)
            .chain(std::iter::once(128))
            .all(|end| {
                let run = mine & !below(from) & below(end);
                let clear = run == 0 || {
                    let (first, last) = (run.trailing_zeros(), 127 - run.leading_zeros());
                    interval_clear(
                        b,
                        decrement(slot, fours, run),
                        m,
                        nn[first as usize],
                        nn[last as usize],
                    )
                };
                if end < 128 {
                    (b, from) = (chained[end], end);
                }
                clear
            })
    })
}

/// 128 bytes of 0 or 1 as the bits of a `u128`, eight at a time: a multiply moves byte
/// `k`'s low bit of a `u64` to bit `56 + k`, every other product of the sum landing above
/// bit 63 or below bit 56, each at a bit of its own (no carries).
fn pack_bits(bytes: &[u8; 128]) -> u128 {
    bytes.chunks_exact(8).rev().fold(0u128, |bits, eight| {
        let x = u64::from_le_bytes(eight.try_into().expect("eight bytes"));
        bits << 8 | (x.wrapping_mul(0x0102_0408_1020_4080) >> 56) as u128
    })
}

/// [V58] on every slot, and the slot flags as [`SlotBits`], with the number of canonical ones;
/// `None` when the rule fails.
pub(super) fn scan_slots(t: &Tables) -> Option<(SlotBits, u64)> {
    let (m, m_r) = (t.m, t.m_r);
    // The exception and record words decoded once, in order, for both checks (the lists may
    // be bit fields: a field read in the slot loop kept its step from being inlined).
    let exception_words: Vec<u32> = t.exceptions.iter().collect();
    let record_words: Vec<u32> = t.records.iter().collect();
    if !words_hold(t, m, &exception_words, &record_words) {
        return None;
    }
    let (exception_count, record_count) = (t.exceptions.count(), t.record_count());
    // Word 0 in place of a word past the end: the counts below fail the scan then.
    let exception = |i: usize| exception_words.get(i).copied().unwrap_or(0);
    let record = |i: usize| record_words.get(RECORD_WORDS * i).copied().unwrap_or(0);
    // Per 64 slots the canonical and the jumping ones ([`SlotBits`]): four words per block
    // (the last block's last two may be past the last slot: dropped).
    let words = 2 * (2 * m_r as usize).div_ceil(64);
    let mut bits = Vec::with_capacity(words + 2);
    let mut canonical = 0u64;
    let (mut exceptions, mut records) = (0usize, 0usize);
    let mut bad = false;
    // Each block's chained tips: written for its stored slots first, then (when the range
    // test cannot clear the block) for its delta slots; every other entry is masked out
    // where it is read, so the array is not cleared between blocks (512 bytes a block).
    let mut chained = [0u32; 128];
    for block in 0..(m_r as usize).div_ceil(1 << BLOCK_SHIFT) {
        // Spelled out: through an array's `map` the head reads were not inlined.
        bad |= (t.before_block(block, 0) != exceptions) | (t.before_block(block, 1) != records);
        let first = (block << BLOCK_SHIFT) as u32;
        let slot = t.block_planes(block);
        let used = 2 * ((m_r - first) as usize).min(1 << BLOCK_SHIFT);
        let beyond = if used == 128 { 0 } else { u128::MAX << used };
        bad |= slot.p.iter().any(|p| p & beyond != 0);
        // The chains: each side's tip decremented by its delta symbols and set by its
        // exception and irregular slots (a few in a hundred). First the stored words, in
        // slot order (a list's words are used in that order).
        let stored = slot.stored();
        // Each list's words in its own slot order; the WART bits set in 64-bit halves (a
        // `u128` shift by a variable amount costs a branch).
        let mut wart_halves = [0u64; 2];
        let mut take = |bit: usize, word: u32| {
            wart_halves[bit / 64] |= ((word & WART != 0) as u64) << (bit % 64);
            chained[bit] = word & VALUE;
        };
        for bit in Bits128(slot.exceptions()) {
            take(bit, exception(exceptions));
            exceptions += 1;
        }
        for bit in Bits128(slot.irregular()) {
            take(bit, record(records));
            records += 1;
        }
        let n = Neighbours::of_block(t, first, used, &slot);
        let stored_wart = match t.implied_warts {
            false => wart_halves[0] as u128 | (wart_halves[1] as u128) << 64,
            // IMPLIED_WARTS: a stored slot before a canonical T2 whose tip is not `v.n.n`
            // (a few in a thousand slots are before one).
            true => Bits128(stored & n.next_is_t2).fold(0, |warts, bit| {
                let v = first + bit as u32 / 2;
                let wart = implied_wart(true, chained[bit], t.ring_next_next(v));
                warts | (wart as u128) << bit
            }),
        };
        let [p0, p1, p2] = slot.p;
        let fours = t.block_fours(&slot);
        let (delta, rule_5, irregular) = (!p2 | fours, p0 & !p1 & p2 & !fours, slot.irregular());
        let from_chain = delta | stored;
        // The slots whose chained tip is `v.n.n`. A block whose chains provably reach
        // neither outside the vertices nor one of its `v.n.n` (most) skips the chains; the
        // others chain each side in runs between its stored slots.
        let mut chained_next_next = 0u128;
        if !chains_clear(t, (&slot, fours), block, &chained, &n, m) {
            let nn = n.nn(t);
            if !runs_clear(t, (&slot, fours), block, &chained, &nn[..used], m) {
                let symbols = block_symbols(&slot);
                chain_block(t, block, used, &symbols, (stored, fours), &mut chained);
                let mut outside = [0u8; 128];
                let mut at_next_next = [0u8; 128];
                for bit in 0..128 {
                    outside[bit] = (chained[bit] >= m) as u8;
                    at_next_next[bit] = (chained[bit] == nn[bit]) as u8;
                }
                bad |= pack_bits(&outside) & from_chain & below(used) != 0;
                chained_next_next = pack_bits(&at_next_next);
            }
        }
        // Every slot's flags at once, as bit masks (`slot_flag_masks`). A chained
        // tip in range is never `NULL`; a ring rule's tip is `v.p` (a vertex, never `v.n.n`
        // on a ring of 4 or more, V16), `v.n.n` or `NULL` (symbol 5, on the right unless the
        // slot is a wart's).
        let before_t2 = if t.wart_deltas { n.next_is_t2 } else { 0 };
        // With RIGHT_FOURS a right symbol 5 that is not a four is a redundant copy.
        let right_nulls = if t.fours()[1] { 0 } else { LEFT_SLOTS << 1 };
        let null = rule_5 & right_nulls & !before_t2;
        let next_next = (from_chain & chained_next_next) | (rule_5 & !null);
        let wart = (delta & before_t2) | stored_wart;
        let (block_canonical, jumps) = slot_flag_masks(next_next, !null, wart, irregular);
        let (block_canonical, jumps) = (block_canonical & below(used), jumps & below(used));
        bits.extend([block_canonical, jumps].map(|m| m as u64));
        bits.extend([block_canonical, jumps].map(|m| (m >> 64) as u64));
        canonical += block_canonical.count_ones() as u64;
    }
    bad |= (exceptions != exception_count) | (records != record_count);
    bits.truncate(words);
    let bits = SlotBits {
        words: bits,
        len: 2 * m_r as usize,
    };
    (!bad).then_some((bits, canonical))
}

#[cfg(test)]
mod tests;
