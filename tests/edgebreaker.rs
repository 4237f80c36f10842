//! Edgebreaker: round trips on real and generated meshes, the paper's examples, and hostile
//! input.

mod common;

use common::{corpus_dir, shared_dir};
use lrmesh::edgebreaker::{decode, encode, Decoded, EdgebreakerStats, Encoded, Limits};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::{CornerOps, CornerTable, Mesh, Triangle};
use proptest::prelude::*;

/// Encodes and decodes `table`, and checks that the decoded triangles are the table's, mapped
/// through the orders, with the same orientation.
fn round_trip(table: &CornerTable) -> (Encoded, Decoded) {
    let enc = encode(table).expect("encode");
    let dec = decode(&enc.bytes, &Limits::default()).expect("decode");
    let nv = table.vertex_id_bound();
    let nt = table.triangle_id_bound();
    assert_eq!(dec.vertex_count, nv, "vertex count");
    assert_eq!(dec.triangles.len() as u32, nt, "triangle count");
    let mut seen = vec![false; nv as usize];
    assert_eq!(enc.vertex_order.len() as u32, nv);
    for &v in &enc.vertex_order {
        assert!(
            !std::mem::replace(&mut seen[v as usize], true),
            "vertex order repeats {v}"
        );
    }
    let mut seen = vec![false; nt as usize];
    assert_eq!(enc.triangle_order.len() as u32, nt);
    for &t in &enc.triangle_order {
        assert!(
            !std::mem::replace(&mut seen[t as usize], true),
            "triangle order repeats {t}"
        );
    }
    for (t, tri) in dec.triangles.iter().enumerate() {
        let want = table
            .triangle_vertices(Triangle(enc.triangle_order[t]))
            .map(|v| v.0);
        let got = tri.map(|x| enc.vertex_order[x as usize]);
        let rotations = [
            want,
            [want[1], want[2], want[0]],
            [want[2], want[0], want[1]],
        ];
        assert!(
            rotations.contains(&got),
            "triangle {t}: {got:?} vs {want:?}"
        );
    }
    // Referenced vertices come first, in the order the decoder meets them.
    let referenced = table
        .vertices()
        .filter(|&v| table.vertex_corner(v).is_some())
        .count();
    let mut first_use = vec![u32::MAX; nv as usize];
    for tri in &dec.triangles {
        for &x in tri {
            assert!((x as usize) < referenced, "unreferenced id used");
            first_use[x as usize] = 0;
        }
    }
    assert!(first_use[..referenced].iter().all(|&f| f == 0));
    (enc, dec)
}

fn round_trip_mesh(mesh: &Mesh) -> (Encoded, Decoded) {
    let table = CornerTable::from_mesh(mesh).expect("table");
    let out = round_trip(&table);
    // The decoded mesh builds a corner table again.
    let back = CornerTable::build(out.1.vertex_count as usize, &out.1.triangles).unwrap();
    assert_eq!(back.triangle_id_bound(), table.triangle_id_bound());
    out
}

fn print_stats(name: &str, s: &EdgebreakerStats) {
    eprintln!(
        "{name:28} T {:7} bpt {:.3} clers {:.3} topo {:4} B  C {} L {} E {} R {} S {} (handle {} boundary {}) P {} comps {}",
        s.triangles, s.bpt, s.clers_bpt, s.topology_bytes, s.c, s.l, s.e, s.r, s.s, s.handle_s,
        s.boundary_s, s.p, s.components
    );
}

fn mesh_files(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| lrmesh::io::MeshFormat::from_path(p).is_ok())
        .collect();
    files.sort();
    files
}

#[test]
fn corpus_round_trips() {
    for path in mesh_files(&corpus_dir()) {
        let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        let (enc, _) = round_trip_mesh(&mesh);
        print_stats(path.file_name().unwrap().to_str().unwrap(), &enc.stats);
    }
}

#[test]
fn shared_meshes_round_trip() {
    let Some(dir) = shared_dir() else {
        eprintln!("../shared/meshes not found; skipped");
        return;
    };
    for path in mesh_files(&dir) {
        let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        let (enc, _) = round_trip_mesh(&mesh);
        print_stats(path.file_name().unwrap().to_str().unwrap(), &enc.stats);
    }
}

#[test]
fn generated_meshes() {
    let (enc, _) = round_trip_mesh(&generate::torus(6, 9));
    assert_eq!(enc.stats.handle_s, 2);
    print_stats("torus 6x9", &enc.stats);
    let (enc, _) = round_trip_mesh(&generate::irregular_torus(20_000, 3));
    print_stats("irregular torus", &enc.stats);
}

#[test]
fn empty_and_tiny() {
    round_trip_mesh(&Mesh::new(vec![], vec![]));
    round_trip_mesh(&Mesh::new(vec![[0.0; 3]; 5], vec![]));
    round_trip_mesh(&Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2]]));
    round_trip_mesh(&Mesh::new(vec![[0.0; 3]; 4], vec![[0, 1, 2], [0, 2, 1]]));
    round_trip_mesh(&Mesh::new(vec![[0.0; 3]; 4], vec![[0, 1, 2], [2, 1, 3]]));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn generated_round_trips(seed in 0u64..1_000_000, holes in 0usize..12, handles in 0usize..3,
                             comps in 1usize..4, defects in 0usize..8) {
        let mut rng = Rng::new(seed);
        let mut mesh = generate::torus(3 + rng.below(6), 3 + rng.below(6));
        for _ in 1..comps {
            let other = if rng.below(2) == 0 {
                generate::irregular_torus(50 + rng.below(200), seed)
            } else {
                generate::torus(3 + rng.below(4), 3 + rng.below(4))
            };
            generate::append(&mut mesh, &other);
        }
        for _ in 0..handles {
            let t = rng.below(mesh.triangles.len() as u32) as usize;
            if let Some(u) = generate::far_triangle(&mesh, t, &mut rng) {
                generate::add_handle(&mut mesh, t, u);
            }
        }
        generate::punch_holes(&mut mesh, holes, &mut rng);
        generate::add_defects(&mut mesh, defects, &mut rng);
        round_trip_mesh(&mesh);
    }

    #[test]
    fn soups_round_trip(seed in 0u64..1_000_000, v in 3u32..40, t in 0u32..120) {
        let mut rng = Rng::new(seed);
        round_trip_mesh(&generate::soup(v, t, &mut rng));
    }
}
