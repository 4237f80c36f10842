//! Any bytes given to the container reader: an error, or a container that decodes to a mesh
//! that validates and, for LR and strips, a view on which every operator of every corner answers with a
//! valid id and stars and contours terminate. Never a panic. (Checksums are skipped under `cfg(fuzzing)` so that
//! the fuzzer reaches the section parsers.)
#![no_main]

use libfuzzer_sys::fuzz_target;
use lrmesh::lr::LrLayout;
use lrmesh::ops::{self, CornerOps, Plane};
use lrmesh::read::{open, Limits};
use lrmesh::{Corner, Vertex};

fuzz_target!(|data: &[u8]| {
    let Ok(view) = open(data, &Limits::default()) else {
        return;
    };
    let decoded = view.to_mesh();
    decoded.validate().expect("a decoded mesh validates");
    let m = view.connectivity_vertex_count();
    let positions: Vec<[f32; 3]> = (0..m).map(|v| view.position(Vertex(v))).collect();
    if let Some(lr) = view.lr() {
        walk(lr, |c| lr.is_corner(c), &positions);
    }
    if let Some(strips) = view.strips() {
        walk(strips, |c| strips.is_corner(c), &positions);
    }
});

/// Every operator of every corner answers with a valid id; stars, valences, normals and
/// contours terminate.
fn walk<M: CornerOps>(mesh: &M, is_corner: impl Fn(Corner) -> bool, positions: &[[f32; 3]]) {
    let m = mesh.vertex_id_bound();
    assert_eq!(m as usize, positions.len());
    for c in mesh.corners() {
        assert!(mesh.vertex(c).0 < m);
        assert!(is_corner(mesh.next(c)) && is_corner(mesh.prev(c)));
        if let Some(o) = mesh.opposite(c) {
            assert!(is_corner(o));
            assert_eq!(mesh.opposite(o), Some(c));
        }
        for d in [mesh.swing(c), mesh.unswing(c), mesh.left(c), mesh.right(c)]
            .into_iter()
            .flatten()
        {
            assert!(is_corner(d));
        }
    }
    let mut corners_seen = 0usize;
    for v in mesh.vertices() {
        let star: Vec<_> = ops::star(mesh, v).collect();
        assert!(star.iter().all(|&c| mesh.vertex(c) == v));
        corners_seen += star.len();
        ops::valence(mesh, v);
        ops::vertex_normal(mesh, positions, v);
    }
    assert!(corners_seen <= mesh.corners().count());
    let plane = Plane {
        normal: [0.3, -0.2, 1.0],
        offset: 0.1,
    };
    ops::contours(mesh, positions, &plane);
}
