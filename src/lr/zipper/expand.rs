//! The standard LR tables a Zipper encodes, read back in one pass: every slot's tip and
//! flags block by block (each block's planes read once, each side's chain followed slot by
//! slot), then as for any layout ([`crate::lr::read_back`]) the opposites of irregular slots
//! and T0 corners resolved once. The LR's operators answer as the Zipper's do, several times
//! faster.

use super::slots::plane_bit;
use super::tables::ZipperTables;
use super::{BLOCK_SHIFT, DELTAS, FOUR, IRREGULAR_SLOT, NEXT_NEXT_OR_NULL, PREVIOUS, RECORD_WORDS};
use crate::lr::read_back::{push_slot, with_slots};
use crate::lr::tables::{LrLayout, LrTables, LEFT, NULL, RIGHT, VALUE};
use crate::words::Words;

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
    /// `64 block ..`, at most 64, below `m_r`). The ring steps the slots need (`v.n` for the
    /// next slot's symbol, `v.p` and `v.n.n` for the ring rules' tips) are taken from the
    /// block's ring ends, found once, instead of from the ring tables for every slot.
    pub(crate) fn each_slot_of_block(
        &self,
        block: usize,
        mut f: impl FnMut((u32, usize), (u32, bool, bool)),
    ) {
        let m_r = self.m_r;
        let first = (block << BLOCK_SHIFT) as u32;
        let end = m_r.min(first + (1 << BLOCK_SHIFT));
        if first >= end {
            return;
        }
        let mut slot = self.block_planes(block);
        let ring = BlockRing::new(self, first, end);
        // Each side's chain value, and the next exception word and record, in slot order: a
        // slot's tip as `tip_and_wart` gives it, without summing the chain from the last
        // stored slot for every slot.
        let mut chain = [LEFT, RIGHT].map(|side| self.chain_head(block, side));
        let fours = self.block_fours(&slot);
        let (mut x, mut r) = (self.before_block(block, 0), self.before_block(block, 1));
        // Whether the next slot of (v, side)'s side has symbol 4: for every slot at once from
        // the block's planes where `v.n` is `v + 1` in the block (the slot two bits on),
        // else read as `next_is_t2` reads it.
        let [p0, p1, p2] = slot.p;
        let inside = ring.inside_slots();
        let next_t2 = (!p0 & !p1 & p2) >> 2 & inside;
        let next_is_t2 = |v: u32, side: usize| {
            let bit = 2 * (v - first) + side as u32;
            if plane_bit(inside, bit) != 0 {
                return plane_bit(next_t2, bit) != 0;
            }
            self.symbol(ring.next(self, v), side) == PREVIOUS
        };
        for v in first..end {
            for side in [LEFT, RIGHT] {
                slot.bit = 2 * (v - first) + side as u32;
                let four = plane_bit(fours, slot.bit) != 0;
                let read = match slot.symbol_at(slot.bit) {
                    s if s < DELTAS || four => {
                        chain[side] = chain[side].wrapping_sub(if four { FOUR } else { s });
                        let wart = self.wart_deltas && next_is_t2(v, side);
                        (chain[side], wart, false)
                    }
                    PREVIOUS => (ring.prev(self, v), false, false),
                    NEXT_NEXT_OR_NULL => {
                        // As `ring_rule_tip` gives it.
                        let null = self.rule_5_is_null_given(side, || next_is_t2(v, side));
                        let tip = if null { NULL } else { ring.next_next(self, v) };
                        (tip, false, false)
                    }
                    s => {
                        let irregular = s == IRREGULAR_SLOT;
                        let word = match irregular {
                            true => self.records.at(RECORD_WORDS * r),
                            false => self.exceptions.at(x),
                        };
                        (r, x) = (r + irregular as usize, x + !irregular as usize);
                        chain[side] = word & VALUE;
                        let wart = self.stored_wart_given(
                            word,
                            || next_is_t2(v, side),
                            || ring.next_next(self, v),
                        );
                        (word & VALUE, wart, irregular)
                    }
                };
                f((v, side), read);
            }
        }
    }
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
        let mut lasts = 0u64;
        for v in first..end {
            lasts |= (is_last(v) as u64) << (v - first);
        }
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
