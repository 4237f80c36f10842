//! Local improvement of a ring after RING-EXPANDER: *leaf moves*, which trade a dead end of
//! the invaded region for another so that fewer triangles are left with no ring edge.
//!
//! The invaded triangles form a tree whose leaves are T2 triangles: a leaf `A` is an ear
//! with tip `x`, the only invaded triangle at `x`. Giving `A` back to the outside and
//! invading instead another triangle `F` of `x`'s fan, one whose edge across from `x` lies
//! on the ring, keeps a ring through the same vertices (`x` moves onto that edge) and
//! changes the classes of at most eight triangles. A move is kept when it lowers the number
//! of T0 triangles that no wart takes, the expensive ones (six references each, and
//! irregular neighbours); every other pass also keeps moves that leave it unchanged, which
//! lets the search cross the plateaus between improvements. On the shared meshes this takes
//! a third of those triangles away (references per triangle: armadillo 1.218 → 1.133,
//! bunny00 1.188 → 1.120).

use super::closed::{next3, Closed};
use super::ring::{ring_edges, t0_without_wart, Marks};

/// Passes over the leaves: strict, sideways, strict, … Six reach nearly all of the gain
/// of twenty on the shared meshes.
const PASSES: usize = 6;

/// The most fan triangles tried around one tip: a tip of higher valence keeps the rest.
const MAX_FAN: usize = 64;

/// The working memory of the leaf moves, made once per mesh and reused by its components
/// (a component's marks are cleared when it is done), so that a mesh of many small
/// components costs no more than one of their size.
pub(super) struct LeafMoves {
    leaves: Vec<u32>,
    set: Vec<u32>,
    /// Triangles near a move kept in this pass or the previous one: after the first strict
    /// and sideways passes, only leaves among them can have a move not tried before.
    near: Marks,
    near_next: Marks,
}

impl LeafMoves {
    pub(super) fn new(mesh: &Closed) -> LeafMoves {
        LeafMoves {
            leaves: Vec::new(),
            set: Vec::with_capacity(32),
            near: Marks::new(mesh.triangle_count()),
            near_next: Marks::new(mesh.triangle_count()),
        }
    }

    /// Applies leaf moves to the invaded triangles `tm` of a component whose triangles are
    /// `triangles`. The visited vertices do not change: every move keeps its tip on the ring.
    pub(super) fn improve(&mut self, mesh: &Closed, triangles: &[u32], tm: &mut Marks) {
        for pass in 0..PASSES {
            let sideways = pass % 2 == 1;
            let everywhere = pass == 0 || sideways;
            let near = &self.near;
            self.leaves.clear();
            self.leaves.extend(triangles.iter().copied().filter(|&t| {
                t < mesh.real_triangles
                    && tm.get(t as usize)
                    && (everywhere || near.get(t as usize))
                    && ring_edges(mesh, tm, t) == 2
            }));
            let mut improved = false;
            for &a in &self.leaves {
                // An earlier move this pass may have taken the leaf away or grown it.
                if !tm.get(a as usize) || ring_edges(mesh, tm, a) != 2 {
                    continue;
                }
                if let Some(lowered) = try_leaf(mesh, tm, a, sideways, &mut self.set) {
                    improved |= lowered;
                    for &t in &self.set {
                        self.near_next.set(t as usize);
                    }
                }
            }
            for &t in triangles {
                self.near.put(t as usize, self.near_next.get(t as usize));
                self.near_next.clear(t as usize);
            }
            if !improved && !sideways {
                break;
            }
        }
        for &t in triangles {
            self.near.clear(t as usize);
        }
    }
}

/// The triangles whose cost a move of `a` and `f` can change: those two, their neighbours
/// (whose ring edges change) and the neighbours' neighbours (whose wart can change).
fn affected(mesh: &Closed, a: u32, f: u32, out: &mut Vec<u32>) {
    out.clear();
    for t in [a, f] {
        out.push(t);
        for i in 0..3 {
            let u = mesh.o(3 * t + i) / 3;
            out.push(u);
            out.extend((0..3).map(|k| mesh.o(3 * u + k) / 3));
        }
    }
    out.sort_unstable();
    out.dedup();
}

fn cost(mesh: &Closed, tm: &Marks, set: &[u32]) -> usize {
    set.iter()
        .filter(|&&t| t0_without_wart(mesh, tm, t))
        .count()
}

/// Tries the moves of leaf `a` in turn around its tip and keeps the first that lowers the
/// cost (or, `sideways`, that does not raise it): `Some(whether it lowered it)`, with the
/// triangles it affected in `set`; `None` when no move was kept.
fn try_leaf(
    mesh: &Closed,
    tm: &mut Marks,
    a: u32,
    sideways: bool,
    set: &mut Vec<u32>,
) -> Option<bool> {
    // The corner at the tip faces the leaf's one edge to an invaded triangle.
    let tip = (3 * a..3 * a + 3).find(|&c| tm.get(mesh.o(c) as usize / 3))?;
    // Around the tip by c.s = c.n.o.n, from the fan triangle after `a` until back at it.
    let mut c = next3(mesh.o(next3(tip)));
    for _ in 0..MAX_FAN {
        let f = c / 3;
        if f == a {
            break;
        }
        let across = mesh.o(c) / 3;
        if f < mesh.real_triangles && !tm.get(f as usize) && tm.get(across as usize) {
            affected(mesh, a, f, set);
            let before = cost(mesh, tm, set);
            // Nothing to lower, and a strict pass keeps nothing else.
            if before == 0 && !sideways {
                c = next3(mesh.o(next3(c)));
                continue;
            }
            tm.clear(a as usize);
            tm.set(f as usize);
            let after = cost(mesh, tm, set);
            if after < before || (sideways && after == before) {
                return Some(after < before);
            }
            tm.clear(f as usize);
            tm.set(a as usize);
        }
        c = next3(mesh.o(next3(c)));
    }
    None
}
