//! PLY importer tests: ASCII and binary bodies of either endianness with extra properties and
//! elements, property names, malformed headers and bodies located at their line or byte, and
//! a header of many statements. Helpers: `tests/common/io_helpers.rs`.

mod common;

use common::io_helpers::*;
use lrmesh::io::MeshFormat;
use lrmesh::mesh::Semantic;
use lrmesh::Location;

// ---------------------------------------------------------------------------------------------
// PLY

#[test]
fn ply_big_endian_with_extra_data() {
    let bytes = big_endian_ply();
    let l = read(&bytes, MeshFormat::Ply);
    let m = &l.mesh;
    assert_eq!(
        m.positions,
        vec![
            [0.5, -0.0, 1.0],
            [1.0, 0.0, 2.0],
            [1.0, 1.0, 3.0],
            [0.0, 1.0, -4.0]
        ]
    );
    assert_eq!(m.positions[0][1].to_bits(), (-0.0f32).to_bits());
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [0, 3, 3]]);
    assert_eq!(m.vertex_colors_rgba8().unwrap()[3], [30, 20, 30, 255]);
    assert_eq!(
        m.vertex_values::<2>(&Semantic::TexCoord(0)).unwrap()[2],
        [0.5, 1.0]
    );
    assert!(m.attribute(&Semantic::Normal).is_none());
    assert_eq!(l.warnings.len(), 1, "{:?}", l.warnings);
    let w = &l.warnings[0];
    for name in [
        "vertex.confidence",
        "vertex.neighbours",
        "element `edge`",
        "face.flags",
    ] {
        assert!(w.contains(name), "{name} not in {w}");
    }
}

#[test]
fn ply_ascii_with_extra_data() {
    let text = b"ply\nformat ascii 1.0\ncomment hand made\n\
element vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float confidence\n\
property list uchar float weights\nproperty float nx\nproperty float ny\nproperty float nz\n\
property float red\nproperty float green\nproperty float blue\nproperty float alpha\n\
element edge 2\nproperty int vertex1\nproperty int vertex2\n\
element face 2\nproperty list uchar int vertex_index\nproperty uchar material\nend_header\n\
0 0 0 0.5 2 0.1 0.2 0 0 1 1 0 0 1\n\
1 0 0 nan 0 0 0 1 0 0.5 0 0.5\n\
1 1 0 1e30 1 7 0 0 1 0 0 1 0.5\n\
0 1 -0 0.5 0\n  0 0 -1 0 0 0 0\n\
0 1\n2 3\n\
4 0 1 2 3 9\n3 3 2 1 0\n";
    let l = read(text, MeshFormat::Ply);
    let m = &l.mesh;
    assert_eq!(m.vertex_count(), 4);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [3, 2, 1]]);
    assert_eq!(m.positions[3][2].to_bits(), (-0.0f32).to_bits());
    assert_eq!(
        m.vertex_values::<3>(&Semantic::Normal).unwrap()[3],
        [0.0, 0.0, -1.0]
    );
    assert_eq!(
        m.vertex_colors_rgba8().unwrap(),
        vec![
            [255, 0, 0, 255],
            [0, 128, 0, 128],
            [0, 0, 255, 128],
            [0, 0, 0, 0]
        ]
    );
    let w = l.warnings.join("\n");
    for name in [
        "vertex.confidence",
        "vertex.weights",
        "element `edge`",
        "face.material",
    ] {
        assert!(w.contains(name), "{name} not in {w}");
    }
}

#[test]
fn ply_color_and_texcoord_names() {
    let text = b"ply\nformat ascii 1.0\nelement vertex 1\nproperty int diffuse_red\nproperty short diffuse_green\n\
property uchar diffuse_blue\nproperty float x\nproperty float y\nproperty float z\nproperty double texture_u\nproperty double texture_v\nend_header\n\
300 -5 7 1 2 3 0.25 0.75\n";
    let l = read(text, MeshFormat::Ply);
    assert_eq!(
        l.mesh.vertex_colors_rgba8().unwrap(),
        vec![[255, 0, 7, 255]]
    );
    assert_eq!(
        l.mesh.vertex_values::<2>(&Semantic::TexCoord(0)).unwrap(),
        vec![[0.25, 0.75]]
    );
    assert!(
        l.warnings.iter().any(|w| w.contains("2 color components")),
        "{:?}",
        l.warnings
    );
}

fn ply_binary(header: &str, body: &[u8]) -> Vec<u8> {
    let mut b = format!("ply\nformat binary_little_endian 1.0\n{header}end_header\n").into_bytes();
    b.extend(body);
    b
}

const XYZ: &str = "property float x\nproperty float y\nproperty float z\n";

fn floats(xs: &[f32]) -> Vec<u8> {
    xs.iter().flat_map(|x| x.to_le_bytes()).collect()
}

#[test]
fn ply_malformed() {
    use MeshFormat::Ply;
    let tri = floats(&[0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0]);
    let header =
        format!("element vertex 3\n{XYZ}element face 1\nproperty list uchar int vertex_indices\n");
    let body_at = ply_binary(&header, &[]).len() as u64;
    let face = |idx: [i32; 3]| {
        let mut b = tri.clone();
        b.push(3);
        for i in idx {
            b.extend(i.to_le_bytes());
        }
        b
    };
    read(&ply_binary(&header, &face([0, 1, 2])), Ply);
    assert_err(
        &ply_binary(&header, &face([0, -1, 2])),
        Ply,
        Location::Byte(body_at + 36 + 1 + 4),
        &["negative vertex index -1"],
    );
    assert_err(
        &ply_binary(&header, &face([0, 1, 3])),
        Ply,
        Location::Byte(body_at + 36 + 1 + 8),
        &["vertex index 3 out of range", "3 vertices"],
    );
    // A face with 2 vertices.
    let mut two = tri.clone();
    two.extend([2, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0]);
    assert_err(
        &ply_binary(&header, &two),
        Ply,
        Location::Byte(body_at + 36),
        &["face with 2 vertices"],
    );
    // NaN and infinite coordinates, in a float and in a double.
    let mut nan = tri.clone();
    nan[16..20].copy_from_slice(&f32::NAN.to_le_bytes());
    assert_err(
        &ply_binary(&header, &{
            let mut b = nan;
            b.extend(&face([0, 1, 2])[36..]);
            b
        }),
        Ply,
        Location::Byte(body_at + 16),
        &["record 1", "property `y`", "NaN"],
    );
    let dheader = "element vertex 1\nproperty double x\nproperty double y\nproperty double z\n";
    let mut d = Vec::new();
    for x in [0.0f64, 1e300, 0.0] {
        d.extend(x.to_le_bytes());
    }
    assert_err(
        &ply_binary(dheader, &d),
        Ply,
        Location::Byte(ply_binary(dheader, &[]).len() as u64 + 8),
        &["infinite or beyond the f32 range"],
    );
    // Truncated body: inside the last index of a quad, and too short for the counts.
    let mut quad = face([0, 1, 2]);
    quad[36] = 4;
    quad.extend(2i32.to_le_bytes());
    let full = ply_binary(&header, &quad);
    assert_err(
        &full[..full.len() - 2],
        Ply,
        Location::Byte(body_at + 36),
        &[
            "truncated",
            "list of 4 `int` values needs 16 bytes, but only 14",
        ],
    );
    let h2 = format!("element vertex 2\nproperty list uchar uchar extra\n{XYZ}");
    let mut b2 = vec![5, 1, 2, 3, 4, 5];
    b2.extend(floats(&[0.0, 1.0, 2.0]));
    b2.push(0);
    b2.extend(floats(&[3.0, 4.0, 5.0]));
    let full = ply_binary(&h2, &b2);
    let at = ply_binary(&h2, &[]).len() as u64 + 27;
    assert_eq!(read(&full, Ply).mesh.positions[1], [3.0, 4.0, 5.0]);
    assert_err(
        &full[..full.len() - 2],
        Ply,
        Location::Byte(at),
        &["record 1, property `z`", "truncated", "file ends at byte"],
    );
    let full = ply_binary(&header, &face([0, 1, 2]));
    assert_err(
        &full[..body_at as usize + 30],
        Ply,
        Location::Byte(body_at),
        &["need at least 49 bytes", "body has 30"],
    );
    // Header problems.
    assert_err(
        b"PLY\n",
        Ply,
        Location::Line(1),
        &["first line must be `ply`"],
    );
    assert_err(
        b"ply\nformat binary_middle_endian 1.0\nend_header\n",
        Ply,
        Location::Line(2),
        &["unknown format `binary_middle_endian`"],
    );
    assert_err(
        b"ply\nformat ascii 2.0\nend_header\n",
        Ply,
        Location::Line(2),
        &["version `2.0`"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float16 x\nend_header\n",
        Ply,
        Location::Line(4),
        &["unknown property type `float16`"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty list float int x\nend_header\n",
        Ply,
        Location::Line(4),
        &["not an integer"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n",
        Ply,
        Location::Line(3),
        &["no property `z`"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nelement face 0\nproperty list uchar float vertex_indices\nend_header\n",
        Ply,
        Location::Line(7),
        &["non-integer items"],
    );
    // An unknown header line is skipped with a warning (tests/io_tolerant.rs); what follows
    // is still checked: here the vertex element lacks its coordinates.
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\nfrobnicate\nend_header\n",
        Ply,
        Location::Line(3),
        &["no property `x`"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\n",
        Ply,
        Location::Line(4),
        &["before the `end_header`"],
    );
    assert_err(
        b"ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n",
        Ply,
        Location::Whole,
        &["no `vertex` element"],
    );
    assert_err(
        b"ply\nelement vertex 0\nend_header\n",
        Ply,
        Location::Line(2),
        &["before the `format` line"],
    );
    // ASCII body problems.
    let ascii = |body: &str| {
        format!("ply\nformat ascii 1.0\nelement vertex 3\n{XYZ}element face 1\nproperty list uchar int vertex_indices\nend_header\n{body}").into_bytes()
    };
    read(&ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"), Ply);
    assert_err(
        &ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 -2\n"),
        Ply,
        Location::Line(13),
        &["negative vertex index -2"],
    );
    assert_err(
        &ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1 5\n"),
        Ply,
        Location::Line(13),
        &["vertex index 5 out of range"],
    );
    assert_err(
        &ascii("0 0 0\n1 abc 0\n0 1 0\n3 0 1 2\n"),
        Ply,
        Location::Line(11),
        &["`abc` is not a number"],
    );
    assert_err(
        &ascii("0 0 0\n1 inf 0\n0 1 0\n3 0 1 2\n"),
        Ply,
        Location::Line(11),
        &["infinite"],
    );
    assert_err(
        &ascii("0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n"),
        Ply,
        Location::Line(13),
        &["256 is out of range for type `uchar`"],
    );
    assert_err(
        &ascii("0 0 0\n1 0 0\n0 1 0\n3 0 1.5 2\n"),
        Ply,
        Location::Line(13),
        &["`1.5` is not an integer"],
    );
    assert_err(
        &ascii("0 0 0\n1 0 0\n0 1 0\n4 0 1 2            \n"),
        Ply,
        Location::Line(14),
        &["ends before this value"],
    );
}

#[test]
fn ply_header_of_many_statements_is_linear() {
    // 100 000 properties and elements: a quadratic duplicate check would take minutes.
    let mut h = String::from("ply\nformat ascii 1.0\nelement vertex 0\n");
    h.push_str(XYZ);
    for i in 0..50_000 {
        h.push_str(&format!("property uchar p{i}\n"));
    }
    for i in 0..50_000 {
        h.push_str(&format!("element e{i} 0\n"));
    }
    h.push_str("end_header\n");
    let l = read(h.as_bytes(), MeshFormat::Ply);
    assert!(l.warnings[0].contains("and 99980 more"), "{:?}", l.warnings);
}
