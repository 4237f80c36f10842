//! Any bytes given to the Edgebreaker decoder: an error, or triangles whose vertex ids are
//! below the decoded vertex count. Never a panic, never an allocation beyond the limits.
#![no_main]

use libfuzzer_sys::fuzz_target;
use lrmesh::edgebreaker::{decode, Limits};

fuzz_target!(|data: &[u8]| {
    let limits = Limits {
        max_triangles: 1 << 20,
        max_vertices: 1 << 20,
    };
    if let Ok(decoded) = decode(data, &limits) {
        assert!(decoded
            .triangles
            .iter()
            .all(|t| t.iter().all(|&v| v < decoded.vertex_count)));
    }
});
