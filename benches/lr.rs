//! Standard LR against the corner table, in one run: construction time, and the loops of the
//! LR paper's Fig. 10 (c.v and c.o over every corner, valence and normal of every vertex,
//! contour walks), each as the median of several runs and as a ratio to the corner table.
//!
//! `cargo bench --bench lr` on a generated irregular mesh of 2M triangles; set
//! `LRMESH_BENCH_TRIANGLES` for another size, or `LRMESH_BENCH_MESH=path` for a mesh file.

mod common;

use common::median_time;

use std::time::Duration;

use lrmesh::lr::{Lr, LrOptions};
use lrmesh::ops::{self, Plane};
use lrmesh::{CornerOps, CornerTable, Triangle};

/// Planes across the mesh's bounding box, each with a triangle it cuts.
fn contour_starts<M: CornerOps>(mesh: &M, positions: &[[f32; 3]]) -> Vec<(Plane, Triangle)> {
    let (lo, hi) = positions.iter().fold((f32::MAX, f32::MIN), |(lo, hi), p| {
        (lo.min(p[2]), hi.max(p[2]))
    });
    (0..16)
        .filter_map(|k| {
            let plane = Plane {
                normal: [0.05, 0.02, 1.0],
                offset: lo + (hi - lo) * (k as f32 + 0.5) / 16.0,
            };
            let t = mesh.triangles().find(|&t| {
                let above = mesh
                    .triangle_vertices(t)
                    .map(|v| plane.above(positions[v.idx()]));
                above[0] != above[1] || above[1] != above[2]
            })?;
            Some((plane, t))
        })
        .collect()
}

/// The Fig. 10 loops on one representation: (name, items, time).
fn loops<M: CornerOps>(
    mesh: &M,
    positions: &[[f32; 3]],
    runs: usize,
) -> Vec<(&'static str, usize, Duration)> {
    let corners = mesh.corners().count();
    let vertices = mesh.vertices().count();
    let starts = contour_starts(mesh, positions);
    let walked: usize = starts
        .iter()
        .map(|(plane, t)| ops::contour(mesh, positions, plane, *t).len())
        .sum();
    vec![
        (
            "c.v, every corner",
            corners,
            median_time(runs, || {
                mesh.corners().fold(0u32, |a, c| a ^ mesh.vertex(c).0)
            }),
        ),
        (
            "c.o, every corner",
            corners,
            median_time(runs, || {
                mesh.corners()
                    .fold(0u32, |a, c| a ^ mesh.opposite(c).map_or(0, |o| o.0))
            }),
        ),
        (
            "valence, every vertex",
            vertices,
            median_time(runs, || {
                mesh.vertices().map(|v| ops::valence(mesh, v)).sum::<u32>()
            }),
        ),
        (
            "normal, every vertex",
            vertices,
            median_time(runs, || ops::vertex_normals(mesh, positions)),
        ),
        (
            "contour walk",
            walked,
            median_time(runs, || {
                starts
                    .iter()
                    .map(|(plane, t)| ops::contour(mesh, positions, plane, *t).len())
                    .sum::<usize>()
            }),
        ),
    ]
}

fn main() {
    // `cargo bench` passes `--bench`; this binary takes no options of its own.
    let mesh = common::bench_mesh();
    let runs = 7;
    println!(
        "mesh: {} vertices, {} triangles; median of {runs} runs each",
        mesh.positions.len(),
        mesh.triangles.len()
    );
    let table = CornerTable::from_mesh(&mesh).unwrap();
    let lr = Lr::build(&table, &LrOptions::default()).unwrap();
    let counts = lr.counts();
    println!(
        "LR: rpt {:.3}, {} isolated vertices, {} T0, {} T0^w, {} T^i; {} references against the corner table's {}",
        counts.references_per_triangle(),
        counts.isolated_vertices(),
        counts.t0,
        counts.t0_wart,
        counts.irregular,
        lr.tables().references(),
        table.v_table().len() + table.o_table().len() + table.c_table().len(),
    );

    let ct_build = median_time(runs, || CornerTable::from_mesh(&mesh).unwrap());
    let options = LrOptions::default();
    let lr_build = median_time(runs, || Lr::build(&table, &options).unwrap());
    let one_try = median_time(runs, || {
        Lr::build(
            &table,
            &LrOptions {
                tries: 1,
                ..options
            },
        )
        .unwrap()
    });
    let n = mesh.triangles.len() as f64;
    println!();
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
    for (name, t) in [
        (
            format!("LR from the corner table, {} tries", options.tries),
            lr_build,
        ),
        ("LR from the corner table, 1 try".to_string(), one_try),
    ] {
        println!(
            "{:<34} {:>9.1} ms {:>14.2} {:>8.2}",
            name,
            t.as_secs_f64() * 1e3,
            n / t.as_secs_f64() / 1e6,
            t.as_secs_f64() / ct_build.as_secs_f64()
        );
    }

    let ct_loops = loops(&table, &table.extend_to_copies(&mesh.positions), runs);
    let lr_positions: Vec<[f32; 3]> = (0..lr.vertex_id_bound())
        .map(|v| mesh.positions[lr.input_vertex(lrmesh::Vertex(v)) as usize])
        .collect();
    let lr_loops = loops(&lr, &lr_positions, runs);
    println!();
    println!(
        "{:<24} {:>12} {:>12} {:>12} {:>12} {:>10}",
        "Fig. 10 loop", "CT ns/item", "LR ns/item", "CT total", "LR total", "LR / CT"
    );
    for ((name, ct_items, ct_t), (_, lr_items, lr_t)) in ct_loops.iter().zip(&lr_loops) {
        let per = |t: &Duration, items: &usize| t.as_secs_f64() * 1e9 / (*items).max(1) as f64;
        println!(
            "{:<24} {:>12.2} {:>12.2} {:>9.2} ms {:>9.2} ms {:>10.2}",
            name,
            per(ct_t, ct_items),
            per(lr_t, lr_items),
            ct_t.as_secs_f64() * 1e3,
            lr_t.as_secs_f64() * 1e3,
            per(lr_t, lr_items) / per(ct_t, ct_items)
        );
    }
}
