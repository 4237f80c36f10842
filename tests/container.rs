//! The `.lrm` container: lossless round trips, the zero-copy view against the owned LR and the
//! corner table, determinism, and rejection of every damaged byte.

mod common;

use common::{
    assert_within_half_a_step, check_against_table, corpus_dir, forge_fields, sections_of,
};
use lrmesh::fuzz_checks::{assert_same_in_order, assert_same_up_to_order, rotated};
use lrmesh::generate::{self, Rng};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::Lr;
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::read::{open, Limits};
use lrmesh::strips::Cts;
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::{CornerOps, CornerTable, Error, Mesh};
use proptest::prelude::*;

fn corpus() -> Vec<(String, Mesh)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let path = entry.unwrap().path();
        if lrmesh::io::MeshFormat::from_path(&path).is_ok() {
            let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
            out.push((
                path.file_name().unwrap().to_string_lossy().into_owned(),
                mesh,
            ));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

fn with_attributes(mut mesh: Mesh, seed: u64) -> Mesh {
    let mut rng = Rng::new(seed);
    let n = mesh.positions.len();
    let normals: Vec<[f32; 3]> = (0..n)
        .map(|_| [rng.unit(), rng.unit(), -rng.unit()])
        .collect();
    mesh.set_attribute(Attribute::per_vertex(Semantic::Normal, &normals));
    let texcoords: Vec<[f32; 2]> = (0..n).map(|_| [rng.unit(), rng.unit()]).collect();
    mesh.set_attribute(Attribute::per_vertex(Semantic::TexCoord(0), &texcoords));
    let colors: Vec<[u8; 4]> = (0..n)
        .map(|_| [0; 4].map(|_: u8| rng.below(256) as u8))
        .collect();
    mesh.set_attribute(Attribute::rgba8(&colors));
    mesh
}

fn round_trip(mesh: &Mesh, keep_order: bool) -> Vec<u8> {
    round_trip_as(mesh, keep_order, Connectivity::Edgebreaker);
    round_trip_as(mesh, keep_order, Connectivity::Strips);
    round_trip_as(mesh, keep_order, Connectivity::Lr)
}

fn round_trip_as(mesh: &Mesh, keep_order: bool, connectivity: Connectivity) -> Vec<u8> {
    let options = EncodeOptions {
        keep_order,
        connectivity,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    let view = open(&bytes, &Limits::default()).unwrap();
    let back = view.to_mesh();
    if keep_order {
        assert_same_in_order(&back, mesh);
    } else {
        assert_same_up_to_order(&back, mesh);
    }
    bytes
}

#[test]
fn corpus_round_trips() {
    for (name, mesh) in corpus() {
        eprintln!("{name}");
        round_trip(&mesh, false);
        round_trip(&mesh, true);
        round_trip(&with_attributes(mesh, 5), true);
    }
}

#[test]
fn encoding_is_deterministic() {
    for (_, mesh) in corpus().into_iter().take(6) {
        let options = EncodeOptions::default();
        assert_eq!(
            encode(&mesh, &options).unwrap(),
            encode(&mesh, &options).unwrap()
        );
    }
}

#[test]
fn view_equals_owned_lr_and_corner_table() {
    for (name, mesh) in corpus() {
        // As given, so that the owned LR of the same mesh is the file's.
        let options = EncodeOptions {
            orient: Orient::AsGiven,
            ..EncodeOptions::default()
        };
        let bytes = encode(&mesh, &options).unwrap();
        let view = open(&bytes, &Limits::default()).unwrap();
        let table = CornerTable::from_mesh(&mesh).unwrap();
        let owned = Lr::build(&table, &options.lr).unwrap();
        let lr = view.lr().expect("an LR container");
        assert_eq!(lr.triangle_id_bound(), owned.triangle_id_bound(), "{name}");
        for c in owned.corners() {
            assert_eq!(lr.vertex(c), owned.vertex(c), "{name} c.v {c:?}");
            assert_eq!(lr.opposite(c), owned.opposite(c), "{name} c.o {c:?}");
            assert_eq!(lr.swing(c), owned.swing(c), "{name} c.s {c:?}");
        }
        for v in owned.vertices() {
            assert_eq!(lr.vertex_corner(v), owned.vertex_corner(v));
            assert_eq!(
                view.position(v),
                mesh.positions[owned.input_vertex(v) as usize]
            );
        }
        // And the view checks out against the corner table on its own.
        let key = |c: lrmesh::Corner| {
            (
                owned.input_triangle(lr.triangle(c)),
                owned.input_vertex(lr.vertex(c)),
            )
        };
        check_against_table(lr, key, |v| view.position(v), &table, &mesh);
    }
}

/// The strips kind: the view on the buffer answers every operator exactly as the owned
/// constrained strips do, and agrees with the corner table corner by corner.
#[test]
fn strips_view_equals_owned_cts_and_corner_table() {
    let mut meshes = corpus();
    let mut rng = Rng::new(11);
    let mut defective = generate::torus(6, 7);
    generate::append(&mut defective, &generate::torus(3, 4));
    generate::punch_holes(&mut defective, 3, &mut rng);
    generate::add_defects(&mut defective, 8, &mut rng);
    meshes.push(("generated defective".into(), defective));
    meshes.push(("soup".into(), generate::soup(12, 30, &mut rng)));
    for (name, mesh) in meshes {
        let options = EncodeOptions {
            connectivity: Connectivity::Strips,
            orient: Orient::AsGiven,
            ..EncodeOptions::default()
        };
        let bytes = encode(&mesh, &options).unwrap();
        let view = open(&bytes, &Limits::default()).unwrap();
        assert!(view.lr().is_none());
        let strips = view.strips().expect("a strips container");
        let table = CornerTable::from_mesh(&mesh).unwrap();
        let owned = Cts::build(&table, &options.strips).unwrap();
        assert_eq!(
            strips.triangle_id_bound(),
            owned.triangle_id_bound(),
            "{name}"
        );
        assert_eq!(strips.vertex_id_bound(), owned.vertex_id_bound(), "{name}");
        assert_eq!(strips.triangle_count(), owned.triangle_count(), "{name}");
        assert!(strips.triangles().eq(owned.triangles()), "{name}");
        for c in owned.corners() {
            assert_eq!(strips.vertex(c), owned.vertex(c), "{name} c.v {c:?}");
            assert_eq!(strips.opposite(c), owned.opposite(c), "{name} c.o {c:?}");
            assert_eq!(strips.swing(c), owned.swing(c), "{name} c.s {c:?}");
        }
        for v in owned.vertices() {
            assert_eq!(strips.vertex_corner(v), owned.vertex_corner(v), "{name}");
            assert_eq!(
                view.position(v),
                mesh.positions[owned.input_vertex(v) as usize]
            );
        }
        let key = |c: lrmesh::Corner| {
            (
                owned.input_triangle(strips.triangle(c)),
                owned.input_vertex(strips.vertex(c)),
            )
        };
        check_against_table(strips, key, |v| view.position(v), &table, &mesh);
        let summary = view.summary();
        assert_eq!(summary.connectivity, "strips");
        assert!(summary.rpt.is_some());
    }
}

/// Forged `STRP` sections (checksums recomputed, so the rules themselves must catch them):
/// every word of a small section set to other values gives an error naming `STRP`, or a
/// container whose operators answer with valid ids; never a panic.
#[test]
fn forged_strips_sections_are_rejected_or_consistent() {
    use lrmesh::format::Tag;
    let mut mesh = generate::torus(3, 4);
    generate::punch_holes(&mut mesh, 1, &mut Rng::new(3));
    let options = EncodeOptions {
        connectivity: Connectivity::Strips,
        ..EncodeOptions::default()
    };
    let bytes = encode(&mesh, &options).unwrap();
    let values = |original: u32| {
        vec![
            0,
            1,
            2,
            5,
            original.wrapping_add(1),
            original.wrapping_sub(1),
            original ^ 0x8000_0000,
            u32::MAX,
            u32::MAX - 1,
        ]
    };
    let (rejected, accepted) = forge_fields(&bytes, Tag::STRP, 4, values, |view| {
        let strips = view.strips().unwrap();
        for c in strips.corners() {
            assert!(strips.vertex(c).0 < strips.vertex_id_bound());
            if let Some(o) = strips.opposite(c) {
                assert_eq!(strips.opposite(o), Some(c));
            }
        }
        for v in strips.vertices() {
            lrmesh::ops::star(strips, v).count();
        }
        view.to_mesh().validate().unwrap();
    });
    assert!(rejected > 0);
    eprintln!("{rejected} forged sections rejected, {accepted} accepted as consistent");
}

/// Quantized positions come back within half a grid step (plus the f32 rounding of the
/// decoded value), in every kind, at every level, for several precisions; and the file is
/// smaller than the exact one.
#[test]
fn quantized_positions_are_within_half_a_step() {
    let mesh = read_mesh(&corpus_dir().join("fandisk.off"), &ReadOptions::default())
        .unwrap()
        .mesh;
    for connectivity in Connectivity::ALL {
        for bits in [1, 8, 11, 16, 23, 30] {
            for level in [0, 6] {
                let options = EncodeOptions {
                    connectivity,
                    keep_order: true,
                    position_bits: Some(bits),
                    level,
                    ..EncodeOptions::default()
                };
                let bytes = encode(&mesh, &options).unwrap();
                let view = open(&bytes, &Limits::default()).unwrap();
                assert!(view.is_quantized());
                let back = view.to_mesh();
                let worst = assert_within_half_a_step(
                    &back.positions,
                    &mesh.positions,
                    bits,
                    &format!("{connectivity:?} {bits} bits level {level}"),
                );
                // The bound is tight: some coordinate is more than a third of a step off.
                if bits < 20 {
                    assert!(worst > 0.33, "{connectivity:?} {bits}: worst {worst}");
                }
                assert_eq!(back.triangles.len(), mesh.triangles.len());
                let exact = EncodeOptions {
                    position_bits: None,
                    ..options
                };
                if bits <= 16 {
                    assert!(bytes.len() < encode(&mesh, &exact).unwrap().len());
                }
            }
        }
    }
}

/// Every single-byte change and every truncation of a small container is an error, never a
/// panic.
#[test]
fn every_damaged_byte_is_rejected() {
    for (name, connectivity) in [
        ("tetrahedron.off", Connectivity::Lr),
        ("hedra_open.off", Connectivity::Lr),
        ("hedra_open.off", Connectivity::Edgebreaker),
        ("tetrahedron.off", Connectivity::Strips),
        ("hedra_open.off", Connectivity::Strips),
    ] {
        let mesh = read_mesh(&corpus_dir().join(name), &ReadOptions::default())
            .unwrap()
            .mesh;
        let bytes = encode(
            &mesh,
            &EncodeOptions {
                keep_order: true,
                connectivity,
                ..EncodeOptions::default()
            },
        )
        .unwrap();
        open(&bytes, &Limits::default()).unwrap();
        let mut damaged = bytes.clone();
        for at in 0..bytes.len() {
            for x in 1..=255u8 {
                damaged[at] = bytes[at] ^ x;
                assert!(
                    open(&damaged, &Limits::default()).is_err(),
                    "{name}: byte {at} ^ {x:#x} accepted"
                );
            }
            damaged[at] = bytes[at];
        }
        for len in 0..bytes.len() {
            assert!(
                open(&bytes[..len], &Limits::default()).is_err(),
                "{name}: truncated to {len} accepted"
            );
        }
        let mut longer = bytes.clone();
        longer.push(0);
        assert!(
            open(&longer, &Limits::default()).is_err(),
            "trailing byte accepted"
        );
    }
}

#[test]
fn errors_name_section_and_offset() {
    let mesh = generate::torus(4, 5);
    let bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let mut bad = bytes.clone();
    let last = bad.len() - 1;
    bad[last] ^= 1;
    let message = open(&bad, &Limits::default()).unwrap_err().to_string();
    assert!(
        message.contains("checksum mismatch") && message.contains("byte offset"),
        "{message}"
    );
    let mut newer = bytes.clone();
    newer[8] = 2;
    assert!(matches!(
        open(&newer, &Limits::default()),
        Err(Error::UnsupportedVersion { major: 2, .. })
    ));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(120))]

    #[test]
    fn generated_round_trips(around in 3u32..8, along in 3u32..8, holes in 0usize..6,
                             defects in 0usize..10, seed in any::<u64>(), keep_order in any::<bool>(),
                             attributes in any::<bool>()) {
        let mut rng = Rng::new(seed);
        let mut mesh = generate::torus(around, along);
        generate::append(&mut mesh, &generate::torus(3, 4));
        generate::punch_holes(&mut mesh, holes, &mut rng);
        generate::add_defects(&mut mesh, defects, &mut rng);
        if attributes {
            mesh = with_attributes(mesh, seed);
        }
        round_trip(&mesh, keep_order);
    }

    #[test]
    fn soup_round_trips(vertices in 1u32..20, triangles in 0u32..40, seed in any::<u64>()) {
        let mesh = generate::soup(vertices, triangles, &mut Rng::new(seed));
        round_trip(&mesh, true);
        round_trip(&mesh, false);
    }
}

/// Readers skip optional sections they do not know and reject required ones.
#[test]
fn unknown_sections() {
    use lrmesh::format::{Flags, Tag};
    use lrmesh::write::assemble;
    let mesh = generate::torus(4, 5);
    let bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let mut sections = sections_of(&bytes);
    assert_eq!(
        assemble(&sections),
        bytes,
        "reassembling gives the same bytes"
    );
    sections.insert(
        1,
        (Tag(*b"XTRA"), Flags::NONE, b"later minor versions".to_vec()),
    );
    let with_optional = assemble(&sections);
    let view = open(&with_optional, &Limits::default()).unwrap();
    assert_eq!(view.to_mesh().triangles.len(), mesh.triangles.len());
    sections[1].1 = Flags::REQUIRED;
    let with_required = assemble(&sections);
    assert!(matches!(
        open(&with_required, &Limits::default()),
        Err(Error::UnknownRequiredSection { index: 1, .. })
    ));
}

/// An Edgebreaker stream that decodes to a degenerate triangle (one byte changed from a real
/// encoding, found while writing spec/EDGEBREAKER.md) is not a valid container.
#[test]
fn edgebreaker_stream_decoding_to_a_degenerate_triangle_is_rejected() {
    use lrmesh::format::{Flags, Tag};
    use lrmesh::write::assemble;
    let mesh = read_mesh(
        &corpus_dir().join("hedra_open.off"),
        &ReadOptions::default(),
    )
    .unwrap()
    .mesh;
    let options = EncodeOptions {
        connectivity: Connectivity::Edgebreaker,
        ..EncodeOptions::default()
    };
    let bytes = encode(&mesh, &options).unwrap();
    let mut sections = sections_of(&bytes);
    let ebrk = sections.iter_mut().find(|s| s.0 == Tag::EBRK).unwrap();
    assert_eq!(ebrk.1, Flags::REQUIRED);
    let forged = [0xeb, 0x01, 0x06, 0x00, 0x06, 0x02, 0x86, 0xa0, 0x2a];
    let decoded = lrmesh::edgebreaker::decode(&forged, &Default::default()).unwrap();
    assert!(decoded
        .triangles
        .iter()
        .any(|t| t[0] == t[1] || t[1] == t[2] || t[0] == t[2]));
    ebrk.2 = forged.to_vec();
    let message = open(&assemble(&sections), &Limits::default())
        .unwrap_err()
        .to_string();
    assert!(
        message.contains("EBRK") && message.contains("degenerate"),
        "{message}"
    );
}

/// A small container claiming billions of vertices or triangles fails at once with an error,
/// before anything is allocated for them.
#[test]
fn hostile_counts_fail_fast() {
    use lrmesh::format::Tag;
    use lrmesh::write::assemble;
    let mesh = generate::torus(3, 4);
    let bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let sections = sections_of(&bytes);
    let mut hostile = Vec::new();
    for (tag, at, value) in [
        (Tag::STRP, 0, 3_000_000_000),  // vertices
        (Tag::STRP, 4, 1_000_000_000),  // strip entries
        (Tag::STRP, 4, 3_000_000_000),  // strip entries
        (Tag::MESH, 0, u32::MAX - 2),   // vertices
        (Tag::MESH, 8, u32::MAX - 2),   // triangles
        (Tag::MESH, 12, u32::MAX - 2),  // kept triangles
        (Tag::LRTB, 0, 3_000_000_000),  // m
        (Tag::LRTB, 4, 3_000_000_000),  // ring vertices
        (Tag::LRTB, 12, 3_000_000_000), // T0 triangles
        (Tag::LRTB, 16, 1_000_000_000), // VO* records
    ] {
        hostile.push((tag, at, value));
    }
    let strips = encode(
        &mesh,
        &EncodeOptions {
            connectivity: Connectivity::Strips,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    let strips_sections = sections_of(&strips);
    for (tag, at, value) in hostile {
        let mut forged = if tag == Tag::STRP {
            strips_sections.clone()
        } else {
            sections.clone()
        };
        let section = forged.iter_mut().find(|s| s.0 == tag).unwrap();
        section.2[at..at + 4].copy_from_slice(&value.to_le_bytes());
        let bytes = assemble(&forged);
        assert!(bytes.len() < 4096);
        let error = open(&bytes, &Limits::default()).unwrap_err();
        assert!(error.to_string().contains("byte offset"), "{error}");
    }
}

/// Found by the round-trip fuzz target: with duplicate positions, a decoded triangle is a
/// rotation of the input one that a comparison starting "at the smallest entry" took for a
/// different triangle. (The library was right; the comparison now takes the smallest rotation.)
#[test]
fn duplicate_positions_round_trip_up_to_rotation() {
    let (r, p, q) = (
        [89.5, -109.5, 121.7],
        [121.7f32, 121.7, 121.7],
        [121.7, 121.7, -105.8],
    );
    let mut triangles = vec![[3, 3, 3], [3, 3, 3], [3, 4, 2], [3, 2, 0]];
    triangles.extend(std::iter::repeat_n([0, 0, 0], 5));
    let mesh = Mesh::new(vec![r, p, q, p, p], triangles);
    assert_eq!(
        rotated([p, q, p].map(|x| x.map(f32::to_bits))),
        rotated([p, p, q].map(|x| x.map(f32::to_bits)))
    );
    round_trip(&mesh, false);
    round_trip(&mesh, true);
}

/// `summarize` (what `lrmesh info` prints) reads the connectivity and positions by their
/// headers alone: damage inside their data leaves it answering as for the intact file, where
/// `open` refuses the file; damage to a header it reads is an error naming the section.
#[test]
fn summarize_reads_headers_only() {
    let limits = Limits::default();
    let mesh = generate::irregular_torus(4000, 3);
    for connectivity in Connectivity::ALL {
        let options = EncodeOptions {
            connectivity,
            ..EncodeOptions::default()
        };
        let bytes = encode(&mesh, &options).unwrap();
        let intact = open(&bytes, &limits).unwrap().summary();
        assert_eq!(lrmesh::read::summarize(&bytes, &limits).unwrap(), intact);
        let data = lrmesh::read::Sections::parse(&bytes, &limits)
            .unwrap()
            .sections
            .iter()
            .find(|s| s.tag.name() != "GEOM" && s.flags.is_required() && s.bytes.len() > 64)
            .map(|s| {
                // The header's vertex count: the first word, but for a compact `ZIPR`'s.
                let count = match s.tag.name().as_str() {
                    "ZIPR" => lrmesh::format::layout::ZiprHeader::read(s.bytes).count_offset(0),
                    _ => 0,
                };
                (s.offset as usize, s.bytes.len(), count)
            })
            .unwrap();
        // A byte in the middle of the connectivity's data, then in its header.
        let mut damaged = bytes.clone();
        damaged[data.0 + data.1 / 2] ^= 0x5A;
        assert!(open(&damaged, &limits).is_err(), "{connectivity:?}");
        assert_eq!(
            lrmesh::read::summarize(&damaged, &limits).unwrap(),
            intact,
            "{connectivity:?}"
        );
        if connectivity != Connectivity::Edgebreaker {
            let mut damaged = bytes.clone();
            damaged[data.0 + data.2] ^= 0x01; // the header's vertex count
            let e = lrmesh::read::summarize(&damaged, &limits).unwrap_err();
            assert!(matches!(e, Error::Format(_)), "{connectivity:?}: {e}");
        }
    }
}

/// `encode_owned` (which frees the triangles once the corner table holds them) writes the
/// bytes `encode` writes, with attributes (which keep them) and without, for every kind.
#[test]
fn encode_owned_writes_the_same_bytes() {
    let plain = generate::irregular_torus(3000, 5);
    let mut attributed = plain.clone();
    let normals: Vec<[f32; 3]> = (0..plain.positions.len())
        .map(|i| [(i % 7) as f32, 1.0, 0.5])
        .collect();
    attributed
        .attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    for mesh in [plain, attributed] {
        for connectivity in Connectivity::ALL {
            let options = EncodeOptions {
                connectivity,
                ..EncodeOptions::default()
            };
            let want = encode(&mesh, &options).unwrap();
            let got = lrmesh::write::encode_owned(mesh.clone(), &options).unwrap();
            assert!(got == want, "{connectivity:?}");
        }
    }
}
