//! The decoding side of the bit-efficient LR: the tables [`CompactTables`] as they lie on
//! disk, the helpers that unpack pair words, records, corner fields and T0 rows, and the
//! [`LrLayout`] implementation through which the corner operators read them. Kept apart from
//! the encoder so that what a container's reader runs is in one place.

use super::plain::{self, short15};
use super::{
    BLOCK_SHIFT, BY_LEFT_RULE, BY_RIGHT_RULE, ESCAPE, EXTENDED, FIELD13, GROUP_SHIFT,
    HEAD_TIP_SHIFT, IN_ADJACENT_ROW, OVERFLOW_FLAG, OVERFLOW_ROW_WORDS, RECORD_SHIFT, RIGHT_LONG,
    T0_ROW_UNITS, TAG_T0, WART_LEFT, X_IRREGULAR, X_WART,
};
use crate::corner_table::NONE;
use crate::lr::tables::{LrLayout, LEFT, NULL, RIGHT};
use crate::words::{Units, Words};

/// Sign-extends the low 13 bits.
#[inline(always)]
fn short13(bits: u32) -> i32 {
    ((bits as i32) << 19) >> 19
}

/// Sign-extends the low 12 bits.
#[inline(always)]
fn short12(bits: u16) -> i32 {
    ((bits as i32) << 20) >> 20
}

/// Units of the corner field starting with `unit`.
#[inline(always)]
fn corner_width(unit: u16) -> usize {
    if unit == ESCAPE {
        3
    } else {
        1
    }
}

/// An extended pair as [`CompactTables::decode_extended`] reads it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ExtendedPair {
    /// Its record's first unit.
    pub start: usize,
    /// Its record's units.
    pub len: usize,
    /// The tips of its left and right slots (`NULL` for a missing right triangle).
    pub tips: [u32; 2],
    /// The WART flags of its slots.
    pub wart: [bool; 2],
    /// The IRREGULAR flags of its slots.
    pub irregular: [bool; 2],
    /// Whether each side is IRREGULAR exactly when the head says it stores an opposite.
    pub flags_agree: bool,
    /// The stored opposites, at the positions of [`LrLayout::stored_opposite`]
    /// (`2 side + second`).
    pub opposites: [Option<u32>; 4],
}

/// The bit-efficient LR tables over words `W` and units `U` (vectors after construction,
/// little-endian bytes in a container): the arrays of `spec/FORMAT.md` §3.5d.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompactTables<W, U> {
    pub(crate) ring_starts: W,
    /// Empty with one ring (never read then).
    pub(crate) ring_last: W,
    pub(crate) ring_rank: W,
    /// One word per ring vertex.
    pub(crate) pairs: W,
    /// Per block: its first record unit, and the T0 rows anchored before it.
    pub(crate) blocks: W,
    /// Per group of T0 rows: the anchor its offsets start from.
    pub(crate) groups: W,
    /// With `tip_bases`, per block: the base of its left tips, then of its right tips
    /// (two's complement); empty without.
    pub(crate) bases: W,
    /// A corner of each isolated vertex (`NONE` for a vertex without triangles).
    pub(crate) c: W,
    /// Overflow rows of T0 rows that do not fit in units.
    pub(crate) overflow: W,
    /// T0 rows.
    pub(crate) t0: U,
    /// Records of extended pairs, in ring order.
    pub(crate) records: U,
    pub(crate) m_r: u32,
    pub(crate) m: u32,
    /// As [`LrTables`](crate::lr::LrTables)' field: derived, never stored.
    pub(crate) boundaries_on_ring: bool,
    /// The header's `TIP_BASES` flag: plain tips are 14-bit offsets from `v` or from `v`
    /// plus the block's base (see `plain`).
    pub(crate) tip_bases: bool,
}

/// Where the parts of an extended pair's record are.
struct Record {
    /// The head unit.
    head: u16,
    /// First unit after the head and the long tips: the stored opposites.
    opposites: usize,
    /// The left tip's long value's first unit, if long.
    left_long: Option<usize>,
    /// The right tip's long value's first unit, if long.
    right_long: Option<usize>,
}

impl<W: Words, U: Units> CompactTables<W, U> {
    #[inline(always)]
    fn pair(&self, v: u32) -> u32 {
        self.pairs.at(v as usize)
    }

    /// The base of side `side`'s plain tips in `v`'s block, `None` without tip bases.
    #[inline(always)]
    pub(crate) fn base(&self, v: u32, side: usize) -> Option<i32> {
        self.tip_bases
            .then(|| self.bases.at(2 * (v >> BLOCK_SHIFT) as usize + side) as i32)
    }

    /// Whether the tables have tip bases (the header's `TIP_BASES` flag).
    pub fn has_tip_bases(&self) -> bool {
        self.tip_bases
    }

    #[inline(always)]
    fn long_at(&self, at: usize) -> u32 {
        self.records.at(at) as u32 | (self.records.at(at + 1) as u32) << 16
    }

    /// The record of extended pair `v` with pair word `p`.
    #[inline(always)]
    fn record(&self, v: u32, p: u32) -> Record {
        let start = self.record_start(v, p);
        let head = self.records.at(start);
        let mut at = start + 1;
        let left_long = (p & FIELD13 == 0).then(|| {
            at += 2;
            at - 2
        });
        let right_long = (head >> HEAD_TIP_SHIFT == RIGHT_LONG).then(|| {
            at += 2;
            at - 2
        });
        Record {
            head,
            opposites: at,
            left_long,
            right_long,
        }
    }

    /// Decodes a corner field from its first unit; `long` reads a long field's value.
    #[inline(always)]
    fn corner_field(
        &self,
        unit: u16,
        ring_reference: u32,
        t0_reference: u32,
        long: impl FnOnce() -> u32,
    ) -> u32 {
        if unit & 0x7FFF == ESCAPE {
            return if unit & TAG_T0 != 0 { NONE } else { long() };
        }
        let d = short15(unit as u32);
        if unit & TAG_T0 != 0 {
            (8 * self.m_r)
                .wrapping_add(4u32.wrapping_mul(t0_reference))
                .wrapping_add_signed(d)
        } else {
            8u32.wrapping_mul(ring_reference).wrapping_add_signed(d)
        }
    }

    /// Extended pair `v` (pair word `p`) decoded in one walk over its record, reading only
    /// units it has checked exist: `None` when the record runs past the record units. For a
    /// reader's checks, which would otherwise decode the record once per question.
    #[inline(always)]
    pub(crate) fn decode_extended(&self, v: u32, p: u32) -> Option<ExtendedPair> {
        let n = self.records.count();
        let start = self.record_start(v, p);
        let head = *(start < n).then(|| self.records.at(start)).as_ref()?;
        let mut at = start + 1;
        let long = |at: &mut usize| {
            *at += 2;
            (*at <= n).then(|| self.long_at(*at - 2))
        };
        let left = match p & FIELD13 {
            0 => long(&mut at)?,
            _ => v.wrapping_add_signed(short13(p)),
        };
        let right = match head >> HEAD_TIP_SHIFT {
            RIGHT_LONG => long(&mut at)?,
            bits => match short12(bits) {
                0 => NULL,
                d => v.wrapping_add_signed(d),
            },
        };
        let t0_reference = self.blocks.at(2 * (v >> BLOCK_SHIFT) as usize + 1);
        let mut opposites = [None; 4];
        for (q, x) in opposites.iter_mut().enumerate() {
            if head >> q & 1 != 0 {
                let unit = *(at < n).then(|| self.records.at(at)).as_ref()?;
                let width = corner_width(unit);
                if at + width > n {
                    return None;
                }
                *x = Some(self.corner_field(unit, v, t0_reference, || self.long_at(at + 1)));
                at += width;
            }
        }
        let irregular = [LEFT, RIGHT].map(|side| p & X_IRREGULAR[side] != 0);
        Some(ExtendedPair {
            start,
            len: at - start,
            tips: [left, right],
            wart: [LEFT, RIGHT].map(|side| p & X_WART[side] != 0),
            irregular,
            flags_agree: [LEFT, RIGHT]
                .iter()
                .all(|&side| (head >> (2 * side) & 3 != 0) == irregular[side]),
            opposites,
        })
    }

    /// The first unit of the record of extended pair `v` with pair word `p`.
    #[inline(always)]
    pub(crate) fn record_start(&self, v: u32, p: u32) -> usize {
        let block = (v >> BLOCK_SHIFT) as usize;
        self.blocks.at(2 * block) as usize + ((p >> RECORD_SHIFT) & FIELD13) as usize
    }

    /// Number of T0 overflow rows.
    pub fn overflow_rows(&self) -> u32 {
        (self.overflow.count() / OVERFLOW_ROW_WORDS) as u32
    }

    /// Number of record units.
    pub fn record_units(&self) -> u32 {
        self.records.count() as u32
    }

    /// Whether the pair of ring vertex `v` has a record.
    pub fn is_extended(&self, v: u32) -> bool {
        self.pair(v) >> 30 == EXTENDED
    }

    /// The first unit of T0 row `j`, and whether it overflows.
    #[inline(always)]
    fn row(&self, j: usize) -> (usize, bool) {
        let at = T0_ROW_UNITS * j;
        (at, self.t0.at(at + 3) & OVERFLOW_FLAG != 0)
    }

    #[inline(always)]
    fn overflow_word(&self, at: usize, f: usize) -> u32 {
        let row = self.t0.at(at + 1) as usize | (self.t0.at(at + 2) as usize) << 16;
        self.overflow.at(OVERFLOW_ROW_WORDS * row + f)
    }

    /// The corner of T0 row `j - 1` or `j + 1` (in this order) facing half-edge `y -> x`,
    /// or `NONE`.
    #[inline(always)]
    pub(super) fn find_in_adjacent_row(&self, j: usize, x: u32, y: u32) -> u32 {
        let rows = self.t0_count() as usize;
        for other in [j.wrapping_sub(1), j + 1] {
            if other >= rows {
                continue;
            }
            let vs = [0, 1, 2].map(|i| self.t0_vertex((3 * other + i) as u32));
            for i in 0..3 {
                if vs[(i + 1) % 3] == y && vs[(i + 2) % 3] == x {
                    return 8 * self.m_r + 4 * other as u32 + i as u32;
                }
            }
        }
        NONE
    }

    #[inline(always)]
    fn anchor(&self, j: usize, at: usize) -> u32 {
        self.groups
            .at(j >> GROUP_SHIFT)
            .wrapping_add(self.t0.at(at) as u32)
    }
}

impl<W: Words, U: Units> LrLayout for CompactTables<W, U> {
    #[inline(always)]
    fn ring_vertices(&self) -> u32 {
        self.m_r
    }
    #[inline(always)]
    fn vertex_count(&self) -> u32 {
        self.m
    }
    #[inline(always)]
    fn t0_count(&self) -> u32 {
        (self.t0.count() / T0_ROW_UNITS) as u32
    }
    #[inline(always)]
    fn ring_count(&self) -> usize {
        self.ring_starts.count().saturating_sub(1)
    }
    #[inline(always)]
    fn ring_start(&self, ring: usize) -> u32 {
        self.ring_starts.at(ring)
    }
    #[inline(always)]
    fn ring_last_word(&self, i: usize) -> u32 {
        self.ring_last.at(i)
    }
    #[inline(always)]
    fn ring_rank_word(&self, i: usize) -> u32 {
        self.ring_rank.at(i)
    }

    #[inline(always)]
    fn tip(&self, v: u32, side: usize) -> u32 {
        let p = self.pair(v);
        if p >> 30 != EXTENDED {
            let base = || self.base(v, side).unwrap_or(0);
            return plain::tip(v, p >> (15 * side), self.tip_bases, base);
        }
        if side == LEFT {
            match short13(p) {
                0 => self.long_at(self.record(v, p).left_long.unwrap_or(0)),
                d => v.wrapping_add_signed(d),
            }
        } else {
            let r = self.record(v, p);
            match r.right_long {
                Some(at) => self.long_at(at),
                None => match short12(r.head >> HEAD_TIP_SHIFT) {
                    0 => NULL,
                    d => v.wrapping_add_signed(d),
                },
            }
        }
    }

    #[inline(always)]
    fn wart(&self, v: u32, side: usize) -> bool {
        let p = self.pair(v);
        match p >> 30 {
            EXTENDED => p & X_WART[side] != 0,
            config => config == WART_LEFT + side as u32,
        }
    }

    #[inline(always)]
    fn irregular(&self, v: u32, side: usize) -> bool {
        let p = self.pair(v);
        p >> 30 == EXTENDED && p & X_IRREGULAR[side] != 0
    }

    #[inline(always)]
    fn tip_and_wart(&self, v: u32, side: usize) -> (u32, bool) {
        let (tip, wart, _) = self.slot_fields(v, side);
        (tip, wart)
    }

    #[inline(always)]
    fn slot_fields(&self, v: u32, side: usize) -> (u32, bool, bool) {
        // A plain pair (most of them) answers every field from one test of its
        // configuration.
        let p = self.pair(v);
        if p >> 30 != EXTENDED {
            let base = || self.base(v, side).unwrap_or(0);
            let tip = plain::tip(v, p >> (15 * side), self.tip_bases, base);
            return (tip, p >> 30 == WART_LEFT + side as u32, false);
        }
        (
            self.tip(v, side),
            p & X_WART[side] != 0,
            p & X_IRREGULAR[side] != 0,
        )
    }

    #[inline(always)]
    fn stored_opposite(&self, v: u32, side: usize, second: usize) -> Option<u32> {
        let p = self.pair(v);
        if p >> 30 != EXTENDED || p & X_IRREGULAR[side] == 0 {
            return None;
        }
        let r = self.record(v, p);
        let flags = r.head & 0xF;
        let q = 2 * side + second;
        if flags >> q & 1 == 0 {
            return None;
        }
        let mut at = r.opposites;
        for earlier in 0..q {
            if flags >> earlier & 1 != 0 {
                at += corner_width(self.records.at(at));
            }
        }
        let unit = self.records.at(at);
        let t0_reference = self.blocks.at(2 * (v >> BLOCK_SHIFT) as usize + 1);
        Some(self.corner_field(unit, v, t0_reference, || self.long_at(at + 1)))
    }

    #[inline(always)]
    fn t0_vertex(&self, k: u32) -> u32 {
        let (j, i) = ((k / 3) as usize, (k % 3) as usize);
        let (at, overflow) = self.row(j);
        if overflow {
            return self.overflow_word(at, i);
        }
        let anchor = self.anchor(j, at);
        if i == 0 {
            anchor
        } else {
            anchor.wrapping_add_signed(short15(self.t0.at(at + i) as u32))
        }
    }

    #[inline(always)]
    fn t0_opposite(&self, k: u32) -> u32 {
        let (j, i) = ((k / 3) as usize, (k % 3) as usize);
        let (at, overflow) = self.row(j);
        if overflow {
            return self.overflow_word(at, 3 + i);
        }
        let code = self.t0.at(at + 3) >> (2 * i) & 3;
        let row_vertex = |i: usize| self.t0_vertex(3 * j as u32 + (i % 3) as u32);
        let (x, y) = (row_vertex(i + 1), row_vertex(i + 2));
        match code {
            BY_LEFT_RULE => self.find_left(x, y),
            BY_RIGHT_RULE => self.find_right(x, y),
            IN_ADJACENT_ROW => self.find_in_adjacent_row(j, x, y),
            _ => NONE,
        }
    }

    #[inline(always)]
    fn boundaries_on_ring(&self) -> bool {
        self.boundaries_on_ring
    }

    #[inline(always)]
    fn isolated_corner(&self, i: u32) -> u32 {
        self.c.at(i as usize)
    }
}

/// Bytes of the tables as a container stores them (`spec/FORMAT.md` §3.5d), header included.
pub(super) fn stored_bytes<W: Words, U: Units>(t: &CompactTables<W, U>) -> u64 {
    let words = t.ring_starts.count()
        + t.ring_last.count()
        + t.ring_rank.count()
        + t.pairs.count()
        + t.blocks.count()
        + t.bases.count()
        + t.groups.count()
        + t.c.count()
        + t.overflow.count();
    let units = t.t0.count() + t.records.count();
    // The eight counts that describe the tables (m, m_r, rings, n0, U, F, k, reserved).
    const COUNTS: u64 = 8;
    4 * (COUNTS + words as u64) + 2 * units as u64
}
