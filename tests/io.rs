//! Importer and exporter tests: the corpus, round trips, hand-written inputs for each format,
//! malformed input, truncation at every length and the fuzz regressions.

use std::path::{Path, PathBuf};

use lrmesh::io::{
    obj, off, ply, read_mesh, read_mesh_bytes, stl, write_mesh, write_mesh_to, Loaded, MeshFormat,
    ReadOptions,
};
use lrmesh::{Error, Location, Mesh, ParseError};

// ---------------------------------------------------------------------------------------------
// Helpers

fn repo() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn corpus_dir() -> PathBuf {
    repo().join("corpus/meshes")
}

struct Entry {
    name: String,
    v: usize,
    t: usize,
    dup_positions: usize,
    unreferenced: usize,
}

fn manifest() -> Vec<Entry> {
    let text = std::fs::read_to_string(corpus_dir().join("MANIFEST.tsv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split('\t').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (cm, cv, ct, cd, cu) = (
        col("mesh"),
        col("V"),
        col("T"),
        col("dup_positions"),
        col("unreferenced_V"),
    );
    lines
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            Entry {
                name: f[cm].to_string(),
                v: f[cv].parse().unwrap(),
                t: f[ct].parse().unwrap(),
                dup_positions: f[cd].parse().unwrap(),
                unreferenced: f[cu].parse().unwrap(),
            }
        })
        .collect()
}

fn load(name: &str) -> Mesh {
    read_mesh(&corpus_dir().join(name), &ReadOptions::default())
        .unwrap_or_else(|e| panic!("{name}: {e}"))
        .mesh
}

fn read(bytes: &[u8], format: MeshFormat) -> Loaded {
    read_mesh_bytes(bytes, format, &ReadOptions::default()).unwrap_or_else(|e| {
        panic!(
            "{e}\ninput:\n{}",
            String::from_utf8_lossy(&bytes[..bytes.len().min(2000)])
        )
    })
}

fn read_weld(bytes: &[u8], weld: bool) -> Mesh {
    read_mesh_bytes(bytes, MeshFormat::Stl, &ReadOptions { weld })
        .unwrap()
        .mesh
}

fn parse_err(bytes: &[u8], format: MeshFormat) -> ParseError {
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
fn assert_err(bytes: &[u8], format: MeshFormat, location: Location, needles: &[&str]) {
    let e = parse_err(bytes, format);
    assert_eq!(e.format, format.name(), "{e}");
    assert_eq!(e.location, location, "{e}");
    for n in needles {
        assert!(e.message.contains(n), "`{n}` not in: {e}");
    }
}

/// Every float of a mesh as bits, so that -0.0 and 0.0 differ.
type Bits = (
    Vec<[u32; 3]>,
    Vec<[u32; 3]>,
    Option<Vec<[u32; 3]>>,
    Option<Vec<[u32; 2]>>,
    Option<Vec<[u8; 4]>>,
);

fn bits(m: &Mesh) -> Bits {
    (
        m.positions.iter().map(|p| p.map(f32::to_bits)).collect(),
        m.triangles.clone(),
        m.normals
            .as_ref()
            .map(|n| n.iter().map(|p| p.map(f32::to_bits)).collect()),
        m.texcoords
            .as_ref()
            .map(|n| n.iter().map(|p| p.map(f32::to_bits)).collect()),
        m.colors.clone(),
    )
}

fn write_to_vec(mesh: &Mesh, format: MeshFormat) -> Vec<u8> {
    let mut out = Vec::new();
    write_mesh_to(&mut out, mesh, format).unwrap();
    out
}

fn stl_binary(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    stl::write_binary(&mut out, mesh).unwrap();
    out
}

fn stl_ascii(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    stl::write_ascii(&mut out, mesh).unwrap();
    out
}

/// A small mesh with awkward floats, a degenerate triangle and an unreferenced vertex.
fn awkward_mesh() -> Mesh {
    Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [-0.0, 1e-45, f32::MAX],
            [f32::MIN_POSITIVE, -1e-40, 123_456.79],
            [1e7, -3.4e38, 0.1],
            [5.0, -5.0, 1.0 / 3.0],
        ],
        vec![[0, 1, 2], [0, 2, 3], [3, 4, 5], [1, 1, 2], [5, 4, 3]],
    )
}

fn with_attributes(mut m: Mesh, normals: bool, texcoords: bool, colors: bool) -> Mesh {
    let n = m.vertex_count();
    if normals {
        m.normals = Some(
            (0..n)
                .map(|i| match i % 3 {
                    0 => [-0.0, 0.0, 1.0],
                    1 => [0.577_350_26, -0.577_350_26, 1e-42],
                    _ => [i as f32, -1e30, 0.25],
                })
                .collect(),
        );
    }
    if texcoords {
        m.texcoords = Some(
            (0..n)
                .map(|i| [i as f32 / 7.0, if i == 2 { -0.0 } else { 1e-20 }])
                .collect(),
        );
    }
    if colors {
        m.colors = Some(
            (0..n)
                .map(|i| {
                    let i = i as u8;
                    [i * 40, 255 - i, 1, if i == 3 { 0 } else { 255 }]
                })
                .collect(),
        );
    }
    m
}

// ---------------------------------------------------------------------------------------------
// Corpus

#[test]
fn corpus_counts_match_manifest() {
    let entries = manifest();
    assert!(entries.len() >= 18);
    for e in entries {
        let loaded = read_mesh(&corpus_dir().join(&e.name), &ReadOptions::default())
            .unwrap_or_else(|err| panic!("{}: {err}", e.name));
        let m = &loaded.mesh;
        assert_eq!(
            (m.vertex_count(), m.triangle_count()),
            (e.v, e.t),
            "{}",
            e.name
        );
        m.validate().unwrap();
        assert!(
            loaded.warnings.is_empty(),
            "{}: {:?}",
            e.name,
            loaded.warnings
        );
    }
}

#[test]
fn shared_meshes_when_present() {
    // The two large meshes of the shared set are not in the repository; check them when the
    // shared folder is next to it.
    let shared = repo().join("../shared/meshes");
    let Ok(text) = std::fs::read_to_string(shared.join("MANIFEST.tsv")) else {
        return;
    };
    for line in text.lines().skip(1) {
        let f: Vec<&str> = line.split('\t').collect();
        let path = shared.join(f[0]);
        if f.len() < 3 || !path.exists() {
            continue;
        }
        let m = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        assert_eq!(m.vertex_count(), f[1].parse::<usize>().unwrap(), "{}", f[0]);
        assert_eq!(
            m.triangle_count(),
            f[2].parse::<usize>().unwrap(),
            "{}",
            f[0]
        );
    }
}

#[test]
fn bunny_obj_and_ply_are_identical() {
    let a = load("bunny_small.obj");
    let b = load("bunny_small.ply");
    assert_eq!(a, b);
    assert_eq!(bits(&a), bits(&b));
}

#[test]
fn corpus_through_stl_with_and_without_weld() {
    let entries = manifest();
    for name in [
        "tetrahedron.off",
        "cube_quad.off",
        "icosahedron.off",
        "hedra_open.off",
        "torus_quad.off",
        "3torus.off",
        "bunny_small.ply",
    ] {
        let e = entries.iter().find(|e| e.name == name).unwrap();
        let m = load(name);
        for (kind, bytes) in [("binary", stl_binary(&m)), ("ascii", stl_ascii(&m))] {
            let ctx = format!("{name} as {kind} STL");
            let plain = read_weld(&bytes, false);
            assert_eq!(plain.triangle_count(), m.triangle_count(), "{ctx}");
            assert_eq!(plain.vertex_count(), 3 * m.triangle_count(), "{ctx}");
            for (t, (a, b)) in plain.triangles.iter().zip(&m.triangles).enumerate() {
                assert_eq!(*a, [3 * t as u32, 3 * t as u32 + 1, 3 * t as u32 + 2]);
                for k in 0..3 {
                    assert_eq!(
                        plain.positions[a[k] as usize], m.positions[b[k] as usize],
                        "{ctx}"
                    );
                }
            }
            let welded = read_weld(&bytes, true);
            welded.validate().unwrap();
            assert_eq!(welded.triangle_count(), m.triangle_count(), "{ctx}");
            if e.dup_positions == 0 {
                assert_eq!(welded.vertex_count(), e.v - e.unreferenced, "{ctx}");
            }
            for (a, b) in welded.triangles.iter().zip(&m.triangles) {
                for k in 0..3 {
                    assert_eq!(
                        welded.positions[a[k] as usize], m.positions[b[k] as usize],
                        "{ctx}"
                    );
                }
            }
        }
    }
}

#[test]
fn weld_merges_negative_zero_in_first_seen_order() {
    let m = Mesh::new(
        vec![
            [0.0, 1.0, 0.0],
            [-0.0, 1.0, -0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        vec![[2, 0, 3], [1, 3, 2]],
    );
    for bytes in [stl_binary(&m), stl_ascii(&m)] {
        let w = read_weld(&bytes, true);
        assert_eq!(
            w.positions,
            vec![[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
        );
        assert_eq!(w.triangles, vec![[0, 1, 2], [1, 2, 0]]);
        assert_eq!(
            w.positions[1][0].to_bits(),
            0.0f32.to_bits(),
            "first seen kept"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// Round trips

#[test]
fn round_trips_keep_every_bit() {
    for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
        for (normals, texcoords, colors) in [
            (false, false, false),
            (true, false, false),
            (false, true, false),
            (false, false, true),
            (true, true, false),
            (true, false, true),
            (false, true, true),
            (true, true, true),
        ] {
            let m = with_attributes(awkward_mesh(), normals, texcoords, colors);
            let bytes = write_to_vec(&m, format);
            let back = read(&bytes, format);
            let ctx = format!(
                "{format} normals={normals} texcoords={texcoords} colors={colors}:\n{}",
                String::from_utf8_lossy(&bytes)
            );
            assert!(back.warnings.is_empty(), "{ctx}\n{:?}", back.warnings);
            assert_eq!(back.mesh, m, "{ctx}");
            assert_eq!(bits(&back.mesh), bits(&m), "{ctx}");
        }
    }
}

#[test]
fn round_trips_of_every_color_value() {
    // Opaque colors (OBJ writes no alpha then), colors with alpha, and colors made only of 0
    // and 1, which a text reader would take for fractions if written as integers.
    let n = 256;
    let positions: Vec<[f32; 3]> = (0..n).map(|i| [i as f32, 0.0, 0.0]).collect();
    let palettes: [Vec<[u8; 4]>; 3] = [
        (0..n).map(|i| [i as u8, 255 - i as u8, 7, 255]).collect(),
        (0..n).map(|i| [0, 1, 255, i as u8]).collect(),
        (0..n).map(|i| [(i % 2) as u8, 1, 0, 1]).collect(),
    ];
    for colors in palettes {
        let mut m = Mesh::new(positions.clone(), vec![[0, 1, 2]]);
        m.colors = Some(colors);
        for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
            let back = read(&write_to_vec(&m, format), format);
            assert_eq!(back.mesh.colors, m.colors, "{format}");
        }
    }
}

#[test]
fn round_trip_of_an_empty_mesh() {
    let m = Mesh::default();
    for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
        assert_eq!(read(&write_to_vec(&m, format), format).mesh, m, "{format}");
    }
    let empty = read_weld(&stl_binary(&m), false);
    assert_eq!(empty, m);
    assert_eq!(read_weld(&stl_ascii(&m), false), m);
}

#[test]
fn corpus_round_trips() {
    for name in [
        "double-torus-3-holes.off",
        "bunny_small.obj",
        "polygon_mesh.off",
    ] {
        let m = load(name);
        for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
            let back = read(&write_to_vec(&m, format), format).mesh;
            assert_eq!(bits(&back), bits(&m), "{name} as {format}");
        }
    }
}

#[test]
fn write_mesh_by_extension() {
    let dir = std::env::temp_dir().join(format!("lrmesh-io-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let m = with_attributes(awkward_mesh(), true, true, true);
    for ext in ["obj", "OFF", "ply"] {
        let path = dir.join(format!("m.{ext}"));
        write_mesh(&path, &m).unwrap();
        let back = read_mesh(&path, &ReadOptions::default()).unwrap();
        assert_eq!(bits(&back.mesh), bits(&m), "{ext}");
    }
    assert!(matches!(
        write_mesh(&dir.join("m.stl"), &m),
        Err(Error::UnknownFormat { .. })
    ));
    assert!(matches!(
        write_mesh(&dir.join("m.xyz"), &m),
        Err(Error::UnknownFormat { .. })
    ));
    assert!(matches!(
        write_mesh_to(Vec::new(), &m, MeshFormat::Stl),
        Err(Error::UnknownFormat { .. })
    ));
    // A bad file read through a path names the path.
    let bad = dir.join("bad.off");
    std::fs::write(&bad, "OFF\n1 0 0\n0 0 x\n").unwrap();
    match read_mesh(&bad, &ReadOptions::default()) {
        Err(Error::Parse(e)) => {
            assert_eq!(e.file.as_deref(), Some(bad.as_path()));
            assert!(e.to_string().contains("bad.off"), "{e}");
            assert!(e.to_string().contains("OFF line 3"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        read_mesh(&dir.join("missing.ply"), &ReadOptions::default()),
        Err(Error::Io { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn writers_refuse_invalid_meshes() {
    let mut m = Mesh::new(vec![[0.0; 3]], vec![[0, 0, 1]]);
    assert!(matches!(
        write_mesh_to(Vec::new(), &m, MeshFormat::Off),
        Err(Error::InvalidMesh(_))
    ));
    assert!(off::write(Vec::new(), &m).is_err());
    assert!(obj::write(Vec::new(), &m).is_err());
    assert!(ply::write(Vec::new(), &m).is_err());
    assert!(stl::write_binary(Vec::new(), &m).is_err());
    m.triangles.clear();
    m.normals = Some(vec![]);
    assert!(off::write(Vec::new(), &m).is_err());
}

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
    assert_eq!(l.mesh.normals.unwrap()[2], [0.0, 0.0, -1.0]);
    let l = read(
        b"STOFF\n3 1\n0 0 0 0.5 1\n1 0 0 1 1\n0 1 0 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(
        l.mesh.texcoords.unwrap(),
        vec![[0.5, 1.0], [1.0, 1.0], [0.0, 0.0]]
    );
    let l = read(
        b"STCNOFF\n3 1 0\n0 0 0 0 0 1 255 0 0 0.5 1\n1 0 0 0 0 1 0 255 0 128 1 1\n0 1 0 0 0 1 0 0 255 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    let m = l.mesh;
    assert_eq!(
        m.colors.unwrap(),
        vec![[255, 0, 0, 255], [0, 255, 0, 128], [0, 0, 255, 255]]
    );
    assert_eq!(
        m.texcoords.unwrap(),
        vec![[0.5, 1.0], [1.0, 1.0], [0.0, 0.0]]
    );
    assert_eq!(m.normals.unwrap()[0], [0.0, 0.0, 1.0]);

    // Float colors (some component has a decimal point) are fractions of 255.
    let l = read(
        b"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0.5 0.25 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(
        l.mesh.colors.unwrap(),
        vec![[255, 0, 0, 255], [128, 64, 0, 255], [0, 0, 255, 255]]
    );
    // Integer colors all at most 1 are fractions too.
    let l = read(
        b"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 0 1 0\n0 1 0 0 0 1\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.colors.unwrap()[1], [0, 255, 0, 255]);

    // A plain OFF with colors on every vertex line has colors; on some lines, none.
    let l = read(
        b"OFF\n3 1 0\n0 0 0 10 20 30\n1 0 0 1 2 3 4\n0 1 0 0 0 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert_eq!(l.mesh.colors.unwrap()[1], [1, 2, 3, 4]);
    let l = read(
        b"OFF\n3 1 0\n0 0 0 10 20 30\n1 0 0\n0 1 0\n3 0 1 2\n",
        MeshFormat::Off,
    );
    assert!(l.mesh.colors.is_none());
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

// ---------------------------------------------------------------------------------------------
// PLY

/// A PLY file with a big-endian body: extra vertex properties (a float, a list) before and
/// after the coordinates, an extra face property and an extra element between the two.
fn big_endian_ply() -> Vec<u8> {
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
    assert_eq!(m.colors.as_ref().unwrap()[3], [30, 20, 30, 255]);
    assert_eq!(m.texcoords.as_ref().unwrap()[2], [0.5, 1.0]);
    assert!(m.normals.is_none());
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
    assert_eq!(m.normals.as_ref().unwrap()[3], [0.0, 0.0, -1.0]);
    assert_eq!(
        m.colors.as_ref().unwrap(),
        &vec![
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
    assert_eq!(l.mesh.colors.unwrap(), vec![[255, 0, 7, 255]]);
    assert_eq!(l.mesh.texcoords.unwrap(), vec![[0.25, 0.75]]);
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
    assert_err(
        b"ply\nformat ascii 1.0\nelement vertex 1\nfrobnicate\nend_header\n",
        Ply,
        Location::Line(4),
        &["unknown header statement `frobnicate`"],
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

// ---------------------------------------------------------------------------------------------
// Fuzz seeds and regressions

fn fuzz_target_format(target: &str) -> Option<MeshFormat> {
    Some(match target {
        "import_obj" => MeshFormat::Obj,
        "import_off" => MeshFormat::Off,
        "import_ply" => MeshFormat::Ply,
        "import_stl" => MeshFormat::Stl,
        _ => return None,
    })
}

fn files_under(dir: &Path) -> Vec<(MeshFormat, PathBuf)> {
    let mut out = Vec::new();
    let Ok(targets) = std::fs::read_dir(dir) else {
        return out;
    };
    for t in targets.flatten() {
        let Some(format) = fuzz_target_format(&t.file_name().to_string_lossy()) else {
            continue;
        };
        for f in std::fs::read_dir(t.path()).unwrap().flatten() {
            out.push((format, f.path()));
        }
    }
    out.sort_by(|a, b| a.1.cmp(&b.1));
    out
}

#[test]
fn fuzz_seeds_are_valid() {
    let seeds = files_under(&repo().join("corpus/fuzz"));
    for (format, path) in &seeds {
        let bytes = std::fs::read(path).unwrap();
        assert!(bytes.len() < 2048, "{}", path.display());
        read_mesh_bytes(&bytes, *format, &ReadOptions::default())
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    }
}
