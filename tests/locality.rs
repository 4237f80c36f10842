//! Large meshes are encoded in a cache-friendly order (`mesh::locality`, from
//! `LOCALITY_TRIANGLES` = 2^17 triangles) unless their order is kept: nothing is lost on the
//! way, in any kind, with per-vertex and per-corner values, parts, defects and recorded
//! flips; the borrowed and the owned encoders take the same order.

use lrmesh::fuzz_checks::{assert_same_in_order, assert_same_up_to_order};
use lrmesh::generate::{self, Rng};
use lrmesh::mesh::{orient, Attribute, Part, Parts, Semantic};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, encode_owned, Connectivity, EncodeOptions, Orient};
use lrmesh::Mesh;

/// About 140,000 triangles in scattered order: an irregular torus with holes, defects
/// (duplicates, degenerate and dangling triangles, isolated vertices), a per-vertex normal,
/// per-corner texture coordinates and three parts, its triangles and vertices shuffled.
fn large() -> Mesh {
    let mut rng = Rng::new(21);
    let mut mesh = generate::irregular_torus(140_000, 4);
    generate::punch_holes(&mut mesh, 30, &mut rng);
    generate::add_defects(&mut mesh, 60, &mut rng);
    shuffle(&mut mesh, &mut rng);
    let normals: Vec<[f32; 3]> = (0..mesh.positions.len())
        .map(|i| [(i % 11) as f32, 1.0, -0.5])
        .collect();
    mesh.attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    let corners = 3 * mesh.triangles.len();
    let uv: Vec<[f32; 2]> = (0..corners.div_ceil(2)).map(|i| [i as f32, 0.25]).collect();
    let index = (0..corners as u32).map(|c| c / 2).collect();
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, index));
    let mut parts = Parts::default();
    for t in 0..mesh.triangles.len() {
        let part = Part {
            material: Some(format!("m{}", t % 3)),
            ..Part::default()
        };
        let p = parts.intern(part);
        parts.of_triangle.push(p);
    }
    mesh.parts = Some(parts);
    mesh
}

/// Renames the vertices and reorders the triangles at random (before any attribute).
fn shuffle(mesh: &mut Mesh, rng: &mut Rng) {
    let n = mesh.positions.len();
    let mut rename: Vec<u32> = (0..n as u32).collect();
    rng.shuffle(&mut rename);
    let mut positions = vec![[0.0; 3]; n];
    for (v, &p) in mesh.positions.iter().enumerate() {
        positions[rename[v] as usize] = p;
    }
    mesh.positions = positions;
    for tri in &mut mesh.triangles {
        *tri = tri.map(|v| rename[v as usize]);
    }
    rng.shuffle(&mut mesh.triangles);
}

/// `mesh` encoded with `options` and decoded.
fn decoded(mesh: &Mesh, options: &EncodeOptions) -> Mesh {
    let bytes = encode(mesh, options).unwrap();
    open(&bytes, &Limits::default()).unwrap().to_mesh()
}

#[test]
fn a_large_mesh_loses_nothing_in_any_kind_with_or_without_its_order() {
    let mesh = large();
    assert!(mesh.triangles.len() >= 1 << 17);
    for connectivity in Connectivity::ALL {
        for keep_order in [false, true] {
            let options = EncodeOptions {
                connectivity,
                keep_order,
                ..EncodeOptions::default()
            };
            let back = decoded(&mesh, &options);
            if keep_order {
                assert_same_in_order(&back, &mesh);
            } else {
                assert_same_up_to_order(&back, &mesh);
            }
        }
    }
}

#[test]
fn recorded_flips_follow_their_triangles() {
    let mut mesh = large();
    mesh.attributes.clear();
    mesh.parts = None;
    let mut rng = Rng::new(5);
    for _ in 0..5000 {
        let t = rng.below(mesh.triangles.len() as u32) as usize;
        let [a, b, c] = mesh.triangles[t];
        mesh.triangles[t] = [a, c, b];
    }
    assert!(orient(&mesh).flipped_count() > 0);
    for connectivity in [Connectivity::Lr, Connectivity::Edgebreaker] {
        let options = EncodeOptions {
            connectivity,
            orient: Orient::Repair,
            ..EncodeOptions::default()
        };
        assert_same_up_to_order(&decoded(&mesh, &options), &mesh);
    }
}

#[test]
fn the_owned_encoder_takes_the_same_order() {
    let mut plain = large();
    plain.attributes.clear();
    plain.parts = None;
    for connectivity in Connectivity::ALL {
        let options = EncodeOptions {
            connectivity,
            ..EncodeOptions::default()
        };
        let want = encode(&plain, &options).unwrap();
        let got = encode_owned(plain.clone(), &options).unwrap();
        assert!(got == want, "{connectivity:?}");
    }
}
