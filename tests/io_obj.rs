//! OBJ importer tests: the features read and warned about, and malformed input located at its
//! line. Helpers: `tests/common/io_helpers.rs`.

mod common;

use common::io_helpers::*;
use lrmesh::io::MeshFormat;
use lrmesh::Location;

// ---------------------------------------------------------------------------------------------
// OBJ

#[test]
fn obj_features() {
    let text = b"# comment\nmtllib x.mtl\no thing\ng group\ns 1\nusemtl m\n\
v 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\nv 9 9 9\n\
vt 0 0\nvt 1 0\nvt 1 1 0\nvt 0 1\nvn 0 0 1\n\
f 1/1/1 2/2/1 3/3/1 4/4/1\nf -4/-4 -2/-2 -1/-1\nl 1 2\np 1\n";
    let l = read(text, MeshFormat::Obj);
    let m = &l.mesh;
    assert_eq!(m.vertex_count(), 5);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [1, 3, 4]]);
    // vt has 4 records for 5 vertices, so the first corner rule applies; vertex 4 gets
    // vt 4 from the second face, nothing is missing.
    assert_eq!(
        m.texcoords.as_ref().unwrap(),
        &vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.0, 1.0]]
    );
    // vn only reaches the vertices of the first face.
    assert_eq!(m.normals.as_ref().unwrap()[4], [0.0, 0.0, 0.0]);
    let w = l.warnings.join("\n");
    assert!(w.contains("1 of 5 vertices have no normals"), "{w}");
    assert!(w.contains("skipped 2 line"), "{w}");
    assert!(w.contains("a seam"), "{w}");

    // Forward references, i//n, continuation lines, unknown statements.
    let text = b"f 1//1 2//1 \\\n 3//1\nvn 0 0 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nfrobnicate 1\n";
    let l = read(text, MeshFormat::Obj);
    assert_eq!(l.mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(l.mesh.normals.as_ref().unwrap().len(), 3);
    assert!(
        l.warnings.iter().any(|w| w.contains("`frobnicate`")),
        "{:?}",
        l.warnings
    );

    // Colors on every v line; on only some lines they are dropped with a warning.
    let l = read(
        b"v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 1\nf 1 2 3\n",
        MeshFormat::Obj,
    );
    assert_eq!(l.mesh.colors.unwrap()[1], [0, 128, 0, 255]);
    let l = read(
        b"v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
        MeshFormat::Obj,
    );
    assert!(l.mesh.colors.is_none());
    assert!(
        l.warnings[0].contains("colors were ignored"),
        "{:?}",
        l.warnings
    );

    // Seams: vertex 2 (1-based) gets different texture coordinates in two faces.
    let l = read(
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\nf 1/1 2/2 3/3\nf 2/4 4/4 3/3\n",
        MeshFormat::Obj,
    );
    assert_eq!(l.mesh.texcoords.as_ref().unwrap()[1], [1.0, 0.0]);
    assert!(
        l.warnings
            .iter()
            .any(|w| w.starts_with("1 vertices are used with differing texture coordinates")),
        "{:?}",
        l.warnings
    );
    // Two vt records with the same value are no seam.
    let l = read(
        b"v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/2 3/2 2/2\n",
        MeshFormat::Obj,
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
}

#[test]
fn obj_malformed() {
    use MeshFormat::Obj;
    let v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    let e = |s: String| s.into_bytes();
    assert_err(
        &e(format!("{v3}f 1 2 3\nf 1 2 4\n")),
        Obj,
        Location::Line(5),
        &["vertex index 4 out of range", "3 vertices"],
    );
    assert_err(
        &e(format!("{v3}f 1 2 3\nf 1 -4 3\n")),
        Obj,
        Location::Line(5),
        &["relative vertex index -4"],
    );
    assert_err(
        &e(format!("{v3}f 1 0 3\n")),
        Obj,
        Location::Line(4),
        &["index 0"],
    );
    assert_err(
        &e(format!("{v3}f 1 2\n")),
        Obj,
        Location::Line(4),
        &["2 vertices", "at least 3"],
    );
    assert_err(
        &e(format!("{v3}vt 0 0\nf 1/1 2/2 3/1\n")),
        Obj,
        Location::Line(5),
        &["texture coordinate index 2 out of range"],
    );
    assert_err(
        &e(format!("{v3}vn 0 0 1\nf 1//1 2//1 3//2\n")),
        Obj,
        Location::Line(5),
        &["normal index 2 out of range"],
    );
    for corner in ["1/", "1/2/", "1/1/1/1", "/1", "a", "1//"] {
        let err = parse_err(&e(format!("{v3}vt 0 0\nvn 0 0 1\nf {corner} 2 3\n")), Obj);
        assert_eq!(err.location, Location::Line(6), "{err}");
    }
    for (bad, what) in [
        ("nan", "NaN"),
        ("inf", "infinite"),
        ("1e40", "infinite"),
        ("x", "not a number"),
    ] {
        assert_err(
            &e(format!("v 0 0 0\nv 1 {bad} 0\n")),
            Obj,
            Location::Line(2),
            &["coordinate", what],
        );
        assert_err(
            &e(format!("vn 0 0 1\nvn 1 {bad} 0\n")),
            Obj,
            Location::Line(2),
            &["normal", what],
        );
        assert_err(
            &e(format!("vt 0 0\n\nvt {bad} 0\n")),
            Obj,
            Location::Line(3),
            &["texture coordinate", what],
        );
    }
    assert_err(b"v 0 0\n", Obj, Location::Line(1), &["found 2"]);
    assert_err(b"v 0 0 0 1 1\n", Obj, Location::Line(1), &["found 5"]);
    assert_err(b"vn 0 0\n", Obj, Location::Line(1), &["found 2"]);
    assert_err(b"vt\n", Obj, Location::Line(1), &["found 0"]);
    assert_err(
        b"f 1 2 99999999999\n",
        Obj,
        Location::Line(1),
        &["out of range"],
    );
}
