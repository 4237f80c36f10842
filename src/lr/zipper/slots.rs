//! Reading a slot of the Zipper tables: the symbol planes of its block ([`Slot`]), the
//! block's heads (chain anchors, counts before it), the chains of delta slots with their
//! fours, the stored words of exception and irregular slots with their WART flags, and the
//! T0 row a row record names (FORMAT.md §3.5e, OPERATORS.md §8).

use super::tables::ZipperTables;
use super::{
    BLOCK_SHIFT, COMPACT_SUPER_SHIFT, FOUR, HEAD_WORDS, PLANE_WORDS, PREVIOUS, RECORD_WORDS,
    SHORT_HEAD_WORDS, SUPER_SHIFT,
};
use crate::lr::tables::{LrLayout, LEFT, NULL, RIGHT, VALUE, WART};
use crate::words::Words;

/// The bits of the left slots of a block (slot `2i + side`).
pub(crate) const LEFT_SLOTS: u128 = 0x5555_5555_5555_5555_5555_5555_5555_5555;

/// The symbol planes of one block and where a slot lies in them.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Slot {
    pub block: usize,
    /// The slot's bit: `2i + side`.
    pub bit: u32,
    pub p: [u128; 3],
}

impl Slot {
    /// The symbol of the slot at `bit`.
    #[inline(always)]
    pub fn symbol_at(&self, bit: u32) -> u32 {
        // From the 64-bit halves that hold the bit: a shift of a `u128` by a variable amount
        // takes several instructions per plane.
        let [a, b, c] = self.p.map(|p| plane_bit(p, bit));
        a | b << 1 | c << 2
    }

    /// The three words of the slot's group (always among the planes read).
    #[inline]
    pub fn group(&self) -> [u32; 3] {
        self.p.map(|p| (p >> (self.bit & !31)) as u32)
    }

    /// The block's exception slots, one bit each.
    #[inline]
    pub fn exceptions(&self) -> u128 {
        !self.p[0] & self.p[1] & self.p[2]
    }

    /// The block's irregular slots.
    #[inline]
    pub fn irregular(&self) -> u128 {
        self.p[0] & self.p[1] & self.p[2]
    }

    /// The block's slots whose word is stored: exception and irregular slots.
    #[inline]
    pub fn stored(&self) -> u128 {
        self.p[1] & self.p[2]
    }

    /// The block's *fours* among the slots `sides` (FORMAT.md §3.5e.4): symbol 5 where the
    /// slot two bits on (the next vertex's on the same side; none past the block) is not
    /// symbol 4, but for the last ring vertex's slots (`last`: their bits, if in the block).
    #[inline(always)]
    pub fn fours(&self, sides: u128, last: u128) -> u128 {
        let [p0, p1, p2] = self.p;
        let t2 = !p0 & !p1 & p2;
        p0 & !p1 & p2 & sides & !(t2 >> 2) & !last
    }
}

/// Bit `bit` of a plane, from the 64-bit half that holds it (a shift of a `u128` by a
/// variable amount takes several instructions).
#[inline(always)]
pub(super) fn plane_bit(p: u128, bit: u32) -> u32 {
    let half = if bit < 64 { p as u64 } else { (p >> 64) as u64 };
    (half >> (bit % 64) & 1) as u32
}

/// The symbol of bit `b` of a group's three words.
#[inline]
pub(super) fn group_symbol(g: [u32; 3], b: usize) -> u32 {
    (g[0] >> b) & 1 | ((g[1] >> b) & 1) << 1 | ((g[2] >> b) & 1) << 2
}

/// The WART flag that `IMPLIED_WARTS` gives an exception or irregular slot whose tip is
/// `tip` (FORMAT.md §3.5e.5): the next slot of its side has symbol 4 (`next_is_t2`) and the
/// tip is not `v.n.n` (`next_next`), which would be the T2's redundant copy. The one
/// definition that the operators, the open's fast pass and the slot-by-slot check share.
#[inline(always)]
pub(crate) fn implied_wart(next_is_t2: bool, tip: u32, next_next: u32) -> bool {
    next_is_t2 && tip != next_next
}

/// The edges that the transversal corners of slot `(v, side)` face, corner 0 (`8v + 0` or
/// `8v + 4`) then 1 (`8v + 2` or `8v + 6`), for its tip and far vertex: the left triangle is
/// `(v, tip, far)`, the right `(far, tip, v)`.
pub(crate) fn slot_edges(v: u32, side: usize, tip: u32, far: u32) -> [[u32; 2]; 2] {
    match side {
        LEFT => [[tip, far], [v, tip]],
        _ => [[tip, v], [far, tip]],
    }
}

/// The first of `edges` (by index `k`) whose two ends are both vertices of the T0 row
/// `row`, with the row's corner `i` at its third vertex (FORMAT.md §3.5e.5).
pub(crate) fn row_corner(edges: [[u32; 2]; 2], row: [u32; 3]) -> Option<(usize, u32)> {
    edges.iter().enumerate().find_map(|(k, &[x, y])| {
        let third = (0..3).find(|&i| row[i as usize] != x && row[i as usize] != y)?;
        let ends = row.iter().filter(|&&w| w == x || w == y).count();
        (x != y && ends == 2 && row.contains(&x) && row.contains(&y)).then_some((k, third))
    })
}

/// The slots whose symbol 5 may be a four: the left ones with `LEFT_FOURS`, the right ones
/// with `RIGHT_FOURS` (FORMAT.md §3.5e.4).
pub(crate) fn four_sides(left: bool, right: bool) -> u128 {
    (if left { LEFT_SLOTS } else { 0 }) | (if right { LEFT_SLOTS << 1 } else { 0 })
}

/// The bits of the last ring vertex's slots in block `block` (none in the others).
#[inline(always)]
pub(crate) fn last_vertex_bits(m_r: u32, block: usize) -> u128 {
    let first = (block << BLOCK_SHIFT) as u32;
    match m_r - first <= 1 << BLOCK_SHIFT {
        true => 3 << (2 * (m_r - first - 1)),
        false => 0,
    }
}

/// Byte `i` of `SPREAD[b]` is bit `i` of `b`.
const SPREAD: [u64; 256] = {
    let mut table = [0; 256];
    let mut b = 0;
    while b < 256 {
        let mut i = 0;
        while i < 8 {
            table[b] |= ((b as u64 >> i) & 1) << (8 * i);
            i += 1;
        }
        b += 1;
    }
    table
};

/// A byte per slot of a block whose bit `k` is the slot's bit in `masks[k]` (a block's
/// symbol planes, and the masks a decoder adds to them), eight slots at a time by table
/// lookups: a shift of a `u128` by a variable amount per slot costs more than the rest of a
/// loop over the slots.
#[inline(always)]
pub(crate) fn slot_bytes<const N: usize>(masks: [u128; N]) -> [u8; 128] {
    let bytes = masks.map(u128::to_le_bytes);
    let mut slots = [0; 128];
    for (k, eight) in slots.chunks_exact_mut(8).enumerate() {
        let mut word = 0;
        for (j, mask) in bytes.iter().enumerate() {
            word |= SPREAD[mask[k] as usize] << j;
        }
        eight.copy_from_slice(&word.to_le_bytes());
    }
    slots
}

/// The bits below bit `k` (all for `k` = 128).
#[inline]
pub(crate) fn below(k: usize) -> u128 {
    u128::MAX.checked_shr(128 - k as u32).unwrap_or(0)
}

/// Bits `0..=i`.
#[inline]
pub(super) fn up_to(i: u32) -> u128 {
    u128::MAX >> (127 - i)
}

/// Words of the plane array for `m_r` ring vertices: three per group of 32 slots (16 ring
/// vertices), 12 per block.
pub fn plane_array_words(m_r: u32) -> usize {
    3 * (2 * m_r as usize).div_ceil(32)
}

impl<W: Words> ZipperTables<W> {
    /// The three plane words of group `g` (slots `32g ..`, counted over the whole ring).
    #[inline]
    pub(super) fn group(&self, g: usize) -> [u32; 3] {
        self.planes.array(3 * g)
    }

    /// The symbol of slot `(v, side)`, from its group's three words alone.
    #[inline]
    pub(crate) fn symbol(&self, v: u32, side: usize) -> u32 {
        let slot = 2 * v as usize + side;
        group_symbol(self.group(slot / 32), slot % 32)
    }

    /// The planes of slot `(v, side)`'s block (every group of it: a four is told by the slot
    /// two bits on, which may lie in the next group).
    #[inline(always)]
    pub(crate) fn slot(&self, v: u32, side: usize) -> Slot {
        let block = (v >> BLOCK_SHIFT) as usize;
        let bit = 2 * (v & ((1 << BLOCK_SHIFT) - 1)) + side as u32;
        Slot {
            bit,
            ..self.block_planes(block)
        }
    }

    /// The planes of block `block`'s groups `0..=last` (of all four when the block is
    /// whole: one read of 12 words with fixed shifts is cheaper than a loop), for slot bit
    /// `bit`.
    #[inline(always)]
    pub(crate) fn planes_until(&self, block: usize, last: u32, bit: u32) -> Slot {
        if let Some(w) = self.planes.try_array::<PLANE_WORDS>(PLANE_WORDS * block) {
            let plane = |k: usize| {
                w[k] as u128
                    | (w[3 + k] as u128) << 32
                    | (w[6 + k] as u128) << 64
                    | (w[9 + k] as u128) << 96
            };
            let p = [plane(0), plane(1), plane(2)];
            return Slot { block, bit, p };
        }
        let mut p = [0u128; 3];
        for q in 0..=last as usize {
            let g = self.group(4 * block + q);
            for k in 0..3 {
                p[k] |= (g[k] as u128) << (32 * q);
            }
        }
        Slot { block, bit, p }
    }

    /// Every plane of block `block` (its last group: the block's slots, or the ring's).
    #[inline(always)]
    pub(crate) fn block_planes(&self, block: usize) -> Slot {
        let groups = plane_array_words(self.m_r) / 3 - 4 * block;
        self.planes_until(block, groups.min(4) as u32 - 1, 0)
    }

    /// The anchor of side `side`'s chain in block `block`: its value before the block's
    /// first slot.
    #[inline(always)]
    pub(crate) fn chain_head(&self, block: usize, side: usize) -> u32 {
        if self.compact {
            let offset = self.anchors.at(2 * block + side);
            ((block << BLOCK_SHIFT) as u32).wrapping_add(offset)
        } else if self.short_heads {
            let offset = (self.heads.at(SHORT_HEAD_WORDS * block) >> (16 * side)) as u16 as i16;
            ((block << BLOCK_SHIFT) as u32).wrapping_add_signed(offset as i32)
        } else {
            self.heads.at(HEAD_WORDS * block + side)
        }
    }

    /// The exception words (`k` 0) or the records (`k` 1) before block `block`.
    #[inline(always)]
    pub(crate) fn before_block(&self, block: usize, k: usize) -> usize {
        if self.compact {
            let offset = self.head_counts.at(2 * block + k);
            let base = match block >> COMPACT_SUPER_SHIFT {
                0 => 0,
                s => self.super_counts.at(2 * (s - 1) + k),
            };
            base as usize + offset as usize
        } else if self.short_heads {
            let offset = (self.heads.at(SHORT_HEAD_WORDS * block + 1) >> (16 * k)) & 0xFFFF;
            let superblock = block >> SUPER_SHIFT;
            let base = match superblock {
                0 => 0,
                s => self.super_counts.at(2 * (s - 1) + k),
            };
            base as usize + offset as usize
        } else {
            self.heads.at(HEAD_WORDS * block + 2 + k) as usize
        }
    }

    /// The word holding the WART flag and the tip of exception or irregular slot `bit`.
    #[inline(always)]
    pub(super) fn stored_word(&self, slot: &Slot, bit: u32) -> u32 {
        let below = (1u128 << bit) - 1;
        // Symbols 6 (exception) and 7 (irregular) differ in plane 0.
        if plane_bit(slot.p[0], bit) == 0 {
            let x = self.before_block(slot.block, 0)
                + (slot.exceptions() & below).count_ones() as usize;
            self.exceptions.at(x)
        } else {
            self.records.at(RECORD_WORDS * self.record_index(slot, bit))
        }
    }

    /// Index of the record of irregular slot `bit`.
    #[inline(always)]
    pub(super) fn record_index(&self, slot: &Slot, bit: u32) -> usize {
        let below = (1u128 << bit) - 1;
        self.before_block(slot.block, 1) + (slot.irregular() & below).count_ones() as usize
    }

    /// The tip of a delta slot: its side's chain value after it.
    #[inline(always)]
    pub(super) fn chain(&self, slot: &Slot) -> u32 {
        let side = (slot.bit & 1) as usize;
        let same = (LEFT_SLOTS << side) & up_to(slot.bit);
        let resets = slot.stored() & same;
        let (base, range) = if resets == 0 {
            (self.chain_head(slot.block, side), same)
        } else {
            let j = 127 - resets.leading_zeros();
            (self.stored_word(slot, j) & VALUE, same & !up_to(j))
        };
        let deltas = range & !slot.p[2];
        let mut sum = (slot.p[0] & deltas).count_ones() + 2 * (slot.p[1] & deltas).count_ones();
        if self.four_sides != 0 {
            sum += FOUR * (self.block_fours(slot) & range).count_ones();
        }
        base.wrapping_sub(sum)
    }

    /// Whether the slot of symbol 5 at `slot.bit` is a four (a delta slot).
    #[inline(always)]
    pub(crate) fn is_four(&self, slot: &Slot) -> bool {
        self.four_sides != 0 && plane_bit(self.block_fours(slot), slot.bit) != 0
    }

    /// The fours of `slot`'s block.
    #[inline(always)]
    pub(crate) fn block_fours(&self, slot: &Slot) -> u128 {
        slot.fours(self.four_sides, last_vertex_bits(self.m_r, slot.block))
    }

    /// With `WART_DELTAS`, whether the next slot of `(v, side)`'s side is a canonical T2
    /// (symbol 4): then a delta symbol there is a wart and symbol 5 the T2's redundant copy
    /// on either side (OPERATORS.md §8.1). `group` holds the slot's group's words, where
    /// the next slot lies unless `v` ends its ring or the slot ends the group.
    #[inline(always)]
    pub(crate) fn before_t2(&self, v: u32, side: usize, group: [u32; 3]) -> bool {
        self.wart_deltas && self.next_is_t2(v, side, group)
    }

    /// Whether the next slot of `(v, side)`'s side has symbol 4 (a canonical T2), `group`
    /// as for [`before_t2`](Self::before_t2).
    #[inline(always)]
    pub(crate) fn next_is_t2(&self, v: u32, side: usize, group: [u32; 3]) -> bool {
        let next = self.ring_next(v);
        let b = (2 * v as usize + side) % 32;
        let next_symbol = if next == v + 1 && b < 30 {
            group_symbol(group, b + 2)
        } else {
            self.symbol(next, side)
        };
        next_symbol == PREVIOUS
    }

    /// The WART flag of exception or irregular slot `(v, side)` whose word is `word`: the
    /// word's flag, or with `IMPLIED_WARTS` whether the next slot of its side has symbol 4
    /// and its tip is not `v.n.n` (FORMAT.md §3.5e.5).
    #[inline(always)]
    pub(crate) fn stored_slot_wart(&self, v: u32, side: usize, word: u32, group: [u32; 3]) -> bool {
        self.stored_wart_given(
            word,
            || self.next_is_t2(v, side, group),
            || self.ring_next_next(v),
        )
    }

    /// [`stored_slot_wart`](Self::stored_slot_wart) with the slot's ring steps asked of
    /// `next_is_t2` and `next_next` (only with `IMPLIED_WARTS`): a block decoded in one pass
    /// takes them from the block's ring ends.
    #[inline(always)]
    pub(crate) fn stored_wart_given(
        &self,
        word: u32,
        next_is_t2: impl FnOnce() -> bool,
        next_next: impl FnOnce() -> u32,
    ) -> bool {
        match self.implied_warts {
            false => word & WART != 0,
            true => implied_wart(next_is_t2(), word & VALUE, next_next()),
        }
    }

    /// With `ROW_RECORDS`, the opposite of transversal corner `second` of irregular slot
    /// `(v, side)`, the `r`-th, whose record names T0 row `row` (FORMAT.md §3.5e.5): the
    /// row's corner across the edge that corner faces, when that edge is the first of the
    /// slot's two whose ends are both in the row; `None` (the ring rules' answer) otherwise.
    #[inline(always)]
    pub(super) fn row_opposite(
        &self,
        slot: &Slot,
        (v, side): (u32, usize),
        r: usize,
        row: u32,
        second: usize,
    ) -> Option<u32> {
        let word = self.records.at(RECORD_WORDS * r);
        let tip = word & VALUE;
        let wart = self.stored_slot_wart(v, side, word, slot.group());
        let far = self.far_given(v, wart);
        let vertices = [0, 1, 2].map(|i| self.t0_vertex(3 * row + i));
        match row_corner(slot_edges(v, side, tip, far), vertices) {
            Some((k, i)) if k == second => Some((8 * self.m_r).wrapping_add(4 * row + i)),
            _ => None,
        }
    }

    /// The tip the ring rules give a slot of symbol 4 (`v.p`) or 5 that is not a four
    /// (`v.n.n` on the left, on a right side with fours or before a canonical T2, else
    /// `NULL`).
    #[inline(always)]
    pub(crate) fn ring_rule_tip(&self, slot: &Slot, v: u32, side: usize, symbol: u32) -> u32 {
        if symbol == PREVIOUS {
            self.ring_prev(v)
        } else if self.rule_5_is_null(v, side, slot.group()) {
            NULL
        } else {
            self.ring_next_next(v)
        }
    }

    /// Whether a slot of symbol 5 that is not a four has the tip `NULL` by the ring rules: a
    /// right slot, when the right side has no fours and the slot does not come before a
    /// canonical T2 (`v.n.n` otherwise). `group` as for [`before_t2`](Self::before_t2).
    #[inline(always)]
    pub(crate) fn rule_5_is_null(&self, v: u32, side: usize, group: [u32; 3]) -> bool {
        self.rule_5_is_null_given(side, || self.next_is_t2(v, side, group))
    }

    /// [`rule_5_is_null`](Self::rule_5_is_null) with whether the next slot of the side has
    /// symbol 4 asked of `next_is_t2` (only on a right side without fours, with
    /// `WART_DELTAS`).
    #[inline(always)]
    pub(crate) fn rule_5_is_null_given(
        &self,
        side: usize,
        next_is_t2: impl FnOnce() -> bool,
    ) -> bool {
        side == RIGHT
            && self.four_sides & LEFT_SLOTS << RIGHT == 0
            && !(self.wart_deltas && next_is_t2())
    }
}
