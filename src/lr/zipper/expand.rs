//! The standard LR tables a Zipper encodes, read back in one pass: every slot's tip and
//! flags block by block (each block's planes read once, each side's chain followed slot by
//! slot), and the opposites the ring rules would infer for irregular slots and T0 corners
//! resolved once. The LR's operators then
//! answer as the Zipper's do, several times faster: a verifying reader checks the semantic
//! rules on them (FORMAT.md §5.1 asks the same answers of both).

use super::tables::ZipperTables;
use super::{BLOCK_SHIFT, DELTAS, IRREGULAR_SLOT, NEXT_NEXT_OR_NULL, PREVIOUS, RECORD_WORDS};
use crate::lr::tables::{LrLayout, LrTables, IRREGULAR, LEFT, RIGHT, VALUE, WART};
use crate::words::Words;

impl<W: Words> ZipperTables<W> {
    /// The standard LR tables whose every answer (tips, WART and IRREGULAR flags, the
    /// opposites of irregular slots and T0 corners, rings, C) is this Zipper's: an irregular
    /// slot's record holds both opposites, stored or inferred. Memory: two words per ring
    /// vertex and three per irregular slot and T0 corner.
    pub(crate) fn to_lr_tables(&self) -> LrTables<Vec<u32>> {
        let m_r = self.m_r;
        let mut lr = Vec::with_capacity(2 * m_r as usize);
        let mut vo_star = Vec::new();
        let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);
        for block in 0..blocks {
            let mut slot = self.block_planes(block);
            let first = (block << BLOCK_SHIFT) as u32;
            // Each side's chain value, and the next exception word and record, in slot
            // order: a slot's tip as `slot_tip_and_wart` gives it, without summing the
            // chain from the last stored slot for every slot.
            let mut chain = [LEFT, RIGHT].map(|side| self.chain_head(block, side));
            let (mut x, mut r) = (self.before_block(block, 0), self.before_block(block, 1));
            for v in first..m_r.min(first + (1 << BLOCK_SHIFT)) {
                for side in [LEFT, RIGHT] {
                    slot.bit = 2 * (v - first) + side as u32;
                    let (tip, wart, irregular) = match slot.symbol_at(slot.bit) {
                        s if s < DELTAS => {
                            chain[side] = chain[side].wrapping_sub(s);
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
                            (word & VALUE, word & WART != 0, irregular)
                        }
                    };
                    let flags = if wart { WART } else { 0 };
                    if irregular {
                        lr.push(IRREGULAR | flags | (vo_star.len() / 3) as u32);
                        let opposites = [0, 1].map(|k| super::encode::opposite(self, v, side, k));
                        vo_star.extend([tip, opposites[0], opposites[1]]);
                    } else {
                        lr.push(flags | tip);
                    }
                }
            }
        }
        let copy = |words: &W| {
            (0..words.count())
                .map(|i| words.at(i))
                .collect::<Vec<u32>>()
        };
        LrTables {
            lr,
            vo_v: self.t0_v.iter().collect(),
            vo_o: (0..3 * self.t0_count())
                .map(|k| self.t0_opposite(k))
                .collect(),
            vo_star,
            c: self.c.iter().collect(),
            ring_starts: copy(&self.ring_starts),
            ring_last: copy(&self.ring_last),
            ring_rank: copy(&self.ring_rank),
            m_r,
            m: self.m,
            boundaries_on_ring: self.boundaries_on_ring,
        }
    }
}

/// Whether `lr` answers every operator as `z` does: the same corners, each one's vertex and
/// opposite, and each vertex's corner. The check of [`ZipperTables::to_lr_tables`] in tests
/// and fuzzing.
#[cfg(any(test, fuzzing))]
pub(crate) fn answers_agree<W: Words>(z: &ZipperTables<W>, lr: &LrTables<Vec<u32>>) -> bool {
    use crate::ids::{Corner, Vertex};
    use crate::ops::CornerOps;
    let corners = 8 * z.ring_vertices() + 4 * z.t0_count();
    let slots_agree = (0..z.ring_vertices()).all(|v| {
        [LEFT, RIGHT].into_iter().all(|side| {
            (z.tip_and_wart(v, side), z.irregular(v, side))
                == (lr.tip_and_wart(v, side), lr.irregular(v, side))
        })
    });
    let corners_agree = (0..corners).map(Corner).all(|c| match z.is_corner(c) {
        true => lr.is_corner(c) && (z.vertex(c), z.opposite(c)) == (lr.vertex(c), lr.opposite(c)),
        false => !lr.is_corner(c),
    });
    let vertices_agree = (0..z.vertex_count())
        .map(Vertex)
        .all(|v| z.vertex_corner(v) == lr.vertex_corner(v));
    slots_agree && corners_agree && vertices_agree
}
