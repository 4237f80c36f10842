//! The container in one run: encode, the well-formed check (`read::open`) and full validation
//! (`read::open_verified`) against a plain copy of the same bytes, decode to a mesh, and the
//! Fig. 10 loops on the zero-copy view against the owned LR and the corner table.
//!
//! `cargo bench --bench container`; `LRMESH_BENCH_TRIANGLES` or `LRMESH_BENCH_MESH=file` as in
//! the LR bench.

mod common;

use common::median_time;

use std::time::Duration;

use lrmesh::bench::{fig10_loops, LOOP_NAMES};
use lrmesh::lr::Lr;
use lrmesh::read::{open, open_verified, Limits};
use lrmesh::write::{encode, EncodeOptions};
use lrmesh::{CornerOps, CornerTable};

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let mesh = common::bench_mesh();
    let runs = 7;
    let options = EncodeOptions::default();
    let bytes = encode(&mesh, &options).unwrap();
    println!(
        "mesh: {} vertices, {} triangles; container {:.1} MiB; median of {runs} runs",
        mesh.positions.len(),
        mesh.triangles.len(),
        bytes.len() as f64 / (1 << 20) as f64
    );
    let encode_time = median_time(runs, || encode(&mesh, &options).unwrap());
    let memcpy = median_time(runs, || bytes.to_vec());
    let validate = median_time(runs, || {
        open(&bytes, &Limits::default()).unwrap().triangle_count()
    });
    let verify = median_time(runs, || {
        open_verified(&bytes, &Limits::default())
            .unwrap()
            .triangle_count()
    });
    let view = open(&bytes, &Limits::default()).unwrap();
    let decode = median_time(runs, || view.to_mesh());
    let gib = |d: Duration| bytes.len() as f64 / d.as_secs_f64() / (1u64 << 30) as f64;
    println!();
    println!(
        "{:<32} {:>10} {:>10} {:>12}",
        "step", "ms", "GiB/s", "vs memcpy"
    );
    println!(
        "{:<32} {:>10.2} {:>10.2} {:>12}",
        "memcpy of the bytes (baseline)",
        ms(memcpy),
        gib(memcpy),
        "1.00"
    );
    for (name, t) in [
        ("open (well formed)", validate),
        ("open_verified (every rule)", verify),
        ("decode to an indexed mesh", decode),
        ("encode (corner table + LR)", encode_time),
    ] {
        println!(
            "{:<32} {:>10.2} {:>10.2} {:>12.1}",
            name,
            ms(t),
            gib(t),
            t.as_secs_f64() / memcpy.as_secs_f64()
        );
    }

    let table = CornerTable::from_mesh(&mesh).unwrap();
    let owned = Lr::build(&table, &options.lr).unwrap();
    let positions: Vec<[f32; 3]> = (0..owned.vertex_id_bound())
        .map(|v| view.position(lrmesh::Vertex(v)))
        .collect();
    let ct = fig10_loops(&table, &table.extend_to_copies(&mesh.positions), runs);
    let lr = fig10_loops(&owned, &positions, runs);
    let zero_copy = fig10_loops(view.lr().expect("an LR container"), &positions, runs);
    let (lr_ratio, view_ratio) = (lr.ratios(&ct), zero_copy.ratios(&ct));
    println!();
    println!(
        "{:<24} {:>10} {:>10} {:>10} {:>12} {:>12}",
        "Fig. 10 loop (ms)", "CT", "LR owned", "LR view", "owned / CT", "view / CT"
    );
    for (i, name) in LOOP_NAMES.iter().enumerate() {
        println!(
            "{:<24} {:>10.2} {:>10.2} {:>10.2} {:>12.2} {:>12.2}",
            name,
            ms(ct.times[i]),
            ms(lr.times[i]),
            ms(zero_copy.times[i]),
            lr_ratio[i],
            view_ratio[i]
        );
    }
}
