//! Forged containers for predicted attribute values (`ATTR` value encoding 2, FORMAT.md
//! §3.9.2, spec/GEOMETRY.md §7: [V47]). How a rule is broken and what the reader must
//! report: `tests/common/forge.rs`. The streams are range coded, so a damaged stream is
//! found by changing its bytes one at a time: the tests fail if no change reaches a check.

mod common;

use std::collections::BTreeSet;

use common::forge::*;
use lrmesh::format::attributes::AttributeHeader;
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::Mesh;

/// A torus with per-corner texture coordinates (a seam every seventh triangle) and, last,
/// per-vertex normals: the normals' stream runs to the end of `ATTR`.
fn torus() -> Mesh {
    let mut mesh = generate::torus(12, 8);
    let uv: Vec<[f32; 2]> = mesh
        .triangles
        .iter()
        .enumerate()
        .flat_map(|(t, tri)| {
            let shift = if t % 7 == 0 { 0.5 } else { 0.0 };
            let p = &mesh.positions;
            tri.map(|v| [p[v as usize][0] + shift, p[v as usize][1]])
        })
        .collect();
    let corners = (0..uv.len() as u32).collect();
    // The torus's own normals: away from the circle through its tube's centres.
    let radius = |p: &[f32; 3]| (p[0] * p[0] + p[1] * p[1]).sqrt();
    let (lo, hi) = mesh
        .positions
        .iter()
        .map(radius)
        .fold((f32::MAX, 0f32), |(l, h), r| (l.min(r), h.max(r)));
    let big = (lo + hi) / 2.0;
    let normals: Vec<[f32; 3]> = mesh
        .positions
        .iter()
        .map(|p| {
            let r = radius(p);
            [p[0] - big * p[0] / r, p[1] - big * p[1] / r, p[2]]
        })
        .collect();
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
    mesh.attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    mesh
}

fn options(connectivity: Connectivity) -> EncodeOptions {
    EncodeOptions {
        connectivity,
        position_bits: Some(12),
        normal_bits: Some(8),
        texcoord_bits: Some(10),
        ..EncodeOptions::default()
    }
}

fn encoded_with(mesh: &Mesh, connectivity: Connectivity) -> Vec<u8> {
    let bytes = encode(mesh, &options(connectivity)).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// Every record of the `ATTR` payload: (offset, header).
fn records(bytes: &[u8]) -> Vec<(usize, AttributeHeader)> {
    let p = payload(bytes, Tag::ATTR);
    let count = u32::from_le_bytes(p[..4].try_into().unwrap());
    let file = open(bytes, &Limits::default()).unwrap();
    let mut at = 4;
    (0..count as usize)
        .map(|i| {
            let h = AttributeHeader::parse(&p[at..]);
            let r = (at, h);
            at += file.attributes()[i].stored_bytes() as usize;
            r
        })
        .collect()
}

/// Where the stream of the predicted record at `at` starts (after `b`, `lo` and `size` for
/// a grid, and `n`), and `n`.
fn stream_of(bytes: &[u8], at: usize, h: &AttributeHeader) -> (usize, usize) {
    let start = at + 32 + h.name_len as usize;
    let header = if h.semantic == 1 {
        1
    } else {
        5 + 4 * h.components as usize
    };
    let p = payload(bytes, Tag::ATTR);
    let n = u32::from_le_bytes(p[start + header..start + header + 4].try_into().unwrap());
    (start + header + 4, n as usize)
}

/// The message of the [V47] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v47_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 47, "ATTR")
}

/// [V47] Both records of the torus are predicted; predicted values appear only with the
/// Edgebreaker connectivity.
#[test]
fn v47_predicted_values_need_edgebreaker() {
    let mesh = torus();
    let eb = encoded_with(&mesh, Connectivity::Edgebreaker);
    let recs = records(&eb);
    assert_eq!(
        recs.iter()
            .map(|r| r.1.value_encoding())
            .collect::<Vec<_>>(),
        [2, 2]
    );
    let (normal_at, _) = recs[1];
    let normals = payload(&eb, Tag::ATTR)[normal_at..].to_vec();
    let lr = encoded_with(&mesh, Connectivity::Lr);
    let lr_recs = records(&lr);
    let (lr_normal_at, lr_h) = lr_recs[1];
    assert_eq!(lr_h.value_encoding(), 1);
    // The Edgebreaker record, with the LR container's slot count, in place of the LR one.
    let bad = forge(&lr, Tag::ATTR, |p| {
        p.truncate(lr_normal_at);
        p.extend_from_slice(&normals);
        p[lr_normal_at + 16..lr_normal_at + 20].copy_from_slice(&lr_h.slots.to_le_bytes());
    });
    let m = v47_message(&bad).unwrap();
    assert!(m.contains("need the Edgebreaker connectivity"), "{m}");
}

/// [V47] The stream's length `n` lies within the section.
#[test]
fn v47_stream_within_the_section() {
    let bytes = encoded_with(&torus(), Connectivity::Edgebreaker);
    let (at, h) = records(&bytes)[1];
    let (stream, n) = stream_of(&bytes, at, &h);
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[stream - 4..stream].copy_from_slice(&(n as u32 + 1).to_le_bytes())
    });
    let m = v47_message(&bad).unwrap();
    assert!(m.contains("section has"), "{m}");
    let bad = forge(&bytes, Tag::ATTR, |p| p.truncate(stream - 2));
    let m = v47_message(&bad).unwrap();
    assert!(
        m.contains("no room for the predicted values' length"),
        "{m}"
    );
}

/// [V47] Damaged streams: no class above `b`, no integer outside `0 ..= 2^b − 1`, no overrun.
#[test]
fn v47_damaged_streams_are_refused() {
    let bytes = encoded_with(&torus(), Connectivity::Edgebreaker);
    let (at, h) = records(&bytes)[1];
    let (stream, n) = stream_of(&bytes, at, &h);
    let mut seen = BTreeSet::new();
    for i in stream..stream + n {
        for x in [0x01u8, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::ATTR, |p| p[i] ^= x);
            if let Some(m) = v47_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    for m in ["a residual longer than 8 bits", "outside 0 ..= 255"] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    // A stream cut short (with `n` and the section cut alike) ends before its last value.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p.truncate(stream);
        p[stream - 4..stream].copy_from_slice(&0u32.to_le_bytes());
    });
    let m = v47_message(&bad).unwrap();
    assert!(m.contains("the stream ends before value"), "{m}");
}

/// [V47] At most `3F` extra values: each is the value of some flagged corner, and the
/// bound keeps a forged `E` from sizing the decoder's arrays. (Coded seams check `E`
/// exactly, [V49]: the texture coordinates' record gets the seam tables of encoding 0.)
#[test]
fn v47_extra_values_bounded_by_the_flagged_corners() {
    let coded = encoded_with(&torus(), Connectivity::Edgebreaker);
    let (at, h) = records(&coded)[0];
    assert_eq!((h.value_encoding(), h.seam_encoding()), (2, 1));
    let (stream, n) = stream_of(&coded, at, &h);
    let tables = with_seam_tables(&coded, 0, at, stream + n, None);
    open(&tables, &Limits::default()).unwrap();
    assert!(h.flagged > 0 && h.extra <= 3 * h.flagged);
    // One extra value more than the flagged corners (V40 and V41 still hold).
    let bad = with_seam_tables(&coded, 0, at, stream + n, Some(3 * h.flagged + 1));
    let m = v47_message(&bad).unwrap();
    assert!(m.contains("more than the"), "{m}");
}

/// [V47] The normal predictor (byte 22): 0, or 1 for normals; [V40] 0 without predicted
/// values.
#[test]
fn v47_normal_predictor() {
    let mesh = torus();
    let eb = encoded_with(&mesh, Connectivity::Edgebreaker);
    let at = section_at(&eb, Tag::ATTR);
    let recs = records(&eb);
    let ((uv_at, _), (normal_at, normal)) = (recs[0], recs[1]);
    assert_eq!(
        normal.normal_predictor(),
        0,
        "this torus's normals follow its surface"
    );
    let bad = forge(&eb, Tag::ATTR, |p| p[normal_at + 22] = 2);
    breaks(
        &bad,
        47,
        "ATTR",
        at + normal_at as u64 + 22,
        "normal predictor 2",
    );
    let bad = forge(&eb, Tag::ATTR, |p| p[uv_at + 22] = 1);
    breaks(
        &bad,
        47,
        "ATTR",
        at + uv_at as u64 + 22,
        "normal predictor 1",
    );
    let lr = encoded_with(&mesh, Connectivity::Lr);
    let (lr_normal_at, _) = records(&lr)[1];
    let bad = forge(&lr, Tag::ATTR, |p| p[lr_normal_at + 22] = 1);
    breaks(
        &bad,
        40,
        "ATTR",
        section_at(&lr, Tag::ATTR) + lr_normal_at as u64 + 22,
        "without predicted values",
    );
    // The byte is read: the stream of predictor 0 read with predictor 1 is refused or
    // gives other normals.
    let flipped = forge(&eb, Tag::ATTR, |p| p[normal_at + 22] = 1);
    if v47_message(&flipped).is_none() {
        let normals = |b: &[u8]| open(b, &Limits::default()).unwrap().to_mesh().attributes;
        assert_ne!(normals(&flipped)[1], normals(&eb)[1]);
    }
}

/// Normals on a coarse grid are predicted from their neighbours alone (normal predictor 1,
/// container 1.3) and decode to the normals of the packed record of level 0.
#[test]
fn coarse_normals_are_predicted_from_their_neighbours() {
    let mesh = torus();
    let mut coarse = options(Connectivity::Edgebreaker);
    // On a grid of 4 levels per axis the torus's triangles no longer face where its
    // normals point.
    coarse.position_bits = Some(2);
    let bytes = encode(&mesh, &coarse).unwrap();
    let (_, normals) = records(&bytes)[1];
    assert_eq!(
        (normals.value_encoding(), normals.normal_predictor()),
        (2, 1)
    );
    assert_eq!(bytes[10], 3, "minor version 3");
    let mut packed = coarse.clone();
    packed.level = 0;
    let a = open(&encode(&mesh, &packed).unwrap(), &Limits::default())
        .unwrap()
        .to_mesh();
    let b = open(&bytes, &Limits::default()).unwrap().to_mesh();
    for (t, &tri) in a.triangles.iter().enumerate() {
        for k in 0..3 {
            let (x, y) = (&a.attributes[1], &b.attributes[1]);
            assert_eq!(x.corner_bytes(t, k, tri), y.corner_bytes(t, k, tri));
        }
    }
}

/// `format::attributes::record_len` walks records of every value and seam encoding: the
/// records of these containers tile their `ATTR` payloads.
#[test]
fn record_lengths_tile_the_payload() {
    let mesh = torus();
    for connectivity in [Connectivity::Edgebreaker, Connectivity::Lr] {
        for level in [0, 6] {
            let mut o = options(connectivity);
            o.level = level;
            let bytes = encode(&mesh, &o).unwrap();
            let file = open(&bytes, &Limits::default()).unwrap();
            let p = payload(&bytes, Tag::ATTR);
            let mut at = 4;
            for a in file.attributes() {
                let len = lrmesh::format::attributes::record_len(
                    &p,
                    at,
                    file.connectivity_vertex_count(),
                )
                .expect("a record length");
                assert_eq!(len as u64, a.stored_bytes());
                at += len;
            }
            assert_eq!(at, p.len());
        }
    }
}

/// What the tests above forge from decodes to the packed values of level 0.
#[test]
fn the_files_forged_from_decode_right() {
    let mesh = torus();
    let mut packed = options(Connectivity::Edgebreaker);
    packed.level = 0;
    let a = encode(&mesh, &packed).unwrap();
    let b = encoded_with(&mesh, Connectivity::Edgebreaker);
    let (a, b) = (
        open(&a, &Limits::default()).unwrap().to_mesh(),
        open(&b, &Limits::default()).unwrap().to_mesh(),
    );
    assert_eq!(a.triangles, b.triangles);
    // The same value at every corner (the values may be listed in another order: level 6
    // codes the seams, GEOMETRY.md §8).
    for (x, y) in a.attributes.iter().zip(&b.attributes) {
        for (t, &tri) in a.triangles.iter().enumerate() {
            for k in 0..3 {
                assert_eq!(x.corner_bytes(t, k, tri), y.corner_bytes(t, k, tri));
            }
        }
    }
}

/// The fuzz target `container_forged` starts from containers with predicted values (and
/// from packed ones): its byte edits reach the decoder of encoding 2.
#[test]
fn the_fuzz_target_reaches_predicted_values() {
    let mut encodings = BTreeSet::new();
    for choice in 0..=255u8 {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let file = open(&bytes, &Limits::default()).unwrap();
        encodings.extend(file.attributes().iter().map(|a| a.value_encoding()));
    }
    assert_eq!(encodings, BTreeSet::from([0, 1, 2]));
}
