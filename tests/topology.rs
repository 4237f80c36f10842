//! The topology report and the corner table on real meshes: every figure of the manifest, which
//! was computed independently of this crate, must come out the same.

mod common;

use common::{check_corner_table, corpus_dir, shared_dir};
use lrmesh::io::{self, ReadOptions};
use lrmesh::TopologyReport;
use std::collections::HashMap;
use std::path::Path;

/// The manifest's rows, keyed by file name, each a map from column name to text.
fn manifest(dir: &Path) -> Vec<(String, HashMap<String, String>)> {
    let text = std::fs::read_to_string(dir.join("MANIFEST.tsv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines
        .next()
        .unwrap()
        .split('\t')
        .map(String::from)
        .collect();
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let row: HashMap<String, String> = header
                .iter()
                .cloned()
                .zip(l.split('\t').map(String::from))
                .collect();
            (row["mesh"].clone(), row)
        })
        .collect()
}

fn check_against_manifest(dir: &Path) -> usize {
    let rows = manifest(dir);
    for (name, row) in &rows {
        let loaded = io::read_mesh(&dir.join(name), &ReadOptions::default()).unwrap();
        let r = TopologyReport::of(&loaded.mesh);
        let int = |key: &str| row[key].parse::<i64>().unwrap();
        let flag = |key: &str| row[key] == "True";
        let close = |key: &str, got: f64, tolerance: f64| {
            let want: f64 = row[key].parse().unwrap();
            assert!(
                (got - want).abs() <= tolerance,
                "{name}: {key} {got} != {want}"
            );
        };
        let got = [
            ("V", r.vertices as i64),
            ("T", r.triangles as i64),
            ("E", r.edges as i64),
            ("boundary_loops", r.boundary_loops as i64),
            ("boundary_edges", r.boundary_edges as i64),
            ("components", r.components as i64),
            ("euler", r.euler),
            ("nonmanifold_edges", r.nonmanifold_edges as i64),
            ("nonmanifold_vertices", r.nonmanifold_vertices as i64),
            ("degenerate_comb", r.degenerate_triangles as i64),
            ("zero_area", r.zero_area_triangles as i64),
            ("duplicate_tris", r.duplicate_triangles as i64),
            ("dup_positions", r.duplicate_positions as i64),
            ("unreferenced_V", r.unreferenced_vertices as i64),
            ("max_valence", r.max_valence as i64),
        ];
        for (key, value) in got {
            assert_eq!(value, int(key), "{name}: {key}");
        }
        let genus = match row["genus"].as_str() {
            "n/a" => None,
            g => Some(g.parse::<i64>().unwrap()),
        };
        assert_eq!(r.genus, genus, "{name}: genus");
        assert_eq!(r.edge_manifold, flag("edge_manifold"), "{name}");
        assert_eq!(r.vertex_manifold, flag("vertex_manifold"), "{name}");
        assert_eq!(r.oriented, flag("oriented"), "{name}");
        close("valence6_pct", r.valence6_pct, 0.005);
        close("mean_valence", r.mean_valence, 0.0005);

        // The corner table of every real mesh keeps its invariants and maps back exactly.
        check_corner_table(&loaded.mesh);
    }
    rows.len()
}

#[test]
fn corpus_matches_manifest() {
    let checked = check_against_manifest(&corpus_dir());
    assert!(checked >= 18, "only {checked} manifest rows");
}

/// The shared set holds two large meshes the repository leaves out; check them when present.
#[test]
fn shared_meshes_match_manifest() {
    // Without them, shared_dir says so loudly (and fails under CI).
    if let Some(dir) = shared_dir() {
        let checked = check_against_manifest(&dir);
        eprintln!("checked {checked} meshes of {}", dir.display());
    }
}

#[test]
fn json_report_has_the_documented_keys() {
    let loaded = io::read_mesh(
        &corpus_dir().join("hedra_open.off"),
        &ReadOptions::default(),
    )
    .unwrap();
    let json = serde_json::to_value(TopologyReport::of(&loaded.mesh)).unwrap();
    for key in [
        "vertices",
        "triangles",
        "edges",
        "boundary_edges",
        "boundary_loops",
        "components",
        "euler",
        "genus",
        "nonmanifold_edges",
        "nonmanifold_vertices",
        "degenerate_triangles",
        "duplicate_triangles",
        "unreferenced_vertices",
    ] {
        assert!(json.get(key).is_some(), "missing key {key}");
    }
    assert_eq!(json["boundary_loops"], 1);
    assert_eq!(json["genus"], 0);
}

#[test]
fn undefined_genus_is_null_in_json() {
    let mesh = lrmesh::Mesh::new(vec![[0.0; 3]; 5], vec![[0, 1, 2], [0, 3, 4]]);
    let json = serde_json::to_value(TopologyReport::of(&mesh)).unwrap();
    assert!(json["genus"].is_null());
}

/// The figures of a report that a test states by hand, in the order of `TopologyReport`.
#[derive(Debug, PartialEq)]
struct Counts {
    vertices: u64,
    triangles: u64,
    edges: u64,
    boundary_edges: u64,
    boundary_loops: u64,
    components: u64,
    euler: i64,
    genus: Option<i64>,
    nonmanifold_edges: u64,
    nonmanifold_vertices: u64,
    inconsistent_edges: u64,
    degenerate_triangles: u64,
    zero_area_triangles: u64,
    duplicate_triangles: u64,
    duplicate_positions: u64,
    unreferenced_vertices: u64,
    flags: [bool; 3],
}

fn counts(positions: Vec<[f32; 3]>, triangles: Vec<[u32; 3]>) -> Counts {
    let r = TopologyReport::of(&lrmesh::Mesh::new(positions, triangles));
    Counts {
        vertices: r.vertices,
        triangles: r.triangles,
        edges: r.edges,
        boundary_edges: r.boundary_edges,
        boundary_loops: r.boundary_loops,
        components: r.components,
        euler: r.euler,
        genus: r.genus,
        nonmanifold_edges: r.nonmanifold_edges,
        nonmanifold_vertices: r.nonmanifold_vertices,
        inconsistent_edges: r.inconsistent_edges,
        degenerate_triangles: r.degenerate_triangles,
        zero_area_triangles: r.zero_area_triangles,
        duplicate_triangles: r.duplicate_triangles,
        duplicate_positions: r.duplicate_positions,
        unreferenced_vertices: r.unreferenced_vertices,
        flags: [r.edge_manifold, r.vertex_manifold, r.oriented],
    }
}

/// Defect counts on meshes built by hand, each figure worked out from spec/TOPOLOGY.md's
/// definitions (not from the code), so that non-zero counts have an independent oracle.
#[test]
fn defect_counts_of_hand_built_meshes() {
    // Three triangles on the edge {0, 1}: one non-manifold edge, six boundary edges in one
    // piece, vertex 0's corners linked through that edge (one fan each vertex).
    let fin = counts(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 4]],
    );
    assert_eq!(
        fin,
        Counts {
            vertices: 5,
            triangles: 3,
            edges: 7,
            boundary_edges: 6,
            boundary_loops: 1,
            components: 1,
            euler: 1,
            genus: None,
            nonmanifold_edges: 1,
            nonmanifold_vertices: 0,
            inconsistent_edges: 0,
            degenerate_triangles: 0,
            zero_area_triangles: 0,
            duplicate_triangles: 0,
            duplicate_positions: 0,
            unreferenced_vertices: 0,
            flags: [false, true, false],
        }
    );
    // A bowtie through vertex 0 (two fans there), an unreferenced vertex, and an unreferenced
    // one on vertex 1's position.
    let bowtie = counts(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [5.0, 5.0, 5.0],
            [1.0, 0.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 3, 4]],
    );
    assert_eq!(
        bowtie,
        Counts {
            vertices: 7,
            triangles: 2,
            edges: 6,
            boundary_edges: 6,
            boundary_loops: 1,
            components: 1,
            euler: 1,
            genus: None,
            nonmanifold_edges: 0,
            nonmanifold_vertices: 1,
            inconsistent_edges: 0,
            degenerate_triangles: 0,
            zero_area_triangles: 0,
            duplicate_triangles: 0,
            duplicate_positions: 1,
            unreferenced_vertices: 2,
            flags: [true, false, true],
        }
    );
    // Two triangles using {0, 1} in the same direction (inconsistent); a degenerate (4, 4, 5)
    // whose two uses of {4, 5} run both ways; a collinear triangle and its reversed duplicate.
    let mixed = counts(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
            [5.0, 0.0, 0.0],
            [6.0, 0.0, 0.0],
            [10.0, 0.0, 0.0],
            [11.0, 0.0, 0.0],
            [12.0, 0.0, 0.0],
        ],
        vec![[0, 1, 2], [0, 1, 3], [4, 4, 5], [6, 7, 8], [8, 7, 6]],
    );
    assert_eq!(
        mixed,
        Counts {
            vertices: 9,
            triangles: 5,
            edges: 9,
            boundary_edges: 4,
            boundary_loops: 1,
            components: 3,
            euler: 5,
            genus: Some(0),
            nonmanifold_edges: 0,
            nonmanifold_vertices: 0,
            inconsistent_edges: 1,
            degenerate_triangles: 1,
            zero_area_triangles: 3,
            duplicate_triangles: 1,
            duplicate_positions: 0,
            unreferenced_vertices: 0,
            flags: [true, true, false],
        }
    );
}
