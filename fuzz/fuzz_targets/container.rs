//! Any bytes given to the container reader: an error, or a container that decodes to a mesh
//! that validates and, for LR, a view on which every operator of every corner answers with a
//! valid id and stars and contours terminate. Never a panic. (Checksums are skipped under `cfg(fuzzing)` so that
//! the fuzzer reaches the section parsers.)
#![no_main]

use libfuzzer_sys::fuzz_target;
use lrmesh::ops::{self, CornerOps, Plane};
use lrmesh::read::{open, Limits};
use lrmesh::Vertex;

fuzz_target!(|data: &[u8]| {
    let Ok(view) = open(data, &Limits::default()) else {
        return;
    };
    let decoded = view.to_mesh();
    decoded.validate().expect("a decoded mesh validates");
    let Some(lr) = view.lr() else {
        return;
    };
    let m = lr.vertex_id_bound();
    for c in lr.corners() {
        assert!(lr.vertex(c).0 < m);
        assert!(lr.is_corner(lr.next(c)) && lr.is_corner(lr.prev(c)));
        if let Some(o) = lr.opposite(c) {
            assert!(lr.is_corner(o));
            assert_eq!(lr.opposite(o), Some(c));
        }
        for d in [lr.swing(c), lr.unswing(c), lr.left(c), lr.right(c)].into_iter().flatten() {
            assert!(lr.is_corner(d));
        }
    }
    let positions: Vec<[f32; 3]> = (0..m).map(|v| view.position(Vertex(v))).collect();
    let mut corners_seen = 0usize;
    for v in lr.vertices() {
        let star: Vec<_> = ops::star(lr, v).collect();
        assert!(star.iter().all(|&c| lr.vertex(c) == v));
        corners_seen += star.len();
        ops::valence(lr, v);
        ops::vertex_normal(lr, &positions, v);
    }
    assert!(corners_seen <= lr.corners().count());
    let plane = Plane {
        normal: [0.3, -0.2, 1.0],
        offset: 0.1,
    };
    ops::contours(lr, &positions, &plane);
});
