//! Helpers shared by the bench binaries: timing and the meshes to time.
#![allow(dead_code)]

use std::hint::black_box;
use std::time::{Duration, Instant};

use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::{generate, Mesh};

/// The median wall-clock time of `runs` calls of `f`, its result kept alive past the timer.
pub fn median_time<R>(runs: usize, mut f: impl FnMut() -> R) -> Duration {
    let mut times: Vec<Duration> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            black_box(f());
            start.elapsed()
        })
        .collect();
    times.sort();
    times[runs / 2]
}

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
