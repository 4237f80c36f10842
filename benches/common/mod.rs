//! Helpers shared by the bench binaries: the meshes to time. Timing and the LR paper's
//! Fig. 10 loops live in the library ([`lrmesh::bench`]), shared with `lrmesh bench`.
#![allow(dead_code)]

use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::{generate, Mesh};

#[allow(unused_imports)]
pub use lrmesh::bench::median_time;

/// The triangle count of the generated mesh: `LRMESH_BENCH_TRIANGLES`, 2,000,000 by default.
pub fn generated_triangles() -> u32 {
    std::env::var("LRMESH_BENCH_TRIANGLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2_000_000)
}

/// The mesh file `LRMESH_BENCH_MESH` names, or else an irregular genus-1 mesh of
/// [`generated_triangles`] triangles.
pub fn bench_mesh() -> Mesh {
    if let Ok(path) = std::env::var("LRMESH_BENCH_MESH") {
        return read_mesh(path.as_ref(), &ReadOptions::default())
            .expect("LRMESH_BENCH_MESH")
            .mesh;
    }
    generate::irregular_torus(generated_triangles(), 1)
}
