//! Forged containers for the range-coded kept triangles (`KEPC`, FORMAT.md §3.7.1: [V50]).
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

/// A torus with 40 degenerate triangles of every pattern (a vertex repeated at corners 0
/// and 1, 1 and 2, 0 and 2, or all three) and a vertex that spans far from the one before.
fn kept_mesh() -> Mesh {
    let mut mesh = generate::torus(12, 8);
    let n = mesh.positions.len() as u32;
    for i in 0..40u32 {
        let (a, b) = ((7 * i) % n, (7 * i + 1 + i % 3) % n);
        mesh.triangles.push(match i % 4 {
            0 => [a, a, b],
            1 => [a, b, b],
            2 => [b, a, b],
            _ => [a, a, a],
        });
    }
    mesh
}

fn encoded_with(connectivity: Connectivity) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity,
        ..EncodeOptions::default()
    };
    let bytes = encode(&kept_mesh(), &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// The message of the [V50] error of `bytes`, `None` if it opens; any other error fails.
#[track_caller]
fn v50_message(bytes: &[u8]) -> Option<String> {
    rule_message(bytes, 50, "KEPC")
}

/// [V50] `KEPC` gives the triangles `KEPT` stores (level 0 writes `KEPT`), in fewer bytes.
#[test]
fn v50_kept_coded_means_kept() {
    let coded = encoded_with(Connectivity::Edgebreaker);
    let mut options = EncodeOptions {
        connectivity: Connectivity::Edgebreaker,
        ..EncodeOptions::default()
    };
    options.level = 0;
    let plain = encode(&kept_mesh(), &options).unwrap();
    let (a, b) = (
        open(&coded, &Limits::default()).unwrap(),
        open(&plain, &Limits::default()).unwrap(),
    );
    assert!(a.sections.section(Tag::KEPT).is_none());
    assert!(b.sections.section(Tag::KEPC).is_none());
    assert!(payload(&coded, Tag::KEPC).len() < payload(&plain, Tag::KEPT).len());
    assert_eq!(a.kept_triangle_count(), 40);
    for j in 0..40 {
        for k in 0..3 {
            assert_eq!(a.kept_vertex(j, k), b.kept_vertex(j, k));
        }
    }
    assert_eq!(a.to_mesh(), b.to_mesh());
}

/// [V50] Only with the Edgebreaker connectivity, and never with `KEPT`.
#[test]
fn v50_kept_coded_needs_edgebreaker_alone() {
    let coded = encoded_with(Connectivity::Edgebreaker);
    let kepc = payload(&coded, Tag::KEPC);
    let lr = encoded_with(Connectivity::Lr);
    let bad = forge_sections(&lr, |s| {
        let kept = s.iter_mut().find(|s| s.0 == Tag::KEPT).unwrap();
        kept.0 = Tag::KEPC;
        kept.2 = kepc.clone();
    });
    let m = v50_message(&bad).unwrap();
    assert!(m.contains("needs the Edgebreaker connectivity"), "{m}");
    let plain = {
        let mut options = EncodeOptions {
            connectivity: Connectivity::Edgebreaker,
            ..EncodeOptions::default()
        };
        options.level = 0;
        encode(&kept_mesh(), &options).unwrap()
    };
    let kept = payload(&plain, Tag::KEPT);
    let bad = forge_sections(&coded, |s| {
        let flags = s.iter().find(|s| s.0 == Tag::KEPC).unwrap().1;
        s.push((Tag::KEPT, flags, kept.clone()));
    });
    let m = v50_message(&bad).unwrap();
    assert!(m.contains("both KEPT and KEPC"), "{m}");
}

/// [V50] Length `8 + n`; `k` bounded by what `n` bytes can hold; `k` is `MESH`'s `K`.
#[test]
fn v50_lengths_and_counts() {
    let bytes = encoded_with(Connectivity::Edgebreaker);
    let at = section_at(&bytes, Tag::KEPC);
    let n = get(&payload(&bytes, Tag::KEPC), 4);
    breaks(
        &forge(&bytes, Tag::KEPC, |p| put(p, 4, n + 1)),
        50,
        "KEPC",
        at,
        "",
    );
    let cut = forge(&bytes, Tag::KEPC, |p| p.truncate(6));
    breaks(&cut, 50, "KEPC", at + 4, "");
    let bad = forge(&bytes, Tag::KEPC, |p| put(p, 0, 1 << 30));
    breaks(&bad, 50, "KEPC", at + 8, "more than");
    // One triangle fewer decodes, and MESH's K no longer agrees.
    let bad = forge(&bytes, Tag::KEPC, |p| put(p, 0, 39));
    breaks(&bad, 12, "MESH", section_at(&bytes, Tag::MESH) + 12, "KEPC");
}

/// [V50] Damaged streams: no pattern above 4, no vertex out of range or repeated, no overrun.
#[test]
fn v50_damaged_streams_are_refused() {
    let bytes = encoded_with(Connectivity::Edgebreaker);
    let n = get(&payload(&bytes, Tag::KEPC), 4) as usize;
    let mut seen = BTreeSet::new();
    for i in 8..8 + n {
        for x in [0x01u8, 0x10, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::KEPC, |p| p[i] ^= x);
            if let Some(m) = v50_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    for m in ["pattern", "not below"] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    // A stream cut short (with `n` and the section cut alike) ends before its last triangle.
    let bad = forge(&bytes, Tag::KEPC, |p| {
        p.truncate(8 + n / 2);
        put(p, 4, (n / 2) as u32);
    });
    let m = v50_message(&bad).unwrap();
    assert!(m.contains("the stream ends before kept triangle"), "{m}");
}

/// The fuzz target `container_forged` starts from containers with `KEPC`: its byte edits
/// reach its decoder.
#[test]
fn the_fuzz_target_reaches_kept_coded() {
    let reached = (0..=255u8).any(|choice| {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let file = open(&bytes, &Limits::default()).unwrap();
        file.sections.section(Tag::KEPC).is_some()
    });
    assert!(reached);
}
