//! The bit-efficient LR (section 6 of the LR paper; byte layout in `spec/FORMAT.md` §3.5d,
//! decoding in `spec/OPERATORS.md` §7): the slots, T0 triangles and rings of a standard LR,
//! in 16-bit units.
//!
//! - Each ring vertex `v` has one 32-bit **pair word** for its two slots. Its top two bits
//!   choose a configuration: two plain slots, a wart on the left, a wart on the right, or
//!   *extended*. A plain pair holds both tips as 15-bit signed offsets `tip - v`
//!   (HYBRID-RING-EXPANDER keeps them small, section 6.1); offset 0 on the right is `NULL`.
//!   *Beyond the paper*, with **tip bases** (when they save bytes) an offset is 14 bits from
//!   `v` or from `v` plus a base per side and block of 256 ring vertices: the depth-first
//!   ring, with the fewest T0 and irregular triangles, then needs almost no records (see
//!   `plain`).
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
//!   row anchored in it (the reference of T0 corner fields in its records); with tip bases,
//!   the base of its left and of its right tips.
//!
//! The operators are those of [`LrLayout`](super::LrLayout); this module only encodes and
//! decodes: the tables and their decoding are in `tables`, the construction in `encode`, the
//! statistics in `stats`.

mod encode;
pub mod plain;
mod stats;
mod tables;

pub use stats::CompactStats;
pub use tables::CompactTables;

use super::{InputMaps, LrCounts, LrOptions};
use crate::ids::{Triangle, Vertex};
use tables::stored_bytes;

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
pub(crate) const SHORT_MAX: i64 = 0x3FFF;

/// Options of the bit-efficient LR construction.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompactOptions {
    /// Options of each LR construction (seeds and tries).
    pub lr: LrOptions,
    /// Periods `k` of HYBRID-RING-EXPANDER to choose from (0: depth-first RING-EXPANDER),
    /// as the paper chose `k` per mesh: the one whose rings promise the smallest encoding.
    pub periods: Vec<u32>,
    /// Tip bases (the `LRBE` flag `TIP_BASES`, version 1.11; see `plain`): `None` when they
    /// make the section smaller, `Some(true)` always, `Some(false)` never (a file that
    /// readers of version 1.10 read).
    pub tip_bases: Option<bool>,
}

impl Default for CompactOptions {
    fn default() -> Self {
        CompactOptions {
            lr: LrOptions::default(),
            // Longer periods behave like depth first and were never the smallest on the
            // shared meshes (with 256, 512 and 1024 too, the same sizes were chosen).
            periods: vec![0, 16, 32, 64, 128],
            tip_bases: None,
        }
    }
}

/// A mesh's connectivity in bit-efficient LR form, with the maps back to the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompactLr {
    tables: CompactTables<Vec<u32>, Vec<u16>>,
    /// Of the standard LR it encodes: the counts and the maps to the input.
    lr: InputMaps,
    /// The HYBRID-RING-EXPANDER period of `lr` (0: depth first).
    period: u32,
    /// Compact T0 row -> standard T0 row.
    t0_standard: Vec<u32>,
}

impl CompactLr {
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
        super::input_triangles_of(
            &self.tables,
            self.counts().triangles as usize + kept.len(),
            kept,
            |v| self.input_vertex(v),
            |t| self.input_triangle(t),
        )
    }

    /// The statistics of `lrmesh stats` (JSON object `lr_compact`).
    pub fn stats(&self) -> CompactStats {
        CompactStats::new(self)
    }
}
