//! Zipper: the LR's slots in about three bits each (after Gurung, Luffel, Lindstrom and
//! Rossignac, "Zipper: a compact connectivity data structure for triangle meshes", CAD 45(2),
//! 2013; our own layout).
//!
//! Along a ring the tips of consecutive slots on one side run backwards one small step at a
//! time: the left tips walk the previous turn of the spiral, the right tips the next one. So
//! each slot stores a 3-bit **symbol** instead of a 32-bit entry:
//!
//! - `0..=3`: the tip is the side's **chain value** minus the symbol, and becomes the chain
//!   value;
//! - `4`: the tip is `v.p` (a canonical T2); `5`: on the left the tip is `v.n.n` (the
//!   redundant copy of a T2), on the right `NULL` (no triangle); the chain value does not
//!   move;
//! - `6`: an **exception**, a word with the WART flag and the tip;
//! - `7`: an **irregular** slot, a record with the WART flag and the tip, then the opposite
//!   that the ring rules cannot infer (always a T0 corner on the meshes we measured: the
//!   slots next to T0 triangles), or a pair of opposites stored whole.
//!
//! An exception's or record's tip becomes the chain value. A slot followed on its side by a
//! canonical T2 can only hold the T2's redundant copy or a wart (the T2 covers the slot's
//! ring edge on that side): with the header flag `WART_DELTAS` a delta symbol there is a
//! wart and symbol 5 the redundant copy on either side, so that most warts (a tenth of the
//! triangles of a scan after the ring's leaf moves) cost a symbol, not an exception word. The slots of 64 ring vertices
//! (slot `2i + side` of the block) make three 128-bit planes, one bit of each symbol per
//! plane, stored as groups of 32 slots whose three plane words are adjacent (a symbol is one
//! group's read), so that a tip is found in constant time with bit operations: the last exception or
//! record of its side in the block at or before it (or the block's **anchor** for that side,
//! the chain value before the block) minus the sum of the delta symbols in between, a few
//! population counts. Each block's head holds the two anchors and the exceptions and records
//! before the block.
//!
//! T0 rows hold three vertices and a word of 2-bit codes: each opposite is found by the
//! left-slot or the right-slot search of the ring rules (the searches of the ring corners),
//! is `NONE`, or is stored in a list of explicit opposites (the row's word says where its
//! first one is). Rings and C are the standard LR's, and so are every id and flag: every
//! operator is [`LrLayout`](super::LrLayout)'s and answers as the standard LR does.

mod cursor;
mod encode;
mod expand;
mod packed;
mod slots;
mod tables;

pub use cursor::{ZipperCursor, CACHED_BLOCKS};
pub(crate) use encode::ring_blocks;
pub use packed::{
    first_bit, join_bits, list_fields, packed_words, ring_block_field, unjoined_zipr, Field,
    FieldKind, Packed,
};
pub use slots::plane_array_words;
pub(crate) use slots::Slot;
pub(crate) use slots::{below, four_sides, implied_wart, slot_bytes, LEFT_SLOTS};
pub use tables::ZipperTables;

use super::{InputMaps, Lr, LrCounts, LrOptions};
use crate::corner_table::CornerTable;
use crate::error::Result;
use crate::ids::{Triangle, Vertex};

/// Ring vertices per block: `v >> BLOCK_SHIFT` is the block of `v`.
pub const BLOCK_SHIFT: u32 = 6;
/// Slots in a block: two per ring vertex.
pub(crate) const BLOCK_SLOTS: usize = 2 << BLOCK_SHIFT;
/// Symbols below this are chain deltas.
pub const DELTAS: u32 = 4;
/// Symbol: the tip is `v.p`.
pub const PREVIOUS: u32 = 4;
/// Symbol: the tip is `v.n.n` on the left, `NULL` on the right.
pub const NEXT_NEXT_OR_NULL: u32 = 5;
/// The decrement of a *four*: a slot of symbol 5 that the header's `LEFT_FOURS` or
/// `RIGHT_FOURS` flag makes a delta slot (FORMAT.md §3.5e.4).
pub const FOUR: u32 = 4;
/// Symbol: the slot's tip and WART flag are in the exception list.
pub const EXCEPTION: u32 = 6;
/// Symbol: the slot is irregular, its record in the record list.
pub const IRREGULAR_SLOT: u32 = 7;
/// Words per block in the plane array: four groups of 32 slots, each the three planes' words
/// (the last block has only the groups its slots need).
pub const PLANE_WORDS: usize = 12;
/// Words per block in the head array: the left and right anchors, the exceptions and the
/// records before the block.
pub const HEAD_WORDS: usize = 4;
/// Words per block in the head array with `SHORT_HEADS` (version 1.9): the anchors as 16-bit
/// offsets from the block's first vertex, then the exceptions and records before the block
/// as 16-bit offsets from those before its superblock.
pub const SHORT_HEAD_WORDS: usize = 2;
/// Blocks per superblock: `block >> SUPER_SHIFT` is the superblock of `block`, whose
/// exceptions and records before it the `SUPER` array holds (from superblock 1 on).
pub const SUPER_SHIFT: u32 = 8;
/// Blocks per superblock in the compact form (version 1.13, FORMAT.md §3.5e.3): the heads'
/// counts are offsets from their superblock's, in as few bits as the largest needs.
pub const COMPACT_SUPER_SHIFT: u32 = 4;
/// The widest field of a compact head (anchor offsets and counts), in bits.
pub const MAX_HEAD_WIDTH: u8 = 16;

/// Bytes per count in a compact `ZIPR` header: the fewest that hold the largest of `counts`
/// (1 to 4).
pub fn count_bytes(counts: &[u32]) -> u8 {
    let largest = counts.iter().copied().max().unwrap_or(0);
    (32 - largest.leading_zeros()).div_ceil(8).max(1) as u8
}

/// Bytes of a compact `ZIPR` header whose eight counts take `k` bytes each.
pub fn compact_header_len(k: u8) -> usize {
    8 + 8 * k as usize
}
/// Words per record: WART flag and tip, then which opposites are stored and the stored one.
pub const RECORD_WORDS: usize = 2;
/// Record word 1, bits 30–31: no opposite stored (both inferred).
pub const STORES_NONE: u32 = 0;
/// The first transversal corner's opposite is the T0 corner `8 m_r` + the low 30 bits.
pub const STORES_FIRST: u32 = 1;
/// The second transversal corner's opposite is the T0 corner `8 m_r` + the low 30 bits.
pub const STORES_SECOND: u32 = 2;
/// Both opposites are stored whole, in the pair list at the index of the low 30 bits.
pub const STORES_BOTH: u32 = 3;
/// Where a record's storage state lies in its word 1.
pub const STATE_SHIFT: u32 = 30;
/// T0 row codes of an opposite.
pub const BY_LEFT_RULE: u32 = 0;
/// The opposite is the right-slot search's answer.
pub const BY_RIGHT_RULE: u32 = 1;
/// The corner has no opposite (a boundary).
pub const NO_OPPOSITE: u32 = 2;
/// The opposite is in the list of explicit T0 opposites.
pub const EXPLICIT: u32 = 3;
/// Bits of a T0 row's code word below its first explicit opposite's index.
pub const EXPLICIT_SHIFT: u32 = 6;

/// A mesh's connectivity in Zipper form, with the maps back to the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Zipper {
    tables: ZipperTables<Vec<u32>>,
    /// Of the standard LR it encodes (the same vertex and triangle ids): the counts and the
    /// maps to the input.
    lr: InputMaps,
}

impl Zipper {
    /// Builds the standard LR of `ct` and encodes it.
    ///
    /// # Errors
    /// [`Error::Unsupported`](crate::Error::Unsupported) when the mesh exceeds the LR's id
    /// space.
    pub fn build(ct: &CornerTable, options: &LrOptions) -> Result<Zipper> {
        Zipper::encode(Lr::build_for_encoding(ct, options)?)
    }

    /// The smallest of the Zipper tables built from `seeds` seeds: `options.seed` and those
    /// after it. Where the ring expansions start decides the ring, and so how many slots
    /// the symbols cannot code (exceptions, records) and how many T0 rows there are: on
    /// small meshes the smallest of 16 builds is 5–12% below the first. Of equal sizes the
    /// first seed's is kept, so that the same options give the same tables. The seeds are
    /// shared round robin among up to `options.threads` threads, each build on one.
    ///
    /// # Errors
    /// As [`Zipper::build`].
    pub fn build_smallest(ct: &CornerTable, options: &LrOptions, seeds: u32) -> Result<Zipper> {
        if seeds <= 1 {
            return Zipper::build(ct, options);
        }
        let workers = options.threads.clamp(1, seeds);
        let one = LrOptions {
            threads: 1,
            ..*options
        };
        // Worker w builds seeds w, w + workers, ...: its smallest (size, seed index, tables).
        let best_of = |w: u32| -> Result<Option<Candidate>> {
            let mut best = None;
            for k in (w..seeds).step_by(workers as usize) {
                let seed = options.seed.wrapping_add(u64::from(k));
                let z = Zipper::build(ct, &LrOptions { seed, ..one })?;
                keep_smaller(&mut best, (z.tables.stored_bytes(), k, z));
            }
            Ok(best)
        };
        let results: Vec<Result<Option<Candidate>>> = std::thread::scope(|scope| {
            let handles: Vec<_> = (1..workers)
                .map(|w| scope.spawn(move || best_of(w)))
                .collect();
            let first = best_of(0);
            // A worker only panics on a broken invariant: pass it on.
            let rest = handles
                .into_iter()
                .map(|h| h.join().expect("zipper worker"));
            std::iter::once(first).chain(rest).collect()
        });
        let mut best = None;
        for result in results {
            if let Some(candidate) = result? {
                keep_smaller(&mut best, candidate);
            }
        }
        best.map(|(_, _, z)| z)
            .ok_or_else(|| crate::Error::Internal("zipper: no seed built".into()))
    }

    /// Encodes a standard LR (same vertex, triangle and corner ids).
    ///
    /// # Errors
    /// [`Error::Unsupported`](crate::Error::Unsupported) when the T0 rows have more explicit
    /// opposites than their code words can index (2^26).
    pub fn encode(lr: Lr) -> Result<Zipper> {
        let tables = encode::encode(lr.tables())?;
        let lr = lr.into_input_maps();
        Ok(Zipper { tables, lr })
    }

    /// The tables, which implement the corner operators.
    pub fn tables(&self) -> &ZipperTables<Vec<u32>> {
        &self.tables
    }

    /// The standard LR counts of the ring.
    pub fn counts(&self) -> LrCounts {
        self.lr.counts()
    }

    /// The input vertex that vertex `v` stands for.
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.lr.input_vertex(v)
    }

    /// The input triangle that canonical triangle `t` stands for.
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.lr.input_triangle(t)
    }

    /// Degenerate input triangles, kept aside: `(input index, input vertex triple)`.
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        self.lr.kept_aside()
    }

    /// The input triangles, in input order, from the Zipper tables alone (each with the same
    /// orientation, possibly rotated).
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

    /// The statistics of `lrmesh stats` (JSON object `zipper`).
    pub fn stats(&self) -> ZipperStats {
        let t = &self.tables;
        let n = self.counts().triangles.max(1) as f64;
        let bytes = t.stored_bytes();
        let parts = t.part_words();
        let bits = |words: usize| 32.0 * words as f64 / n;
        ZipperStats {
            triangles: self.counts().triangles,
            exceptions_pct: 100.0 * (t.exception_count() + t.record_count()) as f64 / n,
            bytes,
            bits_per_triangle: 8.0 * bytes as f64 / n,
            symbol_bits: bits(parts[0]),
            exception_bits: bits(parts[1]),
            record_bits: bits(parts[2]),
            t0_bits: bits(parts[3]),
        }
    }
}

/// A Zipper of [`Zipper::build_smallest`]'s search: its size in bytes, its seed's index, it.
type Candidate = (u64, u32, Zipper);

/// Makes `best` the smaller of it and `candidate` by size, then seed index (the first seed's
/// of equal sizes).
fn keep_smaller(best: &mut Option<Candidate>, candidate: Candidate) {
    if best
        .as_ref()
        .is_none_or(|(b, j, _)| (candidate.0, candidate.1) < (*b, *j))
    {
        *best = Some(candidate);
    }
}

/// The Zipper's statistics (`lrmesh stats`, JSON object `zipper`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ZipperStats {
    /// Triangles `n` (degenerate ones, kept aside, not counted).
    pub triangles: u32,
    /// Exception and irregular slots, as a percentage of triangles.
    pub exceptions_pct: f64,
    /// Bytes of the tables.
    pub bytes: u64,
    /// Connectivity bits per triangle: every byte of the tables.
    pub bits_per_triangle: f64,
    /// Of those, the symbol planes and block heads.
    pub symbol_bits: f64,
    /// The exception entries.
    pub exception_bits: f64,
    /// The records of irregular slots.
    pub record_bits: f64,
    /// The T0 rows and their explicit opposites.
    pub t0_bits: f64,
}

impl std::fmt::Display for ZipperStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "zipper")?;
        writeln!(f, "  exceptions               {:.2}%", self.exceptions_pct)?;
        writeln!(
            f,
            "  symbols and heads        {:.2} bits/t",
            self.symbol_bits
        )?;
        writeln!(
            f,
            "  exceptions               {:.2} bits/t",
            self.exception_bits
        )?;
        writeln!(
            f,
            "  irregular records        {:.2} bits/t",
            self.record_bits
        )?;
        writeln!(f, "  T0 rows                  {:.2} bits/t", self.t0_bits)?;
        writeln!(f, "  bytes                    {}", self.bytes)?;
        writeln!(
            f,
            "  bits per triangle        {:.2}",
            self.bits_per_triangle
        )
    }
}

#[cfg(test)]
mod tests;
