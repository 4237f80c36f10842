//! The decoding side of the Zipper: the tables [`ZipperTables`] as they lie on disk and the
//! [`LrLayout`] implementation through which the corner operators read them.

use super::packed::Packed;
use super::{
    BLOCK_SHIFT, BY_LEFT_RULE, BY_RIGHT_RULE, COMPACT_SUPER_SHIFT, DELTAS, EXCEPTION, EXPLICIT,
    EXPLICIT_SHIFT, FOUR, HEAD_WORDS, IRREGULAR_SLOT, NEXT_NEXT_OR_NULL, NO_OPPOSITE, PLANE_WORDS,
    PREVIOUS, RECORD_WORDS, SHORT_HEAD_WORDS, STATE_SHIFT, STORES_BOTH, STORES_FIRST,
    STORES_SECOND, SUPER_SHIFT,
};
use crate::corner_table::NONE;
use crate::lr::tables::{is_last_by_bits, ring_of_by_bits, LrLayout, LEFT, NULL, VALUE, WART};
use crate::words::Words;

/// The bits of the left slots of a block (slot `2i + side`).
pub(crate) const LEFT_SLOTS: u128 = 0x5555_5555_5555_5555_5555_5555_5555_5555;

/// The Zipper tables over words `W` (vectors after construction, little-endian bytes in a
/// container).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ZipperTables<W> {
    /// The first vertex of rings 1 to `rings − 1` (ring 0 starts at 0, the last ends at
    /// `m_r`).
    pub(crate) ring_starts: W,
    /// `R`: rings.
    pub(crate) rings: u32,
    /// Empty with one ring (never read then), and with `RING_BLOCKS`.
    pub(crate) ring_last: W,
    pub(crate) ring_rank: W,
    /// With several rings and the header's `RING_BLOCKS` flag, the ring of each block's first
    /// vertex; empty otherwise.
    pub(crate) ring_blocks: Packed<W>,
    /// Per block: the three symbol planes.
    pub(crate) planes: W,
    /// Per block: the two anchors, the exceptions and the records before it (four words; two
    /// with `short_heads`); empty in the compact form, whose heads are the two lists below.
    pub(crate) heads: W,
    /// In the compact form (version 1.13): each block's left and right anchor as signed
    /// offsets from its first vertex, in the header's anchor width.
    pub(crate) anchors: Packed<W>,
    /// In the compact form: each block's exceptions and records before it, as offsets from
    /// those before its superblock of 16 blocks.
    pub(crate) head_counts: Packed<W>,
    /// Exception words: WART flag and tip.
    pub(crate) exceptions: Packed<W>,
    /// Records of irregular slots: WART flag and tip, then the stored opposite.
    pub(crate) records: Packed<W>,
    /// Opposite pairs of records that store both, two words each.
    pub(crate) pairs: Packed<W>,
    /// T0 rows' vertices, three each.
    pub(crate) t0_v: Packed<W>,
    /// T0 rows' code words: three 2-bit opposite codes and the index of the first explicit
    /// opposite.
    pub(crate) t0_codes: Packed<W>,
    /// Explicit T0 opposites, row by row.
    pub(crate) t0_explicit: Packed<W>,
    /// A corner of each isolated vertex (`NONE` for a vertex without triangles).
    pub(crate) c: Packed<W>,
    /// With `short_heads` (superblocks of 256 blocks) or in the compact form (of 16), per
    /// superblock from the second: the exceptions and the records before it.
    pub(crate) super_counts: W,
    pub(crate) m_r: u32,
    pub(crate) m: u32,
    /// As [`LrTables`](crate::lr::LrTables)' field: derived, never stored.
    pub(crate) boundaries_on_ring: bool,
    /// The header's `WART_DELTAS` flag: a delta slot followed on its side by a canonical T2
    /// is a wart.
    pub(crate) wart_deltas: bool,
    /// The header's `SHORT_HEADS` flag: two-word heads and superblock counts.
    pub(crate) short_heads: bool,
    /// The compact form of the section (version 1.13): a short header and bit-field heads.
    pub(crate) compact: bool,
    /// The header's `PACKED_LISTS` flag: the lists above as bit fields (read as words).
    pub(crate) packed_lists: bool,
    /// The header's `INNER_RING_STARTS` flag.
    pub(crate) inner_ring_starts: bool,
    /// The header's `RING_BLOCKS` flag.
    pub(crate) ring_blocks_flag: bool,
    /// The slots of the sides whose symbol 5 may be a four (a delta of 4): the left ones
    /// with the header's `LEFT_FOURS` flag, the right ones with `RIGHT_FOURS`.
    pub(crate) four_sides: u128,
    /// The header's `ROW_RECORDS` flag: a record of state 1 names a T0 row.
    pub(crate) row_records: bool,
    /// The header's `IMPLIED_WARTS` flag: stored words hold no WART flag.
    pub(crate) implied_warts: bool,
    /// The header's `JOINED_LISTS` flag: in the file, the nine bit lists are one stream
    /// (each list here is read where it lies in it).
    pub(crate) joined_lists: bool,
}

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
fn plane_bit(p: u128, bit: u32) -> u32 {
    let half = if bit < 64 { p as u64 } else { (p >> 64) as u64 };
    (half >> (bit % 64) & 1) as u32
}

/// The symbol of bit `b` of a group's three words.
#[inline]
fn group_symbol(g: [u32; 3], b: usize) -> u32 {
    (g[0] >> b) & 1 | ((g[1] >> b) & 1) << 1 | ((g[2] >> b) & 1) << 2
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

/// The bits below bit `k` (all for `k` = 128).
#[inline]
pub(crate) fn below(k: usize) -> u128 {
    u128::MAX.checked_shr(128 - k as u32).unwrap_or(0)
}

/// Bits `0..=i`.
#[inline]
fn up_to(i: u32) -> u128 {
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
    fn group(&self, g: usize) -> [u32; 3] {
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
        if PLANE_WORDS * (block + 1) <= self.planes.count() {
            let w: [u32; PLANE_WORDS] = self.planes.array(PLANE_WORDS * block);
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
    fn stored_word(&self, slot: &Slot, bit: u32) -> u32 {
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
    fn record_index(&self, slot: &Slot, bit: u32) -> usize {
        let below = (1u128 << bit) - 1;
        self.before_block(slot.block, 1) + (slot.irregular() & below).count_ones() as usize
    }

    /// The tip of a delta slot: its side's chain value after it.
    #[inline(always)]
    fn chain(&self, slot: &Slot) -> u32 {
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
        match self.implied_warts {
            false => word & WART != 0,
            true => {
                self.next_is_t2(v, side, group) && word & VALUE != self.ring_next(self.ring_next(v))
            }
        }
    }

    /// With `ROW_RECORDS`, the opposite of transversal corner `second` of irregular slot
    /// `(v, side)`, the `r`-th, whose record names T0 row `row` (FORMAT.md §3.5e.5): the
    /// row's corner across the edge that corner faces, when that edge is the first of the
    /// slot's two whose ends are both in the row; `None` (the ring rules' answer) otherwise.
    #[inline(always)]
    fn row_opposite(
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
        } else if side == LEFT
            || self.four_sides != 0 && plane_bit(self.four_sides, slot.bit) != 0
            || self.before_t2(v, side, slot.group())
        {
            self.ring_next(self.ring_next(v))
        } else {
            NULL
        }
    }

    /// Whether the header's `SHORT_HEADS` flag is set (version 1.9).
    pub fn short_heads(&self) -> bool {
        self.short_heads
    }

    /// Whether the section is in the compact form (version 1.13): a short header and heads
    /// as bit fields.
    pub fn compact(&self) -> bool {
        self.compact
    }

    /// In the compact form, the widths of a head's fields in bits: anchor, exceptions,
    /// records.
    pub fn head_widths(&self) -> Option<[u8; 3]> {
        let [x, i] = self.head_counts.fields().map(|f| f.width);
        self.compact.then_some([self.anchors.field_width(), x, i])
    }

    /// Whether the header's `PACKED_LISTS` flag is set (version 1.10).
    pub fn packed_lists(&self) -> bool {
        self.packed_lists
    }

    /// Whether the header's `INNER_RING_STARTS` flag is set (version 1.12): the file stores
    /// the starts of rings 1 to `R − 1` only (the tables hold those either way).
    pub fn inner_ring_starts(&self) -> bool {
        self.inner_ring_starts
    }

    /// Whether the header's `RING_BLOCKS` flag is set (version 1.12): with several rings, the
    /// ring of each block's first vertex stands for the ring-end bits and ranks.
    pub fn ring_blocks(&self) -> bool {
        self.ring_blocks_flag
    }

    /// Whether the header's `WART_DELTAS` flag is set (version 1.8).
    pub fn wart_deltas(&self) -> bool {
        self.wart_deltas
    }

    /// Whether the header's `JOINED_LISTS` flag is set (version 1.16).
    pub fn joined_lists(&self) -> bool {
        self.joined_lists
    }

    /// Whether the header's `ROW_RECORDS` and `IMPLIED_WARTS` flags are set (version 1.15).
    pub fn row_records_and_implied_warts(&self) -> [bool; 2] {
        [self.row_records, self.implied_warts]
    }

    /// Whether the header's `LEFT_FOURS` and `RIGHT_FOURS` flags are set (version 1.14).
    pub fn fours(&self) -> [bool; 2] {
        [LEFT_SLOTS, LEFT_SLOTS << 1].map(|side| self.four_sides & side != 0)
    }

    /// Number of exception slots.
    pub fn exception_count(&self) -> usize {
        self.exceptions.count()
    }

    /// Number of irregular slots.
    pub fn record_count(&self) -> usize {
        self.records.count() / RECORD_WORDS
    }

    /// Number of opposite pairs (records that store both opposites).
    pub fn pair_count(&self) -> usize {
        self.pairs.count() / 2
    }

    /// Number of explicit T0 opposites.
    pub fn explicit_count(&self) -> usize {
        self.t0_explicit.count()
    }

    /// The nine bit lists of the compact form, in file order: the anchors, the head counts,
    /// then `EXCEPTIONS` to `C`.
    pub(crate) fn bit_lists(&self) -> [&Packed<W>; 9] {
        [
            &self.anchors,
            &self.head_counts,
            &self.exceptions,
            &self.records,
            &self.pairs,
            &self.t0_v,
            &self.t0_codes,
            &self.t0_explicit,
            &self.c,
        ]
    }

    /// Words of the parts: symbols and heads, exceptions, records, T0 rows.
    pub(crate) fn part_words(&self) -> [usize; 4] {
        [
            self.planes.count()
                + self.heads.count()
                + self.anchors.words.count()
                + self.head_counts.words.count()
                + self.super_counts.count(),
            self.exceptions.words.count(),
            self.records.words.count() + self.pairs.words.count(),
            self.t0_v.words.count() + self.t0_codes.words.count() + self.t0_explicit.words.count(),
        ]
    }

    /// The eight counts of the header: `m`, `m_r`, `R`, `n0`, `X`, `I`, `P`, `E`.
    pub fn header_counts(&self) -> [u32; 8] {
        [
            self.m,
            self.m_r,
            self.rings,
            self.t0_count(),
            self.exception_count() as u32,
            self.record_count() as u32,
            self.pair_count() as u32,
            self.explicit_count() as u32,
        ]
    }

    /// Bytes of the section as a container stores the tables, header included.
    pub fn stored_bytes(&self) -> u64 {
        let header = match self.compact {
            true => super::compact_header_len(super::count_bytes(&self.header_counts())),
            false => 40,
        };
        let mut words = self.ring_starts.count()
            + self.ring_last.count()
            + self.ring_rank.count()
            + self.ring_blocks.words.count()
            + self.part_words().iter().sum::<usize>()
            + self.c.words.count();
        if self.joined_lists {
            // The nine lists' words give way to one stream of their bits.
            let lists = self.bit_lists();
            words -= lists.iter().map(|l| l.words.count()).sum::<usize>();
            words += lists.iter().map(|l| l.bits()).sum::<u64>().div_ceil(32) as usize;
        }
        header as u64 + 4 * words as u64
    }
}

impl<W: Words> LrLayout for ZipperTables<W> {
    #[inline]
    fn ring_vertices(&self) -> u32 {
        self.m_r
    }
    #[inline]
    fn vertex_count(&self) -> u32 {
        self.m
    }
    #[inline]
    fn t0_count(&self) -> u32 {
        self.t0_codes.count() as u32
    }
    #[inline]
    fn ring_count(&self) -> usize {
        self.rings as usize
    }
    #[inline]
    fn ring_start(&self, ring: usize) -> u32 {
        match ring {
            0 => 0,
            r if r >= self.rings as usize => self.m_r,
            r => self.ring_starts.at(r - 1),
        }
    }
    /// With `RING_BLOCKS`: `v + 1` starts the next ring (OPERATORS.md §8).
    #[inline(always)]
    fn is_last(&self, v: u32) -> bool {
        if self.ring_blocks.count() == 0 {
            return is_last_by_bits(self, v);
        }
        v + 1 == self.ring_start(self.ring_of(v) + 1)
    }
    /// With `RING_BLOCKS`: the last ring starting at or before `v` among those from the ring
    /// of `v`'s block's first vertex to that of the next block's (at most 17: a ring has 4
    /// vertices or more), by bisection.
    #[inline(always)]
    fn ring_of(&self, v: u32) -> usize {
        if self.ring_blocks.count() == 0 {
            return ring_of_by_bits(self, v);
        }
        let block = (v >> BLOCK_SHIFT) as usize;
        let mut low = self.ring_blocks.at(block) as usize;
        let mut high = match block + 1 < self.ring_blocks.count() {
            true => self.ring_blocks.at(block + 1) as usize,
            false => self.rings as usize - 1,
        };
        // ring_start(r) = ring_starts[r − 1] for 0 < r < R.
        while low < high {
            let mid = (low + high).div_ceil(2);
            if self.ring_starts.at(mid - 1) <= v {
                low = mid;
            } else {
                high = mid - 1;
            }
        }
        low
    }
    #[inline]
    fn ring_last_word(&self, i: usize) -> u32 {
        self.ring_last.at(i)
    }
    #[inline]
    fn ring_rank_word(&self, i: usize) -> u32 {
        self.ring_rank.at(i)
    }
    #[inline]
    fn tip(&self, v: u32, side: usize) -> u32 {
        // The block's planes read once: the symbol, then the chain or the stored word.
        let slot = self.slot(v, side);
        match slot.symbol_at(slot.bit) {
            s if s < DELTAS => self.chain(&slot),
            NEXT_NEXT_OR_NULL if self.is_four(&slot) => self.chain(&slot),
            s @ (PREVIOUS | NEXT_NEXT_OR_NULL) => self.ring_rule_tip(&slot, v, side, s),
            _ => self.stored_word(&slot, slot.bit) & VALUE,
        }
    }
    #[inline]
    fn tip_and_wart(&self, v: u32, side: usize) -> (u32, bool) {
        let slot = self.slot(v, side);
        match slot.symbol_at(slot.bit) {
            s if s < DELTAS => (self.chain(&slot), self.before_t2(v, side, slot.group())),
            NEXT_NEXT_OR_NULL if self.is_four(&slot) => {
                (self.chain(&slot), self.before_t2(v, side, slot.group()))
            }
            s @ (PREVIOUS | NEXT_NEXT_OR_NULL) => (self.ring_rule_tip(&slot, v, side, s), false),
            _ => {
                let word = self.stored_word(&slot, slot.bit);
                (
                    word & VALUE,
                    self.stored_slot_wart(v, side, word, slot.group()),
                )
            }
        }
    }
    #[inline]
    fn wart(&self, v: u32, side: usize) -> bool {
        let slot = 2 * v as usize + side;
        let group = self.group(slot / 32);
        let symbol = group_symbol(group, slot % 32);
        if symbol < DELTAS {
            return self.before_t2(v, side, group);
        }
        if symbol == NEXT_NEXT_OR_NULL && self.four_sides != 0 {
            return self.is_four(&self.slot(v, side)) && self.before_t2(v, side, group);
        }
        if symbol < EXCEPTION {
            return false;
        }
        let slot = self.slot(v, side);
        let word = self.stored_word(&slot, slot.bit);
        self.stored_slot_wart(v, side, word, group)
    }
    #[inline]
    fn irregular(&self, v: u32, side: usize) -> bool {
        self.symbol(v, side) == IRREGULAR_SLOT
    }
    #[inline]
    fn stored_opposite(&self, v: u32, side: usize, second: usize) -> Option<u32> {
        if self.symbol(v, side) != IRREGULAR_SLOT {
            return None;
        }
        let slot = self.slot(v, side);
        let r = self.record_index(&slot, slot.bit);
        let word = self.records.at(RECORD_WORDS * r + 1);
        let value = word & ((1 << STATE_SHIFT) - 1);
        match (word >> STATE_SHIFT, second) {
            (STORES_BOTH, _) => Some(self.pairs.at(2 * value as usize + second)),
            (STORES_FIRST, _) if self.row_records => {
                self.row_opposite(&slot, (v, side), r, value, second)
            }
            (STORES_FIRST, 0) | (STORES_SECOND, 1) => Some((8 * self.m_r).wrapping_add(value)),
            _ => None,
        }
    }
    #[inline]
    fn t0_vertex(&self, k: u32) -> u32 {
        self.t0_v.at(k as usize)
    }
    #[inline]
    fn t0_opposite(&self, k: u32) -> u32 {
        let (j, i) = (k / 3, k % 3);
        let word = self.t0_codes.at(j as usize);
        let code = word >> (2 * i) & 3;
        let row_vertex = |i: u32| self.t0_vertex(3 * j + i % 3);
        match code {
            BY_LEFT_RULE => self.find_left(row_vertex(i + 1), row_vertex(i + 2)),
            BY_RIGHT_RULE => self.find_right(row_vertex(i + 1), row_vertex(i + 2)),
            NO_OPPOSITE => NONE,
            _ => {
                // Explicit: after the row's explicit opposites of the corners before it.
                let before = (0..i).filter(|&e| word >> (2 * e) & 3 == EXPLICIT).count();
                self.t0_explicit
                    .at((word >> EXPLICIT_SHIFT) as usize + before)
            }
        }
    }
    #[inline]
    fn boundaries_on_ring(&self) -> bool {
        self.boundaries_on_ring
    }
    #[inline]
    fn isolated_corner(&self, i: u32) -> u32 {
        self.c.at(i as usize)
    }
}
