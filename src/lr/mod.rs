//! The Laced Ring (LR) representation (Gurung, Luffel, Lindstrom, Rossignac, ACM TOG 2011,
//! sections 4 and 5): about one vertex reference per triangle, with the standard corner
//! operators in constant time.
//!
//! # Layout (as in the paper, with the deviations marked)
//!
//! - A **ring** is a loop of edges through most vertices, built by RING-EXPANDER. Ring vertices
//!   get ids `0..m_r` in ring order; isolated vertices `m_r..m`. *Deviation:* every component
//!   gets its own ring, numbered one after the other, so `v.n` is `v + 1` except at the last
//!   vertex of a ring, which wraps to its ring's first (found in constant time through
//!   the ring-end bit vector). A ring of three vertices (a component of one or two triangles) is not kept:
//!   its vertices become isolated and its triangles T0, which spares every operator the
//!   special case of a triangle with three ring edges.
//! - Ring edge `(v, v.n)` has a **left** triangle `2v = (v, L[v], v.n)` with corners
//!   `8v+0, 8v+1, 8v+2` and a **right** triangle `2v+1 = (v.n, R[v], v)` with corners
//!   `8v+4, 8v+5, 8v+6`. The left triangles are the invaded ones (the disk that RING-EXPANDER
//!   grows); the right ones are the rest. `8v+3` and `8v+7` are unused.
//! - **T0** triangles (no ring edge) are stored in the VO table, three vertices and three
//!   opposite corners each, as triangles `2m_r + j` with corners `8m_r + 4j + i`.
//! - A **T2** triangle (two ring edges, on consecutive ring edges `(v.p, v)` and `(v, v.n)`)
//!   appears in both slots; the slot of the second ring edge is canonical (`L[v] = v.p`), the
//!   other is redundant (`L[v.p] = v.p.n.n`) and its corners map to the canonical ones.
//! - **Warts** (section 5): a T0 triangle next to a T2 takes over the T2's redundant slot, with
//!   the WART flag in that entry; the slot's far vertex is then `v.n.n` instead of `v.n`.
//! - An entry whose triangle's opposites the operators cannot infer from the ring gets the
//!   IRREGULAR flag and indexes a VO* record `(tip, o_a, o_b)` holding the tip vertex and the
//!   opposites of its two transversal corners. *Generalisation:* the construction runs the
//!   operators and marks a triangle irregular exactly when their answer would differ from the
//!   corner table's (which covers T1^i/T2^i next to T0s, and every oddity of pseudo-manifold
//!   input, such as two edges between the same two vertices).
//! - **Boundaries** (section 4.6): each boundary loop of the corner table gets a dummy vertex
//!   and a fan of dummy triangles, so RING-EXPANDER runs on a closed mesh; dummy vertices are
//!   never on the ring, a right triangle that is a dummy has `R[v] = NULL`, and dummy T0s are
//!   not stored at all. `c.o` across a boundary is `None`.
//! - The C table holds a corner for each isolated vertex (`NONE` for unreferenced ones).
//!
//! Entries are 32 bits: bit 31 IRREGULAR, bit 30 WART, bits 0–29 a vertex id, `NULL`, or a
//! VO* record index. So a mesh may have up to `2^30 - 2` vertices.
//!
//! The operators are written once, in [`LrLayout`], for any encoding of the tables: the
//! standard [`LrTables`] (owned, or on a container's bytes) and the bit-efficient
//! [`CompactTables`] of section 6 ([`compact`]), built by [`CompactLr`].

mod build;
mod closed;
pub mod compact;
mod leaf_moves;
pub mod open_fans;
pub(crate) mod read_back;
mod ring;
mod tables;
pub mod zipper;

pub use compact::{CompactLr, CompactOptions, CompactStats, CompactTables};
pub use open_fans::OpenFans;
pub(crate) use tables::{bits_and_ranks, boundaries_on_ring_given, one_ring_next_next, ring_bits};
pub use tables::{LrLayout, LrTables, IRREGULAR, NULL, VALUE, WART};
pub use zipper::{Zipper, ZipperCursor, ZipperStats, ZipperTables};

use crate::corner_table::NONE;
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;

/// Options of the LR construction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LrOptions {
    /// RING-EXPANDER runs per component, each from another seed corner; the ring with the
    /// fewest isolated vertices is kept.
    pub tries: u32,
    /// Seed of the random choice of seed corners: the same value gives the same LR.
    pub seed: u64,
    /// Threads for the phases that run in parallel (the tries of a large component, the
    /// search for irregular triangles); 0 and 1 use the calling thread only. The LR is the
    /// same for any count.
    pub threads: u32,
}

impl Default for LrOptions {
    fn default() -> Self {
        LrOptions {
            tries: 4,
            seed: 1,
            threads: 1,
        }
    }
}

/// Counts of the LR paper's Table 1 (standard LR columns).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct LrCounts {
    /// Triangles `n` (canonical, kept-aside degenerate ones not included).
    pub triangles: u32,
    /// Vertices `m` (those of the corner table: input vertices plus copies).
    pub vertices: u32,
    /// Vertices on a ring, `m_r`.
    pub ring_vertices: u32,
    /// Rings (one per component with a ring).
    pub rings: u32,
    /// T0 triangles stored in VO after wart skipping, `n_0`.
    pub t0: u32,
    /// T0 triangles moved into a wart's redundant slot.
    pub t0_wart: u32,
    /// Irregular triangles with a VO* record, `n^i`.
    pub irregular: u32,
    /// Of those, the ones with no T0 neighbour: the ring rules could not infer an opposite
    /// (pseudo-manifold oddities, or a rule that misses a case).
    pub irregular_without_t0: u32,
}

impl LrCounts {
    /// Isolated vertices `m_i = m - m_r`.
    pub fn isolated_vertices(&self) -> u32 {
        self.vertices - self.ring_vertices
    }

    /// References per triangle, section 8: `(2 m_r + 6 n_0 + 3 n^i + m_i) / n`.
    pub fn references_per_triangle(&self) -> f64 {
        let refs = 2 * self.ring_vertices as u64
            + 6 * self.t0 as u64
            + 3 * self.irregular as u64
            + self.isolated_vertices() as u64;
        refs as f64 / self.triangles.max(1) as f64
    }
}

/// A mesh's connectivity in standard LR form, with the permutations back to the input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Lr {
    /// The tables the operators read.
    tables: LrTables<Vec<u32>>,
    /// The counts and the maps to the input.
    maps: InputMaps,
    /// Input vertex -> an LR vertex standing for it (the first fan's, for split vertices).
    input_vertex_lr: Vec<u32>,
    /// Input triangle -> LR triangle (`NONE` for degenerate triangles, kept aside).
    input_triangle_lr: Vec<u32>,
}

/// An LR's counts and maps to the input: what a layout encoded from a standard LR (the
/// bit-efficient LR, the Zipper) keeps of it. Not its tables nor the maps from the input,
/// which the layouts do not read: the owned Zipper of the 3.3M-triangle armadillo holds 33 MB
/// less.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub(crate) struct InputMaps {
    counts: LrCounts,
    /// LR vertex -> input vertex.
    vertex_input: Vec<u32>,
    /// LR triangle id -> input triangle (`NONE` for ids that are not canonical triangles).
    triangle_input: Vec<u32>,
    /// Degenerate input triangles: `(input index, input vertex triple)`.
    kept_aside: Vec<(u32, [u32; 3])>,
}

impl InputMaps {
    /// The Table 1 counts of the LR.
    pub fn counts(&self) -> LrCounts {
        self.counts
    }

    /// The input vertex that LR vertex `v` stands for.
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.vertex_input[v.idx()]
    }

    /// The input triangle that canonical LR triangle `t` stands for.
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.triangle_input[t.idx()]
    }

    /// Degenerate input triangles, kept aside.
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        &self.kept_aside
    }
}

impl Lr {
    /// The counts and maps to the input, the rest dropped ([`InputMaps`]).
    pub(crate) fn into_input_maps(self) -> InputMaps {
        self.maps
    }

    /// Gives slot `slot` a VO* record `(tip, o_a, o_b)` and the IRREGULAR flag.
    fn make_irregular(&mut self, slot: usize, o_a: u32, o_b: u32) {
        let t = &mut self.tables;
        let entry = t.lr[slot];
        if entry & IRREGULAR != 0 {
            return;
        }
        let record = t.vo_star.len() as u32 / 3;
        t.vo_star.extend_from_slice(&[entry & VALUE, o_a, o_b]);
        t.lr[slot] = IRREGULAR | (entry & WART) | record;
    }

    /// The Table 1 counts of this LR.
    pub fn counts(&self) -> LrCounts {
        self.maps.counts()
    }

    /// The input vertex that LR vertex `v` stands for.
    pub fn input_vertex(&self, v: Vertex) -> u32 {
        self.maps.input_vertex(v)
    }

    /// The input triangle that canonical LR triangle `t` stands for.
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.maps.input_triangle(t)
    }

    /// An LR vertex that input vertex `v` became (the first fan's, for a vertex that the
    /// pseudo-manifold conversion split).
    pub fn lr_vertex(&self, input_vertex: u32) -> Vertex {
        Vertex(self.input_vertex_lr[input_vertex as usize])
    }

    /// The LR triangle that input triangle `t` became; `None` for a degenerate triangle.
    pub fn lr_triangle(&self, input_triangle: u32) -> Option<Triangle> {
        match self.input_triangle_lr[input_triangle as usize] {
            NONE => None,
            t => Some(Triangle(t)),
        }
    }

    /// Degenerate input triangles, kept aside: `(input index, input vertex triple)`.
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        self.maps.kept_aside()
    }

    /// The input triangles, in input order, from the LR alone. Each comes back with the same
    /// orientation, possibly rotated (an LR triangle starts at its ring vertex).
    pub fn input_triangles(&self) -> Vec<[u32; 3]> {
        input_triangles_of(
            self,
            self.input_triangle_lr.len(),
            self.kept_aside(),
            |v| self.input_vertex(v),
            |t| self.input_triangle(t),
        )
    }

    /// The tables, which implement the corner operators.
    pub fn tables(&self) -> &LrTables<Vec<u32>> {
        &self.tables
    }
}

/// The input triangles of any LR layout, in input order (`count` of them): each canonical
/// triangle of `tables` through the maps back to the input, then the kept-aside ones.
pub(crate) fn input_triangles_of<T: CornerOps>(
    tables: &T,
    count: usize,
    kept: &[(u32, [u32; 3])],
    input_vertex: impl Fn(Vertex) -> u32,
    input_triangle: impl Fn(Triangle) -> u32,
) -> Vec<[u32; 3]> {
    let mut out = vec![[0u32; 3]; count];
    for t in tables.triangles() {
        out[input_triangle(t) as usize] = tables.triangle_vertices(t).map(&input_vertex);
    }
    for &(input, tri) in kept {
        out[input as usize] = tri;
    }
    out
}

/// The class of a canonical LR triangle, as coloured in the LR paper's Fig. 1 and Fig. 7.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TriangleClass {
    /// No ring edge, stored in VO.
    T0,
    /// A T0 stored in a wart's redundant slot (`T0^w`).
    T0Wart,
    /// One ring edge, on the left (invaded) side.
    T1Left,
    /// One ring edge, on the right side.
    T1Right,
    /// Two ring edges (a dead end).
    T2,
    /// A T2 whose redundant slot holds a T0 (`T2^w`, a wart).
    T2Wart,
}

/// What pictures and statistics read from any encoding of the LR tables (standard, compact,
/// owned or on a container's bytes): the class of each triangle and the vertices of each
/// ring. The operators never need it.
pub trait LrInspect: LrLayout {
    /// The class of canonical triangle `t`; `None` when `t` is not one
    /// ([`LrLayout::is_triangle`]).
    fn triangle_class(&self, t: Triangle) -> Option<TriangleClass> {
        if !self.is_triangle(t) {
            return None;
        }
        if t.0 >= 2 * self.ring_vertices() {
            return Some(TriangleClass::T0);
        }
        let (v, side) = (t.0 / 2, (t.0 % 2) as usize);
        if self.wart(v, side) {
            return Some(TriangleClass::T0Wart);
        }
        let p = self.ring_prev(v);
        Some(if self.tip(v, side) == p {
            if self.wart(p, side) {
                TriangleClass::T2Wart
            } else {
                TriangleClass::T2
            }
        } else if side == tables::LEFT {
            TriangleClass::T1Left
        } else {
            TriangleClass::T1Right
        })
    }

    /// The ring vertices of ring `ring` (ids are consecutive along a ring), or `None` past
    /// the last ring.
    fn ring_range(&self, ring: usize) -> Option<std::ops::Range<u32>> {
        (ring < self.ring_count()).then(|| self.ring_start(ring)..self.ring_start(ring + 1))
    }

    /// Each ring vertex's place along its ring, 0 (its first) to 1 (its last): what pictures
    /// colour by ring order.
    fn ring_places(&self) -> Vec<f32> {
        let mut place = vec![0.0; self.ring_vertices() as usize];
        for range in (0..self.ring_count()).filter_map(|r| self.ring_range(r)) {
            let span = (range.len().max(2) - 1) as f32;
            for v in range.clone() {
                place[v as usize] = (v - range.start) as f32 / span;
            }
        }
        place
    }

    /// The place along its ring of triangle `t` (`places` from [`LrInspect::ring_places`]): a
    /// ring-edge triangle takes its ring edge's, a T0 the mean of its ring vertices'; `None`
    /// when none of its vertices is on a ring.
    fn triangle_ring_place(&self, places: &[f32], t: Triangle) -> Option<f32>
    where
        Self: Sized,
    {
        if t.0 < 2 * self.ring_vertices() {
            return places.get((t.0 / 2) as usize).copied();
        }
        let on_ring: Vec<f32> = self
            .triangle_vertices(t)
            .iter()
            .filter_map(|v| places.get(v.idx()).copied())
            .collect();
        (!on_ring.is_empty()).then(|| on_ring.iter().sum::<f32>() / on_ring.len() as f32)
    }
}

impl<T: LrLayout> LrInspect for T {}

/// The operators of [`Lr::tables`].
impl CornerOps for Lr {
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
    #[inline(always)]
    fn vertex(&self, c: Corner) -> Vertex {
        self.tables.vertex(c)
    }
    #[inline(always)]
    fn triangle(&self, c: Corner) -> Triangle {
        self.tables.triangle(c)
    }
    #[inline(always)]
    fn next(&self, c: Corner) -> Corner {
        self.tables.next(c)
    }
    #[inline(always)]
    fn prev(&self, c: Corner) -> Corner {
        self.tables.prev(c)
    }
    #[inline(always)]
    fn opposite(&self, c: Corner) -> Option<Corner> {
        self.tables.opposite(c)
    }
    #[inline(always)]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        self.tables.vertex_corner(v)
    }
    #[inline(always)]
    fn any_corner(&self, v: Vertex) -> Option<Corner> {
        self.tables.any_corner(v)
    }
    #[inline(always)]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        self.tables.triangle_corner(t)
    }
}

/// The LR paper's Table 1 columns for one mesh (`lrmesh stats`, JSON object `lr`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct LrStats {
    /// Triangles `n` (degenerate ones, kept aside, not counted).
    pub triangles: u32,
    /// Vertices `m`, including pseudo-manifold copies.
    pub vertices: u32,
    /// Isolated vertices `m_i` (not on a ring; unreferenced ones included).
    pub isolated_vertices: u32,
    /// Rings: one per component that has one.
    pub rings: u32,
    /// Percentage of valence-6 vertices of the mesh as read.
    pub valence6_pct: f64,
    /// Percentage of T0 triangles after wart skipping.
    pub t0_pct: f64,
    /// Percentage of T0 triangles stored in a wart's slot (T0^w).
    pub t0w_pct: f64,
    /// Percentage of irregular triangles (T1^i and T2^i, with a VO* record).
    pub ti_pct: f64,
    /// References per triangle, `(2 m_r + 6 n_0 + 3 n^i + m_i) / n`.
    pub rpt: f64,
    /// Ring vertices whose open fan `LRTB` lists for `v.c` (flag `OPEN_FANS`, FORMAT.md
    /// §3.5.1): one per boundary edge off the ring; 0 without the list.
    pub open_fans: u32,
}

impl LrStats {
    /// The statistics of `lr`, with the mesh's valence-6 percentage from its topology report.
    pub fn new(lr: &Lr, valence6_pct: f64) -> LrStats {
        let c = lr.counts();
        let pct = |x: u32| 100.0 * x as f64 / c.triangles.max(1) as f64;
        LrStats {
            triangles: c.triangles,
            vertices: c.vertices,
            isolated_vertices: c.isolated_vertices(),
            rings: c.rings,
            valence6_pct,
            t0_pct: pct(c.t0),
            t0w_pct: pct(c.t0_wart),
            ti_pct: pct(c.irregular),
            rpt: c.references_per_triangle(),
            open_fans: lr
                .tables()
                .open_fans
                .as_ref()
                .map_or(0, |f| f.count() as u32),
        }
    }
}

impl std::fmt::Display for LrStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "standard LR")?;
        writeln!(f, "  triangles n              {}", self.triangles)?;
        writeln!(f, "  vertices m               {}", self.vertices)?;
        writeln!(f, "  isolated vertices m_i    {}", self.isolated_vertices)?;
        writeln!(f, "  rings                    {}", self.rings)?;
        writeln!(f, "  valence 6                {:.1}%", self.valence6_pct)?;
        writeln!(f, "  T0 (after wart skipping) {:.2}%", self.t0_pct)?;
        writeln!(f, "  T0^w                     {:.2}%", self.t0w_pct)?;
        writeln!(f, "  T^i                      {:.2}%", self.ti_pct)?;
        writeln!(f, "  references per triangle  {:.3}", self.rpt)?;
        writeln!(f, "  open fans listed         {}", self.open_fans)
    }
}
