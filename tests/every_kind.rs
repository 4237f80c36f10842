//! The front door and the container view for every connectivity kind, checked against the
//! corner table: `lrmesh::open`'s connectivity answers the corner operators through
//! `CornerOps` for LR, bit-efficient LR, strips and Edgebreaker alike; swinging from `v.c`
//! alone visits exactly the vertex's fan (FORMAT.md [V38]); the vertex maps and attribute
//! accessors give the input's values.

mod common;

use std::collections::BTreeMap;

use common::corpus_dir;
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::ops::CornerOps;
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::{generate, CornerTable, Mesh, Vertex};

/// The corners met swinging from `v.c` with `c.s` alone, stopping at a boundary or back at
/// the start.
fn swing_only<M: CornerOps>(m: &M, v: Vertex) -> Vec<lrmesh::Corner> {
    let Some(start) = m.vertex_corner(v) else {
        return Vec::new();
    };
    let mut out = vec![start];
    let mut c = start;
    while let Some(d) = m.swing(c) {
        if d == start {
            break;
        }
        assert!(
            out.len() <= 3 * m.triangle_id_bound() as usize,
            "swing loops"
        );
        out.push(d);
        c = d;
    }
    out
}

/// Every fan of `m` as (vertex label, sorted triangles of the fan as sorted label triples),
/// gathered by swinging from `v.c` alone, after checking that this visits every corner of
/// `v`: the fans' multiset is what a representation must share with the corner table.
fn fans<M: CornerOps>(m: &M, label: impl Fn(Vertex) -> u32) -> Vec<(u32, Vec<[u32; 3]>)> {
    let mut corners_of: BTreeMap<u32, usize> = BTreeMap::new();
    for c in m.corners() {
        *corners_of.entry(m.vertex(c).0).or_default() += 1;
    }
    let mut out = Vec::new();
    for v in m.vertices() {
        let fan = swing_only(m, v);
        assert_eq!(
            fan.len(),
            corners_of.get(&v.0).copied().unwrap_or(0),
            "swinging from v.c of vertex {v} misses corners"
        );
        let mut triangles: Vec<[u32; 3]> = fan
            .iter()
            .map(|&c| {
                let mut t = m.triangle_vertices(m.triangle(c)).map(&label);
                t.sort_unstable();
                t
            })
            .collect();
        triangles.sort_unstable();
        if !triangles.is_empty() {
            out.push((label(v), triangles));
        }
    }
    out.sort();
    out
}

/// Encodes `mesh` in every kind (input order kept) and checks the view against the corner
/// table: same fans, complete from `v.c`; every opposite across the same edge; positions
/// and attributes through the vertex map.
fn check_every_kind(mesh: &Mesh, name: &str) {
    let table = CornerTable::from_mesh(mesh).unwrap();
    let expected = fans(&table, |v| table.original_vertex(v).0);
    let normals = mesh.vertex_values::<3>(&Semantic::Normal);
    let texcoords = mesh.vertex_values::<2>(&Semantic::TexCoord(0));
    let colors = mesh.vertex_colors_rgba8();
    for kind in Connectivity::ALL {
        let options = EncodeOptions {
            connectivity: kind,
            keep_order: true,
            // As given: the fans expected are the input's.
            orient: Orient::AsGiven,
            ..EncodeOptions::default()
        };
        let bytes = encode(mesh, &options).unwrap();
        let file = lrmesh::open(&bytes).unwrap();
        let view = file.connectivity();
        let input = |v: Vertex| file.input_vertex(v).expect("the file keeps the order");
        assert_eq!(fans(view, input), expected, "{name} {kind:?}: fans");
        // Opposites face each other across the same edge, as input vertices.
        for c in view.corners() {
            if let Some(o) = view.opposite(c) {
                assert_eq!(view.opposite(o), Some(c), "{name} {kind:?}");
                assert_eq!(
                    input(view.vertex(view.next(o))),
                    input(view.vertex(view.prev(c))),
                    "{name} {kind:?}: corner {c}"
                );
            }
        }
        for v in view.vertices() {
            let x = input(v) as usize;
            assert!(file.position(v) == mesh.positions[x], "{name} {kind:?} {v}");
            assert_eq!(
                file.normal(v),
                normals.as_ref().map(|n| n[x]),
                "{name} {kind:?}"
            );
            assert_eq!(
                file.texcoord(v),
                texcoords.as_ref().map(|t| t[x]),
                "{name} {kind:?}"
            );
            assert_eq!(
                file.color(v),
                colors.as_ref().map(|c| c[x]),
                "{name} {kind:?}"
            );
            assert_eq!(
                mesh.positions[file.output_vertex(v) as usize],
                mesh.positions[x],
                "{name} {kind:?}: output vertex"
            );
        }
        let back = file.to_mesh();
        assert!(
            back.positions == mesh.positions,
            "{name} {kind:?}: positions"
        );
        common::assert_same_up_to_rotation(&back.triangles, &mesh.triangles, name);
    }
}

/// Every mesh of `corpus/`, in every kind.
#[test]
fn corpus_meshes_in_every_kind() {
    let mut checked = 0;
    for entry in std::fs::read_dir(corpus_dir()).unwrap() {
        let path = entry.unwrap().path();
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if !["off", "obj", "ply"].contains(&ext) {
            continue;
        }
        let mesh = lrmesh::load(&path).unwrap();
        check_every_kind(&mesh, &path.display().to_string());
        checked += 1;
    }
    assert!(checked >= 15, "only {checked} corpus meshes");
}

/// Generated meshes with boundaries, handles, several components and every defect, with
/// attributes on every vertex.
#[test]
fn generated_meshes_in_every_kind() {
    for seed in 0..6 {
        let mut rng = generate::Rng::new(seed);
        let mut mesh = generate::irregular_torus(300, seed);
        generate::add_random_handles(&mut mesh, 2, &mut rng);
        generate::punch_holes(&mut mesh, 3, &mut rng);
        generate::append(&mut mesh, &generate::torus(3, 4));
        generate::add_defects(&mut mesh, 3, &mut rng);
        let n = mesh.positions.len();
        let normals: Vec<[f32; 3]> = (0..n).map(|i| [i as f32, 1.0, -1.0]).collect();
        mesh.set_attribute(Attribute::per_vertex(Semantic::Normal, &normals));
        let texcoords: Vec<[f32; 2]> = (0..n).map(|i| [0.5, i as f32]).collect();
        mesh.set_attribute(Attribute::per_vertex(Semantic::TexCoord(0), &texcoords));
        let colors: Vec<[u8; 4]> = (0..n).map(|i| [i as u8, 2, 3, 255]).collect();
        mesh.set_attribute(Attribute::rgba8(&colors));
        check_every_kind(&mesh, &format!("generated {seed}"));
        let soup = generate::soup(40, 90, &mut rng);
        check_every_kind(&soup, &format!("soup {seed}"));
    }
}

/// The front door: save and load by extension (`.lrm` included), `save_with` options, and an
/// encoding written to any `std::io::Write` equal to the one in memory.
#[test]
fn load_save_open() {
    let dir = std::env::temp_dir().join(format!("lrmesh-front-door-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mesh = lrmesh::load(corpus_dir().join("elephant-with-holes.off")).unwrap();
    for ext in ["lrm", "obj", "off", "ply"] {
        let path = dir.join(format!("elephant.{ext}"));
        lrmesh::save(&path, &mesh).unwrap();
        let back = lrmesh::load(&path).unwrap();
        assert_eq!(back.triangle_count(), mesh.triangle_count(), "{ext}");
        assert_eq!(back.vertex_count(), mesh.vertex_count(), "{ext}");
    }
    let options = EncodeOptions {
        connectivity: Connectivity::Edgebreaker,
        keep_order: true,
        ..EncodeOptions::default()
    };
    let path = dir.join("elephant-eb.lrm");
    lrmesh::save_with(&path, &mesh, &options).unwrap();
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(bytes, encode(&mesh, &options).unwrap());
    let mut written = Vec::new();
    lrmesh::write::encode_to(&mut written, &mesh, &options).unwrap();
    assert_eq!(written, bytes);
    let back = lrmesh::load(&path).unwrap();
    assert!(back.positions == mesh.positions, "keep-order round trip");
    common::assert_same_up_to_rotation(&back.triangles, &mesh.triangles, "keep-order round trip");
    assert!(matches!(
        lrmesh::load(dir.join("elephant.xyz")),
        Err(lrmesh::Error::UnknownFormat { .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}

/// Encoding what was already built gives the same bytes as encoding from the mesh, and a
/// structure built from another mesh is refused.
#[test]
fn encode_built_matches_encode() {
    use lrmesh::lr::{Lr, LrOptions};
    use lrmesh::write::{encode_built, Built};
    let mesh = generate::irregular_torus(500, 3);
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let options = EncodeOptions::default();
    let from_mesh = encode(&mesh, &options).unwrap();
    assert_eq!(
        encode_built(&mesh, Built::Lr(&lr), &options).unwrap(),
        from_mesh
    );
    assert_eq!(
        encode_built(&mesh, Built::Table(&table), &options).unwrap(),
        from_mesh
    );
    let other = generate::torus(3, 3);
    assert!(matches!(
        encode_built(&other, Built::Lr(&lr), &options),
        Err(lrmesh::Error::InvalidArgument(_))
    ));
}

/// An id that is not a corner of the mesh is refused, not answered with a made-up corner.
#[test]
fn unused_corner_ids_panic_on_the_view() {
    let mesh = generate::torus(4, 5);
    let bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let file = lrmesh::open(&bytes).unwrap();
    let view = file.connectivity();
    let unused = (0..8 * view.vertex_id_bound())
        .map(lrmesh::Corner)
        .find(|&c| !view.is_corner(c))
        .expect("LR corner ids have gaps");
    let answer = std::panic::catch_unwind(|| view.opposite(unused));
    assert!(answer.is_err(), "corner {unused} answered {answer:?}");
}
