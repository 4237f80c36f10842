//! A reader of Zipper tables for loops over a mesh: the same operators, with the slots of the
//! blocks read last kept decoded (`spec/OPERATORS.md` §8.6).
//!
//! Every Zipper operator reads slot fields (a tip, the WART and IRREGULAR flags), and each
//! such read decodes the slot from its block's symbol planes: about 250–300 instructions,
//! most of an operator's time (the valence loop reads some 20 slots per vertex). The
//! operators of a loop keep returning to the same few blocks: those of the vertex at hand
//! and of the ring rows beside it. [`ZipperCursor`] decodes a block's 128 slots in one pass
//! (`ZipperTables::decode_block`: each side's chain followed slot by slot, then every slot's
//! word chosen by masks in a loop the compiler vectorizes, about 45 instructions a slot in
//! all, as much as some 20 reads from the tables) the first time it reads one of them, and
//! keeps the last [`CACHED_BLOCKS`] blocks so: a slot read is then one word, after a look at
//! a small array of tags. Each operator still reads a bounded number of words (the blocks it
//! decodes on top of the tables' reads), so it stays constant time on the loaded bytes, and
//! on a valid file it answers exactly as the tables do (on a file that is only well formed,
//! both answer in range).

use super::tables::ZipperTables;
use super::{BLOCK_SHIFT, BLOCK_SLOTS};
use crate::lr::tables::{LrLayout, IRREGULAR, NULL, RIGHT, VALUE, WART};
use crate::words::Words;
use std::cell::Cell;

/// Blocks kept decoded, direct-mapped by the block's low bits: 512 blocks of 64 ring
/// vertices (256 KiB of words, allocated with the cursor) hold the ring rows a fan or a walk
/// comes back to on the scanned meshes (256 decoded a third more blocks in bunny00's valence
/// loop, evicted and read again).
pub const CACHED_BLOCKS: usize = 512;

/// The words of the blocks kept decoded, entry after entry.
const CACHED_SLOTS: usize = CACHED_BLOCKS * BLOCK_SLOTS;

/// The operators of a [`ZipperTables`] (through [`LrLayout`], hence
/// [`CornerOps`](crate::ops::CornerOps)) with the slots of recently read blocks kept
/// decoded; see the module documentation. Its answers are the tables' own. A cursor keeps
/// its cache in cells, so it is not `Sync`: make one per thread (`ZipperTables::cursor`).
#[derive(Debug)]
pub struct ZipperCursor<'a, W: Words> {
    tables: &'a ZipperTables<W>,
    /// The tables' `m_r` and number of rings, which every ring step asks for: kept here,
    /// where the compiler sees that no decoding changes them.
    m_r: u32,
    rings: usize,
    /// The block each entry holds decoded, `usize::MAX` for none: apart from the words, so
    /// that the check before every read looks at a small array that stays in the L1 cache
    /// (next to the words, it took a second cache line per read).
    tags: Box<[Cell<usize>; CACHED_BLOCKS]>,
    /// Each entry's block decoded: each slot's word as the standard LR stores it (the tip,
    /// with the `WART` and `IRREGULAR` flags), so that a read is one word. Slot `(v, side)`
    /// of a block held is at `2v + side` modulo the array's length.
    words: Box<[Cell<u32>; CACHED_SLOTS]>,
}

impl<W: Words> ZipperTables<W> {
    /// A cursor over these tables (see [`ZipperCursor`]).
    pub fn cursor(&self) -> ZipperCursor<'_, W> {
        ZipperCursor {
            tables: self,
            m_r: self.ring_vertices(),
            rings: self.ring_count(),
            tags: boxed(|| Cell::new(usize::MAX)),
            words: boxed(|| Cell::new(0)),
        }
    }
}

/// An array of `N` values made by `f`, built on the heap.
fn boxed<T, const N: usize>(f: impl FnMut() -> T) -> Box<[T; N]> {
    let all: Box<[T]> = std::iter::repeat_with(f).take(N).collect();
    match all.try_into() {
        Ok(array) => array,
        Err(_) => unreachable!("N values taken"),
    }
}

impl<W: Words> ZipperCursor<'_, W> {
    /// The tables read.
    pub fn tables(&self) -> &ZipperTables<W> {
        self.tables
    }

    /// Forgets every block decoded, as a new cursor: so that a benchmark that runs a loop
    /// several times times each run from an empty cache, as a single loop runs (the blocks
    /// a run leaves decoded would otherwise answer the next run's first reads).
    pub fn clear(&self) {
        for tag in self.tags.iter() {
            tag.set(usize::MAX);
        }
    }

    /// The word of slot `(v, side)` (its tip with the `WART` and `IRREGULAR` flags) from its
    /// block decoded in the cache, decoding the block first if its entry holds another;
    /// `None` for a slot of a block that is not whole (of 64 ring vertices all below `m_r`),
    /// whose fields the caller reads from the tables as they read them alone: a vertex past
    /// the ring (which only a file that is not semantically valid asks for) and the ring's
    /// last block when partial never have a word, so that a read finds one by its block's
    /// tag alone.
    #[inline(always)]
    fn cached(&self, v: u32, side: usize) -> Option<u32> {
        let block = (v >> BLOCK_SHIFT) as usize;
        let entry = block % CACHED_BLOCKS;
        if self.tags[entry].get() != block {
            if block >= (self.m_r >> BLOCK_SHIFT) as usize {
                return None;
            }
            self.decode(block, entry);
        }
        Some(self.words[(2 * v as usize + side) % CACHED_SLOTS].get())
    }

    /// Decodes whole block `block` into cache entry `entry`. Out of line: the reads that
    /// find their block held stay short.
    #[inline(never)]
    fn decode(&self, block: usize, entry: usize) {
        self.tags[entry].set(block);
        let mut words = [0; BLOCK_SLOTS];
        self.tables.decode_block(block, &mut words);
        let held = &self.words[entry * BLOCK_SLOTS..(entry + 1) * BLOCK_SLOTS];
        for (cell, word) in held.iter().zip(words) {
            cell.set(word);
        }
    }
}

impl<W: Words> LrLayout for ZipperCursor<'_, W> {
    #[inline]
    fn ring_vertices(&self) -> u32 {
        self.m_r
    }
    #[inline]
    fn vertex_count(&self) -> u32 {
        self.tables.vertex_count()
    }
    #[inline]
    fn t0_count(&self) -> u32 {
        self.tables.t0_count()
    }
    #[inline]
    fn ring_count(&self) -> usize {
        self.rings
    }
    #[inline]
    fn ring_start(&self, ring: usize) -> u32 {
        self.tables.ring_start(ring)
    }
    #[inline(always)]
    fn is_last(&self, v: u32) -> bool {
        self.tables.is_last(v)
    }
    #[inline(always)]
    fn ring_of(&self, v: u32) -> usize {
        self.tables.ring_of(v)
    }
    #[inline]
    fn ring_last_word(&self, i: usize) -> u32 {
        self.tables.ring_last_word(i)
    }
    #[inline]
    fn ring_rank_word(&self, i: usize) -> u32 {
        self.tables.ring_rank_word(i)
    }
    #[inline(always)]
    fn tip(&self, v: u32, side: usize) -> u32 {
        match self.cached(v, side) {
            Some(word) => word & VALUE,
            None => self.tables.tip(v, side),
        }
    }
    #[inline(always)]
    fn wart(&self, v: u32, side: usize) -> bool {
        match self.cached(v, side) {
            Some(word) => word & WART != 0,
            None => self.tables.wart(v, side),
        }
    }
    #[inline(always)]
    fn irregular(&self, v: u32, side: usize) -> bool {
        match self.cached(v, side) {
            Some(word) => word & IRREGULAR != 0,
            None => self.tables.irregular(v, side),
        }
    }
    #[inline(always)]
    fn tip_and_wart(&self, v: u32, side: usize) -> (u32, bool) {
        match self.cached(v, side) {
            Some(word) => (word & VALUE, word & WART != 0),
            None => self.tables.tip_and_wart(v, side),
        }
    }
    #[inline(always)]
    fn slot_fields(&self, v: u32, side: usize) -> (u32, bool, bool) {
        match self.cached(v, side) {
            Some(word) => (word & VALUE, word & WART != 0, word & IRREGULAR != 0),
            None => self.tables.slot_fields(v, side),
        }
    }
    #[inline(always)]
    fn redundant_given(&self, v: u32, side: usize, tip: u32) -> bool {
        // Both flags from one word.
        tip == self.ring_next_next(v)
            && match self.cached(v, side) {
                Some(word) => word & (WART | IRREGULAR) == 0,
                None => self.tables.redundant_given(v, side, tip),
            }
    }
    #[inline(always)]
    fn right_is_null(&self, v: u32) -> bool {
        match self.cached(v, RIGHT) {
            Some(word) => word & VALUE == NULL,
            None => self.tables.right_is_null(v),
        }
    }
    #[inline(always)]
    fn stored_opposite(&self, v: u32, side: usize, second: usize) -> Option<u32> {
        match self.cached(v, side) {
            Some(word) if word & IRREGULAR == 0 => None,
            _ => self.tables.stored_opposite(v, side, second),
        }
    }
    #[inline]
    fn t0_vertex(&self, k: u32) -> u32 {
        self.tables.t0_vertex(k)
    }
    #[inline]
    fn t0_opposite(&self, k: u32) -> u32 {
        self.tables.t0_opposite_in(self, k)
    }
    #[inline]
    fn isolated_corner(&self, i: u32) -> u32 {
        self.tables.isolated_corner(i)
    }
    #[inline]
    fn boundaries_on_ring(&self) -> bool {
        self.tables.boundaries_on_ring()
    }
}
