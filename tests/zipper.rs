//! The Zipper against the corner table (every canonical corner) and against the standard LR
//! it encodes (every slot), on real and generated meshes.

mod common;

use common::{
    assert_same_up_to_rotation, check_against_table, corpus_dir, shared_dir, torus_with_everything,
};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrLayout, LrOptions, Zipper, ZipperTables};
use lrmesh::{CornerOps, CornerTable, Mesh};
use proptest::prelude::*;

fn check_zipper(mesh: &Mesh, options: &LrOptions) -> Zipper {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let zipper = check_zipper_of(&table, mesh, |t| Zipper::build(t, options).unwrap());
    let tables = zipper.tables();
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

/// `Zipper::build_smallest` keeps the smallest tables of its seeds (the first of equals),
/// whatever the thread count, and they answer every corner as the corner table does.
#[test]
fn the_smallest_of_several_seeds() {
    let mut mesh = generate::irregular_torus(600, 3);
    generate::punch_holes(&mut mesh, 6, &mut Rng::new(2));
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let options = LrOptions {
        seed: 7,
        ..LrOptions::default()
    };
    let sizes: Vec<u64> = (0..12)
        .map(|k| {
            let seed = 7 + k;
            let z = Zipper::build(&table, &LrOptions { seed, ..options }).unwrap();
            z.tables().stored_bytes()
        })
        .collect();
    let smallest = *sizes.iter().min().unwrap();
    let first = sizes.iter().position(|&b| b == smallest).unwrap() as u64;
    assert!(
        smallest < sizes[0],
        "the seeds give different sizes: {sizes:?}"
    );
    let expected = Zipper::build(
        &table,
        &LrOptions {
            seed: 7 + first,
            ..options
        },
    )
    .unwrap();
    for threads in [1, 2, 5] {
        let z = Zipper::build_smallest(&table, &LrOptions { threads, ..options }, 12).unwrap();
        assert_eq!(z.tables(), expected.tables(), "{threads} threads");
    }
    let z = check_zipper_of(&table, &mesh, |t| {
        Zipper::build_smallest(t, &options, 12).unwrap()
    });
    assert_eq!(z.tables().stored_bytes(), smallest);
    // One seed: the one build.
    let one = Zipper::build_smallest(&table, &options, 1).unwrap();
    assert_eq!(one.tables().stored_bytes(), sizes[0]);
}

/// The writer's search: one seed below the default level, up to 32 seeds at it on a small
/// mesh, fewer as meshes grow, one from 2^19 triangles; more at higher levels.
#[test]
fn seeds_by_level_and_size() {
    use lrmesh::write::zipper_seeds;
    assert_eq!(zipper_seeds(0, 100), 1);
    assert_eq!(zipper_seeds(5, 100), 1);
    assert_eq!(zipper_seeds(6, 100), 32);
    assert_eq!(zipper_seeds(6, 1 << 16), 8);
    assert_eq!(zipper_seeds(6, 1 << 18), 2);
    assert_eq!(zipper_seeds(6, 1 << 19), 1);
    assert_eq!(zipper_seeds(6, 3_300_000), 1);
    assert_eq!(zipper_seeds(7, 100), 64);
    assert_eq!(zipper_seeds(9, 100), 256);
    assert_eq!(zipper_seeds(9, 1 << 16), 64);
    assert_eq!(zipper_seeds(9, 0), 256);
    // The file `encode` writes at the default level holds the smallest tables.
    let mesh = generate::irregular_torus(400, 9);
    let encode = |level| {
        let options = lrmesh::write::EncodeOptions {
            connectivity: lrmesh::write::Connectivity::Zipper,
            level,
            ..Default::default()
        };
        lrmesh::write::encode(&mesh, &options).unwrap().len()
    };
    assert!(
        encode(6) < encode(5),
        "the search finds a smaller ring on this mesh"
    );
}

/// `stored_bytes` is the `ZIPR` section's length in the container, with joined lists (the
/// writer's form) and on meshes with one ring and several, with and without holes.
#[test]
fn stored_bytes_are_the_written_section() {
    let mut holed = generate::irregular_torus(3_000, 4);
    generate::punch_holes(&mut holed, 9, &mut Rng::new(3));
    let two = generate::surface(&generate::SurfaceOptions {
        triangles: 2_000,
        genus: 2,
        holes: 0,
        components: 2,
        irregular: true,
        seed: 1,
    });
    for mesh in [generate::irregular_torus(5_000, 2), holed, two] {
        let options = lrmesh::write::EncodeOptions {
            connectivity: lrmesh::write::Connectivity::Zipper,
            ..Default::default()
        };
        let bytes = lrmesh::write::encode(&mesh, &options).unwrap();
        let view = lrmesh::read::open(&bytes, &lrmesh::read::Limits::default()).unwrap();
        let tables = view.zipper().expect("a zipper container");
        assert!(tables.joined_lists());
        // No copies, kept or reversed triangles: the connectivity is the ZIPR section alone.
        assert_eq!(view.summary().vertex_copies, 0);
        assert_eq!(tables.stored_bytes(), view.summary().connectivity_bytes);
    }
}

/// [`check_zipper`] of the Zipper that `build` makes from `table` (of `mesh`).
fn check_zipper_of(
    table: &CornerTable,
    mesh: &Mesh,
    build: impl Fn(&CornerTable) -> Zipper,
) -> Zipper {
    let zipper = build(table);
    let tables = zipper.tables();
    let key = |c: lrmesh::Corner| {
        (
            zipper.input_triangle(tables.triangle(c)),
            zipper.input_vertex(tables.vertex(c)),
        )
    };
    let position = |v: lrmesh::Vertex| mesh.positions[zipper.input_vertex(v) as usize];
    check_against_table(tables, key, position, table, mesh);
    check_against_table(&tables.cursor(), key, position, table, mesh);
    check_cursor(tables);
    assert_same_up_to_rotation(&zipper.input_triangles(), &mesh.triangles, "zipper");
    zipper
}

/// A cursor reads every slot as the tables do, whatever the order of the reads: in slot
/// order, then in a scattered order that makes it evict and decode blocks again and again.
fn check_cursor(tables: &ZipperTables<Vec<u32>>) {
    let m_r = tables.ring_vertices();
    let mut order: Vec<u32> = (0..2 * m_r).collect();
    let cursor = tables.cursor();
    for pass in 0..2 {
        for &s in &order {
            let (v, side) = (s / 2, (s % 2) as usize);
            assert_eq!(
                (cursor.tip_and_wart(v, side), cursor.irregular(v, side)),
                (tables.tip_and_wart(v, side), tables.irregular(v, side)),
                "slot ({v}, {side}), pass {pass}"
            );
            for second in 0..2 {
                assert_eq!(
                    cursor.stored_opposite(v, side, second),
                    tables.stored_opposite(v, side, second)
                );
            }
        }
        Rng::new(u64::from(m_r)).shuffle(&mut order);
    }
    for v in tables.vertices() {
        assert_eq!(cursor.vertex_corner(v), tables.vertex_corner(v), "{v:?}.c");
    }
    for k in 0..3 * tables.t0_count() {
        assert_eq!(cursor.t0_opposite(k), tables.t0_opposite(k), "T0 row {k}");
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
