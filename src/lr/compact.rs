//! The bit-efficient LR (section 6 of the LR paper; byte layout in `spec/FORMAT.md` §3.5d,
//! decoding in `spec/OPERATORS.md` §7): the slots, T0 triangles and rings of a standard LR,
//! in 16-bit units.
//!
//! - Each ring vertex `v` has one 32-bit **pair word** for its two slots. Its top two bits
//!   choose a configuration: two plain slots, a wart on the left, a wart on the right, or
//!   *extended*. A plain pair holds both tips as 15-bit signed offsets `tip - v`
//!   (HYBRID-RING-EXPANDER keeps them small, section 6.1); offset 0 on the right is `NULL`.
//! - An extended pair word holds the WART and IRREGULAR flags of both sides (so that the
//!   operators' frequent flag checks never leave the word), the left tip in 13 bits, and where
//!   its **record** starts. The record's head says which transversal corners have a stored
//!   opposite and holds the right tip in 12 bits; then come the tips too far for their short
//!   form (the paper's long references), then the stored opposites. *Beyond the paper:* only
//!   the opposites that the ring rules cannot infer are stored (usually one per irregular
//!   triangle, not two), as 16-bit fields.
//! - A **corner field** is one unit holding a 15-bit signed difference, or three units
//!   holding the absolute corner. A tag bit tells ring corners (relative to `8·v`) from T0
//!   corners (relative to the first corner of a nearby T0 row).
//! - **T0 rows** are 4 units: the anchor (the smallest ring vertex, which becomes corner 0)
//!   relative to its group of 64 rows, the other two vertices relative to it, and a 2-bit code
//!   per corner: the opposite is found by the left-slot rule, by the right-slot rule (the
//!   searches the ring corners use), in the row before or after (T0 neighbours are placed
//!   next to each other), or is `NONE`. *Beyond the paper*, which stores 192 bits per T0.
//!   Rows that do not fit this move to a 32-bit overflow row.
//! - Per block of 256 ring vertices: where the block's first record starts, and the first T0
//!   row anchored in it (the reference of T0 corner fields in its records).
//!
//! The operators are those of [`LrLayout`]; this module only encodes and decodes.

use super::tables::{LrLayout, LrTables, LEFT, NULL, RIGHT};
use super::{Lr, LrCounts, LrInspect, LrOptions, TriangleClass};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;
use crate::words::{Units, Words};

/// Ring vertices per block: `v >> BLOCK_SHIFT` is the block of `v`.
pub const BLOCK_SHIFT: u32 = 8;
/// T0 rows per group: `j >> GROUP_SHIFT` is the group of row `j`.
pub const GROUP_SHIFT: u32 = 6;
/// Units per T0 row.
pub const T0_ROW_UNITS: usize = 4;
/// Words per T0 overflow row: the three vertices, then the three opposites.
pub const OVERFLOW_ROW_WORDS: usize = 6;
/// Pair-word configuration (bits 30–31): two plain slots.
pub const PLAIN: u32 = 0;
/// Configuration: the left slot is a wart slot.
pub const WART_LEFT: u32 = 1;
/// Configuration: the right slot is a wart slot.
pub const WART_RIGHT: u32 = 2;
/// Configuration: the pair has a record.
pub const EXTENDED: u32 = 3;
/// Extended pair word: bits 0–12 the left tip's 13-bit offset (0: long, in the record),
/// bits 13–25 the record's start relative to its block's first record, bits 26–29 the
/// IRREGULAR flags (left, right) and the WART flags (left, right).
const RECORD_SHIFT: u32 = 13;
const FIELD13: u32 = 0x1FFF;
const X_IRREGULAR: [u32; 2] = [1 << 26, 1 << 27];
const X_WART: [u32; 2] = [1 << 28, 1 << 29];
/// Record head: bits 0–3 which transversal corners have a stored opposite (left 0, left 2,
/// right 4, right 6); bits 4–15 the right tip's 12-bit offset (0: `NULL`; `RIGHT_LONG`:
/// long, in the record).
const HEAD_TIP_SHIFT: u32 = 4;
const RIGHT_LONG: u16 = 0x800;
/// T0 row codes of an opposite.
const BY_LEFT_RULE: u16 = 0;
const BY_RIGHT_RULE: u16 = 1;
const IN_ADJACENT_ROW: u16 = 2;
const NO_OPPOSITE: u16 = 3;
/// T0 row unit 3: the row is in the overflow table.
const OVERFLOW_FLAG: u16 = 0x8000;
/// A corner field's tag bit: set for a T0 corner.
const TAG_T0: u16 = 0x8000;
/// The 15-bit pattern of a long corner field (tag 0) or of `NONE` (tag 1).
const ESCAPE: u16 = 0x4000;
/// The largest difference a 15-bit field holds.
const SHORT_MAX: i64 = 0x3FFF;

/// Sign-extends the low 15 bits.
#[inline(always)]
fn short15(unit: u32) -> i32 {
    ((unit as i32) << 17) >> 17
}

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
    /// As [`LrTables`]' field: derived, never stored.
    pub(crate) boundaries_on_ring: bool,
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

    /// The first unit of the record of extended pair `v` with pair word `p`.
    #[inline(always)]
    pub(crate) fn record_start(&self, v: u32, p: u32) -> usize {
        let block = (v >> BLOCK_SHIFT) as usize;
        self.blocks.at(2 * block) as usize + ((p >> RECORD_SHIFT) & FIELD13) as usize
    }

    /// Whether the IRREGULAR flags of extended pair `v` agree with its record's head (a side
    /// is IRREGULAR iff it stores an opposite). Reads the head: check `record_len` first.
    pub(crate) fn irregular_flags_agree(&self, v: u32) -> bool {
        let p = self.pair(v);
        let head = self.records.at(self.record_start(v, p));
        [LEFT, RIGHT]
            .iter()
            .all(|&side| (head >> (2 * side) & 3 != 0) == (p & X_IRREGULAR[side] != 0))
    }

    /// The units of the record of extended pair `v`, or `None` when they run past the
    /// record units. Reads only units it has checked exist (for validation).
    pub(crate) fn record_len(&self, v: u32) -> Option<usize> {
        let p = self.pair(v);
        let start = self.record_start(v, p);
        let n = self.records.count();
        let head = *(start < n).then(|| self.records.at(start)).as_ref()?;
        let mut at = start + 1;
        if p & FIELD13 == 0 {
            at += 2;
        }
        if head >> HEAD_TIP_SHIFT == RIGHT_LONG {
            at += 2;
        }
        for q in 0..4 {
            if head >> q & 1 != 0 {
                if at >= n {
                    return None;
                }
                at += corner_width(self.records.at(at));
            }
        }
        (at <= n).then_some(at - start)
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
    fn find_in_adjacent_row(&self, j: usize, x: u32, y: u32) -> u32 {
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
            return match short15(p >> (15 * side)) {
                0 => NULL,
                d => v.wrapping_add_signed(d),
            };
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

/// Options of the bit-efficient LR construction.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompactOptions {
    /// Options of each LR construction (seeds and tries).
    pub lr: LrOptions,
    /// Periods `k` of HYBRID-RING-EXPANDER to try (0: depth-first RING-EXPANDER); the
    /// smallest result is kept, as the paper chose `k` per mesh.
    pub periods: Vec<u32>,
}

impl Default for CompactOptions {
    fn default() -> Self {
        CompactOptions {
            lr: LrOptions::default(),
            periods: vec![0, 16, 32, 64, 128, 256, 512, 1024],
        }
    }
}

/// A mesh's connectivity in bit-efficient LR form, with the maps back to the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompactLr {
    tables: CompactTables<Vec<u32>, Vec<u16>>,
    /// The standard LR it encodes: vertex ids, counts and the maps to the input.
    lr: Lr,
    /// The HYBRID-RING-EXPANDER period of `lr` (0: depth first).
    period: u32,
    /// Compact T0 row -> standard T0 row.
    t0_standard: Vec<u32>,
}

/// Bytes of the tables as a container stores them (`spec/FORMAT.md` §3.5d), header included.
fn stored_bytes<W: Words, U: Units>(t: &CompactTables<W, U>) -> u64 {
    let words = t.ring_starts.count()
        + t.ring_last.count()
        + t.ring_rank.count()
        + t.pairs.count()
        + t.blocks.count()
        + t.groups.count()
        + t.c.count()
        + t.overflow.count();
    let units = t.t0.count() + t.records.count();
    // The eight counts that describe the tables (m, m_r, rings, n0, U, F, k, reserved).
    const COUNTS: u64 = 8;
    4 * (COUNTS + words as u64) + 2 * units as u64
}

impl CompactLr {
    /// Builds the bit-efficient LR: one standard LR per period of `options`, each encoded;
    /// the smallest is kept.
    ///
    /// # Errors
    /// [`Error::Unsupported`] when the mesh exceeds the LR's id space.
    pub fn build(ct: &CornerTable, options: &CompactOptions) -> Result<CompactLr> {
        let mut best: Option<CompactLr> = None;
        let periods: &[u32] = if options.periods.is_empty() {
            &[0]
        } else {
            &options.periods
        };
        for &period in periods {
            let lr = Lr::build_with_period(ct, &options.lr, period)?;
            let candidate = CompactLr::encode(lr, period)?;
            if best
                .as_ref()
                .is_none_or(|b| candidate.stored_bytes() < b.stored_bytes())
            {
                best = Some(candidate);
            }
        }
        Ok(best.expect("at least one period"))
    }

    /// Encodes a standard LR built with period `period`.
    fn encode(lr: Lr, period: u32) -> Result<CompactLr> {
        let t = lr.tables();
        let m_r = t.m_r;
        let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);

        // T0 rows: rotated to start at their anchor, sorted by it.
        let n0 = t.t0_count() as usize;
        let mut rotation = vec![0usize; n0];
        let mut anchors = Vec::with_capacity(n0);
        for (j, r) in rotation.iter_mut().enumerate() {
            let vs = [0, 1, 2].map(|i| t.vo_v[3 * j + i]);
            *r = (0..3)
                .filter(|&i| vs[i] < m_r)
                .min_by_key(|&i| vs[i])
                .unwrap_or(0);
            anchors.push((vs[*r], j as u32));
        }
        anchors.sort_unstable();
        let anchor_of: Vec<u32> = {
            let mut a = vec![0; n0];
            for &(anchor, j) in &anchors {
                a[j as usize] = anchor;
            }
            a
        };
        let t0_standard = t0_order(t, &anchors);
        let mut t0_compact = vec![0u32; n0];
        for (jc, &j) in t0_standard.iter().enumerate() {
            t0_compact[j as usize] = jc as u32;
        }
        let base = 8 * m_r;
        let map_corner = |c: u32| {
            if c == NONE || c < base {
                return c;
            }
            let (j, i) = (((c - base) / 4) as usize, ((c - base) % 4) as usize);
            base + 4 * t0_compact[j] + ((i + 3 - rotation[j]) % 3) as u32
        };

        // Blocks: the first row anchored in each (the reference of T0 corner fields in its
        // records; their first record comes with the pairs).
        let mut block_words = vec![0u32; 2 * blocks];
        let mut first_row = vec![u32::MAX; blocks + 1];
        first_row[blocks] = n0 as u32;
        for (jc, &j) in t0_standard.iter().enumerate() {
            let block = (anchor_of[j as usize] >> BLOCK_SHIFT).min(blocks as u32) as usize;
            first_row[block] = first_row[block].min(jc as u32);
        }
        for b in (0..blocks).rev() {
            first_row[b] = first_row[b].min(first_row[b + 1]);
            block_words[2 * b + 1] = first_row[b];
        }

        // Pairs and records.
        let mut pairs = Vec::with_capacity(m_r as usize);
        let mut records: Vec<u16> = Vec::new();
        for v in 0..m_r {
            let block = (v >> BLOCK_SHIFT) as usize;
            if v % (1 << BLOCK_SHIFT) == 0 {
                block_words[2 * block] = records.len() as u32;
            }
            let tips = [LEFT, RIGHT].map(|side| t.tip(v, side));
            let warts = [LEFT, RIGHT].map(|side| t.wart(v, side));
            let stored = stored_corners(t, v);
            let offsets = [LEFT, RIGHT].map(|side| pair_offset(tips[side], v, side));
            if stored == [None; 4] {
                let config = match warts {
                    [false, false] => Some(PLAIN),
                    [true, false] => Some(WART_LEFT),
                    [false, true] => Some(WART_RIGHT),
                    _ => None,
                };
                if let (Some(config), [Some(l), Some(r)]) = (config, offsets) {
                    pairs.push(config << 30 | (r as u32 & 0x7FFF) << 15 | (l as u32 & 0x7FFF));
                    continue;
                }
            }
            let relative = records.len() as u32 - block_words[2 * block];
            let left = match tips[LEFT] as i64 - v as i64 {
                d if d != 0 && d.abs() <= (FIELD13 >> 1) as i64 => Some(d as u32 & FIELD13),
                _ => None,
            };
            let mut word = EXTENDED << 30 | relative << RECORD_SHIFT | left.unwrap_or(0);
            for side in [LEFT, RIGHT] {
                if warts[side] {
                    word |= X_WART[side];
                }
                if stored[2 * side].is_some() || stored[2 * side + 1].is_some() {
                    word |= X_IRREGULAR[side];
                }
            }
            pairs.push(word);
            let right = match tips[RIGHT] {
                NULL => Some(0),
                tip => {
                    let d = tip as i64 - v as i64;
                    (d != 0 && d.abs() < RIGHT_LONG as i64).then_some(d as u16 & 0xFFF)
                }
            };
            let mut head = 0u16;
            for (q, o) in stored.iter().enumerate() {
                head |= (o.is_some() as u16) << q;
            }
            head |= right.unwrap_or(RIGHT_LONG) << HEAD_TIP_SHIFT;
            records.push(head);
            if left.is_none() {
                records.extend([tips[LEFT] as u16, (tips[LEFT] >> 16) as u16]);
            }
            if right.is_none() {
                records.extend([tips[RIGHT] as u16, (tips[RIGHT] >> 16) as u16]);
            }
            let t0_reference = block_words[2 * block + 1];
            for o in stored.into_iter().flatten() {
                let o = map_corner(o);
                match short_corner(o, v, t0_reference, m_r) {
                    Some(unit) => records.push(unit),
                    None => records.extend([ESCAPE, o as u16, (o >> 16) as u16]),
                }
            }
            if relative > FIELD13 {
                return Err(Error::Unsupported("LR record block overflow".into()));
            }
        }
        let several = t.ring_count() > 1;
        let mut tables = CompactTables {
            ring_starts: t.ring_starts.clone(),
            ring_last: if several {
                t.ring_last.clone()
            } else {
                Vec::new()
            },
            ring_rank: if several {
                t.ring_rank.clone()
            } else {
                Vec::new()
            },
            pairs,
            blocks: block_words,
            groups: Vec::new(),
            c: t.c.iter().map(|&x| map_corner(x)).collect(),
            overflow: Vec::new(),
            t0: Vec::new(),
            records,
            m_r,
            m: t.m,
            boundaries_on_ring: t.boundaries_on_ring,
        };

        // T0 rows, whose opposites are found with the ring slots and the rows before them.
        let triangle = |jc: usize| {
            let (j, r) = (t0_standard[jc] as usize, rotation[t0_standard[jc] as usize]);
            [0, 1, 2].map(|i| t.vo_v[3 * j + (i + r) % 3])
        };
        tables.groups = t0_standard
            .chunks(1 << GROUP_SHIFT)
            .map(|group| {
                group
                    .iter()
                    .map(|&j| anchor_of[j as usize])
                    .min()
                    .unwrap_or(0)
            })
            .collect();
        for jc in 0..n0 {
            let (j, r) = (t0_standard[jc] as usize, rotation[t0_standard[jc] as usize]);
            let vs = triangle(jc);
            let os = [0, 1, 2].map(|i| map_corner(t.vo_o[3 * j + (i + r) % 3]));
            let group_base = tables.groups[jc >> GROUP_SHIFT];
            let next = (jc + 1 < n0).then(|| triangle(jc + 1));
            let row = vs[0]
                .checked_sub(group_base)
                .and_then(|offset| t0_row(&tables, vs, os, offset, jc as u32, next));
            match row {
                Some(row) => tables.t0.extend(row),
                None => {
                    let index = (tables.overflow.len() / OVERFLOW_ROW_WORDS) as u32;
                    tables
                        .t0
                        .extend([0, index as u16, (index >> 16) as u16, OVERFLOW_FLAG]);
                    tables.overflow.extend(vs.into_iter().chain(os));
                }
            }
        }

        // The encoding must answer exactly as the standard LR does (corner ids mapped).
        for tri in t.triangles() {
            for c in t.triangle_corners(tri) {
                let ours = Corner(map_corner(c.0));
                if tables.vertex(ours) != t.vertex(c)
                    || tables.opposite_raw(ours.0) != map_corner(t.opposite_raw(c.0))
                {
                    return Err(Error::Internal(format!(
                        "bit-efficient LR disagrees with the standard LR at corner {}",
                        c.0
                    )));
                }
            }
        }
        Ok(CompactLr {
            tables,
            lr,
            period,
            t0_standard,
        })
    }

    /// The tables, which implement the corner operators.
    pub fn tables(&self) -> &CompactTables<Vec<u32>, Vec<u16>> {
        &self.tables
    }

    /// The HYBRID-RING-EXPANDER period `k` chosen (0: depth first).
    pub fn period(&self) -> u32 {
        self.period
    }

    /// The standard LR counts of the ring chosen.
    pub fn counts(&self) -> LrCounts {
        self.lr.counts()
    }

    /// Bytes of the connectivity section (`LRBE`) this LR becomes.
    pub fn stored_bytes(&self) -> u64 {
        stored_bytes(&self.tables)
    }

    /// The input vertex that vertex `v` stands for.
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.lr.input_vertex(v)
    }

    /// The input triangle that canonical triangle `t` stands for.
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        let ring_slots = 2 * self.tables.m_r;
        if t.0 < ring_slots {
            return self.lr.input_triangle(t);
        }
        let standard = self.t0_standard[(t.0 - ring_slots) as usize];
        self.lr.input_triangle(Triangle(ring_slots + standard))
    }

    /// Degenerate input triangles, kept aside: `(input index, input vertex triple)`.
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        self.lr.kept_aside()
    }

    /// The input triangles, in input order, from the bit-efficient LR alone (each with the
    /// same orientation, possibly rotated).
    pub fn input_triangles(&self) -> Vec<[u32; 3]> {
        let kept = self.kept_aside();
        let mut out = vec![[0u32; 3]; self.counts().triangles as usize + kept.len()];
        for t in self.tables.triangles() {
            let [a, b, c] = self
                .tables
                .triangle_vertices(t)
                .map(|v| self.input_vertex(v));
            out[self.input_triangle(t) as usize] = [a, b, c];
        }
        for &(input, tri) in kept {
            out[input as usize] = tri;
        }
        out
    }

    /// The statistics of `lrmesh stats` (JSON object `lr_compact`).
    pub fn stats(&self) -> CompactStats {
        CompactStats::new(self)
    }
}

/// A plain pair's offset `tip - v` of one side, if it fits (`NULL`: 0 on the right).
fn pair_offset(tip: u32, v: u32, side: usize) -> Option<i16> {
    if tip == NULL {
        return (side == RIGHT).then_some(0);
    }
    let d = tip as i64 - v as i64;
    (d != 0 && (-SHORT_MAX - 1..=SHORT_MAX).contains(&d)).then_some(d as i16)
}

/// The order of the T0 rows (standard T0 indices): by anchor, except that T0 triangles next
/// to each other follow each other, as paths, so that a row finds its T0 neighbours in the
/// rows before and after it.
fn t0_order(t: &LrTables<Vec<u32>>, anchors: &[(u32, u32)]) -> Vec<u32> {
    let n0 = anchors.len();
    let base = 8 * t.m_r;
    let mut rank = vec![0u32; n0];
    for (k, &(_, j)) in anchors.iter().enumerate() {
        rank[j as usize] = k as u32;
    }
    let neighbours = |j: usize| {
        let mut out = [u32::MAX; 3];
        for (i, slot) in out.iter_mut().enumerate() {
            let o = t.vo_o[3 * j + i];
            if o != NONE && o >= base {
                *slot = (o - base) / 4;
            }
        }
        // Lowest anchor first.
        out.sort_unstable_by_key(|&u| {
            if u == u32::MAX {
                u32::MAX
            } else {
                rank[u as usize]
            }
        });
        out
    };
    let mut placed = vec![false; n0];
    let mut probed = vec![false; n0];
    let mut order = Vec::with_capacity(n0);
    for &(_, start) in anchors {
        if placed[start as usize] {
            continue;
        }
        // Walk to the end of a path through unplaced neighbours, then place from there back.
        let mut end = start;
        let mut probe = vec![start];
        probed[start as usize] = true;
        while let Some(&u) = neighbours(end as usize)
            .iter()
            .find(|&&u| u != u32::MAX && !placed[u as usize] && !probed[u as usize])
        {
            probed[u as usize] = true;
            probe.push(u);
            end = u;
        }
        for u in probe {
            probed[u as usize] = false;
        }
        let mut j = end;
        loop {
            placed[j as usize] = true;
            order.push(j);
            match neighbours(j as usize)
                .iter()
                .find(|&&u| u != u32::MAX && !placed[u as usize])
            {
                Some(&u) => j = u,
                None => break,
            }
        }
    }
    order
}

/// The opposites slot pair `v` must store, in the order left 0, left 2, right 4, right 6:
/// those of irregular slots that the ring rules do not infer. A slot whose tip looks like a
/// redundant T2's keeps both, which marks it canonical.
fn stored_corners(t: &LrTables<Vec<u32>>, v: u32) -> [Option<u32>; 4] {
    let mut out = [None; 4];
    for side in [LEFT, RIGHT] {
        let [a, b] = [0, 1].map(|second| t.stored_opposite(v, side, second));
        let (Some(a), Some(b)) = (a, b) else {
            continue;
        };
        let i = 4 * side as u32;
        let fails = [
            t.inferred_opposite(v, i) != a,
            t.inferred_opposite(v, i + 2) != b,
        ];
        let looks_redundant = !t.wart(v, side) && t.tip(v, side) == t.ring_next(t.ring_next(v));
        let keep = if looks_redundant || fails == [false, false] {
            [true, true]
        } else {
            fails
        };
        out[2 * side] = keep[0].then_some(a);
        out[2 * side + 1] = keep[1].then_some(b);
    }
    out
}

/// The T0 row `row` of a triangle with vertices `vs` and opposites `os` (anchor first),
/// or `None` when it must overflow. `tables` has its ring slots and the rows before `row`;
/// `next` is the triangle of the next row, if any.
fn t0_row<W: Words, U: Units>(
    tables: &CompactTables<W, U>,
    vs: [u32; 3],
    os: [u32; 3],
    anchor_offset: u32,
    row: u32,
    next: Option<[u32; 3]>,
) -> Option<[u16; T0_ROW_UNITS]> {
    let anchor_offset = u16::try_from(anchor_offset).ok()?;
    let [d1, d2] = [vs[1], vs[2]].map(|x| x as i64 - vs[0] as i64);
    if [d1, d2]
        .iter()
        .any(|d| !(-SHORT_MAX..=SHORT_MAX).contains(d))
    {
        return None;
    }
    let t0_base = 8 * tables.m_r;
    let mut codes = 0u16;
    for i in 0..3 {
        let (x, y) = (vs[(i + 1) % 3], vs[(i + 2) % 3]);
        // The decoder searches the previous row, then the next one.
        let adjacent = || {
            let previous = tables.find_in_adjacent_row(row as usize, x, y);
            if previous != NONE {
                return Some(previous);
            }
            let next = next?;
            (0..3)
                .find(|&k| next[(k + 1) % 3] == y && next[(k + 2) % 3] == x)
                .map(|k| t0_base + 4 * (row + 1) + k as u32)
        };
        let code = if os[i] == NONE {
            NO_OPPOSITE
        } else if tables.find_left(x, y) == os[i] {
            BY_LEFT_RULE
        } else if tables.find_right(x, y) == os[i] {
            BY_RIGHT_RULE
        } else if adjacent() == Some(os[i]) {
            IN_ADJACENT_ROW
        } else {
            return None;
        };
        codes |= code << (2 * i);
    }
    Some([anchor_offset, d1 as u16 & 0x7FFF, d2 as u16 & 0x7FFF, codes])
}

/// A short corner field, if it fits: `NONE`, a ring corner relative to `8·ring_reference`,
/// or a T0 corner relative to the first corner of T0 row `t0_reference`.
fn short_corner(c: u32, ring_reference: u32, t0_reference: u32, m_r: u32) -> Option<u16> {
    let base = 8 * m_r as i64;
    let (d, tag) = match c {
        NONE => return Some(TAG_T0 | ESCAPE),
        c if (c as i64) < base => (c as i64 - 8 * ring_reference as i64, 0),
        c => (c as i64 - base - 4 * t0_reference as i64, TAG_T0),
    };
    (-SHORT_MAX..=SHORT_MAX)
        .contains(&d)
        .then_some(tag | (d as u16 & 0x7FFF))
}

/// The bit-efficient LR's statistics (`lrmesh stats`, JSON object `lr_compact`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct CompactStats {
    /// The HYBRID-RING-EXPANDER period chosen (0: depth first).
    pub k: u32,
    /// Triangles `n` (degenerate ones, kept aside, not counted).
    pub triangles: u32,
    /// Isolated vertices `m_i`.
    pub isolated_vertices: u32,
    /// Percentage of T0 triangles after wart skipping.
    pub t0_pct: f64,
    /// Percentage of T0 triangles in a wart's slot.
    pub t0w_pct: f64,
    /// Percentage of irregular T1 triangles (T0^w included, stored as T1).
    pub t1i_pct: f64,
    /// Percentage of irregular T2 triangles.
    pub t2i_pct: f64,
    /// Percentage of pairs with a record (long references or irregular slots), of triangles.
    pub tl_pct: f64,
    /// Percentage of T0 rows whose fields overflow to 32 bits, of triangles.
    pub t0_overflow_pct: f64,
    /// Bytes of the `LRBE` section.
    pub bytes: u64,
    /// Connectivity bits per triangle: every byte of the `LRBE` section.
    pub bpt: f64,
}

impl CompactStats {
    fn new(lr: &CompactLr) -> CompactStats {
        let t = &lr.tables;
        let counts = lr.counts();
        let n = counts.triangles.max(1) as f64;
        let pct = |x: usize| 100.0 * x as f64 / n;
        let (mut t1i, mut t2i) = (0, 0);
        for v in 0..t.m_r {
            for side in [LEFT, RIGHT] {
                if t.irregular(v, side) {
                    // T0^w slots are stored as T1s, so they count there.
                    match t.triangle_class(Triangle(2 * v + side as u32)) {
                        Some(TriangleClass::T2 | TriangleClass::T2Wart) => t2i += 1,
                        _ => t1i += 1,
                    }
                }
            }
        }
        let extended = (0..t.m_r).filter(|&v| t.is_extended(v)).count();
        let bytes = lr.stored_bytes();
        CompactStats {
            k: lr.period,
            triangles: counts.triangles,
            isolated_vertices: counts.isolated_vertices(),
            t0_pct: pct(counts.t0 as usize),
            t0w_pct: pct(counts.t0_wart as usize),
            t1i_pct: pct(t1i),
            t2i_pct: pct(t2i),
            tl_pct: pct(extended),
            t0_overflow_pct: pct(t.overflow_rows() as usize),
            bytes,
            bpt: 8.0 * bytes as f64 / n,
        }
    }
}

impl std::fmt::Display for CompactStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "bit-efficient LR")?;
        writeln!(f, "  period k                 {}", self.k)?;
        writeln!(f, "  isolated vertices m_i    {}", self.isolated_vertices)?;
        writeln!(f, "  T0 (after wart skipping) {:.2}%", self.t0_pct)?;
        writeln!(f, "  T0^w                     {:.2}%", self.t0w_pct)?;
        writeln!(f, "  T1^i                     {:.2}%", self.t1i_pct)?;
        writeln!(f, "  T2^i                     {:.2}%", self.t2i_pct)?;
        writeln!(f, "  pairs with a record      {:.2}%", self.tl_pct)?;
        writeln!(f, "  bytes                    {}", self.bytes)?;
        writeln!(f, "  bits per triangle        {:.2}", self.bpt)
    }
}
