//! The standard LR tables a Zipper encodes, read back in one pass: every slot's tip and
//! flags block by block (each block's planes read once, each side's chain followed slot by
//! slot), then as for any layout ([`crate::lr::read_back`]) the opposites of irregular slots
//! and T0 corners resolved once. The LR's operators answer as the Zipper's do, several times
//! faster.

use super::slots::{below, slot_bytes, LEFT_SLOTS};
use super::tables::ZipperTables;
use super::{BLOCK_SHIFT, BLOCK_SLOTS as SLOTS, DELTAS, EXCEPTION, PREVIOUS, RECORD_WORDS};
use crate::lr::read_back::{push_slot, with_slots};
use crate::lr::tables::{LrLayout, LrTables, IRREGULAR, LEFT, NULL, RIGHT, VALUE, WART};
use crate::words::{Bits128, BitsSet, Words};

impl<W: Words> ZipperTables<W> {
    /// The standard LR tables whose every answer (tips, WART and IRREGULAR flags, the
    /// opposites of irregular slots and T0 corners, rings, C) is this Zipper's: an irregular
    /// slot's record holds both opposites, stored or inferred. Memory: two words per ring
    /// vertex and three per irregular slot and T0 corner.
    pub(crate) fn to_lr_tables(&self) -> LrTables<Vec<u32>> {
        let mut lr = Vec::with_capacity(2 * self.m_r as usize);
        let mut vo_star = Vec::new();
        self.each_slot(|slot, read| push_slot(self, slot, read, &mut lr, &mut vo_star));
        with_slots(self, lr, vo_star)
    }

    /// Calls `f` with every slot `(v, side)` in slot order and its tip, WART flag and
    /// whether it is irregular, as `tip_and_wart` and `irregular` give them: block by
    /// block, each block's planes read once and each side's chain followed slot by slot.
    pub(crate) fn each_slot(&self, mut f: impl FnMut((u32, usize), (u32, bool, bool))) {
        let blocks = (self.m_r as usize).div_ceil(1 << BLOCK_SHIFT);
        for block in 0..blocks {
            self.each_slot_of_block(block, &mut f);
        }
    }

    /// [`each_slot`](Self::each_slot) for the slots of block `block` alone (of ring vertices
    /// `64 block ..`, at most 64, below `m_r`), from [`decode_block`](Self::decode_block).
    pub(crate) fn each_slot_of_block(
        &self,
        block: usize,
        mut f: impl FnMut((u32, usize), (u32, bool, bool)),
    ) {
        let mut words = [0u32; SLOTS];
        let slots = self.decode_block(block, &mut words);
        let first = (block << BLOCK_SHIFT) as u32;
        for (bit, &word) in words[..slots].iter().enumerate() {
            let slot = (first + bit as u32 / 2, bit % 2);
            f(
                slot,
                (word & VALUE, word & WART != 0, word & IRREGULAR != 0),
            );
        }
    }

    /// Decodes the slots of block `block` into `out` (bit `2i + side` for the block's ring
    /// vertex `64 block + i`), each as the standard LR's word: its tip (as `tip_and_wart`
    /// gives it) with the `WART` and `IRREGULAR` flags; returns the number of slots (the
    /// words past them are unspecified). No branch on a slot's symbol (taken at random: a
    /// symbol-by-symbol `match` mispredicts about every other slot): each side's chain is a
    /// scan over the slots' bytes of codes, and every word is then chosen from its code,
    /// its chain and the guessed ring steps by masks, in a loop over the whole block that
    /// the compiler vectorizes. The ring steps (`v.p`, `v.n.n`, the next slot's symbol)
    /// come from the block's ring ends, found once, and only at a ring end or the block's
    /// last vertex from the ring tables. Only the stored slots (exception words and
    /// records, a few percent) branch.
    pub(crate) fn decode_block(&self, block: usize, out: &mut [u32; SLOTS]) -> usize {
        let first = (block << BLOCK_SHIFT) as u32;
        let end = self.m_r.min(first + (1 << BLOCK_SHIFT));
        if first >= end {
            return 0;
        }
        let count = (end - first) as usize;
        let slot = self.block_planes(block);
        let ring = BlockRing::new(self, first, end);
        let [p0, p1, p2] = slot.p;
        let fours = self.block_fours(&slot);
        // Whether the next slot of each slot's side is a canonical T2 (symbol 4): from the
        // planes two bits on where `v.n` is `v + 1` in the block, else from the tables.
        let inside = ring.inside_slots();
        let mut next_t2 = (!p0 & !p1 & p2) >> 2 & inside;
        for bit in Bits128(below(2 * count) & !inside) {
            let (v, side) = (first + bit as u32 / 2, bit % 2);
            if self.symbol(ring.next(self, v), side) == PREVIOUS {
                next_t2 |= 1 << bit;
            }
        }
        let before_t2 = if self.wart_deltas { next_t2 } else { 0 };
        // Symbol 5 reads NULL on the right without right fours, but before a canonical T2
        // under WART_DELTAS (`rule_5_is_null_given`).
        let right_null = match self.four_sides & LEFT_SLOTS << RIGHT {
            0 => LEFT_SLOTS << RIGHT,
            _ => 0,
        };
        let null_5 = right_null & !before_t2;
        let codes = slot_bytes([p0, p1, p2, fours, before_t2, null_5]);
        // The stored slots' words (exception words and records in slot order): they reset
        // their side's chain.
        let stored = p1 & p2 & below(2 * count);
        let mut stored_words = [0u32; SLOTS];
        let (mut x, mut r) = (self.before_block(block, 0), self.before_block(block, 1));
        for bit in Bits128(stored) {
            stored_words[bit] = match p0 >> bit & 1 != 0 {
                true => {
                    r += 1;
                    self.records.at(RECORD_WORDS * (r - 1))
                }
                false => {
                    x += 1;
                    self.exceptions.at(x - 1)
                }
            };
        }
        // Each side's chain after each slot: a scan without a branch.
        let mut chains = [0u32; SLOTS];
        let [mut left, mut right] = [LEFT, RIGHT].map(|side| self.chain_head(block, side));
        for i in 0..count {
            let bit = 2 * i;
            left = chain_after(codes[bit], left, stored_words[bit]);
            right = chain_after(codes[bit + 1], right, stored_words[bit + 1]);
            chains[bit] = left;
            chains[bit + 1] = right;
        }
        // Every slot's word from its code, its chain and the ring steps guessed (`v.p` as
        // `v − 1`, `v.n.n` as `v + 2`, corrected below where a ring or the block ends), in
        // a loop without a branch over the whole block (which the compiler vectorizes; the
        // slots past the ring's end are not read).
        for bit in 0..SLOTS {
            let v = first + (bit >> 1) as u32;
            out[bit] = word_of_code(codes[bit], chains[bit], (v.wrapping_sub(1), v + 2));
        }
        // The stored slots' words, with their WART flags.
        for bit in Bits128(stored) {
            let v = first + bit as u32 / 2;
            let word = stored_words[bit];
            let next_is_t2 = || (next_t2 >> bit) & 1 != 0;
            let wart = self.stored_wart_given(word, next_is_t2, || ring.next_next(self, v));
            out[bit] = word_of(word & VALUE, wart, p0 >> bit & 1 != 0);
        }
        // The vertices whose `v.p` or `v.n.n` may be another: a ring's first, a ring's last
        // or the one before it, the block's last. Only symbols 4 and 5 read them (a four
        // and a NULL five do not).
        let steps =
            below(count) as u64 & (ring.firsts | ring.lasts | ring.lasts >> 1) | 1 << (count - 1);
        let (symbol_4, fives) = (!p0 & !p1 & p2, p0 & !p1 & p2 & !fours & !null_5);
        for i in BitsSet(steps) {
            let (v, i) = (first + i, i as usize);
            for bit in [2 * i, 2 * i + 1] {
                if symbol_4 >> bit & 1 != 0 {
                    out[bit] = ring.prev(self, v);
                } else if fives >> bit & 1 != 0 {
                    out[bit] = ring.next_next(self, v);
                }
            }
        }
        2 * count
    }
}

/// A side's chain after a slot whose byte of codes (from [`slot_bytes`]: bits 0–2 the
/// symbol, 3 a four, 4 a delta wart, 5 a NULL five) is `code`, from the chain `chain`
/// before it: less its delta (symbols 0–3, or 4 for a four), or the tip of its stored word
/// `stored` (symbols 6 and 7), or unchanged (symbols 4 and 5 of the ring rules).
#[inline(always)]
fn chain_after(code: u8, chain: u32, stored: u32) -> u32 {
    let code = code as u32;
    let (symbol, four) = (code & 7, code >> 3 & 1);
    let delta = mask_of((symbol < DELTAS) as u32 | four);
    let after = chain.wrapping_sub((symbol - four) & delta);
    select(mask_of((symbol >= EXCEPTION) as u32), stored & VALUE, after)
}

/// The word of a slot that is not stored, from its byte of codes (see [`chain_after`]), its
/// side's chain after it, and `v.p` and `v.n.n` as guessed: a delta's tip is the chain
/// (with the WART flag of a delta wart), symbol 4's `v.p`, symbol 5's `v.n.n` or `NULL`.
/// Each choice by a mask, not a branch.
#[inline(always)]
fn word_of_code(code: u8, chain: u32, (prev, next_next): (u32, u32)) -> u32 {
    let code = code as u32;
    let symbol = code & 7;
    let delta = mask_of((symbol < DELTAS) as u32 | code >> 3 & 1);
    let rule_5 = select(mask_of(code >> 5 & 1), NULL, next_next);
    let ring_tip = select(mask_of(symbol & 1), rule_5, prev);
    select(delta, chain, ring_tip) | WART & delta & mask_of(code >> 4 & 1)
}

/// The ring steps of the vertices of one block, `first .. end`: which of them end their
/// ring (`lasts`) and which start one (`firsts`), bit `v - first`, read once; a step from
/// a ring end (or from outside the block) is left to the ring tables.
struct BlockRing {
    first: u32,
    end: u32,
    lasts: u64,
    firsts: u64,
    one_ring: bool,
}

impl BlockRing {
    fn new<W: Words>(t: &ZipperTables<W>, first: u32, end: u32) -> BlockRing {
        let one_ring = t.ring_count() == 1;
        let is_last = |v: u32| match one_ring {
            true => v + 1 == t.ring_vertices(),
            false => t.is_last(v),
        };
        let lasts = match one_ring {
            // The ring's one end, when in the block (`first` is at most `m_r − 1`).
            true => {
                let last = t.ring_vertices() - 1;
                ((last < end) as u64) << (last - first).min(63)
            }
            false => (first..end).fold(0, |lasts, v| lasts | (is_last(v) as u64) << (v - first)),
        };
        let first_starts = first == 0 || is_last(first - 1);
        BlockRing {
            first,
            end,
            lasts,
            firsts: lasts << 1 | first_starts as u64,
            one_ring,
        }
    }

    /// `v.n`, as `ring_next` gives it.
    #[inline(always)]
    fn next<W: Words>(&self, t: &ZipperTables<W>, v: u32) -> u32 {
        match v >= self.first && v < self.end && self.lasts >> (v - self.first) & 1 == 0 {
            true => v + 1,
            false => t.ring_next(v),
        }
    }

    /// The slots (bit `2i + side` of the block's vertex `first + i`) whose vertex's `v.n` is
    /// `v + 1` in the block: not a ring end, nor the block's last vertex.
    #[inline(always)]
    fn inside_slots(&self) -> u128 {
        let count = self.end - self.first;
        // Vertices `i` with `i + 1 < count` and no ring end, one bit each.
        let vertices = !self.lasts & u64::MAX.checked_shr(65 - count).unwrap_or(0);
        let spread = spread_bits(vertices as u32) as u128
            | (spread_bits((vertices >> 32) as u32) as u128) << 64;
        spread | spread << 1
    }

    /// `v.p`, as `ring_prev` gives it (`v` in the block).
    #[inline(always)]
    fn prev<W: Words>(&self, t: &ZipperTables<W>, v: u32) -> u32 {
        match self.firsts >> (v - self.first) & 1 == 0 {
            true => v - 1,
            false => t.ring_prev(v),
        }
    }

    /// `v.n.n`, as `ring_next_next` gives it.
    #[inline(always)]
    fn next_next<W: Words>(&self, t: &ZipperTables<W>, v: u32) -> u32 {
        match self.one_ring {
            true => t.ring_next_next(v),
            false => self.next(t, self.next(t, v)),
        }
    }
}

/// The bits of `x` spread to the even bits of a 64-bit word (bit `i` to bit `2i`).
#[inline(always)]
fn spread_bits(x: u32) -> u64 {
    let mut x = x as u64;
    x = (x | x << 16) & 0x0000_FFFF_0000_FFFF;
    x = (x | x << 8) & 0x00FF_00FF_00FF_00FF;
    x = (x | x << 4) & 0x0F0F_0F0F_0F0F_0F0F;
    x = (x | x << 2) & 0x3333_3333_3333_3333;
    (x | x << 1) & 0x5555_5555_5555_5555
}

/// All ones when `bit` (0 or 1) is 1, else 0: for [`select`].
#[inline(always)]
fn mask_of(bit: u32) -> u32 {
    0u32.wrapping_sub(bit)
}

/// `a` where `mask` is all ones, `b` where it is 0, without a branch.
#[inline(always)]
fn select(mask: u32, a: u32, b: u32) -> u32 {
    (a & mask) | (b & !mask)
}

/// A slot's word as the standard LR stores it: its tip with the `WART` and `IRREGULAR` flags.
#[inline(always)]
fn word_of(tip: u32, wart: bool, irregular: bool) -> u32 {
    tip | if wart { WART } else { 0 } | if irregular { IRREGULAR } else { 0 }
}
