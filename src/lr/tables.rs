//! The LR tables and the corner operators on them, written once for any storage: owned
//! vectors (after construction) or little-endian bytes of a container (zero-copy view).

use crate::corner_table::NONE;
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;
use crate::words::Words;

use super::open_fans::OpenFans;

/// Entry flag: the slot's triangle has a VO* record; the entry's value is the record index.
pub const IRREGULAR: u32 = 1 << 31;
/// Entry flag: the slot holds a T0 triangle in a wart's redundant slot; its far vertex is
/// `v.n.n`.
pub const WART: u32 = 1 << 30;
/// The value bits of an entry: a vertex id, [`NULL`], or a VO* record index.
pub const VALUE: u32 = WART - 1;
/// The tip of a right triangle that does not exist (a boundary ring edge).
pub const NULL: u32 = VALUE;

/// Left or right side of a ring edge: the offset of its slot in the LR table.
pub(crate) const LEFT: usize = 0;
pub(crate) const RIGHT: usize = 1;

/// The standard LR tables (see the module documentation of [`crate::lr`]).
///
/// Rings are ranges of consecutive vertex ids. `ring_starts` holds each ring's first vertex
/// and `m_r` at the end; `ring_last` has bit `v` set when `v` ends its ring, and `ring_rank`
/// counts the set bits before each 32-bit word, so that the ring of `v` (and so `v.n` at a
/// ring's end) is found in constant time.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LrTables<W> {
    /// `L[v], R[v]` interleaved: entry `2v + side`.
    pub(crate) lr: W,
    /// VO: vertices of T0 triangles, three each.
    pub(crate) vo_v: W,
    /// VO: opposites of T0 corners, three each (`NONE` on a boundary).
    pub(crate) vo_o: W,
    /// VO*: records `(tip, o_a, o_b)`.
    pub(crate) vo_star: W,
    /// C: a corner of each isolated vertex (`NONE` for a vertex without triangles).
    pub(crate) c: W,
    pub(crate) ring_starts: W,
    pub(crate) ring_last: W,
    pub(crate) ring_rank: W,
    /// Ring vertices.
    pub(crate) m_r: u32,
    /// All vertices.
    pub(crate) m: u32,
    /// Whether every boundary edge is a ring edge whose right slot has tip `NULL` (derived,
    /// not stored: see [`LrLayout::boundaries_on_ring`]).
    pub(crate) boundaries_on_ring: bool,
    /// The ring vertices whose open fan `v.c` looks up (`OPEN_FANS`), if listed.
    pub(crate) open_fans: Option<OpenFans<W>>,
}

/// Whether every corner of `tables` without an opposite (`without_opposite` of them, counted
/// by the caller: the builder from its corner table, a reader while validating every
/// opposite) is the tip corner of a left slot whose right slot has tip `NULL`
/// (see [`LrLayout::boundaries_on_ring`]).
pub(crate) fn boundaries_on_ring_given<T: LrLayout>(tables: &T, without_opposite: usize) -> bool {
    let null_right = (0..tables.ring_vertices())
        .filter(|&v| tables.tip(v, RIGHT) == NULL)
        .count();
    null_right == without_opposite
}

/// [`LrLayout::is_last`] from the ring-end bit vector.
#[inline(always)]
pub(crate) fn is_last_by_bits<T: LrLayout + ?Sized>(t: &T, v: u32) -> bool {
    t.ring_last_word(v as usize / 32) >> (v % 32) & 1 != 0
}

/// [`LrLayout::ring_of`] from the ring-end bit vector and its ranks.
#[inline(always)]
pub(crate) fn ring_of_by_bits<T: LrLayout + ?Sized>(t: &T, v: u32) -> usize {
    let k = v as usize / 32;
    rank_of_bit(t.ring_last_word(k), t.ring_rank_word(k), v) as usize
}

/// The number of set bits before bit `i` of a bit vector whose word `⌊i/32⌋` is `word` and
/// has `rank` set bits before it (the ring-end bits, the open fans' bits).
#[inline(always)]
pub(crate) fn rank_of_bit(word: u32, rank: u32, i: u32) -> u32 {
    rank + (word & ((1u32 << (i % 32)) - 1)).count_ones()
}

/// `v.n.n` for ring vertex `v` when the ring is the only one, of `m_r` vertices (at least 4,
/// as every ring): `v + 2`, wrapped without a branch (the passes over every slot stay
/// vectorizable).
#[inline(always)]
pub(crate) fn one_ring_next_next(v: u32, m_r: u32) -> u32 {
    (v + 2) - m_r * (v + 2 >= m_r) as u32
}

/// Ring bit vector and ranks for rings starting at `starts` (which ends with `m_r`).
pub(crate) fn ring_bits(starts: &[u32]) -> (Vec<u32>, Vec<u32>) {
    let m_r = *starts.last().unwrap_or(&0) as usize;
    bits_and_ranks(m_r, starts.windows(2).map(|w| w[1] as usize - 1))
}

/// A bit vector of `len` bits, 32 to a word, with the bits `set` (each below `len`), and per
/// word the number of bits set in the words before it.
pub(crate) fn bits_and_ranks(
    len: usize,
    set: impl IntoIterator<Item = usize>,
) -> (Vec<u32>, Vec<u32>) {
    let mut bits = vec![0u32; len.div_ceil(32)];
    for i in set {
        bits[i / 32] |= 1 << (i % 32);
    }
    let mut rank = Vec::with_capacity(bits.len());
    let mut count = 0;
    for word in &bits {
        rank.push(count);
        count += word.count_ones();
    }
    (bits, rank)
}

impl<W: Words> LrTables<W> {
    /// Number of VO* records.
    pub fn record_count(&self) -> u32 {
        (self.vo_star.count() / 3) as u32
    }

    /// Storage in 32-bit references: LR, VO, VO* and C (the rpt numerator).
    pub fn references(&self) -> u64 {
        (self.lr.count()
            + self.vo_v.count()
            + self.vo_o.count()
            + self.vo_star.count()
            + self.c.count()) as u64
    }

    #[inline(always)]
    pub(crate) fn entry(&self, v: u32, side: usize) -> u32 {
        self.lr.at(2 * v as usize + side)
    }
}

impl<W: Words> LrLayout for LrTables<W> {
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
        (self.vo_v.count() / 3) as u32
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
        let e = self.entry(v, side);
        if e & IRREGULAR != 0 {
            self.vo_star.at(3 * (e & VALUE) as usize)
        } else {
            e & VALUE
        }
    }
    #[inline(always)]
    fn wart(&self, v: u32, side: usize) -> bool {
        self.entry(v, side) & WART != 0
    }
    #[inline(always)]
    fn irregular(&self, v: u32, side: usize) -> bool {
        self.entry(v, side) & IRREGULAR != 0
    }
    #[inline(always)]
    fn stored_opposite(&self, v: u32, side: usize, second: usize) -> Option<u32> {
        let e = self.entry(v, side);
        (e & IRREGULAR != 0).then(|| self.vo_star.at(3 * (e & VALUE) as usize + 1 + second))
    }
    #[inline(always)]
    fn t0_vertex(&self, k: u32) -> u32 {
        self.vo_v.at(k as usize)
    }
    #[inline(always)]
    fn t0_opposite(&self, k: u32) -> u32 {
        self.vo_o.at(k as usize)
    }
    #[inline(always)]
    fn boundaries_on_ring(&self) -> bool {
        self.boundaries_on_ring
    }
    #[inline(always)]
    fn open_fans_listed(&self) -> bool {
        self.open_fans.is_some()
    }
    #[inline(always)]
    fn listed_fan_start(&self, v: u32) -> Option<u32> {
        self.open_fans.as_ref().and_then(|f| f.start(v))
    }
    fn listed_fans(&self) -> Option<Vec<(u32, u32)>> {
        self.open_fans.as_ref().map(|f| f.iter().collect())
    }

    #[inline(always)]
    fn isolated_corner(&self, i: u32) -> u32 {
        self.c.at(i as usize)
    }
}

/// What an encoding of the LR tables answers: the rings, what each slot holds, the T0 rows
/// and C. The operators are written once, as provided methods on top of these, so that the
/// standard tables ([`LrTables`]) and the bit-efficient ones
/// ([`CompactTables`](super::CompactTables)) share them; every layout implements
/// [`CornerOps`] through them.
///
/// Slot `(v, side)` is the left (`side = 0`) or right (`side = 1`) triangle of ring edge
/// `(v, v.n)`; `spec/OPERATORS.md` defines the terms.
pub trait LrLayout {
    /// Number of ring vertices `m_r`.
    fn ring_vertices(&self) -> u32;
    /// Number of vertices `m`, isolated ones included.
    fn vertex_count(&self) -> u32;
    /// Number of T0 triangles stored as rows.
    fn t0_count(&self) -> u32;
    /// Number of rings.
    fn ring_count(&self) -> usize;
    /// First vertex of ring `ring`; `ring_start(ring_count())` is `m_r`.
    fn ring_start(&self, ring: usize) -> u32;
    /// Word `i` of the ring-end bit vector (read only with several rings).
    fn ring_last_word(&self, i: usize) -> u32;
    /// Set bits of the ring-end bit vector before word `i` (read only with several rings).
    fn ring_rank_word(&self, i: usize) -> u32;
    /// The tip vertex of slot `(v, side)`, or [`NULL`] for a right triangle that does not
    /// exist.
    fn tip(&self, v: u32, side: usize) -> u32;
    /// Whether slot `(v, side)` holds a T0 in a wart's redundant slot (its far vertex is
    /// `v.n.n`).
    fn wart(&self, v: u32, side: usize) -> bool;
    /// Whether slot `(v, side)` stores the opposite of a transversal corner (which also
    /// makes it canonical, whatever its tip).
    fn irregular(&self, v: u32, side: usize) -> bool;
    /// [`tip`](Self::tip) and [`wart`](Self::wart) of slot `(v, side)` together: a layout
    /// that decodes a slot's fields (the Zipper) reads them once.
    #[inline(always)]
    fn tip_and_wart(&self, v: u32, side: usize) -> (u32, bool) {
        (self.tip(v, side), self.wart(v, side))
    }
    /// [`tip`](Self::tip), [`wart`](Self::wart) and [`irregular`](Self::irregular) of slot
    /// `(v, side)` together: a layout that decodes a slot's word (the Zipper's cursor) reads
    /// it once.
    #[inline(always)]
    fn slot_fields(&self, v: u32, side: usize) -> (u32, bool, bool) {
        let (tip, wart) = self.tip_and_wart(v, side);
        (tip, wart, self.irregular(v, side))
    }
    /// Whether the tip of right slot `v` is [`NULL`] (no right triangle: a boundary ring
    /// edge): a layout whose tips take decoding (the Zipper) tells it from less.
    #[inline(always)]
    fn right_is_null(&self, v: u32) -> bool {
        self.tip(v, RIGHT) == NULL
    }
    /// The stored opposite, if any, of a transversal corner of slot `(v, side)`: of its
    /// first (`8v` or `8v+4`) for `second = 0`, of its second (`8v+2` or `8v+6`) for
    /// `second = 1`.
    fn stored_opposite(&self, v: u32, side: usize, second: usize) -> Option<u32>;
    /// Vertex of T0 corner row `k` (`3j + i` for corner `i` of T0 triangle `j`).
    fn t0_vertex(&self, k: u32) -> u32;
    /// Opposite of T0 corner row `k`, `NONE` on a boundary.
    fn t0_opposite(&self, k: u32) -> u32;
    /// The corner of isolated vertex `m_r + i`, `NONE` for a vertex without triangles.
    fn isolated_corner(&self, i: u32) -> u32;
    /// Whether every corner without an opposite is the tip corner of a left slot whose
    /// right slot has tip `NULL`: the mesh's boundaries all run along the ring, so that
    /// `v.c` finds a fan's start in constant time (OPERATORS.md §4). Derived from the
    /// tables when they are built or validated, never stored.
    fn boundaries_on_ring(&self) -> bool;
    /// Whether the tables list the open fans (`OPEN_FANS`, FORMAT.md §3.5.1): every ring
    /// vertex whose fan is open, but those after a boundary ring edge, with its fan's first
    /// corner, so that `v.c` never walks a fan.
    #[inline(always)]
    fn open_fans_listed(&self) -> bool {
        false
    }
    /// The first corner listed for ring vertex `v` (with [`open_fans_listed`](Self::open_fans_listed)).
    #[inline(always)]
    fn listed_fan_start(&self, _v: u32) -> Option<u32> {
        None
    }
    /// The listed `(vertex, first corner)` pairs in order, `None` without the list.
    fn listed_fans(&self) -> Option<Vec<(u32, u32)>> {
        None
    }

    /// Whether `v` ends its ring (by default from the ring-end bits).
    #[inline(always)]
    fn is_last(&self, v: u32) -> bool {
        is_last_by_bits(self, v)
    }

    /// Index of the ring that holds `v`: the number of ring ends before `v` (by default from
    /// the ring-end bits and ranks).
    #[inline(always)]
    fn ring_of(&self, v: u32) -> usize {
        ring_of_by_bits(self, v)
    }

    /// `v.n`: the next vertex along `v`'s ring.
    #[inline(always)]
    fn ring_next(&self, v: u32) -> u32 {
        if self.ring_count() == 1 {
            // One ring, the common case: no bit vector to consult.
            return if v + 1 == self.ring_vertices() {
                0
            } else {
                v + 1
            };
        }
        if self.is_last(v) {
            self.first_of_ring(v)
        } else {
            v + 1
        }
    }

    /// The first vertex of `v`'s ring. Out of line, as is [`last_of_ring`](Self::last_of_ring):
    /// only a ring's end needs its rank, and every operator inlines the ring steps several
    /// times over.
    #[inline(never)]
    fn first_of_ring(&self, v: u32) -> u32 {
        self.ring_start(self.ring_of(v))
    }

    /// The last vertex of `v`'s ring.
    #[inline(never)]
    fn last_of_ring(&self, v: u32) -> u32 {
        self.ring_start(self.ring_of(v) + 1) - 1
    }

    /// `v.p`: the previous vertex along `v`'s ring.
    #[inline(always)]
    fn ring_prev(&self, v: u32) -> u32 {
        if self.ring_count() == 1 {
            return if v == 0 {
                self.ring_vertices() - 1
            } else {
                v - 1
            };
        }
        if v == 0 || self.is_last(v - 1) {
            self.last_of_ring(v)
        } else {
            v - 1
        }
    }

    /// `v.n.n` of ring vertex `v`: with one ring, `v + 2` wrapped without a branch (every
    /// canonical check compares a tip with it).
    #[inline(always)]
    fn ring_next_next(&self, v: u32) -> u32 {
        if self.ring_count() == 1 {
            return one_ring_next_next(v, self.ring_vertices());
        }
        self.ring_next(self.ring_next(v))
    }

    /// The slot's third vertex: `v.n`, or `v.n.n` in a wart slot (the skipped ring).
    #[inline(always)]
    fn far(&self, v: u32, side: usize) -> u32 {
        self.far_given(v, self.wart(v, side))
    }

    /// [`far`](Self::far) of a slot of `v` whose WART flag is known (the operators below
    /// pass what they have read, so that a layout that decodes a slot's fields, like the
    /// Zipper, does it once).
    #[inline(always)]
    fn far_given(&self, v: u32, wart: bool) -> u32 {
        if wart {
            self.ring_next_next(v)
        } else {
            self.ring_next(v)
        }
    }

    /// Whether slot `(v, side)` is the redundant copy of a T2 (its first ring edge).
    #[inline(always)]
    fn redundant(&self, v: u32, side: usize) -> bool {
        self.redundant_given(v, side, self.tip(v, side))
    }

    /// [`redundant`](Self::redundant) for a slot whose tip is known.
    #[inline(always)]
    fn redundant_given(&self, v: u32, side: usize, tip: u32) -> bool {
        tip == self.ring_next_next(v) && !self.irregular(v, side) && !self.wart(v, side)
    }

    /// Maps a corner of a redundant T2 copy to the same corner of the canonical slot.
    #[inline(always)]
    fn canonical(&self, c: u32) -> u32 {
        if c >= 8 * self.ring_vertices() {
            return c;
        }
        self.canonical_given(c, self.tip(c >> 3, (c >> 2 & 1) as usize))
    }

    /// [`canonical`](Self::canonical) of a slot corner `c` (below `8 m_r`) whose slot's tip
    /// is known.
    #[inline(always)]
    fn canonical_given(&self, c: u32, tip: u32) -> u32 {
        let (v, i) = (c >> 3, c & 7);
        let side = (i >> 2) as usize;
        if !self.redundant_given(v, side, tip) {
            return c;
        }
        let w = self.ring_next(v);
        let j = if side == LEFT {
            (i + 1) % 3
        } else {
            4 + (i - 4 + 2) % 3
        };
        8 * w + j
    }

    /// The corner on the other side of ring edge `(v, v.n)` from `side`, facing it.
    #[inline(always)]
    fn across(&self, v: u32, side: usize) -> u32 {
        if side == LEFT {
            if self.wart(v, RIGHT) {
                return 8 * self.ring_next(v) + 4;
            }
            match self.tip(v, RIGHT) {
                NULL => NONE,
                tip => self.canonical_given(8 * v + 5, tip),
            }
        } else if self.wart(v, LEFT) {
            8 * self.ring_next(v) + 2
        } else {
            self.canonical(8 * v + 1)
        }
    }

    /// A triangle of side `side` holding the half-edge `b -> a` (left) or `a -> b` (right):
    /// the corner facing that half-edge, or `NONE`. Such a triangle is the slot of `b` with
    /// tip `a`, or the slot of `a.p` (or of `a.p.p`, a wart's) with tip `b`; the two sides'
    /// rules mirror each other, so that one body serves both with the side as a value
    /// rather than a branch.
    #[inline(always)]
    fn find(&self, side: usize, a: u32, b: u32) -> u32 {
        let m_r = self.ring_vertices();
        // Corner of the tip's slot facing the edge, and of a slot of `a.p`'s.
        let (at_b, at_p) = (2 + 2 * side as u32, 6 * side as u32);
        if b < m_r && self.tip(b, side) == a {
            return self.canonical_given(8 * b + at_b, a);
        }
        if a < m_r {
            let p = self.ring_prev(a);
            if self.tip_and_wart(p, side) == (b, false) {
                return self.canonical_given(8 * p + at_p, b);
            }
            let pp = self.ring_prev(p);
            if self.wart(pp, side) && self.tip(pp, side) == b {
                return self.canonical_given(8 * pp + at_p, b);
            }
        }
        NONE
    }

    /// A left triangle holding half-edge `y -> x` (facing an edge `x -> y` of a left
    /// triangle): the corner facing it, or `NONE`.
    #[inline(always)]
    fn find_left(&self, x: u32, y: u32) -> u32 {
        self.find(LEFT, x, y)
    }

    /// A right triangle holding half-edge `y -> x`: the corner facing it, or `NONE`.
    #[inline(always)]
    fn find_right(&self, x: u32, y: u32) -> u32 {
        self.find(RIGHT, y, x)
    }

    /// `c.o` for a canonical corner, as a raw id (`NONE` on a boundary). Written with the
    /// corner's side and position as values, not a `match` on them: a jump table there is
    /// an indirect branch that a walk around a vertex mispredicts at most steps.
    #[inline(always)]
    fn opposite_raw(&self, c: u32) -> u32 {
        let m_r = self.ring_vertices();
        if c >= 8 * m_r {
            return self.t0_opposite(c - c / 4 - 6 * m_r);
        }
        let v = c >> 3;
        let side = (c >> 2 & 1) as usize;
        if c & 3 == 1 {
            // The corner facing the ring edge (or, in a wart slot, the wart's edge).
            return if self.wart(v, side) {
                8 * self.ring_next(v) + 6 * side as u32
            } else {
                self.across(v, side)
            };
        }
        // The slot's fields read once; only an irregular slot stores opposites.
        let (tip, wart, irregular) = self.slot_fields(v, side);
        if irregular {
            if let Some(o) = self.stored_opposite(v, side, (c >> 1 & 1) as usize) {
                return o;
            }
        }
        self.inferred_opposite_given(v, c & 7, tip, wart)
    }

    /// `c.o` of transversal corner `8v + i` (`i` in 0, 2, 4, 6) by the ring rules alone
    /// (OPERATORS.md §4), without the slot's stored opposites.
    #[inline(always)]
    fn inferred_opposite(&self, v: u32, i: u32) -> u32 {
        let (tip, wart) = self.tip_and_wart(v, (i >> 2) as usize);
        self.inferred_opposite_given(v, i, tip, wart)
    }

    /// [`inferred_opposite`](Self::inferred_opposite) for a slot whose tip and WART flag
    /// are known. Corners 0 and 6 face the edge from the tip to the slot's far vertex,
    /// corners 2 and 4 the edge from `v` to the tip (`outer`: the slot's side and the
    /// corner's position in it differ).
    #[inline(always)]
    fn inferred_opposite_given(&self, v: u32, i: u32, tip: u32, wart: bool) -> u32 {
        let side = (i >> 2) as usize;
        let outer = (i >> 1 ^ i >> 2) & 1 == 0;
        let p = self.ring_prev(v);
        // A canonical T2 (v.p, v, v.n): tip v.p; one of its corners faces ring edge (v.p, v).
        let t2 = !wart && tip == p;
        if outer {
            if t2 && self.wart(p, side) {
                return 8 * p + 1 + 4 * side as u32;
            }
            self.find(side, tip, self.far_given(v, wart))
        } else if t2 {
            self.across(p, side)
        } else {
            self.find(side, v, tip)
        }
    }

    /// Whether slot `(v, side)` holds a canonical triangle: it exists (a right slot may be a
    /// boundary's `NULL`) and is not a redundant T2 copy.
    #[inline(always)]
    fn slot_is_triangle(&self, v: u32, side: usize) -> bool {
        let tip = self.tip(v, side);
        tip != NULL && !self.redundant_given(v, side, tip)
    }

    /// Whether `t` is a canonical triangle id (not a redundant copy, unused or a missing right
    /// triangle).
    #[inline]
    fn is_triangle(&self, t: Triangle) -> bool {
        let (t, m_r) = (t.0, self.ring_vertices());
        if t >= 2 * m_r {
            return t - 2 * m_r < self.t0_count();
        }
        self.slot_is_triangle(t / 2, (t % 2) as usize)
    }

    /// Whether `c` is a corner of a canonical triangle.
    #[inline]
    fn is_corner(&self, c: Corner) -> bool {
        c.0 & 3 != 3 && self.is_triangle(Triangle(c.0 >> 2))
    }
}

/// The corner operators of every LR layout.
impl<T: LrLayout> CornerOps for T {
    fn vertex_id_bound(&self) -> u32 {
        self.vertex_count()
    }

    fn triangle_id_bound(&self) -> u32 {
        2 * self.ring_vertices() + self.t0_count()
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.triangle_id_bound())
            .map(Triangle)
            .filter(|&t| self.is_triangle(t))
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        (0..self.vertex_count()).map(Vertex)
    }

    #[inline(always)]
    fn vertex(&self, c: Corner) -> Vertex {
        let (c, m_r) = (c.0, self.ring_vertices());
        if c >= 8 * m_r {
            return Vertex(self.t0_vertex(c - c / 4 - 6 * m_r));
        }
        // Corners 1 and 5 are the tips, 0 and 6 the slot's vertex, 2 and 4 its far vertex:
        // tested as values, not a `match` (a jump table, mispredicted along a walk).
        let (v, side, k) = (c >> 3, (c >> 2 & 1) as usize, c & 3);
        Vertex(if k == 1 {
            self.tip(v, side)
        } else if k == 2 * side as u32 {
            v
        } else {
            self.far(v, side)
        })
    }

    #[inline(always)]
    fn triangle(&self, c: Corner) -> Triangle {
        Triangle(c.0 >> 2)
    }

    #[inline(always)]
    fn next(&self, c: Corner) -> Corner {
        // Without a branch (the walks around a vertex take a next at every step): corners
        // `4t + k`, `k` in 0..3, bit 1 set only on the last.
        Corner(c.0 + 1 - 3 * (c.0 >> 1 & 1))
    }

    #[inline(always)]
    fn prev(&self, c: Corner) -> Corner {
        Corner(c.0 + 3 * (c.0 & 3 == 0) as u32 - 1)
    }

    #[inline(always)]
    fn opposite(&self, c: Corner) -> Option<Corner> {
        Corner::from_stored(self.opposite_raw(c.0))
    }

    #[inline(always)]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        let m_r = self.ring_vertices();
        if v.0 >= m_r {
            return Corner::from_stored(self.isolated_corner(v.0 - m_r));
        }
        // The fan's first corner (OPERATORS.md §4.2): after a boundary ring edge (u, v) it is
        // v's corner in u's left triangle; the list of open fans has every other open fan's;
        // without the list, with every boundary on the ring, any other ring vertex has a
        // closed fan; otherwise the fan is walked back to its start.
        let u = self.ring_prev(v.0);
        let boundary_before = self.right_is_null(u);
        if boundary_before && !self.wart(u, LEFT) {
            return Some(Corner(self.canonical(8 * u + 2)));
        }
        let c = Corner(self.canonical(8 * v.0));
        if self.open_fans_listed() {
            return Some(self.listed_fan_start(v.0).map_or(c, Corner));
        }
        if self.boundaries_on_ring() && !boundary_before {
            return Some(c);
        }
        Some(crate::ops::fan_start(self, c))
    }

    /// Corner 0 of `v`'s left slot (made canonical), which every ring vertex has: no look at
    /// boundaries or walk back to an open fan's start, as `v.c` needs.
    #[inline(always)]
    fn any_corner(&self, v: Vertex) -> Option<Corner> {
        let m_r = self.ring_vertices();
        if v.0 >= m_r {
            return Corner::from_stored(self.isolated_corner(v.0 - m_r));
        }
        Some(Corner(self.canonical(8 * v.0)))
    }

    #[inline(always)]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        Corner(4 * t.0)
    }
}
