//! The bit-efficient LR in the container (kind 4, section `LRBE`): round trips, the
//! zero-copy view against the owned tables and the corner table, and forged sections.

mod common;

use common::{assert_same_up_to_rotation, check_against_table, corpus_dir, forge_fields};
use lrmesh::format::Tag;
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{CompactLr, CompactOptions, LrLayout};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::{CornerOps, CornerTable, Mesh};

/// As given, so that the owned structures of the same mesh are the file's.
fn options() -> EncodeOptions {
    EncodeOptions {
        connectivity: Connectivity::LrCompact,
        orient: Orient::AsGiven,
        ..EncodeOptions::default()
    }
}

fn meshes() -> Vec<(String, Mesh)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let path = entry.unwrap().path();
        if lrmesh::io::MeshFormat::from_path(&path).is_ok() {
            let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
            out.push((path.display().to_string(), mesh));
        }
    }
    let mut rng = Rng::new(5);
    let mut defective = generate::torus(7, 9);
    generate::append(&mut defective, &generate::torus(3, 4));
    generate::punch_holes(&mut defective, 3, &mut rng);
    generate::add_defects(&mut defective, 8, &mut rng);
    out.push(("generated defective".into(), defective));
    out.push(("soup".into(), generate::soup(14, 40, &mut rng)));
    out.push((
        "large irregular".into(),
        generate::irregular_torus(40_000, 9),
    ));
    out
}

#[test]
fn view_equals_owned_tables_and_corner_table() {
    for (name, mesh) in meshes() {
        let bytes = encode(&mesh, &options()).unwrap();
        let view = open(&bytes, &Limits::default()).unwrap();
        assert!(view.lr().is_none());
        let stored = view.lr_compact().expect("an lr-compact container");
        let table = CornerTable::from_mesh(&mesh).unwrap();
        let compact_options = CompactOptions {
            lr: options().lr,
            periods: options().periods,
            tip_bases: options().tip_bases,
        };
        let owned = CompactLr::build(&table, &compact_options).unwrap();
        assert!(bytes.len() as u64 > owned.stored_bytes());
        let tables = owned.tables();
        assert_eq!(
            stored.triangle_id_bound(),
            tables.triangle_id_bound(),
            "{name}"
        );
        assert!(stored.triangles().eq(tables.triangles()), "{name}");
        for c in tables.corners() {
            assert_eq!(stored.vertex(c), tables.vertex(c), "{name} c.v {c:?}");
            assert_eq!(stored.opposite(c), tables.opposite(c), "{name} c.o {c:?}");
        }
        for v in tables.vertices() {
            assert_eq!(stored.vertex_corner(v), tables.vertex_corner(v), "{name}");
        }
        let key = |c: lrmesh::Corner| {
            (
                owned.input_triangle(stored.triangle(c)),
                owned.input_vertex(stored.vertex(c)),
            )
        };
        check_against_table(stored, key, |v| view.position(v), &table, &mesh);
        let summary = view.summary();
        assert_eq!(summary.connectivity, "lr-compact");
        assert_eq!(summary.t0_triangles, Some(stored.t0_count()));
        // Kept order gives the input back exactly.
        let keep = EncodeOptions {
            keep_order: true,
            ..options()
        };
        let back = open(&encode(&mesh, &keep).unwrap(), &Limits::default())
            .unwrap()
            .to_mesh();
        assert_eq!(back.positions, mesh.positions, "{name}");
        assert_same_up_to_rotation(&back.triangles, &mesh.triangles, &name);
    }
}

#[test]
fn forced_period_is_recorded_and_smaller_choice_wins() {
    use lrmesh::format::layout::LrbeHeader;
    let mesh = generate::irregular_torus(20_000, 4);
    // (file size, period recorded in the LRBE header)
    let results: Vec<(usize, u32)> = [vec![0], vec![32], vec![0, 32]]
        .into_iter()
        .map(|periods| {
            let o = EncodeOptions {
                periods,
                ..options()
            };
            let bytes = encode(&mesh, &o).unwrap();
            let file = lrmesh::open(&bytes).unwrap();
            let section = file.sections.section(lrmesh::format::Tag::LRBE).unwrap();
            (bytes.len(), LrbeHeader::read(section.bytes).period)
        })
        .collect();
    assert_eq!(results[0].1, 0, "a forced period is recorded");
    assert_eq!(results[1].1, 32, "a forced period is recorded");
    assert_ne!(
        results[0].0, results[1].0,
        "the periods give different sizes"
    );
    let smaller = if results[0].0 < results[1].0 { 0 } else { 1 };
    assert_eq!(results[2], results[smaller], "the smaller choice wins");
}

/// Forged `LRBE` sections (checksums recomputed, so that the rules themselves must catch
/// them): every unit of small sections set to other values gives an error naming `LRBE`, or a
/// container whose operators answer with valid ids and whose swings terminate.
#[test]
fn forged_sections_are_rejected_or_consistent() {
    let mut holed = generate::torus(5, 6);
    generate::punch_holes(&mut holed, 2, &mut Rng::new(3));
    let mut defective = generate::torus(4, 5);
    generate::append(&mut defective, &generate::torus(3, 4));
    generate::add_defects(&mut defective, 4, &mut Rng::new(8));
    let torus = read_mesh(
        &corpus_dir().join("torus_quad.off"),
        &ReadOptions::default(),
    )
    .unwrap()
    .mesh;
    let (mut rejected, mut accepted) = (0, 0);
    for mesh in [torus, holed, defective] {
        let bytes = encode(&mesh, &options()).unwrap();
        let values = |original: u32| {
            vec![
                0,
                1,
                0x3FFF,
                0x4000,
                0x8000,
                0xC000,
                0xFFFF,
                (original as u16).wrapping_add(1) as u32,
                (original as u16).wrapping_sub(1) as u32,
                original ^ 0x0200,
            ]
        };
        let (r, a) = forge_fields(&bytes, Tag::LRBE, 2, values, |view| {
            let lr = view.lr_compact().unwrap();
            for c in lr.corners() {
                assert!(lr.vertex(c).0 < lr.vertex_id_bound());
                if let Some(o) = lr.opposite(c) {
                    assert_eq!(lr.opposite(o), Some(c));
                }
            }
            for v in lr.vertices() {
                assert!(lrmesh::ops::star(lr, v).count() <= 4 * lr.triangle_id_bound() as usize);
            }
            view.to_mesh().validate().unwrap();
        });
        rejected += r;
        accepted += a;
    }
    assert!(rejected > 0);
    eprintln!("{rejected} forged sections rejected, {accepted} accepted as consistent");
}
