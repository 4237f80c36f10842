//! Importer and exporter tests over whole meshes: the corpus against its manifest (and through
//! STL, welded or not), round trips that keep every bit through every writer, writing by
//! extension, and the fuzz seeds. Helpers: `tests/common/io_helpers.rs`.

mod common;

use common::corpus_dir;
use common::io_helpers::*;
use lrmesh::io::{
    obj, off, ply, read_mesh, read_mesh_bytes, stl, write_mesh, write_mesh_to, MeshFormat,
    ReadOptions,
};
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::{Error, Mesh};
use std::path::{Path, PathBuf};

// ---------------------------------------------------------------------------------------------
// Helpers

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

/// Every float of a mesh as bits, so that -0.0 and 0.0 differ.
type Bits = (Vec<[u32; 3]>, Vec<[u32; 3]>, Vec<AttributeBits>);

/// An attribute's semantic, whether it is per corner, and its values as f32 bits (normalized
/// integers as their fractions) at every vertex, or at every corner when per corner.
type AttributeBits = (Semantic, bool, Vec<Vec<u32>>);

fn bits(m: &Mesh) -> Bits {
    let mut attributes: Vec<AttributeBits> = m
        .attributes
        .iter()
        .map(|a| {
            let value_bits = |i: usize| a.value_f32(i).into_iter().map(f32::to_bits).collect();
            let values = if a.is_per_corner() {
                (0..3 * m.triangles.len())
                    .map(|c| value_bits(a.value_index(c / 3, c % 3, m.triangles[c / 3])))
                    .collect()
            } else {
                (0..a.value_count()).map(value_bits).collect()
            };
            (a.semantic.clone(), a.is_per_corner(), values)
        })
        .collect();
    attributes.sort_by(|a, b| a.0.cmp(&b.0));
    (
        m.positions.iter().map(|p| p.map(f32::to_bits)).collect(),
        m.triangles.clone(),
        attributes,
    )
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
            assert_eq!(
                sorted_attributes(&back.mesh),
                sorted_attributes(&m),
                "{ctx}"
            );
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
        m.set_attribute(Attribute::rgba8(&colors));
        for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
            let back = read(&write_to_vec(&m, format), format);
            assert_eq!(
                back.mesh.vertex_colors_rgba8(),
                Some(colors.clone()),
                "{format}"
            );
        }
    }
}

#[test]
fn round_trip_of_an_empty_mesh() {
    let m = Mesh::default();
    for format in [MeshFormat::Off, MeshFormat::Ply] {
        assert_eq!(read(&write_to_vec(&m, format), format).mesh, m, "{format}");
    }
    // OBJ has no header that could declare zero vertices: a file without `v` and `f` is
    // refused (it could be any text), so an empty mesh does not come back from OBJ.
    let obj = write_to_vec(&m, MeshFormat::Obj);
    let e = parse_err(&obj, MeshFormat::Obj);
    assert!(e.message.contains("no vertex or face statement"), "{e}");
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
    for ext in ["obj", "OFF", "ply", "gltf", "GLB"] {
        let path = dir.join(format!("m.{ext}"));
        write_mesh(&path, &m).unwrap();
        let back = read_mesh(&path, &ReadOptions::default()).unwrap();
        assert_eq!(bits(&back.mesh), bits(&m), "{ext}");
    }
    // STL keeps the triangles' corners, not the vertices or attributes.
    write_mesh(&dir.join("m.stl"), &m).unwrap();
    let back = read_mesh(&dir.join("m.stl"), &ReadOptions::default()).unwrap();
    assert_eq!(back.mesh.triangle_count(), m.triangle_count());
    assert!(matches!(
        write_mesh(&dir.join("m.xyz"), &m),
        Err(Error::UnknownFormat { .. })
    ));
    let mut stl_bytes = Vec::new();
    write_mesh_to(&mut stl_bytes, &m, MeshFormat::Stl).unwrap();
    assert_eq!(stl_bytes.len(), 84 + 50 * m.triangle_count());
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
    // A normal attribute with no value for the one vertex.
    m.set_attribute(Attribute::per_vertex::<3>(Semantic::Normal, &[]));
    assert!(off::write(Vec::new(), &m).is_err());
}

// ---------------------------------------------------------------------------------------------
// Fuzz seeds and regressions

fn fuzz_target_format(target: &str) -> Option<MeshFormat> {
    Some(match target {
        "import_obj" => MeshFormat::Obj,
        "import_off" => MeshFormat::Off,
        "import_ply" => MeshFormat::Ply,
        "import_stl" => MeshFormat::Stl,
        // The glTF reader tells GLB from JSON by the magic: one format reads both.
        "import_gltf" => MeshFormat::Glb,
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
