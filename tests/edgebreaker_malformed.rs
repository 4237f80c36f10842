//! Hand-built malformed Edgebreaker streams, one per error of
//! [`lrmesh::edgebreaker::decode`] (`src/edgebreaker/decode.rs`, `topology.rs`, `rebuild.rs`;
//! rules EB1–EB24 of `spec/EDGEBREAKER.md` §6): each must fail with a `Parse` error of format
//! `"Edgebreaker"`, at the byte offset the decoder stood at, with its own message.
//!
//! Headers are built field by field. Streams that fail deep in the range-coded parts are real
//! encodings (checked by `forged_streams_start_from_real_encodings`) with one or two bytes
//! changed; the changes were found by trying every value of every byte, and are kept here as
//! literals.
//!
//! Six error returns cannot be reached by any stream, so they have no test:
//!
//! - `"handle corner out of range"` (`State::glue_early`): the topology stream only yields
//!   handles `(t, 3 o + r)` with `t < o < nt` and `r` 1 or 2, so both corners exist and lie in
//!   different triangles.
//! - `"gate out of range"` (`State::glue3`, `State::glue_fresh`): every corner glued is a
//!   corner of a triangle below `nt` or a `d1` link, which only ever holds such corners.
//! - `"hole of fewer than 2 vertices"` (`split`): a hole length is coded as `len − 2` and
//!   decoded as that plus 2, or as 0 for no hole.
//! - `"boundary S at a closed fan"` (`State::hole`, EB23) and `"external boundary at a closed
//!   fan"` (`State::external`, EB22): the `D1` walk from a corner `x` comes back to `x` only
//!   through the corner whose `d1` is `x`, which needs the edge facing `prev(x)` glued. For the
//!   external boundary that edge is the gate, which the check before (EB21) has found free.
//!   For a boundary `S` with tip `c = 3t` it is `t`'s left edge, glued before `t` is decoded
//!   only by a handle `(h, 3t + 2)` with `h < t`; the walk then needs the corner `3h + 1`,
//!   reached only across `h`'s gate, which is glued when `h − 1` is decoded, later.
//! - `"CLERS stream ends early"` before a component's first symbol (`run`): no bit is read
//!   between the check after the previous component's last symbol and this one, and the
//!   decoder's first 4 bytes never overrun.

mod common;

use lrmesh::edgebreaker::{decode, encode, Limits};
use lrmesh::{CornerTable, Error, Location, Mesh, ParseError};

/// The error of decoding `bytes` with `limits`.
#[track_caller]
fn parse_error_with(bytes: &[u8], limits: &Limits) -> ParseError {
    match decode(bytes, limits) {
        Err(Error::Parse(p)) => *p,
        Err(e) => panic!("expected a parse error, got {e}"),
        Ok(d) => panic!("decoded {} triangles from {bytes:02x?}", d.triangles.len()),
    }
}

/// Asserts that `bytes` is malformed at byte `at`, with `words` in the message.
#[track_caller]
fn assert_malformed_with(bytes: &[u8], limits: &Limits, at: u64, words: &str) {
    let p = parse_error_with(bytes, limits);
    assert_eq!(p.format, "Edgebreaker");
    assert_eq!(p.location, Location::Byte(at), "{}", p.message);
    assert!(p.message.contains(words), "{:?} lacks {words:?}", p.message);
}

#[track_caller]
fn assert_malformed(bytes: &[u8], at: u64, words: &str) {
    assert_malformed_with(bytes, &Limits::default(), at, words)
}

fn leb128(mut x: u64) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let byte = (x & 0x7F) as u8;
        x >>= 7;
        if x == 0 {
            out.push(byte);
            return out;
        }
        out.push(byte | 0x80);
    }
}

/// Magic, version, `nv`, `nu`, `nt`, the topology stream's length, the topology stream.
fn stream(nv: u64, nu: u64, nt: u64, topology: &[u8]) -> Vec<u8> {
    let mut out = vec![0xEB, 0x01];
    for x in [nv, nu, nt, topology.len() as u64] {
        out.extend(leb128(x));
    }
    out.extend_from_slice(topology);
    out
}

// The real encodings the forged streams below start from.
const TRIANGLE: [u8; 7] = [0xeb, 0x01, 0x03, 0x00, 0x01, 0x01, 0x80];
const TETRAHEDRON: [u8; 8] = [0xeb, 0x01, 0x04, 0x00, 0x04, 0x01, 0x65, 0x80];
const HEDRA_OPEN: [u8; 9] = [0xeb, 0x01, 0x06, 0x00, 0x06, 0x02, 0x86, 0xa0, 0xea];
const ANNULUS: [u8; 11] = [
    0xeb, 0x01, 0x08, 0x00, 0x08, 0x02, 0x87, 0x10, 0xba, 0xcf, 0xe0,
];

/// `base` with byte `at` set to `x`.
fn changed(base: &[u8], at: usize, x: u8) -> Vec<u8> {
    let mut b = base.to_vec();
    b[at] = x;
    b
}

/// The four-cell annulus of `spec/EDGEBREAKER.md` §10.2.
fn annulus() -> Mesh {
    let n = 4;
    let positions = (0..2 * n)
        .map(|i| [i as f32, (i * i) as f32, 0.0])
        .collect();
    let mut triangles = Vec::new();
    for i in 0..n {
        let j = (i + 1) % n;
        triangles.push([i, j, n + i]);
        triangles.push([j, n + j, n + i]);
    }
    Mesh::new(positions, triangles)
}

#[test]
fn forged_streams_start_from_real_encodings() {
    let corpus = |name: &str| lrmesh::load(common::corpus_dir().join(name)).unwrap();
    let triangle = Mesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    );
    for (mesh, bytes) in [
        (triangle, &TRIANGLE[..]),
        (corpus("tetrahedron.off"), &TETRAHEDRON[..]),
        (corpus("hedra_open.off"), &HEDRA_OPEN[..]),
        (annulus(), &ANNULUS[..]),
    ] {
        let encoded = encode(&CornerTable::from_mesh(&mesh).unwrap())
            .unwrap()
            .bytes;
        assert_eq!(encoded, bytes);
        decode(bytes, &Limits::default()).unwrap();
    }
}

// ---------------------------------------------------------------------------------------
// Header (EB1–EB8), src/edgebreaker/decode.rs.

#[test]
fn bad_magic_byte() {
    for bytes in [
        &[][..],
        &[0xEB],
        &[0xEC, 0x01, 0x03, 0x00, 0x01, 0x01, 0x80],
        &[0x00, 0x01],
    ] {
        assert_malformed(bytes, 0, "not an Edgebreaker stream (bad magic byte)");
    }
}

#[test]
fn unsupported_version() {
    for version in [0, 2, 0xFF] {
        let bytes = changed(&TRIANGLE, 1, version);
        assert_malformed(&bytes, 1, &format!("unsupported version {version}"));
    }
}

#[test]
fn header_ends_inside_an_integer() {
    assert_malformed(&[0xEB, 0x01], 2, "header ends inside the vertex count");
    assert_malformed(
        &[0xEB, 0x01, 0x83],
        2,
        "header ends inside the vertex count",
    );
    assert_malformed(
        &TRIANGLE[..3],
        3,
        "header ends inside the unreferenced vertex count",
    );
    assert_malformed(&TRIANGLE[..4], 4, "header ends inside the triangle count");
    assert_malformed(
        &[0xEB, 0x01, 3, 0, 0x81, 0x80],
        4,
        "header ends inside the triangle count",
    );
    assert_malformed(
        &TRIANGLE[..5],
        5,
        "header ends inside the topology stream length",
    );
}

#[test]
fn integer_does_not_fit_64_bits() {
    // A tenth byte holding more than bit 63, or with its continuation bit set.
    let mut too_big = vec![0xEB, 0x01];
    too_big.extend([0x80; 9]);
    too_big.push(0x02);
    assert_malformed(&too_big, 2, "vertex count does not fit 64 bits");
    let mut too_long = vec![0xEB, 0x01, 0x03];
    too_long.extend([0xFF; 9]);
    too_long.extend([0x81, 0x00]);
    assert_malformed(
        &too_long,
        3,
        "unreferenced vertex count does not fit 64 bits",
    );
    // 2^63 fits (and is then over the limit).
    let mut fits = vec![0xEB, 0x01];
    fits.extend([0x80; 9]);
    fits.extend([0x01, 0x00, 0x00, 0x00]);
    assert_malformed(&fits, 2, "9223372036854775808 vertices exceed the limit");
}

#[test]
fn vertices_exceed_the_limit() {
    let limit = Limits::default().max_vertices;
    assert_malformed(
        &stream(limit + 1, 0, 1, &[0x80]),
        2,
        "vertices exceed the limit",
    );
    decode(&stream(limit, limit - 3, 1, &[0x80]), &Limits::default()).unwrap();
    // Whatever the reader's limit, nv < 2^32 − 1 (EB4).
    let unlimited = Limits {
        max_vertices: u64::MAX,
        max_triangles: u64::MAX,
    };
    let bytes = stream(u32::MAX as u64, 0, 1, &[0x80]);
    assert_malformed_with(
        &bytes,
        &unlimited,
        2,
        "4294967295 vertices exceed the limit",
    );
}

#[test]
fn triangles_exceed_the_limit() {
    let limit = Limits::default().max_triangles;
    assert_malformed(
        &stream(3, 0, limit + 1, &[]),
        2,
        "triangles exceed the limit",
    );
    let unlimited = Limits {
        max_vertices: u64::MAX,
        max_triangles: u64::MAX,
    };
    let bytes = stream(3, 0, (u32::MAX / 3) as u64, &[]);
    assert_malformed_with(
        &bytes,
        &unlimited,
        2,
        "1431655765 triangles exceed the limit",
    );
}

#[test]
fn more_unreferenced_vertices_than_vertices() {
    let bytes = changed(&TRIANGLE, 3, 4);
    assert_malformed(&bytes, 2, "more unreferenced vertices than vertices");
}

#[test]
fn referenced_vertices_cannot_belong_to_the_triangles() {
    // More than 3 nt, or fewer than 3 with triangles.
    assert_malformed(
        &changed(&TRIANGLE, 2, 4),
        2,
        "4 referenced vertices cannot belong to 1 triangles",
    );
    assert_malformed(
        &changed(&TRIANGLE, 2, 2),
        2,
        "2 referenced vertices cannot belong to 1 triangles",
    );
    assert_malformed(&stream(5, 3, 1, &[0x80]), 2, "2 referenced vertices");
    // No triangles, no referenced vertex: valid.
    decode(&stream(5, 5, 0, &[]), &Limits::default()).unwrap();
}

#[test]
fn topology_stream_runs_past_the_end() {
    // topo_len = 2 with one byte after the header (at offset 6).
    assert_malformed(
        &changed(&TRIANGLE, 5, 2),
        6,
        "topology stream runs past the end",
    );
    let mut long = stream(3, 0, 1, &[0x80]);
    long[5] = 0x81;
    long.insert(6, 0x01); // topo_len = 129, header now ends at 7
    assert_malformed(&long, 7, "topology stream runs past the end");
}

#[test]
fn triangles_cannot_be_coded_in_the_bytes() {
    // rest = 0 bytes hold at most 3 · 1430 · 4 = 17160 triangles.
    assert_malformed(
        &stream(3, 0, 17161, &[]),
        2,
        "17161 triangles cannot be coded in 0 bytes",
    );
    let rest = parse_error_with(&stream(3, 0, 17160, &[]), &Limits::default());
    assert!(
        !rest.message.contains("cannot be coded"),
        "{}",
        rest.message
    );
}

#[test]
fn topology_stream_ends_early() {
    // Hedra_open's topology byte 7 (0xa0) made 0xc4: its decoder reads more than 4 bytes
    // past the stream's end.
    assert_malformed(
        &changed(&HEDRA_OPEN, 7, 0xc4),
        8,
        "topology stream ends early",
    );
}

// ---------------------------------------------------------------------------------------
// Topology stream (EB9–EB13), src/edgebreaker/topology.rs. Offsets are where the topology
// decoder stood: its stream starts at 6 here and the decoder reads 4 bytes at once.

#[test]
fn topology_integer_too_long() {
    // All ones: the component count's unary prefix reaches 40 bits.
    let bytes = stream(3, 0, 1, &[0xFF; 8]);
    assert_malformed(&bytes, 10, "topology stream: integer too long");
}

#[test]
fn more_components_than_triangles() {
    assert_malformed(
        &changed(&TRIANGLE, 6, 0x68),
        7,
        "topology stream: more components than triangles",
    );
}

#[test]
fn component_sizes_exceed_the_triangle_count() {
    assert_malformed(
        &changed(&TRIANGLE, 6, 0x60),
        7,
        "topology stream: component sizes exceed the triangle count",
    );
}

#[test]
fn component_sizes_do_not_add_up() {
    // nt = 2 for a topology of one component of one triangle.
    assert_malformed(
        &changed(&TRIANGLE, 4, 2),
        7,
        "topology stream: component sizes do not add up to the triangle count",
    );
}

#[test]
fn more_handles_than_triangles() {
    assert_malformed(
        &changed(&TRIANGLE, 6, 0x84),
        7,
        "topology stream: more handles than triangles",
    );
}

#[test]
fn handle_triangle_out_of_range() {
    assert_malformed(
        &changed(&TRIANGLE, 6, 0x83),
        7,
        "topology stream: handle triangle out of range",
    );
}

#[test]
fn handle_at_the_first_or_last_triangle() {
    assert_malformed(
        &changed(&TETRAHEDRON, 6, 0x69),
        7,
        "topology stream: handle at the first or last triangle of a component",
    );
}

#[test]
fn handle_corner_outside_its_component() {
    assert_malformed(
        &changed(&HEDRA_OPEN, 7, 0xbb),
        8,
        "topology stream: handle corner outside its component",
    );
}

// ---------------------------------------------------------------------------------------
// The reverse pass (EB14–EB24), src/edgebreaker/rebuild.rs. Offsets are where the CLERS
// decoder stood (clamped to the end of the input), except for the handle gluing, made
// before the pass, at 0.

#[test]
fn handle_edge_glued_twice() {
    // Hedra_open's topology byte 7 (0xa0) made 0xc3: a handle whose edge is glued twice.
    assert_malformed(
        &changed(&HEDRA_OPEN, 7, 0xc3),
        0,
        "handle at triangle 1: edge glued twice",
    );
}

#[test]
fn clers_stream_ends_early() {
    assert_malformed(&changed(&HEDRA_OPEN, 8, 0xbd), 9, "CLERS stream ends early");
}

#[test]
fn edge_glued_to_its_own_triangle() {
    assert_malformed(
        &changed(&TETRAHEDRON, 7, 0x00),
        8,
        "edge glued to its own triangle",
    );
}

#[test]
fn edge_glued_twice() {
    assert_malformed(&changed(&HEDRA_OPEN, 7, 0xb5), 9, "edge glued twice");
}

#[test]
fn more_vertices_than_declared() {
    // The tetrahedron's nv = 4 made 3.
    assert_malformed(
        &changed(&TETRAHEDRON, 2, 3),
        8,
        "more vertices than declared",
    );
}

#[test]
fn corner_reached_twice() {
    assert_malformed(&changed(&TETRAHEDRON, 7, 0x6c), 8, "corner reached twice");
}

#[test]
fn hole_length_too_long() {
    // The annulus's CLERS stream made to end at the top of the boundary S's interval: every
    // following decision is a 1, and the hole length's prefix runs past 32 bits.
    let mut bytes = ANNULUS[..8].to_vec();
    bytes.extend([0x2b, 0xba]);
    bytes.extend([0xFF; 8]);
    assert_malformed(&bytes, 18, "hole length too long");
}

#[test]
fn s_without_a_matching_e() {
    assert_malformed(&changed(&TETRAHEDRON, 7, 0x60), 8, "S without a matching E");
}

#[test]
fn e_without_a_matching_s() {
    assert_malformed(&changed(&TETRAHEDRON, 7, 0x78), 8, "E without a matching S");
}

#[test]
fn first_triangle_glued_at_its_gate() {
    let bytes = changed(&HEDRA_OPEN, 7, 0xb7);
    assert_malformed(
        &bytes,
        9,
        "first triangle of a component with boundary glued at its gate",
    );
}

#[test]
fn fewer_vertices_than_declared() {
    // The tetrahedron's nv = 4 made 5.
    assert_malformed(
        &changed(&TETRAHEDRON, 2, 5),
        8,
        "fewer vertices than declared",
    );
}

#[test]
fn corner_without_a_vertex() {
    assert_malformed(&changed(&ANNULUS, 7, 0x18), 11, "corner without a vertex");
}
