//! The triangle adjacency structure of Reuter, Behr and Alexa, "An Improved Adjacency Data
//! Structure for Fast Triangle Stripping" (JGT 2005), with indices in place of pointers.
//!
//! Every triangle is one record holding its three half-edges (their twins), its stripping state
//! and the two links of the doubly-linked degree list it sits in ([`Node`]). Half-edge `3t + i`
//! of triangle `t = [v0, v1, v2]` runs from `v_i` to `v_(i+1) mod 3`; its triangle is `h / 3` and
//! its next half-edge `3t + (i + 1) mod 3`, so neither needs storing.
//!
//! # Construction (linear time)
//!
//! The paper links half-edges through a per-vertex vector of outgoing half-edges. We bucket them
//! instead by their lower vertex and direction with one counting sort, so that the two
//! half-edges of an edge sit in two neighbouring buckets; small buckets are matched by scanning,
//! large ones (a vertex of high valence) through a per-vertex scratch array, so the whole pass
//! stays linear.
//!
//! **Set aside** (the paper's "non-manifold case", emitted later as single triangles):
//! triangles with a repeated vertex or a vertex out of range, and every triangle that uses a
//! directed half-edge that a lower-numbered triangle already uses (a duplicate, an
//! inconsistently oriented neighbour, or a third triangle on an edge). *Deviation:* the paper
//! adds triangles one by one and checks only against the triangles already accepted; we check
//! against all lower-numbered ones, which needs no sequential pass and sets aside at most a few
//! more triangles. Half-edges of set-aside triangles are unlinked, so every twin joins two
//! kept triangles along an edge used once in each direction.

use crate::corner_table::{CornerTable, NONE};
use crate::ops::CornerOps;

/// Stripping state of a triangle that is in no degree list: already emitted.
pub(crate) const DONE: u32 = 4;
/// Stripping state of a set-aside triangle.
pub(crate) const ASIDE: u32 = 5;

/// Bucket size up to which half-edges are matched by scanning the bucket.
const SCAN_LIMIT: usize = 24;

/// One triangle with its three half-edges embedded, as in the paper's `Triangle` class.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Node {
    /// The twin of each half-edge, as a half-edge id `3u + j`, or `u32::MAX` on a boundary
    /// (or cut) edge.
    pub twin: [u32; 3],
    /// Next triangle in the same degree list (`u32::MAX` at the end).
    pub(crate) next: u32,
    /// Previous triangle in the same degree list (`u32::MAX` at the head).
    pub(crate) prev: u32,
    /// Degree (0 to 3: number of unprocessed neighbours) while in a degree list; else
    /// `DONE` or `ASIDE`.
    pub(crate) state: u32,
}

/// The triangle adjacency graph of an indexed triangle set (see the module documentation).
#[derive(Debug, Clone)]
pub struct Adjacency {
    pub(crate) nodes: Vec<Node>,
    pub(crate) tris: Vec<[u32; 3]>,
    pub(crate) vertex_count: usize,
    aside: u32,
}

#[inline(always)]
fn link(nodes: &mut [Node], h: u32, g: u32) {
    nodes[(h / 3) as usize].twin[(h % 3) as usize] = g;
    nodes[(g / 3) as usize].twin[(g % 3) as usize] = h;
}

impl Adjacency {
    /// Builds the adjacency graph of `triangles` over `vertex_count` vertices in linear time.
    /// Never fails: triangles that cannot join the graph are set aside (see the module
    /// documentation).
    pub fn build(vertex_count: usize, triangles: &[[u32; 3]]) -> Adjacency {
        let n = triangles.len();
        let blank = Node {
            twin: [NONE; 3],
            next: NONE,
            prev: NONE,
            state: 0,
        };
        let mut nodes = vec![blank; n];
        // Two buckets per vertex: half-edges lo -> hi, then hi -> lo.
        let mut start = vec![0u32; 2 * vertex_count + 2];
        for (t, tri) in triangles.iter().enumerate() {
            let [a, b, c] = *tri;
            if a == b || b == c || a == c || tri.iter().any(|&x| x as usize >= vertex_count) {
                nodes[t].state = ASIDE;
                continue;
            }
            for (x, y) in [(a, b), (b, c), (c, a)] {
                let key = 2 * x.min(y) as usize + (x > y) as usize;
                start[key + 1] += 1;
            }
        }
        for i in 1..start.len() {
            start[i] += start[i - 1];
        }
        let total = start[start.len() - 1] as usize;
        // (higher vertex, half-edge) in half-edge order within each bucket.
        let mut bucket = vec![(0u32, 0u32); total];
        {
            let mut fill = start.clone();
            for (t, tri) in triangles.iter().enumerate() {
                if nodes[t].state == ASIDE {
                    continue;
                }
                let [a, b, c] = *tri;
                for (i, (x, y)) in [(a, b), (b, c), (c, a)].into_iter().enumerate() {
                    let key = 2 * x.min(y) as usize + (x > y) as usize;
                    let slot = &mut fill[key];
                    bucket[*slot as usize] = (x.max(y), 3 * t as u32 + i as u32);
                    *slot += 1;
                }
            }
        }
        let mut first_fwd: Vec<u32> = Vec::new();
        let mut first_bwd: Vec<u32> = Vec::new();
        let dup = |nodes: &mut [Node], h: u32| nodes[(h / 3) as usize].state = ASIDE;
        for lo in 0..vertex_count {
            let (s, m, e) = (
                start[2 * lo] as usize,
                start[2 * lo + 1] as usize,
                start[2 * lo + 2] as usize,
            );
            if s == e {
                continue;
            }
            let (fwd, bwd) = (&bucket[s..m], &bucket[m..e]);
            if e - s <= SCAN_LIMIT {
                for (i, &(hi, h)) in fwd.iter().enumerate() {
                    if fwd[..i].iter().any(|x| x.0 == hi) {
                        dup(&mut nodes, h);
                    } else if let Some(&(_, g)) = bwd.iter().find(|x| x.0 == hi) {
                        link(&mut nodes, h, g);
                    }
                }
                for (i, &(hi, h)) in bwd.iter().enumerate() {
                    if bwd[..i].iter().any(|x| x.0 == hi) {
                        dup(&mut nodes, h);
                    }
                }
            } else {
                if first_fwd.is_empty() {
                    first_fwd = vec![NONE; vertex_count];
                    first_bwd = vec![NONE; vertex_count];
                }
                for &(hi, h) in fwd {
                    let f = &mut first_fwd[hi as usize];
                    if *f == NONE {
                        *f = h;
                    } else {
                        dup(&mut nodes, h);
                    }
                }
                for &(hi, h) in bwd {
                    let b = &mut first_bwd[hi as usize];
                    if *b == NONE {
                        *b = h;
                        let f = first_fwd[hi as usize];
                        if f != NONE {
                            link(&mut nodes, f, h);
                        }
                    } else {
                        dup(&mut nodes, h);
                    }
                }
                for &(hi, _) in fwd.iter().chain(bwd) {
                    first_fwd[hi as usize] = NONE;
                    first_bwd[hi as usize] = NONE;
                }
            }
        }
        drop(bucket);
        // Unlink the set-aside triangles.
        let mut aside = 0;
        for t in 0..n {
            if nodes[t].state != ASIDE {
                continue;
            }
            aside += 1;
            for i in 0..3 {
                let g = nodes[t].twin[i];
                if g != NONE {
                    nodes[(g / 3) as usize].twin[(g % 3) as usize] = NONE;
                    nodes[t].twin[i] = NONE;
                }
            }
        }
        Adjacency {
            nodes,
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
        let mut nodes = Vec::with_capacity(n);
        let mut tris = Vec::with_capacity(n);
        for t in 0..n {
            let mut twin = [NONE; 3];
            for (i, tw) in twin.iter_mut().enumerate() {
                let d = o[3 * t + (i + 2) % 3];
                if d != NONE {
                    *tw = 3 * (d / 3) + (d % 3 + 1) % 3;
                }
            }
            nodes.push(Node {
                twin,
                next: NONE,
                prev: NONE,
                state: 0,
            });
            tris.push([v[3 * t], v[3 * t + 1], v[3 * t + 2]]);
        }
        Adjacency {
            nodes,
            tris,
            vertex_count: table.vertex_id_bound() as usize,
            aside: 0,
        }
    }

    /// Number of triangles, set-aside ones included.
    pub fn triangle_count(&self) -> usize {
        self.nodes.len()
    }

    /// Number of set-aside triangles.
    pub fn set_aside_count(&self) -> u32 {
        self.aside
    }

    /// Whether triangle `t` was set aside.
    pub fn is_set_aside(&self, t: u32) -> bool {
        self.nodes
            .get(t as usize)
            .is_some_and(|node| node.state == ASIDE)
    }

    /// The twin of half-edge `h` (`3t + i`), `None` on a boundary, a cut edge or out of range.
    pub fn twin(&self, h: u32) -> Option<u32> {
        let g = *self
            .nodes
            .get((h / 3) as usize)?
            .twin
            .get((h % 3) as usize)?;
        (g != NONE).then_some(g)
    }

    /// The triangle records.
    pub fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The triangles, as given.
    pub fn triangles(&self) -> &[[u32; 3]] {
        &self.tris
    }
}
