//! Forged containers for the range-coded vertex copies (`COPC`, FORMAT.md §3.6.1: [V52]).
//! How a rule is broken and what the reader must report: `tests/common/forge.rs`. The stream
//! is range coded, so a damaged stream is found by changing its bytes one at a time: the
//! tests fail if no change reaches a check.

mod common;

use std::collections::BTreeSet;

use common::forge::*;
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::Mesh;

/// Two tori touching at twelve vertices: each shared vertex has two fans, so the container
/// holds twelve copies.
fn pinched() -> Mesh {
    let mut mesh = generate::torus(12, 8);
    let first = mesh.positions.len() as u32;
    generate::append(&mut mesh, &generate::torus(8, 6));
    let shared: Vec<(u32, u32)> = (0..12).map(|i| (first + 4 * i, 7 * i)).collect();
    for t in mesh.triangles.iter_mut() {
        for x in t.iter_mut() {
            if let Some(&(_, to)) = shared.iter().find(|&&(from, _)| from == *x) {
                *x = to;
            }
        }
    }
    mesh
}

fn encoded(connectivity: Connectivity, level: u8) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity,
        level,
        ..EncodeOptions::default()
    };
    let bytes = encode(&pinched(), &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// The message of the [V52] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v52_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 52, "COPC")
}

/// [V52] `COPC` gives the pairs `COPY` stores (level 0 writes `COPY`), in fewer bytes.
#[test]
fn v52_copies_coded_mean_copies() {
    let (coded, plain) = (
        encoded(Connectivity::Edgebreaker, 6),
        encoded(Connectivity::Edgebreaker, 0),
    );
    let (a, b) = (
        open(&coded, &Limits::default()).unwrap(),
        open(&plain, &Limits::default()).unwrap(),
    );
    assert!(a.sections.section(Tag::COPY).is_none());
    assert!(b.sections.section(Tag::COPC).is_none());
    assert!(payload(&coded, Tag::COPC).len() < payload(&plain, Tag::COPY).len() / 2);
    assert_eq!(a.summary().vertex_copies, 12);
    assert_eq!(a.summary().vertex_copies, b.summary().vertex_copies);
    assert_eq!(a.to_mesh(), b.to_mesh());
    assert_eq!(coded[10], 3, "minor version 3");
}

/// [V52] Only with the Edgebreaker connectivity, and never with `COPY`.
#[test]
fn v52_copies_coded_need_edgebreaker_alone() {
    let coded = encoded(Connectivity::Edgebreaker, 6);
    let copc = payload(&coded, Tag::COPC);
    let lr = encoded(Connectivity::Lr, 6);
    let bad = forge_sections(&lr, |s| {
        let copy = s.iter_mut().find(|s| s.0 == Tag::COPY).unwrap();
        copy.0 = Tag::COPC;
        copy.2 = copc.clone();
    });
    let m = v52_message(&bad).unwrap();
    assert!(m.contains("needs the Edgebreaker connectivity"), "{m}");
    let copy = payload(&encoded(Connectivity::Edgebreaker, 0), Tag::COPY);
    let bad = forge_sections(&coded, |s| {
        let flags = s.iter().find(|s| s.0 == Tag::COPC).unwrap().1;
        s.push((Tag::COPY, flags, copy.clone()));
    });
    let m = v52_message(&bad).unwrap();
    assert!(m.contains("both COPY and COPC"), "{m}");
}

/// [V52] Length `8 + n`; `k` bounded by the vertices and by what `n` bytes can hold; `k` is
/// the copy count of [V12].
#[test]
fn v52_lengths_and_counts() {
    let bytes = encoded(Connectivity::Edgebreaker, 6);
    let at = section_at(&bytes, Tag::COPC);
    let n = get(&payload(&bytes, Tag::COPC), 4);
    breaks(
        &forge(&bytes, Tag::COPC, |p| put(p, 4, n + 1)),
        52,
        "COPC",
        at,
        "",
    );
    breaks(
        &forge(&bytes, Tag::COPC, |p| p.truncate(6)),
        52,
        "COPC",
        at + 4,
        "",
    );
    let bad = forge(&bytes, Tag::COPC, |p| put(p, 0, 1 << 30));
    breaks(&bad, 52, "COPC", at + 8, "cannot be coded");
    // One copy fewer decodes, and MESH's W no longer agrees.
    let bad = forge(&bytes, Tag::COPC, |p| put(p, 0, 11));
    breaks(
        &bad,
        12,
        "MESH",
        section_at(&bytes, Tag::MESH) + 4,
        "11 copies",
    );
}

/// [V52] Damaged streams: no copy at or past `V`, no original at or after its copy or that
/// is a copy, no overrun.
#[test]
fn v52_damaged_streams_are_refused() {
    let bytes = encoded(Connectivity::Edgebreaker, 6);
    let n = get(&payload(&bytes, Tag::COPC), 4) as usize;
    let mut seen = BTreeSet::new();
    for i in 8..8 + n {
        for x in [0x01u8, 0x10, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::COPC, |p| p[i] ^= x);
            if let Some(m) = v52_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    for m in ["not below", "an original not below the copy"] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    let bad = forge(&bytes, Tag::COPC, |p| {
        p.truncate(8 + n / 2);
        put(p, 4, (n / 2) as u32);
    });
    let m = v52_message(&bad).unwrap();
    assert!(m.contains("the stream ends before copy"), "{m}");
}

/// The fuzz target `container_forged` starts from containers with `COPC`: its byte edits
/// reach its decoder.
#[test]
fn the_fuzz_target_reaches_copies_coded() {
    let reached = (0..=255u8).any(|choice| {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let file = open(&bytes, &Limits::default()).unwrap();
        file.sections.section(Tag::COPC).is_some()
    });
    assert!(reached);
}
