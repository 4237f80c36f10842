//! The decoding side of the Zipper: the tables [`ZipperTables`] as they lie on disk and the
//! [`LrLayout`] implementation through which the corner operators read them (a slot is read
//! in `slots`).

use super::packed::Packed;
use super::slots::{group_symbol, LEFT_SLOTS};
use super::{
    BLOCK_SHIFT, BY_LEFT_RULE, BY_RIGHT_RULE, DELTAS, EXCEPTION, EXPLICIT, EXPLICIT_SHIFT,
    IRREGULAR_SLOT, NEXT_NEXT_OR_NULL, NO_OPPOSITE, PREVIOUS, RECORD_WORDS, STATE_SHIFT,
    STORES_BOTH, STORES_FIRST, STORES_SECOND,
};
use crate::corner_table::NONE;
use crate::lr::tables::{is_last_by_bits, ring_of_by_bits, LrLayout, RIGHT, VALUE};
use crate::words::Words;

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

impl<W: Words> ZipperTables<W> {
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
        let lists = self.bit_lists();
        let list_words = match self.joined_lists {
            // One stream of the nine lists' bits, padded to a word at its end.
            true => lists.iter().map(|l| l.bits()).sum::<u64>().div_ceil(32) as usize,
            false => lists.iter().map(|l| l.words.count()).sum(),
        };
        let words = self.ring_starts.count()
            + self.ring_last.count()
            + self.ring_rank.count()
            + self.ring_blocks.words.count()
            + self.planes.count()
            + self.heads.count()
            + self.super_counts.count()
            + list_words;
        header as u64 + 4 * words as u64
    }
}

impl<W: Words> ZipperTables<W> {
    /// The opposite of T0 corner row `k`, its ring-rule cases (`find_left`, `find_right`)
    /// answered through `layout`: these tables, or a [`ZipperCursor`](super::ZipperCursor)
    /// over them.
    #[inline]
    pub(crate) fn t0_opposite_in<L: LrLayout>(&self, layout: &L, k: u32) -> u32 {
        let (j, i) = (k / 3, k % 3);
        let word = self.t0_codes.at(j as usize);
        let code = word >> (2 * i) & 3;
        let row_vertex = |i: u32| self.t0_vertex(3 * j + i % 3);
        match code {
            BY_LEFT_RULE => layout.find_left(row_vertex(i + 1), row_vertex(i + 2)),
            BY_RIGHT_RULE => layout.find_right(row_vertex(i + 1), row_vertex(i + 2)),
            NO_OPPOSITE => NONE,
            _ => {
                // Explicit: after the row's explicit opposites of the corners before it.
                let before = (0..i).filter(|&e| word >> (2 * e) & 3 == EXPLICIT).count();
                self.t0_explicit
                    .at((word >> EXPLICIT_SHIFT) as usize + before)
            }
        }
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
    /// From the symbol alone: only a slot of symbol 5 can have a `NULL` tip (every other
    /// tip is below `m`, FORMAT.md \[V58\]), and with right fours no right slot does.
    #[inline]
    fn right_is_null(&self, v: u32) -> bool {
        let slot = 2 * v as usize + RIGHT;
        let group = self.group(slot / 32);
        group_symbol(group, slot % 32) == NEXT_NEXT_OR_NULL && self.rule_5_is_null(v, RIGHT, group)
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
        self.t0_opposite_in(self, k)
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
