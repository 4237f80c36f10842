//! The corner table of an LR construction closed by a dummy vertex over each boundary loop,
//! so that RING-EXPANDER meets no boundary ([`super::ring`]).

use super::bits_and_ranks;
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ops::CornerOps;

/// The corner table closed by dummy vertices and triangles over each boundary loop. The
/// table's `V` and `O` are borrowed, not copied (they are most of an encode's memory): the
/// dummy triangles live in arrays of their own, and a boundary corner's opposite (`NONE` in
/// the table) is found by its rank among the boundary corners ([`BoundaryRank`]).
pub(super) struct Closed<'a> {
    real_v: &'a [u32],
    real_o: &'a [u32],
    /// `V` and `O` of the dummy triangles, from corner `3 · real_triangles` on.
    dummy_v: Vec<u32>,
    dummy_o: Vec<u32>,
    /// The ranks of the boundary corners: the one of rank `k` faces corner 2 of dummy
    /// triangle `real_triangles + k`.
    boundary: BoundaryRank,
    pub(super) real_triangles: u32,
    pub(super) real_vertices: u32,
    /// Real and dummy vertices.
    pub(super) total_vertices: u32,
}

pub(super) fn next3(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

pub(super) fn prev3(c: u32) -> u32 {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

impl<'a> Closed<'a> {
    /// Adds, for every boundary half-edge `a -> b` (facing corner `c`), a dummy triangle
    /// `(b, a, d)` where `d` is the dummy vertex of that boundary loop.
    pub(super) fn new(ct: &'a CornerTable) -> Result<Closed<'a>> {
        let (real_v, real_o) = (ct.v_table(), ct.o_table());
        let real_triangles = (real_v.len() / 3) as u32;
        let real_vertices = ct.vertex_id_bound();
        let boundary: Vec<u32> = (0..real_v.len() as u32)
            .filter(|&c| real_o[c as usize] == NONE)
            .collect();
        let ranks = BoundaryRank::new(real_o.len(), &boundary);
        let total = real_v.len() + 3 * boundary.len();
        if total >= (NONE / 2) as usize {
            return Err(Error::Unsupported("mesh too large for LR".into()));
        }
        let dummies = 3 * boundary.len();
        let (mut v, mut o) = (vec![NONE; dummies], vec![NONE; dummies]);
        // The boundary half-edge arriving at each vertex (one at most: one fan per vertex).
        let incoming_len = if dummies > 0 {
            real_vertices as usize
        } else {
            0
        };
        let mut incoming = vec![NONE; incoming_len];
        for &c in &boundary {
            incoming[real_v[prev3(c) as usize] as usize] = c;
        }
        // Dummy triangle k (of boundary corner k), at 3k in the dummy arrays.
        let rank = |c: u32| ranks.rank(c) as usize;
        let base_corner = 3 * real_triangles;
        for (k, &c) in boundary.iter().enumerate() {
            let (a, b) = (real_v[next3(c) as usize], real_v[prev3(c) as usize]);
            let base = 3 * k;
            v[base] = b;
            v[base + 1] = a;
            o[base + 2] = c;
            // Corner 0 (at b) faces a -> d: the dummy of the boundary half-edge into a.
            let before = rank(incoming[a as usize]);
            o[base] = base_corner + 3 * before as u32 + 1;
            o[3 * before + 1] = base_corner + base as u32;
        }
        drop(incoming);
        // One dummy vertex per loop: walk the loop through the corner-0/corner-1 links.
        let mut next_dummy_vertex = real_vertices;
        for k in 0..boundary.len() {
            if v[3 * k + 2] != NONE {
                continue;
            }
            let d = next_dummy_vertex;
            next_dummy_vertex += 1;
            let mut u = k;
            while v[3 * u + 2] == NONE {
                v[3 * u + 2] = d;
                u = (o[3 * u] - base_corner) as usize / 3;
            }
        }
        Ok(Closed {
            real_v,
            real_o,
            dummy_v: v,
            dummy_o: o,
            boundary: ranks,
            real_triangles,
            real_vertices,
            total_vertices: next_dummy_vertex,
        })
    }

    /// Real and dummy triangles.
    pub(super) fn triangle_count(&self) -> usize {
        (self.real_v.len() + self.dummy_v.len()) / 3
    }

    /// The vertex of corner `c`.
    #[inline(always)]
    pub(super) fn v(&self, c: u32) -> u32 {
        let c = c as usize;
        match self.real_v.get(c) {
            Some(&x) => x,
            None => self.dummy_v[c - self.real_v.len()],
        }
    }

    /// The opposite of corner `c` (never `NONE`: the mesh is closed).
    #[inline(always)]
    pub(super) fn o(&self, c: u32) -> u32 {
        match self.real_o.get(c as usize) {
            Some(&NONE) => 3 * (self.real_triangles + self.boundary.rank(c)) + 2,
            Some(&d) => d,
            None => self.dummy_o[c as usize - self.real_o.len()],
        }
    }

    #[inline]
    pub(super) fn right(&self, c: u32) -> u32 {
        self.o(prev3(c))
    }
}

/// The rank of a boundary corner (one whose opposite is `NONE`) among the boundary corners,
/// in constant time: a bit per corner, set on the boundary ones, and per word of 32 bits the
/// number set before it (about 0.75 bytes per triangle). A binary search over the boundary
/// corners made the LR construction of a triangle soup, whose corners are almost all on the
/// boundary, 2.7 times slower.
struct BoundaryRank {
    bits: Vec<u32>,
    before: Vec<u32>,
}

impl BoundaryRank {
    /// The ranks among `boundary`, the boundary corners of a table of `corners` corners.
    fn new(corners: usize, boundary: &[u32]) -> BoundaryRank {
        let (bits, before) = bits_and_ranks(corners, boundary.iter().map(|&c| c as usize));
        BoundaryRank { bits, before }
    }

    /// The number of boundary corners below `c` (the rank of `c` when it is one).
    #[inline(always)]
    fn rank(&self, c: u32) -> u32 {
        let (w, b) = ((c / 32) as usize, c % 32);
        self.before[w] + (self.bits[w] & ((1u32 << b) - 1)).count_ones()
    }
}

#[cfg(all(test, feature = "generate"))]
mod tests {
    use super::*;
    use crate::generate::{self, Rng};

    /// The constant-time rank counts the boundary corners before each corner, on a torus with
    /// holes, a soup (almost every corner on the boundary) and a closed torus (none).
    #[test]
    fn boundary_rank_counts_the_boundary_corners_before() {
        let mut rng = Rng::new(9);
        let mut holed = generate::irregular_torus(3_000, 1);
        generate::punch_holes(&mut holed, 200, &mut rng);
        let soup = generate::soup(500, 2_000, &mut rng);
        for mesh in [holed, soup, generate::torus(10, 12)] {
            let ct = CornerTable::from_mesh(&mesh).expect("a valid mesh");
            let o = ct.o_table();
            let boundary: Vec<u32> = (0..o.len() as u32)
                .filter(|&c| o[c as usize] == NONE)
                .collect();
            let ranks = BoundaryRank::new(o.len(), &boundary);
            let mut before = 0;
            for (c, &d) in o.iter().enumerate() {
                assert_eq!(ranks.rank(c as u32), before, "corner {c}");
                before += (d == NONE) as u32;
            }
        }
    }
}
