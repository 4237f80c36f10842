//! The stripper of Reuter, Behr and Alexa (section 4), a variant of STRIPE (Evans, Skiena,
//! Varshney 1996), running in place on the [`Adjacency`] records.
//!
//! 1. Set-aside triangles go to the triangle list.
//! 2. *Fans* (optional): every vertex with at least [`StripOptions::fan_threshold`] triangles
//!    around it, in vertex order, gives a fan of its still unprocessed triangles that follow one
//!    another around it.
//! 3. The remaining triangles sit in four lists, one per degree 0 to 3 (the number of
//!    unprocessed neighbours), kept with lazy deletion (see `Lists`). Each strip starts at the
//!    head of the lowest non-empty list; a triangle of degree 0 there is *isolated* and goes to the triangle list. The strip
//!    takes the start's lowest-degree neighbour as its second triangle and then grows by
//!    alternating turns: through the edge made by the last two indices when that neighbour is
//!    free, otherwise through the triangle's other free edge after a *swap* (one repeated index,
//!    a zero-area triangle), otherwise it ends. Each triangle taken leaves its list and drops
//!    its free neighbours to the list below.
//! 4. With [`StripOptions::samples`] above one, the stripping is repeated with randomised
//!    starts (a rotated list order and random ties) and the result with the fewest indices is
//!    kept.

use super::adjacency::{Adjacency, ASIDE, DONE};
use super::{StripOptions, Strips, RESTART};
use crate::corner_table::NONE;
use crate::rng::Rng;

/// The four degree lists, with lazy deletion. List `d` is the triangles whose degree was `d`
/// from the start, in (rotated) triangle order, under the triangles whose degree dropped to `d`
/// since, newest first: exactly the order of the paper's doubly-linked lists filled back to
/// front and relinked at the head, without touching any neighbour's links.
///
/// The first part is a cursor over the triangles that start with degree `d` (collected in one
/// pass for `d < 3`; all triangles for `d = 3`), the second a stack. A triangle whose
/// degree drops is pushed onto the lower stack; its entry in the higher list goes stale (its
/// state no longer names that list) and is skipped when it comes up. Degrees only fall, so a
/// triangle enters each stack at most once, and when a stack is empty every triangle whose
/// state names the list was there from the start, so the cursor finds the head.
struct Lists {
    stacks: [Vec<u32>; 4],
    /// The triangles of degree 0, 1 and 2 at the start, in rotated triangle order.
    initial: [Vec<u32>; 3],
    /// Next position to look at: in `initial[d]`, or for `d = 3` in the rotated order.
    cursor: [u32; 4],
    n: u32,
    offset: u32,
}

impl Lists {
    /// Takes `t` out of its list for good and drops its free neighbours one degree.
    #[inline(always)]
    fn take(&mut self, twins: &[u32], state: &mut [u8], t: u32) {
        state[t as usize] = DONE;
        self.drop_neighbours(&twins_of(twins, t), state);
    }

    /// Drops the free triangles across `twin` one degree.
    #[inline(always)]
    fn drop_neighbours(&mut self, twin: &[u32; 3], state: &mut [u8]) {
        for &g in twin {
            self.drop_across(g, state, NONE);
        }
    }

    /// Drops the triangle across half-edge `g` one degree if it is free and not `skip`.
    #[inline(always)]
    fn drop_across(&mut self, g: u32, state: &mut [u8], skip: u32) {
        if g == NONE {
            return;
        }
        let u = g / 4;
        let d = state[u as usize];
        if d <= 3 && u != skip {
            // A free neighbour shares an edge with the taken triangle: its degree is at least
            // one.
            let d = d.saturating_sub(1);
            state[u as usize] = d;
            self.stacks[d as usize].push(u);
        }
    }

    /// The head of the lowest non-empty list (stale entries on top are dropped).
    #[inline(always)]
    fn lowest(&mut self, state: &[u8]) -> Option<u32> {
        for d in 0..4 {
            while let Some(&t) = self.stacks[d].last() {
                if state[t as usize] == d as u8 {
                    return Some(t);
                }
                self.stacks[d].pop();
            }
            if d < 3 {
                while let Some(&t) = self.initial[d].get(self.cursor[d] as usize) {
                    if state[t as usize] == d as u8 {
                        return Some(t);
                    }
                    self.cursor[d] += 1;
                }
            } else {
                while self.cursor[3] < self.n {
                    let k = self.cursor[3] + self.offset;
                    let t = if k >= self.n { k - self.n } else { k };
                    if state[t as usize] == 3 {
                        return Some(t);
                    }
                    self.cursor[3] += 1;
                }
            }
        }
        None
    }
}

/// The twins of triangle `t`'s three half-edges.
#[inline(always)]
fn twins_of(twins: &[u32], t: u32) -> [u32; 3] {
    let h = 4 * t as usize;
    [twins[h], twins[h + 1], twins[h + 2]]
}

#[inline(always)]
fn free(state: &[u8], g: u32) -> bool {
    g != NONE && state[(g / 4) as usize] <= 3
}

/// Strips `adj` with `options`, keeping the best of the samples.
pub(crate) fn stripify_adjacency(adj: &mut Adjacency, options: &StripOptions) -> Strips {
    stripify_twins(
        &adj.twins,
        &adj.degree,
        &adj.tris,
        adj.vertex_count,
        options,
    )
}

/// Strips the triangles `tris` whose half-edges have the twins `twins`.
pub(crate) fn stripify_twins(
    twins: &[u32],
    degree: &[u8],
    tris: &[[u32; 3]],
    vertex_count: usize,
    options: &StripOptions,
) -> Strips {
    let mut rng = Rng::new(options.seed);
    let mut best: Option<Strips> = None;
    let mut state = degree.to_vec();
    let any_aside = degree.contains(&ASIDE);
    for sample in 0..options.samples.max(1) {
        if sample > 0 {
            state.copy_from_slice(degree);
        }
        let out = run(
            twins,
            &mut state,
            any_aside,
            tris,
            vertex_count,
            options,
            sample,
            &mut rng,
        );
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
#[allow(clippy::too_many_arguments)]
fn run(
    twins: &[u32],
    state: &mut [u8],
    any_aside: bool,
    tris: &[[u32; 3]],
    vertex_count: usize,
    options: &StripOptions,
    sample: u32,
    rng: &mut Rng,
) -> Strips {
    let n = tris.len() as u32;
    let mut out = Strips {
        // Strips take about 1.4 indices per triangle with their restarts (a realloc and a
        // copy when they outgrow the capacity); pages never written cost nothing.
        strips: Vec::with_capacity(2 * n as usize + 8),
        strip_order: Vec::with_capacity(n as usize),
        ..Strips::default()
    };
    let offset = if sample == 0 || n == 0 {
        0
    } else {
        rng.below(n)
    };
    let mut initial = [Vec::new(), Vec::new(), Vec::new()];
    for t in (offset..n).chain(0..offset) {
        let d = state[t as usize];
        if d < 3 {
            initial[d as usize].push(t);
        }
    }
    let mut lists = Lists {
        stacks: [
            Vec::new(),
            Vec::with_capacity(n as usize / 4),
            Vec::with_capacity(n as usize / 2),
            Vec::new(),
        ],
        initial,
        cursor: [0; 4],
        n,
        offset,
    };
    // Set-aside triangles, verbatim.
    if any_aside {
        for t in 0..n {
            if state[t as usize] == ASIDE {
                out.list.extend_from_slice(&tris[t as usize]);
                out.list_order.push(t);
            }
        }
    }
    if options.fan_threshold >= 3 {
        fans(
            tris,
            twins,
            state,
            &mut lists,
            vertex_count,
            options,
            &mut out,
        );
    }
    let mut swaps = 0u32;
    while let Some(t0) = lists.lowest(state) {
        lists.take(twins, state, t0);
        // The start's lowest-degree free neighbour.
        let mut best = NONE;
        let mut best_degree = u8::MAX;
        let twin = twins_of(twins, t0);
        for (i, &g) in twin.iter().enumerate() {
            if !free(state, g) {
                continue;
            }
            let d = state[(g / 4) as usize];
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
        // The strip's last two indices.
        let (mut p, mut q) = (tri[i], tri[(i + 1) % 3]);
        loop {
            let cur = entry / 4;
            state[cur as usize] = DONE;
            out.strip_order.push(cur);
            let k = (entry % 4) as usize;
            let tv = tris[cur as usize];
            let r = tv[(k + 2) % 3];
            // The entry half-edge runs tv[k] -> tv[k+1]; the natural exit edge joins q and r.
            let (natural, other) = if tv[k] == q {
                ((k + 2) % 3, (k + 1) % 3)
            } else {
                ((k + 1) % 3, (k + 2) % 3)
            };
            // Taking `cur` drops its free neighbours one degree but the strip's next triangle,
            // taken at once: the one across the entry is taken already, and so is the one across
            // the edge not taken when the strip swaps or ends (it was not free).
            let twin = twins_of(twins, cur);
            let next = if free(state, twin[natural]) {
                out.strips.push(r);
                (p, q) = (q, r);
                lists.drop_across(twin[other], state, twin[natural] / 4);
                twin[natural]
            } else if free(state, twin[other]) {
                out.strips.extend_from_slice(&[p, r]);
                swaps += 1;
                q = r;
                twin[other]
            } else {
                out.strips.push(r);
                break;
            };
            entry = next;
        }
    }
    out.swaps = swaps;
    out
}

/// Fans around vertices with at least `options.fan_threshold` triangles.
fn fans(
    tris: &[[u32; 3]],
    twins: &[u32],
    state: &mut [u8],
    lists: &mut Lists,
    vertex_count: usize,
    options: &StripOptions,
    out: &mut Strips,
) {
    let mut count = vec![0u32; vertex_count];
    let mut corner = vec![NONE; vertex_count];
    for (t, tri) in tris.iter().enumerate() {
        if state[t] == ASIDE {
            continue;
        }
        for (i, &v) in tri.iter().enumerate() {
            count[v as usize] += 1;
            corner[v as usize] = 4 * t as u32 + i as u32;
        }
    }
    // The half-edge `step` after `h` in its triangle.
    let half = |h: u32, step: u32| 4 * (h / 4) + (h % 4 + step) % 3;
    let mut rim = Vec::new();
    for v in 0..vertex_count {
        let h0 = corner[v];
        if count[v] < options.fan_threshold || h0 == NONE || state[(h0 / 4) as usize] > 3 {
            continue;
        }
        // Back to the first free triangle of the fan: the half-edge leaving v in the previous
        // triangle is the next of the twin of the one leaving v here.
        let mut h = h0;
        loop {
            let g = twins[h as usize];
            if !free(state, g) {
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
            let t = h / 4;
            let tv = tris[t as usize];
            let i = (h % 4) as usize;
            if members == 0 {
                rim.push(tv[(i + 1) % 3]);
            }
            rim.push(tv[(i + 2) % 3]);
            members += 1;
            let g = twins[half(h, 2) as usize];
            if !free(state, g) || g == first {
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
            let t = h / 4;
            let g = twins[half(h, 2) as usize];
            lists.take(twins, state, t);
            out.fan_order.push(t);
            h = g;
        }
    }
}
