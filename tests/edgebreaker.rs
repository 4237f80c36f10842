//! Edgebreaker: round trips on real and generated meshes, the paper's examples, and hostile
//! input.

mod common;

use common::{assert_same_up_to_rotation, corpus_dir, shared_dir};
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
        generate::add_random_handles(&mut mesh, handles, &mut rng);
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

/// The annulus of the paper's Fig. 10: `n` outer and `n` inner vertices, `2n` triangles.
fn annulus(n: u32) -> Mesh {
    let mut positions = Vec::new();
    for i in 0..n {
        let a = i as f32 / n as f32 * std::f32::consts::TAU;
        positions.push([2.0 * a.cos(), 2.0 * a.sin(), 0.0]);
    }
    for i in 0..n {
        let a = (i as f32 + 0.5) / n as f32 * std::f32::consts::TAU;
        positions.push([a.cos(), a.sin(), 0.0]);
    }
    let mut triangles = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.push([i, j, n + i]);
        triangles.push([j, n + j, n + i]);
    }
    Mesh::new(positions, triangles)
}

/// Fig. 9: the torus of 3x3 cells (18 triangles). Its CLERS string in the paper,
/// `CCCCRCSCRSSRLSEEE` after the implicit first triangle, has 6 C, 4 S of which 2 are handle
/// S, and 3 E; any start gives the same counts, and the two handle S go to the topology stream.
#[test]
fn paper_torus_fig9() {
    let (enc, dec) = round_trip_mesh(&generate::torus(3, 3));
    let s = &enc.stats;
    print_stats("torus 3x3 (Fig. 9)", s);
    assert_eq!(s.triangles, 18);
    assert_eq!((s.p, s.c, s.handle_s, s.boundary_s), (1, 6, 2, 0));
    assert_eq!(
        s.e,
        s.s - s.handle_s + 1,
        "every normal S opens a branch that an E closes"
    );
    assert_eq!(s.c + s.l + s.e + s.r + s.s + s.p, 18);
    assert_eq!(dec.vertex_count, 9);
}

/// Fig. 10: an annulus. The external boundary comes first, the inner one is reached by one
/// boundary S; every vertex is on a boundary, so there is no C at all.
#[test]
fn paper_annulus_fig10() {
    for n in [3, 4, 8, 50] {
        let mesh = annulus(n);
        let (enc, dec) = round_trip_mesh(&mesh);
        let s = &enc.stats;
        print_stats(&format!("annulus {n} (Fig. 10)"), s);
        assert_eq!((s.components, s.boundary_components), (1, 1));
        assert_eq!((s.boundary_s, s.handle_s, s.c, s.p), (1, 0, 0, 0));
        assert_eq!(dec.triangles.len() as u32, 2 * n);
        // The first n decoded vertices are one boundary curve, in order.
        let outer: Vec<u32> = enc.vertex_order[..n as usize].to_vec();
        let ring = |v: u32| v / n;
        assert!(outer.iter().all(|&v| ring(v) == ring(outer[0])));
    }
}

/// Genus and boundaries together: handle S count 2g, boundary S count b - 1 per component.
#[test]
fn handles_and_holes_counts() {
    let mesh = read_mesh(
        &corpus_dir().join("double-torus-3-holes.off"),
        &ReadOptions::default(),
    )
    .unwrap()
    .mesh;
    let (enc, _) = round_trip_mesh(&mesh);
    assert_eq!((enc.stats.handle_s, enc.stats.boundary_s), (4, 2));
    let mesh = read_mesh(&corpus_dir().join("cheese.off"), &ReadOptions::default())
        .unwrap()
        .mesh;
    let (enc, _) = round_trip_mesh(&mesh);
    assert_eq!(enc.stats.handle_s, 2 * 133);
}

/// The decoded connectivity is a mesh the corner table and the LR accept.
#[test]
fn decoded_mesh_builds_lr() {
    for name in ["elephant-with-holes.off", "b9_mesh.off", "knot1.off"] {
        let mesh = read_mesh(&corpus_dir().join(name), &ReadOptions::default())
            .unwrap()
            .mesh;
        let (_, dec) = round_trip_mesh(&mesh);
        let table = CornerTable::build(dec.vertex_count as usize, &dec.triangles).unwrap();
        let lr = lrmesh::lr::Lr::build(&table, &lrmesh::lr::LrOptions::default()).unwrap();
        let back = lr.input_triangles();
        assert_same_up_to_rotation(&back, &dec.triangles, "LR of the decoded mesh");
    }
}

fn small_encodings() -> Vec<(String, Vec<u8>)> {
    let mut rng = Rng::new(99);
    let mut soup = generate::soup(12, 30, &mut rng);
    generate::add_defects(&mut soup, 4, &mut rng);
    let mut holed = generate::torus(4, 5);
    generate::punch_holes(&mut holed, 3, &mut rng);
    let meshes = [
        (
            "tetrahedron",
            read_mesh(
                &corpus_dir().join("tetrahedron.off"),
                &ReadOptions::default(),
            )
            .unwrap()
            .mesh,
        ),
        ("torus 3x3", generate::torus(3, 3)),
        ("annulus 5", annulus(5)),
        ("holed torus", holed),
        ("soup", soup),
    ];
    meshes
        .into_iter()
        .map(|(name, m)| {
            let table = CornerTable::from_mesh(&m).unwrap();
            (name.to_string(), encode(&table).unwrap().bytes)
        })
        .collect()
}

#[test]
fn hostile_truncations_and_byte_changes() {
    let limits = Limits::default();
    for (name, bytes) in small_encodings() {
        assert!(decode(&bytes, &limits).is_ok(), "{name} decodes");
        for len in 0..bytes.len() {
            let _ = decode(&bytes[..len], &limits);
        }
        let mut oks = 0;
        let mut copy = bytes.clone();
        for i in 0..bytes.len() {
            for value in 0..=255u8 {
                copy[i] = value;
                if let Ok(d) = decode(&copy, &limits) {
                    oks += 1;
                    // Whatever decodes is in range.
                    assert!(d.triangles.iter().flatten().all(|&v| v < d.vertex_count));
                }
            }
            copy[i] = bytes[i];
        }
        eprintln!(
            "{name}: {} bytes, {oks} of {} single-byte changes still decode",
            bytes.len(),
            256 * bytes.len()
        );
    }
}

#[test]
fn hostile_bit_flips_on_a_real_mesh() {
    let mesh = read_mesh(
        &corpus_dir().join("elephant-with-holes.off"),
        &ReadOptions::default(),
    )
    .unwrap()
    .mesh;
    let bytes = encode(&CornerTable::from_mesh(&mesh).unwrap())
        .unwrap()
        .bytes;
    let mut copy = bytes.clone();
    for i in 0..bytes.len() {
        for mask in [0x01u8, 0x10, 0x80, 0xFF] {
            copy[i] ^= mask;
            let _ = decode(&copy, &Limits::default());
            copy[i] = bytes[i];
        }
    }
    for len in (0..bytes.len()).step_by(7) {
        assert!(decode(&bytes[..len], &Limits::default()).is_err() || len == bytes.len());
    }
}

#[test]
fn huge_declared_counts_fail_fast() {
    fn leb(out: &mut Vec<u8>, mut x: u64) {
        loop {
            let b = (x & 0x7F) as u8;
            x >>= 7;
            if x == 0 {
                out.push(b);
                return;
            }
            out.push(b | 0x80);
        }
    }
    for (nv, nt) in [
        (3u64 << 30, 1u64 << 30),
        (1 << 26, 1 << 26),
        (3_000_000, 1_000_000),
        (u64::MAX, u64::MAX),
    ] {
        let mut bytes = vec![0xEB, 1];
        leb(&mut bytes, nv);
        leb(&mut bytes, 0);
        leb(&mut bytes, nt);
        leb(&mut bytes, 3);
        bytes.extend_from_slice(&[0x55; 40]);
        let err = decode(&bytes, &Limits::default()).unwrap_err().to_string();
        assert!(err.contains("Edgebreaker"), "{err}");
    }
    // Within the limits and holdable by the bytes, but garbage: an error, soon.
    let mut bytes = vec![0xEB, 1];
    leb(&mut bytes, 30_000);
    leb(&mut bytes, 0);
    leb(&mut bytes, 60_000);
    leb(&mut bytes, 2);
    bytes.extend_from_slice(&[0xA7; 61]);
    assert!(decode(&bytes, &Limits::default()).is_err());
    // Limits are honoured.
    let small = Limits {
        max_triangles: 10,
        max_vertices: 10,
    };
    let big = encode(&CornerTable::from_mesh(&generate::torus(4, 4)).unwrap()).unwrap();
    assert!(decode(&big.bytes, &small).is_err());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn random_bytes_never_panic(body in proptest::collection::vec(any::<u8>(), 0..200),
                                nv in 0u64..100, nt in 0u64..100, topo in 0u64..20) {
        let mut bytes = vec![0xEB, 1, nv as u8, 0, nt as u8, topo as u8];
        bytes.extend_from_slice(&body);
        let _ = decode(&bytes, &Limits::default());
        let _ = decode(&body, &Limits::default());
    }
}
