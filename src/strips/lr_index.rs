//! The LR as a rendering index list (LR paper, section 7).
//!
//! Ring vertices are consecutive, so they need not be written: each ring edge `(v, v.n)` gets
//! two references, the tips of its left triangle `(v, tip, v.n)` and of its right triangle
//! `(v.n, tip, v)`, in ring order; T0 triangles follow verbatim, three references each. A
//! slot without a triangle of its own (the redundant copy of a T2, or a missing right
//! triangle on a boundary) holds `v` itself, which would make a zero-area triangle; a slot
//! holding a wart (a T0 triangle in a T2's redundant slot) has [`INDEX_WART`] set, and its far
//! vertex is `v.n.n`. That is about one reference per triangle, against three for a triangle
//! list.
//!
//! [`LrIndexList::triangle_list`] expands it into a plain triangle list (what a geometry shader
//! would emit), in the LR's vertex numbering: a vertex buffer permuted by
//! [`Lr::input_vertex`] draws it.

use crate::lr::{Lr, LrLayout};
use crate::words::Words;

/// Offsets of a ring edge's left and right slots.
const LEFT: usize = 0;
const RIGHT: usize = 1;

/// Flag of a tip reference: the slot holds a wart, whose far vertex is `v.n.n`.
pub const INDEX_WART: u32 = 1 << 31;

/// An LR written as a rendering index list (see the module documentation).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct LrIndexList {
    ring_starts: Vec<u32>,
    tips: Vec<u32>,
    t0: Vec<u32>,
    triangles: u32,
}

/// Writes `lr` as a rendering index list.
pub fn lr_index_list(lr: &Lr) -> LrIndexList {
    let tables = lr.tables();
    let m_r = tables.ring_vertices();
    let mut tips = Vec::with_capacity(2 * m_r as usize);
    for v in 0..m_r {
        for side in [LEFT, RIGHT] {
            if tables.slot_is_triangle(v, side) {
                let wart = if tables.wart(v, side) { INDEX_WART } else { 0 };
                tips.push(tables.tip(v, side) | wart);
            } else {
                tips.push(v);
            }
        }
    }
    let ring_starts = (0..tables.ring_starts.count())
        .map(|i| tables.ring_starts.at(i))
        .collect();
    let t0 = (0..tables.vo_v.count())
        .map(|i| tables.vo_v.at(i))
        .collect();
    LrIndexList {
        ring_starts,
        tips,
        t0,
        triangles: lr.counts().triangles,
    }
}

impl LrIndexList {
    /// The first vertex of each ring, then the number of ring vertices.
    pub fn ring_starts(&self) -> &[u32] {
        &self.ring_starts
    }

    /// Two tip references per ring vertex: left slot, right slot.
    pub fn tips(&self) -> &[u32] {
        &self.tips
    }

    /// The T0 triangles, three vertices each.
    pub fn t0(&self) -> &[u32] {
        &self.t0
    }

    /// References stored: ring starts, tips and T0 vertices.
    pub fn references(&self) -> usize {
        self.ring_starts.len() + self.tips.len() + self.t0.len()
    }

    /// References per triangle of the LR (0 without triangles).
    pub fn references_per_triangle(&self) -> f64 {
        self.references() as f64 / self.triangles.max(1) as f64
    }

    /// The triangles as a triangle list (three indices each) in the LR's vertex ids: per ring
    /// vertex its left then its right triangle, then the T0 triangles. Slots without a triangle
    /// are left out.
    pub fn triangle_list(&self) -> Vec<u32> {
        let mut out = Vec::with_capacity(3 * self.triangles as usize);
        for ring in self.ring_starts.windows(2) {
            let (first, end) = (ring[0], ring[1]);
            let next = |v: u32| if v + 1 >= end { first } else { v + 1 };
            for v in first..end {
                for side in [LEFT, RIGHT] {
                    let Some(&e) = self.tips.get(2 * v as usize + side) else {
                        continue;
                    };
                    let tip = e & !INDEX_WART;
                    if tip == v {
                        continue;
                    }
                    let far = if e & INDEX_WART != 0 {
                        next(next(v))
                    } else {
                        next(v)
                    };
                    if side == LEFT {
                        out.extend_from_slice(&[v, tip, far]);
                    } else {
                        out.extend_from_slice(&[far, tip, v]);
                    }
                }
            }
        }
        out.extend_from_slice(&self.t0[..self.t0.len() / 3 * 3]);
        out
    }
}
