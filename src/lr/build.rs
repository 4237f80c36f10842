//! Construction of the LR from a corner table: closing boundaries with dummy vertices,
//! RING-EXPANDER per component, triangle classes, warts, and irregular records.

use super::closed::{next3, prev3};
use super::ring::{Prepared, Rings};
use super::tables::{
    boundaries_on_ring_given, ring_bits, LrLayout, LrTables, LEFT, NULL, RIGHT, VALUE, WART,
};
use super::{InputMaps, Lr, LrCounts, LrOptions, OpenFans};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ids::{Triangle, Vertex};

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
    /// [`Error::Unsupported`] when the mesh exceeds the id space (`2^30 - 2` vertices, corner
    /// ids below `2^32`).
    pub fn build(ct: &CornerTable, options: &LrOptions) -> Result<Lr> {
        Lr::build_with_period(ct, options, 0)
    }

    /// Builds the LR with HYBRID-RING-EXPANDER of period `period` (section 6.1), or with
    /// RING-EXPANDER (depth first) for `period = 0`.
    pub fn build_with_period(ct: &CornerTable, options: &LrOptions, period: u32) -> Result<Lr> {
        let prepared = Prepared::new(ct)?;
        let rings = prepared.rings(period, options);
        Lr::from_rings(ct, prepared, rings, options)
    }

    /// [`Lr::build`] for an encoder that keeps only the counts and the maps to the input
    /// ([`Lr::into_input_maps`]): the maps from the input are left empty, so the result
    /// must not answer [`Lr::lr_vertex`] or [`Lr::lr_triangle`].
    pub(crate) fn build_for_encoding(ct: &CornerTable, options: &LrOptions) -> Result<Lr> {
        let prepared = Prepared::new(ct)?;
        let rings = prepared.rings(0, options);
        Lr::for_encoding_from_rings(ct, prepared, rings, options)
    }

    /// [`Lr::from_rings`] for an encoder, as [`Lr::build_for_encoding`].
    pub(super) fn for_encoding_from_rings(
        ct: &CornerTable,
        prepared: Prepared,
        rings: Rings,
        options: &LrOptions,
    ) -> Result<Lr> {
        Ok(Lr::tables_from_rings(ct, prepared, rings, options)?.finish_with(ct, false))
    }

    /// The LR of `ct` with the rings `rings` of its closed mesh `prepared`.
    fn from_rings(
        ct: &CornerTable,
        prepared: Prepared,
        rings: Rings,
        options: &LrOptions,
    ) -> Result<Lr> {
        Ok(Lr::tables_from_rings(ct, prepared, rings, options)?.finish(ct))
    }

    /// The LR of `ct`, taking the table so that its `V` and `O` are freed before the maps
    /// back to the input are made (an encoder's peak memory is there otherwise).
    ///
    /// # Errors
    /// As [`Lr::build`].
    pub(crate) fn build_owned(mut ct: CornerTable, options: &LrOptions) -> Result<Lr> {
        let prepared = Prepared::new(&ct)?;
        let rings = prepared.rings(0, options);
        let partial = Lr::tables_from_rings(&ct, prepared, rings, options)?;
        ct.free_corners();
        Ok(partial.finish(&ct))
    }

    /// The tables of the LR of `ct` with the rings `rings` of its closed mesh `prepared`.
    /// Each working array is freed once the steps after it no longer read it, and the
    /// components first: the encoder's peak memory is here.
    fn tables_from_rings(
        ct: &CornerTable,
        prepared: Prepared,
        rings: Rings,
        options: &LrOptions,
    ) -> Result<Partial> {
        let mesh = prepared.into_closed();
        let real_vertices = mesh.real_vertices;
        let Rings {
            ring_corner,
            starts,
            ring_id,
            ..
        } = rings;
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
            open_fans: None,
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
            let r = mesh.o(c);
            for (side, tip) in [(LEFT, c), (RIGHT, r)] {
                let t = tip / 3;
                if t < mesh.real_triangles {
                    slots_of[t as usize] += 1;
                    tables.lr[2 * v + side] = vertex_of(mesh.v(tip));
                    slot_tip_corner[2 * v + side] = tip;
                } else {
                    tables.lr[2 * v + side] = NULL;
                }
            }
        }
        drop(ring_corner);

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
        let mut is_t0 = vec![false; nt_real];
        let mut t0_count = 0u32;
        for t in 0..nt_real {
            if slots_of[t] == 0 {
                is_t0[t] = true;
                t0_count += 1;
            }
        }
        drop(slots_of);
        let mut t0_wart = 0u32;
        let t0_before_warts: Vec<usize> = (0..nt_real).filter(|&t| is_t0[t]).collect();
        for t in t0_before_warts {
            for i in 0..3 {
                let k = 3 * t as u32 + i;
                let u = mesh.o(k) / 3;
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
                tables.lr[slot] = vertex_of(mesh.v(k)) | WART;
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
            maps: InputMaps {
                kept_aside: ct.kept_aside().to_vec(),
                ..InputMaps::default()
            },
            input_vertex_lr: Vec::new(),
            input_triangle_lr: Vec::new(),
        };
        let mut false_redundant = Vec::new();
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip != NONE
                && lr_struct.tables.redundant(v, side)
                && t2_redundant[tip as usize / 3] != slot as u32
            {
                lr_struct.make_irregular(slot, NONE, NONE);
                false_redundant.push(slot);
            }
        }

        drop(t2_redundant);
        // Corner ids: canonical slots, then T0 triangles into VO.
        let t0_list: Vec<u32> = (0..nt_real as u32).filter(|&t| is_t0[t as usize]).collect();
        drop(is_t0);
        // Per table triangle, its LR corners: `4·id + s`, corner `c` of the table becoming LR
        // corner `4·id + (c mod 3 + s) mod 3`; 4 bytes per triangle where a map per corner
        // takes 12. A slot triangle's corners at v, the tip and the far vertex are its LR
        // corners 0, 1, 2 on the left (`8v + 0..=2`) and 2, 1, 0 on the right (`8v + 6..=4`,
        // see [`slot_corners`]): either way the tip (position `r` in its triangle) is corner
        // 1, so `s = (1 - r) mod 3`. A T0 keeps its corner order (`s = 0`).
        let mut triangle_lr = vec![NONE; nt_real];
        let base = 8 * m_r;
        for (j, &t) in t0_list.iter().enumerate() {
            triangle_lr[t as usize] = base + 4 * j as u32;
        }
        for (slot, &tip) in slot_tip_corner.iter().enumerate() {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || lr_struct.tables.redundant(v, side) {
                continue;
            }
            triangle_lr[tip as usize / 3] = 8 * v + 4 * side as u32 + (4 - tip % 3) % 3;
        }
        let ct_to_lr = |c: u32| match triangle_lr[c as usize / 3] {
            NONE => NONE,
            w => (w & !3) + (c % 3 + (w & 3)) % 3,
        };
        let truth_o = |ct_corner: u32| match ct.o_table()[ct_corner as usize] {
            NONE => NONE,
            d => ct_to_lr(d),
        };
        for &t in &t0_list {
            for i in 0..3 {
                let c = 3 * t + i;
                lr_struct.tables.vo_v.push(vertex_of(mesh.v(c)));
                lr_struct.tables.vo_o.push(truth_o(c));
            }
        }
        // The closed tables (a copy of the table's on a mesh with boundaries) are not read
        // again.
        drop(mesh);

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
        // Making a slot irregular keeps its tip and flags, so no other slot's inference
        // changes: the slots are searched in parallel chunks and recorded in order.
        let tables = &lr_struct.tables;
        let check = |slot: usize| {
            let tip = slot_tip_corner[slot];
            let (v, side) = ((slot / 2) as u32, slot % 2);
            if tip == NONE || tables.redundant(v, side) {
                return None;
            }
            let (a, b) = transversal(tip, side);
            let (ia, ib) = if side == LEFT { (0, 2) } else { (4, 6) };
            let (oa, ob) = (truth_o(a), truth_o(b));
            (tables.opposite_raw(8 * v + ia) != oa || tables.opposite_raw(8 * v + ib) != ob)
                .then_some((slot, oa, ob))
        };
        let slots = slot_tip_corner.len();
        let irregular = parallel_chunks(slots, options.threads, "LR tables", |range| {
            let start = range.start;
            let checked = range.inspect(|&slot| crate::progress::tick(slot - start));
            checked.filter_map(check).collect::<Vec<_>>()
        });
        let mut irregular_without_t0 = false_redundant_count;
        for (slot, oa, ob) in irregular.into_iter().flatten() {
            let in_vo = |o: u32| o != NONE && o >= base;
            if !in_vo(oa) && !in_vo(ob) {
                irregular_without_t0 += 1;
            }
            lr_struct.make_irregular(slot, oa, ob);
        }

        drop(slot_tip_corner);
        // Every opposite now agrees with the table's, so the corners without one are the
        // table's boundary corners.
        let without_opposite = ct.o_table().iter().filter(|&&o| o == NONE).count();
        lr_struct.tables.boundaries_on_ring =
            boundaries_on_ring_given(&lr_struct.tables, without_opposite);
        // While the corner table still has its opposites (`build_owned` frees them next).
        lr_struct.tables.open_fans = open_fans(&lr_struct.tables, ct, &lr_vertex, ct_to_lr);
        lr_struct.maps.counts = LrCounts {
            triangles: nt_real as u32,
            vertices: real_vertices,
            ring_vertices: m_r,
            rings: lr_struct.tables.ring_count() as u32,
            t0: t0_count - t0_wart,
            t0_wart,
            irregular: lr_struct.tables.vo_star.len() as u32 / 3,
            irregular_without_t0,
        };
        Ok(Partial {
            lr: lr_struct,
            lr_vertex,
            triangle_lr,
        })
    }
}

/// An LR whose tables are done but not yet its C table and maps back to the input: all that
/// is left to read of the corner table is its vertex copies, C and triangle order, so an
/// owner of the table may free its `V` and `O` first ([`Lr::build_owned`]).
pub(super) struct Partial {
    lr: Lr,
    /// Per table vertex, its LR id.
    lr_vertex: Vec<u32>,
    /// Per table triangle, its LR corners: `4·id + s` (see `from_rings`).
    triangle_lr: Vec<u32>,
}

impl Partial {
    /// The LR: its C table and the maps back to the input, each working array freed once
    /// read.
    pub(super) fn finish(self, ct: &CornerTable) -> Lr {
        self.finish_with(ct, true)
    }

    /// [`Partial::finish`], with the maps from the input only when `from_input`.
    fn finish_with(self, ct: &CornerTable, from_input: bool) -> Lr {
        let Partial {
            lr: mut lr_struct,
            lr_vertex,
            triangle_lr,
        } = self;
        let m = lr_struct.maps.counts.vertices;
        let m_r = lr_struct.maps.counts.ring_vertices;
        let ct_to_lr = |c: u32| match triangle_lr[c as usize / 3] {
            NONE => NONE,
            w => (w & !3) + (c % 3 + (w & 3)) % 3,
        };
        lr_struct.tables.c = vec![NONE; (m - m_r) as usize];
        lr_struct.maps.vertex_input = vec![0; m as usize];
        for x in 0..m {
            let id = lr_vertex[x as usize];
            lr_struct.maps.vertex_input[id as usize] = ct.original_vertex(Vertex(x)).0;
            if id >= m_r {
                let c = ct.c_table()[x as usize];
                lr_struct.tables.c[(id - m_r) as usize] =
                    if c == NONE { NONE } else { ct_to_lr(c) };
            }
        }
        if from_input {
            lr_struct.input_vertex_lr = vec![NONE; ct.input_vertex_count() as usize];
            for x in (0..m).rev() {
                let input = ct.original_vertex(Vertex(x)).idx();
                lr_struct.input_vertex_lr[input] = lr_vertex[x as usize];
            }
        }
        drop(lr_vertex);
        let ids = 2 * m_r as usize + lr_struct.tables.t0_count() as usize;
        lr_struct.maps.triangle_input = vec![NONE; ids];
        for (t, &w) in triangle_lr.iter().enumerate() {
            lr_struct.maps.triangle_input[(w / 4) as usize] = ct.input_triangle(Triangle(t as u32));
        }
        drop(triangle_lr);
        if !from_input {
            return lr_struct;
        }
        // The inverse of `triangle_input` (ids of redundant slots and missing right
        // triangles hold NONE).
        let inputs = lr_struct.maps.counts.triangles as usize + ct.kept_aside().len();
        lr_struct.input_triangle_lr = vec![NONE; inputs];
        for (id, &input) in lr_struct.maps.triangle_input.iter().enumerate() {
            if input != NONE {
                lr_struct.input_triangle_lr[input as usize] = id as u32;
            }
        }
        lr_struct
    }
}

/// The list of open fans of `tables` (FORMAT.md §3.5.1), read from the corner table `ct`
/// whose vertex `x` is LR vertex `lr_vertex[x]` and whose corner `c` is LR corner
/// `ct_to_lr(c)`: every ring vertex whose fan is open, but those whose fan `v.c` starts
/// after a boundary ring edge, with the table's `v.c` (its fan's start). `None` when `v.c`
/// needs no list: every boundary on the ring and no such vertex.
fn open_fans(
    tables: &LrTables<Vec<u32>>,
    ct: &CornerTable,
    lr_vertex: &[u32],
    ct_to_lr: impl Fn(u32) -> u32,
) -> Option<OpenFans<Vec<u32>>> {
    let m_r = tables.m_r;
    let (c_table, o_table) = (ct.c_table(), ct.o_table());
    let mut pairs = Vec::new();
    for (x, &v) in lr_vertex.iter().enumerate() {
        let c = c_table[x];
        if v >= m_r || c == NONE {
            continue;
        }
        let prev = prev3(c);
        let u = tables.ring_prev(v);
        let after_boundary_edge = tables.right_is_null(u) && !tables.wart(u, LEFT);
        if o_table[prev as usize] == NONE && !after_boundary_edge {
            pairs.push((v, ct_to_lr(c)));
        }
    }
    if pairs.is_empty() && tables.boundaries_on_ring {
        return None;
    }
    pairs.sort_unstable();
    Some(OpenFans::from_pairs(&pairs, m_r))
}

/// Slots per thread below which a search stays on the calling thread.
const PARALLEL_SLOTS: usize = 1 << 16;

/// `work` over `0..n` split into contiguous chunks, one per thread (up to `threads`), the
/// results in the order of the chunks. The calling thread takes the first chunk: the phase
/// `phase` it announces is that chunk's progress (the others run alongside).
fn parallel_chunks<T: Send>(
    n: usize,
    threads: u32,
    phase: &str,
    work: impl Fn(std::ops::Range<usize>) -> T + Sync,
) -> Vec<T> {
    let chunks = (threads.max(1) as usize)
        .min(n.div_ceil(PARALLEL_SLOTS))
        .max(1);
    let size = n.div_ceil(chunks);
    crate::progress::phase(phase, size as u64);
    let work = &work;
    std::thread::scope(|scope| {
        let handles: Vec<_> = (1..chunks)
            .map(|k| scope.spawn(move || work(k * size..n.min((k + 1) * size))))
            .collect();
        let first = work(0..n.min(size));
        // A worker only panics on a broken invariant: pass it on.
        let rest = handles.into_iter().map(|h| h.join().expect("LR worker"));
        std::iter::once(first).chain(rest).collect()
    })
}
