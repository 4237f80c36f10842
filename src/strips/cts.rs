//! Constrained triangle strips (CTS) and the adjacent-strips table `A` of Annaka, Matsuoka and
//! Miyazawa, "Memory Efficient Adjacent Triangle Connectivity of a Face Using Triangle Strips"
//! (WSCG 2005), with the corner operators.
//!
//! # Layout
//!
//! * `T`: the strips of the corner table's triangles one after the other, each followed by one
//!   [`DELIMITER`] when its length is odd and two when it is even, so that every strip starts
//!   at an even position. The triangle at position `j` is `(T[j], T[j+1], T[j+2])`, oriented
//!   as written when `j` is even and as `(T[j+1], T[j], T[j+2])` when `j` is odd: the parity
//!   of a triangle gives its orientation, and any triangle is reached in constant time from
//!   its position. Lone triangles are strips of three. *Extension:* a strip may contain swaps
//!   (`p, q, p`: a zero-area triangle); a position whose three entries repeat an index holds no
//!   triangle.
//! * `A`, as long as `T`: for the triangle at `j`, `A[j+1]` is the position of the triangle
//!   across its edge `{T[j], T[j+2]}` (the edge no strip neighbour shares), `A[j]` the one
//!   across `{T[j], T[j+1]}` when `j` starts its strip, and `A[j+2]` the one across
//!   `{T[j+1], T[j+2]}` when it ends it; [`DELIMITER`] across a boundary or cut edge. The
//!   other two neighbours are `j - 1` and `j + 1` in the strip, or `j - 2` and `j + 2` across a
//!   swap.
//! * `C`: one corner per vertex. *Addition:* the paper has no vertex-to-triangle map; the
//!   operator `v.c` needs one. It is not counted in [`Cts::bits_per_triangle`].
//!
//! The tables and the operators on them are [`CtsTables`], generic over their storage
//! ([`Words`]): owned vectors in a [`Cts`], or the little-endian bytes of a container's `STRP`
//! section read in place (`spec/FORMAT.md`), with one implementation of the operators.
//!
//! # Ids
//!
//! Triangle `j` is the triangle at position `j` of `T` (ids have gaps: delimiters and swaps);
//! corner `3j + i` is its `i`-th corner in its orientation; vertices are the corner table's
//! (input vertices, then pseudo-manifold copies).
//!
//! # Operators
//!
//! All of [`CornerOps`] in constant time: `c.v`, `c.t`, `c.n`, `c.p` from the position and its
//! parity, `c.o` from the strip neighbours or `A` (the paper stores triangle positions; the
//! corner within the neighbour is the one off the shared edge, found among its three), `v.c`
//! from `C`. What the paper's structure alone cannot give, without `C`, is `v.c`; and, like
//! the paper, it describes the pseudo-manifold of the [`CornerTable`]: non-manifold edges are
//! cut and non-manifold vertices split into copies, and degenerate triangles are not part of it.

use super::adjacency::Adjacency;
use super::{stripify_adjacency, StripOptions, RESTART};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;
use crate::words::Words;

/// Separates strips in `T`; marks "no neighbour" in `A`.
pub const DELIMITER: u32 = u32::MAX;

/// Corner `i` of the triangle at an even (`[0]`) or odd (`[1]`) position is at this offset in
/// `T` (the permutation is its own inverse).
const OFFSET: [[usize; 3]; 2] = [[0, 1, 2], [1, 0, 2]];

/// `T`, `A` and `C` and the corner operators on them, for any storage of the words (see the
/// module documentation). Built by [`Cts::build`], or read in place from a container.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CtsTables<W> {
    /// The strips, separated by [`DELIMITER`]s.
    pub(crate) t: W,
    /// The adjacent-strips table, as long as `t`.
    pub(crate) a: W,
    /// A corner of each vertex (`NONE` for a vertex without triangles).
    pub(crate) c: W,
    /// Number of triangles in `t`.
    pub(crate) triangles: u32,
}

/// Constrained triangle strips with the adjacent-strips table (see the module documentation),
/// owned, with the way back to the input's triangles and vertices.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cts {
    tables: CtsTables<Vec<u32>>,
    /// Position -> input triangle (`NONE` where no triangle starts).
    input_triangle: Vec<u32>,
    /// Vertex -> input vertex.
    input_vertex: Vec<u32>,
    /// Degenerate input triangles the corner table kept aside.
    kept_aside: Vec<(u32, [u32; 3])>,
}

impl Cts {
    /// Strips the corner table's triangles with `options` (fans are not used) and builds `T`,
    /// `A` and `C`.
    ///
    /// # Errors
    /// [`Error::Unsupported`] when the corner ids `3j + i` would not fit 32 bits.
    pub fn build(table: &CornerTable, options: &StripOptions) -> Result<Cts> {
        let mut adj = Adjacency::from_corner_table(table);
        let options = StripOptions {
            fan_threshold: 0,
            ..*options
        };
        let strips = stripify_adjacency(&mut adj, &options);
        let n = adj.triangle_count();
        let mut t = Vec::with_capacity(strips.strips.len() + 2 * strips.list.len());
        let mut at = Vec::with_capacity(t.capacity());
        let mut order = strips.strip_order.iter().copied();
        let mut push_strip = |seq: &[u32], order: &mut dyn Iterator<Item = u32>| {
            for w in seq.windows(3) {
                let real = w[0] != w[1] && w[1] != w[2] && w[0] != w[2];
                at.push(if real {
                    order.next().unwrap_or(NONE)
                } else {
                    NONE
                });
            }
            t.extend_from_slice(seq);
            let pad = if seq.len() % 2 == 1 { 1 } else { 2 };
            // Positions of the strip's last two entries and of the delimiters hold no triangle.
            at.extend(std::iter::repeat_n(NONE, pad + seq.len().min(2)));
            t.extend(std::iter::repeat_n(DELIMITER, pad));
        };
        for seq in strips.strips.split(|&x| x == RESTART) {
            if !seq.is_empty() {
                push_strip(seq, &mut order);
            }
        }
        for (tri, &tt) in strips.list.chunks_exact(3).zip(&strips.list_order) {
            push_strip(tri, &mut std::iter::once(tt));
        }
        if 3 * t.len() as u64 >= NONE as u64 {
            return Err(Error::Unsupported(format!(
                "{n} triangles make {} strip entries, too many for 32-bit corner ids",
                t.len()
            )));
        }
        let mut position = vec![NONE; n];
        for (j, &tt) in at.iter().enumerate() {
            if tt != NONE {
                position[tt as usize] = j as u32;
            }
        }
        let mut tables = CtsTables {
            a: vec![DELIMITER; t.len()],
            c: vec![NONE; table.vertex_id_bound() as usize],
            triangles: n as u32,
            t,
        };
        let v_table = table.v_table();
        for (j, &tt) in at.iter().enumerate() {
            if tt == NONE {
                continue;
            }
            for (i, &q) in OFFSET[j % 2].iter().enumerate() {
                let vertex = tables.t[j + q];
                if tables.c[vertex as usize] == NONE {
                    tables.c[vertex as usize] = (3 * j + i) as u32;
                }
                let Some(slot) = tables.a_slot(j, q) else {
                    continue;
                };
                // The table corner of tt at this vertex, and the triangle across from it.
                let tc = (0..3)
                    .map(|k| 3 * tt as usize + k)
                    .find(|&k| v_table[k] == vertex);
                let across = tc
                    .map(|k| table.o_table()[k])
                    .filter(|&o| o != NONE)
                    .map_or(DELIMITER, |o| position[(o / 3) as usize]);
                tables.a[slot] = across;
            }
        }
        // Each vertex's corner starts its fan, so that swinging from it visits every corner.
        for v in 0..tables.c.len() {
            if let Some(c) = Corner::from_stored(tables.c[v]) {
                tables.c[v] = crate::ops::fan_start(&tables, c).0;
            }
        }
        Ok(Cts {
            input_triangle: at
                .iter()
                .map(|&tt| {
                    if tt == NONE {
                        NONE
                    } else {
                        table.input_triangle(Triangle(tt))
                    }
                })
                .collect(),
            input_vertex: table
                .vertices()
                .map(|v| table.original_vertex(v).0)
                .collect(),
            kept_aside: table.kept_aside().to_vec(),
            tables,
        })
    }

    /// Degenerate input triangles kept aside, with their input ids (as the corner table's).
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        &self.kept_aside
    }

    /// The index table `T`, strips separated by [`DELIMITER`]s.
    pub fn t(&self) -> &[u32] {
        &self.tables.t
    }

    /// The adjacent-strips table `A` (positions in `T`, [`DELIMITER`] for none).
    pub fn a(&self) -> &[u32] {
        &self.tables.a
    }

    /// The vertex-to-corner table `C` (`u32::MAX` for a vertex without triangles).
    pub fn c(&self) -> &[u32] {
        &self.tables.c
    }

    /// The tables the operators run on.
    pub fn tables(&self) -> &CtsTables<Vec<u32>> {
        &self.tables
    }

    /// Storage of `T` and `A` at 32 bits an entry, per triangle (the paper's integer arrays).
    pub fn bits_per_triangle(&self) -> f64 {
        self.tables.bits_per_triangle()
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> u32 {
        self.tables.triangles
    }

    /// The input triangle of triangle `t` (`u32::MAX` when no triangle starts at `t`).
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.input_triangle.get(t.idx()).copied().unwrap_or(NONE)
    }

    /// The input vertex that vertex `v` stands for (itself, or the original of a copy).
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.input_vertex.get(v.idx()).copied().unwrap_or(NONE)
    }
}

impl<W: Words> CtsTables<W> {
    /// Storage of `T` and `A` at 32 bits an entry, per triangle (the paper's integer arrays).
    pub fn bits_per_triangle(&self) -> f64 {
        32.0 * (self.t.count() + self.a.count()) as f64 / self.triangles.max(1) as f64
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> u32 {
        self.triangles
    }

    /// Entries of `T` (and of `A`).
    pub fn len(&self) -> usize {
        self.t.count()
    }

    /// Whether `T` is empty (no triangles).
    pub fn is_empty(&self) -> bool {
        self.t.count() == 0
    }

    /// Entry `j` of `T`, `None` past its end.
    pub fn t_at(&self, j: usize) -> Option<u32> {
        (j < self.t.count()).then(|| self.t.at(j))
    }

    /// Entry `j` of `A`, `None` past its end.
    pub fn a_at(&self, j: usize) -> Option<u32> {
        (j < self.a.count()).then(|| self.a.at(j))
    }

    /// The three entries at `j` if they are all vertices.
    #[inline(always)]
    fn triple(&self, j: usize) -> Option<[u32; 3]> {
        if j + 3 > self.t.count() {
            return None;
        }
        let w = [self.t.at(j), self.t.at(j + 1), self.t.at(j + 2)];
        (w[0] != DELIMITER && w[1] != DELIMITER && w[2] != DELIMITER).then_some(w)
    }

    /// Whether a triangle starts at position `j`.
    #[inline(always)]
    pub fn is_triangle(&self, j: usize) -> bool {
        self.triple(j)
            .is_some_and(|w| w[0] != w[1] && w[1] != w[2] && w[0] != w[2])
    }

    /// Whether a swap (zero-area triangle) starts at position `j`.
    #[inline(always)]
    pub fn is_swap(&self, j: usize) -> bool {
        self.triple(j)
            .is_some_and(|w| w[0] == w[1] || w[1] == w[2] || w[0] == w[2])
    }

    /// Whether `c` is a corner of a triangle.
    pub fn is_corner(&self, c: Corner) -> bool {
        self.is_triangle((c.0 / 3) as usize)
    }

    /// The strip neighbour across `{T[j], T[j+1]}`, `NONE` at a strip's start.
    #[inline(always)]
    pub(crate) fn back(&self, j: usize) -> u32 {
        if j >= 1 && self.is_triangle(j - 1) {
            (j - 1) as u32
        } else if j >= 2 && self.is_swap(j - 1) && self.is_triangle(j - 2) {
            (j - 2) as u32
        } else {
            NONE
        }
    }

    /// The strip neighbour across `{T[j+1], T[j+2]}`, `NONE` at a strip's end.
    #[inline(always)]
    pub(crate) fn forward(&self, j: usize) -> u32 {
        if self.is_triangle(j + 1) {
            (j + 1) as u32
        } else if self.is_swap(j + 1) && self.is_triangle(j + 2) {
            (j + 2) as u32
        } else {
            NONE
        }
    }

    /// The position of `A` that the opposite of the corner at offset `q` of triangle `j`
    /// reads, or `None` when the strip itself gives the neighbour.
    #[inline(always)]
    pub(crate) fn a_slot(&self, j: usize, q: usize) -> Option<usize> {
        match q {
            1 => Some(j + 1),
            2 => (self.back(j) == NONE).then_some(j),
            _ => (self.forward(j) == NONE).then_some(j + 2),
        }
    }
}

impl CornerOps for Cts {
    fn vertex_id_bound(&self) -> u32 {
        self.tables.vertex_id_bound()
    }

    fn triangle_id_bound(&self) -> u32 {
        self.tables.triangle_id_bound()
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        self.tables.triangles()
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        self.tables.vertices()
    }

    #[inline]
    fn vertex(&self, c: Corner) -> Vertex {
        self.tables.vertex(c)
    }

    #[inline]
    fn triangle(&self, c: Corner) -> Triangle {
        self.tables.triangle(c)
    }

    #[inline]
    fn next(&self, c: Corner) -> Corner {
        self.tables.next(c)
    }

    #[inline]
    fn prev(&self, c: Corner) -> Corner {
        self.tables.prev(c)
    }

    #[inline]
    fn opposite(&self, c: Corner) -> Option<Corner> {
        self.tables.opposite(c)
    }

    #[inline]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        self.tables.vertex_corner(v)
    }

    #[inline]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        self.tables.triangle_corner(t)
    }
}

impl<W: Words> CornerOps for CtsTables<W> {
    fn vertex_id_bound(&self) -> u32 {
        self.c.count() as u32
    }

    fn triangle_id_bound(&self) -> u32 {
        self.t.count() as u32
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.t.count())
            .filter(|&j| self.is_triangle(j))
            .map(|j| Triangle(j as u32))
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        (0..self.c.count() as u32).map(Vertex)
    }

    #[inline]
    fn vertex(&self, c: Corner) -> Vertex {
        let j = (c.0 / 3) as usize;
        Vertex(self.t.at(j + OFFSET[j % 2][(c.0 % 3) as usize]))
    }

    #[inline]
    fn triangle(&self, c: Corner) -> Triangle {
        Triangle(c.0 / 3)
    }

    #[inline]
    fn next(&self, c: Corner) -> Corner {
        Corner(if c.0 % 3 == 2 { c.0 - 2 } else { c.0 + 1 })
    }

    #[inline]
    fn prev(&self, c: Corner) -> Corner {
        Corner(if c.0 % 3 == 0 { c.0 + 2 } else { c.0 - 1 })
    }

    fn opposite(&self, c: Corner) -> Option<Corner> {
        let j = (c.0 / 3) as usize;
        let q = OFFSET[j % 2][(c.0 % 3) as usize];
        let nb = match q {
            1 => self.a.at(j + 1),
            2 => match self.back(j) {
                NONE => self.a.at(j),
                b => b,
            },
            _ => match self.forward(j) {
                NONE => self.a.at(j + 2),
                f => f,
            },
        };
        if nb == DELIMITER {
            return None;
        }
        // The neighbour's corner off the shared edge (the two entries other than q).
        let (x, y) = match q {
            0 => (self.t.at(j + 1), self.t.at(j + 2)),
            1 => (self.t.at(j), self.t.at(j + 2)),
            _ => (self.t.at(j), self.t.at(j + 1)),
        };
        let k = nb as usize;
        let off = (0..3).find(|&r| {
            let w = self.t.at(k + r);
            w != x && w != y
        })?;
        Some(Corner(3 * nb + OFFSET[k % 2][off] as u32))
    }

    #[inline]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        Corner::from_stored(self.c.at(v.idx()))
    }

    #[inline]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        Corner(3 * t.0)
    }
}
