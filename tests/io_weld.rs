//! `ReadOptions::weld` in every text and binary format with shared vertices (OBJ, OFF, PLY):
//! vertices at equal positions merge, and every corner keeps its position and its values.

use lrmesh::io::{read_mesh_bytes, write_mesh_to, MeshFormat, ReadOptions};
use lrmesh::mesh::{Attribute, Semantic};
use lrmesh::Mesh;

/// A unit square as two triangles that share no vertex (six vertices, two of them
/// duplicated per side of the diagonal), each triangle with its own normal and colour, and
/// an unused vertex at the origin's position too.
fn split_square() -> Mesh {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    let mut mesh = Mesh {
        positions: vec![p[0], p[1], p[2], p[0], p[2], p[3], [-0.0, 0.0, 0.0]],
        triangles: vec![[0, 1, 2], [3, 4, 5]],
        ..Mesh::default()
    };
    let normals = [[0.0, 0.0, 1.0]; 3]
        .into_iter()
        .chain([[0.0, 0.6, 0.8]; 3])
        .chain([[1.0, 0.0, 0.0]])
        .collect::<Vec<[f32; 3]>>();
    mesh.attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    mesh
}

/// Every corner's position and normal, triangle by triangle.
fn corners(mesh: &Mesh) -> Vec<(Vec<u32>, Vec<u8>)> {
    let normals = &mesh.attributes[0];
    let mut out = Vec::new();
    for (t, &tri) in mesh.triangles.iter().enumerate() {
        for (k, &v) in tri.iter().enumerate() {
            let p = mesh.positions[v as usize]
                .map(|x| (x + 0.0).to_bits())
                .to_vec();
            out.push((p, normals.corner_bytes(t, k, tri)));
        }
    }
    out
}

#[test]
fn weld_merges_equal_positions_in_obj_off_and_ply() {
    let mesh = split_square();
    for format in [MeshFormat::Obj, MeshFormat::Off, MeshFormat::Ply] {
        let mut bytes = Vec::new();
        write_mesh_to(&mut bytes, &mesh, format).unwrap();
        let plain = read_mesh_bytes(&bytes, format, &ReadOptions { weld: false })
            .unwrap()
            .mesh;
        assert_eq!(plain.positions.len(), 7, "{format:?}");
        let welded = read_mesh_bytes(&bytes, format, &ReadOptions { weld: true })
            .unwrap()
            .mesh;
        // The origin, its unused copy (-0.0 is 0.0), and the diagonal's ends merge.
        assert_eq!(welded.positions.len(), 4, "{format:?}");
        assert_eq!(welded.triangles, vec![[0, 1, 2], [0, 2, 3]], "{format:?}");
        assert!(welded.attributes[0].is_per_corner(), "{format:?}");
        assert_eq!(corners(&welded), corners(&plain), "{format:?}");
        assert_eq!(corners(&plain), corners(&mesh), "{format:?}");
    }
}

/// `Mesh::weld_within`: vertices a little apart (an STL written with rounding) merge into
/// the first one within the tolerance, positions moving by at most it; farther ones stay.
#[test]
fn weld_within_a_tolerance() {
    let e = 1e-4;
    let mesh = Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [1.0 + e, 0.0, 0.0], // 1 again
            [0.0, 1.0 - e, e],   // 2 again
            [1.0, 1.0, 0.0],
            [1.0, 1.0 + 3.0 * e, 0.0], // farther than the tolerance from 5
        ],
        vec![[0, 1, 2], [3, 5, 4], [3, 6, 4]],
    );
    let welded = mesh.weld_within(2.0 * e);
    assert_eq!(welded.positions.len(), 5);
    assert_eq!(welded.triangles, vec![[0, 1, 2], [1, 3, 2], [1, 4, 2]]);
    assert_eq!(welded.positions[4], [1.0, 1.0 + 3.0 * e, 0.0]);
    // No tolerance: exact positions only.
    assert_eq!(mesh.weld_within(0.0), mesh.weld());
    assert_eq!(mesh.weld().positions.len(), 7);
}
