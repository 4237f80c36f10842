//! Consistent orientation (`lrmesh encode --orient`): triangles reversed so that every edge
//! two triangles share runs once in each direction, where the surface allows it.
//!
//! An edge used twice in the same direction looks like two boundary edges to the corner
//! table, so a mesh whose triangles were written with mixed orientations (a shuffled CAD
//! export) falls apart into many small pieces, and every representation grows: the LR of
//! corpus `blobby-shuffled` stores 3.9 references per triangle where the same surface,
//! oriented, needs 1.1.

use super::Mesh;

/// A mesh with its orientation made consistent, and what was changed.
#[derive(Debug, Clone, PartialEq)]
pub struct Oriented {
    /// The mesh with the triangles of `flipped` reversed (`[a, b, c]` becomes `[a, c, b]`,
    /// per-corner attribute values following their corners).
    pub mesh: Mesh,
    /// Whether each triangle was reversed.
    pub flipped: Vec<bool>,
    /// Edges of two triangles that still run twice in one direction: each closes a loop of
    /// an odd number of reversals (a Möbius band, a Klein bottle), where no choice agrees.
    pub conflicts: usize,
}

impl Oriented {
    /// Number of triangles reversed.
    pub fn flipped_count(&self) -> usize {
        self.flipped.iter().filter(|&&f| f).count()
    }
}

/// Reverses triangles of `mesh` so that each edge shared by exactly two triangles runs once
/// in each direction wherever the surface is orientable. Per component (triangles joined
/// through such edges), the orientation the majority of its triangles already has is kept,
/// so that a consistent mesh comes back unchanged. Edges of three or more triangles, and
/// degenerate triangles (a repeated vertex), join nothing and are never reversed.
/// Linear in the triangles after one sort of the edges.
pub fn orient(mesh: &Mesh) -> Oriented {
    let tris = &mesh.triangles;
    let n = tris.len();
    let degenerate = |t: &[u32; 3]| t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    // Half-edges by undirected edge: (low, high, triangle, whether it runs low -> high).
    let mut edges: Vec<(u32, u32, u32, bool)> = Vec::with_capacity(3 * n);
    for (t, tri) in tris.iter().enumerate() {
        if degenerate(tri) {
            continue;
        }
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            edges.push((a.min(b), a.max(b), t as u32, a < b));
        }
    }
    edges.sort_unstable();
    // Neighbours through edges of exactly two triangles: (other triangle, same direction).
    let mut start = vec![0u32; n + 1];
    let mut pairs: Vec<(u32, u32, bool)> = Vec::new();
    for run in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        if let [(_, _, s, ds), (_, _, t, dt)] = run {
            if s != t {
                pairs.push((*s, *t, ds == dt));
                start[*s as usize] += 1;
                start[*t as usize] += 1;
            }
        }
    }
    let mut total = 0;
    for x in start.iter_mut() {
        total += *x;
        *x = total;
    }
    let mut adjacent = vec![(0u32, false); total as usize];
    for &(s, t, same) in &pairs {
        for (from, to) in [(s, t), (t, s)] {
            let slot = &mut start[from as usize];
            *slot -= 1;
            adjacent[*slot as usize] = (to, same);
        }
    }

    // Breadth first per component: a neighbour across an edge run in the same direction
    // takes the opposite state, otherwise the same.
    const UNSEEN: u8 = 2;
    let mut state = vec![UNSEEN; n];
    let mut queue = Vec::new();
    let mut conflicts = 0;
    for root in 0..n {
        if state[root] != UNSEEN || degenerate(&tris[root]) {
            continue;
        }
        state[root] = 0;
        queue.clear();
        queue.push(root as u32);
        let mut head = 0;
        while let Some(&t) = queue.get(head) {
            head += 1;
            let (s, e) = (start[t as usize] as usize, start[t as usize + 1] as usize);
            for &(u, same) in &adjacent[s..e] {
                let wanted = state[t as usize] ^ same as u8;
                match state[u as usize] {
                    UNSEEN => {
                        state[u as usize] = wanted;
                        queue.push(u);
                    }
                    // Each such edge is met from both sides.
                    x if x != wanted && t < u => conflicts += 1,
                    _ => {}
                }
            }
        }
        // Keep the majority's orientation.
        let reversed = queue.iter().filter(|&&t| state[t as usize] == 1).count();
        if 2 * reversed > queue.len() {
            for &t in &queue {
                state[t as usize] ^= 1;
            }
        }
    }
    let flipped: Vec<bool> = state.iter().map(|&s| s == 1).collect();
    Oriented {
        mesh: reversed(mesh, &flipped),
        flipped,
        conflicts,
    }
}

/// `mesh` with each triangle `t` where `flipped[t]` reversed: `[a, b, c]` becomes
/// `[a, c, b]`, and the per-corner values of corners 1 and 2 trade places with them. Its own
/// inverse.
pub fn reversed(mesh: &Mesh, flipped: &[bool]) -> Mesh {
    let mut out = mesh.clone();
    for (t, _) in flipped.iter().enumerate().filter(|(_, &f)| f) {
        reverse_triangle(&mut out, t);
    }
    out
}

/// Reverses triangle `t` of `mesh` in place: `[a, b, c]` becomes `[a, c, b]`, and the
/// per-corner values of corners 1 and 2 trade places with them. The one place that does it,
/// for [`reversed`] and for the reader's section `FLIP`.
pub(crate) fn reverse_triangle(mesh: &mut Mesh, t: usize) {
    mesh.triangles[t].swap(1, 2);
    for a in &mut mesh.attributes {
        if let Some(corners) = &mut a.corners {
            corners.swap(3 * t + 1, 3 * t + 2);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate;

    /// Directed edges used by more than one triangle.
    fn repeated_directions(mesh: &Mesh) -> usize {
        let mut directed: Vec<(u32, u32)> = mesh
            .triangles
            .iter()
            .flat_map(|t| (0..3).map(move |i| (t[i], t[(i + 1) % 3])))
            .collect();
        directed.sort_unstable();
        directed.windows(2).filter(|w| w[0] == w[1]).count()
    }

    #[test]
    fn a_shuffled_torus_comes_back_consistent_and_the_flips_undo() {
        let mut mesh = generate::torus(12, 9);
        let before = mesh.clone();
        let mut rng = crate::rng::Rng::new(5);
        let shuffled: Vec<bool> = (0..mesh.triangles.len())
            .map(|_| rng.below(3) == 0)
            .collect();
        mesh = reversed(&mesh, &shuffled);
        assert!(repeated_directions(&mesh) > 0);
        let o = orient(&mesh);
        assert_eq!(repeated_directions(&o.mesh), 0);
        assert_eq!(o.conflicts, 0);
        // The majority kept: exactly the triangles reversed above come back.
        assert_eq!(o.mesh, before);
        assert_eq!(o.flipped, shuffled);
        assert_eq!(reversed(&o.mesh, &o.flipped), mesh);
    }

    #[test]
    fn a_consistent_mesh_is_unchanged() {
        let mesh = generate::irregular_torus(2000, 3);
        let o = orient(&mesh);
        assert_eq!(o.flipped_count(), 0);
        assert_eq!(o.mesh, mesh);
    }

    #[test]
    fn a_moebius_band_keeps_one_conflict() {
        // A strip of 8 quads whose ends join with a half twist.
        let k = 8u32;
        let mut triangles = Vec::new();
        for i in 0..k {
            let (a, b) = (i, i + k);
            let (c, d) = if i + 1 < k {
                (i + 1, i + 1 + k)
            } else {
                (k, 0)
            };
            triangles.push([a, b, c]);
            triangles.push([c, b, d]);
        }
        let mesh = Mesh::new(vec![[0.0; 3]; 2 * k as usize], triangles);
        let o = orient(&mesh);
        assert_eq!(o.conflicts, 1);
        assert_eq!(repeated_directions(&o.mesh), 1);
    }

    #[test]
    fn per_corner_values_follow_their_corners() {
        let mut mesh = Mesh::new(
            vec![[0.0; 3]; 4],
            vec![[0, 1, 2], [1, 2, 3]], // the second runs 1 -> 2 as the first does
        );
        mesh.attributes.push(crate::mesh::Attribute {
            semantic: crate::mesh::Semantic::Custom("k".into()),
            components: 1,
            normalized: false,
            values: crate::mesh::Values::U32((0..6).collect()),
            corners: Some((0..6).collect()),
        });
        let o = orient(&mesh);
        assert_eq!(o.flipped_count(), 1);
        let t = o.flipped.iter().position(|&f| f).unwrap();
        let corners = o.mesh.attributes[0].corners.as_ref().unwrap();
        let tri = o.mesh.triangles[t];
        // Vertex `tri[k]` still has the value it had at that vertex.
        for k in 0..3 {
            let original = mesh.triangles[t].iter().position(|&v| v == tri[k]).unwrap();
            assert_eq!(corners[3 * t + k], (3 * t + original) as u32);
        }
    }
}
