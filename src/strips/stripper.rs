//! The stripper of Reuter, Behr and Alexa (section 4), a variant of STRIPE (Evans, Skiena,
//! Varshney 1996), running in place on the [`Adjacency`] records.
//!
//! 1. Set-aside triangles go to the triangle list.
//! 2. *Fans* (optional): every vertex with at least [`StripOptions::fan_threshold`] triangles
//!    around it, in vertex order, gives a fan of its still unprocessed triangles that follow one
//!    another around it.
//! 3. The remaining triangles sit in four doubly-linked lists, one per degree 0 to 3 (the
//!    number of unprocessed neighbours). Each strip starts at the head of the lowest non-empty
//!    list; a triangle of degree 0 there is *isolated* and goes to the triangle list. The strip
//!    takes the start's lowest-degree neighbour as its second triangle and then grows by
//!    alternating turns: through the edge made by the last two indices when that neighbour is
//!    free, otherwise through the triangle's other free edge after a *swap* (one repeated index,
//!    a zero-area triangle), otherwise it ends. Each triangle taken leaves its list and drops
//!    its free neighbours to the list below, by relinking.
//! 4. With [`StripOptions::samples`] above one, the stripping is repeated with randomised
//!    starts (a rotated list order and random ties) and the result with the fewest indices is
//!    kept.

use super::adjacency::{Adjacency, Node, ASIDE, DONE};
use super::{StripOptions, Strips, RESTART};
use crate::corner_table::NONE;
use crate::generate::Rng;

/// The four degree lists, threaded through the nodes.
struct Lists {
    head: [u32; 4],
}

impl Lists {
    #[inline(always)]
    fn push(&mut self, nodes: &mut [Node], t: u32, d: u32) {
        let h = self.head[d as usize];
        let node = &mut nodes[t as usize];
        node.state = d;
        node.prev = NONE;
        node.next = h;
        if h != NONE {
            nodes[h as usize].prev = t;
        }
        self.head[d as usize] = t;
    }

    #[inline(always)]
    fn unlink(&mut self, nodes: &mut [Node], t: u32) {
        let Node {
            next, prev, state, ..
        } = nodes[t as usize];
        if prev == NONE {
            self.head[state as usize] = next;
        } else {
            nodes[prev as usize].next = next;
        }
        if next != NONE {
            nodes[next as usize].prev = prev;
        }
    }

    /// Takes `t` out of its list for good and drops its free neighbours one degree.
    #[inline(always)]
    fn take(&mut self, nodes: &mut [Node], t: u32) {
        self.unlink(nodes, t);
        nodes[t as usize].state = DONE;
        let twin = nodes[t as usize].twin;
        for g in twin {
            if g == NONE {
                continue;
            }
            let u = g / 3;
            let d = nodes[u as usize].state;
            if d <= 3 {
                self.unlink(nodes, u);
                // A free neighbour shares an edge with t, so its degree is at least one.
                self.push(nodes, u, d.saturating_sub(1));
            }
        }
    }

    #[inline(always)]
    fn lowest(&self) -> Option<u32> {
        self.head.iter().copied().find(|&h| h != NONE)
    }
}

#[inline(always)]
fn free(nodes: &[Node], g: u32) -> bool {
    g != NONE && nodes[(g / 3) as usize].state <= 3
}

/// Strips `adj` with `options`, keeping the best of the samples.
pub(crate) fn stripify_adjacency(adj: &mut Adjacency, options: &StripOptions) -> Strips {
    let mut rng = Rng::new(options.seed);
    let mut best: Option<Strips> = None;
    for sample in 0..options.samples.max(1) {
        let out = run(adj, options, sample, &mut rng);
        if best
            .as_ref()
            .is_none_or(|b| out.index_count() < b.index_count())
        {
            best = Some(out);
        }
    }
    best.unwrap_or_default()
}

/// One stripping of `adj`; sample 0 is deterministic, later ones randomised through `rng`.
fn run(adj: &mut Adjacency, options: &StripOptions, sample: u32, rng: &mut Rng) -> Strips {
    let tris = &adj.tris;
    let nodes = &mut adj.nodes[..];
    let n = nodes.len() as u32;
    let mut out = Strips {
        strips: Vec::with_capacity(n as usize + n as usize / 4),
        strip_order: Vec::with_capacity(n as usize),
        ..Strips::default()
    };
    let mut lists = Lists { head: [NONE; 4] };
    let offset = if sample == 0 || n == 0 {
        0
    } else {
        rng.below(n)
    };
    // Fill the lists back to front so that each list's head is its lowest triangle (after the
    // rotation by `offset`).
    for k in (0..n).rev() {
        let t = if k + offset >= n {
            k + offset - n
        } else {
            k + offset
        };
        let node = &nodes[t as usize];
        if node.state == ASIDE {
            continue;
        }
        let d = node.twin.iter().filter(|&&g| g != NONE).count() as u32;
        lists.push(nodes, t, d);
    }
    // Set-aside triangles, verbatim.
    for t in 0..n {
        if nodes[t as usize].state == ASIDE {
            out.list.extend_from_slice(&tris[t as usize]);
            out.list_order.push(t);
        }
    }
    if options.fan_threshold >= 3 {
        fans(tris, nodes, &mut lists, adj.vertex_count, options, &mut out);
    }
    let mut swaps = 0u32;
    while let Some(t0) = lists.lowest() {
        lists.take(nodes, t0);
        // The start's lowest-degree free neighbour.
        let mut best = NONE;
        let mut best_degree = u32::MAX;
        let twin = nodes[t0 as usize].twin;
        for (i, &g) in twin.iter().enumerate() {
            if !free(nodes, g) {
                continue;
            }
            let d = nodes[(g / 3) as usize].state;
            if d < best_degree || (d == best_degree && sample > 0 && rng.below(2) == 0) {
                best = i as u32;
                best_degree = d;
            }
        }
        let tri = tris[t0 as usize];
        if best == NONE {
            out.isolated += 1;
            out.list.extend_from_slice(&tri);
            out.list_order.push(t0);
            continue;
        }
        if out.strip_count > 0 {
            out.strips.push(RESTART);
        }
        out.strip_count += 1;
        let i = best as usize;
        // Half-edge i runs a -> b; the strip starts c, a, b so that its first triangle keeps
        // t0's orientation and its last two indices are the shared edge.
        out.strips
            .extend_from_slice(&[tri[(i + 2) % 3], tri[i], tri[(i + 1) % 3]]);
        out.strip_order.push(t0);
        let mut entry = twin[i];
        loop {
            let cur = entry / 3;
            lists.take(nodes, cur);
            out.strip_order.push(cur);
            let k = (entry % 3) as usize;
            let tv = tris[cur as usize];
            let r = tv[(k + 2) % 3];
            let q = out.strips[out.strips.len() - 1];
            // The entry half-edge runs tv[k] -> tv[k+1]; the natural exit edge joins q and r.
            let (natural, other) = if tv[k] == q {
                ((k + 2) % 3, (k + 1) % 3)
            } else {
                ((k + 1) % 3, (k + 2) % 3)
            };
            let twin = nodes[cur as usize].twin;
            if free(nodes, twin[natural]) {
                out.strips.push(r);
                entry = twin[natural];
            } else if free(nodes, twin[other]) {
                let p = out.strips[out.strips.len() - 2];
                out.strips.push(p);
                out.strips.push(r);
                swaps += 1;
                entry = twin[other];
            } else {
                out.strips.push(r);
                break;
            }
        }
    }
    out.swaps = swaps;
    out
}

/// Fans around vertices with at least `options.fan_threshold` triangles.
fn fans(
    tris: &[[u32; 3]],
    nodes: &mut [Node],
    lists: &mut Lists,
    vertex_count: usize,
    options: &StripOptions,
    out: &mut Strips,
) {
    let mut count = vec![0u32; vertex_count];
    let mut corner = vec![NONE; vertex_count];
    for (t, tri) in tris.iter().enumerate() {
        if nodes[t].state == ASIDE {
            continue;
        }
        for (i, &v) in tri.iter().enumerate() {
            count[v as usize] += 1;
            corner[v as usize] = 3 * t as u32 + i as u32;
        }
    }
    let half = |h: u32, step: u32| 3 * (h / 3) + (h % 3 + step) % 3;
    let mut rim = Vec::new();
    for v in 0..vertex_count {
        let h0 = corner[v];
        if count[v] < options.fan_threshold || h0 == NONE || nodes[(h0 / 3) as usize].state > 3 {
            continue;
        }
        // Back to the first free triangle of the fan: the half-edge leaving v in the previous
        // triangle is the next of the twin of the one leaving v here.
        let mut h = h0;
        loop {
            let g = nodes[(h / 3) as usize].twin[(h % 3) as usize];
            if !free(nodes, g) {
                break;
            }
            let back = half(g, 1);
            if back == h0 {
                break;
            }
            h = back;
        }
        // Forward: the next triangle holds the twin of the half-edge entering v here.
        rim.clear();
        let mut members = 0u32;
        let first = h;
        loop {
            let t = h / 3;
            let tv = tris[t as usize];
            let i = (h % 3) as usize;
            if members == 0 {
                rim.push(tv[(i + 1) % 3]);
            }
            rim.push(tv[(i + 2) % 3]);
            members += 1;
            let g = nodes[t as usize].twin[(i + 2) % 3];
            if !free(nodes, g) || g == first {
                break;
            }
            h = g;
            if members >= count[v] {
                break;
            }
        }
        if members < options.fan_threshold {
            continue;
        }
        if out.fan_count > 0 {
            out.fans.push(RESTART);
        }
        out.fan_count += 1;
        out.fans.push(v as u32);
        out.fans.extend_from_slice(&rim);
        let mut h = first;
        for _ in 0..members {
            let t = h / 3;
            let g = nodes[t as usize].twin[((h % 3 + 2) % 3) as usize];
            lists.take(nodes, t);
            out.fan_order.push(t);
            h = g;
        }
    }
}
