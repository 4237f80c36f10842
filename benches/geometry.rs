//! Whole-file encode and decode of an Edgebreaker container with its positions, the lrmesh
//! side of `scripts/geometry-compare.sh` (Draco's side: `scripts/draco_bench/draco_bench.cc`).
//!
//! `cargo bench --bench geometry -- MESH BITS [RUNS [LEVEL]]`, or the bench binary itself with
//! the same arguments. BITS is `--quantize-position` (1 to 30), 0 for lossless f32 positions;
//! LEVEL is `-l` (default 6).
//!
//! - encode: [`lrmesh::write::encode`] of the mesh as read (validation, corner table,
//!   Edgebreaker, positions, assembly), default level: as `lrmesh encode --connectivity
//!   edgebreaker [--quantize-position BITS]`, without the metadata's source name;
//! - decode: [`lrmesh::read::open`] of the bytes (validation, Edgebreaker and position
//!   decoding) then [`lrmesh::Container::to_mesh`]: connectivity, positions and every
//!   attribute in arrays in memory.
//!
//! Prints one line of `key=value` pairs: faces, vertices, bytes (the container's size),
//! geom_bytes (its `GEOM` section), max_err (largest coordinate error after a round trip, in
//! units of the bounding box's largest extent; checked against the half step of the grid),
//! enc_mtps and dec_mtps (median M triangles/s over RUNS runs, 11 by default), and open_mtps
//! (the same for `read::open` alone: validation, Edgebreaker and positions decoded, without
//! the copy into a mesh).

mod common;

use common::median_time;
use std::path::Path;
use std::time::Duration;

use lrmesh::format::Tag;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::read::{open, Limits, Sections};
use lrmesh::write::{encode, Connectivity, EncodeOptions};

fn main() {
    // `cargo bench` adds `--bench`; keep the positional arguments only.
    let args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .collect();
    let [path, bits, rest @ ..] = args.as_slice() else {
        eprintln!("usage: geometry MESH BITS [RUNS [LEVEL]]   (BITS 0: lossless f32)");
        std::process::exit(2);
    };
    let bits: u8 = bits.parse().expect("BITS: 0 to 30");
    let runs: usize = rest.first().map_or(11, |r| r.parse().expect("RUNS"));
    let level: u8 = rest.get(1).map_or(6, |l| l.parse().expect("LEVEL: 0 to 9"));
    let mesh = read_mesh(Path::new(path), &ReadOptions::default())
        .expect("the mesh")
        .mesh;
    let options = EncodeOptions {
        connectivity: Connectivity::Edgebreaker,
        position_bits: (bits > 0).then_some(bits),
        level,
        ..EncodeOptions::default()
    };
    let limits = Limits::default();
    let bytes = encode(&mesh, &options).expect("encode");
    let decoded = open(&bytes, &limits).expect("open").to_mesh();
    let faces = decoded.triangles.len();
    assert_eq!(
        faces,
        mesh.triangles.len(),
        "triangle count after a round trip"
    );
    let geom_bytes = Sections::parse(&bytes, &limits)
        .expect("sections")
        .section(Tag::GEOM)
        .expect("GEOM")
        .bytes
        .len();

    // The error, vertex by vertex: the same positions stored in the input's order.
    let ordered = encode(
        &mesh,
        &EncodeOptions {
            keep_order: true,
            ..options.clone()
        },
    )
    .expect("encode, keeping the order");
    let back = open(&ordered, &limits).expect("open").to_mesh();
    assert_eq!(back.positions.len(), mesh.positions.len());
    let (lo, hi) = mesh
        .positions
        .iter()
        .fold(([f64::MAX; 3], [f64::MIN; 3]), |(lo, hi), p| {
            (
                [0, 1, 2].map(|k| lo[k].min(p[k] as f64)),
                [0, 1, 2].map(|k| hi[k].max(p[k] as f64)),
            )
        });
    let side = (0..3).map(|k| hi[k] - lo[k]).fold(0.0, f64::max);
    let max_err = mesh
        .positions
        .iter()
        .zip(&back.positions)
        .flat_map(|(a, b)| (0..3).map(move |k| (a[k] as f64 - b[k] as f64).abs()))
        .fold(0.0, f64::max)
        / if side > 0.0 { side } else { 1.0 };
    let half_step = if bits == 0 {
        0.0
    } else {
        0.5 / ((1u64 << bits) - 1) as f64
    };
    // Room for the rounding of the dequantized value to f32.
    let largest = (0..3)
        .map(|k| lo[k].abs().max(hi[k].abs()))
        .fold(0.0, f64::max);
    let rounding = if bits == 0 || side == 0.0 {
        0.0
    } else {
        f32::EPSILON as f64 * largest / side
    };
    assert!(
        max_err <= half_step * (1.0 + 1e-9) + rounding,
        "error {max_err} beyond half a grid step {half_step}"
    );

    let t_enc = median_time(runs, || encode(&mesh, &options).unwrap());
    let t_dec = median_time(runs, || open(&bytes, &limits).unwrap().to_mesh());
    let t_open = median_time(runs, || open(&bytes, &limits).unwrap().triangle_count());
    let rate = |d: Duration| faces as f64 / d.as_secs_f64() / 1e6;
    println!(
        "faces={faces} vertices={} bytes={} geom_bytes={geom_bytes} max_err={max_err:.3e} enc_mtps={:.2} dec_mtps={:.2} open_mtps={:.2}",
        decoded.positions.len(),
        bytes.len(),
        rate(t_enc),
        rate(t_dec),
        rate(t_open)
    );
}
