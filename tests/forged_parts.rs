//! Forged containers for the runs and the coded labels of `PART` (FORMAT.md §3.10.1,
//! §3.10.2: [V48], [V51]). How a rule is
//! broken and what the reader must report: `tests/common/forge.rs`. The runs are range
//! coded, so a damaged stream is found by changing its bytes one at a time: the tests fail
//! if no change reaches a check.

mod common;

use std::collections::BTreeSet;

use common::forge::*;
use lrmesh::format::labels::{CODED, JSON};
use lrmesh::format::parts::{PartsHeader, HEADER_LEN, RUNS};
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::mesh::{Part, Parts};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::Mesh;

/// A torus whose triangles form three parts, in bands of the input order.
fn torus() -> Mesh {
    let mut mesh = generate::torus(12, 8);
    let mut parts = Parts::default();
    let n = mesh.triangles.len();
    for t in 0..n {
        let i = parts.intern(Part {
            group: Some(format!("band{}", 3 * t / n)),
            ..Part::default()
        });
        parts.of_triangle.push(i);
    }
    mesh.parts = Some(parts);
    mesh
}

fn edgebreaker(level: u8) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity: Connectivity::Edgebreaker,
        level,
        ..EncodeOptions::default()
    };
    let bytes = encode(&torus(), &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// Where the runs start in `PART`, and their length `n`.
fn runs(bytes: &[u8]) -> (usize, usize) {
    let p = payload(bytes, Tag::PART);
    let h = PartsHeader::parse(&p);
    assert_eq!(h.encoding, RUNS);
    let at = HEADER_LEN + h.json_len as usize;
    (at + 4, get(&p, at) as usize)
}

/// The message of the [V48] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v48_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 48, "PART")
}

/// [V48] The header: a known index encoding, the reserved bytes 0, and with runs the
/// section exactly as long as `n` says.
#[test]
fn v48_header_and_length() {
    let bytes = edgebreaker(6);
    let at = section_at(&bytes, Tag::PART);
    let (stream, n) = runs(&bytes);
    breaks(
        &forge(&bytes, Tag::PART, |p| p[9] = 2),
        48,
        "PART",
        at + 9,
        "unknown index encoding 2",
    );
    breaks(
        &forge(&bytes, Tag::PART, |p| p[11] = 1),
        48,
        "PART",
        at + 11,
        "reserved",
    );
    breaks(
        &forge(&bytes, Tag::PART, |p| p.push(0)),
        48,
        "PART",
        at,
        "counts call for",
    );
    breaks(
        &forge(&bytes, Tag::PART, |p| put(p, stream - 4, n as u32 + 1)),
        48,
        "PART",
        at,
        "counts call for",
    );
    breaks(
        &forge(&bytes, Tag::PART, |p| p.truncate(stream - 2)),
        48,
        "PART",
        at + stream as u64 - 4,
        "truncated",
    );
}

/// [V48] Damaged runs: a part not below `P`, a run past the last slot, an overrun.
#[test]
fn v48_damaged_runs_are_refused() {
    let bytes = edgebreaker(6);
    let (stream, n) = runs(&bytes);
    let mut seen = BTreeSet::new();
    for i in stream..stream + n {
        for x in [0x01u8, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::PART, |p| p[i] ^= x);
            if let Some(m) = v48_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    for m in ["a part not below 3", "a run past the last of"] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    let bad = forge(&bytes, Tag::PART, |p| {
        p.truncate(stream);
        put(p, stream - 4, 0);
    });
    let m = v48_message(&bad).unwrap();
    assert!(m.contains("the stream ends before slot"), "{m}");
}

/// The message of the [V51] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v51_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 51, "PART")
}

/// [V51] A known labels encoding, and no more parts than the coded labels may decode to.
#[test]
fn v51_labels_encoding_and_part_count() {
    let bytes = edgebreaker(6);
    let at = section_at(&bytes, Tag::PART);
    let p = payload(&bytes, Tag::PART);
    let h = PartsHeader::parse(&p);
    assert_eq!(h.labels, CODED);
    breaks(
        &forge(&bytes, Tag::PART, |p| p[10] = 2),
        51,
        "PART",
        at + 10,
        "unknown labels encoding 2",
    );
    // A million parts (20 bits per index; the runs do not depend on it) from a stream of
    // a few bytes: refused before anything is allocated for them.
    let bad = forge(&bytes, Tag::PART, |p| {
        put(p, 0, 1_000_000);
        p[8] = 20;
    });
    breaks(&bad, 51, "PART", at + 16, "1000000 parts exceed the");
}

/// [V51] Damaged coded labels: a reference to a name not spelled yet, a library without a
/// name, labels beyond the bound, an overrun; found by changing the stream's bytes.
#[test]
fn v51_damaged_labels_are_refused() {
    let bytes = edgebreaker(6);
    let h = PartsHeader::parse(&payload(&bytes, Tag::PART));
    let mut seen = BTreeSet::new();
    for i in HEADER_LEN..HEADER_LEN + h.json_len as usize {
        for x in [0x01u8, 0x10, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::PART, |p| p[i] ^= x);
            if let Some(m) = v51_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    assert!(
        seen.iter().any(|s| s.contains("a reference to none of")),
        "{seen:?}"
    );
    // The stream cut short: the decoder reads zeros past its end.
    let bad = forge(&bytes, Tag::PART, |p| {
        let j = h.json_len as usize;
        p.drain(HEADER_LEN + 1..HEADER_LEN + j);
        put(p, 12, 1);
    });
    let m = v51_message(&bad).expect("a cut stream is refused");
    assert!(m.contains("ends inside") || m.contains("none of"), "{m}");
}

/// Coded labels decode to the labels of the JSON of level 0, and are shorter; a file of
/// any connectivity gets them from level 1.
#[test]
fn coded_labels_decode_right() {
    let (json, coded) = (edgebreaker(0), edgebreaker(6));
    let (a, b) = (
        PartsHeader::parse(&payload(&json, Tag::PART)),
        PartsHeader::parse(&payload(&coded, Tag::PART)),
    );
    assert_eq!((a.labels, b.labels), (JSON, CODED));
    assert!(
        b.json_len < a.json_len / 2,
        "{} vs {}",
        b.json_len,
        a.json_len
    );
    let (a, b) = (
        open(&json, &Limits::default()).unwrap().to_mesh(),
        open(&coded, &Limits::default()).unwrap().to_mesh(),
    );
    assert_eq!(a.parts.unwrap().parts, b.parts.unwrap().parts);
    let lr = encode(&torus(), &EncodeOptions::default()).unwrap();
    assert_eq!(PartsHeader::parse(&payload(&lr, Tag::PART)).labels, CODED);
    // Minor version 4 for the flag of its closed LR (§6), 3 for the labels alone.
    assert_eq!(lr[10], 4, "minor version 4");
    let lr = encode(
        &torus(),
        &EncodeOptions {
            connectivity: lrmesh::write::Connectivity::Strips,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    assert_eq!(PartsHeader::parse(&payload(&lr, Tag::PART)).labels, CODED);
    assert_eq!(lr[10], 3, "minor version 3");
}

/// The runs decode to the parts of the packed section of level 0, and are shorter.
#[test]
fn the_files_forged_from_decode_right() {
    let (packed, runs) = (edgebreaker(0), edgebreaker(6));
    assert_eq!(PartsHeader::parse(&payload(&packed, Tag::PART)).encoding, 0);
    assert!(payload(&runs, Tag::PART).len() < payload(&packed, Tag::PART).len());
    let (a, b) = (
        open(&packed, &Limits::default()).unwrap().to_mesh(),
        open(&runs, &Limits::default()).unwrap().to_mesh(),
    );
    assert_eq!(a.triangles, b.triangles);
    assert_eq!(a.parts, b.parts);
}

/// The fuzz target `container_forged` starts from containers with runs (and with packed
/// indices, JSON and coded labels): its byte edits reach both decoders.
#[test]
fn the_fuzz_target_reaches_runs() {
    let (mut encodings, mut labels) = (BTreeSet::new(), BTreeSet::new());
    for choice in 0..=255u8 {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        if section_at_opt(&bytes, Tag::PART) {
            let h = PartsHeader::parse(&payload(&bytes, Tag::PART));
            encodings.insert(h.encoding);
            labels.insert(h.labels);
        }
    }
    assert_eq!(encodings, BTreeSet::from([0, RUNS]));
    assert_eq!(labels, BTreeSet::from([JSON, CODED]));
}

fn section_at_opt(bytes: &[u8], tag: Tag) -> bool {
    open(bytes, &Limits::default())
        .unwrap()
        .sections
        .section(tag)
        .is_some()
}
