//! The rings of an LR construction: on the corner table closed over its boundaries
//! ([`Closed`]), RING-EXPANDER (or HYBRID-RING-EXPANDER) per component from the best of
//! several seed corners, improved by leaf moves ([`super::leaf_moves`]), and the walk that
//! numbers the ring vertices. [`Prepared`] holds what every ring of one corner table shares,
//! so that the bit-efficient LR can compare periods without closing the mesh again.

use super::closed::{prev3, Closed};
use super::compact::{plain, BLOCK_SHIFT, SHORT_MAX};
use super::leaf_moves::LeafMoves;
use super::{LrOptions, NULL};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use expansion::Expansion;

mod expansion;

/// Per-component work lists of the closed mesh.
struct Component {
    /// Real and dummy triangles.
    triangles: Vec<u32>,
    /// Where the dummy triangles are in `triangles`, in increasing order (few: one per
    /// boundary edge), so that the real ones, from which the seeds are drawn, need no list
    /// of their own.
    dummies_at: Vec<u32>,
    /// Real vertices.
    vertices: Vec<u32>,
}

impl Component {
    /// Real triangles in the component.
    fn real_count(&self) -> usize {
        self.triangles.len() - self.dummies_at.len()
    }

    /// The `r`-th real triangle of `triangles` (`r < real_count()`): it is at `r` plus the
    /// number of dummies before it, which are the dummies `j` with at most `r` real
    /// triangles before them (`dummies_at[j] - j`, non-decreasing in `j`).
    fn real_triangle(&self, r: usize) -> u32 {
        let (mut lo, mut hi) = (0, self.dummies_at.len());
        while lo < hi {
            let j = (lo + hi) / 2;
            if self.dummies_at[j] as usize - j <= r {
                lo = j + 1;
            } else {
                hi = j;
            }
        }
        self.triangles[r + lo]
    }
}

fn components(mesh: &Closed) -> Vec<Component> {
    let nt = mesh.triangle_count();
    let mut seen = vec![false; nt];
    let mut vertex_seen = vec![false; mesh.real_vertices as usize];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..mesh.real_triangles {
        if seen[start as usize] {
            continue;
        }
        let mut comp = Component {
            triangles: Vec::new(),
            dummies_at: Vec::new(),
            vertices: Vec::new(),
        };
        seen[start as usize] = true;
        stack.push(start);
        while let Some(t) = stack.pop() {
            if t >= mesh.real_triangles {
                comp.dummies_at.push(comp.triangles.len() as u32);
            }
            comp.triangles.push(t);
            for i in 0..3 {
                let c = 3 * t + i;
                let x = mesh.v(c);
                if x < mesh.real_vertices && !vertex_seen[x as usize] {
                    vertex_seen[x as usize] = true;
                    comp.vertices.push(x);
                }
                let u = mesh.o(c) / 3;
                if !seen[u as usize] {
                    seen[u as usize] = true;
                    stack.push(u);
                }
            }
        }
        if comp.triangles.len() >= ASCENDING_TRIANGLES {
            ascending(&mut comp.triangles);
            ascending(&mut comp.vertices);
            // The dummy triangles, numbered after the real ones, are now last.
            let (real, all) = (comp.real_count() as u32, comp.triangles.len() as u32);
            comp.dummies_at = (real..all).collect();
        }
        // Grown by doubling: up to half of each list would be slack through the expansions.
        comp.triangles.shrink_to_fit();
        comp.vertices.shrink_to_fit();
        out.push(comp);
    }
    out
}

/// Components of at least this many triangles keep their lists in increasing order: every
/// pass over a component (resetting its marks, scoring a try, copying the best) then reads
/// the tables and the marks in order instead of in the order of the search, which on a large
/// mesh is a cache miss per triangle. Smaller components keep the search order (their
/// passes stay in cache either way), and so the seed corners and rings they always had.
const ASCENDING_TRIANGLES: usize = 1 << 16;

/// Puts distinct `ids` in increasing order in linear time: through a bit set over their range
/// when it is at most 64 times as long as the list (a component's ids usually are: a mesh
/// lists neighbours near one another), by sorting otherwise.
fn ascending(ids: &mut [u32]) {
    let (Some(&lo), Some(&hi)) = (ids.iter().min(), ids.iter().max()) else {
        return;
    };
    let range = (hi - lo) as usize + 1;
    if range / 64 > ids.len() {
        ids.sort_unstable();
        return;
    }
    let mut marks = Marks::new(range);
    for &x in ids.iter() {
        marks.set((x - lo) as usize);
    }
    let mut k = 0;
    for (w, &word) in marks.0.iter().enumerate() {
        let mut bits = word;
        while bits != 0 {
            ids[k] = lo + 64 * w as u32 + bits.trailing_zeros();
            k += 1;
            bits &= bits - 1;
        }
    }
}

/// Ring edges of triangle `t`: edges to a neighbour on the other side of the ring.
pub(super) fn ring_edges(mesh: &Closed, tm: &Marks, t: u32) -> usize {
    let inside = tm.get(t as usize);
    (0..3)
        .filter(|&i| tm.get(mesh.o(3 * t + i) as usize / 3) != inside)
        .count()
}

/// Whether triangle `t` is a real T0 that no wart can take, given the ring edges of any
/// triangle: no ring edge and no real T2 neighbour. (A T2 has one edge off the ring, so no
/// two T0s compete for it, and every other T0 finds a wart.)
#[inline]
pub(super) fn t0_without_wart(mesh: &Closed, t: u32, edges: impl Fn(u32) -> usize) -> bool {
    let t2 = |u: u32| u < mesh.real_triangles && edges(u) == 2;
    t < mesh.real_triangles && edges(t) == 0 && !(0..3).any(|i| t2(mesh.o(3 * t + i) / 3))
}

/// T0 triangles of a component that no wart can take.
fn t0_after_warts(mesh: &Closed, comp: &Component, tm: &Marks) -> usize {
    let edges = |u| ring_edges(mesh, tm, u);
    comp.triangles
        .iter()
        .filter(|&&t| t0_without_wart(mesh, t, edges))
        .count()
}

fn reset(comp: &Component, vm: &mut Marks, tm: &mut Marks) {
    for &x in &comp.vertices {
        vm.clear(x as usize);
    }
    for &t in &comp.triangles {
        tm.clear(t as usize);
    }
}

/// What every ring construction of one corner table shares: the closed mesh and its
/// components.
pub(super) struct Prepared<'a> {
    pub(super) mesh: Closed<'a>,
    components: Vec<Component>,
}

/// The walked rings of every component.
pub(super) struct Rings {
    /// Per ring vertex, in ring order: the tip corner of its left slot.
    pub(super) ring_corner: Vec<u32>,
    /// Where each ring starts in `ring_corner`, then its length.
    pub(super) starts: Vec<u32>,
    /// Per real vertex: its ring position, `NONE` off the rings.
    pub(super) ring_id: Vec<u32>,
}

impl<'a> Prepared<'a> {
    /// Closes `ct` and finds its components.
    ///
    /// # Errors
    /// [`Error::Unsupported`] when the mesh exceeds the LR's vertex ids.
    pub(super) fn new(ct: &'a CornerTable) -> Result<Prepared<'a>> {
        let mesh = Closed::new(ct)?;
        if mesh.real_vertices >= NULL {
            return Err(Error::Unsupported(
                "LR holds at most 2^30 - 2 vertices".into(),
            ));
        }
        let components = components(&mesh);
        Ok(Prepared { mesh, components })
    }

    /// Triangles of the closed mesh, dummies included.
    pub(super) fn triangle_count(&self) -> usize {
        self.mesh.triangle_count()
    }

    /// The closed mesh, the components freed.
    pub(super) fn into_closed(self) -> Closed<'a> {
        self.mesh
    }

    /// The rings by RING-EXPANDER (`period` 0) or HYBRID-RING-EXPANDER of `period`: per
    /// component the best of `tries` seed corners drawn from `seed`
    /// ([`Expansion::best_of`]), walked to number its vertices.
    pub(super) fn rings(&self, period: u32, options: &LrOptions) -> Rings {
        let mut expansion = Expansion::new(&self.mesh, period, options.seed, options.threads);
        let mut rings = Rings::new(&self.mesh);
        // At most one ring vertex per real vertex: no slack from growing by doubling.
        let vertices = self.components.iter().map(|c| c.vertices.len()).sum();
        rings.ring_corner.reserve_exact(vertices);
        let mut moves = LeafMoves::new(&self.mesh);
        for comp in &self.components {
            expansion.best_of(comp, options.tries);
            moves.improve(&self.mesh, &comp.triangles, &mut expansion.main.tm);
            rings.walk(&self.mesh, comp, &expansion.main.tm);
        }
        rings
    }

    /// A guess of what the rings of `period` cost a bit-efficient LR beyond its pair words,
    /// in bytes: a T0 row and the records of its irregular neighbours for each T0 triangle no
    /// wart takes, more for one whose vertices lie too far apart along the ring for a row,
    /// and a record for each pair with a tip too far for a plain pair's field, without tip
    /// bases or with them and their bytes, whichever is less, as the writer chooses (only a
    /// component of more vertices than a near field reaches can have such tips, so only
    /// such a component's ring is walked). The rings are one expansion per component (the first
    /// seed corner of [`Prepared::rings`]), or with `exact` the rings the build makes (all
    /// its tries and the leaf moves). The factors are least-squares fits of the built sizes
    /// over the shared meshes and periods; `lr::compact` ranks periods by it.
    ///
    /// The sum only grows, so it stops as soon as it reaches `bound` (the best period's so
    /// far), before the walks that cost most: a result at or above `bound` only says that
    /// this period is no better.
    pub(super) fn compact_estimate(
        &self,
        period: u32,
        options: &LrOptions,
        exact: bool,
        bound: u64,
    ) -> u64 {
        let mesh = &self.mesh;
        let mut expansion = Expansion::new(mesh, period, options.seed, 1);
        let mut rings = Rings::new(mesh);
        let mut moves = exact.then(|| LeafMoves::new(mesh));
        let mut bytes = 0;
        // Long pairs without and with tip bases, and the bytes of the bases.
        let (mut long, mut bases) = ([0u64; 2], 0u64);
        for comp in &self.components {
            let t0 = match moves.as_mut() {
                Some(moves) => {
                    expansion.best_of(comp, options.tries);
                    let tm = &mut expansion.main.tm;
                    moves.improve(mesh, &comp.triangles, tm);
                    t0_after_warts(mesh, comp, tm)
                }
                None => expansion.best_of(comp, 1),
            };
            bytes += T0_BYTES * t0 as u64;
            if bytes >= bound {
                return bytes;
            }
            if comp.vertices.len() as i64 > plain::NEAR_MAX {
                let first = rings.ring_corner.len();
                let tm = &expansion.main.tm;
                rings.walk(mesh, comp, tm);
                bytes += FAR_T0_BYTES * rings.far_t0(mesh, comp, tm);
                if bytes >= bound {
                    return bytes;
                }
                let offsets = rings.tip_offsets(mesh, first);
                let [without, with] = plain::long_pairs(&offsets, 1 << BLOCK_SHIFT);
                long[0] += without;
                long[1] += with;
                bases += BASE_BYTES * offsets.len().div_ceil(1 << BLOCK_SHIFT) as u64;
            }
        }
        // The writer keeps the tip bases when they save bytes.
        bytes + (LONG_PAIR_BYTES * long[0]).min(LONG_PAIR_BYTES * long[1] + bases)
    }
}

/// Estimated bytes of a pair whose tip is too far for a plain pair ([`Prepared::compact_estimate`]).
const LONG_PAIR_BYTES: u64 = 10;
/// Bytes of a block's two tip bases.
const BASE_BYTES: u64 = 8;
/// Estimated bytes beyond [`T0_BYTES`] of a T0 triangle whose vertices lie too far apart
/// along the ring for a row's offsets: an overflow row, and long corner fields for the
/// records that name it.
const FAR_T0_BYTES: u64 = 32;
/// Estimated bytes of a T0 triangle: its row and its neighbours' records.
const T0_BYTES: u64 = 26;

/// One bit per vertex or triangle: the marks of a ring expansion, eight times smaller than
/// `bool`s, so that more of them stay in cache while the expander walks a large mesh.
pub(super) struct Marks(Vec<u64>);

impl Marks {
    pub(super) fn new(n: usize) -> Marks {
        Marks(vec![0; n.div_ceil(64)])
    }

    #[inline(always)]
    pub(super) fn get(&self, i: usize) -> bool {
        self.0[i >> 6] >> (i & 63) & 1 != 0
    }

    #[inline(always)]
    pub(super) fn set(&mut self, i: usize) {
        self.0[i >> 6] |= 1 << (i & 63);
    }

    #[inline(always)]
    pub(super) fn clear(&mut self, i: usize) {
        self.0[i >> 6] &= !(1 << (i & 63));
    }

    #[inline(always)]
    pub(super) fn put(&mut self, i: usize, on: bool) {
        if on {
            self.set(i)
        } else {
            self.clear(i)
        }
    }
}

impl Rings {
    fn new(mesh: &Closed) -> Rings {
        Rings {
            ring_corner: Vec::new(),
            starts: vec![0u32],
            ring_id: vec![NONE; mesh.real_vertices as usize],
        }
    }

    /// Walks the ring of `comp`'s invaded triangles `tm`, numbering its vertices; a ring of
    /// three adds nothing (the component stays T0 triangles and isolated vertices).
    fn walk(&mut self, mesh: &Closed, comp: &Component, tm: &Marks) {
        // A corner of an invaded triangle facing a non-invaded one starts the walk.
        let start = comp
            .triangles
            .iter()
            .filter(|&&t| tm.get(t as usize))
            .flat_map(|&t| 3 * t..3 * t + 3)
            .find(|&c| !tm.get(mesh.o(c) as usize / 3))
            .expect("an invaded region has a boundary");
        let first = self.ring_corner.len();
        let mut c = start;
        loop {
            self.ring_corner.push(c);
            // Rotate around the far vertex through invaded triangles to the next ring edge.
            let mut k = prev3(c);
            while tm.get(mesh.o(k) as usize / 3) {
                k = prev3(mesh.o(k));
            }
            c = k;
            if c == start {
                break;
            }
        }
        if self.ring_corner.len() - first == 3 {
            self.ring_corner.truncate(first);
            return;
        }
        for (k, &c) in self.ring_corner[first..].iter().enumerate() {
            self.ring_id[mesh.v(prev3(c)) as usize] = (first + k) as u32;
        }
        self.starts.push(self.ring_corner.len() as u32);
    }

    /// The T0 triangles of `comp` (marks `tm`, walked) that no wart takes and whose vertices
    /// lie further apart along the rings than a T0 row's 15-bit offsets reach, or off them
    /// ([`Prepared::compact_estimate`]).
    fn far_t0(&self, mesh: &Closed, comp: &Component, tm: &Marks) -> u64 {
        let edges = |u| ring_edges(mesh, tm, u);
        let far = |t: u32| {
            let ids = [0, 1, 2].map(|i| self.ring_id[mesh.v(3 * t + i) as usize]);
            let (lo, hi) = (ids.iter().min(), ids.iter().max());
            ids.contains(&NONE) || hi.zip(lo).is_some_and(|(h, l)| (h - l) as i64 > SHORT_MAX)
        };
        comp.triangles
            .iter()
            .filter(|&&t| t0_without_wart(mesh, t, edges) && far(t))
            .count() as u64
    }

    /// The offsets `tip − v` of the left and right tips of the ring vertices from position
    /// `first` on, as [`plain::long_pairs`] takes them: 0 for a dummy (`NULL`), `i64::MAX`
    /// for a tip off the rings ([`Prepared::compact_estimate`]).
    fn tip_offsets(&self, mesh: &Closed, first: usize) -> Vec<[i64; 2]> {
        let offset = |v: usize, tip: u32| {
            if tip >= mesh.real_vertices {
                return 0; // a dummy: NULL
            }
            match self.ring_id[tip as usize] {
                NONE => i64::MAX,
                r => r as i64 - v as i64,
            }
        };
        let corners = self.ring_corner.iter().enumerate().skip(first);
        corners
            .map(|(v, &c)| [offset(v, mesh.v(c)), offset(v, mesh.v(mesh.o(c)))])
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Rng;

    /// Dense ids go through the bit set, sparse ones through the sort: both sort.
    #[test]
    fn ascending_sorts_dense_and_sparse_ids() {
        let mut rng = Rng::new(7);
        for (count, range) in [
            (0, 1),
            (1, 1),
            (1000, 1500),
            (1000, 64_000),
            (1000, 1 << 30),
        ] {
            let mut ids: Vec<u32> = (0..count).map(|_| rng.below(range)).collect();
            ids.sort_unstable();
            ids.dedup();
            let expected = ids.clone();
            // Shuffled, as a search lists them.
            rng.shuffle(&mut ids);
            ascending(&mut ids);
            assert_eq!(ids, expected, "{count} ids below {range}");
        }
    }

    /// Leaf moves never raise a component's count of T0 triangles without a wart, lower it
    /// on irregular meshes, and keep the ring through the same vertices, each once.
    #[cfg(feature = "generate")]
    #[test]
    fn leaf_moves_lower_costly_t0s_and_keep_the_ring_vertices() {
        use crate::generate::{surface, SurfaceOptions};
        for (genus, holes, components) in [(0, 0, 1), (2, 12, 3), (1, 40, 2)] {
            let mesh = surface(&SurfaceOptions {
                triangles: 12_000,
                genus,
                holes,
                components,
                irregular: true,
                seed: 5,
            });
            let ct = CornerTable::from_mesh(&mesh).unwrap();
            let prepared = Prepared::new(&ct).unwrap();
            let closed = &prepared.mesh;
            let mut expansion = Expansion::new(closed, 0, 1, 1);
            let mut moves = LeafMoves::new(closed);
            let ring_vertices = |tm: &Marks, comp: &Component| {
                let mut rings = Rings::new(closed);
                rings.walk(closed, comp, tm);
                let mut v: Vec<u32> = rings
                    .ring_corner
                    .iter()
                    .map(|&c| closed.v(prev3(c)))
                    .collect();
                let len = v.len();
                v.sort_unstable();
                v.dedup();
                assert_eq!(v.len(), len, "a vertex twice on the ring");
                v
            };
            let (mut before, mut after) = (0, 0);
            for comp in &prepared.components {
                expansion.best_of(comp, 4);
                let tm = &mut expansion.main.tm;
                let (count, vertices) = (t0_after_warts(closed, comp, tm), ring_vertices(tm, comp));
                moves.improve(closed, &comp.triangles, tm);
                let moved = t0_after_warts(closed, comp, tm);
                assert!(moved <= count, "{moved} after the moves, {count} before");
                assert_eq!(ring_vertices(tm, comp), vertices);
                (before, after) = (before + count, after + moved);
            }
            assert!(
                after < before,
                "genus {genus}: {after} of {before} T0s left"
            );
        }
    }

    /// A bound cuts a period's estimate short only at or above the bound, so the period
    /// chosen is the one the whole estimates rank first: checked on components above and
    /// below the near field's reach (walked or not), with and without `exact`.
    #[cfg(feature = "generate")]
    #[test]
    fn bounded_estimates_stop_only_at_or_above_the_bound() {
        use crate::generate::{surface, SurfaceOptions};
        let mesh = surface(&SurfaceOptions {
            triangles: 40_000,
            genus: 2,
            holes: 30,
            components: 2,
            irregular: true,
            seed: 3,
        });
        let ct = CornerTable::from_mesh(&mesh).unwrap();
        let prepared = Prepared::new(&ct).unwrap();
        assert!(prepared
            .components
            .iter()
            .any(|c| c.vertices.len() as i64 > plain::NEAR_MAX));
        let options = LrOptions::default();
        for exact in [false, true] {
            for period in [0, 16, 128] {
                let whole = prepared.compact_estimate(period, &options, exact, u64::MAX);
                assert!(whole > 0);
                for bound in [0, whole / 2, whole, whole + 1] {
                    let cut = prepared.compact_estimate(period, &options, exact, bound);
                    match bound > whole {
                        true => assert_eq!(cut, whole, "period {period}, bound {bound}"),
                        false => assert!(cut >= bound, "period {period}: {cut} below {bound}"),
                    }
                }
            }
        }
    }
}
