//! The corner table on generated meshes: its invariants, the map back to the input, and the
//! generic algorithms, on closed meshes, holes, handles, components and defect-ridden soups.

mod common;

use common::check_corner_table;
use lrmesh::generate::{self, Rng};
use lrmesh::ops::{self, Plane};
use lrmesh::{CornerOps, CornerTable, Mesh, TopologyReport, Triangle, Vertex};
use proptest::prelude::*;

/// How to make a test mesh: a torus grid, then handles, more components, holes and defects.
#[derive(Debug, Clone)]
struct Recipe {
    around: u32,
    along: u32,
    flips: usize,
    handles: usize,
    extra_components: usize,
    holes: usize,
    defects: usize,
    seed: u64,
}

impl Recipe {
    fn make(&self) -> Mesh {
        let mut rng = Rng::new(self.seed);
        let mut mesh = generate::torus(self.around, self.along);
        generate::flip_edges(&mut mesh, self.flips, &mut rng);
        generate::add_random_handles(&mut mesh, self.handles, &mut rng);
        for k in 0..self.extra_components {
            let other = generate::torus(3 + k as u32, 4);
            generate::append(&mut mesh, &other);
        }
        generate::punch_holes(&mut mesh, self.holes, &mut rng);
        generate::add_defects(&mut mesh, self.defects, &mut rng);
        mesh
    }
}

fn recipe() -> impl Strategy<Value = Recipe> {
    (
        3u32..9,
        3u32..9,
        0usize..40,
        0usize..3,
        0usize..3,
        0usize..6,
        0usize..12,
        any::<u64>(),
    )
        .prop_map(
            |(around, along, flips, handles, extra_components, holes, defects, seed)| Recipe {
                around,
                along,
                flips,
                handles,
                extra_components,
                holes,
                defects,
                seed,
            },
        )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn invariants_on_generated_meshes(r in recipe()) {
        check_corner_table(&r.make());
    }

    #[test]
    fn invariants_on_soups(vertices in 1u32..30, triangles in 0u32..80, seed in any::<u64>()) {
        let mesh = generate::soup(vertices, triangles, &mut Rng::new(seed));
        check_corner_table(&mesh);
    }

    /// Handles and components change the report exactly as topology says they must.
    #[test]
    fn report_follows_handles_and_components(r in recipe()) {
        let r = Recipe { holes: 0, defects: 0, ..r };
        let mesh = r.make();
        let report = TopologyReport::of(&mesh);
        prop_assert_eq!(report.components, 1 + r.extra_components as u64);
        prop_assert_eq!(report.boundary_edges, 0);
        prop_assert_eq!(report.nonmanifold_edges, 0);
        prop_assert_eq!(report.inconsistent_edges, 0);
        // Each torus adds one to the genus, and so does each handle that found a far triangle.
        let handles = report.genus.unwrap() - 1 - r.extra_components as i64;
        prop_assert!(handles >= 0 && handles <= r.handles as i64, "{report:?}");
        prop_assert_eq!(report.euler, 2 * report.components as i64 - 2 * report.genus.unwrap());
    }

    /// On clean manifold meshes the generic valence equals the number of distinct neighbours.
    #[test]
    fn valence_counts_neighbours(r in recipe()) {
        let mesh = Recipe { defects: 0, ..r }.make();
        let report = TopologyReport::of(&mesh);
        prop_assume!(report.vertex_manifold && report.oriented);
        let table = CornerTable::from_mesh(&mesh).unwrap();
        let mut neighbours = vec![std::collections::BTreeSet::new(); mesh.positions.len()];
        for t in &mesh.triangles {
            for i in 0..3 {
                neighbours[t[i] as usize].insert(t[(i + 1) % 3]);
                neighbours[t[(i + 1) % 3] as usize].insert(t[i]);
            }
        }
        for v in table.vertices() {
            prop_assert_eq!(ops::valence(&table, v) as usize, neighbours[v.idx()].len());
        }
    }
}

#[test]
fn torus_report() {
    let mesh = generate::torus(5, 7);
    let r = TopologyReport::of(&mesh);
    assert_eq!((r.vertices, r.triangles, r.edges), (35, 70, 105));
    assert_eq!((r.euler, r.genus, r.components), (0, Some(1), 1));
    assert_eq!(r.valence6_pct, 100.0);
}

#[test]
fn connected_sum_of_two_tori_has_genus_two() {
    let mut mesh = generate::torus(4, 5);
    generate::append(&mut mesh, &generate::torus(3, 4));
    assert_eq!(TopologyReport::of(&mesh).components, 2);
    generate::add_handle(&mut mesh, 0, 40 + 5);
    let r = TopologyReport::of(&mesh);
    assert_eq!((r.components, r.genus, r.boundary_edges), (1, Some(2), 0));
}

#[test]
fn irregular_torus_is_a_clean_torus() {
    let mesh = generate::irregular_torus(5000, 7);
    let r = TopologyReport::of(&mesh);
    assert!(r.triangles >= 5000);
    assert_eq!(
        (r.genus, r.nonmanifold_edges, r.inconsistent_edges),
        (Some(1), 0, 0)
    );
    assert!(
        r.valence6_pct < 60.0,
        "flips should make valences irregular: {r:?}"
    );
    check_corner_table(&mesh);
}

#[test]
fn normals_of_a_torus_point_out_of_the_tube() {
    let mesh = generate::torus(12, 20);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let normals = ops::vertex_normals(&table, &mesh.positions);
    for (p, n) in mesh.positions.iter().zip(&normals) {
        // The tube's centre line is the unit circle in the z = 0 plane.
        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
        let out = [p[0] - p[0] / r, p[1] - p[1] / r, p[2]];
        let d = out[0] * n[0] + out[1] * n[1] + out[2] * n[2];
        assert!(
            d > 0.9 * (out.iter().map(|x| x * x).sum::<f32>()).sqrt(),
            "{p:?} {n:?}"
        );
    }
}

/// Consecutive triangles of a contour share an edge that the plane cuts; every cut triangle is
/// in exactly one contour.
fn check_contours(mesh: &Mesh, plane: &Plane) -> Vec<Vec<Triangle>> {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let positions = table.extend_to_copies(&mesh.positions);
    let lines = ops::contours(&table, &positions, plane);
    let cut = |t: Triangle| {
        let above = table
            .triangle_vertices(t)
            .map(|v| plane.above(positions[v.idx()]));
        above[0] != above[1] || above[1] != above[2]
    };
    let total: usize = lines.iter().map(Vec::len).sum();
    assert_eq!(total, table.triangles().filter(|&t| cut(t)).count());
    let mut seen = std::collections::HashSet::new();
    for line in &lines {
        for pair in line.windows(2) {
            let shared = table
                .triangle_corners(pair[0])
                .into_iter()
                .any(|c| table.opposite(c).map(|d| table.triangle(d)) == Some(pair[1]));
            assert!(shared, "{:?} and {:?} are not neighbours", pair[0], pair[1]);
        }
        for &t in line {
            assert!(cut(t) && seen.insert(t));
        }
    }
    lines
}

#[test]
fn contour_of_a_torus_through_its_equator_is_two_loops() {
    let mesh = generate::torus(16, 24);
    let plane = Plane {
        normal: [0.0, 0.0, 1.0],
        offset: 0.01,
    };
    assert_eq!(check_contours(&mesh, &plane).len(), 2);
    // A vertical plane through the axis cuts the tube twice.
    let plane = Plane {
        normal: [1.0, 0.0, 0.0],
        offset: 0.013,
    };
    assert_eq!(check_contours(&mesh, &plane).len(), 2);
}

#[test]
fn contours_with_holes_are_paths() {
    let mut mesh = generate::torus(16, 24);
    generate::punch_holes(&mut mesh, 30, &mut Rng::new(3));
    let plane = Plane {
        normal: [0.3, 0.2, 1.0],
        offset: 0.02,
    };
    check_contours(&mesh, &plane);
}

#[test]
fn unreferenced_vertices_have_no_corner() {
    let mesh = Mesh::new(vec![[0.0; 3]; 5], vec![[0, 1, 2]]);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    assert_eq!(table.vertex_corner(Vertex(3)), None);
    assert_eq!(ops::valence(&table, Vertex(4)), 0);
    assert_eq!(ops::valence(&table, Vertex(0)), 2);
    check_corner_table(&mesh);
}

#[test]
fn bowtie_vertex_is_split_and_mapped_back() {
    // Two triangles meeting at vertex 0 only.
    let mesh = Mesh::new(vec![[0.0; 3]; 5], vec![[0, 1, 2], [0, 3, 4]]);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    assert_eq!(table.conversion().vertex_copies, 1);
    assert_eq!(table.original_vertex(Vertex(5)), Vertex(0));
    assert_eq!(table.input_triangles(), mesh.triangles);
    assert_eq!(TopologyReport::of(&mesh).nonmanifold_vertices, 1);
}

#[test]
fn three_triangles_on_an_edge_are_cut_apart() {
    let mesh = Mesh::new(vec![[0.0; 3]; 5], vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]]);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    assert_eq!(table.conversion().cut_nonmanifold_edges, 1);
    assert!(table
        .o_table()
        .iter()
        .all(|&o| o == lrmesh::corner_table::NONE));
    assert_eq!(table.conversion().vertex_copies, 4);
    check_corner_table(&mesh);
}

#[test]
fn degenerate_triangles_are_kept_aside_in_place() {
    let mesh = Mesh::new(
        vec![[0.0; 3]; 4],
        vec![[0, 1, 2], [1, 1, 3], [2, 1, 3], [3, 3, 3]],
    );
    let table = CornerTable::from_mesh(&mesh).unwrap();
    assert_eq!(table.kept_aside(), &[(1, [1, 1, 3]), (3, [3, 3, 3])]);
    assert_eq!(table.triangle_id_bound(), 2);
    assert_eq!(table.input_triangle(Triangle(1)), 2);
    check_corner_table(&mesh);
}

#[test]
fn out_of_range_index_is_an_error() {
    let err = CornerTable::build(3, &[[0, 1, 3]]).unwrap_err();
    assert!(
        err.to_string().contains("triangle 0 refers to vertex 3"),
        "{err}"
    );
}
