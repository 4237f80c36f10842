//! The standard corner operators (LR paper, Fig. 2) as a trait, and algorithms written once on
//! top of it: a vertex's star, valence, vertex normals and the contour traversal.
//!
//! Every connectivity representation of the crate implements [`CornerOps`]; tests check each one
//! against the corner table through it. Ids need not be dense: a representation may leave gaps,
//! so loops go through [`CornerOps::triangles`] and [`CornerOps::vertices`], not `0..count`.

use crate::ids::{Corner, Triangle, Vertex};

/// The standard set of corner operators over one pseudo-manifold triangle mesh.
///
/// Corners of a triangle are ordered so that `next` walks its vertices in the triangle's
/// orientation. `opposite` is `None` across a boundary (or cut) edge.
///
/// # Panics
/// The operators take ids of the mesh: corners of its triangles ([`CornerOps::corners`], or
/// answers of other operators), vertices and triangles below the bounds. An id beyond a
/// bound panics. Representations whose corner ids have gaps (the LR's and the strips' ids
/// follow their tables) answer an unused id below the bound without checking it, for speed:
/// the answer is then unspecified, or a panic (never undefined behaviour). Callers that hold ids
/// from elsewhere check them first, or go through [`crate::read::Connectivity`], which
/// panics on any id that is not a corner rather than make an answer up.
pub trait CornerOps {
    /// Exclusive upper bound of vertex ids.
    fn vertex_id_bound(&self) -> u32;
    /// Exclusive upper bound of triangle ids.
    fn triangle_id_bound(&self) -> u32;
    /// Every triangle, once.
    fn triangles(&self) -> impl Iterator<Item = Triangle> + '_;
    /// Every vertex, once, including vertices that no triangle uses.
    fn vertices(&self) -> impl Iterator<Item = Vertex> + '_;

    /// `c.v`: the vertex of corner `c`.
    fn vertex(&self, c: Corner) -> Vertex;
    /// `c.t`: the triangle of corner `c`.
    fn triangle(&self, c: Corner) -> Triangle;
    /// `c.n`: the next corner around `c.t`.
    fn next(&self, c: Corner) -> Corner;
    /// `c.p`: the previous corner around `c.t`.
    fn prev(&self, c: Corner) -> Corner;
    /// `c.o`: the corner facing `c` across the edge opposite `c`; `None` on a boundary.
    fn opposite(&self, c: Corner) -> Option<Corner>;
    /// `v.c`: a corner of vertex `v`, from which [`CornerOps::swing`] visits all of `v`'s
    /// corners; `None` for a vertex without triangles.
    fn vertex_corner(&self, v: Vertex) -> Option<Corner>;
    /// Some corner of vertex `v`, not necessarily `v.c`; `None` for a vertex without
    /// triangles. Walks that go round a fan both ways from where they start ([`valence`],
    /// [`vertex_normal`]) need no more, and an LR layout without a list of open fans finds
    /// `v.c` of a vertex next to a boundary off the ring only by walking the fan back to its
    /// start (which made those walks twice as long on every vertex of such a mesh). By
    /// default `v.c`.
    #[inline(always)]
    fn any_corner(&self, v: Vertex) -> Option<Corner> {
        self.vertex_corner(v)
    }
    /// `t.c`: the first corner of triangle `t`.
    fn triangle_corner(&self, t: Triangle) -> Corner;

    /// `c.s = c.n.o.n`: the next corner around `c.v`; `None` at a boundary.
    #[inline(always)]
    fn swing(&self, c: Corner) -> Option<Corner> {
        self.opposite(self.next(c)).map(|d| self.next(d))
    }
    /// `c.p.o.p`: the previous corner around `c.v` (the inverse of swing); `None` at a boundary.
    #[inline(always)]
    fn unswing(&self, c: Corner) -> Option<Corner> {
        self.opposite(self.prev(c)).map(|d| self.prev(d))
    }
    /// `c.l = c.n.o`: the left neighbour of `c`.
    #[inline]
    fn left(&self, c: Corner) -> Option<Corner> {
        self.opposite(self.next(c))
    }
    /// `c.r = c.p.o`: the right neighbour of `c`.
    #[inline]
    fn right(&self, c: Corner) -> Option<Corner> {
        self.opposite(self.prev(c))
    }
    /// The three corners of `t`, starting at `t.c`.
    #[inline]
    fn triangle_corners(&self, t: Triangle) -> [Corner; 3] {
        let c = self.triangle_corner(t);
        [c, self.next(c), self.prev(c)]
    }
    /// The three vertices of `t`, in its orientation, starting at `t.c.v`.
    #[inline]
    fn triangle_vertices(&self, t: Triangle) -> [Vertex; 3] {
        self.triangle_corners(t).map(|c| self.vertex(c))
    }
    /// Every corner, once: three per triangle.
    fn corners(&self) -> impl Iterator<Item = Corner> + '_ {
        self.triangles().flat_map(move |t| self.triangle_corners(t))
    }
}

/// Most steps of a walk around a vertex or across triangles: a corner count no valid mesh
/// exceeds. Walks stop there, so that on tables whose operators answer ids in range but do
/// not form fans (a container opened without [`crate::read::open_verified`]'s checks)
/// they still end.
#[inline(always)]
fn walk_limit<M: CornerOps + ?Sized>(mesh: &M) -> u32 {
    mesh.triangle_id_bound().saturating_mul(3)
}

/// The first corner of `c`'s fan: unswinging from `c` until there is no unswing (an open
/// fan) or the walk comes back to `c` (a closed fan, where `c` itself is returned). At most
/// one step per corner of the vertex, when swing is injective (every valid mesh), and never
/// more than the walk limit.
pub fn fan_start<M: CornerOps + ?Sized>(mesh: &M, c: Corner) -> Corner {
    let mut d = c;
    let mut steps = walk_limit(mesh);
    while let Some(e) = mesh.unswing(d) {
        if e == c || steps == 0 {
            return c;
        }
        steps -= 1;
        d = e;
    }
    d
}

/// The corners around a vertex, in swing order (see [`star`]).
pub struct Star<'a, M: CornerOps + ?Sized> {
    mesh: &'a M,
    start: Corner,
    current: Option<Corner>,
    backwards: bool,
    /// Corners still allowed (the walk limit).
    left: u32,
}

impl<M: CornerOps + ?Sized> Iterator for Star<'_, M> {
    type Item = Corner;

    fn next(&mut self) -> Option<Corner> {
        let c = self.current?;
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        self.current = if self.backwards {
            self.mesh.unswing(c)
        } else {
            match self.mesh.swing(c) {
                Some(d) if d == self.start => None,
                Some(d) => Some(d),
                None => {
                    // An open fan: finish by walking from the start the other way.
                    self.backwards = true;
                    self.mesh.unswing(self.start)
                }
            }
        };
        Some(c)
    }
}

/// The corners of vertex `v`, each once: swinging from `v.c`, and when the fan is open and
/// `v.c` is not at its end, unswinging from `v.c` for the rest.
pub fn star<M: CornerOps + ?Sized>(mesh: &M, v: Vertex) -> Star<'_, M> {
    let start = mesh.vertex_corner(v);
    Star {
        mesh,
        start: start.unwrap_or(Corner(0)),
        current: start,
        backwards: false,
        left: walk_limit(mesh),
    }
}

/// Number of edges at `v`: its corner count, plus one when its fan is open.
pub fn valence<M: CornerOps + ?Sized>(mesh: &M, v: Vertex) -> u32 {
    let Some(start) = mesh.any_corner(v) else {
        return 0;
    };
    let limit = walk_limit(mesh);
    let mut count = 0;
    let mut c = start;
    loop {
        count += 1;
        match mesh.swing(c) {
            Some(d) if d == start => return count,
            _ if count >= limit => return count,
            Some(d) => c = d,
            None => break,
        }
    }
    // Open fan: count the corners before the start too, and the extra edge.
    let mut c = start;
    while let Some(d) = mesh.unswing(c) {
        if count >= limit {
            break;
        }
        count += 1;
        c = d;
    }
    count + 1
}

fn sub(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The area-weighted normal of `v`: the normalised sum of the cross products of the triangles
/// around it. `positions` is indexed by the representation's vertex ids. Zero for a vertex
/// without triangles or with a degenerate star.
///
/// Each neighbour is read once: going round with swing, a triangle's next vertex is the one
/// before's previous vertex (they share that edge), and going back with unswing, its previous
/// vertex is the next vertex of the one after. The triangles are summed in the order of a
/// star from [`CornerOps::any_corner`].
pub fn vertex_normal<M: CornerOps + ?Sized>(
    mesh: &M,
    positions: &[[f32; 3]],
    v: Vertex,
) -> [f32; 3] {
    let p = positions[v.idx()];
    let mut sum = [0.0f32; 3];
    let mut add = |a: Vertex, b: Vertex| {
        let n = cross(sub(positions[a.idx()], p), sub(positions[b.idx()], p));
        sum = [sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]];
    };
    if let Some(start) = mesh.any_corner(v) {
        let limit = walk_limit(mesh);
        let first = mesh.vertex(mesh.next(start));
        let (mut c, mut a, mut count) = (start, first, 0);
        let open = loop {
            let b = mesh.vertex(mesh.prev(c));
            add(a, b);
            count += 1;
            match mesh.swing(c) {
                Some(d) if d == start => break false,
                _ if count >= limit => break false,
                Some(d) => (c, a) = (d, b),
                None => break true,
            }
        };
        // An open fan: the triangles before the start, walking back.
        let (mut c, mut b) = (start, first);
        while open && count < limit {
            let Some(d) = mesh.unswing(c) else { break };
            let a = mesh.vertex(mesh.next(d));
            add(a, b);
            count += 1;
            (c, b) = (d, a);
        }
    }
    let len = dot(sum, sum).sqrt();
    if len > 0.0 {
        sum.map(|x| x / len)
    } else {
        [0.0; 3]
    }
}

/// The normal of every vertex (see [`vertex_normal`]), indexed by vertex id.
pub fn vertex_normals<M: CornerOps + ?Sized>(mesh: &M, positions: &[[f32; 3]]) -> Vec<[f32; 3]> {
    let mut out = vec![[0.0; 3]; mesh.vertex_id_bound() as usize];
    for v in mesh.vertices() {
        out[v.idx()] = vertex_normal(mesh, positions, v);
    }
    out
}

/// A plane `normal · p = offset`. Points with `normal · p >= offset` are above it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// The plane's normal (need not be unit length).
    pub normal: [f32; 3],
    /// The plane's offset along the normal.
    pub offset: f32,
}

impl Plane {
    /// Whether `p` is on the upper side (or on the plane itself).
    #[inline]
    pub fn above(&self, p: [f32; 3]) -> bool {
        dot(self.normal, p) >= self.offset
    }
}

/// Whether the plane separates the endpoints of the edge facing corner `c`.
#[inline]
fn edge_cut<M: CornerOps + ?Sized>(
    mesh: &M,
    positions: &[[f32; 3]],
    plane: &Plane,
    c: Corner,
) -> bool {
    let a = positions[mesh.vertex(mesh.next(c)).idx()];
    let b = positions[mesh.vertex(mesh.prev(c)).idx()];
    plane.above(a) != plane.above(b)
}

/// Follows the contour from triangle `from` through its cut edge facing `exit`, until it closes
/// at `stop` or leaves the mesh. Pushes every triangle entered.
fn walk_contour<M: CornerOps + ?Sized>(
    mesh: &M,
    positions: &[[f32; 3]],
    plane: &Plane,
    mut exit: Corner,
    stop: Triangle,
    out: &mut Vec<Triangle>,
) -> bool {
    loop {
        let Some(entry) = mesh.opposite(exit) else {
            return false;
        };
        let t = mesh.triangle(entry);
        if t == stop {
            return true;
        }
        if out.len() >= mesh.triangle_id_bound() as usize {
            // More triangles than the mesh has: the tables do not form a surface.
            return false;
        }
        out.push(t);
        // A cut triangle has exactly two cut edges: leave by the one we did not enter by.
        let n = mesh.next(entry);
        exit = if edge_cut(mesh, positions, plane, n) {
            n
        } else {
            mesh.prev(entry)
        };
    }
}

/// The contour of the plane through the mesh from triangle `start` (LR paper, section 8): the
/// triangles the plane cuts, in the order of the walk across cut edges. A closed contour comes
/// back to `start`; an open one runs between two boundary edges and is returned end to end.
/// Empty when the plane does not cut `start`.
pub fn contour<M: CornerOps + ?Sized>(
    mesh: &M,
    positions: &[[f32; 3]],
    plane: &Plane,
    start: Triangle,
) -> Vec<Triangle> {
    let cut: Vec<Corner> = mesh
        .triangle_corners(start)
        .into_iter()
        .filter(|&c| edge_cut(mesh, positions, plane, c))
        .collect();
    let [forward, backward] = cut[..] else {
        return Vec::new();
    };
    let mut ahead = Vec::new();
    if walk_contour(mesh, positions, plane, forward, start, &mut ahead) {
        let mut out = Vec::with_capacity(ahead.len() + 1);
        out.push(start);
        out.extend(ahead);
        return out;
    }
    let mut behind = Vec::new();
    walk_contour(mesh, positions, plane, backward, start, &mut behind);
    behind.reverse();
    behind.push(start);
    behind.extend(ahead);
    behind
}

/// Every contour of the plane through the mesh: each cut triangle appears in exactly one.
pub fn contours<M: CornerOps + ?Sized>(
    mesh: &M,
    positions: &[[f32; 3]],
    plane: &Plane,
) -> Vec<Vec<Triangle>> {
    let mut seen = vec![false; mesh.triangle_id_bound() as usize];
    let mut out = Vec::new();
    for t in mesh.triangles() {
        if seen[t.idx()] {
            continue;
        }
        let line = contour(mesh, positions, plane, t);
        for s in &line {
            seen[s.idx()] = true;
        }
        if !line.is_empty() {
            out.push(line);
        }
    }
    out
}
