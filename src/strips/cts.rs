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

/// Separates strips in `T`; marks "no neighbour" in `A`.
pub const DELIMITER: u32 = u32::MAX;

/// Corner `i` of the triangle at an even (`[0]`) or odd (`[1]`) position is at this offset in
/// `T` (the permutation is its own inverse).
const OFFSET: [[usize; 3]; 2] = [[0, 1, 2], [1, 0, 2]];

/// Constrained triangle strips with the adjacent-strips table (see the module documentation).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Cts {
    t: Vec<u32>,
    a: Vec<u32>,
    c: Vec<u32>,
    /// Position -> input triangle (`NONE` where no triangle starts).
    input_triangle: Vec<u32>,
    /// Vertex -> input vertex.
    input_vertex: Vec<u32>,
    triangles: u32,
}

impl Cts {
    /// Strips the corner table's triangles with `options` (fans are not used) and builds `T`,
    /// `A` and `C`.
    ///
    /// # Errors
    /// [`Error::InvalidMesh`] when the corner ids `3j + i` would not fit 32 bits.
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
            return Err(Error::InvalidMesh(format!(
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
        let mut cts = Cts {
            a: vec![DELIMITER; t.len()],
            c: vec![NONE; table.vertex_id_bound() as usize],
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
            triangles: n as u32,
            t,
        };
        let v_table = table.v_table();
        for (j, &tt) in at.iter().enumerate() {
            if tt == NONE {
                continue;
            }
            for (i, &q) in OFFSET[j % 2].iter().enumerate() {
                let vertex = cts.t[j + q];
                if cts.c[vertex as usize] == NONE {
                    cts.c[vertex as usize] = (3 * j + i) as u32;
                }
                let slot = match q {
                    1 => j + 1,
                    2 if cts.back(j) == NONE => j,
                    0 if cts.forward(j) == NONE => j + 2,
                    _ => continue,
                };
                // The table corner of tt at this vertex, and the triangle across from it.
                let tc = (0..3)
                    .map(|k| 3 * tt as usize + k)
                    .find(|&k| v_table[k] == vertex);
                let across = tc
                    .map(|k| table.o_table()[k])
                    .filter(|&o| o != NONE)
                    .map_or(DELIMITER, |o| position[(o / 3) as usize]);
                cts.a[slot] = across;
            }
        }
        Ok(cts)
    }

    /// The index table `T`, strips separated by [`DELIMITER`]s.
    pub fn t(&self) -> &[u32] {
        &self.t
    }

    /// The adjacent-strips table `A` (positions in `T`, [`DELIMITER`] for none).
    pub fn a(&self) -> &[u32] {
        &self.a
    }

    /// Storage of `T` and `A` at 32 bits an entry, per triangle (the paper's integer arrays).
    pub fn bits_per_triangle(&self) -> f64 {
        32.0 * (self.t.len() + self.a.len()) as f64 / self.triangles.max(1) as f64
    }

    /// Number of triangles.
    pub fn triangle_count(&self) -> u32 {
        self.triangles
    }

    /// The input triangle of triangle `t` (`u32::MAX` when no triangle starts at `t`).
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.input_triangle.get(t.idx()).copied().unwrap_or(NONE)
    }

    /// The input vertex that vertex `v` stands for (itself, or the original of a copy).
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.input_vertex.get(v.idx()).copied().unwrap_or(NONE)
    }

    /// The three entries at `j` if they are all vertices.
    #[inline(always)]
    fn triple(&self, j: usize) -> Option<[u32; 3]> {
        let w = self.t.get(j..j + 3)?;
        (w[0] != DELIMITER && w[1] != DELIMITER && w[2] != DELIMITER).then(|| [w[0], w[1], w[2]])
    }

    /// Whether a triangle starts at position `j`.
    #[inline(always)]
    fn is_triangle(&self, j: usize) -> bool {
        self.triple(j)
            .is_some_and(|w| w[0] != w[1] && w[1] != w[2] && w[0] != w[2])
    }

    /// Whether a swap (zero-area triangle) starts at position `j`.
    #[inline(always)]
    fn is_swap(&self, j: usize) -> bool {
        self.triple(j)
            .is_some_and(|w| w[0] == w[1] || w[1] == w[2] || w[0] == w[2])
    }

    /// The strip neighbour across `{T[j], T[j+1]}`, `NONE` at a strip's start.
    #[inline(always)]
    fn back(&self, j: usize) -> u32 {
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
    fn forward(&self, j: usize) -> u32 {
        if self.is_triangle(j + 1) {
            (j + 1) as u32
        } else if self.is_swap(j + 1) && self.is_triangle(j + 2) {
            (j + 2) as u32
        } else {
            NONE
        }
    }
}

impl CornerOps for Cts {
    fn vertex_id_bound(&self) -> u32 {
        self.c.len() as u32
    }

    fn triangle_id_bound(&self) -> u32 {
        self.t.len() as u32
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.t.len())
            .filter(|&j| self.is_triangle(j))
            .map(|j| Triangle(j as u32))
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        (0..self.c.len() as u32).map(Vertex)
    }

    #[inline]
    fn vertex(&self, c: Corner) -> Vertex {
        let j = (c.0 / 3) as usize;
        Vertex(self.t[j + OFFSET[j % 2][(c.0 % 3) as usize]])
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
            1 => self.a[j + 1],
            2 => match self.back(j) {
                NONE => self.a[j],
                b => b,
            },
            _ => match self.forward(j) {
                NONE => self.a[j + 2],
                f => f,
            },
        };
        if nb == DELIMITER {
            return None;
        }
        // The neighbour's corner off the shared edge (the two entries other than q).
        let (x, y) = match q {
            0 => (self.t[j + 1], self.t[j + 2]),
            1 => (self.t[j], self.t[j + 2]),
            _ => (self.t[j], self.t[j + 1]),
        };
        let k = nb as usize;
        let off = (0..3).find(|&r| {
            let w = self.t[k + r];
            w != x && w != y
        })?;
        Some(Corner(3 * nb + OFFSET[k % 2][off] as u32))
    }

    #[inline]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        Corner::from_stored(self.c[v.idx()])
    }

    #[inline]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        Corner(3 * t.0)
    }
}
