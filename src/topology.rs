//! The topology report: what an indexed triangle set is, as read, before any conversion.
//!
//! Definitions (the same as the shared mesh manifest's, and `spec/TOPOLOGY.md`):
//! - an **edge** is an unordered pair of distinct vertices used by at least one triangle; a
//!   triangle uses the edges between its consecutive corners (a degenerate triangle `a a b`
//!   uses `ab` twice and no edge `aa`);
//! - a **boundary edge** is used once; **boundary loops** are the connected pieces of the graph
//!   of boundary edges; a **non-manifold edge** is used three or more times; an
//!   **inconsistent edge** is used exactly twice, both times in the same direction;
//! - **components** are connected through shared vertices;
//! - **euler** = V − E + T with V counting referenced vertices only; **genus** =
//!   (2·components − boundary_loops − euler) / 2 when there are neither non-manifold edges
//!   nor non-manifold vertices (otherwise undefined);
//! - a **non-manifold vertex** has triangles that form more than one fan, fans being connected
//!   through edges at the vertex that two or more of its triangles share;
//! - a **degenerate triangle** repeats a vertex index; a **zero-area triangle** has a zero
//!   cross product (computed in f64); a **duplicate triangle** has the same vertex set as an
//!   earlier one; a **duplicate position** equals an earlier vertex's position;
//! - **valence** is the number of edges at a vertex; the valence figures are over referenced
//!   vertices.

use serde::Serialize;

use crate::corner_table::EdgeBuckets;
use crate::Mesh;

/// The topology of a mesh as read. JSON keys are the field names.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TopologyReport {
    /// Vertices in the file, referenced or not.
    pub vertices: u64,
    /// Triangles, after fan triangulation, degenerate ones included.
    pub triangles: u64,
    /// Distinct edges.
    pub edges: u64,
    /// Edges used by exactly one triangle.
    pub boundary_edges: u64,
    /// Connected pieces of the boundary-edge graph.
    pub boundary_loops: u64,
    /// Connected components through shared vertices.
    pub components: u64,
    /// V − E + T over referenced vertices.
    pub euler: i64,
    /// Genus, where the mesh is edge- and vertex-manifold and the formula gives an integer ≥ 0.
    pub genus: Option<i64>,
    /// Edges used by three or more triangles.
    pub nonmanifold_edges: u64,
    /// Vertices whose triangles form more than one fan.
    pub nonmanifold_vertices: u64,
    /// Edges used twice in the same direction.
    pub inconsistent_edges: u64,
    /// Triangles that repeat a vertex index.
    pub degenerate_triangles: u64,
    /// Triangles with zero area (degenerate ones included).
    pub zero_area_triangles: u64,
    /// Triangles with the same vertex set as an earlier triangle.
    pub duplicate_triangles: u64,
    /// Vertices whose position equals an earlier vertex's.
    pub duplicate_positions: u64,
    /// Vertices used by no triangle.
    pub unreferenced_vertices: u64,
    /// No edge is used more than twice.
    pub edge_manifold: bool,
    /// Every referenced vertex has a single fan.
    pub vertex_manifold: bool,
    /// Every edge used twice is used once in each direction, and none is non-manifold.
    pub oriented: bool,
    /// Percentage of referenced vertices with valence 6.
    pub valence6_pct: f64,
    /// Mean valence of referenced vertices (2E / V).
    pub mean_valence: f64,
    /// Largest valence.
    pub max_valence: u64,
}

/// Union-find with path halving, over `0..n`.
struct UnionFind(Vec<u32>);

impl UnionFind {
    fn new(n: usize) -> Self {
        UnionFind((0..n as u32).collect())
    }
    fn find(&mut self, mut x: u32) -> u32 {
        while self.0[x as usize] != x {
            let up = self.0[self.0[x as usize] as usize];
            self.0[x as usize] = up;
            x = up;
        }
        x
    }
    fn union(&mut self, a: u32, b: u32) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.0[ra.max(rb) as usize] = ra.min(rb);
        }
    }
}

impl TopologyReport {
    /// Computes the report. The mesh must be valid ([`Mesh::validate`]); indices out of range
    /// panic.
    pub fn of(mesh: &Mesh) -> TopologyReport {
        let nv = mesh.positions.len();
        let tris = &mesh.triangles;

        let mut referenced = vec![false; nv];
        for tri in tris {
            for &v in tri {
                referenced[v as usize] = true;
            }
        }
        let referenced_count = referenced.iter().filter(|&&r| r).count() as u64;

        // Every use of an edge as its corner `3t+i` (the edge from corner i to corner i+1 of
        // triangle t), bucketed by its lower vertex.
        let uses = EdgeBuckets::new(nv, 3 * tris.len() as u32, |c| {
            let tri = tris[c as usize / 3];
            let i = c as usize % 3;
            (tri[i], tri[(i + 1) % 3])
        });

        // Corner `3t+i` stands for vertex tri[i] in triangle t; fans join corners of one
        // vertex whose triangles share an edge at that vertex.
        let corner_vertex = |c: u32| tris[c as usize / 3][c as usize % 3];
        let mut fans = UnionFind::new(tris.len() * 3);
        let mut boundary_graph = UnionFind::new(nv);
        let mut in_boundary = vec![false; nv];
        let mut valence = vec![0u32; nv];
        let (mut edges, mut boundary_edges, mut nonmanifold_edges, mut inconsistent_edges) =
            (0u64, 0u64, 0u64, 0u64);
        // The bucket being read, as (higher vertex, corner) sorted so that the uses of one
        // edge are adjacent.
        let mut bucket: Vec<(u32, u32)> = Vec::new();
        for lo in 0..nv as u32 {
            uses.read(lo, &mut bucket);
            bucket.sort_unstable();
            for group in bucket.chunk_by(|a, b| a.0 == b.0) {
                let hi = group[0].0;
                edges += 1;
                for x in [lo, hi] {
                    valence[x as usize] = valence[x as usize].saturating_add(1);
                }
                match group.len() {
                    1 => {
                        boundary_edges += 1;
                        boundary_graph.union(lo, hi);
                        in_boundary[lo as usize] = true;
                        in_boundary[hi as usize] = true;
                    }
                    2 => {
                        if corner_vertex(group[0].1) == corner_vertex(group[1].1) {
                            inconsistent_edges += 1;
                        }
                    }
                    _ => nonmanifold_edges += 1,
                }
                // The corners at `lo` (and at `hi`) of all triangles on this edge join one fan.
                let at = |c: u32, x: u32| {
                    let following = 3 * (c / 3) + (c % 3 + 1) % 3;
                    if corner_vertex(c) == x {
                        c
                    } else {
                        following
                    }
                };
                for &(_, c) in &group[1..] {
                    fans.union(at(group[0].1, lo), at(c, lo));
                    fans.union(at(group[0].1, hi), at(c, hi));
                }
            }
        }
        drop(uses);

        // Fans per vertex: count distinct fan roots among each vertex's corners.
        let mut first_root = vec![u32::MAX; nv];
        let mut nonmanifold = vec![false; nv];
        for c in 0..(tris.len() * 3) as u32 {
            let v = corner_vertex(c) as usize;
            let root = fans.find(c);
            if first_root[v] == u32::MAX {
                first_root[v] = root;
            } else if first_root[v] != root {
                nonmanifold[v] = true;
            }
        }
        drop((fans, first_root));
        let nonmanifold_vertices = nonmanifold.iter().filter(|&&x| x).count() as u64;

        let boundary_loops = (0..nv as u32)
            .filter(|&v| in_boundary[v as usize] && boundary_graph.find(v) == v)
            .count() as u64;

        let mut components_uf = UnionFind::new(nv);
        for tri in tris {
            components_uf.union(tri[0], tri[1]);
            components_uf.union(tri[0], tri[2]);
        }
        let components = (0..nv as u32)
            .filter(|&v| referenced[v as usize] && components_uf.find(v) == v)
            .count() as u64;

        let degenerate_triangles = tris
            .iter()
            .filter(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2])
            .count() as u64;
        let zero_area_triangles = tris
            .iter()
            .filter(|t| zero_area(t.map(|v| mesh.positions[v as usize])))
            .count() as u64;
        let duplicate_triangles = repeats(tris.iter().map(|t| {
            let mut s = *t;
            s.sort_unstable();
            s
        }));
        let duplicate_positions = repeats(
            mesh.positions
                .iter()
                .map(|p| p.map(|x| if x == 0.0 { 0 } else { x.to_bits() })),
        );

        let triangles = tris.len() as u64;
        let euler = referenced_count as i64 - edges as i64 + triangles as i64;
        let edge_manifold = nonmanifold_edges == 0;
        let vertex_manifold = nonmanifold_vertices == 0;
        let genus = if edge_manifold && vertex_manifold {
            let twice = 2 * components as i64 - boundary_loops as i64 - euler;
            (twice >= 0 && twice % 2 == 0).then_some(twice / 2)
        } else {
            None
        };
        let valence6 = (0..nv)
            .filter(|&v| referenced[v] && valence[v] == 6)
            .count() as f64;
        let pct = |x: f64| {
            if referenced_count == 0 {
                0.0
            } else {
                x / referenced_count as f64
            }
        };
        TopologyReport {
            vertices: nv as u64,
            triangles,
            edges,
            boundary_edges,
            boundary_loops,
            components,
            euler,
            genus,
            nonmanifold_edges,
            nonmanifold_vertices,
            inconsistent_edges,
            degenerate_triangles,
            zero_area_triangles,
            duplicate_triangles,
            duplicate_positions,
            unreferenced_vertices: nv as u64 - referenced_count,
            edge_manifold,
            vertex_manifold,
            oriented: edge_manifold && inconsistent_edges == 0,
            valence6_pct: 100.0 * pct(valence6),
            mean_valence: pct(2.0 * edges as f64),
            max_valence: valence.iter().copied().max().unwrap_or(0) as u64,
        }
    }
}

/// How many of `keys` equal an earlier one. By sorting rather than hashing: the keys come
/// from the input, and a sort's cost does not depend on what they are.
fn repeats(keys: impl Iterator<Item = [u32; 3]>) -> u64 {
    let mut keys: Vec<[u32; 3]> = keys.collect();
    keys.sort_unstable();
    keys.windows(2).filter(|w| w[0] == w[1]).count() as u64
}

fn zero_area(p: [[f32; 3]; 3]) -> bool {
    let d = |a: [f32; 3], b: [f32; 3]| [0, 1, 2].map(|i| a[i] as f64 - b[i] as f64);
    let (a, b) = (d(p[1], p[0]), d(p[2], p[0]));
    let n = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    n == [0.0; 3]
}

impl std::fmt::Display for TopologyReport {
    /// One `name: value` line per figure, in the order of the JSON keys.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let genus = self
            .genus
            .map_or_else(|| "undefined".to_string(), |g| g.to_string());
        let rows: [(&str, String); 22] = [
            ("vertices", self.vertices.to_string()),
            ("triangles", self.triangles.to_string()),
            ("edges", self.edges.to_string()),
            ("boundary edges", self.boundary_edges.to_string()),
            ("boundary loops", self.boundary_loops.to_string()),
            ("components", self.components.to_string()),
            ("euler characteristic", self.euler.to_string()),
            ("genus", genus),
            ("non-manifold edges", self.nonmanifold_edges.to_string()),
            (
                "non-manifold vertices",
                self.nonmanifold_vertices.to_string(),
            ),
            (
                "inconsistently oriented edges",
                self.inconsistent_edges.to_string(),
            ),
            (
                "degenerate triangles",
                self.degenerate_triangles.to_string(),
            ),
            ("zero-area triangles", self.zero_area_triangles.to_string()),
            ("duplicate triangles", self.duplicate_triangles.to_string()),
            ("duplicate positions", self.duplicate_positions.to_string()),
            (
                "unreferenced vertices",
                self.unreferenced_vertices.to_string(),
            ),
            ("edge-manifold", self.edge_manifold.to_string()),
            ("vertex-manifold", self.vertex_manifold.to_string()),
            ("oriented", self.oriented.to_string()),
            ("valence-6 vertices", format!("{:.2}%", self.valence6_pct)),
            ("mean valence", format!("{:.3}", self.mean_valence)),
            ("max valence", self.max_valence.to_string()),
        ];
        for (name, value) in rows {
            writeln!(f, "{name:<30} {value}")?;
        }
        Ok(())
    }
}
