//! Hostile input to every importer: counts that would need gigabytes fail before allocating,
//! and every truncation and many byte mutations of small valid files of each format give a
//! parse error or a valid mesh, never a panic. Helpers: `tests/common/io_helpers.rs`.

mod common;

use common::io_helpers::*;
use lrmesh::io::{read_mesh_bytes, MeshFormat, ReadOptions};
use lrmesh::{Error, Location, Mesh};

// ---------------------------------------------------------------------------------------------
// Counts far beyond the file

#[test]
fn huge_counts_fail_fast() {
    // Each input claims about 4 billion records in about 100 bytes: an error, not an
    // allocation.
    let pad = |mut s: Vec<u8>| {
        s.resize(s.len().max(100), b'\n');
        s
    };
    assert_err(
        &pad(b"OFF\n4000000000 1 0\n0 0 0\n".to_vec()),
        MeshFormat::Off,
        Location::Line(2),
        &["4000000000 vertices", "only"],
    );
    assert_err(
        &pad(b"OFF\n3 1000000000 0\n0 0 0\n".to_vec()),
        MeshFormat::Off,
        Location::Line(2),
        &["1000000000 faces"],
    );
    assert_err(
        &pad(b"OFF\n18446744073709551615 18446744073709551615\n".to_vec()),
        MeshFormat::Off,
        Location::Line(2),
        &["exceeds the limit"],
    );
    let ply_header = b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
    assert_err(
        &pad(ply_header.to_vec()),
        MeshFormat::Ply,
        Location::Byte(ply_header.len() as u64),
        &["4000000000 `vertex`", "48000000000 bytes"],
    );
    let ply_ascii = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face 1000000000\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n";
    assert_err(
        &pad(ply_ascii.to_vec()),
        MeshFormat::Ply,
        Location::Line(10),
        &["1000000000 `face`"],
    );
    // An element of no properties with a huge count, and a huge list length.
    let mut empty_element = b"ply\nformat binary_little_endian 1.0\nelement nothing 18446744073709551615\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n".to_vec();
    let l = read(&empty_element, MeshFormat::Ply);
    assert_eq!(l.mesh.vertex_count(), 0);
    empty_element.truncate(0);
    let mut list = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uint uint vertex_indices\nend_header\n".to_vec();
    let list_at = list.len() as u64 + 36;
    list.extend(std::iter::repeat_n(0u8, 36));
    list.extend(4_000_000_000u32.to_le_bytes());
    list.extend([0u8; 12]);
    assert_err(
        &list,
        MeshFormat::Ply,
        Location::Byte(list_at),
        &["4000000000", "bytes"],
    );
    // Binary STL whose count says 4 billion triangles.
    let mut stl = vec![b' '; 80];
    stl.extend(4_000_000_000u32.to_le_bytes());
    stl.resize(100, 0);
    assert_err(
        &stl,
        MeshFormat::Stl,
        Location::Byte(100),
        &["truncated", "4000000000 triangles"],
    );
}

// ---------------------------------------------------------------------------------------------
// No panic on any input

/// Small valid files of every format and flavour.
fn small_files() -> Vec<(MeshFormat, &'static str, Vec<u8>)> {
    let m = with_attributes(
        Mesh::new(
            vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [0.0, 1.0, -0.5],
                [1.0, 1.0, 0.5],
            ],
            vec![[0, 1, 2], [1, 3, 2]],
        ),
        true,
        true,
        true,
    );
    let mut ascii_ply = b"ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty list uchar int l\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    ascii_ply.extend_from_slice(
        b"0 0 0 0 1 2 3\n1 0 0 1 7 1 2 3\n0 1 0 0 1 2 3\n1 1 1 2 1 1 1 2 3\n4 0 1 2 3\n3 3 2 1\n",
    );
    vec![
        (MeshFormat::Off, "off", write_to_vec(&m, MeshFormat::Off)),
        (
            MeshFormat::Off,
            "off plain",
            b"OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 1\n3 0 1 2\n4 1 3 2 0\n".to_vec(),
        ),
        (MeshFormat::Obj, "obj", write_to_vec(&m, MeshFormat::Obj)),
        (
            MeshFormat::Obj,
            "obj polygon",
            b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 1\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 -1/1/1 3/1/1\n"
                .to_vec(),
        ),
        (
            MeshFormat::Ply,
            "ply binary",
            write_to_vec(&m, MeshFormat::Ply),
        ),
        (MeshFormat::Ply, "ply big endian", big_endian_ply()),
        (MeshFormat::Ply, "ply ascii", ascii_ply),
        (MeshFormat::Stl, "stl binary", stl_binary(&m)),
        (MeshFormat::Stl, "stl ascii", stl_ascii(&m)),
    ]
}

fn must_not_panic(bytes: &[u8], format: MeshFormat) {
    for weld in [false, true] {
        match read_mesh_bytes(bytes, format, &ReadOptions { weld }) {
            Ok(l) => l.mesh.validate().unwrap(),
            Err(Error::Parse(_)) => {}
            Err(e) => panic!("{format}: not a parse error: {e}"),
        }
        if format != MeshFormat::Stl {
            break;
        }
    }
}

#[test]
fn truncation_at_every_length() {
    for (format, name, bytes) in small_files() {
        let full = read(&bytes, format);
        assert!(full.mesh.triangle_count() >= 2, "{name}");
        for len in 0..bytes.len() {
            must_not_panic(&bytes[..len], format);
        }
    }
}

#[test]
fn byte_mutations() {
    for (format, _, bytes) in small_files() {
        for i in 0..bytes.len() {
            for x in [0u8, b' ', b'\n', b'9', b'-', b'.', 0xff, bytes[i] ^ 0x80] {
                let mut b = bytes.clone();
                b[i] = x;
                must_not_panic(&b, format);
            }
        }
    }
}
