//! Forged containers for the rules of the sections around the connectivity (§3 of
//! `spec/FORMAT.md`): `META`, `MESH`, `GEOM` and the attributes **[V11]**..**[V14]**, `COPY`,
//! `KEPT` and `PERM` **[V24]**..**[V26]**, and the required sections **[V39]**. How a rule is
//! broken and what the reader must report: `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::MeshRecord;
use lrmesh::format::{Flags, Tag};
use lrmesh::generate;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::{Error, Mesh, Rule};

fn torus() -> Mesh {
    generate::torus(4, 5)
}

// ---------------------------------------------------------------------------------------
// §3 Sections around the connectivity.

/// [V11] `META` is a JSON object with a string `generator`; this crate reads at most 1 MiB.
#[test]
fn v11_metadata() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::META);
    for json in [
        &b"not json"[..],
        b"[1, 2]",
        b"{\"source\": \"x.off\"}",
        b"{\"generator\": 5}",
        b"{\"generator\": \"g\", \"extra\": {\"k\": 1}}",
        b"\xff\xfe",
    ] {
        let bad = forge(&bytes, Tag::META, |p| *p = json.to_vec());
        breaks(&bad, 11, "META", at, "metadata");
    }
    let later = forge(&bytes, Tag::META, |p| {
        *p = b"{\"generator\": \"g\", \"later\": [1]}".to_vec()
    });
    open(&later, &Limits::default()).unwrap();
    let limits = Limits {
        max_metadata_bytes: 10,
        ..Limits::default()
    };
    match open(&bytes, &limits) {
        Err(Error::LimitExceeded {
            what: "metadata size",
            value: 35,
            limit: 10,
        }) => {}
        other => panic!("{other:?}"),
    }
}

/// [V12] `MESH`: length 24, a known kind, reserved 0, `W ≤ V`, `W = V − copies`, `N` the
/// connectivity's triangles, `K` the kept ones.
#[test]
fn v12_mesh_counts() {
    let tetra = vector("closed_tetrahedron.lrm");
    let at = section_at(&tetra, Tag::MESH);
    let mesh_field =
        |bytes: &[u8], field: usize, x: u32| forge(bytes, Tag::MESH, |p| put(p, field, x));
    breaks(&forge(&tetra, Tag::MESH, |p| p.push(0)), 12, "MESH", at, "");
    let bad = forge(&tetra, Tag::MESH, |p| p.truncate(20));
    breaks(&bad, 12, "MESH", at, "");
    for kind in [0, 6, u32::MAX] {
        breaks(&mesh_field(&tetra, 16, kind), 12, "MESH", at + 16, "kind");
    }
    breaks(&mesh_field(&tetra, 20, 1), 12, "MESH", at + 20, "reserved");
    breaks(&mesh_field(&tetra, 4, 5), 12, "MESH", at + 4, "");
    // W = V − copies: one copy in this vector (V = 9, W = 8).
    let copies = vector("nonmanifold_vertex.lrm");
    let at_copies = section_at(&copies, Tag::MESH);
    for w in [9, 7] {
        let bad = mesh_field(&copies, 4, w);
        breaks(&bad, 12, "MESH", at_copies + 4, "copies");
    }
    // K: one kept triangle in that vector, none in the tetrahedron.
    let bad = mesh_field(&copies, 12, 0);
    breaks(&bad, 12, "MESH", at_copies + 12, "KEPT");
    breaks(&mesh_field(&tetra, 12, 1), 12, "MESH", at + 12, "KEPT");
    // N, for every kind (for EBRK, [V27] says the same).
    for connectivity in Connectivity::ALL {
        let bytes = encoded(&torus(), connectivity);
        let at = section_at(&bytes, Tag::MESH);
        for n in [39, 41, 0] {
            let bad = mesh_field(&bytes, 8, n);
            breaks(&bad, 12, "MESH", at + 8, "connectivity holds");
        }
    }
}

/// [V13] `GEOM`: its length, finite values, `lo ≤ hi`, a known encoding, reserved 0.
#[test]
fn v13_positions() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::GEOM);
    let bad = forge(&bytes, Tag::GEOM, |p| p.extend([0; 4]));
    breaks(&bad, 13, "GEOM", at, "");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(8 + 12 * 3));
    breaks(&bad, 13, "GEOM", at, "");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(3));
    breaks(&bad, 13, "GEOM", at, "");
    for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        // Vertex 2, coordinate 1.
        let bad = forge(&bytes, Tag::GEOM, |p| put(p, 8 + 24 + 4, x.to_bits()));
        breaks(&bad, 13, "GEOM", at + 36, "non-finite");
    }
    let bad = forge(&bytes, Tag::GEOM, |p| put(p, 4, 1));
    breaks(&bad, 13, "GEOM", at + 4, "reserved");
    for encoding in [7, u32::MAX] {
        let bad = forge(&bytes, Tag::GEOM, |p| put(p, 0, encoding));
        breaks(&bad, 13, "GEOM", at, "encoding");
    }
    // Encoding 1: box at 8 (lo) and 20 (hi), then 6 bytes a vertex.
    let q = encode(
        &torus(),
        &EncodeOptions {
            position_bits: Some(16),
            level: 0,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    let at = section_at(&q, Tag::GEOM);
    let bad = forge(&q, Tag::GEOM, |p| p.extend([0; 2]));
    breaks(&bad, 13, "GEOM", at, "");
    for k in 0..3 {
        let bad = forge(&q, Tag::GEOM, |p| {
            put(p, 8 + 4 * k, 5.0f32.to_bits());
            put(p, 20 + 4 * k, (-5.0f32).to_bits());
        });
        breaks(&bad, 13, "GEOM", at + 8 + 4 * k as u64, "minimum above");
        for field in [8, 20] {
            let bad = forge(&q, Tag::GEOM, |p| put(p, field + 4 * k, f32::NAN.to_bits()));
            breaks(&bad, 13, "GEOM", at + (field + 4 * k) as u64, "non-finite");
        }
    }
    let bad = forge(&q, Tag::GEOM, |p| put(p, 4, 1));
    breaks(&bad, 13, "GEOM", at + 4, "reserved");
}

// ---------------------------------------------------------------------------------------
// §3.6–3.8 COPY, KEPT, PERM.

/// [V24] `COPY`: length `4 + 8k`; ids below `V`; copies increasing; originals not copies.
#[test]
fn v24_copies() {
    let bytes = vector("defective_torus.lrm"); // V = 23, three copies
    let at = section_at(&bytes, Tag::COPY);
    let p = payload(&bytes, Tag::COPY);
    assert_eq!(get(&p, 0), 3);
    let word = |f: usize, x: u32| forge(&bytes, Tag::COPY, |p| put(p, f, x));
    let bad = forge(&bytes, Tag::COPY, |p| p.extend([0; 8]));
    breaks(&bad, 24, "COPY", at, "");
    breaks(&word(0, 2), 24, "COPY", at, "");
    breaks(&word(0, 4), 24, "COPY", at, "");
    let bad = forge(&bytes, Tag::COPY, |p| p.truncate(3));
    breaks(&bad, 24, "COPY", at, "");
    // A copy id out of range, copies not increasing (pair 1 given pair 0's copy).
    breaks(&word(4 + 8 * 2, 23), 24, "COPY", at + 4 + 16, "below 23");
    let bad = word(4 + 8, get(&p, 4));
    breaks(&bad, 24, "COPY", at + 4 + 8, "increasing");
    // An original that is itself a copy.
    let bad = word(4 + 8 * 2 + 4, get(&p, 4));
    breaks(&bad, 24, "COPY", at + 4 + 16 + 4, "itself a copy");
}

/// [V24] An original out of range is located at the original's word.
#[test]

fn v24_original_out_of_range_located() {
    let bytes = vector("defective_torus.lrm");
    let at = section_at(&bytes, Tag::COPY);
    let bad = forge(&bytes, Tag::COPY, |p| put(p, 4 + 4, 23));
    breaks(&bad, 24, "COPY", at + 8, "");
}

/// [V25] `KEPT`: length `4 + 12k`; ids below `V`.
#[test]
fn v25_kept_triangles() {
    let bytes = vector("nonmanifold_vertex.lrm"); // V = 9, one kept triangle
    let at = section_at(&bytes, Tag::KEPT);
    let bad = forge(&bytes, Tag::KEPT, |p| p.extend([0; 4]));
    breaks(&bad, 25, "KEPT", at, "");
    let bad = forge(&bytes, Tag::KEPT, |p| put(p, 0, 2));
    breaks(&bad, 25, "KEPT", at, "");
    let bad = forge(&bytes, Tag::KEPT, |p| p.truncate(2));
    breaks(&bad, 25, "KEPT", at, "");
    for (i, x) in [(0, 9), (2, NONE)] {
        let bad = forge(&bytes, Tag::KEPT, |p| put(p, 4 + 4 * i, x));
        breaks(&bad, 25, "KEPT", at + 4 + 4 * i as u64, "out of range");
    }
}

/// [V26] `PERM`: counts `W` and `N + K`; length `8 + 4 (W + T)`; two permutations.
#[test]
fn v26_permutations() {
    let bytes = vector("nonmanifold_vertex.lrm"); // W = 8, N + K = 9
    let at = section_at(&bytes, Tag::PERM);
    let p = payload(&bytes, Tag::PERM);
    let word = |f: usize, x: u32| forge(&bytes, Tag::PERM, |p| put(p, f, x));
    breaks(&word(0, 9), 26, "PERM", at, "permutations of 9 vertices");
    let bad = forge(&bytes, Tag::PERM, |p| p.extend([0; 4]));
    breaks(&bad, 26, "PERM", at, "");
    let bad = forge(&bytes, Tag::PERM, |p| p.truncate(p.len() - 4));
    breaks(&bad, 26, "PERM", at, "");
    // Vertex list: a repeat, a value out of range; triangle list the same.
    let (vertices, triangles) = (8usize, 8 + 4 * 8usize);
    let bad = word(vertices + 4, get(&p, vertices));
    breaks(&bad, 26, "PERM", at + 12, "permutation");
    let bad = word(vertices + 28, 8);
    breaks(&bad, 26, "PERM", at + 8 + 28, "permutation");
    let bad = word(triangles + 8, get(&p, triangles));
    breaks(&bad, 26, "PERM", at + 40 + 8, "permutation");
    breaks(&word(triangles, 9), 26, "PERM", at + 40, "permutation");
}

/// [V26] A wrong triangle count is located at its own field, offset 4.
#[test]

fn v26_triangle_count_located() {
    let bytes = vector("nonmanifold_vertex.lrm");
    let bad = forge(&bytes, Tag::PERM, |p| put(p, 4, 10));
    breaks(&bad, 26, "PERM", section_at(&bytes, Tag::PERM) + 4, "");
}

/// [V54] `FLIP`: `T = N + K`; length `4 + ⌈T/8⌉`; the padding bits 0.
#[test]
fn v54_reversed_triangles() {
    let bytes = vector("misoriented_cube.lrm"); // N + K = 12; triangles 2 3 5 10 11 reversed
    let at = section_at(&bytes, Tag::FLIP);
    let bits: u16 = (1 << 2) | (1 << 3) | (1 << 5) | (1 << 10) | (1 << 11);
    let mut want = 12u32.to_le_bytes().to_vec();
    want.extend(bits.to_le_bytes());
    assert_eq!(payload(&bytes, Tag::FLIP), want);
    breaks(
        &forge(&bytes, Tag::FLIP, |p| put(p, 0, 13)),
        54,
        "FLIP",
        at,
        "the mesh has 12",
    );
    let longer = forge(&bytes, Tag::FLIP, |p| p.push(0));
    breaks(&longer, 54, "FLIP", at, "");
    let shorter = forge(&bytes, Tag::FLIP, |p| {
        p.pop();
    });
    breaks(&shorter, 54, "FLIP", at, "");
    // A padding bit: triangle 12 of 12.
    let padding = forge(&bytes, Tag::FLIP, |p| p[5] |= 1 << 4);
    breaks(&padding, 54, "FLIP", at + 5, "padding");
    // No bit set is valid, and then nothing is reversed.
    let none = forge(&bytes, Tag::FLIP, |p| {
        p[4] = 0;
        p[5] = 0;
    });
    let limits = lrmesh::read::Limits::default();
    let reversed = lrmesh::read::open_verified(&bytes, &limits)
        .unwrap()
        .to_mesh();
    let as_stored = lrmesh::read::open_verified(&none, &limits)
        .unwrap()
        .to_mesh();
    let differ = (reversed.triangles.iter())
        .zip(&as_stored.triangles)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differ, 5);
}

/// [V39] `MESH`, `GEOM` and the connectivity section of MESH's kind are present, checked
/// when first needed.
#[test]
fn v39_required_sections() {
    let bytes = vector("closed_tetrahedron.lrm");
    let without = |tags: &[Tag]| forge_sections(&bytes, |s| s.retain(|x| !tags.contains(&x.0)));
    for tag in [Tag::MESH, Tag::GEOM, Tag::LRTB] {
        breaks(&without(&[tag]), 39, &tag.name(), 0, "missing");
    }
    // Kind 3 without STRP (LRTB is then surplus, and ignored).
    let strips_kind = forge(&bytes, Tag::MESH, |p| put(p, MeshRecord::KIND_AT, 3));
    breaks(&strips_kind, 39, "STRP", 0, "missing");
    // Checked when first needed: MESH after META, GEOM after MESH, the connectivity after
    // the attributes.
    let bad_meta = forge(&without(&[Tag::MESH]), Tag::META, |p| p.truncate(3));
    assert_eq!(format_error(&bad_meta).rule, Rule(11));
    let bad_mesh = forge(&without(&[Tag::GEOM]), Tag::MESH, |p| put(p, 20, 1));
    assert_eq!(format_error(&bad_mesh).rule, Rule(12));
    let bad_geom = forge(&without(&[Tag::LRTB]), Tag::GEOM, |p| put(p, 4, 1));
    assert_eq!(format_error(&bad_geom).rule, Rule(13));
    // A surplus connectivity section is not validated.
    let strips = vector("closed_tetrahedron.strips.lrm");
    let surplus = forge_sections(&strips, |s| {
        s.push((Tag::LRTB, Flags::REQUIRED, b"junk".to_vec()))
    });
    open(&surplus, &Limits::default()).unwrap();
}
