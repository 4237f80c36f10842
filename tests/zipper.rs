//! The Zipper against the corner table (every canonical corner) and against the standard LR
//! it encodes (every slot), on real and generated meshes.

mod common;

use common::{
    assert_same_up_to_rotation, check_against_table, corpus_dir, shared_dir, torus_with_everything,
};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrLayout, LrOptions, Zipper};
use lrmesh::{CornerOps, CornerTable, Mesh};
use proptest::prelude::*;

fn check_zipper(mesh: &Mesh, options: &LrOptions) -> Zipper {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let zipper = Zipper::build(&table, options).unwrap();
    let tables = zipper.tables();
    let key = |c: lrmesh::Corner| {
        (
            zipper.input_triangle(tables.triangle(c)),
            zipper.input_vertex(tables.vertex(c)),
        )
    };
    let position = |v: lrmesh::Vertex| mesh.positions[zipper.input_vertex(v) as usize];
    check_against_table(tables, key, position, &table, mesh);
    assert_same_up_to_rotation(&zipper.input_triangles(), &mesh.triangles, "zipper");
    let stats = zipper.stats();
    assert_eq!(stats.bytes, tables.stored_bytes());
    zipper
}

#[test]
fn torus_and_small_cases() {
    let options = LrOptions::default();
    check_zipper(&generate::torus(6, 9), &options);
    check_zipper(&Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2]]), &options);
    check_zipper(
        &Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2], [0, 2, 1]]),
        &options,
    );
    check_zipper(&Mesh::new(vec![[0.0; 3]; 4], vec![]), &options);
}

/// Every slot holds what the standard LR of the same ring holds, over many blocks, several
/// rings and boundaries.
#[test]
fn same_slots_as_standard_lr() {
    let mut rng = Rng::new(5);
    let mut mesh = generate::irregular_torus(30_000, 11);
    generate::punch_holes(&mut mesh, 20, &mut rng);
    mesh.triangles.extend(
        generate::torus(5, 7)
            .triangles
            .iter()
            .map(|t| t.map(|v| v + mesh.positions.len() as u32)),
    );
    mesh.positions.extend(generate::torus(5, 7).positions);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let s = lr.tables().clone();
    let zipper = Zipper::encode(lr).unwrap();
    let z = zipper.tables();
    assert!(z.ring_count() > 1);
    assert_eq!(z.ring_vertices(), s.ring_vertices());
    for v in 0..z.ring_vertices() {
        for side in [0, 1] {
            assert_eq!(z.tip(v, side), s.tip(v, side), "tip {v} {side}");
            assert_eq!(z.wart(v, side), s.wart(v, side), "wart {v} {side}");
            assert_eq!(z.irregular(v, side), s.irregular(v, side));
            for k in [0, 1] {
                let i = 4 * side as u32 + 2 * k as u32;
                let opposite = |t: &dyn Fn() -> (Option<u32>, u32)| {
                    let (stored, inferred) = t();
                    stored.unwrap_or(inferred)
                };
                assert_eq!(
                    opposite(&|| (z.stored_opposite(v, side, k), z.inferred_opposite(v, i))),
                    opposite(&|| (s.stored_opposite(v, side, k), s.inferred_opposite(v, i))),
                    "opposite {v} {side} {k}"
                );
            }
        }
    }
}

#[test]
fn corpus_and_shared_meshes() {
    let mut dirs = vec![corpus_dir()];
    dirs.extend(shared_dir());
    for dir in dirs {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if lrmesh::io::MeshFormat::from_path(&path).is_err() {
                continue;
            }
            let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
            let zipper = check_zipper(&mesh, &LrOptions::default());
            let s = zipper.stats();
            let table = CornerTable::from_mesh(&mesh).unwrap();
            let compact = CompactLr::build(&table, &CompactOptions::default()).unwrap();
            eprintln!(
                "{:30} exc {:5.2}% sym {:5.2} exc {:5.2} rec {:5.2} t0 {:5.2} bpt {:6.2} (compact {:6.2})",
                path.file_name().unwrap().to_string_lossy(),
                s.exceptions_pct,
                s.symbol_bits,
                s.exception_bits,
                s.record_bits,
                s.t0_bits,
                s.bits_per_triangle,
                compact.stats().bpt,
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn soups(vertices in 1u32..25, triangles in 0u32..60, seed in any::<u64>()) {
        let mesh = generate::soup(vertices, triangles, &mut Rng::new(seed));
        check_zipper(&mesh, &LrOptions { tries: 2, seed, ..LrOptions::default() });
    }

    #[test]
    fn tori_with_everything(around in 3u32..9, along in 3u32..9, holes in 0usize..8,
                            defects in 0usize..10, handles in 0usize..3, seed in any::<u64>()) {
        let mesh = torus_with_everything(around, along, holes, defects, handles, seed);
        check_zipper(&mesh, &LrOptions { tries: 2, seed, ..LrOptions::default() });
    }
}
