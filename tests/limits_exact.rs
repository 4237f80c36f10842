//! Limits and ranges at their exact edge: what a bound allows is accepted and one step past
//! it is refused (the reader's `>` is not a `>=`).

use lrmesh::edgebreaker::{decode, encode, Limits as EbLimits};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode as encode_container, EncodeOptions};
use lrmesh::{generate, CornerTable, Error, Mesh};

/// An Edgebreaker stream declaring exactly the limits decodes; one below refuses.
#[test]
fn edgebreaker_counts_at_the_limit() {
    let mesh = generate::torus(5, 4);
    let stream = encode(&CornerTable::from_mesh(&mesh).unwrap())
        .unwrap()
        .bytes;
    let (nv, nt) = (mesh.positions.len() as u64, mesh.triangles.len() as u64);
    let exact = EbLimits {
        max_triangles: nt,
        max_vertices: nv,
    };
    assert_eq!(decode(&stream, &exact).unwrap().triangles.len() as u64, nt);
    for tight in [
        EbLimits {
            max_triangles: nt - 1,
            ..exact
        },
        EbLimits {
            max_vertices: nv - 1,
            ..exact
        },
    ] {
        assert!(matches!(decode(&stream, &tight), Err(Error::Parse(_))));
    }
    // Every vertex unreferenced (no triangle): the count may equal the vertex count.
    let lonely = encode(&CornerTable::build(3, &[]).unwrap()).unwrap().bytes;
    let decoded = decode(&lonely, &EbLimits::default()).unwrap();
    assert_eq!((decoded.vertex_count, decoded.triangles.len()), (3, 0));
}

/// A `META` section exactly as large as the limit is read; one byte less of limit refuses.
#[test]
fn metadata_at_the_limit() {
    let bytes = encode_container(&generate::torus(3, 3), &EncodeOptions::default()).unwrap();
    let meta = open(&bytes, &Limits::default())
        .unwrap()
        .sections
        .section(lrmesh::format::Tag::META)
        .unwrap()
        .bytes
        .len() as u64;
    let exact = Limits {
        max_metadata_bytes: meta,
        ..Limits::default()
    };
    assert!(open(&bytes, &exact).unwrap().metadata.is_some());
    let tight = Limits {
        max_metadata_bytes: meta - 1,
        ..Limits::default()
    };
    assert!(matches!(
        open(&bytes, &tight),
        Err(Error::LimitExceeded { .. })
    ));
}

/// Quantized positions of a flat mesh: a bounding box with `lo = hi` on an axis is valid
/// ([V13] refuses only `lo > hi`), and the flat coordinate decodes exactly.
#[test]
fn quantized_flat_box_is_valid() {
    let mesh = Mesh::new(
        vec![
            [0.0, 0.0, 2.5],
            [1.0, 0.0, 2.5],
            [0.0, 1.0, 2.5],
            [1.0, 1.0, 2.5],
        ],
        vec![[0, 1, 2], [2, 1, 3]],
    );
    let options = EncodeOptions {
        position_bits: Some(16),
        keep_order: true,
        ..EncodeOptions::default()
    };
    let bytes = encode_container(&mesh, &options).unwrap();
    let back = open(&bytes, &Limits::default()).unwrap().to_mesh();
    assert!(back.positions.iter().all(|p| p[2] == 2.5));
    assert_eq!(back.positions, mesh.positions);
}

/// An Edgebreaker stream can decode to a triangle that repeats a vertex; a container
/// refuses it ([V27]), wherever in the triangle the repeat is. The streams are found by
/// changing one byte of real encodings at a time, so the test fails if none exists any more.
#[test]
fn edgebreaker_degenerate_triangles_are_refused() {
    use lrmesh::format::Tag;
    let mut found = [false; 3];
    for name in [
        "hedra_open.off",
        "tetrahedron.off",
        "icosahedron.off",
        "cube_quad.off",
        "torus_quad.off",
    ] {
        let mesh = lrmesh::load(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("corpus/meshes")
                .join(name),
        )
        .unwrap();
        let options = EncodeOptions {
            connectivity: lrmesh::write::Connectivity::Edgebreaker,
            ..EncodeOptions::default()
        };
        let bytes = encode_container(&mesh, &options).unwrap();
        let file = open(&bytes, &Limits::default()).unwrap();
        let sections: Vec<_> = file
            .sections
            .sections
            .iter()
            .map(|s| (s.tag, s.flags, s.bytes.to_vec()))
            .collect();
        let index = sections.iter().position(|s| s.0 == Tag::EBRK).unwrap();
        let stream = sections[index].2.clone();
        let m = file.connectivity_vertex_count();
        for at in 2..stream.len() {
            for value in 0..=255u8 {
                let mut forged = stream.clone();
                forged[at] = value;
                let Ok(decoded) = decode(&forged, &EbLimits::default()) else {
                    continue;
                };
                let patterns = |t: &[u32; 3]| [t[0] == t[1], t[1] == t[2], t[0] == t[2]];
                let Some(t) = decoded
                    .triangles
                    .iter()
                    .find(|t| patterns(t).contains(&true))
                else {
                    continue;
                };
                if decoded.vertex_count != m {
                    continue;
                }
                let p = patterns(t);
                for k in 0..3 {
                    found[k] |= p[k];
                }
                let mut with = sections.clone();
                with[index].2 = forged;
                match open(&lrmesh::write::assemble(&with), &Limits::default()) {
                    Err(Error::Format(e)) => {
                        assert_eq!(e.rule, lrmesh::Rule(27), "{e}");
                    }
                    other => panic!("{name}: byte {at} = {value}: {other:?}"),
                }
            }
        }
    }
    eprintln!("repeat patterns reached: {found:?}");
    assert!(
        found[0],
        "no stream decodes to a degenerate triangle any more"
    );
}

/// Sections at their smallest: a mesh without vertices (GEOM of its 8-byte header alone, a
/// STRP section of its header alone) and one with vertices but no triangle, in every kind.
#[test]
fn smallest_sections_in_every_kind() {
    use lrmesh::write::Connectivity;
    let lonely = Mesh::new(vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]], Vec::new());
    for mesh in [Mesh::default(), lonely] {
        for connectivity in Connectivity::ALL {
            let options = EncodeOptions {
                connectivity,
                keep_order: true,
                ..EncodeOptions::default()
            };
            let bytes = encode_container(&mesh, &options).unwrap();
            let back = open(&bytes, &Limits::default())
                .unwrap_or_else(|e| panic!("{connectivity:?}: {e}"))
                .to_mesh();
            assert_eq!(back, mesh, "{connectivity:?}");
        }
    }
}

/// Corner ids must fit 32 bits ([V15], [V33]): `8 m_r + 4 n0 < 2^32 − 1`, reported at `n0`
/// even when `m_r = 0` makes a product of the two terms vanish.
#[test]
fn corner_id_bound_with_no_ring() {
    use lrmesh::format::Tag;
    let mesh = generate::torus(3, 4);
    for (connectivity, tag, rule) in [
        (lrmesh::write::Connectivity::Lr, Tag::LRTB, 15),
        (lrmesh::write::Connectivity::LrCompact, Tag::LRBE, 33),
    ] {
        let options = EncodeOptions {
            connectivity,
            ..EncodeOptions::default()
        };
        let bytes = encode_container(&mesh, &options).unwrap();
        let file = open(&bytes, &Limits::default()).unwrap();
        let mut sections: Vec<_> = file
            .sections
            .sections
            .iter()
            .map(|s| (s.tag, s.flags, s.bytes.to_vec()))
            .collect();
        let offset = file.sections.section(tag).unwrap().offset;
        let payload = &mut sections.iter_mut().find(|s| s.0 == tag).unwrap().2;
        // m_r = 0 and R = 0 (consistent), n0 = 2^30: 4 n0 alone reaches 2^32.
        payload[4..8].copy_from_slice(&0u32.to_le_bytes());
        payload[8..12].copy_from_slice(&0u32.to_le_bytes());
        payload[12..16].copy_from_slice(&(1u32 << 30).to_le_bytes());
        match open(&lrmesh::write::assemble(&sections), &Limits::default()) {
            Err(Error::Format(e)) => {
                assert_eq!(
                    (e.rule, e.section.as_str(), e.offset),
                    (lrmesh::Rule(rule), tag.name().as_str(), offset + 12),
                    "{e}"
                );
            }
            other => panic!("{tag}: {other:?}"),
        }
    }
}
