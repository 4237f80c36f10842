//! The corner table (Rossignac 2001) for any indexed triangle set.
//!
//! The corner table stores, for corner `c = 3t + i` of triangle `t`, its vertex `V[c]` and its
//! opposite corner `O[c]`, plus a corner `C[v]` of each vertex. It describes a pseudo-manifold:
//! every edge has at most two triangles, consistently oriented, and every vertex has a single
//! fan of triangles. Real meshes are not like that, so [`CornerTable::build`] converts the input
//! first (LR paper, section 4.1), with these rules, applied in this order:
//!
//! 1. **Degenerate triangles** (a vertex index repeated) are kept aside, in input order, and are
//!    not part of the table. [`CornerTable::kept_aside`] gives them back.
//! 2. **Edge matching.** The remaining triangles' half-edges are grouped by undirected edge.
//!    An edge with exactly two half-edges of opposite direction is *matched*: the two facing
//!    corners become each other's `O`. Every other edge is *cut*: its half-edges all get
//!    `O = NONE`, like boundary edges. That covers boundary edges (one half-edge), edges whose
//!    two triangles disagree on orientation (two half-edges in the same direction), and
//!    non-manifold edges (three or more half-edges). Duplicate triangles need no rule of their
//!    own: they meet their twin along same-direction or non-manifold edges and are cut apart.
//! 3. **Vertex splitting.** Around each vertex, corners are linked by swing across matched edges
//!    into fans. The fan that contains the vertex's lowest-numbered corner keeps the vertex id;
//!    every further fan, taken in the order of its lowest corner, gets a new vertex, a *copy*,
//!    numbered from the input vertex count upward. [`CornerTable::original_vertex`] maps every
//!    copy back to its input vertex, so the input triangles come back exactly
//!    ([`CornerTable::input_triangles`]).
//! 4. **`C` table.** `C[v]` is the first corner of the vertex's fan: for a fan that ends at cut or
//!    boundary edges, the corner from which swinging visits the whole fan; for a closed fan, its
//!    lowest corner. Unreferenced vertices have `C[v] = NONE`.
//!
//! Triangles of the table keep the input's order with degenerate ones removed
//! ([`CornerTable::input_triangle`] gives the input index of each).
//!
//! Construction is linear in time and space: half-edges are bucketed by their lower vertex with a
//! counting sort, and each bucket is grouped by its higher vertex with a per-vertex counter.

use crate::error::{Error, Result};
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;

pub use crate::ids::NONE;

/// Next corner around the triangle: `c.n`.
#[inline(always)]
fn next(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

/// Previous corner around the triangle: `c.p`.
#[inline(always)]
fn prev(c: u32) -> u32 {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

/// `c.n.o.n` with opposites `o`: the next corner around `c`'s vertex, or `NONE`.
#[inline(always)]
fn swing(o: &[u32], c: u32) -> u32 {
    match o[next(c) as usize] {
        NONE => NONE,
        d => next(d),
    }
}

/// `c.p.o.p` with opposites `o`: the previous corner around `c`'s vertex, or `NONE`.
#[inline(always)]
fn unswing(o: &[u32], c: u32) -> u32 {
    match o[prev(c) as usize] {
        NONE => NONE,
        d => prev(d),
    }
}

/// What the pseudo-manifold conversion had to change, counted.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Conversion {
    /// Undirected edges cut because two triangles use them in the same direction.
    pub cut_inconsistent_edges: u32,
    /// Undirected edges cut because three or more triangles use them.
    pub cut_nonmanifold_edges: u32,
    /// Vertex copies made for extra fans.
    pub vertex_copies: u32,
    /// Degenerate triangles kept aside.
    pub kept_aside: u32,
}

/// A corner table over the pseudo-manifold made from an indexed triangle set.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CornerTable {
    v: Vec<u32>,
    o: Vec<u32>,
    c: Vec<u32>,
    input_vertices: u32,
    copy_of: Vec<u32>,
    /// The input index of each triangle; empty when triangle `t` is input triangle `t`.
    input_triangle: Vec<u32>,
    kept_aside: Vec<(u32, [u32; 3])>,
    conversion: Conversion,
}

impl CornerTable {
    /// Builds the corner table of `triangles` over `vertex_count` vertices, converting the input
    /// to a pseudo-manifold by the rules in the module documentation.
    ///
    /// # Errors
    /// [`Error::InvalidMesh`] when a triangle refers to a vertex `>= vertex_count`, or when the
    /// counts (with vertex copies) do not fit 32-bit ids.
    pub fn build(vertex_count: usize, triangles: &[[u32; 3]]) -> Result<CornerTable> {
        CornerTable::from_triangles(vertex_count, triangles.to_vec())
    }

    /// [`CornerTable::build`] from triangles the table may keep: their vector becomes the
    /// `V` table (the degenerate ones taken out), so that a caller that no longer needs
    /// them holds them once, not twice.
    ///
    /// # Errors
    /// As [`CornerTable::build`].
    pub fn from_triangles(
        vertex_count: usize,
        mut triangles: Vec<[u32; 3]>,
    ) -> Result<CornerTable> {
        if vertex_count >= NONE as usize || triangles.len() >= (NONE / 3) as usize {
            return Err(Error::InvalidMesh(format!(
                "{vertex_count} vertices and {} triangles exceed the 32-bit id space",
                triangles.len()
            )));
        }
        let nv = vertex_count as u32;
        // Filled only once a triangle is kept aside: until then triangle `t` is input `t`.
        let mut input_triangle = Vec::new();
        let mut kept_aside = Vec::new();
        let degenerate = |tri: &[u32; 3]| tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2];
        for (t, tri) in triangles.iter().enumerate() {
            if let Some(&bad) = tri.iter().find(|&&x| x >= nv) {
                return Err(Error::InvalidMesh(format!(
                    "triangle {t} refers to vertex {bad}, but there are {nv} vertices"
                )));
            }
            if degenerate(tri) {
                if kept_aside.is_empty() {
                    input_triangle = (0..t as u32).collect();
                }
                kept_aside.push((t as u32, *tri));
            } else if !kept_aside.is_empty() {
                input_triangle.push(t as u32);
            }
        }
        if !kept_aside.is_empty() {
            triangles.retain(|tri| !degenerate(tri));
        }
        let mut v = triangles.into_flattened();
        let (o, cut_inconsistent_edges, cut_nonmanifold_edges) = match_edges(nv, &v);
        let (c, copy_of) = split_fans(nv, &mut v, &o)?;
        let conversion = Conversion {
            cut_inconsistent_edges,
            cut_nonmanifold_edges,
            vertex_copies: copy_of.len() as u32,
            kept_aside: kept_aside.len() as u32,
        };
        Ok(CornerTable {
            v,
            o,
            c,
            input_vertices: nv,
            copy_of,
            input_triangle,
            kept_aside,
            conversion,
        })
    }

    /// The corner table of non-degenerate triangles over `vertex_count` vertices whose
    /// opposites `o` are already known (the Edgebreaker decoder glues edges as it goes):
    /// exactly what [`CornerTable::build`] gives, without matching edges, when `o` pairs
    /// consistent corners, every vertex has one fan and no two edges of a fan end at the
    /// same vertex (then `build` would match the same pairs); else built by `build`.
    pub(crate) fn from_glued(
        vertex_count: u32,
        triangles: Vec<[u32; 3]>,
        o: Vec<u32>,
    ) -> Result<CornerTable> {
        let v = triangles.into_flattened();
        match glued_c_table(vertex_count, &v, &o) {
            Some(c) => Ok(CornerTable {
                input_triangle: Vec::new(),
                v,
                o,
                c,
                input_vertices: vertex_count,
                copy_of: Vec::new(),
                kept_aside: Vec::new(),
                conversion: Conversion::default(),
            }),
            None => {
                let triangles = v.chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
                CornerTable::from_triangles(vertex_count as usize, triangles)
            }
        }
    }

    /// Builds the corner table of a mesh's triangles (see [`CornerTable::build`]).
    ///
    /// # Errors
    /// As [`CornerTable::build`].
    pub fn from_mesh(mesh: &crate::Mesh) -> Result<CornerTable> {
        CornerTable::build(mesh.positions.len(), &mesh.triangles)
    }

    /// Frees the `V` and `O` tables, for an owner that reads only `C` and the maps to the
    /// input from now on (the LR builder's last step): [`CornerTable::v_table`] and
    /// [`CornerTable::o_table`] are empty after, and no corner operator may be used.
    pub(crate) fn free_corners(&mut self) {
        self.v = Vec::new();
        self.o = Vec::new();
    }

    /// The `V` table: the vertex of every corner.
    pub fn v_table(&self) -> &[u32] {
        &self.v
    }

    /// The `O` table: the opposite of every corner, [`NONE`] across a boundary or cut edge.
    pub fn o_table(&self) -> &[u32] {
        &self.o
    }

    /// The `C` table: a corner of every vertex (copies included), [`NONE`] when unreferenced.
    pub fn c_table(&self) -> &[u32] {
        &self.c
    }

    /// Number of vertices of the input; vertex ids from here up are copies.
    pub fn input_vertex_count(&self) -> u32 {
        self.input_vertices
    }

    /// The input vertex that `v` stands for: itself, or the vertex it is a copy of.
    pub fn original_vertex(&self, v: Vertex) -> Vertex {
        match v.0.checked_sub(self.input_vertices) {
            Some(k) => Vertex(self.copy_of[k as usize]),
            None => v,
        }
    }

    /// Per-vertex values of the input (positions, say) extended to the table's vertex ids:
    /// each copy gets its original's value.
    pub fn extend_to_copies<T: Copy>(&self, input: &[T]) -> Vec<T> {
        let mut out = input.to_vec();
        out.extend(self.copy_of.iter().map(|&v| input[v as usize]));
        out
    }

    /// The input index of triangle `t` of the table.
    pub fn input_triangle(&self, t: Triangle) -> u32 {
        self.input_triangle.get(t.idx()).copied().unwrap_or(t.0)
    }

    /// Degenerate input triangles, kept aside: `(input index, vertex triple)`, in input order.
    pub fn kept_aside(&self) -> &[(u32, [u32; 3])] {
        &self.kept_aside
    }

    /// What the pseudo-manifold conversion changed.
    pub fn conversion(&self) -> Conversion {
        self.conversion
    }

    /// The input triangles, exactly as given to [`CornerTable::build`]: table triangles mapped
    /// back through [`CornerTable::original_vertex`], with the kept-aside ones in their places.
    pub fn input_triangles(&self) -> Vec<[u32; 3]> {
        let total = self.v.len() / 3 + self.kept_aside.len();
        let mut out = vec![[0u32; 3]; total];
        for t in 0..self.v.len() / 3 {
            let input = self.input_triangle(Triangle(t as u32));
            let corner = |i: usize| self.original_vertex(Vertex(self.v[3 * t + i])).0;
            out[input as usize] = [corner(0), corner(1), corner(2)];
        }
        for &(input, tri) in &self.kept_aside {
            out[input as usize] = tri;
        }
        out
    }
}

/// The uses of edges bucketed by their lower vertex with a counting sort, each use by its
/// corner alone (4 bytes; its higher vertex is read again when its bucket is): the linear
/// pass that matches the corner table's opposites and counts the topology report's edges.
pub(crate) struct EdgeBuckets<F> {
    /// Where each vertex's bucket begins in `corners`, then the end.
    start: Vec<u32>,
    corners: Vec<u32>,
    /// The two vertices of the edge a corner stands for.
    ends: F,
}

impl<F: Fn(u32) -> (u32, u32)> EdgeBuckets<F> {
    /// Buckets corners `0..count` by the lower vertex of `ends(c)` (below `nv`), in
    /// increasing corner order; a corner whose two ends are one vertex stands for no edge.
    pub(crate) fn new(nv: usize, count: u32, ends: F) -> EdgeBuckets<F> {
        let lower = |c: u32| {
            let (a, b) = ends(c);
            (a != b).then_some(a.min(b) as usize)
        };
        let mut start = vec![0u32; nv + 1];
        for lo in (0..count).filter_map(lower) {
            start[lo + 1] += 1;
        }
        for i in 0..nv {
            start[i + 1] += start[i];
        }
        let mut corners = vec![0u32; start[nv] as usize];
        let mut fill = start.clone();
        for c in 0..count {
            if let Some(lo) = lower(c) {
                corners[fill[lo] as usize] = c;
                fill[lo] += 1;
            }
        }
        EdgeBuckets {
            start,
            corners,
            ends,
        }
    }

    /// The bucket of vertex `lo` as `(higher vertex, corner)` pairs, into `out`.
    pub(crate) fn read(&self, lo: u32, out: &mut Vec<(u32, u32)>) {
        out.clear();
        let (begin, end) = (self.start[lo as usize], self.start[lo as usize + 1]);
        let bucket = &self.corners[begin as usize..end as usize];
        out.extend(bucket.iter().map(|&c| {
            let (a, b) = (self.ends)(c);
            (a.max(b), c)
        }));
    }
}

/// Pairs opposite corners across matched edges; returns `O` and the counts of cut inconsistent
/// and cut non-manifold edges.
///
/// The half-edge facing corner `c` runs from `V[c.n]` to `V[c.p]`. Half-edges are bucketed by
/// their lower vertex (counting sort); within a bucket, `count[hi]` and `first[hi]` group them by
/// their higher vertex, and are reset afterwards so the whole pass stays linear.
fn match_edges(nv: u32, v: &[u32]) -> (Vec<u32>, u32, u32) {
    let corners = v.len();
    let buckets = EdgeBuckets::new(nv as usize, corners as u32, |c| {
        (v[next(c) as usize], v[prev(c) as usize])
    });

    let mut o = vec![NONE; corners];
    let mut count = vec![0u32; nv as usize];
    let mut first = vec![NONE; nv as usize];
    let (mut inconsistent, mut nonmanifold) = (0u32, 0u32);
    let mut entries: Vec<(u32, u32)> = Vec::new();
    crate::progress::phase("corner table", nv as u64);
    for lo in 0..nv {
        crate::progress::tick(lo as usize);
        buckets.read(lo, &mut entries);
        for &(hi, c) in &entries {
            let n = &mut count[hi as usize];
            *n += 1;
            if *n == 1 {
                first[hi as usize] = c;
            }
        }
        for &(hi, c) in &entries {
            let d = first[hi as usize];
            match count[hi as usize] {
                2 if c != d => {
                    // Opposite directions: c runs a->b, d must run b->a.
                    if v[next(c) as usize] == v[prev(d) as usize] {
                        o[c as usize] = d;
                        o[d as usize] = c;
                    } else {
                        inconsistent += 1;
                    }
                }
                k if k > 2 && c == d => nonmanifold += 1,
                _ => {}
            }
        }
        for &(hi, _) in &entries {
            count[hi as usize] = 0;
        }
    }
    (o, inconsistent, nonmanifold)
}

/// The `C` table of [`CornerTable::from_glued`] (the corner `split_fans` picks: the first of
/// the fan of the lowest corner of each vertex), or `None` when `o` is not what matching the
/// edges of non-degenerate triangles `v` (ids below `nv`) gives without a vertex copy.
fn glued_c_table(nv: u32, v: &[u32], o: &[u32]) -> Option<Vec<u32>> {
    let corners = v.len();
    if o.len() != corners || v.iter().any(|&x| x >= nv) {
        return None;
    }
    // Pairs of corners of other triangles, whose edges join the same vertices the other way.
    for (c, &d) in o.iter().enumerate() {
        let (c, d) = (c as u32, d as usize);
        if d != NONE as usize
            && (d >= corners
                || o[d] != c
                || d as u32 / 3 == c / 3
                || v[next(c) as usize] != v[prev(d as u32) as usize]
                || v[prev(c) as usize] != v[next(d as u32) as usize])
        {
            return None;
        }
    }
    // With `o` an involution, swinging is injective: every walk below ends.
    let (swing, unswing) = (|c| swing(o, c), |c| unswing(o, c));
    let mut c_table = vec![NONE; nv as usize];
    // The last vertex whose fan had this one as a neighbour.
    let mut stamp = vec![NONE; nv as usize];
    let mut in_fans = 0usize;
    for c in 0..corners as u32 {
        let a = v[c as usize];
        if c_table[a as usize] != NONE {
            continue;
        }
        // Each corner once: swing from `c` around the fan; if it opens, unswing from `c` to
        // its start. Consecutive corners of a fan share a neighbour (`v[d.p]` is `v[d'.n]`
        // for `d'` after `d`, the pairs being consistent): each corner stamps its `v[d.n]`,
        // and an open fan's last corner also its `v[d.p]`.
        let (mut fan, mut neighbours) = (0usize, 0usize);
        let mut stamp_neighbour = |b: u32| {
            if stamp[b as usize] != a {
                stamp[b as usize] = a;
                neighbours += 1;
            }
        };
        let mut d = c;
        let closed = loop {
            fan += 1;
            stamp_neighbour(v[next(d) as usize]);
            let after = swing(d);
            if after == NONE {
                stamp_neighbour(v[prev(d) as usize]);
                break false;
            }
            if after == c {
                break true;
            }
            d = after;
        };
        let mut first = c;
        if !closed {
            let mut d = unswing(c);
            while d != NONE {
                fan += 1;
                stamp_neighbour(v[next(d) as usize]);
                first = d;
                d = unswing(d);
            }
        }
        c_table[a as usize] = first;
        // A fan of k corners has k edges if closed, k + 1 if open: one neighbour each.
        if neighbours != fan + usize::from(!closed) {
            return None;
        }
        in_fans += fan;
    }
    // Every corner in the one fan of its vertex.
    (in_fans == corners).then_some(c_table)
}

/// Gives every fan its own vertex (copies for the second and later fans of a vertex) and builds
/// `C`. Rewrites `v` for corners of copies; returns `C` and the copy-to-original map.
fn split_fans(nv: u32, v: &mut [u32], o: &[u32]) -> Result<(Vec<u32>, Vec<u32>)> {
    let (swing, unswing) = (|c| swing(o, c), |c| unswing(o, c));
    let mut c_table = vec![NONE; nv as usize];
    let mut copy_of = Vec::new();
    let mut visited = vec![false; v.len()];
    for c in 0..v.len() as u32 {
        if visited[c as usize] {
            continue;
        }
        // Walk back to the start of the fan (or around a closed fan back to c).
        let mut first = c;
        loop {
            let back = unswing(first);
            if back == NONE {
                break;
            }
            if back == c {
                first = c;
                break;
            }
            first = back;
        }
        let original = v[c as usize];
        let vertex = if c_table[original as usize] == NONE {
            c_table[original as usize] = first;
            original
        } else {
            let id = nv as usize + copy_of.len();
            if id >= NONE as usize {
                return Err(Error::Unsupported(
                    "vertex copies exceed the 32-bit id space".into(),
                ));
            }
            copy_of.push(original);
            c_table.push(first);
            id as u32
        };
        let mut d = first;
        loop {
            visited[d as usize] = true;
            v[d as usize] = vertex;
            d = swing(d);
            if d == NONE || d == first {
                break;
            }
        }
    }
    Ok((c_table, copy_of))
}

impl CornerOps for CornerTable {
    fn vertex_id_bound(&self) -> u32 {
        self.c.len() as u32
    }

    fn triangle_id_bound(&self) -> u32 {
        (self.v.len() / 3) as u32
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.triangle_id_bound()).map(Triangle)
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        (0..self.vertex_id_bound()).map(Vertex)
    }

    #[inline]
    fn vertex(&self, c: Corner) -> Vertex {
        Vertex(self.v[c.idx()])
    }

    #[inline]
    fn triangle(&self, c: Corner) -> Triangle {
        Triangle(c.0 / 3)
    }

    #[inline]
    fn next(&self, c: Corner) -> Corner {
        Corner(next(c.0))
    }

    #[inline]
    fn prev(&self, c: Corner) -> Corner {
        Corner(prev(c.0))
    }

    #[inline]
    fn opposite(&self, c: Corner) -> Option<Corner> {
        Corner::from_stored(self.o[c.idx()])
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
