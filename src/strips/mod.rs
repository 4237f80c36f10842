//! Triangle strips: a fast stripper on the adjacency structure of Reuter, Behr and Alexa
//! (JGT 2005), constrained triangle strips with the adjacent-strips table of Annaka, Matsuoka
//! and Miyazawa (WSCG 2005) as a random-access connectivity, and the LR as a rendering index
//! list (LR paper, section 7).
//!
//! * [`stripify`] turns any indexed triangle set into strips (with swaps), fans and a list of
//!   lone triangles, emitting every input triangle exactly once with its orientation
//!   ([`Strips::triangles`] decodes them the way a GPU draws them).
//! * [`Cts`] is the constrained strips `T` and the adjacent-strips table `A` built on a
//!   [`CornerTable`](crate::CornerTable), with the corner operators.
//! * [`lr_index_list`] writes a [`Lr`](crate::lr::Lr) as one vertex reference per T1/T2
//!   triangle, T0 triangles verbatim, and [`LrIndexList::triangle_list`] expands it into a
//!   triangle list for the GPU.
//! * [`StripStats`] gives the figures of `lrmesh stats` (key `strips`).
//!
//! Nothing here panics on any input; meshes need not be manifold or oriented.

mod adjacency;
mod cts;
mod lr_index;
mod stats;
mod stripper;

pub use adjacency::Adjacency;
pub use cts::{Cts, CtsTables, DELIMITER};
pub use lr_index::{lr_index_list, LrIndexList, INDEX_WART};
pub use stats::StripStats;

/// The primitive-restart index that separates strips (and fans) in one index buffer.
pub const RESTART: u32 = u32::MAX;

/// Options of [`stripify`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StripOptions {
    /// Stripping runs, each from other random starts after the first; the result with the
    /// fewest indices is kept (the paper's random sampling, with the vertex count as cost).
    pub samples: u32,
    /// Vertices with at least this many triangles around them become triangle fans first;
    /// below 3, no fans.
    pub fan_threshold: u32,
    /// Seed of the random sampling: the same value gives the same strips.
    pub seed: u64,
}

impl Default for StripOptions {
    fn default() -> Self {
        StripOptions {
            samples: 1,
            fan_threshold: 0,
            seed: 1,
        }
    }
}

/// The output of [`stripify`]: strips, fans and lone triangles, three index buffers a GPU can
/// draw as they are (triangle strip and triangle fan with primitive restart, triangle list).
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Strips {
    /// Triangle strips separated by [`RESTART`]. Triangle `k` of a strip (counting from 0 at
    /// the strip's start) is `(s_k, s_k+1, s_k+2)` when `k` is even and `(s_k+1, s_k, s_k+2)`
    /// when it is odd; a *swap* repeats an index, making a zero-area triangle that stands for
    /// no input triangle.
    pub strips: Vec<u32>,
    /// Triangle fans separated by [`RESTART`]: the centre `c`, then the rim `r_0, r_1, ...`;
    /// triangle `k` is `(c, r_k, r_k+1)`.
    pub fans: Vec<u32>,
    /// Lone triangles, three indices each: set-aside ones (degenerate or out of range, see
    /// [`Adjacency`]) first, in input order, then isolated ones.
    pub list: Vec<u32>,
    /// The input triangle of each non-degenerate strip triangle, in strip order.
    pub strip_order: Vec<u32>,
    /// The input triangle of each fan triangle, in fan order.
    pub fan_order: Vec<u32>,
    /// The input triangle of each triangle of `list`.
    pub list_order: Vec<u32>,
    /// Number of strips.
    pub strip_count: u32,
    /// Number of fans.
    pub fan_count: u32,
    /// Number of swaps (zero-area triangles) in the strips.
    pub swaps: u32,
    /// Triangles in the list because they had no free neighbour when their turn came (the
    /// set-aside ones not included).
    pub isolated: u32,
}

impl Strips {
    /// Indices in all three buffers, restarts included.
    pub fn index_count(&self) -> usize {
        self.strips.len() + self.fans.len() + self.list.len()
    }

    /// Number of input triangles emitted.
    pub fn triangle_count(&self) -> usize {
        self.strip_order.len() + self.fan_order.len() + self.list_order.len()
    }

    /// Indices per triangle, restarts included (0 without triangles).
    pub fn indices_per_triangle(&self) -> f64 {
        self.index_count() as f64 / self.triangle_count().max(1) as f64
    }

    /// The triangles the three buffers draw, oriented, in the order of `strip_order`,
    /// `fan_order` and `list_order` one after the other. Zero-area triangles of strips (swaps)
    /// are skipped; those of the list (degenerate input triangles) are kept.
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        let mut out = Vec::with_capacity(self.triangle_count());
        decode_strips(&self.strips, &mut out);
        for fan in self.fans.split(|&x| x == RESTART) {
            if let Some((&c, rim)) = fan.split_first() {
                out.extend(rim.windows(2).map(|w| [c, w[0], w[1]]));
            }
        }
        out.extend(self.list.chunks_exact(3).map(|t| [t[0], t[1], t[2]]));
        out
    }
}

/// Appends the non-degenerate triangles of strips separated by [`RESTART`] to `out`.
pub fn decode_strips(strips: &[u32], out: &mut Vec<[u32; 3]>) {
    for strip in strips.split(|&x| x == RESTART) {
        for (k, w) in strip.windows(3).enumerate() {
            if w[0] == w[1] || w[1] == w[2] || w[0] == w[2] {
                continue;
            }
            out.push(if k % 2 == 0 {
                [w[0], w[1], w[2]]
            } else {
                [w[1], w[0], w[2]]
            });
        }
    }
}

/// Strips the triangles `triangles` over `vertex_count` vertices: builds the [`Adjacency`]
/// graph and runs the stripper of Reuter, Behr and Alexa on it (see the `stripper` notes in
/// the documentation of [`Strips`] and [`StripOptions`]). Every input triangle comes out
/// exactly once, with its orientation: in a strip, a fan or the list of lone triangles.
/// Linear time per sample; never panics.
pub fn stripify(vertex_count: usize, triangles: &[[u32; 3]], options: &StripOptions) -> Strips {
    // The twins alone: the stripper reads the triangles where they are.
    let (twins, degree, _) = adjacency::link_twins(vertex_count, triangles);
    stripper::stripify_twins(&twins, &degree, triangles, vertex_count, options)
}

/// Strips an [`Adjacency`] graph (which may be reused: each run resets its lists).
pub fn stripify_adjacency(adj: &mut Adjacency, options: &StripOptions) -> Strips {
    stripper::stripify_adjacency(adj, options)
}
