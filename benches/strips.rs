//! Our stripper against meshoptimizer's `meshopt_stripify`, in the same run: indices per
//! triangle (restarts counted) and millions of triangles per second, on the corpus, the team's
//! shared meshes and an irregular torus of 2M triangles, all in meshoptimizer's vertex-cache
//! order first; then the CTS and LR index list figures.
//!
//! `cargo bench --bench strips`. `LRMESH_BENCH_TRIANGLES` changes the torus size;
//! `LRMESH_BENCH_SECONDS` the time spent on each measurement (default 0.2 s);
//! `LRMESH_BENCH_ONLY=armadillo,knot1` keeps the meshes whose names contain one of the words.
//! `PHASES=1` prints, per mesh, nanoseconds per triangle of the adjacency build and of the
//! stripping apart, next to meshopt's.

use lrmesh::generate;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::strips::{stripify, StripOptions, StripStats};
use lrmesh::Mesh;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// Fastest of repeated runs of `f` within the time budget (at least two runs).
fn time<T>(budget: Duration, mut f: impl FnMut() -> T) -> (Duration, T) {
    let start = Instant::now();
    let mut best = Duration::MAX;
    let mut runs = 0;
    loop {
        let t = Instant::now();
        let out = f();
        best = best.min(t.elapsed());
        runs += 1;
        if runs >= 2 && start.elapsed() >= budget {
            return (best, out);
        }
    }
}

fn meshes_in(dir: &Path) -> Vec<(String, Mesh)> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        if lrmesh::io::MeshFormat::from_path(&path).is_err() {
            continue;
        }
        if let Ok(loaded) = read_mesh(&path, &ReadOptions::default()) {
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            out.push((name.into_owned(), loaded.mesh));
        }
    }
    out.sort_by(|a, b| a.0.cmp(&b.0));
    out
}

struct Row {
    ours_ipt: f64,
    ours_mtps: f64,
    sampled_ipt: f64,
    meshopt_ipt: f64,
    meshopt_mtps: f64,
}

/// The mesh with its triangles in meshoptimizer's strip-friendly vertex-cache order
/// (`meshopt_optimizeVertexCacheStrip`, which is how `meshopt_stripify` expects its input);
/// both stripifiers get the same triangles.
fn cache_ordered(mesh: &Mesh) -> Mesh {
    let flat: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let mut ordered = vec![0u32; flat.len()];
    // SAFETY: `ordered` holds `flat.len()` indices, as the function requires, and every index
    // of `flat` is below the vertex count (the mesh is valid).
    unsafe {
        meshopt::ffi::meshopt_optimizeVertexCacheStrip(
            ordered.as_mut_ptr(),
            flat.as_ptr(),
            flat.len(),
            mesh.positions.len(),
        );
    }
    let triangles = ordered
        .chunks_exact(3)
        .map(|t| [t[0], t[1], t[2]])
        .collect();
    Mesh::new(mesh.positions.clone(), triangles)
}

fn compare(mesh: &Mesh, budget: Duration) -> Row {
    let mesh = &cache_ordered(mesh);
    let n = mesh.triangles.len().max(1) as f64;
    let options = StripOptions::default();
    let (ours_time, ours) = time(budget, || {
        stripify(mesh.positions.len(), &mesh.triangles, &options)
    });
    let sampled = stripify(
        mesh.positions.len(),
        &mesh.triangles,
        &StripOptions {
            samples: 4,
            ..options
        },
    );
    let flat: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let (meshopt_time, theirs) = time(budget, || {
        meshopt::stripify(&flat, mesh.positions.len(), u32::MAX).unwrap_or_default()
    });
    Row {
        ours_ipt: ours.indices_per_triangle(),
        ours_mtps: n / ours_time.as_secs_f64() / 1e6,
        sampled_ipt: sampled.indices_per_triangle(),
        meshopt_ipt: theirs.len() as f64 / n,
        meshopt_mtps: n / meshopt_time.as_secs_f64() / 1e6,
    }
}

/// Where the time goes (`PHASES=1`): adjacency build and stripping apart, next to meshopt, on
/// the cache-ordered meshes.
fn phases(name: &str, mesh: &Mesh, budget: Duration) {
    use lrmesh::strips::{stripify_adjacency, Adjacency};
    let m = cache_ordered(mesh);
    let n = m.triangles.len().max(1) as f64;
    let (tb, mut adj) = time(budget, || Adjacency::build(m.positions.len(), &m.triangles));
    let (ts, _) = time(budget, || {
        stripify_adjacency(&mut adj, &StripOptions::default())
    });
    let flat: Vec<u32> = m.triangles.iter().flatten().copied().collect();
    let (tm, _) = time(budget, || {
        meshopt::stripify(&flat, m.positions.len(), u32::MAX).unwrap_or_default()
    });
    let ns = |t: Duration| t.as_secs_f64() * 1e9 / n;
    println!(
        "{name:<34} ns/triangle: build {:6.1} strip {:6.1} meshopt {:6.1}",
        ns(tb),
        ns(ts),
        ns(tm)
    );
}

fn main() {
    let budget = Duration::from_secs_f64(
        std::env::var("LRMESH_BENCH_SECONDS")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(0.2),
    );
    let torus_size = std::env::var("LRMESH_BENCH_TRIANGLES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2_000_000u32);
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let mut meshes: Vec<(String, Mesh)> = meshes_in(&root.join("corpus/meshes"));
    let corpus_names: Vec<String> = meshes.iter().map(|m| m.0.clone()).collect();
    for (name, mesh) in meshes_in(&root.join("../shared/meshes")) {
        if !corpus_names.contains(&name) {
            meshes.push((format!("shared/{name}"), mesh));
        }
    }
    meshes.push((
        format!("irregular_torus({torus_size})"),
        generate::irregular_torus(torus_size, 1),
    ));
    if let Ok(only) = std::env::var("LRMESH_BENCH_ONLY") {
        meshes.retain(|(name, _)| only.split(',').any(|w| !w.is_empty() && name.contains(w)));
    }

    if std::env::var("PHASES").is_ok() {
        for (name, mesh) in &meshes {
            phases(name, mesh, budget);
        }
        return;
    }
    println!(
        "{:<34} {:>9} | {:>7} {:>7} {:>7} {:>6} | {:>8} {:>8} {:>6}",
        "mesh", "triangles", "ours", "ours x4", "meshopt", "ratio", "ours M/s", "mopt M/s", "ratio"
    );
    println!(
        "{:<34} {:>9} | indices per triangle (restarts counted) | M triangles/s",
        "", ""
    );
    for (name, mesh) in &meshes {
        let r = compare(mesh, budget);
        println!(
            "{:<34} {:>9} | {:>7.3} {:>7.3} {:>7.3} {:>6.3} | {:>8.1} {:>8.1} {:>6.2}",
            name,
            mesh.triangles.len(),
            r.ours_ipt,
            r.sampled_ipt,
            r.meshopt_ipt,
            r.ours_ipt / r.meshopt_ipt,
            r.ours_mtps,
            r.meshopt_mtps,
            r.ours_mtps / r.meshopt_mtps
        );
    }

    println!();
    println!(
        "{:<34} {:>9} | {:>8} {:>8} {:>8} | {:>9} {:>9}",
        "mesh", "triangles", "strips", "fans", "lone", "CTS b/t", "LR idx rpt"
    );
    for (name, mesh) in &meshes {
        match StripStats::of(mesh) {
            Ok(s) => println!(
                "{:<34} {:>9} | {:>8} {:>8} {:>8} | {:>9.1} {:>9.3}",
                name,
                mesh.triangles.len(),
                s.strips,
                s.fans,
                s.isolated_triangles,
                s.cts_bits_per_triangle,
                s.lr_index_rpt
            ),
            Err(e) => println!("{name:<34} error: {e}"),
        }
    }
}
