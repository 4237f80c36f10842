//! Construction of the LR from a corner table: closing boundaries with dummy vertices,
//! RING-EXPANDER per component, triangle classes, warts, and irregular records.

use super::tables::{
    find_boundaries_on_ring, ring_bits, LrLayout, LrTables, LEFT, NULL, RIGHT, VALUE, WART,
};
use super::{Lr, LrCounts, LrOptions};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ids::{Triangle, Vertex};
use crate::ops::CornerOps;
use crate::rng::Rng;

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
            return Err(Error::Unsupported("mesh too large for LR".into()));
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

/// HYBRID-RING-EXPANDER (section 6.1) with period `period`: the invasion proceeds depth
/// first from a double-ended queue of candidate corners, but after every `period`-th invaded
/// triangle it resumes from the oldest candidate (breadth first), which bounds the length of
/// the corridors and so the ring offsets `v.l - v` and `v.r - v`. `period = 1` is breadth
/// first. Dummy vertices must already be marked visited.
fn hybrid_ring_expander(
    mesh: &Closed,
    s: u32,
    period: u32,
    vm: &mut [bool],
    tm: &mut [bool],
    deque: &mut std::collections::VecDeque<u32>,
) {
    let v = &mesh.v;
    vm[v[next3(s) as usize] as usize] = true;
    vm[v[prev3(s) as usize] as usize] = true;
    deque.clear();
    let mut invaded = 0u32;
    let mut c = s;
    loop {
        if !vm[v[c as usize] as usize] {
            vm[v[c as usize] as usize] = true;
            tm[c as usize / 3] = true;
            // c.l and c.r: the corners facing the two edges the invasion exposed.
            deque.push_back(mesh.o[next3(c) as usize]);
            deque.push_back(mesh.o[prev3(c) as usize]);
            invaded = (invaded + 1) % period;
        }
        let candidate = if invaded == 0 {
            deque.pop_front()
        } else {
            deque.pop_back()
        };
        match candidate {
            Some(next) => c = next,
            None => break,
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

/// Ring edges of real triangle `t`: edges to a neighbour on the other side of the ring.
fn ring_edges(mesh: &Closed, tm: &[bool], t: u32) -> usize {
    let inside = tm[t as usize];
    (0..3)
        .filter(|&i| tm[mesh.o[3 * t as usize + i] as usize / 3] != inside)
        .count()
}

/// T0 triangles of a component that no wart can take: those without a T2 neighbour. (A T2 has
/// one edge off the ring, so no two T0s compete for it, and every other T0 finds a wart.)
fn t0_after_warts(mesh: &Closed, comp: &Component, tm: &[bool]) -> usize {
    comp.real_triangles
        .iter()
        .filter(|&&t| {
            ring_edges(mesh, tm, t) == 0
                && (0..3).all(|i| {
                    let u = mesh.o[3 * t as usize + i] / 3;
                    u >= mesh.real_triangles || ring_edges(mesh, tm, u) != 2
                })
        })
        .count()
}

fn reset(comp: &Component, vm: &mut [bool], tm: &mut [bool]) {
    for &x in &comp.vertices {
        vm[x as usize] = false;
    }
    for &t in &comp.triangles {
        tm[t as usize] = false;
    }
}

impl Lr {
    /// Builds the LR of a corner table.
    ///
    /// # Errors
    /// [`Error::Unsupported`] when the mesh exceeds the id space (`2^30 - 2` vertices, corner
    /// ids below `2^32`).
    pub fn build(ct: &CornerTable, options: &LrOptions) -> Result<Lr> {
        Lr::build_with_period(ct, options, 0)
    }

    /// Builds the LR with HYBRID-RING-EXPANDER of period `period` (section 6.1), or with
    /// RING-EXPANDER (depth first) for `period = 0`.
    pub fn build_with_period(ct: &CornerTable, options: &LrOptions, period: u32) -> Result<Lr> {
        let mesh = Closed::new(ct)?;
        let mut deque = std::collections::VecDeque::new();
        let mut expand = |s: u32, vm: &mut [bool], tm: &mut [bool]| {
            if period == 0 {
                ring_expander(&mesh, s, vm, tm)
            } else {
                hybrid_ring_expander(&mesh, s, period, vm, tm, &mut deque)
            }
        };
        let real_vertices = mesh.real_vertices;
        if real_vertices >= NULL {
            return Err(Error::Unsupported(
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
            // Fewest isolated vertices first, then fewest T0 triangles left after wart
            // skipping (each costs its own six references and makes its neighbours irregular).
            let mut best: Option<((usize, usize), u32)> = None;
            for _ in 0..options.tries.max(1) {
                let t = comp.real_triangles[rng.below(comp.real_triangles.len() as u32) as usize];
                let s = 3 * t + rng.below(3);
                reset(&comp, &mut vm, &mut tm);
                expand(s, &mut vm, &mut tm);
                let isolated = comp.vertices.iter().filter(|&&x| !vm[x as usize]).count();
                let t0 = t0_after_warts(&mesh, &comp, &tm);
                if best.is_none_or(|(b, _)| (isolated, t0) < b) {
                    best = Some(((isolated, t0), s));
                }
            }
            let (_, s) = best.expect("at least one try");
            reset(&comp, &mut vm, &mut tm);
            expand(s, &mut vm, &mut tm);
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
            return Err(Error::Unsupported(
                "mesh too large for LR corner ids".into(),
            ));
        }
        let (ring_last, ring_rank) = ring_bits(&starts);
        let mut tables = LrTables {
            lr: vec![0u32; 2 * m_r as usize],
            vo_v: Vec::new(),
            vo_o: Vec::new(),
            vo_star: Vec::new(),
            c: Vec::new(),
            ring_starts: starts,
            ring_last,
            ring_rank,
            m_r,
            m: real_vertices,
            boundaries_on_ring: false,
        };

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
        let mut slot_tip_corner = vec![NONE; 2 * m_r as usize];
        for (v, &c) in ring_corner.iter().enumerate() {
            let r = mesh.o[c as usize];
            for (side, tip) in [(LEFT, c), (RIGHT, r)] {
                let t = tip / 3;
                if t < mesh.real_triangles {
                    slots_of[t as usize] += 1;
                    tables.lr[2 * v + side] = vertex_of(mesh.v[tip as usize]);
                    slot_tip_corner[2 * v + side] = tip;
                } else {
                    tables.lr[2 * v + side] = NULL;
                }
            }
        }

        // Warts: a T0 next to a T2 across the T2's transversal edge moves into the T2's
        // redundant slot (the slot of its first ring edge).
        // T2 triangle -> its redundant slot (the one whose tip is v.n.n).
        let mut t2_redundant = vec![NONE; nt_real];
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            if tip != NONE
                && slots_of[tip as usize / 3] == 2
                && tables.redundant((slot / 2) as u32, slot % 2)
            {
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
        let t0_before_warts: Vec<usize> = (0..nt_real).filter(|&t| is_t0[t]).collect();
        for t in t0_before_warts {
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
                tables.lr[slot] = vertex_of(mesh.v[k as usize]) | WART;
                slot_tip_corner[slot] = k;
                is_t0[t] = false;
                t0_wart += 1;
                break;
            }
        }

        // A slot whose tip merely looks like a redundant T2's (pseudo-manifold input can have
        // two triangles on the same three vertices) is made irregular, which makes it
        // canonical; its record's opposites are filled in below.
        tables.vo_v.reserve(3 * t0_count as usize);
        let mut lr_struct = Lr {
            tables,
            counts: LrCounts::default(),
            vertex_input: Vec::new(),
            triangle_input: Vec::new(),
            input_vertex_lr: Vec::new(),
            input_triangle_lr: Vec::new(),
            kept_aside: ct.kept_aside().to_vec(),
        };
        let mut false_redundant = Vec::new();
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip != NONE
                && lr_struct.tables.redundant(v, side)
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
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || lr_struct.tables.redundant(v, side) {
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
                lr_struct.tables.vo_v.push(vertex_of(mesh.v[c as usize]));
                lr_struct.tables.vo_o.push(truth_o(c));
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
            let record = 3 * (lr_struct.tables.lr[slot] & VALUE) as usize;
            lr_struct.tables.vo_star[record + 1] = truth_o(a);
            lr_struct.tables.vo_star[record + 2] = truth_o(b);
        }
        // Every other slot whose inferred opposites differ from the table's is irregular.
        let mut irregular_without_t0 = false_redundant_count;
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || lr_struct.tables.redundant(v, side) {
                continue;
            }
            let (a, b) = transversal(tip, side);
            let (ia, ib) = if side == LEFT { (0, 2) } else { (4, 6) };
            if lr_struct.tables.opposite_raw(8 * v + ia) != truth_o(a)
                || lr_struct.tables.opposite_raw(8 * v + ib) != truth_o(b)
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
        lr_struct.tables.c = vec![NONE; (m - m_r) as usize];
        lr_struct.vertex_input = vec![0; m as usize];
        for x in 0..m {
            let id = lr_vertex[x as usize];
            lr_struct.vertex_input[id as usize] = ct.original_vertex(Vertex(x)).0;
            if id >= m_r {
                let c = ct.c_table()[x as usize];
                lr_struct.tables.c[(id - m_r) as usize] = if c == NONE {
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
        lr_struct.tables.boundaries_on_ring = find_boundaries_on_ring(&lr_struct.tables);
        lr_struct.counts = LrCounts {
            triangles: nt_real as u32,
            vertices: m,
            ring_vertices: m_r,
            rings: lr_struct.tables.ring_count() as u32,
            t0: t0_count - t0_wart,
            t0_wart,
            irregular: lr_struct.tables.vo_star.len() as u32 / 3,
            irregular_without_t0,
        };
        Ok(lr_struct)
    }
}
