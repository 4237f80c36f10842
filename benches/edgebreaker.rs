//! Edgebreaker encode and decode throughput, in million triangles per second (median of
//! several runs), with the connectivity size, on the corpus meshes, the shared meshes that
//! only live in `../shared/meshes`, and a generated irregular torus of 2M triangles.
//!
//! `cargo bench --bench edgebreaker`; `LRMESH_BENCH_TRIANGLES` changes the generated size,
//! `LRMESH_BENCH_RUNS` the number of runs, `LRMESH_BENCH_FILTER` keeps the meshes whose name
//! contains it; with `LRMESH_BENCH_DECODE_ONLY` set, encoding is not timed (for profiling).

mod common;

use common::median_time;
use std::path::PathBuf;
use std::time::Duration;

use lrmesh::edgebreaker::{decode, encode, Limits};
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::{generate, CornerTable, Mesh};

/// The meshes whose name contains `filter` (read only those).
fn meshes(filter: &str) -> Vec<(String, Mesh)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    let mut seen = std::collections::HashSet::new();
    for dir in [root.join("corpus/meshes"), root.join("../shared/meshes")] {
        let Ok(entries) = std::fs::read_dir(&dir) else {
            continue;
        };
        let mut paths: Vec<PathBuf> = entries.map(|e| e.unwrap().path()).collect();
        paths.sort();
        for path in paths {
            let name = path.file_name().unwrap().to_string_lossy().to_string();
            if !name.contains(filter)
                || lrmesh::io::MeshFormat::from_path(&path).is_err()
                || !seen.insert(name.clone())
            {
                continue;
            }
            let Ok(loaded) = read_mesh(&path, &ReadOptions::default()) else {
                continue;
            };
            if loaded.mesh.triangles.len() >= 1000 {
                out.push((name, loaded.mesh));
            }
        }
    }
    let n = common::generated_triangles();
    let name = format!("irregular_torus({n})");
    if name.contains(filter) {
        out.push((name, generate::irregular_torus(n, 1)));
    }
    out
}

fn main() {
    let runs: usize = std::env::var("LRMESH_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    println!(
        "{:28} {:>9} {:>7} {:>7} {:>9} {:>12} {:>12}",
        "mesh", "triangles", "bpt", "clers", "topo B", "enc Mtri/s", "dec Mtri/s"
    );
    let filter = std::env::var("LRMESH_BENCH_FILTER").unwrap_or_default();
    let decode_only = std::env::var_os("LRMESH_BENCH_DECODE_ONLY").is_some();
    for (name, mesh) in meshes(&filter) {
        let table = CornerTable::from_mesh(&mesh).unwrap();
        let enc = encode(&table).unwrap();
        let nt = enc.stats.triangles as f64;
        let limits = Limits::default();
        assert_eq!(
            decode(&enc.bytes, &limits).unwrap().triangles.len() as f64,
            nt
        );
        let runs = if nt > 500_000.0 {
            runs.min(5)
        } else {
            runs * 3
        };
        let t_enc = if decode_only {
            Duration::ZERO
        } else {
            median_time(runs, || encode(&table).unwrap())
        };
        let t_dec = median_time(runs, || decode(&enc.bytes, &limits).unwrap());
        let rate = |d: Duration| nt / d.as_secs_f64() / 1e6;
        println!(
            "{:28} {:>9} {:>7.3} {:>7.3} {:>9} {:>12} {:>12.1}",
            name,
            enc.stats.triangles,
            enc.stats.bpt,
            enc.stats.clers_bpt,
            enc.stats.topology_bytes,
            if decode_only {
                "-".to_string()
            } else {
                format!("{:.1}", rate(t_enc))
            },
            rate(t_dec)
        );
    }
}
