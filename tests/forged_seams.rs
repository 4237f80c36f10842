//! Forged containers for coded seams (`ATTR` seam encoding 1, FORMAT.md §3.9.3,
//! spec/GEOMETRY.md §8: [V49]). How a rule is broken and what the reader must report:
//! `tests/common/forge.rs`. The stream is range coded, so a damaged stream is found by
//! changing its bytes one at a time: the tests fail if no change reaches a check.

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

/// A torus with per-corner texture coordinates: a seam around every seventh triangle, and
/// one where only a corner changes (every eleventh triangle's first corner).
fn torus() -> Mesh {
    let mut mesh = generate::torus(12, 8);
    let uv: Vec<[f32; 2]> = mesh
        .triangles
        .iter()
        .enumerate()
        .flat_map(|(t, tri)| {
            let shift = if t % 7 == 0 { 0.5 } else { 0.0 };
            let p = &mesh.positions;
            let mut uv = tri.map(|v| [p[v as usize][0] + shift, p[v as usize][1]]);
            if t % 11 == 0 {
                uv[0][1] += 0.25;
            }
            uv
        })
        .collect();
    let corners = (0..uv.len() as u32).collect();
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
    mesh
}

fn encoded_with(mesh: &Mesh, connectivity: Connectivity, quantized: bool) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity,
        texcoord_bits: quantized.then_some(10),
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// The Edgebreaker container of the torus: its one record has coded seams.
fn coded() -> (Vec<u8>, AttributeHeader) {
    let bytes = encoded_with(&torus(), Connectivity::Edgebreaker, false);
    let h = AttributeHeader::parse(&payload(&bytes, Tag::ATTR)[4..]);
    assert_eq!((h.seam_encoding(), h.value_encoding()), (1, 0));
    (bytes, h)
}

/// Where the seam part of the raw record (the first, at offset 4 of `ATTR`) starts: `n`.
fn seam_part(bytes: &[u8], h: &AttributeHeader) -> usize {
    let v = u32::from_le_bytes(payload(bytes, Tag::MESH)[..4].try_into().unwrap());
    4 + 32 + h.name_len as usize + (v + h.extra) as usize * 8
}

/// The message of the [V49] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v49_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 49, "ATTR")
}

/// [V49] Coded seams and the tables they stand for give every corner the same value; the
/// record with tables is longer.
#[test]
fn v49_coded_seams_mean_the_tables() {
    let (bytes, h) = coded();
    assert!(h.flagged > 0 && h.extra > 0);
    let tables = with_seam_tables(&bytes, 0, 4, seam_part(&bytes, &h), None);
    assert!(tables.len() > bytes.len());
    let (a, b) = (
        open(&bytes, &Limits::default()).unwrap().to_mesh(),
        open(&tables, &Limits::default()).unwrap().to_mesh(),
    );
    assert_eq!(a, b);
    // Every triangle comes back with its positions and texture coordinates at its corners
    // (triangles and vertices may be in another order, a triangle rotated).
    let corners = |m: &Mesh| {
        let mut out: Vec<Vec<(Vec<u32>, Vec<u8>)>> = m
            .triangles
            .iter()
            .enumerate()
            .map(|(t, &tri)| {
                let mut c: Vec<_> = (0..3)
                    .map(|k| {
                        let p = m.positions[tri[k] as usize].map(f32::to_bits).to_vec();
                        (p, m.attributes[0].corner_bytes(t, k, tri))
                    })
                    .collect();
                let first = (0..3).min_by_key(|&k| c[k].clone()).unwrap();
                c.rotate_left(first);
                c
            })
            .collect();
        out.sort();
        out
    };
    assert_eq!(corners(&a), corners(&torus()));
}

/// [V49] The seam encoding is 0 or 1, and 1 appears only with the Edgebreaker connectivity.
#[test]
fn v49_coded_seams_need_edgebreaker() {
    let (bytes, _) = coded();
    let m = v49_message(&forge(&bytes, Tag::ATTR, |p| p[4 + 21] = 2)).unwrap();
    assert!(m.contains("unknown seam encoding 2"), "{m}");
    // The Edgebreaker record in the LR container, with the LR container's slot count.
    let record = payload(&bytes, Tag::ATTR)[4..].to_vec();
    let lr = encoded_with(&torus(), Connectivity::Lr, false);
    let slots = AttributeHeader::parse(&payload(&lr, Tag::ATTR)[4..]).slots;
    let bad = forge(&lr, Tag::ATTR, |p| {
        p.truncate(4);
        p.extend_from_slice(&record);
        p[4 + 16..4 + 20].copy_from_slice(&slots.to_le_bytes());
    });
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("need the Edgebreaker connectivity"), "{m}");
}

/// [V49] `F > 0`, and the seam part lies within the section.
#[test]
fn v49_seam_part_within_the_section() {
    let (bytes, h) = coded();
    let part = seam_part(&bytes, &h);
    let bad = forge(&bytes, Tag::ATTR, |p| {
        for at in [
            4 + 5,
            4 + 8,
            4 + 9,
            4 + 10,
            4 + 11,
            4 + 12,
            4 + 13,
            4 + 14,
            4 + 15,
        ] {
            p[at] = 0;
        }
        // No extra values: the values part shrinks to V.
        p.drain(part - 8 * h.extra as usize..part);
    });
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("no flagged triangle"), "{m}");
    let n = get(&payload(&bytes, Tag::ATTR), part);
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, part, n + 1));
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("section has"), "{m}");
    let bad = forge(&bytes, Tag::ATTR, |p| p.truncate(part + 2));
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("no room for the coded seams' length"), "{m}");
}

/// [V49] Exactly `E` extra values and `F` flagged slots.
#[test]
fn v49_counts_agree_with_the_header() {
    let (bytes, h) = coded();
    let part = seam_part(&bytes, &h);
    // One extra value fewer (and its bytes gone): the decoder needs one more.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        put(p, 4 + 8, h.extra - 1);
        p.drain(part - 8..part);
    });
    let m = v49_message(&bad).unwrap();
    assert!(
        m.contains(&format!("more than {} extra values", h.extra - 1)),
        "{m}"
    );
    // One more, with eight bytes of value: the stream gives one fewer.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        put(p, 4 + 8, h.extra + 1);
        p.splice(part..part, [0u8; 8]);
    });
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("extra values coded, the header says"), "{m}");
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, 4 + 12, h.flagged + 1));
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("the coded seams give"), "{m}");
}

/// [V49] Damaged streams: no value a vertex does not have, no overrun.
#[test]
fn v49_damaged_streams_are_refused() {
    let (bytes, h) = coded();
    let part = seam_part(&bytes, &h);
    let n = get(&payload(&bytes, Tag::ATTR), part) as usize;
    let mut seen = BTreeSet::new();
    for i in part + 4..part + 4 + n {
        for x in [0x01u8, 0x10, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::ATTR, |p| p[i] ^= x);
            if let Some(m) = v49_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    for m in ["extra values", "the coded seams give"] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p.truncate(part + 4);
        put(p, part, 0);
    });
    let m = v49_message(&bad).unwrap();
    assert!(m.contains("the stream ends within"), "{m}");
}

/// Quantized (predicted) values read their corners' values from the coded seams too; the
/// other kinds keep the tables.
#[test]
fn coded_seams_with_predicted_values_and_tables_elsewhere() {
    let mesh = torus();
    for connectivity in [
        Connectivity::Edgebreaker,
        Connectivity::Lr,
        Connectivity::Strips,
    ] {
        let bytes = encoded_with(&mesh, connectivity, true);
        let h = AttributeHeader::parse(&payload(&bytes, Tag::ATTR)[4..]);
        let edgebreaker = connectivity == Connectivity::Edgebreaker;
        assert_eq!(h.seam_encoding(), u8::from(edgebreaker));
        assert_eq!(h.value_encoding(), if edgebreaker { 2 } else { 1 });
        let back = open(&bytes, &Limits::default()).unwrap().to_mesh();
        assert_eq!(back.triangles.len(), mesh.triangles.len());
    }
}

/// The fuzz target `container_forged` starts from containers with coded seams (and with
/// tables): its byte edits reach the decoder of seam encoding 1.
#[test]
fn the_fuzz_target_reaches_coded_seams() {
    let mut encodings = BTreeSet::new();
    for choice in 0..=255u8 {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let file = open(&bytes, &Limits::default()).unwrap();
        encodings.extend(
            file.attributes()
                .iter()
                .filter(|a| a.flagged_triangles() > 0)
                .map(|a| a.seam_encoding()),
        );
    }
    assert_eq!(encodings, BTreeSet::from([0, 1]));
}
