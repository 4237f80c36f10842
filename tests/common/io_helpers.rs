//! Reading, writing and expecting errors for the importer and exporter tests (`tests/io_*.rs`).

use super::corpus_dir;
use lrmesh::io::{read_mesh, read_mesh_bytes, stl, write_mesh_to, Loaded, MeshFormat, ReadOptions};
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::{Error, Location, Mesh, ParseError};
use std::path::Path;

pub fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

pub fn load(name: &str) -> Mesh {
    read_mesh(&corpus_dir().join(name), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .mesh
}

pub fn read(bytes: &[u8], format: MeshFormat) -> Loaded {
    read_mesh_bytes(bytes, format, &ReadOptions::default()).unwrap_or_else(|e| {
        panic!(
            "{e}\ninput:\n{}",
            String::from_utf8_lossy(&bytes[..bytes.len().min(2000)])
        )
    })
}

pub fn read_weld(bytes: &[u8], weld: bool) -> Mesh {
    read_mesh_bytes(bytes, MeshFormat::Stl, &ReadOptions { weld })
        .unwrap()
        .mesh
}

pub fn parse_err(bytes: &[u8], format: MeshFormat) -> ParseError {
    match read_mesh_bytes(bytes, format, &ReadOptions::default()) {
        Err(Error::Parse(e)) => *e,
        Err(e) => panic!("not a parse error: {e}"),
        Ok(l) => panic!(
            "accepted ({} vertices, {} triangles): {}",
            l.mesh.vertex_count(),
            l.mesh.triangle_count(),
            String::from_utf8_lossy(&bytes[..bytes.len().min(500)])
        ),
    }
}

/// Asserts that reading fails at `location` with a message that contains every one of
/// `needles`.
#[track_caller]
pub fn assert_err(bytes: &[u8], format: MeshFormat, location: Location, needles: &[&str]) {
    let e = parse_err(bytes, format);
    assert_eq!(e.format, format.name(), "{e}");
    assert_eq!(e.location, location, "{e}");
    for n in needles {
        assert!(e.message.contains(n), "`{n}` not in: {e}");
    }
}

pub fn write_to_vec(mesh: &Mesh, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    write_mesh_to(&mut out, mesh, format).unwrap();
    out
}

pub fn stl_binary(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    stl::write_binary(&mut out, mesh).unwrap();
    out
}

pub fn stl_ascii(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    stl::write_ascii(&mut out, mesh).unwrap();
    out
}

/// `m` with its attributes in the order of their semantics, for comparing two meshes whole:
/// the order of `Mesh::attributes` means nothing, and each reader keeps its format's order.
pub fn sorted_attributes(m: &Mesh) -> Mesh {
    let mut m = m.clone();
    m.attributes.sort_by(|a, b| a.semantic.cmp(&b.semantic));
    m
}

pub fn with_attributes(mut m: Mesh, normals: bool, texcoords: bool, colors: bool) -> Mesh {
    let n = m.vertex_count();
    if normals {
        let normals: Vec<[f32; 3]> = (0..n)
            .map(|i| match i % 3 {
                0 => [-0.0, 0.0, 1.0],
                1 => [0.577_350_26, -0.577_350_26, 1e-42],
                _ => [i as f32, -1e30, 0.25],
            })
            .collect();
        m.set_attribute(Attribute::per_vertex(Semantic::Normal, &normals));
    }
    if texcoords {
        let texcoords: Vec<[f32; 2]> = (0..n)
            .map(|i| [i as f32 / 7.0, if i == 2 { -0.0 } else { 1e-20 }])
            .collect();
        m.set_attribute(Attribute::per_vertex(Semantic::TexCoord(0), &texcoords));
    }
    if colors {
        let colors: Vec<[u8; 4]> = (0..n)
            .map(|i| {
                let i = i as u8;
                [i * 40, 255 - i, 1, if i == 3 { 0 } else { 255 }]
            })
            .collect();
        m.set_attribute(Attribute::rgba8(&colors));
    }
    m
}

/// A PLY file with a big-endian body: extra vertex properties (a float, a list) before and
/// after the coordinates, an extra face property and an extra element between the two.
pub fn big_endian_ply() -> Vec<u8> {
    let mut b = b"ply\r\nformat binary_big_endian 1.0\r\ncomment made by hand\r\nobj_info nothing\r\n\
element vertex 4\r\nproperty float confidence\r\nproperty double x\r\nproperty float y\r\nproperty short z\r\n\
property list uchar int neighbours\r\nproperty uchar red\r\nproperty uchar green\r\nproperty uchar blue\r\n\
property float u\r\nproperty float v\r\n\
element edge 2\r\nproperty int vertex1\r\nproperty int vertex2\r\n\
element face 2\r\nproperty uchar flags\r\nproperty list uchar uint vertex_indices\r\nend_header\r\n"
        .to_vec();
    for (i, p) in [
        [0.5f64, -0.0, 1.0],
        [1.0, 0.0, 2.0],
        [1.0, 1.0, 3.0],
        [0.0, 1.0, -4.0],
    ]
    .iter()
    .enumerate()
    {
        b.extend(0.25f32.to_be_bytes());
        b.extend(p[0].to_be_bytes());
        b.extend((p[1] as f32).to_be_bytes());
        b.extend((p[2] as i16).to_be_bytes());
        b.push(i as u8);
        for k in 0..i {
            b.extend((k as i32).to_be_bytes());
        }
        b.extend([10 * i as u8, 20, 30]);
        b.extend((i as f32 / 4.0).to_be_bytes());
        b.extend(1.0f32.to_be_bytes());
    }
    for (a, c) in [(0i32, 1i32), (2, 3)] {
        b.extend(a.to_be_bytes());
        b.extend(c.to_be_bytes());
    }
    b.push(7);
    b.push(3);
    for v in [0u32, 1, 2] {
        b.extend(v.to_be_bytes());
    }
    b.push(7);
    b.push(4);
    for v in [0u32, 2, 3, 3] {
        b.extend(v.to_be_bytes());
    }
    b
}
