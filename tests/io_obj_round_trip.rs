//! OBJ round trips that keep every corner: a hand-written textured cube with seams and the
//! textured OBJ files of `corpus/assets/obj/` through read -> write -> read and through the
//! container, and generated meshes with per-corner texture coordinates, normals and parts
//! (proptest) through write -> read.

mod common;

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use common::io_helpers::*;
use lrmesh::fuzz_checks::{assert_same_in_order, round_trip_every_kind};
use lrmesh::io::MeshFormat;
use lrmesh::mesh::{Attribute, Part, Parts, Semantic};
use lrmesh::Mesh;
use proptest::prelude::*;

/// The values at corner `k` of triangle `t` of attribute `semantic`, if the mesh has it.
fn at(mesh: &Mesh, semantic: &Semantic, t: usize, k: usize) -> Option<Vec<f32>> {
    let a = mesh.attribute(semantic)?;
    Some(a.value_f32(a.value_index(t, k, mesh.triangles[t])))
}

/// Every connectivity kind, with and without the input order: encoded, decoded, and the
/// same triangles with the same corners (in order when it was kept).
fn through_container(mesh: &Mesh, name: &str) {
    round_trip_every_kind(mesh, name, |_, _, back| {
        // And back to OBJ, as `lrmesh decode x.lrm -o x.obj` does.
        let again = read(&write_to_vec(back, MeshFormat::Obj), MeshFormat::Obj).mesh;
        assert_same_in_order(&again, back);
    });
}

// ---------------------------------------------------------------------------------------------
// A textured cube with a seam at every vertex

const CUBE_NORMALS: [[f32; 3]; 6] = [
    [0.0, 0.0, -1.0],
    [0.0, 0.0, 1.0],
    [0.0, -1.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
];
/// Quads, counter-clockwise from outside, over vertex `x + 2y + 4z`; quad `f` has normal `f`.
const CUBE_QUADS: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];
/// Texture coordinates: quad `f` corner `k` uses record `CUBE_UV_OF[f][k]` (a cross layout,
/// 14 records, so that neighbouring quads share some and not others).
const CUBE_UVS: [[f32; 2]; 14] = [
    [0.25, 0.0],
    [0.5, 0.0],
    [0.0, 0.25],
    [0.25, 0.25],
    [0.5, 0.25],
    [0.75, 0.25],
    [1.0, 0.25],
    [0.0, 0.5],
    [0.25, 0.5],
    [0.5, 0.5],
    [0.75, 0.5],
    [1.0, 0.5],
    [0.25, 0.75],
    [0.5, 0.75],
];
const CUBE_UV_OF: [[usize; 4]; 6] = [
    [3, 8, 9, 4],
    [10, 11, 6, 5],
    [3, 4, 1, 0],
    [8, 12, 13, 9],
    [3, 2, 7, 8],
    [4, 9, 10, 5],
];

fn cube_position(v: usize) -> [f32; 3] {
    [(v & 1) as f32, (v >> 1 & 1) as f32, (v >> 2 & 1) as f32]
}

fn cube_obj() -> String {
    let mut s = String::from("# a cube by hand\nmtllib cube.mtl\n");
    for v in 0..8 {
        let p = cube_position(v);
        s += &format!("v {} {} {}\n", p[0], p[1], p[2]);
    }
    for t in CUBE_UVS {
        s += &format!("vt {} {}\n", t[0], t[1]);
    }
    for n in CUBE_NORMALS {
        s += &format!("vn {} {} {}\n", n[0], n[1], n[2]);
    }
    for (f, quad) in CUBE_QUADS.iter().enumerate() {
        if f % 2 == 0 {
            s += &format!("g side{}\nusemtl {}\n", f / 2, ["red", "blue"][f % 4 / 2]);
        }
        s += "f";
        for k in 0..4 {
            s += &format!(" {}/{}/{}", quad[k] + 1, CUBE_UV_OF[f][k] + 1, f + 1);
        }
        s += "\n";
    }
    s
}

#[test]
fn textured_cube_keeps_every_corner() {
    let loaded = read(cube_obj().as_bytes(), MeshFormat::Obj);
    assert!(loaded.warnings.is_empty(), "{:?}", loaded.warnings);
    let m = &loaded.mesh;
    assert_eq!(m.vertex_count(), 8, "no vertex split at the seams");
    assert_eq!(m.triangle_count(), 12);
    let mut triples = BTreeSet::new();
    for (f, quad) in CUBE_QUADS.iter().enumerate() {
        for (i, fan) in [[0, 1, 2], [0, 2, 3]].iter().enumerate() {
            let t = 2 * f + i;
            for (k, &q) in fan.iter().enumerate() {
                let v = m.triangles[t][k] as usize;
                assert_eq!(v, quad[q], "triangle {t} corner {k}");
                assert_eq!(m.positions[v], cube_position(quad[q]));
                let uv = at(m, &Semantic::TexCoord(0), t, k).unwrap();
                assert_eq!(uv, CUBE_UVS[CUBE_UV_OF[f][q]], "triangle {t} corner {k}");
                let n = at(m, &Semantic::Normal, t, k).unwrap();
                assert_eq!(n, CUBE_NORMALS[f], "triangle {t} corner {k}");
                triples.insert((v, CUBE_UV_OF[f][q], f));
            }
            let part = m.parts.as_ref().unwrap().of(t);
            assert_eq!(part.group.as_deref(), Some(&*format!("side{}", f / 2)));
        }
    }
    assert_eq!(
        triples.len(),
        24,
        "24 (position, vt, vn) corners on 8 positions"
    );
    for semantic in [Semantic::TexCoord(0), Semantic::Normal] {
        assert!(m.attribute(&semantic).unwrap().is_per_corner());
    }

    let written = write_to_vec(m, MeshFormat::Obj);
    let text = String::from_utf8(written.clone()).unwrap();
    assert_eq!(text.lines().filter(|l| l.starts_with("vt ")).count(), 14);
    assert_eq!(text.lines().filter(|l| l.starts_with("vn ")).count(), 6);
    let back = read(&written, MeshFormat::Obj);
    assert!(back.warnings.is_empty(), "{:?}", back.warnings);
    assert_same_in_order(&back.mesh, m);
    through_container(m, "cube");
}

// ---------------------------------------------------------------------------------------------
// The textured OBJ files of corpus/assets/obj

/// What an independent, plain reading of an OBJ file gives at each triangle corner:
/// position, texture coordinate (u, v) and normal, when the corner has them.
type Expected = Vec<([f32; 3], Option<[f32; 2]>, Option<[f32; 3]>)>;

/// The `v`, `vt` and `vn` records of one face corner, 0-based.
type Triple = (usize, Option<usize>, Option<usize>);

/// A deliberately simple reading: no line continuations (the assets have none), `#`
/// comments, fan triangulation. Also gives the distinct `vt` and `vn` records referenced.
fn plain_reading(text: &[u8]) -> (Expected, usize, usize) {
    let (mut v, mut vt, mut vn) = (Vec::new(), Vec::new(), Vec::new());
    let mut faces: Vec<Vec<Triple>> = Vec::new();
    let floats = |w: &[&str]| -> Vec<f32> { w.iter().map(|x| x.parse().unwrap()).collect() };
    let resolve = |tok: &str, count: usize| -> usize {
        let i: i64 = tok.parse().unwrap();
        if i < 0 {
            (count as i64 + i) as usize
        } else {
            i as usize - 1
        }
    };
    for line in String::from_utf8_lossy(text).lines() {
        let line = line.split('#').next().unwrap();
        let w: Vec<&str> = line.split_whitespace().collect();
        match w.first().copied() {
            Some("v") => v.push(floats(&w[1..4])),
            Some("vt") => {
                let mut t = floats(&w[1..]);
                t.resize(2, 0.0);
                vt.push([t[0], t[1]]);
            }
            Some("vn") => vn.push(floats(&w[1..4])),
            Some("f") => faces.push(
                w[1..]
                    .iter()
                    .map(|c| {
                        let p: Vec<&str> = c.split('/').collect();
                        let opt = |i: usize, n: usize| {
                            p.get(i).filter(|s| !s.is_empty()).map(|s| resolve(s, n))
                        };
                        (resolve(p[0], v.len()), opt(1, vt.len()), opt(2, vn.len()))
                    })
                    .collect(),
            ),
            _ => {}
        }
    }
    let mut expected = Vec::new();
    let (mut used_vt, mut used_vn) = (BTreeSet::new(), BTreeSet::new());
    for face in &faces {
        for i in 1..face.len() - 1 {
            for &(p, t, n) in [&face[0], &face[i], &face[i + 1]] {
                used_vt.extend(t);
                used_vn.extend(n);
                expected.push((
                    [v[p][0], v[p][1], v[p][2]],
                    t.map(|t| vt[t]),
                    n.map(|n| [vn[n][0], vn[n][1], vn[n][2]]),
                ));
            }
        }
    }
    (expected, used_vt.len(), used_vn.len())
}

fn asset_objs() -> Vec<PathBuf> {
    let root = repo().join("corpus/assets/obj");
    let mut out = Vec::new();
    let mut dirs = vec![root];
    while let Some(dir) = dirs.pop() {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "obj") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The distinct value indices the corners of `semantic` use.
fn distinct_used(m: &Mesh, semantic: &Semantic) -> usize {
    let Some(a) = m.attribute(semantic) else {
        return 0;
    };
    let used: BTreeSet<usize> = (0..m.triangle_count())
        .flat_map(|t| (0..3).map(move |k| (t, k)))
        .map(|(t, k)| a.value_index(t, k, m.triangles[t]))
        .collect();
    used.len()
}

fn check_asset(path: &Path) {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).unwrap();
    let loaded = read(&bytes, MeshFormat::Obj);
    let m = &loaded.mesh;
    let (expected, used_vt, used_vn) = plain_reading(&bytes);
    assert_eq!(3 * m.triangle_count(), expected.len(), "{name}: corners");
    for (c, (p, uv, n)) in expected.iter().enumerate() {
        let (t, k) = (c / 3, c % 3);
        assert_eq!(
            m.positions[m.triangles[t][k] as usize], *p,
            "{name} corner {c}"
        );
        // A corner without a record, in a file where others have one, has the added zeros.
        let got_uv = at(m, &Semantic::TexCoord(0), t, k);
        let want_uv = uv
            .map(Vec::from)
            .or_else(|| got_uv.as_ref().map(|_| vec![0.0; 2]));
        assert_eq!(got_uv, want_uv, "{name} corner {c} vt");
        let got_n = at(m, &Semantic::Normal, t, k);
        let want_n = n
            .map(Vec::from)
            .or_else(|| got_n.as_ref().map(|_| vec![0.0; 3]));
        assert_eq!(got_n, want_n, "{name} corner {c} vn");
    }
    let missing = |k: usize| {
        expected
            .iter()
            .filter(|e| [e.1.is_none(), e.2.is_none()][k])
            .count()
    };
    for (k, semantic, used) in [
        (0, Semantic::TexCoord(0), used_vt),
        (1, Semantic::Normal, used_vn),
    ] {
        if m.attribute(&semantic).is_some_and(Attribute::is_per_corner) {
            let added = usize::from(missing(k) > 0);
            assert_eq!(
                distinct_used(m, &semantic),
                used + added,
                "{name}: {semantic} records used"
            );
        }
        let what = ["texture coordinate", "normal"][k];
        let warned = format!(
            "{} of {} triangle corners have no {what}",
            missing(k),
            expected.len()
        );
        assert_eq!(
            loaded.warnings.iter().any(|w| w.starts_with(&warned)),
            missing(k) > 0 && used > 0,
            "{name}: {:?}",
            loaded.warnings
        );
    }
    let back = read(&write_to_vec(m, MeshFormat::Obj), MeshFormat::Obj);
    assert!(back.warnings.is_empty(), "{name}: {:?}", back.warnings);
    assert_same_in_order(&back.mesh, m);
    eprintln!(
        "{name}: {} vertices, {} triangles, {} parts, warnings {:?}",
        m.vertex_count(),
        m.triangle_count(),
        m.parts.as_ref().map_or(0, |p| p.parts.len()),
        loaded.warnings
    );
}

#[test]
fn asset_objs_keep_every_corner_through_obj() {
    let files = asset_objs();
    assert!(!files.is_empty(), "corpus/assets/obj has no .obj file");
    for path in &files {
        check_asset(path);
    }
}

#[test]
fn asset_objs_keep_every_corner_through_the_container() {
    for path in asset_objs() {
        let m = read(&std::fs::read(&path).unwrap(), MeshFormat::Obj).mesh;
        through_container(&m, &path.display().to_string());
    }
}

// ---------------------------------------------------------------------------------------------
// Generated meshes

/// Numbers drawn from a list that proptest generates (and shrinks).
struct Draw<'a>(&'a [u32], usize);

impl Draw<'_> {
    fn below(&mut self, n: u32) -> u32 {
        let x = self.0.get(self.1).copied().unwrap_or(0);
        self.1 += 1;
        x % n.max(1)
    }

    fn float(&mut self) -> f32 {
        const AWKWARD: [f32; 6] = [-0.0, 0.0, 1e-42, 1e30, 0.1, -2.5];
        match self.below(3) {
            0 => AWKWARD[self.below(6) as usize],
            _ => (self.below(2001) as f32 - 1000.0) / 7.0,
        }
    }

    fn values<const N: usize>(&mut self, count: u32) -> Vec<[f32; N]> {
        (0..count).map(|_| [(); N].map(|_| self.float())).collect()
    }

    /// None, per vertex, per corner with a few values (so that corners repeat some), or per
    /// corner with one value per vertex that every corner of the vertex uses (which the
    /// reader would take per vertex, were the writer not careful).
    fn attribute<const N: usize>(&mut self, semantic: Semantic, m: &Mesh) -> Option<Attribute> {
        match self.below(4) {
            0 => None,
            1 => Some(Attribute::per_vertex(
                semantic,
                &self.values::<N>(m.vertex_count() as u32),
            )),
            2 => {
                let values = self.values::<N>(m.vertex_count() as u32);
                let corners = m.triangles.iter().flatten().copied().collect();
                Some(Attribute::per_corner(semantic, &values, corners))
            }
            _ => {
                let count = 1 + self.below(6);
                let values = self.values::<N>(count);
                let corners = (0..3 * m.triangle_count())
                    .map(|_| self.below(count))
                    .collect();
                Some(Attribute::per_corner(semantic, &values, corners))
            }
        }
    }

    fn label(&mut self, names: &[&str]) -> Option<String> {
        let i = self.below(names.len() as u32 + 1) as usize;
        names.get(i).map(|s| s.to_string())
    }
}

fn generated(numbers: &[u32]) -> Mesh {
    let mut d = Draw(numbers, 0);
    let nv = 1 + d.below(10);
    let mut m = Mesh::new(
        d.values::<3>(nv),
        (0..1 + d.below(16))
            .map(|_| [0; 3].map(|_| d.below(nv)))
            .collect(),
    );
    if let Some(a) = d.attribute::<2>(Semantic::TexCoord(0), &m) {
        m.attributes.push(a);
    }
    if let Some(a) = d.attribute::<3>(Semantic::Normal, &m) {
        m.attributes.push(a);
    }
    if d.below(2) == 0 {
        let colors: Vec<[u8; 4]> = (0..nv)
            .map(|_| [0; 4].map(|_| d.below(256) as u8))
            .collect();
        m.attributes.push(Attribute::rgba8(&colors));
    }
    if d.below(2) == 0 {
        let mut parts = Parts::default();
        for _ in 0..m.triangle_count() {
            let part = Part {
                object: d.label(&["body", "wheel 2"]),
                group: d.label(&["a", "b c"]),
                material: d.label(&["steel", "Material.001"]),
            };
            let i = parts.intern(part);
            parts.of_triangle.push(i);
        }
        if d.below(2) == 0 {
            parts.material_libraries = vec!["x.mtl".into()];
        }
        // Parts that label nothing and name no library are no parts to the reader.
        if parts.parts.iter().any(|p| *p != Part::default()) || d.below(2) == 0 {
            parts.material_libraries.push("y.mtl".into());
        }
        m.parts = Some(parts);
    }
    m.validate().unwrap();
    m
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn generated_meshes_round_trip_through_obj(
        numbers in proptest::collection::vec(any::<u32>(), 0..600)
    ) {
        let m = generated(&numbers);
        let written = write_to_vec(&m, MeshFormat::Obj);
        let back = read(&written, MeshFormat::Obj);
        prop_assert!(back.warnings.is_empty(), "{:?}", back.warnings);
        assert_same_in_order(&back.mesh, &m);
    }
}
