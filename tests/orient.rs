//! Orientation repair (`write::Orient`, `lrmesh encode --orient`): on a mesh whose triangles
//! were written with mixed orientations, every representation shrinks, the operators answer
//! on the repaired surface, and decoding gives back the input's triangles (section `FLIP`)
//! or, when asked, the repaired ones.

mod common;

use common::{assert_same_up_to_rotation, check_against_table, corpus_dir};
use lrmesh::format::Tag;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::{Lr, LrOptions};
use lrmesh::mesh::{orient, Attribute, Semantic, Values};
use lrmesh::read::{open_verified, Limits, Sections};
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::{CornerTable, Mesh};

fn shuffled() -> Mesh {
    let path = corpus_dir().join("blobby-shuffled.off");
    read_mesh(&path, &ReadOptions::default()).unwrap().mesh
}

fn options(connectivity: Connectivity, keep_order: bool, orient: Orient) -> EncodeOptions {
    EncodeOptions {
        connectivity,
        keep_order,
        orient,
        ..EncodeOptions::default()
    }
}

/// Bytes of the connectivity section (the one of MESH's kind).
fn connectivity_bytes(bytes: &[u8]) -> usize {
    let sections = Sections::parse(bytes, &Limits::default()).unwrap();
    [Tag::LRTB, Tag::EBRK, Tag::STRP, Tag::LRBE, Tag::ZIPR]
        .iter()
        .find_map(|&t| sections.section(t))
        .unwrap()
        .bytes
        .len()
}

/// Each triangle as its oriented triple of positions, rotated to start at the smallest, all
/// sorted: the mesh up to vertex and triangle order.
fn by_position(mesh: &Mesh) -> Vec<[[u32; 3]; 3]> {
    let mut out: Vec<[[u32; 3]; 3]> = mesh
        .triangles
        .iter()
        .map(|t| {
            let p = t.map(|v| mesh.positions[v as usize].map(f32::to_bits));
            let k = (0..3).min_by_key(|&k| p[k]).unwrap();
            [p[k], p[(k + 1) % 3], p[(k + 2) % 3]]
        })
        .collect();
    out.sort_unstable();
    out
}

#[test]
fn the_shuffled_mesh_is_repaired() {
    let mesh = shuffled();
    let o = orient(&mesh);
    assert_eq!(o.conflicts, 0, "a closed genus-0 surface is orientable");
    assert!(o.flipped_count() > 0);
    let rpt = |m: &Mesh| {
        let table = CornerTable::from_mesh(m).unwrap();
        Lr::build(&table, &LrOptions::default())
            .unwrap()
            .counts()
            .references_per_triangle()
    };
    let (before, after) = (rpt(&mesh), rpt(&o.mesh));
    eprintln!("references per triangle: {before:.3} as given, {after:.3} oriented");
    // A closed, consistently oriented mesh of this regularity: about 1.4 (blobby_3cc 1.41).
    assert!(after < 1.5 && after < before / 2.0, "{before} -> {after}");
    // The operators of every kind answer as the repaired mesh's corner table.
    let table = CornerTable::from_mesh(&o.mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let key = |c| {
        use lrmesh::CornerOps;
        (
            lr.input_triangle(lr.triangle(c)),
            lr.input_vertex(lr.vertex(c)),
        )
    };
    let position = |v: lrmesh::Vertex| o.mesh.positions[lr.input_vertex(v) as usize];
    check_against_table(&lr, key, position, &table, &o.mesh);
}

#[test]
fn decoding_gives_back_the_input_or_the_repaired_triangles() {
    let mesh = shuffled();
    let repaired = orient(&mesh).mesh;
    let limits = Limits::default();
    for connectivity in Connectivity::ALL {
        let plain = encode(&mesh, &options(connectivity, false, Orient::AsGiven)).unwrap();
        for keep_order in [true, false] {
            let what = format!("{connectivity:?}, keep order {keep_order}");
            let bytes = encode(&mesh, &options(connectivity, keep_order, Orient::Repair)).unwrap();
            assert!(
                connectivity_bytes(&bytes) < connectivity_bytes(&plain),
                "{what}: smaller"
            );
            let container = open_verified(&bytes, &limits).unwrap();
            assert!(container.sections.section(Tag::FLIP).is_some());
            let back = container.to_mesh();
            if keep_order {
                assert_same_up_to_rotation(&back.triangles, &mesh.triangles, &what);
            } else {
                assert_eq!(by_position(&back), by_position(&mesh), "{what}");
            }
            let options = options(connectivity, keep_order, Orient::RepairAndKeep);
            let bytes = encode(&mesh, &options).unwrap();
            let container = open_verified(&bytes, &limits).unwrap();
            assert!(container.sections.section(Tag::FLIP).is_none());
            let back = container.to_mesh();
            if keep_order {
                assert_same_up_to_rotation(&back.triangles, &repaired.triangles, &what);
            } else {
                assert_eq!(by_position(&back), by_position(&repaired), "{what}");
            }
        }
    }
}

#[test]
fn per_corner_values_come_back_at_their_corners() {
    // Reversed triangles with a per-corner attribute: each corner's value must stay with its
    // vertex through the repair and the reversal on decoding.
    let mut mesh = shuffled();
    let n = mesh.triangles.len();
    mesh.attributes.push(Attribute {
        semantic: Semantic::Custom("corner".into()),
        components: 1,
        normalized: false,
        values: Values::U32((0..3 * n as u32).collect()),
        corners: Some((0..3 * n as u32).collect()),
    });
    for connectivity in Connectivity::ALL {
        let bytes = encode(&mesh, &options(connectivity, true, Orient::Repair)).unwrap();
        let back = open_verified(&bytes, &Limits::default()).unwrap().to_mesh();
        let a = &back.attributes[0];
        let Values::U32(values) = &a.values else {
            panic!("u32 values")
        };
        let corners = a.corners.as_ref().unwrap();
        for (t, (got, want)) in back.triangles.iter().zip(&mesh.triangles).enumerate() {
            for k in 0..3 {
                let value = values[corners[3 * t + k] as usize];
                let input_corner = want.iter().position(|&v| v == got[k]).unwrap();
                assert_eq!(
                    value,
                    (3 * t + input_corner) as u32,
                    "{connectivity:?}: {t}"
                );
            }
        }
    }
}

#[test]
fn a_consistent_mesh_gets_no_flip_section() {
    let mesh = read_mesh(&corpus_dir().join("fandisk.off"), &ReadOptions::default())
        .unwrap()
        .mesh;
    let with = encode(&mesh, &options(Connectivity::Lr, false, Orient::Repair)).unwrap();
    let without = encode(&mesh, &options(Connectivity::Lr, false, Orient::AsGiven)).unwrap();
    assert_eq!(with, without);
}

#[test]
fn the_forging_fuzz_targets_reach_flip() {
    // Bit 4 of the first byte: defects and reversed triangles, orientation repaired.
    for choice in [0x10u8, 0x11, 0x12, 0x13, 0x30, 0xD0] {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let sections = Sections::parse(&bytes, &Limits::default()).unwrap();
        assert!(sections.section(Tag::FLIP).is_some(), "choice {choice:#x}");
    }
}

#[test]
fn encoding_an_oriented_mesh_gives_the_same_bytes() {
    // `encode_oriented` spares a caller who oriented already (to report it) a second pass.
    let mesh = shuffled();
    let o = orient(&mesh);
    for orient_option in [Orient::Repair, Orient::RepairAndKeep] {
        let options = options(Connectivity::Edgebreaker, true, orient_option);
        assert_eq!(
            lrmesh::write::encode_oriented(&o, &options).unwrap(),
            encode(&mesh, &options).unwrap(),
            "{orient_option:?}"
        );
    }
}

/// The default, [`Orient::Auto`]: a mesh written with mixed orientations is stored repaired
/// when that makes the smaller file (the shuffled blobby, every kind, with `FLIP`: decoding
/// gives back the input's triangles); a mesh whose only fault is one reversed triangle, and
/// a consistent mesh, are stored as given by the LR kinds, byte for byte as
/// [`Orient::AsGiven`] stores them.
#[test]
fn auto_keeps_the_smaller_file() {
    let size = |mesh: &Mesh, options: &EncodeOptions| encode(mesh, options).unwrap().len();
    let mesh = shuffled();
    for connectivity in Connectivity::ALL {
        let what = format!("{connectivity:?}");
        let auto = encode(&mesh, &options(connectivity, false, Orient::Auto)).unwrap();
        let as_given = size(&mesh, &options(connectivity, false, Orient::AsGiven));
        let repaired = size(&mesh, &options(connectivity, false, Orient::Repair));
        assert_eq!(auto.len(), repaired.min(as_given), "{what}");
        // The writer that takes the mesh (and frees its triangles once the corner table holds
        // them) gets them back from the table to try both.
        let owned = options(connectivity, false, Orient::Auto);
        assert!(
            lrmesh::write::encode_owned(mesh.clone(), &owned).unwrap() == auto,
            "{what}"
        );
        assert!(
            2 * auto.len() < as_given,
            "{what}: {} of {as_given}",
            auto.len()
        );
        let container = open_verified(&auto, &Limits::default()).unwrap();
        assert!(container.sections.section(Tag::FLIP).is_some(), "{what}");
        assert_eq!(
            by_position(&container.to_mesh()),
            by_position(&mesh),
            "{what}"
        );
    }
    // One reversed triangle of a torus: a bit per triangle costs the Zipper more than what
    // the cut costs it (the strips lose more to it, and the standard LR, whose cut adds a
    // list of open fans of two words per 32 ring vertices: there the repaired file is
    // smaller); a consistent torus has nothing to repair.
    let mut one = lrmesh::generate::torus(30, 40);
    one.triangles[100].swap(1, 2);
    let consistent = lrmesh::generate::torus(12, 9);
    for (mesh, name) in [(one, "one reversed"), (consistent, "consistent")] {
        for connectivity in Connectivity::ALL {
            let what = format!("{name}, {connectivity:?}");
            let auto = encode(&mesh, &options(connectivity, false, Orient::Auto)).unwrap();
            let as_given = encode(&mesh, &options(connectivity, false, Orient::AsGiven)).unwrap();
            let repaired = size(&mesh, &options(connectivity, false, Orient::Repair));
            assert_eq!(auto.len(), repaired.min(as_given.len()), "{what}");
            if name == "consistent" || connectivity == Connectivity::Zipper {
                assert!(auto == as_given, "{what}");
            }
        }
    }
}
