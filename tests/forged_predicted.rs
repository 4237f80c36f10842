//! Forged containers for the predicted positions of Edgebreaker (`GEOM` encodings 2 and 3,
//! spec/GEOMETRY.md: [V44]) and their grid fields ([V13]). How a rule is broken and what the
//! reader must report: `tests/common/forge.rs`. The residual streams are range coded, so a
//! damaged stream is found by changing its bytes one at a time: the tests fail if no change
//! reaches a check any more.

mod common;

use std::collections::BTreeSet;

use common::forge::*;
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::{Error, Mesh, Rule};

/// Bytes before the stream: header, then the grid of encoding 2.
const GRID_STREAM_AT: usize = 28;
const F32_STREAM_AT: usize = 8;

fn torus() -> Mesh {
    generate::torus(12, 8)
}

fn edgebreaker(mesh: &Mesh, bits: Option<u8>) -> Vec<u8> {
    let bytes = encode(
        mesh,
        &EncodeOptions {
            connectivity: Connectivity::Edgebreaker,
            position_bits: bits,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// The message of the [V44] error of `bytes`, `None` if it opens; any other error fails.
fn v44_message(bytes: &[u8], stream_at: u64) -> Option<String> {
    match open(bytes, &Limits::default()) {
        Ok(_) => None,
        Err(Error::Format(e)) => {
            assert_eq!((e.rule, e.section.as_str()), (Rule(44), "GEOM"), "{e}");
            assert!(e.offset >= stream_at, "{e}");
            Some(e.message)
        }
        Err(e) => panic!("{e}"),
    }
}

/// Every message that changing one stream byte at a time gives.
fn messages_of_damaged_streams(bytes: &[u8], stream_at: usize) -> BTreeSet<String> {
    let geom = payload(bytes, Tag::GEOM);
    let at = section_at(bytes, Tag::GEOM) + stream_at as u64;
    let mut seen = BTreeSet::new();
    for i in stream_at..geom.len() {
        for x in [0x01u8, 0x80, 0xFF] {
            let bad = forge(bytes, Tag::GEOM, |p| p[i] ^= x);
            if let Some(m) = v44_message(&bad, at) {
                // Keep what the message says, not which vertex.
                seen.insert(m.split(": ").last().unwrap().to_string());
            }
        }
    }
    seen
}

/// [V44] Predicted positions appear only with the Edgebreaker connectivity.
#[test]
fn v44_predicted_positions_need_edgebreaker() {
    let mesh = torus();
    let predicted = payload(&edgebreaker(&mesh, Some(12)), Tag::GEOM);
    for kind in [
        Connectivity::Lr,
        Connectivity::Strips,
        Connectivity::LrCompact,
    ] {
        let bytes = encoded(&mesh, kind);
        let bad = forge(&bytes, Tag::GEOM, |p| *p = predicted.clone());
        let at = section_at(&bad, Tag::GEOM);
        breaks(&bad, 44, "GEOM", at, "needs the Edgebreaker connectivity");
    }
}

/// [V44] Grid residuals: no class above the grid's bits, no level outside the grid.
#[test]
fn v44_grid_residuals_stay_on_the_grid() {
    let bytes = edgebreaker(&torus(), Some(10));
    let seen = messages_of_damaged_streams(&bytes, GRID_STREAM_AT);
    for m in [
        "a residual longer than the grid's bits",
        "outside the grid 0..=1023",
    ] {
        assert!(seen.iter().any(|s| s.contains(m)), "{m:?} not in {seen:?}");
    }
    // Fewer bits than the stream was coded with: the first large residual is refused.
    let bad = forge(&bytes, Tag::GEOM, |p| put(p, 24, 2));
    let m = v44_message(&bad, section_at(&bad, Tag::GEOM)).unwrap();
    assert!(m.contains("longer than the grid's bits") || m.contains("outside the grid"));
}

/// [V44] Float residuals: an ordered integer in range, of a finite float.
#[test]
fn v44_float_residuals_give_finite_floats() {
    let bytes = edgebreaker(&torus(), None);
    let seen = messages_of_damaged_streams(&bytes, F32_STREAM_AT);
    assert!(seen.iter().any(|s| s.contains("no finite f32")), "{seen:?}");
}

/// [V44] The stream holds every vertex: a truncated one overruns.
#[test]
fn v44_stream_ends_early() {
    for (bits, stream_at) in [(Some(14), GRID_STREAM_AT), (None, F32_STREAM_AT)] {
        let bytes = edgebreaker(&torus(), bits);
        let len = payload(&bytes, Tag::GEOM).len();
        let mut refused = 0;
        for keep in stream_at..len - 4 {
            let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(keep));
            let m = v44_message(&bad, section_at(&bad, Tag::GEOM));
            refused += m.is_some() as usize;
        }
        assert!(
            refused > (len - stream_at) / 2,
            "{bits:?}: {refused} refused"
        );
        let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(stream_at));
        let m = v44_message(&bad, section_at(&bad, Tag::GEOM)).unwrap();
        assert!(m.contains("the stream ends before vertex"), "{m}");
    }
}

/// [V13] The grid of predicted positions: finite box minimum and size, size at least 0,
/// 1 to 30 bits, reserved 0.
#[test]
fn v13_grid_of_predicted_positions() {
    grid_breaks(&edgebreaker(&torus(), Some(12)));
}

/// What the tests above forge from decodes exactly (lossless) or within half a step.
#[test]
fn the_files_forged_from_decode_right() {
    let mesh = torus();
    let exact = open(&edgebreaker(&mesh, None), &Limits::default())
        .unwrap()
        .to_mesh();
    let mut want: Vec<[u32; 3]> = mesh.positions.iter().map(|p| p.map(f32::to_bits)).collect();
    let mut got: Vec<[u32; 3]> = exact
        .positions
        .iter()
        .map(|p| p.map(f32::to_bits))
        .collect();
    want.sort();
    got.sort();
    assert_eq!(got, want);
}
