//! The Laced Ring against the corner table: every canonical corner, on real and generated
//! meshes.

mod common;

use common::{assert_same_up_to_rotation, check_against_table, corpus_dir, torus_with_everything};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{Lr, LrOptions};
use lrmesh::{CornerOps, CornerTable, Mesh};
use proptest::prelude::*;

fn check_lr(mesh: &Mesh, options: &LrOptions) -> Lr {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let lr = Lr::build(&table, options).unwrap();
    let key = |c: lrmesh::Corner| {
        (
            lr.input_triangle(lr.triangle(c)),
            lr.input_vertex(lr.vertex(c)),
        )
    };
    let position = |v: lrmesh::Vertex| mesh.positions[lr.input_vertex(v) as usize];
    check_against_table(&lr, key, position, &table, mesh);
    // The LR alone gives back every input triangle, oriented, up to rotation.
    assert_same_up_to_rotation(&lr.input_triangles(), &mesh.triangles, "LR");
    for k in 0..mesh.triangles.len() {
        match lr.lr_triangle(k as u32) {
            Some(t) => assert_eq!(lr.input_triangle(t), k as u32),
            None => assert!(lr.kept_aside().iter().any(|&(i, _)| i == k as u32)),
        }
    }
    for v in 0..mesh.positions.len() as u32 {
        assert_eq!(lr.input_vertex(lr.lr_vertex(v)), v);
    }
    lr
}

#[test]
fn torus() {
    let lr = check_lr(&generate::torus(6, 9), &LrOptions::default());
    assert_eq!(lr.counts().isolated_vertices(), 0);
}

#[test]
fn irregular_torus() {
    let lr = check_lr(&generate::irregular_torus(20_000, 3), &LrOptions::default());
    eprintln!(
        "{:?} rpt {}",
        lr.counts(),
        lr.counts().references_per_triangle()
    );
}

#[test]
fn single_triangle_and_pocket() {
    check_lr(
        &Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2]]),
        &LrOptions::default(),
    );
    check_lr(
        &Mesh::new(vec![[0.0; 3]; 3], vec![[0, 1, 2], [0, 2, 1]]),
        &LrOptions::default(),
    );
}

#[test]
fn corpus_meshes() {
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let path = entry.unwrap().path();
        if lrmesh::io::MeshFormat::from_path(&path).is_err() {
            continue;
        }
        let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        let lr = check_lr(&mesh, &LrOptions::default());
        eprintln!(
            "{}: {:?} rpt {:.3}",
            path.display(),
            lr.counts(),
            lr.counts().references_per_triangle()
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn soups(vertices in 1u32..25, triangles in 0u32..60, seed in any::<u64>(), tries in 1u32..4) {
        let mesh = generate::soup(vertices, triangles, &mut Rng::new(seed));
        check_lr(&mesh, &LrOptions { tries, seed, ..LrOptions::default() });
    }

    #[test]
    fn tori_with_everything(around in 3u32..9, along in 3u32..9, holes in 0usize..8,
                            defects in 0usize..10, handles in 0usize..3, seed in any::<u64>()) {
        let mesh = torus_with_everything(around, along, holes, defects, handles, seed);
        check_lr(&mesh, &LrOptions { tries: 2, seed, ..LrOptions::default() });
    }
}

/// Several threads share the tries of a large component and the search for irregular
/// triangles: the LR (and so every byte written from it) is the one a single thread builds.
#[test]
fn threads_build_the_same_lr() {
    let mesh = generate::surface(&generate::SurfaceOptions {
        triangles: 160_000,
        genus: 2,
        holes: 40,
        components: 2,
        irregular: true,
        seed: 7,
    });
    let one = check_lr(&mesh, &LrOptions::default());
    for threads in [2, 3] {
        let options = LrOptions {
            threads,
            ..LrOptions::default()
        };
        let table = CornerTable::from_mesh(&mesh).unwrap();
        assert!(
            Lr::build(&table, &options).unwrap() == one,
            "{threads} threads"
        );
    }
    let bytes = |threads| {
        let mut options = lrmesh::write::EncodeOptions {
            connectivity: lrmesh::write::Connectivity::LrCompact,
            periods: vec![0, 32],
            ..Default::default()
        };
        options.lr.threads = threads;
        lrmesh::write::encode(&mesh, &options).unwrap()
    };
    assert_eq!(bytes(1), bytes(2));
}
