//! Forged containers for the anchored grid of Edgebreaker (`GEOM` encoding 6,
//! spec/GEOMETRY.md §9: [V55]) and its grid fields ([V13]). How a rule is broken and what the
//! reader must report: `tests/common/forge.rs`.

mod common;

use std::collections::BTreeSet;

use common::forge::*;
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::{Error, Mesh, Rule};

/// Bytes before the code lengths: header, then the grid.
const LENGTHS_AT: usize = 28;
/// Contexts, each with its code lengths.
const CONTEXTS: usize = 12;

fn torus() -> Mesh {
    generate::torus(12, 8)
}

/// An Edgebreaker container at level 1: positions in encoding 6.
fn anchored(mesh: &Mesh, bits: u8) -> Vec<u8> {
    let bytes = encode(
        mesh,
        &EncodeOptions {
            connectivity: Connectivity::Edgebreaker,
            position_bits: Some(bits),
            level: 1,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    let file = open(&bytes, &Limits::default()).expect("a valid container to forge");
    assert_eq!(file.summary().positions.encoding, "anchored-grid");
    bytes
}

/// Where the stream starts: after the twelve contexts' code lengths.
fn stream_at(geom: &[u8]) -> usize {
    let mut at = LENGTHS_AT;
    for _ in 0..CONTEXTS {
        at += 2 + (geom[at + 1] as usize).div_ceil(2);
    }
    at
}

/// The message of the [V55] error of `bytes`, `None` if it opens; any other error fails.
fn v55_message(bytes: &[u8]) -> Option<String> {
    match open(bytes, &Limits::default()) {
        Ok(_) => None,
        Err(Error::Format(e)) => {
            assert_eq!((e.rule, e.section.as_str()), (Rule(55), "GEOM"), "{e}");
            assert!(e.offset >= section_at(bytes, Tag::GEOM), "{e}");
            Some(e.message)
        }
        Err(e) => panic!("{e}"),
    }
}

/// [V55] The anchored grid appears only with the Edgebreaker connectivity.
#[test]
fn v55_anchored_positions_need_edgebreaker() {
    let mesh = torus();
    let geom = payload(&anchored(&mesh, 12), Tag::GEOM);
    for kind in [
        Connectivity::Lr,
        Connectivity::Strips,
        Connectivity::LrCompact,
    ] {
        let bytes = encoded(&mesh, kind);
        let bad = forge(&bytes, Tag::GEOM, |p| *p = geom.clone());
        let at = section_at(&bad, Tag::GEOM);
        breaks(&bad, 55, "GEOM", at, "needs the Edgebreaker connectivity");
    }
}

/// [V55] Code lengths: within the alphabet, at most 11, a zero padding nibble, not
/// oversubscribing the code space, and present.
#[test]
fn v55_code_lengths() {
    let bytes = anchored(&torus(), 10);
    let geom = payload(&bytes, Tag::GEOM);
    let at = section_at(&bytes, Tag::GEOM) + LENGTHS_AT as u64;
    // The first context with a code.
    let (first, count) = (geom[LENGTHS_AT], geom[LENGTHS_AT + 1]);
    assert!(count > 0);
    // 10 bits: 20 symbols.
    let bad = forge(&bytes, Tag::GEOM, |p| p[LENGTHS_AT] = 20 - count + 1);
    breaks(&bad, 55, "GEOM", at, "code lengths of symbols");
    let bad = forge(&bytes, Tag::GEOM, |p| p[LENGTHS_AT + 2] = 0x0C);
    breaks(&bad, 55, "GEOM", at + 2, "code length 12 above 11");
    // Every length 1: three or more codes of one bit oversubscribe.
    let bad = forge(&bytes, Tag::GEOM, |p| {
        for i in 0..(count as usize).div_ceil(2) {
            p[LENGTHS_AT + 2 + i] = 0x11;
        }
        if count % 2 == 1 {
            p[LENGTHS_AT + 2 + count as usize / 2] = 0x01;
        }
    });
    if count >= 3 {
        breaks(&bad, 55, "GEOM", at, "oversubscribe");
    }
    if count % 2 == 1 {
        let last = LENGTHS_AT + 2 + count as usize / 2;
        let bad = forge(&bytes, Tag::GEOM, |p| p[last] |= 0x10);
        breaks(
            &bad,
            55,
            "GEOM",
            at + 2 + count as u64 / 2,
            "padding nibble",
        );
    }
    // Cut inside the lengths.
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(LENGTHS_AT + 1));
    assert!(v55_message(&bad).is_some());
    let _ = first;
}

/// [V55] The stream: bits that start no code, levels outside the grid, an early end.
#[test]
fn v55_damaged_streams() {
    let bytes = anchored(&torus(), 10);
    let geom = payload(&bytes, Tag::GEOM);
    let start = stream_at(&geom);
    let mut seen = BTreeSet::new();
    for i in start..geom.len() {
        for x in [0x01u8, 0x80, 0xFF] {
            let bad = forge(&bytes, Tag::GEOM, |p| p[i] ^= x);
            if let Some(m) = v55_message(&bad) {
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    assert!(
        seen.iter().any(|s| s.contains("outside the grid 0..=1023")),
        "{seen:?}"
    );
    // An incomplete code: one context keeps a single symbol of length 1, whose other
    // pattern starts no code.
    let bad = forge(&bytes, Tag::GEOM, |p| {
        let mut at = LENGTHS_AT;
        for _ in 0..CONTEXTS {
            let count = p[at + 1] as usize;
            if count > 0 {
                let old = 2 + count.div_ceil(2);
                p.splice(at..at + old, [p[at], 1, 0x01]);
            }
            at += 2 + (p[at + 1] as usize).div_ceil(2);
        }
    });
    let m = v55_message(&bad).expect("an incomplete code is met");
    assert!(m.contains("start no code"), "{m}");
    let mut refused = 0;
    for keep in start..geom.len() - 2 {
        let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(keep));
        refused += v55_message(&bad).is_some() as usize;
    }
    assert!(refused > (geom.len() - start) / 2, "{refused} refused");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(start));
    let m = v55_message(&bad).unwrap();
    assert!(m.contains("the stream ends before vertex"), "{m}");
}

/// [V13] The grid of anchored positions: finite box minimum and size, size at least 0,
/// 1 to 30 bits, reserved 0.
#[test]
fn v13_grid_of_anchored_positions() {
    grid_breaks(&anchored(&torus(), 12));
}

/// The fuzz target `container_forged` starts from containers with `GEOM` encoding 6: its
/// byte edits reach the decoder.
#[test]
fn the_fuzz_target_reaches_the_anchored_grid() {
    let reached = (0..=255u8).any(|choice| {
        let bytes = lrmesh::fuzz_checks::forged_base(choice);
        let file = open(&bytes, &Limits::default()).unwrap();
        file.summary().positions.encoding == "anchored-grid"
    });
    assert!(reached);
}
