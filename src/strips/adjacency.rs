//! The triangle adjacency structure of Reuter, Behr and Alexa, "An Improved Adjacency Data
//! Structure for Fast Triangle Stripping" (JGT 2005), with indices in place of pointers.
//!
//! Every triangle is one record holding its three half-edges, that is their twins (four
//! slots of one array, the fourth unused).
//! *Deviation:* the stripping state and the degree lists live apart from the records, in a
//! byte per triangle and stacks (see the stripper), so that the stripper's look-ups at
//! neighbours stay in a small array. Half-edge `i` of triangle `t = [v0, v1, v2]` runs from
//! `v_i` to `v_(i+1) mod 3`. Inside the module and the stripper its id is `4t + i`, so that
//! its triangle is `h / 4` and its next half-edge `4t + (i + 1) mod 3` (neither stored, and
//! no division by three); [`Adjacency::twin`] speaks the public ids `3t + i`.
//!
//! # Construction (linear time)
//!
//! The paper links half-edges through a per-vertex vector of outgoing half-edges. We bucket them
//! instead by their lower vertex and direction with one counting sort, so that the two
//! half-edges of an edge sit in two neighbouring buckets, matched through a per-vertex scratch
//! array (so the whole pass stays linear, and takes almost no data-dependent branch).
//!
//! **Set aside** (emitted later as single triangles): triangles with a repeated vertex or a
//! vertex out of range, and every triangle of a set of 2^30 or more (whose half-edge ids
//! would not fit 32 bits). **Left unlinked:** on each edge, the lowest half-edge of one direction
//! pairs with the lowest of the other; a half-edge that repeats a direction (a duplicate
//! triangle, an inconsistently oriented neighbour, a third triangle on the edge) gets no twin.
//! So every twin joins two triangles along an edge used once in each direction. *Deviation:*
//! the paper sets aside every triangle of this "non-manifold case"; we keep it in the graph
//! through its other edges, which on a mesh with inconsistent orientation (corpus
//! `blobby-shuffled`) turns most of the lone triangles into strips.

use crate::corner_table::{CornerTable, NONE};
use crate::ops::CornerOps;

/// Stripping state of a triangle that is in no degree list: already emitted.
pub(crate) const DONE: u8 = 4;
/// Stripping state of a set-aside triangle.
pub(crate) const ASIDE: u8 = 5;

/// The triangle adjacency graph of an indexed triangle set (see the module documentation).
#[derive(Debug, Clone)]
pub struct Adjacency {
    /// The twin of each half-edge, in four slots per triangle (`4t + i`, the fourth unused) as
    /// a half-edge id `4u + j`, or `u32::MAX` on a boundary (or cut) edge: the paper's
    /// triangle records. Ids in fours, not threes, spare the stripper's walk a division.
    pub(crate) twins: Vec<u32>,
    /// Number of neighbours of each triangle (its twins), or `ASIDE`: the stripper's starting
    /// state, kept in a small array of its own so that its look-ups stay in cache.
    pub(crate) degree: Vec<u8>,
    pub(crate) tris: Vec<[u32; 3]>,
    pub(crate) vertex_count: usize,
    aside: u32,
}

/// Links the twins of `triangles` over `vertex_count` vertices (see the module documentation)
/// and returns the twins of the half-edges, the degrees (`ASIDE` for set-aside triangles) and
/// the number of set-aside triangles.
pub(crate) fn link_twins(vertex_count: usize, triangles: &[[u32; 3]]) -> (Vec<u32>, Vec<u8>, u32) {
    let n = triangles.len();
    let mut twins = vec![NONE; 4 * n];
    let mut degree = vec![0u8; n];
    // Two buckets per vertex: half-edges lo -> hi, then hi -> lo. `start[k]` counts bucket k,
    // then (inclusive prefix sums, filled downwards) begins it; it ends at `start[k + 1]`.
    let mut start = vec![0u32; 2 * vertex_count + 1];
    let key = |x: u32, y: u32| 2 * x.min(y) as usize + (x > y) as usize;
    // Half-edge ids `4t + i` fit 32 bits below 2^30 triangles; beyond, every triangle is
    // set aside (emitted alone), which keeps the output whole.
    let ids_fit = n < 1 << 30;
    let mut aside = 0;
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        let in_range = (a as usize) < vertex_count
            && (b as usize) < vertex_count
            && (c as usize) < vertex_count;
        if a == b || b == c || a == c || !in_range || !ids_fit {
            degree[t] = ASIDE;
            aside += 1;
            continue;
        }
        start[key(a, b)] += 1;
        start[key(b, c)] += 1;
        start[key(c, a)] += 1;
    }
    let mut total = 0;
    for x in start.iter_mut() {
        total += *x;
        *x = total;
    }
    // (higher vertex, half-edge), in decreasing half-edge order within each bucket.
    let mut bucket = vec![(0u32, 0u32); total as usize];
    for (t, &[a, b, c]) in triangles.iter().enumerate() {
        if degree[t] == ASIDE {
            continue;
        }
        let h = 4 * t as u32;
        for (i, (x, y)) in [(a, b), (b, c), (c, a)].into_iter().enumerate() {
            let slot = &mut start[key(x, y)];
            *slot -= 1;
            bucket[*slot as usize] = (x.max(y), h + i as u32);
        }
    }
    // Match each edge's half-edges, bucket by bucket: the lowest of each direction pair up; a
    // half-edge used again in the same direction (a duplicate, an inconsistently oriented
    // neighbour, a third triangle on the edge) stays unlinked. `lowest[hi]` holds the lowest
    // half-edge of each direction on the edge (lo, hi) while the bucket of lo is matched, and
    // is reset after, so the whole pass stays linear; it takes no data-dependent branch but
    // whether an edge has both directions.
    let mut lowest = vec![[NONE; 2]; vertex_count];
    for lo in 0..vertex_count {
        let (s, e) = (start[2 * lo] as usize, start[2 * lo + 2] as usize);
        let m = start[2 * lo + 1] as usize;
        let (fwd, bwd) = (&bucket[s..m], &bucket[m..e]);
        // Buckets hold decreasing half-edges: the last written is the lowest.
        for &(hi, h) in fwd {
            lowest[hi as usize][0] = h;
        }
        for &(hi, h) in bwd {
            lowest[hi as usize][1] = h;
        }
        for &(hi, _) in fwd {
            let [f, b] = lowest[hi as usize];
            if b != NONE && f != NONE {
                twins[f as usize] = b;
                twins[b as usize] = f;
            }
            lowest[hi as usize] = [NONE; 2];
        }
        for &(hi, _) in bwd {
            lowest[hi as usize][1] = NONE;
        }
    }
    for (d, tw) in degree.iter_mut().zip(twins.chunks_exact(4)) {
        if *d != ASIDE {
            *d = twin_count(tw);
        }
    }
    (twins, degree, aside)
}

/// A triangle's degree: how many of its four twin slots hold a twin.
fn twin_count(slots: &[u32]) -> u8 {
    slots.iter().map(|&g| (g != NONE) as u8).sum()
}

impl Adjacency {
    /// Builds the adjacency graph of `triangles` over `vertex_count` vertices. Never fails:
    /// triangles that cannot join the graph are set aside (see the module documentation).
    pub fn build(vertex_count: usize, triangles: &[[u32; 3]]) -> Adjacency {
        let (twins, degree, aside) = link_twins(vertex_count, triangles);
        Adjacency {
            twins,
            degree,
            tris: triangles.to_vec(),
            vertex_count,
            aside,
        }
    }

    /// The adjacency graph of a corner table's triangles: twins are exactly the table's
    /// opposite corners (half-edge `3t + i` faces corner `3t + (i + 2) mod 3`), vertices the
    /// table's (copies included), and nothing is set aside.
    pub fn from_corner_table(table: &CornerTable) -> Adjacency {
        let v = table.v_table();
        let o = table.o_table();
        let n = v.len() / 3;
        let mut twins = vec![NONE; 4 * n];
        let mut tris = Vec::with_capacity(n);
        for t in 0..n {
            for i in 0..3 {
                let d = o[3 * t + (i + 2) % 3];
                if d != NONE {
                    twins[4 * t + i] = 4 * (d / 3) + (d % 3 + 1) % 3;
                }
            }
            tris.push([v[3 * t], v[3 * t + 1], v[3 * t + 2]]);
        }
        let degree = twins.chunks_exact(4).map(twin_count).collect();
        Adjacency {
            twins,
            tris,
            vertex_count: table.vertex_id_bound() as usize,
            degree,
            aside: 0,
        }
    }

    /// Number of triangles, set-aside ones included.
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// Number of set-aside triangles.
    pub fn set_aside_count(&self) -> u32 {
        self.aside
    }

    /// Whether triangle `t` was set aside.
    pub fn is_set_aside(&self, t: u32) -> bool {
        self.degree.get(t as usize) == Some(&ASIDE)
    }

    /// The twin of half-edge `h` (`3t + i`), `None` on a boundary, a cut edge or out of range.
    pub fn twin(&self, h: u32) -> Option<u32> {
        let g = *self.twins.get(4 * (h / 3) as usize + (h % 3) as usize)?;
        (g != NONE).then_some(3 * (g / 4) + g % 4)
    }

    /// The triangles, as given.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.tris
    }
}

#[cfg(all(test, feature = "generate"))]
mod tests {
    use super::*;
    use crate::generate::{self, Rng};

    /// Each triangle's degree is its number of twins, on a soup of repeated edges and on a
    /// torus in scattered order (buckets of every size).
    #[test]
    fn degrees_count_the_twins() {
        let mut rng = Rng::new(5);
        let soup = generate::soup(40, 3_000, &mut rng).triangles;
        let mut torus = generate::irregular_torus(20_000, 1).triangles;
        rng.shuffle(&mut torus);
        for (vertex_count, tris) in [(40, soup), (torus.len(), torus)] {
            let (twins, degree, _) = link_twins(vertex_count, &tris);
            for (tw, &d) in twins.chunks_exact(4).zip(&degree) {
                if d != ASIDE {
                    assert_eq!(d as usize, tw.iter().filter(|&&g| g != NONE).count());
                }
            }
        }
    }
}
