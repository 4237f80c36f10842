//! OBJ importer tests: the features read and warned about, texture coordinates and normals
//! per corner, negative indices, parts, and malformed input located at its line. Round trips
//! through the writer and the container: `tests/io_obj_round_trip.rs`. Helpers:
//! `tests/common/io_helpers.rs`.

mod common;

use common::io_helpers::*;
use lrmesh::fuzz_checks::assert_same_in_order;
use lrmesh::io::MeshFormat;
use lrmesh::mesh::{Part, Semantic};
use lrmesh::{Location, Mesh};

/// The values at corner `k` of triangle `t` of attribute `semantic`.
fn at(mesh: &Mesh, semantic: &Semantic, t: usize, k: usize) -> Vec<f32> {
    let a = mesh.attribute(semantic).expect("the attribute");
    a.value_f32(a.value_index(t, k, mesh.triangles[t]))
}

fn part(object: Option<&str>, group: Option<&str>, material: Option<&str>) -> Part {
    Part {
        object: object.map(String::from),
        group: group.map(String::from),
        material: material.map(String::from),
    }
}

fn parts_of(mesh: &Mesh) -> Vec<Part> {
    let parts = mesh.parts.as_ref().expect("parts");
    (0..mesh.triangle_count())
        .map(|t| parts.of(t).clone())
        .collect()
}

fn obj(text: &str) -> lrmesh::io::Loaded {
    read(text.as_bytes(), MeshFormat::Obj)
}

#[test]
fn obj_features() {
    let text = "# comment\nmtllib x.mtl\no thing\ng group\ns 1\nusemtl m\n\
v 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\nv 9 9 9\n\
vt 0 0\nvt 1 0\nvt 1 1 0\nvt 0 1\nvn 0 0 1\n\
f 1/1/1 2/2/1 3/3/1 4/4/1\nf -4/-4 -2/-2 -1/-1\nl 1 2\np 1\n";
    let l = obj(text);
    let m = &l.mesh;
    assert_eq!(m.vertex_count(), 5);
    assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3], [1, 3, 4]]);
    // 4 `vt` records for 5 vertices: per corner, the records as they are, each corner
    // naming the one its face gives (relative indices counted among the 4 `vt`).
    let tc = m.attribute(&Semantic::TexCoord(0)).unwrap();
    assert!(tc.is_per_corner());
    assert_eq!(tc.value_count(), 4);
    assert_eq!(
        tc.corners.as_deref().unwrap(),
        &[0, 1, 2, 0, 2, 3, 0, 2, 3][..]
    );
    // The second face gives no normal: its corners get one added zero value, and a warning.
    let n = m.attribute(&Semantic::Normal).unwrap();
    assert_eq!(n.value_count(), 2);
    assert_eq!(n.value_f32(1), vec![0.0, 0.0, 0.0]);
    assert_eq!(
        n.corners.as_deref().unwrap(),
        &[0, 0, 0, 0, 0, 0, 1, 1, 1][..]
    );
    let w = l.warnings.join("\n");
    assert!(w.contains("3 of 9 triangle corners have no normal"), "{w}");
    assert!(w.contains("skipped 2 line"), "{w}");
    assert!(!w.contains("`vt` records have a third"), "{w}");
    // Every triangle in the one part, and the library kept.
    assert_eq!(
        parts_of(m),
        vec![part(Some("thing"), Some("group"), Some("m")); 3]
    );
    assert_eq!(
        m.parts.as_ref().unwrap().material_libraries,
        vec!["x.mtl".to_string()]
    );

    // Forward references, i//n, continuation lines, unknown statements.
    let l = obj("f 1//1 2//1 \\\n 3//1\nvn 0 0 1\nv 0 0 0\nv 1 0 0\nv 0 1 0\nfrobnicate 1\n");
    assert_eq!(l.mesh.triangles, vec![[0, 1, 2]]);
    assert_eq!(at(&l.mesh, &Semantic::Normal, 0, 2), vec![0.0, 0.0, 1.0]);
    assert!(l.mesh.parts.is_none());
    assert!(
        l.warnings.iter().any(|w| w.contains("`frobnicate`")),
        "{:?}",
        l.warnings
    );

    // Colors on every v line; on only some lines they are dropped with a warning.
    let l = obj("v 0 0 0 1 0 0\nv 1 0 0 0 0.5 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
    assert_eq!(l.mesh.vertex_colors_rgba8().unwrap()[1], [0, 128, 0, 255]);
    let l = obj("v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(l.mesh.attribute(&Semantic::Color(0)).is_none());
    assert!(
        l.warnings[0].contains("colors were ignored"),
        "{:?}",
        l.warnings
    );

    // `w` of `vt` other than 0 and of `v` other than 1 are dropped, and said so.
    let l = obj("v 0 0 0 2\nv 1 0 0\nv 0 1 0\nvt 0.5 0.25 1\nf 1/1 2/1 3/1\n");
    assert_eq!(at(&l.mesh, &Semantic::TexCoord(0), 0, 0), vec![0.5, 0.25]);
    let w = l.warnings.join("\n");
    assert!(w.contains("1 `vt` records have a third component"), "{w}");
    assert!(w.contains("1 `v` records have a weight"), "{w}");
}

/// The finding: a vertex used with different texture coordinates keeps each one at
/// each corner (the old reader kept the first one used and warned).
#[test]
fn seams_are_kept_per_corner() {
    let l = obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n\
         f 1/1 2/2 3/3\nf 2/4 4/4 3/3\n",
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let m = &l.mesh;
    assert_eq!(m.vertex_count(), 4, "no vertex is split");
    let uv = |t, k| at(m, &Semantic::TexCoord(0), t, k);
    assert_eq!(uv(0, 1), vec![1.0, 0.0]);
    assert_eq!(uv(1, 0), vec![0.5, 0.5], "vertex 2 in the second face");
    assert_eq!(uv(1, 2), vec![0.0, 1.0]);

    // Two `vt` records with the same value: per corner, no warning.
    let l = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 0 0\nf 1/1 2/1 3/1\nf 1/2 3/2 2/2\n");
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    assert_eq!(
        l.mesh
            .attribute(&Semantic::TexCoord(0))
            .unwrap()
            .corners
            .as_deref(),
        Some(&[0, 0, 0, 1, 1, 1][..])
    );
}

/// As many records as vertices and every corner naming its vertex's record: per vertex, as
/// older writers (ours included) wrote; unreferenced vertices keep theirs.
#[test]
fn records_that_follow_the_vertices_are_per_vertex() {
    let l = obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 5 5 5\nvt 0 0\nvt 1 0\nvt 0 1\nvt 0.5 0.5\n\
         vn 0 0 1\nvn 0 0 1\nvn 0 0 1\nvn 1 0 0\nf 1/1/1 2/2/2 3/3/3\n",
    );
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    for semantic in [Semantic::TexCoord(0), Semantic::Normal] {
        assert!(!l.mesh.attribute(&semantic).unwrap().is_per_corner());
    }
    assert_eq!(
        l.mesh.vertex_values::<2>(&Semantic::TexCoord(0)).unwrap()[3],
        [0.5, 0.5]
    );
    // One corner naming another record makes the attribute per corner.
    let l = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nf 1/1 2/2 3/1\n");
    let tc = l.mesh.attribute(&Semantic::TexCoord(0)).unwrap();
    assert_eq!(tc.corners.as_deref(), Some(&[0, 1, 0][..]));
    assert_eq!(tc.value_count(), 3, "the unreferenced record is kept");
    // Records without faces: per vertex when there is one per vertex, else ignored.
    let l = obj("v 0 0 0\nv 1 0 0\nvt 0 0\nvt 1 1\n");
    assert_eq!(
        l.mesh.vertex_values::<2>(&Semantic::TexCoord(0)),
        Some(vec![[0.0, 0.0], [1.0, 1.0]])
    );
    let l = obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1 2 3\n");
    assert!(l.mesh.attribute(&Semantic::Normal).is_none());
    assert!(
        l.warnings[0].contains("1 `vn` records were ignored"),
        "{:?}",
        l.warnings
    );
}

#[test]
fn negative_indices_count_back_from_the_statement() {
    let l = obj(
        "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n\
         f -3/-3/-1 -2/-2/-1 -1/-1/-1\n\
         v 1 1 0\nvt 1 1\nvn 0 0 -1\n\
         f -3/-3/-2 -1/-1/-1 -2/-2/-1\n\
         f 2/2/1 -1/4/2 -2/-1/-2\n",
    );
    let m = &l.mesh;
    assert_eq!(m.triangles, vec![[0, 1, 2], [1, 3, 2], [1, 3, 2]]);
    let uv = |t, k| at(m, &Semantic::TexCoord(0), t, k);
    let n = |t, k| at(m, &Semantic::Normal, t, k);
    assert_eq!(uv(1, 0), vec![1.0, 0.0]);
    assert_eq!(uv(1, 1), vec![1.0, 1.0]);
    assert_eq!(uv(1, 2), vec![0.0, 1.0]);
    assert_eq!(n(1, 0), vec![0.0, 0.0, 1.0]);
    assert_eq!(n(1, 1), vec![0.0, 0.0, -1.0]);
    assert_eq!(n(2, 2), vec![0.0, 0.0, 1.0]);
    assert_eq!(uv(2, 2), vec![1.0, 1.0]);
}

#[test]
fn objects_groups_and_materials_become_parts() {
    let text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\n\
        f 1 2 3\n\
        mtllib a.mtl b.mtl\nmtllib a.mtl\n\
        o body\ng left  arm\nusemtl skin\nf 1 2 3 4\n\
        g\nf 1 2 4\n\
        usemtl cloth\ns off\nf 2 3 4\n\
        o\ng left arm\nusemtl skin\nf 3 2 1\n";
    let l = obj(text);
    assert!(l.warnings.is_empty(), "{:?}", l.warnings);
    let m = &l.mesh;
    let arm = part(Some("body"), Some("left arm"), Some("skin"));
    assert_eq!(
        parts_of(m),
        vec![
            Part::default(),
            arm.clone(),
            arm.clone(),
            part(Some("body"), None, Some("skin")),
            part(Some("body"), None, Some("cloth")),
            part(None, Some("left arm"), Some("skin")),
        ]
    );
    let parts = m.parts.as_ref().unwrap();
    assert_eq!(parts.parts.len(), 5, "each combination once");
    assert_eq!(parts.material_libraries, vec!["a.mtl", "b.mtl"]);

    // Written back: the same labels per triangle, in order, and the libraries.
    let written = write_to_vec(m, MeshFormat::Obj);
    let text = String::from_utf8(written.clone()).unwrap();
    assert!(text.contains("mtllib a.mtl\nmtllib b.mtl\n"), "{text}");
    assert_eq!(text.matches("usemtl").count(), 3, "{text}");
    assert_same_in_order(&read(&written, MeshFormat::Obj).mesh, m);

    // Labels with nothing in them are no parts.
    let l = obj("g\nusemtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    assert!(l.mesh.parts.is_none());
}

/// Names OBJ cannot hold are written in the nearest form it can, and read back so.
#[test]
fn part_names_are_written_as_obj_can_hold_them() {
    let mut m = Mesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        vec![[0, 1, 2]],
    );
    let mut parts = lrmesh::mesh::Parts::default();
    let i = parts.intern(part(Some("a\\"), Some(" two  words\t"), Some("#1")));
    parts.of_triangle.push(i);
    parts.material_libraries = vec!["my lib.mtl".into(), "x\\".into()];
    m.parts = Some(parts);
    let written = write_to_vec(&m, MeshFormat::Obj);
    let back = read(&written, MeshFormat::Obj).mesh;
    let back_parts = back.parts.as_ref().unwrap();
    assert_eq!(
        back_parts.of(0),
        &part(Some("a\\"), Some("two words"), Some("_1"))
    );
    assert_eq!(back_parts.material_libraries, vec!["my_lib.mtl", "x\\"]);
    assert_eq!(back.triangles, m.triangles, "no statement swallowed a face");
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
        &e(format!("{v3}vt 0 0\nf 1/1 2/-2 3/1\n")),
        Obj,
        Location::Line(5),
        &["relative texture coordinate index -2"],
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
            &e(format!("v 0 0 0\nvn 0 0 1\nvn 1 {bad} 0\n")),
            Obj,
            Location::Line(3),
            &["normal", what],
        );
        assert_err(
            &e(format!("v 0 0 0\nvt 0 0\n\nvt {bad} 0\n")),
            Obj,
            Location::Line(4),
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
    // No `v` and no `f`: not an OBJ file, whatever else it holds.
    for text in [
        "",
        "\n\n# only a comment\n",
        "o x\ng y\nmtllib z.mtl\n",
        "vt 0 0\nvn 0 0 1\n",
    ] {
        assert_err(
            text.as_bytes(),
            Obj,
            Location::Whole,
            &["no vertex or face statement"],
        );
    }
}

/// Per-corner colors, which OBJ cannot hold per corner, are written by splitting the vertices
/// whose corners differ in color; every corner keeps its position, color, texture coordinate
/// and normal.
#[test]
fn per_corner_colors_are_written_by_splitting_vertices() {
    use lrmesh::mesh::{Attribute, Values};
    let mut m = Mesh::new(
        vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
        vec![[0, 1, 2], [1, 3, 2]],
    );
    m.attributes.push(Attribute {
        semantic: Semantic::Color(0),
        components: 4,
        normalized: true,
        values: Values::U8(vec![255, 0, 0, 255, 0, 255, 0, 128]),
        corners: Some(vec![0, 0, 0, 1, 1, 0]),
    });
    m.attributes.push(Attribute::per_corner(
        Semantic::TexCoord(0),
        &[[0.0, 0.0], [0.5, 1.0]],
        vec![0, 1, 0, 1, 1, 0],
    ));
    m.attributes.push(Attribute::per_vertex(
        Semantic::Normal,
        &[
            [0.0, 0.0, 1.0],
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, -1.0],
        ],
    ));
    let back = read(&write_to_vec(&m, MeshFormat::Obj), MeshFormat::Obj);
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    let b = &back.mesh;
    assert_eq!(b.vertex_count(), 5, "vertex 1 is split, the others not");
    assert_eq!(b.triangle_count(), 2);
    for t in 0..2 {
        for k in 0..3 {
            let position = |m: &Mesh| m.positions[m.triangles[t][k] as usize];
            assert_eq!(position(b), position(&m), "triangle {t} corner {k}");
            for semantic in [Semantic::Color(0), Semantic::TexCoord(0), Semantic::Normal] {
                assert_eq!(
                    at(b, &semantic, t, k),
                    at(&m, &semantic, t, k),
                    "{semantic} at triangle {t} corner {k}"
                );
            }
        }
    }
}
