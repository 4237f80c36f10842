//! Triangle strips: every input triangle comes back exactly once, oriented, on real and
//! generated meshes.

mod common;

use common::{assert_same_up_to_rotation, check_against_table, corpus_dir};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{Lr, LrOptions};
use lrmesh::strips::{lr_index_list, stripify, Cts, StripOptions, Strips};
use lrmesh::{CornerOps, CornerTable, Mesh};
use proptest::prelude::*;

/// The triangle rotated so that its smallest index comes first (same orientation).
fn canonical(t: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&i| t[i]).unwrap_or(0);
    [t[k], t[(k + 1) % 3], t[(k + 2) % 3]]
}

fn check_strips(mesh: &Mesh, options: &StripOptions) -> Strips {
    let strips = stripify(mesh.positions.len(), &mesh.triangles, options);
    let back = strips.triangles();
    assert_eq!(back.len(), mesh.triangles.len(), "triangle count");
    assert_eq!(strips.triangle_count(), mesh.triangles.len());
    // Each decoded triangle is the input triangle its order entry names, same orientation.
    let order: Vec<u32> = strips
        .strip_order
        .iter()
        .chain(&strips.fan_order)
        .chain(&strips.list_order)
        .copied()
        .collect();
    let mut seen = vec![false; mesh.triangles.len()];
    for (got, &t) in back.iter().zip(&order) {
        assert!(!seen[t as usize], "triangle {t} emitted twice");
        seen[t as usize] = true;
        assert_eq!(
            canonical(*got),
            canonical(mesh.triangles[t as usize]),
            "triangle {t}"
        );
    }
    assert_eq!(strips.list.len() % 3, 0);
    strips
}

fn all_options() -> Vec<StripOptions> {
    vec![
        StripOptions::default(),
        StripOptions {
            samples: 3,
            fan_threshold: 6,
            seed: 7,
        },
        StripOptions {
            samples: 2,
            fan_threshold: 3,
            seed: 3,
        },
    ]
}

fn corpus() -> Vec<(String, Mesh)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let path = entry.unwrap().path();
        if lrmesh::io::MeshFormat::from_path(&path).is_err() {
            continue;
        }
        let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        out.push((path.display().to_string(), mesh));
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

#[test]
fn corpus_strips() {
    for (name, mesh) in corpus() {
        for options in all_options() {
            let s = check_strips(&mesh, &options);
            eprintln!(
                "{name}: {:.3} indices per triangle ({} strips, {} fans, {} lone)",
                s.indices_per_triangle(),
                s.strip_count,
                s.fan_count,
                s.list.len() / 3
            );
        }
    }
}

/// The LR index list expands to exactly the LR's triangles, and through the LR's vertex map
/// to the input's non-degenerate triangles.
fn check_lr_index(mesh: &Mesh) -> f64 {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let list = lr_index_list(&lr);
    let flat = list.triangle_list();
    assert_eq!(flat.len() % 3, 0);
    let mut got: Vec<[u32; 3]> = flat
        .chunks_exact(3)
        .map(|t| canonical([t[0], t[1], t[2]]))
        .collect();
    let mut want: Vec<[u32; 3]> = lr
        .triangles()
        .map(|t| canonical(lr.triangle_vertices(t).map(|v| v.0)))
        .collect();
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want, "LR index list triangles");
    let mut input: Vec<[u32; 3]> = got
        .iter()
        .map(|t| canonical(t.map(|v| lr.input_vertex(lrmesh::Vertex(v)))))
        .collect();
    let mut expected: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .map(|&t| canonical(t))
        .collect();
    input.sort_unstable();
    expected.sort_unstable();
    assert_eq!(input, expected, "LR index list against the input");
    list.references_per_triangle()
}

/// The constrained strips' operators agree with the corner table, corner by corner.
fn check_cts(mesh: &Mesh, options: &StripOptions) -> Cts {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let cts = Cts::build(&table, options).unwrap();
    let key = |c: lrmesh::Corner| {
        (
            cts.input_triangle(cts.triangle(c)),
            cts.input_vertex(cts.vertex(c)),
        )
    };
    let position = |v: lrmesh::Vertex| mesh.positions[cts.input_vertex(v) as usize];
    check_against_table(&cts, key, position, &table, mesh);
    // Every strip starts at an even position, so parity gives orientation.
    let t = cts.t();
    for j in 0..t.len() {
        let starts =
            t[j] != lrmesh::strips::DELIMITER && (j == 0 || t[j - 1] == lrmesh::strips::DELIMITER);
        assert!(!starts || j % 2 == 0, "strip starting at odd position {j}");
    }
    assert_eq!(cts.a().len(), t.len());
    cts
}

/// The constrained strips stored in a container (`--connectivity strips`) and read in place
/// answer every operator as the owned ones do, and decode to the input's triangles.
fn check_cts_container(mesh: &Mesh) {
    use lrmesh::read::{open, Limits};
    use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
    let options = EncodeOptions {
        connectivity: Connectivity::Strips,
        keep_order: true,
        orient: Orient::AsGiven,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    let view = open(&bytes, &Limits::default()).unwrap();
    let stored = view.strips().expect("a strips container");
    let owned = Cts::build(&CornerTable::from_mesh(mesh).unwrap(), &options.strips).unwrap();
    assert!(stored.triangles().eq(owned.triangles()));
    assert_eq!(stored.vertex_id_bound(), owned.vertex_id_bound());
    for c in owned.corners() {
        assert_eq!(stored.vertex(c), owned.vertex(c), "c.v of {c:?}");
        assert_eq!(stored.opposite(c), owned.opposite(c), "c.o of {c:?}");
    }
    for v in owned.vertices() {
        assert_eq!(
            stored.vertex_corner(v),
            owned.vertex_corner(v),
            "v.c of {v:?}"
        );
    }
    let back = view.to_mesh();
    assert_eq!(back.positions, mesh.positions);
    assert_same_up_to_rotation(&back.triangles, &mesh.triangles, "strips");
}

#[test]
fn corpus_cts() {
    for (name, mesh) in corpus() {
        let cts = check_cts(&mesh, &StripOptions::default());
        eprintln!(
            "{name}: CTS {:.1} bits per triangle",
            cts.bits_per_triangle()
        );
    }
}

#[test]
fn corpus_lr_index_list() {
    for (name, mesh) in corpus() {
        let rpt = check_lr_index(&mesh);
        eprintln!("{name}: LR index list {rpt:.3} references per triangle");
    }
}

#[test]
fn stats_on_corpus_and_empty_mesh() {
    for (name, mesh) in corpus() {
        let stats = lrmesh::strips::StripStats::of(&mesh).unwrap();
        let json = serde_json::to_value(&stats).unwrap();
        for key in [
            "indices_per_triangle",
            "strips",
            "fans",
            "isolated_triangles",
            "cts_bits_per_triangle",
            "lr_index_rpt",
        ] {
            assert!(json.get(key).is_some(), "{name}: {key}");
        }
        eprint!("{name}\n{stats}");
    }
    let empty = lrmesh::strips::StripStats::of(&Mesh::default()).unwrap();
    assert_eq!(empty.indices_per_triangle, 0.0);
}

#[test]
fn small_cases() {
    let p = vec![[0.0; 3]; 4];
    for tris in [
        vec![],
        vec![[0, 1, 2]],
        vec![[0, 1, 2], [0, 2, 1]],
        vec![[0, 1, 2], [2, 1, 3]],
        vec![[0, 1, 2], [0, 1, 2], [1, 0, 3], [0, 0, 1]],
        vec![[0, 1, 2], [1, 0, 3], [0, 1, 3], [1, 0, 2]],
    ] {
        let mesh = Mesh::new(p.clone(), tris.clone());
        for options in all_options() {
            check_strips(&mesh, &options);
        }
        check_lr_index(&mesh);
        check_cts(&mesh, &StripOptions::default());
        check_cts_container(&mesh);
    }
    // Out-of-range indices are emitted as they are, not a panic.
    let s = stripify(2, &[[0, 1, 5], [0, 1, 2]], &StripOptions::default());
    assert_eq!(s.list.len(), 6);
}

#[test]
fn regular_torus_is_mostly_strips() {
    let mesh = generate::torus(20, 30);
    let s = check_strips(&mesh, &StripOptions::default());
    assert!(
        s.indices_per_triangle() < 1.4,
        "{}",
        s.indices_per_triangle()
    );
}

#[test]
fn high_valence_fan() {
    // A cone: one apex with 500 triangles, then a cap fan. Exercises the large-bucket path.
    let k = 500u32;
    let mut tris = Vec::new();
    for i in 0..k {
        tris.push([0, 1 + i, 1 + (i + 1) % k]);
        tris.push([k + 1, 1 + (i + 1) % k, 1 + i]);
    }
    tris.push([0, 1, 2]); // a duplicate: set aside
    let mesh = Mesh::new(vec![[0.0; 3]; k as usize + 2], tris);
    for options in all_options() {
        check_strips(&mesh, &options);
    }
}

/// A half-edge that repeats a direction (duplicate triangle, inconsistently oriented
/// neighbour, third triangle on an edge) is left without a twin; its triangle stays in the
/// graph through its other edges instead of being set aside.
#[test]
fn repeated_half_edges_are_unlinked_not_set_aside() {
    use lrmesh::strips::Adjacency;
    // Triangles 0 and 1 are the same; 2 shares edge 1-2 with them (reversed); 3 is 2 flipped.
    let tris = [[0, 1, 2], [0, 1, 2], [2, 1, 3], [1, 2, 3]];
    let adj = Adjacency::build(4, &tris);
    assert_eq!(adj.set_aside_count(), 0);
    // Half-edge 1 -> 2 of triangle 0 (id 1) pairs with 2 -> 1 of triangle 2 (id 6).
    assert_eq!(adj.twin(1), Some(6));
    assert_eq!(adj.twin(6), Some(1));
    // Triangle 1 repeats it, triangle 3 runs 2 -> 3 and 1 -> 2 like triangle 2 and 0.
    assert_eq!(adj.twin(4), None);
    assert_eq!(adj.twin(9), None);
    // 3 -> 1 of triangle 3 (id 11) is twin to 1 -> 3 of triangle 2 (id 7).
    assert_eq!(adj.twin(11), Some(7));
    check_strips(
        &Mesh::new(vec![[0.0; 3]; 4], tris.to_vec()),
        &StripOptions::default(),
    );
}

/// Found comparing with meshoptimizer: on `blobby-shuffled` (half its edges inconsistently
/// oriented) two thirds of the triangles were set aside and drawn alone (2.75 indices per
/// triangle, meshopt 2.60); left unlinked, most of them join strips.
#[test]
fn inconsistent_orientation_strips_better_than_meshopt() {
    let mesh = read_mesh(
        &corpus_dir().join("blobby-shuffled.off"),
        &ReadOptions::default(),
    )
    .unwrap()
    .mesh;
    let s = check_strips(&mesh, &StripOptions::default());
    let lone = s.list.len() / 3;
    assert!(lone * 4 < mesh.triangles.len(), "{lone} lone triangles");
    assert!(
        s.indices_per_triangle() < 2.3,
        "{}",
        s.indices_per_triangle()
    );
}

fn generated(kind: u32, seed: u64, size: u32) -> Mesh {
    let mut rng = Rng::new(seed);
    let mut mesh = generate::irregular_torus(size.max(20), seed);
    match kind {
        0 => {}
        1 => generate::punch_holes(&mut mesh, (size / 10) as usize, &mut rng),
        2 => {
            let n = mesh.triangles.len();
            if let Some(u) = generate::far_triangle(&mesh, 0, &mut rng) {
                generate::add_handle(&mut mesh, 0, u);
            }
            let _ = n;
        }
        3 => {
            let other = generate::torus(4, 5);
            generate::append(&mut mesh, &other);
        }
        4 => generate::add_defects(&mut mesh, (size / 8) as usize + 1, &mut rng),
        _ => mesh = generate::soup(size / 3 + 3, size, &mut rng),
    }
    mesh
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn generated_strips(kind in 0u32..6, seed in 0u64..1000, size in 20u32..600) {
        let mesh = generated(kind, seed, size);
        for options in all_options() {
            check_strips(&mesh, &options);
        }
        check_lr_index(&mesh);
        check_cts(&mesh, &StripOptions { samples: 2, ..StripOptions::default() });
        check_cts_container(&mesh);
    }
}

/// The twins the adjacency documents, found the slow way, and which triangles are set aside:
/// on each edge, the lowest half-edge of one direction pairs with the lowest of the other;
/// triangles with a repeated vertex or a vertex out of range take no part.
fn reference_twins(vertex_count: usize, tris: &[[u32; 3]]) -> (Vec<Option<u32>>, Vec<bool>) {
    use std::collections::HashMap;
    let usable = |t: &[u32; 3]| {
        t.iter().all(|&v| (v as usize) < vertex_count)
            && t[0] != t[1]
            && t[1] != t[2]
            && t[0] != t[2]
    };
    let aside: Vec<bool> = tris.iter().map(|t| !usable(t)).collect();
    let mut lowest: HashMap<(u32, u32), u32> = HashMap::new();
    for (t, tri) in tris.iter().enumerate() {
        if aside[t] {
            continue;
        }
        for i in 0..3 {
            let h = 3 * t as u32 + i as u32;
            lowest.entry((tri[i], tri[(i + 1) % 3])).or_insert(h);
        }
    }
    let mut twins = vec![None; 3 * tris.len()];
    for (&(x, y), &h) in &lowest {
        if let Some(&g) = lowest.get(&(y, x)) {
            twins[h as usize] = Some(g);
        }
    }
    (twins, aside)
}

/// `Adjacency::build` links exactly the reference's twins and sets aside exactly its
/// triangles.
fn check_adjacency(vertex_count: usize, tris: &[[u32; 3]]) {
    use lrmesh::strips::Adjacency;
    let adj = Adjacency::build(vertex_count, tris);
    let (twins, aside) = reference_twins(vertex_count, tris);
    for (h, &w) in twins.iter().enumerate() {
        assert_eq!(adj.twin(h as u32), w, "half-edge {h}");
    }
    for (t, &a) in aside.iter().enumerate() {
        assert_eq!(adj.is_set_aside(t as u32), a, "triangle {t}");
    }
    let set_aside = aside.iter().filter(|&&a| a).count();
    assert_eq!(adj.set_aside_count() as usize, set_aside);
}

/// On soups full of repeated and non-manifold edges, and on a mesh in order and in
/// scattered order (buckets of every size).
#[test]
fn adjacency_matches_the_reference_on_large_and_scattered_meshes() {
    let mut rng = Rng::new(7);
    let torus = generate::irregular_torus(40_000, 3);
    check_adjacency(torus.positions.len(), &torus.triangles);
    let mut scattered = torus.triangles.clone();
    rng.shuffle(&mut scattered);
    check_adjacency(torus.positions.len(), &scattered);
    let soup = generate::soup(60, 5_000, &mut rng);
    check_adjacency(soup.positions.len(), &soup.triangles);
    // Out-of-range and degenerate triangles among the rest.
    let mut odd = soup.triangles.clone();
    odd.extend([[0, 0, 1], [1, 2, 60], [u32::MAX, 0, 1]]);
    check_adjacency(60, &odd);
    check_adjacency(0, &odd);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn adjacency_matches_the_reference(kind in 0u32..6, seed in 0u64..1000, size in 20u32..3000) {
        let mesh = generated(kind, seed, size);
        check_adjacency(mesh.positions.len(), &mesh.triangles);
    }
}
