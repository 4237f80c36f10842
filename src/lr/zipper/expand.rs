//! The standard LR tables a Zipper encodes, read back in one pass: every slot's tip and
//! flags block by block (each block's planes read once, each side's chain followed slot by
//! slot), then as for any layout ([`crate::lr::read_back`]) the opposites of irregular slots
//! and T0 corners resolved once. The LR's operators answer as the Zipper's do, several times
//! faster.

use super::tables::ZipperTables;
use super::{BLOCK_SHIFT, DELTAS, FOUR, IRREGULAR_SLOT, NEXT_NEXT_OR_NULL, PREVIOUS, RECORD_WORDS};
use crate::lr::read_back::{push_slot, with_slots};
use crate::lr::tables::{LrTables, LEFT, RIGHT, VALUE};
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
        let m_r = self.m_r;
        let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);
        for block in 0..blocks {
            let mut slot = self.block_planes(block);
            let first = (block << BLOCK_SHIFT) as u32;
            // Each side's chain value, and the next exception word and record, in slot
            // order: a slot's tip as `tip_and_wart` gives it, without summing the chain
            // from the last stored slot for every slot.
            let mut chain = [LEFT, RIGHT].map(|side| self.chain_head(block, side));
            let fours = self.block_fours(&slot);
            let (mut x, mut r) = (self.before_block(block, 0), self.before_block(block, 1));
            for v in first..m_r.min(first + (1 << BLOCK_SHIFT)) {
                for side in [LEFT, RIGHT] {
                    slot.bit = 2 * (v - first) + side as u32;
                    let four = fours >> slot.bit & 1 != 0;
                    let read = match slot.symbol_at(slot.bit) {
                        s if s < DELTAS || four => {
                            chain[side] = chain[side].wrapping_sub(if four { FOUR } else { s });
                            let wart = self.before_t2(v, side, slot.group());
                            (chain[side], wart, false)
                        }
                        s @ (PREVIOUS | NEXT_NEXT_OR_NULL) => {
                            (self.ring_rule_tip(&slot, v, side, s), false, false)
                        }
                        s => {
                            let irregular = s == IRREGULAR_SLOT;
                            let word = match irregular {
                                true => self.records.at(RECORD_WORDS * r),
                                false => self.exceptions.at(x),
                            };
                            (r, x) = (r + irregular as usize, x + !irregular as usize);
                            chain[side] = word & VALUE;
                            let wart = self.stored_slot_wart(v, side, word, slot.group());
                            (word & VALUE, wart, irregular)
                        }
                    };
                    f((v, side), read);
                }
            }
        }
    }
}
