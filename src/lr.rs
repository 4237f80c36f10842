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
//!   [`Rings`]). A ring of three vertices (a component of one or two triangles) is not kept:
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

use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::generate::Rng;
use crate::ids::{Corner, Triangle, Vertex};
use crate::ops::CornerOps;

const IRREGULAR: u32 = 1 << 31;
const WART: u32 = 1 << 30;
const VALUE: u32 = WART - 1;
/// The tip of a right triangle that does not exist (a boundary ring edge).
pub const NULL: u32 = VALUE;

/// Left or right side of a ring edge: the offset of its slot in the LR table.
const LEFT: usize = 0;
const RIGHT: usize = 1;

/// Options of the LR construction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LrOptions {
    /// RING-EXPANDER runs per component, each from another seed corner; the ring with the
    /// fewest isolated vertices is kept.
    pub tries: u32,
    /// Seed of the random choice of seed corners: the same value gives the same LR.
    pub seed: u64,
}

impl Default for LrOptions {
    fn default() -> Self {
        LrOptions { tries: 4, seed: 1 }
    }
}

/// The rings: each a range of consecutive vertex ids, so that `v.n` and `v.p` are constant
/// time. The last vertex of each ring is marked in a bit vector with rank counts, which gives
/// its ring's index and so its start.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Rings {
    /// Start of each ring, and `m_r` at the end.
    starts: Vec<u32>,
    /// Bit `v` set when `v` is the last vertex of its ring.
    last: Vec<u64>,
    /// Number of set bits in `last` before each word.
    rank: Vec<u32>,
}

impl Rings {
    fn new(starts: Vec<u32>) -> Rings {
        let m_r = *starts.last().unwrap_or(&0) as usize;
        let mut last = vec![0u64; m_r.div_ceil(64)];
        for w in starts.windows(2) {
            let v = w[1] as usize - 1;
            last[v / 64] |= 1 << (v % 64);
        }
        let mut rank = Vec::with_capacity(last.len());
        let mut count = 0;
        for word in &last {
            rank.push(count);
            count += word.count_ones();
        }
        Rings { starts, last, rank }
    }

    #[inline(always)]
    fn is_last(&self, v: u32) -> bool {
        self.last[v as usize / 64] >> (v % 64) & 1 != 0
    }

    /// Index of the ring that holds `v`: the number of ring ends before `v`.
    #[inline(always)]
    fn ring_of(&self, v: u32) -> usize {
        let word = self.last[v as usize / 64] & ((1u64 << (v % 64)) - 1);
        (self.rank[v as usize / 64] + word.count_ones()) as usize
    }

    /// `v.n`: the next vertex along the ring.
    #[inline(always)]
    pub fn next(&self, v: u32) -> u32 {
        if let [0, end] = self.starts[..] {
            // One ring, the common case: no bit vector to consult.
            return if v + 1 == end { 0 } else { v + 1 };
        }
        if self.is_last(v) {
            self.starts[self.ring_of(v)]
        } else {
            v + 1
        }
    }

    /// `v.p`: the previous vertex along the ring.
    #[inline(always)]
    pub fn prev(&self, v: u32) -> u32 {
        if let [0, end] = self.starts[..] {
            return if v == 0 { end - 1 } else { v - 1 };
        }
        if v == 0 || self.is_last(v - 1) {
            self.starts[self.ring_of(v) + 1] - 1
        } else {
            v - 1
        }
    }

    /// Number of rings.
    pub fn count(&self) -> usize {
        self.starts.len().saturating_sub(1)
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
    /// `L[v], R[v]` interleaved: entry `2v + side`.
    lr: Vec<u32>,
    /// VO table: vertices of T0 triangles, three each.
    vo_v: Vec<u32>,
    /// VO table: opposite corners of T0 triangles, three each (`NONE` on a boundary).
    vo_o: Vec<u32>,
    /// VO* records: tip, then the opposites of the two transversal corners.
    vo_star: Vec<u32>,
    /// C table: a corner of each isolated vertex.
    c: Vec<u32>,
    rings: Rings,
    m_r: u32,
    m: u32,
    counts: LrCounts,
    /// LR vertex -> input vertex.
    vertex_input: Vec<u32>,
    /// LR triangle id -> input triangle (`NONE` for ids that are not canonical triangles).
    triangle_input: Vec<u32>,
    /// Input vertex -> an LR vertex standing for it (the first fan's, for split vertices).
    input_vertex_lr: Vec<u32>,
    /// Input triangle -> LR triangle (`NONE` for degenerate triangles, kept aside).
    input_triangle_lr: Vec<u32>,
    /// Degenerate input triangles: `(input index, input vertex triple)`.
    kept_aside: Vec<(u32, [u32; 3])>,
}

/// The corner table closed by dummy vertices and triangles over each boundary loop.
struct Closed {
    v: Vec<u32>,
    o: Vec<u32>,
    real_triangles: u32,
    real_vertices: u32,
    /// Real and dummy vertices.
    total_vertices: u32,
}

fn next3(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

fn prev3(c: u32) -> u32 {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

impl Closed {
    /// Adds, for every boundary half-edge `a -> b` (facing corner `c`), a dummy triangle
    /// `(b, a, d)` where `d` is the dummy vertex of that boundary loop.
    fn new(ct: &CornerTable) -> Result<Closed> {
        let mut v = ct.v_table().to_vec();
        let mut o = ct.o_table().to_vec();
        let real_triangles = (v.len() / 3) as u32;
        let real_vertices = ct.vertex_id_bound();
        // The boundary half-edge arriving at each vertex (one at most: one fan per vertex).
        let mut incoming = vec![NONE; real_vertices as usize];
        let boundary: Vec<u32> = (0..v.len() as u32)
            .filter(|&c| o[c as usize] == NONE)
            .collect();
        for &c in &boundary {
            incoming[v[prev3(c) as usize] as usize] = c;
        }
        // Dummy triangle of boundary corner c, by the order of `boundary`.
        let mut dummy_of = vec![NONE; v.len()];
        for (k, &c) in boundary.iter().enumerate() {
            dummy_of[c as usize] = real_triangles + k as u32;
        }
        let total = v.len() + 3 * boundary.len();
        if total >= (NONE / 2) as usize {
            return Err(Error::InvalidMesh("mesh too large for LR".into()));
        }
        v.resize(total, NONE);
        o.resize(total, NONE);
        let mut next_dummy_vertex = real_vertices;
        for &c in &boundary {
            let t = dummy_of[c as usize];
            let (a, b) = (v[next3(c) as usize], v[prev3(c) as usize]);
            let base = 3 * t as usize;
            v[base] = b;
            v[base + 1] = a;
            o[base + 2] = c;
            o[c as usize] = base as u32 + 2;
            // Corner 0 (at b) faces a -> d: the dummy of the boundary half-edge into a.
            let before = dummy_of[incoming[a as usize] as usize];
            o[base] = 3 * before + 1;
            o[3 * before as usize + 1] = base as u32;
        }
        // One dummy vertex per loop: walk the loop through the corner-0/corner-1 links.
        for &c in &boundary {
            let t = dummy_of[c as usize] as usize;
            if v[3 * t + 2] != NONE {
                continue;
            }
            let d = next_dummy_vertex;
            next_dummy_vertex += 1;
            let mut u = t;
            while v[3 * u + 2] == NONE {
                v[3 * u + 2] = d;
                u = o[3 * u] as usize / 3;
            }
        }
        Ok(Closed {
            v,
            o,
            real_triangles,
            real_vertices,
            total_vertices: next_dummy_vertex,
        })
    }

    #[inline]
    fn right(&self, c: u32) -> u32 {
        self.o[prev3(c) as usize]
    }
}

/// RING-EXPANDER (section 4.2) from seed corner `s`: marks invaded triangles and visited
/// vertices. Dummy vertices must already be marked visited.
fn ring_expander(mesh: &Closed, s: u32, vm: &mut [bool], tm: &mut [bool]) {
    let v = &mesh.v;
    vm[v[next3(s) as usize] as usize] = true;
    vm[v[prev3(s) as usize] as usize] = true;
    let stop = mesh.o[s as usize];
    let mut c = s;
    loop {
        if !vm[v[c as usize] as usize] {
            vm[v[c as usize] as usize] = true;
            tm[c as usize / 3] = true;
        } else if !tm[c as usize / 3] {
            c = mesh.o[c as usize];
        }
        c = mesh.right(c);
        if c == stop {
            break;
        }
    }
}

/// Per-component work lists of the closed mesh.
struct Component {
    /// Real and dummy triangles.
    triangles: Vec<u32>,
    /// Real triangles only: the seeds are drawn from these.
    real_triangles: Vec<u32>,
    /// Real vertices.
    vertices: Vec<u32>,
}

fn components(mesh: &Closed) -> Vec<Component> {
    let nt = mesh.v.len() / 3;
    let mut seen = vec![false; nt];
    let mut vertex_seen = vec![false; mesh.real_vertices as usize];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..mesh.real_triangles {
        if seen[start as usize] {
            continue;
        }
        let mut comp = Component {
            triangles: Vec::new(),
            real_triangles: Vec::new(),
            vertices: Vec::new(),
        };
        seen[start as usize] = true;
        stack.push(start);
        while let Some(t) = stack.pop() {
            comp.triangles.push(t);
            if t < mesh.real_triangles {
                comp.real_triangles.push(t);
            }
            for i in 0..3 {
                let c = 3 * t as usize + i;
                let x = mesh.v[c];
                if x < mesh.real_vertices && !vertex_seen[x as usize] {
                    vertex_seen[x as usize] = true;
                    comp.vertices.push(x);
                }
                let u = mesh.o[c] / 3;
                if !seen[u as usize] {
                    seen[u as usize] = true;
                    stack.push(u);
                }
            }
        }
        out.push(comp);
    }
    out
}

/// The table corners of a slot, in the order: at `v`, the tip, at the far vertex. Left slot `(v, tip, far)`: tip corner `c`, `v` at `c.p`, far at `c.n`.
/// Right slot `(far, tip, v)`: tip corner `r`, `v` at `r.n`, far at `r.p`.
fn slot_corners(tip_corner: u32, side: usize) -> [u32; 3] {
    if side == LEFT {
        [prev3(tip_corner), tip_corner, next3(tip_corner)]
    } else {
        [next3(tip_corner), tip_corner, prev3(tip_corner)]
    }
}

impl Lr {
    /// Builds the LR of a corner table.
    ///
    /// # Errors
    /// [`Error::InvalidMesh`] when the mesh exceeds the id space (`2^30 - 2` vertices, corner
    /// ids below `2^32`).
    pub fn build(ct: &CornerTable, options: &LrOptions) -> Result<Lr> {
        let mesh = Closed::new(ct)?;
        let real_vertices = mesh.real_vertices;
        if real_vertices >= NULL {
            return Err(Error::InvalidMesh(
                "LR holds at most 2^30 - 2 vertices".into(),
            ));
        }
        let mut vm = vec![false; mesh.total_vertices as usize];
        for x in real_vertices..mesh.total_vertices {
            vm[x as usize] = true;
        }
        let mut tm = vec![false; mesh.v.len() / 3];
        let mut rng = Rng::new(options.seed);

        // Ring per component: best of several seeds, then walk it to number its vertices.
        let mut ring_id = vec![NONE; real_vertices as usize];
        let mut ring_corner = Vec::new(); // per ring vertex: the tip corner of its left slot
        let mut starts = vec![0u32];
        for comp in components(&mesh) {
            // Fewest isolated vertices first, then fewest T0 triangles (before wart skipping).
            let mut best: Option<((usize, usize), u32)> = None;
            for _ in 0..options.tries.max(1) {
                let t = comp.real_triangles[rng.below(comp.real_triangles.len() as u32) as usize];
                let s = 3 * t + rng.below(3);
                reset(&comp, &mut vm, &mut tm);
                ring_expander(&mesh, s, &mut vm, &mut tm);
                let isolated = comp.vertices.iter().filter(|&&x| !vm[x as usize]).count();
                let t0 = comp
                    .real_triangles
                    .iter()
                    .filter(|&&t| {
                        let inside = tm[t as usize];
                        (0..3).all(|i| tm[mesh.o[3 * t as usize + i] as usize / 3] == inside)
                    })
                    .count();
                if best.is_none_or(|(b, _)| (isolated, t0) < b) {
                    best = Some(((isolated, t0), s));
                }
            }
            let (_, s) = best.expect("at least one try");
            reset(&comp, &mut vm, &mut tm);
            ring_expander(&mesh, s, &mut vm, &mut tm);
            // A corner of an invaded triangle facing a non-invaded one starts the walk.
            let start = comp
                .triangles
                .iter()
                .filter(|&&t| tm[t as usize])
                .flat_map(|&t| 3 * t..3 * t + 3)
                .find(|&c| !tm[mesh.o[c as usize] as usize / 3])
                .expect("an invaded region has a boundary");
            let first = ring_corner.len();
            let mut c = start;
            loop {
                ring_corner.push(c);
                // Rotate around the far vertex through invaded triangles to the next ring edge.
                let mut k = prev3(c);
                while tm[mesh.o[k as usize] as usize / 3] {
                    k = prev3(mesh.o[k as usize]);
                }
                c = k;
                if c == start {
                    break;
                }
            }
            if ring_corner.len() - first == 3 {
                // A ring of three: keep the component as T0 triangles and isolated vertices.
                ring_corner.truncate(first);
                for &t in &comp.triangles {
                    tm[t as usize] = false;
                }
                continue;
            }
            for (k, &c) in ring_corner[first..].iter().enumerate() {
                ring_id[mesh.v[prev3(c) as usize] as usize] = (first + k) as u32;
            }
            starts.push(ring_corner.len() as u32);
        }
        let m_r = ring_corner.len() as u32;
        if (m_r as u64) * 8 + 4 * (mesh.real_triangles as u64) >= NONE as u64 {
            return Err(Error::InvalidMesh(
                "mesh too large for LR corner ids".into(),
            ));
        }
        let rings = Rings::new(starts);

        // LR vertex ids: ring vertices by ring position, then isolated ones in table order.
        let mut lr_vertex = ring_id;
        let mut next_isolated = m_r;
        for x in lr_vertex.iter_mut() {
            if *x == NONE {
                *x = next_isolated;
                next_isolated += 1;
            }
        }
        let vertex_of = |ct_vertex: u32| {
            if ct_vertex < real_vertices {
                lr_vertex[ct_vertex as usize]
            } else {
                NULL
            }
        };

        // Slots: which table triangle each ring edge side holds; T2s appear twice.
        let nt_real = mesh.real_triangles as usize;
        let mut slots_of = vec![0u8; nt_real];
        let mut lr = vec![0u32; 2 * m_r as usize];
        let mut slot_tip_corner = vec![NONE; 2 * m_r as usize];
        for (v, &c) in ring_corner.iter().enumerate() {
            let r = mesh.o[c as usize];
            for (side, tip) in [(LEFT, c), (RIGHT, r)] {
                let t = tip / 3;
                if t < mesh.real_triangles {
                    slots_of[t as usize] += 1;
                    lr[2 * v + side] = vertex_of(mesh.v[tip as usize]);
                    slot_tip_corner[2 * v + side] = tip;
                } else {
                    lr[2 * v + side] = NULL;
                }
            }
        }

        // Warts: a T0 next to a T2 across the T2's transversal edge moves into the T2's
        // redundant slot (the slot of its first ring edge).
        let ring_next = |v: u32| rings.next(v);
        let redundant_slot = |slot: usize| {
            // A T2 in slot (v, side) is redundant when its tip is v.n.n.
            let v = (slot / 2) as u32;
            lr[slot] == ring_next(ring_next(v))
        };
        // T2 triangle -> its redundant slot.
        let mut t2_redundant = vec![NONE; nt_real];
        for slot in 0..lr.len() {
            let tip = slot_tip_corner[slot];
            if tip != NONE && slots_of[tip as usize / 3] == 2 && redundant_slot(slot) {
                t2_redundant[tip as usize / 3] = slot as u32;
            }
        }
        let t2_redundant_slot = t2_redundant.clone();
        let mut is_t0 = vec![false; nt_real];
        let mut t0_count = 0u32;
        for t in 0..nt_real {
            if slots_of[t] == 0 {
                is_t0[t] = true;
                t0_count += 1;
            }
        }
        let mut t0_wart = 0u32;
        for t in 0..nt_real {
            if !is_t0[t] {
                continue;
            }
            for i in 0..3 {
                let k = 3 * t as u32 + i;
                let u = mesh.o[k as usize] / 3;
                if u >= mesh.real_triangles {
                    continue;
                }
                let slot = t2_redundant[u as usize];
                if slot == NONE {
                    continue;
                }
                // The slot now holds the T0, with k (facing the shared edge) as its tip corner.
                let slot = slot as usize;
                t2_redundant[u as usize] = NONE;
                lr[slot] = vertex_of(mesh.v[k as usize]) | WART;
                slot_tip_corner[slot] = k;
                is_t0[t] = false;
                t0_wart += 1;
                break;
            }
        }

        // A slot whose tip merely looks like a redundant T2's (pseudo-manifold input can have
        // two triangles on the same three vertices) is made irregular, which makes it
        // canonical; its record's opposites are filled in below.
        let mut lr_struct = Lr {
            lr,
            vo_v: Vec::with_capacity(3 * t0_count as usize),
            vo_o: Vec::new(),
            vo_star: Vec::new(),
            c: Vec::new(),
            rings,
            m_r,
            m: real_vertices,
            counts: LrCounts::default(),
            vertex_input: Vec::new(),
            triangle_input: Vec::new(),
            input_vertex_lr: Vec::new(),
            input_triangle_lr: Vec::new(),
            kept_aside: ct.kept_aside().to_vec(),
        };
        let mut false_redundant = Vec::new();
        for slot in 0..lr_struct.lr.len() {
            let tip = slot_tip_corner[slot];
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip != NONE
                && lr_struct.redundant(v, side)
                && t2_redundant_slot[tip as usize / 3] != slot as u32
            {
                lr_struct.make_irregular(slot, NONE, NONE);
                false_redundant.push(slot);
            }
        }

        // Corner ids: canonical slots, then T0 triangles into VO.
        let t0_list: Vec<u32> = (0..nt_real as u32).filter(|&t| is_t0[t as usize]).collect();
        let mut ct_to_lr = vec![NONE; 3 * nt_real];
        let base = 8 * m_r;
        for (j, &t) in t0_list.iter().enumerate() {
            for i in 0..3 {
                ct_to_lr[3 * t as usize + i] = base + 4 * j as u32 + i as u32;
            }
        }
        for slot in 0..lr_struct.lr.len() {
            let tip = slot_tip_corner[slot];
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || lr_struct.redundant(v, side) {
                continue;
            }
            let offsets = if side == LEFT { [0, 1, 2] } else { [6, 5, 4] };
            for (k, ct_corner) in slot_corners(tip, side).into_iter().enumerate() {
                ct_to_lr[ct_corner as usize] = 8 * v + offsets[k];
            }
        }
        let truth_o = |ct_corner: u32| match ct.o_table()[ct_corner as usize] {
            NONE => NONE,
            d => ct_to_lr[d as usize],
        };
        for &t in &t0_list {
            for i in 0..3 {
                let c = 3 * t + i;
                lr_struct.vo_v.push(vertex_of(mesh.v[c as usize]));
                lr_struct.vo_o.push(truth_o(c));
            }
        }

        // The two transversal corners of a slot: left 0 and 2, right 4 and 6.
        let transversal = |tip: u32, side: usize| {
            let [at_v, _, at_far] = slot_corners(tip, side);
            if side == LEFT {
                (at_v, at_far)
            } else {
                (at_far, at_v)
            }
        };
        let false_redundant_count = false_redundant.len() as u32;
        for slot in false_redundant {
            let (a, b) = transversal(slot_tip_corner[slot], slot % 2);
            let record = 3 * (lr_struct.lr[slot] & VALUE) as usize;
            lr_struct.vo_star[record + 1] = truth_o(a);
            lr_struct.vo_star[record + 2] = truth_o(b);
        }
        // Every other slot whose inferred opposites differ from the table's is irregular.
        let mut irregular_without_t0 = false_redundant_count;
        for slot in 0..lr_struct.lr.len() {
            let tip = slot_tip_corner[slot];
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || lr_struct.redundant(v, side) {
                continue;
            }
            let (a, b) = transversal(tip, side);
            let (ia, ib) = if side == LEFT { (0, 2) } else { (4, 6) };
            if lr_struct.opposite_raw(8 * v + ia) != truth_o(a)
                || lr_struct.opposite_raw(8 * v + ib) != truth_o(b)
            {
                let in_vo = |o: u32| o != NONE && o >= base;
                if !in_vo(truth_o(a)) && !in_vo(truth_o(b)) {
                    irregular_without_t0 += 1;
                }
                lr_struct.make_irregular(slot, truth_o(a), truth_o(b));
            }
        }

        // C table and the maps back to the input.
        let m = real_vertices;
        lr_struct.c = vec![NONE; (m - m_r) as usize];
        lr_struct.vertex_input = vec![0; m as usize];
        for x in 0..m {
            let id = lr_vertex[x as usize];
            lr_struct.vertex_input[id as usize] = ct.original_vertex(Vertex(x)).0;
            if id >= m_r {
                let c = ct.c_table()[x as usize];
                lr_struct.c[(id - m_r) as usize] = if c == NONE {
                    NONE
                } else {
                    ct_to_lr[c as usize]
                };
            }
        }
        lr_struct.input_vertex_lr = vec![NONE; ct.input_vertex_count() as usize];
        for x in (0..m).rev() {
            lr_struct.input_vertex_lr[ct.original_vertex(Vertex(x)).idx()] = lr_vertex[x as usize];
        }
        lr_struct.triangle_input = vec![NONE; 2 * m_r as usize + t0_list.len()];
        lr_struct.input_triangle_lr = vec![NONE; nt_real + ct.kept_aside().len()];
        for t in 0..nt_real {
            let id = ct_to_lr[3 * t] / 4;
            let input = ct.input_triangle(Triangle(t as u32));
            lr_struct.triangle_input[id as usize] = input;
            lr_struct.input_triangle_lr[input as usize] = id;
        }
        lr_struct.counts = LrCounts {
            triangles: nt_real as u32,
            vertices: m,
            ring_vertices: m_r,
            rings: lr_struct.rings.count() as u32,
            t0: t0_count - t0_wart,
            t0_wart,
            irregular: lr_struct.vo_star.len() as u32 / 3,
            irregular_without_t0,
        };
        Ok(lr_struct)
    }

    /// Gives slot `slot` a VO* record `(tip, o_a, o_b)` and the IRREGULAR flag.
    fn make_irregular(&mut self, slot: usize, o_a: u32, o_b: u32) {
        let entry = self.lr[slot];
        if entry & IRREGULAR != 0 {
            return;
        }
        let record = self.vo_star.len() as u32 / 3;
        self.vo_star.extend_from_slice(&[entry & VALUE, o_a, o_b]);
        self.lr[slot] = IRREGULAR | (entry & WART) | record;
    }

    /// The Table 1 counts of this LR.
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
        &self.kept_aside
    }

    /// The input triangles, in input order, from the LR alone. Each comes back with the same
    /// orientation, possibly rotated (an LR triangle starts at its ring vertex).
    pub fn input_triangles(&self) -> Vec<[u32; 3]> {
        let mut out = vec![[0u32; 3]; self.input_triangle_lr.len()];
        for t in self.triangles() {
            let [a, b, c] = self.triangle_vertices(t).map(|v| self.input_vertex(v));
            out[self.input_triangle(t) as usize] = [a, b, c];
        }
        for &(input, tri) in &self.kept_aside {
            out[input as usize] = tri;
        }
        out
    }

    /// The rings.
    pub fn rings(&self) -> &Rings {
        &self.rings
    }

    #[inline(always)]
    fn entry(&self, v: u32, side: usize) -> u32 {
        self.lr[2 * v as usize + side]
    }

    /// The tip vertex of slot `(v, side)` (`NULL` when that right triangle does not exist).
    #[inline(always)]
    fn tip(&self, v: u32, side: usize) -> u32 {
        let e = self.entry(v, side);
        if e & IRREGULAR != 0 {
            self.vo_star[3 * (e & VALUE) as usize]
        } else {
            e & VALUE
        }
    }

    #[inline(always)]
    fn wart(&self, v: u32, side: usize) -> bool {
        self.entry(v, side) & WART != 0
    }

    /// The slot's third vertex: `v.n`, or `v.n.n` in a wart slot (the skipped ring).
    #[inline(always)]
    fn far(&self, v: u32, side: usize) -> u32 {
        let n = self.rings.next(v);
        if self.wart(v, side) {
            self.rings.next(n)
        } else {
            n
        }
    }

    /// Whether slot `(v, side)` is the redundant copy of a T2 (its first ring edge).
    #[inline(always)]
    fn redundant(&self, v: u32, side: usize) -> bool {
        let e = self.entry(v, side);
        e & (IRREGULAR | WART) == 0 && e == self.rings.next(self.rings.next(v))
    }

    /// Maps a corner of a redundant T2 copy to the same corner of the canonical slot.
    #[inline(always)]
    fn canonical(&self, c: u32) -> u32 {
        if c >= 8 * self.m_r {
            return c;
        }
        let (v, i) = (c >> 3, c & 7);
        let side = (i >> 2) as usize;
        if !self.redundant(v, side) {
            return c;
        }
        let w = self.rings.next(v);
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
                8 * self.rings.next(v) + 4
            } else if self.tip(v, RIGHT) == NULL {
                NONE
            } else {
                self.canonical(8 * v + 5)
            }
        } else if self.wart(v, LEFT) {
            8 * self.rings.next(v) + 2
        } else {
            self.canonical(8 * v + 1)
        }
    }

    /// A left triangle holding half-edge `y -> x` (facing an edge `x -> y` of a left
    /// triangle): the corner facing it, or `NONE`.
    #[inline(always)]
    fn find_left(&self, x: u32, y: u32) -> u32 {
        if y < self.m_r && self.tip(y, LEFT) == x {
            return self.canonical(8 * y + 2);
        }
        if x < self.m_r {
            let p = self.rings.prev(x);
            if !self.wart(p, LEFT) && self.tip(p, LEFT) == y {
                return self.canonical(8 * p);
            }
            let pp = self.rings.prev(p);
            if self.wart(pp, LEFT) && self.tip(pp, LEFT) == y {
                return self.canonical(8 * pp);
            }
        }
        NONE
    }

    /// A right triangle holding half-edge `y -> x`: the corner facing it, or `NONE`.
    #[inline(always)]
    fn find_right(&self, x: u32, y: u32) -> u32 {
        if x < self.m_r && self.tip(x, RIGHT) == y {
            return self.canonical(8 * x + 4);
        }
        if y < self.m_r {
            let p = self.rings.prev(y);
            if !self.wart(p, RIGHT) && self.tip(p, RIGHT) == x {
                return self.canonical(8 * p + 6);
            }
            let pp = self.rings.prev(p);
            if self.wart(pp, RIGHT) && self.tip(pp, RIGHT) == x {
                return self.canonical(8 * pp + 6);
            }
        }
        NONE
    }

    /// `c.o` for a canonical corner, as a raw id (`NONE` on a boundary).
    #[inline(always)]
    fn opposite_raw(&self, c: u32) -> u32 {
        if c >= 8 * self.m_r {
            return self.vo_o[(c - c / 4 - 6 * self.m_r) as usize];
        }
        let (v, i) = (c >> 3, c & 7);
        let side = (i >> 2) as usize;
        let e = self.entry(v, side);
        let wart = e & WART != 0;
        if i == 1 || i == 5 {
            // The corner facing the ring edge (or, in a wart slot, the wart's edge).
            return if wart {
                8 * self.rings.next(v) + if side == LEFT { 0 } else { 6 }
            } else {
                self.across(v, side)
            };
        }
        if e & IRREGULAR != 0 {
            let record = 3 * (e & VALUE) as usize;
            let second = (i == 2 || i == 6) as usize;
            return self.vo_star[record + 1 + second];
        }
        let tip = e & VALUE;
        let p = self.rings.prev(v);
        // A canonical T2 (v.p, v, v.n): tip v.p; one of its corners faces ring edge (v.p, v).
        let t2 = !wart && tip == p;
        match i {
            0 if t2 && self.wart(p, LEFT) => 8 * p + 1,
            0 => self.find_left(tip, self.far(v, side)),
            2 if t2 => self.across(p, LEFT),
            2 => self.find_left(v, tip),
            4 if t2 => self.across(p, RIGHT),
            4 => self.find_right(tip, v),
            6 if t2 && self.wart(p, RIGHT) => 8 * p + 5,
            _ => self.find_right(self.far(v, side), tip),
        }
    }

    /// Whether `t` is a canonical triangle id (not a redundant copy, unused or a missing right
    /// triangle).
    pub fn is_triangle(&self, t: Triangle) -> bool {
        let t = t.0;
        if t >= 2 * self.m_r {
            return ((t - 2 * self.m_r) as usize) < self.vo_v.len() / 3;
        }
        let (v, side) = (t / 2, (t % 2) as usize);
        self.tip(v, side) != NULL && !self.redundant(v, side)
    }

    /// Storage of the LR tables in 32-bit references (the rpt numerator).
    pub fn references(&self) -> u64 {
        (self.lr.len() + self.vo_v.len() + self.vo_o.len() + self.vo_star.len() + self.c.len())
            as u64
    }
}

fn reset(comp: &Component, vm: &mut [bool], tm: &mut [bool]) {
    for &x in &comp.vertices {
        vm[x as usize] = false;
    }
    for &t in &comp.triangles {
        tm[t as usize] = false;
    }
}

impl CornerOps for Lr {
    fn vertex_id_bound(&self) -> u32 {
        self.m
    }

    fn triangle_id_bound(&self) -> u32 {
        2 * self.m_r + (self.vo_v.len() / 3) as u32
    }

    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_ {
        (0..self.triangle_id_bound())
            .map(Triangle)
            .filter(|&t| self.is_triangle(t))
    }

    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_ {
        (0..self.m).map(Vertex)
    }

    #[inline]
    fn vertex(&self, c: Corner) -> Vertex {
        let c = c.0;
        if c >= 8 * self.m_r {
            return Vertex(self.vo_v[(c - c / 4 - 6 * self.m_r) as usize]);
        }
        let v = c >> 3;
        Vertex(match c & 7 {
            0 | 6 => v,
            1 => self.tip(v, LEFT),
            2 => self.far(v, LEFT),
            4 => self.far(v, RIGHT),
            _ => self.tip(v, RIGHT),
        })
    }

    #[inline]
    fn triangle(&self, c: Corner) -> Triangle {
        Triangle(c.0 >> 2)
    }

    #[inline]
    fn next(&self, c: Corner) -> Corner {
        Corner(if c.0 & 3 == 2 { c.0 - 2 } else { c.0 + 1 })
    }

    #[inline]
    fn prev(&self, c: Corner) -> Corner {
        Corner(if c.0 & 3 == 0 { c.0 + 2 } else { c.0 - 1 })
    }

    #[inline]
    fn opposite(&self, c: Corner) -> Option<Corner> {
        match self.opposite_raw(c.0) {
            NONE => None,
            d => Some(Corner(d)),
        }
    }

    #[inline]
    fn vertex_corner(&self, v: Vertex) -> Option<Corner> {
        if v.0 >= self.m_r {
            return match self.c[(v.0 - self.m_r) as usize] {
                NONE => None,
                c => Some(Corner(c)),
            };
        }
        Some(Corner(self.canonical(8 * v.0)))
    }

    #[inline]
    fn triangle_corner(&self, t: Triangle) -> Corner {
        Corner(4 * t.0)
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
        writeln!(f, "  references per triangle  {:.3}", self.rpt)
    }
}
