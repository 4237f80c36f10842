//! Every connectivity representation against the corner table, in one run: the table of
//! `lrmesh bench` (bytes, bits per triangle, build and open times, and the loops of the LR
//! paper's Fig. 10 as ratios to the corner table: c.v and c.o over every corner, valence and
//! normal of every vertex, contour walks), then LR construction with one and several
//! RING-EXPANDER tries against the corner table's.
//!
//! `cargo bench --bench lr` on a generated irregular mesh of 2M triangles; set
//! `LRMESH_BENCH_TRIANGLES` for another size, `LRMESH_BENCH_MESH=path` for a mesh file, and
//! `LRMESH_BENCH_RUNS` for the runs per step (default 7).

mod common;

use common::median_time;

use lrmesh::bench::{self, BenchOptions};
use lrmesh::lr::{Lr, LrOptions};
use lrmesh::CornerTable;

fn main() {
    // `cargo bench` passes `--bench`; this binary takes no options of its own.
    let mesh = common::bench_mesh();
    let runs: usize = std::env::var("LRMESH_BENCH_RUNS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(7);
    let options = BenchOptions {
        runs,
        ..BenchOptions::default()
    };
    let report = bench::run(&mesh, &options, &mut |step| eprintln!("timing {step}")).unwrap();
    print!("{report}");

    let table = CornerTable::from_mesh(&mesh).unwrap();
    let lr = Lr::build(&table, &options.lr).unwrap();
    let counts = lr.counts();
    println!();
    println!(
        "LR: rpt {:.3}, {} isolated vertices, {} T0, {} T0^w, {} T^i",
        counts.references_per_triangle(),
        counts.isolated_vertices(),
        counts.t0,
        counts.t0_wart,
        counts.irregular,
    );
    let ct_build = median_time(runs, || CornerTable::from_mesh(&mesh).unwrap());
    let n = mesh.triangles.len() as f64;
    println!(
        "{:<34} {:>12} {:>14} {:>8}",
        "construction", "time", "M triangles/s", "ratio"
    );
    println!(
        "{:<34} {:>9.1} ms {:>14.2} {:>8}",
        "corner table (baseline)",
        ct_build.as_secs_f64() * 1e3,
        n / ct_build.as_secs_f64() / 1e6,
        "1.00"
    );
    for tries in [options.lr.tries, 1] {
        let lr_options = LrOptions {
            tries,
            ..options.lr
        };
        let t = median_time(runs, || Lr::build(&table, &lr_options).unwrap());
        println!(
            "{:<34} {:>9.1} ms {:>14.2} {:>8.2}",
            format!("LR from the corner table, {tries} tries"),
            t.as_secs_f64() * 1e3,
            n / t.as_secs_f64() / 1e6,
            t.as_secs_f64() / ct_build.as_secs_f64()
        );
    }
}
