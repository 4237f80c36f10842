//! Local improvement of a ring after RING-EXPANDER: *leaf moves*, which trade a dead end of
//! one side of the ring for another so that fewer triangles are left with no ring edge.
//!
//! The ring splits the triangles into the invaded side and the rest. A *leaf* is a T2
//! triangle `A` of either side: an ear with tip `x`, the only triangle of its side at `x`
//! (every ring vertex is on the ring once, so each side's triangles at it are one sector).
//! Putting `A` on the other side and, in exchange, a triangle `F` of `x`'s fan onto `A`'s
//! side (one whose edge across from `x` borders that side) keeps the invaded triangles a
//! disk whose boundary runs once through the same vertices: `x` moves onto `F`'s far edge,
//! and at most eight triangles change class. A move is kept when it lowers the number of
//! T0 triangles that no wart takes, the expensive ones (six references each, and irregular
//! neighbours); every other pass also keeps moves that leave it unchanged, which lets the
//! search cross the plateaus between improvements. On the shared meshes this takes about
//! two thirds of those triangles away (references per triangle: armadillo 1.218 → 1.064,
//! bunny00 1.188 → 1.066).

use super::closed::{next3, Closed};
use super::ring::{ring_edges, t0_without_wart, Marks};

/// Passes over the leaves: strict, sideways, strict, … Each pair of passes still gains a
/// little (ten: bunny00 1.055 instead of 1.066); six keep the build within twice RING-EXPANDER's.
const PASSES: usize = 6;

/// The most fan triangles tried around one tip: a tip of higher valence keeps the rest.
const MAX_FAN: usize = 64;

/// The working memory of the leaf moves, made once per mesh and reused by its components
/// (a component's marks are cleared when it is done), so that a mesh of many small
/// components costs no more than one of their size.
pub(super) struct LeafMoves {
    leaves: Vec<u32>,
    set: Vec<u32>,
    /// Ring edges per triangle of the component being improved, kept up to date through the
    /// moves: a move reads some twenty triangles' classes twice.
    edges: Vec<u8>,
    /// Triangles near a move kept in this pass or the previous one: after the first strict
    /// and sideways passes, only leaves among them can have a move not tried before.
    near: Marks,
    near_next: Marks,
    /// Triangles within two edges of a costly T0 when a strict pass starts: a strict move
    /// can only lower the cost when its leaf or its new triangle is among them.
    hot: Marks,
    /// The triangles in `set` while [`affected`] fills it.
    listed: Marks,
}

impl LeafMoves {
    pub(super) fn new(mesh: &Closed) -> LeafMoves {
        LeafMoves {
            leaves: Vec::new(),
            set: Vec::with_capacity(32),
            edges: vec![0; mesh.triangle_count()],
            near: Marks::new(mesh.triangle_count()),
            near_next: Marks::new(mesh.triangle_count()),
            hot: Marks::new(mesh.triangle_count()),
            listed: Marks::new(mesh.triangle_count()),
        }
    }

    /// Applies leaf moves to the triangles `tm` of a component whose triangles are
    /// `triangles`. The visited vertices do not change: every move keeps its tip on the ring.
    pub(super) fn improve(&mut self, mesh: &Closed, triangles: &[u32], tm: &mut Marks) {
        for &t in triangles {
            self.edges[t as usize] = ring_edges(mesh, tm, t) as u8;
        }
        for pass in 0..PASSES {
            let sideways = pass % 2 == 1;
            let everywhere = pass == 0 || sideways;
            if !sideways {
                self.mark_hot(mesh, triangles);
            }
            let (near, edges) = (&self.near, &self.edges);
            self.leaves.clear();
            self.leaves.extend(triangles.iter().copied().filter(|&t| {
                t < mesh.real_triangles
                    && edges[t as usize] == 2
                    && (everywhere || near.get(t as usize))
            }));
            let mut improved = false;
            for k in 0..self.leaves.len() {
                let a = self.leaves[k];
                // An earlier move this pass may have made it a leaf no more.
                if self.edges[a as usize] != 2 {
                    continue;
                }
                if let Some(lowered) = self.try_leaf(mesh, tm, a, sideways) {
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
            self.hot.clear(t as usize);
        }
    }

    /// Marks the triangles within two edges of a costly T0 ([`LeafMoves::hot`]).
    fn mark_hot(&mut self, mesh: &Closed, triangles: &[u32]) {
        for &t in triangles {
            self.hot.clear(t as usize);
        }
        for &t in triangles {
            if !self.costly(mesh, t) {
                continue;
            }
            for i in 0..3 {
                let u = mesh.o(3 * t + i) / 3;
                self.hot.set(u as usize);
                for k in 0..3 {
                    self.hot.set((mesh.o(3 * u + k) / 3) as usize);
                }
            }
        }
    }

    /// Tries the moves of leaf `a` in turn around its tip and keeps the first that lowers
    /// the cost (or, `sideways`, that does not raise it): `Some(whether it lowered it)`, with
    /// the triangles it affected in `set`; `None` when no move was kept.
    fn try_leaf(&mut self, mesh: &Closed, tm: &mut Marks, a: u32, sideways: bool) -> Option<bool> {
        // The corner at the tip faces the leaf's one edge to a triangle on its side.
        let side = tm.get(a as usize);
        let tip = (3 * a..3 * a + 3).find(|&c| tm.get(mesh.o(c) as usize / 3) == side)?;
        // Around the tip by c.s = c.n.o.n, from the fan triangle after `a` until back at it.
        let mut c = next3(mesh.o(next3(tip)));
        for _ in 0..MAX_FAN {
            let f = c / 3;
            if f == a {
                break;
            }
            let across = mesh.o(c) / 3;
            c = next3(mesh.o(next3(c)));
            let candidate = f < mesh.real_triangles
                && tm.get(f as usize) != side
                && tm.get(across as usize) == side;
            if !candidate || !(sideways || self.hot.get(a as usize) || self.hot.get(f as usize)) {
                continue;
            }
            affected(mesh, a, f, &mut self.set, &mut self.listed);
            let before = self.cost(mesh);
            // Nothing to lower, and a strict pass keeps nothing else.
            if before == 0 && !sideways {
                continue;
            }
            let saved = self.flip(mesh, tm, a, f, !side);
            let after = self.cost(mesh);
            if after < before || (sideways && after == before) {
                return Some(after < before);
            }
            self.undo(tm, a, f, side, &saved);
        }
        None
    }

    /// Puts `a` on side `a_side` and `f` on the other, and updates the ring edges of both
    /// and of their neighbours; returns the eight triangles and their ring edges before, for
    /// [`undo`](Self::undo).
    fn flip(
        &mut self,
        mesh: &Closed,
        tm: &mut Marks,
        a: u32,
        f: u32,
        a_side: bool,
    ) -> [(u32, u8); 8] {
        tm.put(a as usize, a_side);
        tm.put(f as usize, !a_side);
        let mut saved = [(0, 0); 8];
        let mut k = 0;
        for t in [a, f] {
            for u in [
                t,
                mesh.o(3 * t) / 3,
                mesh.o(3 * t + 1) / 3,
                mesh.o(3 * t + 2) / 3,
            ] {
                saved[k] = (u, self.edges[u as usize]);
                self.edges[u as usize] = ring_edges(mesh, tm, u) as u8;
                k += 1;
            }
        }
        saved
    }

    /// Takes back a [`flip`](Self::flip) that put `a` off side `a_side`: the sides, and the
    /// ring edges it saved (last first, so that a triangle saved twice gets its first value).
    fn undo(&mut self, tm: &mut Marks, a: u32, f: u32, a_side: bool, saved: &[(u32, u8); 8]) {
        tm.put(a as usize, a_side);
        tm.put(f as usize, !a_side);
        for &(u, edges) in saved.iter().rev() {
            self.edges[u as usize] = edges;
        }
    }

    /// The T0 triangles without a wart among `set` (as the construction's score counts
    /// them).
    fn cost(&self, mesh: &Closed) -> usize {
        self.set.iter().filter(|&&t| self.costly(mesh, t)).count()
    }

    /// Whether `t` is a real T0 without a wart, from the cached ring edges.
    #[inline]
    fn costly(&self, mesh: &Closed, t: u32) -> bool {
        t0_without_wart(mesh, t, |u| self.edges[u as usize] as usize)
    }
}

/// The triangles whose cost a move of `a` and `f` can change, into `out` once each: those
/// two, their neighbours (whose ring edges change) and the neighbours' neighbours (whose wart
/// can change). `listed` marks the ones in `out` while it is filled (cleared after): some
/// twenty triangles, many met twice, which a sort took longer to deduplicate.
fn affected(mesh: &Closed, a: u32, f: u32, out: &mut Vec<u32>, listed: &mut Marks) {
    out.clear();
    let mut add = |t: u32| {
        if !listed.get(t as usize) {
            listed.set(t as usize);
            out.push(t);
        }
    };
    for t in [a, f] {
        add(t);
        for i in 0..3 {
            let u = mesh.o(3 * t + i) / 3;
            add(u);
            for k in 0..3 {
                add(mesh.o(3 * u + k) / 3);
            }
        }
    }
    for &t in out.iter() {
        listed.clear(t as usize);
    }
}
