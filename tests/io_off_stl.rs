//! OFF and STL importer tests: hand-written inputs of every variant, and malformed input
//! located at its line or byte. Helpers: `tests/common/io_helpers.rs`.

mod common;

use common::io_helpers::*;
use lrmesh::io::MeshFormat;
use lrmesh::mesh::Semantic;
use lrmesh::Location;

// ---------------------------------------------------------------------------------------------
// OFF

#[test]
fn off_variants() {
    // Counts on the header line, comments everywhere, blank lines, a quad, a face color.
    let l = read(
        b"# c\n\nOFF 4 1 0 # counts here\n0 0 0\n1 0 0 # c\n\n1 1 0\n0 1 0\n4 0 1 2 3 255 0 0\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.triangles, vec![[0, 1, 2], [0, 2, 3]]);
    assert!(l.warnings.is_empty());

    // NOFF, STOFF, STCNOFF: the attribute order x y z [n] [c] [st].
    let l = read(
        b"NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 -1\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(
        l.mesh.vertex_values::<3>(&Semantic::Normal).unwrap()[2],
        [0.0, 0.0, -1.0]
    );
    let l = read(
        b"STOFF\n3 1\n0 0 0 0.5 1\n1 0 0 1 1\n0 1 0 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(
        l.mesh.vertex_values::<2>(&Semantic::TexCoord(0)).unwrap(),
        vec![[0.5, 1.0], [1.0, 1.0], [0.0, 0.0]]
    );
    let l = read(
        b"STCNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 0.5 1\n1 0 0 0 0 1 0 255 0 128 1 1\n0 1 0 0 0 1 0 0 255 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    let m = l.mesh;
    assert_eq!(
        m.vertex_colors_rgba8().unwrap(),
        vec![[255, 0, 0, 255], [0, 255, 0, 128], [0, 0, 255, 255]]
    );
    assert_eq!(
        m.vertex_values::<2>(&Semantic::TexCoord(0)).unwrap(),
        vec![[0.5, 1.0], [1.0, 1.0], [0.0, 0.0]]
    );
    assert_eq!(
        m.vertex_values::<3>(&Semantic::Normal).unwrap()[0],
        [0.0, 0.0, 1.0]
    );

    // Float colors (some component has a decimal point) are fractions of 255.
    let l = read(
        b"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0.5 0.25 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(
        l.mesh.vertex_colors_rgba8().unwrap(),
        vec![[255, 0, 0, 255], [128, 64, 0, 255], [0, 0, 255, 255]]
    );
    // Integer colors all at most 1 are fractions too.
    let l = read(
        b"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.vertex_colors_rgba8().unwrap()[1], [0, 255, 0, 255]);

    // A plain OFF with colors on every vertex line has colors; on some lines, none.
    let l = read(
        b"OFF\n3 1 0\n0 0 0 10 20 30\n1 0 0 1 2 3 4\n0 1 0 0 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.vertex_colors_rgba8().unwrap()[1], [1, 2, 3, 4]);
    let l = read(
        b"OFF\n3 1 0\n0 0 0 10 20 30\n1 0 0\n0 1 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert!(l.mesh.attribute(&Semantic::Color(0)).is_none());
    assert!(l.warnings[0].contains("only 1 of 3"), "{:?}", l.warnings);

    // Unreferenced vertices stay, repeated vertices give degenerate triangles, CRLF works.
    let l = read(
        b"OFF\r\n4 1 0\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n9 9 9\r\n4 0 1 1 2\r\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.vertex_count(), 4);
    assert_eq!(l.mesh.triangles, vec![[0, 1, 1], [0, 1, 2]]);

    // Content after the last face is a warning.
    let l = read(
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert!(l.warnings[0].contains("line 7"), "{:?}", l.warnings);
}

#[test]
fn off_malformed() {
    use MeshFormat::Off;
    let v3 = "0 0 0\n1 0 0\n0 1 0\n";
    let e = |s: String| s.into_bytes();
    assert_err(b"", Off, Location::Whole, &["empty"]);
    assert_err(b"PLY\n", Off, Location::Line(1), &["`PLY`"]);
    assert_err(b"4OFF\n1 0 0\n0 0 0 0\n", Off, Location::Line(1), &["4OFF"]);
    assert_err(
        b"nOFF\n3\n1 0 0\n0 0 0\n",
        Off,
        Location::Line(1),
        &["nOFF"],
    );
    assert_err(b"OFF BINARY\n", Off, Location::Line(1), &["binary"]);
    assert_err(b"OFF\n", Off, Location::Line(2), &["ends before"]);
    assert_err(b"OFF\n3\n", Off, Location::Line(2), &["found 1 values"]);
    assert_err(
        b"OFF\n3 x 0\n",
        Off,
        Location::Line(2),
        &["`x` is not an integer"],
    );
    assert_err(
        b"OFF\n-3 1 0\n",
        Off,
        Location::Line(2),
        &["`-3` is negative"],
    );
    // Index out of range, negative index, two-vertex face, short face.
    assert_err(
        &e(format!("OFF\n3 1 0\n{v3}3 0 1 3\n")),
        Off,
        Location::Line(6),
        &["face 0", "index 3 out of range", "3 vertices"],
    );
    assert_err(
        &e(format!("OFF\n3 1 0\n{v3}3 0 -1 2\n")),
        Off,
        Location::Line(6),
        &["-1 out of range"],
    );
    assert_err(
        &e(format!("OFF\n3 2 0\n{v3}3 0 1 2\n2 0 1 # padding\n")),
        Off,
        Location::Line(7),
        &["face 1", "2 vertices", "at least 3"],
    );
    assert_err(
        &e(format!("OFF\n3 1 0\n{v3}4 0 1 2\n")),
        Off,
        Location::Line(6),
        &["declares 4 vertices but lists 3"],
    );
    // Truncated: faces missing, vertices missing.
    assert_err(
        &e(format!("OFF\n3 2 0\n{v3}3 0 1 2\n# padding\n")),
        Off,
        Location::Line(8),
        &["ends after 1 of 2 faces"],
    );
    assert_err(
        b"OFF\n3 1 0\n0 0 0\n1 0 0\n# no more vertices, but enough bytes for the counts\n",
        Off,
        Location::Line(6),
        &["ends after 2 of 3 vertices"],
    );
    // NaN, infinity, overflow and garbage in coordinates, normals and texture coordinates.
    for (bad, what) in [
        ("nan", "NaN"),
        ("NaN", "NaN"),
        ("inf", "infinite"),
        ("-infinity", "infinite"),
        ("1e39", "infinite"),
        ("1.2.3", "not a number"),
        ("0x10", "not a number"),
    ] {
        assert_err(
            &e(format!("OFF\n3 1 0\n0 0 0\n1 {bad} 0\n0 1 0\n3 0 1 2\n")),
            Off,
            Location::Line(4),
            &["vertex 1", "coordinate", what],
        );
        assert_err(
            &e(format!(
                "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 {bad} 1\n3 0 1 2\n"
            )),
            Off,
            Location::Line(5),
            &["vertex 2", "normal", what],
        );
        assert_err(
            &e(format!(
                "STOFF\n3 1 0\n0 0 0 0 {bad}\n1 0 0 0 0\n0 1 0 0 0\n3 0 1 2\n"
            )),
            Off,
            Location::Line(3),
            &["texture coordinate", what],
        );
    }
    // Wrong number of values on a vertex line.
    assert_err(
        b"OFF\n3 1 0\n0 0 0\n1 0\n0 1 0\n3 0 1 2 # padding\n",
        Off,
        Location::Line(4),
        &["found 2"],
    );
    assert_err(
        b"COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0\n0 1 0 1 1 1\n3 0 1 2\n",
        Off,
        Location::Line(4),
        &["expected 6 or 7"],
    );
    // Integer colors above 255, negative colors.
    assert_err(
        b"COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 300 0 0\n0 1 0 1 1 1\n3 0 1 2\n",
        Off,
        Location::Line(4),
        &["300", "0..=255"],
    );
    assert_err(
        b"COFF\n3 1 0\n0 0 0 1 1 1\n1 0 0 -3 0 0\n0 1 0 1 1 1\n3 0 1 2\n",
        Off,
        Location::Line(4),
        &["negative color"],
    );
}

// ---------------------------------------------------------------------------------------------
// STL

#[test]
fn stl_ascii_variants() {
    // Upper case, a quad, two solids, odd normals, no final newline.
    let text = b"  SOLID part one\nFACET NORMAL nan nan nan\nOUTER LOOP\nVERTEX 0 0 0\nVERTEX 1 0 0\nVERTEX 1 1 0\nVERTEX 0 1 0\nENDLOOP\nENDFACET\nENDSOLID part one\n\
solid two\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid";
    let l = read(text, MeshFormat::Stl);
    assert_eq!(l.mesh.triangle_count(), 3);
    assert_eq!(l.mesh.vertex_count(), 7);
    assert_eq!(l.mesh.triangles[1], [0, 2, 3]);
    assert!(l.warnings.is_empty());
    let welded = read_weld(text, true);
    assert_eq!(welded.vertex_count(), 4);
    // Missing endsolid after a complete facet: a warning.
    let l = read(
        b"solid\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\n",
        MeshFormat::Stl,
    );
    assert_eq!(l.mesh.triangle_count(), 1);
    assert!(l.warnings[0].contains("endsolid"));
    // A binary file whose header starts with "solid" is still binary.
    let m = load("tetrahedron.off");
    let mut b = stl_binary(&m);
    b[..5].copy_from_slice(b"solid");
    assert_eq!(read_weld(&b, true).vertex_count(), 4);
}

#[test]
fn stl_malformed() {
    use MeshFormat::Stl;
    let facet = |v: &str| {
        format!("solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex {v}\nvertex 1 1 0\nendloop\nendfacet\nendsolid x\n")
            .into_bytes()
    };
    for (bad, what) in [
        ("nan", "NaN"),
        ("inf", "infinite"),
        ("1e39", "infinite"),
        ("a", "not a number"),
    ] {
        assert_err(
            &facet(&format!("1 {bad} 0")),
            Stl,
            Location::Line(5),
            &["coordinate", what],
        );
    }
    assert_err(
        &facet("1 0"),
        Stl,
        Location::Line(6),
        &["`vertex` is not a number"],
    );
    assert_err(
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\nendfacet\nendsolid\n",
        Stl,
        Location::Line(2),
        &["facet with 2 vertices"],
    );
    assert_err(
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\n",
        Stl,
        Location::Line(8),
        &["ends where `endfacet` was expected"],
    );
    assert_err(
        b"solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\nendloop\nendfacet\nendsolid\ngarbage\n",
        Stl,
        Location::Line(10),
        &["expected `solid`", "`garbage`"],
    );
    assert_err(b"hello", Stl, Location::Whole, &["not an STL file"]);
    // Binary: truncated, trailing bytes, NaN and infinite coordinates.
    let m = load("tetrahedron.off");
    let b = stl_binary(&m);
    assert_eq!(b.len(), 84 + 4 * 50);
    assert_err(
        &b[..b.len() - 1],
        Stl,
        Location::Byte(283),
        &["truncated", "4 triangles", "284 bytes"],
    );
    let mut long = b.clone();
    long.push(0);
    assert_err(
        &long,
        Stl,
        Location::Byte(284),
        &["1 bytes after the 4 triangles"],
    );
    for (x, what) in [(f32::NAN, "NaN"), (f32::NEG_INFINITY, "infinite")] {
        let mut bad = b.clone();
        let at = 84 + 50 + 12 + 12 + 4;
        bad[at..at + 4].copy_from_slice(&x.to_le_bytes());
        assert_err(
            &bad,
            Stl,
            Location::Byte(at as u64),
            &["triangle 1, vertex 1", what],
        );
    }
}
