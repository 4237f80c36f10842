//! Random-vertex position lookups (`Container::position`) on the loaded bytes of an LR
//! container: raw positions (`GEOM` encodings 0 and 1, level 0) against random-access
//! blocks (encodings 4 and 5, the default level), 16-bit grid and exact f32.
//!
//! `cargo bench --bench positions` prints, before divan's table, the `GEOM` size of each
//! container; the mesh is `corpus/meshes/b9_mesh.off` (the median of the real meshes in
//! block size at 16 bits) or `LRMESH_BENCH_MESH=path`. Each bench looks up the same 4096
//! pseudo-random vertices. With `LRMESH_BENCH_SIZES=folder` (e.g. `../shared/meshes`), it
//! first prints the `GEOM` size of the LR container of every mesh of the folder with more
//! than 1000 vertices at 11, 14 and 16 bits: bytes per vertex and the ratio to 6.

use std::path::{Path, PathBuf};
use std::sync::LazyLock;

use divan::counter::ItemsCount;
use divan::{black_box, Bencher};
use lrmesh::format::Tag;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::read::{open, Limits, Sections};
use lrmesh::write::{encode, EncodeOptions};
use lrmesh::{Mesh, Vertex};

const LOOKUPS: usize = 4096;

static MESH: LazyLock<Mesh> = LazyLock::new(|| {
    let path = std::env::var_os("LRMESH_BENCH_MESH").map_or_else(
        || PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/meshes/b9_mesh.off"),
        PathBuf::from,
    );
    read_mesh(&path, &ReadOptions::default())
        .expect("the bench mesh")
        .mesh
});

/// The LR container of the mesh with positions of `bits` (`None`: f32) at `level`.
fn container(bits: Option<u8>, level: u8) -> Vec<u8> {
    let options = EncodeOptions {
        position_bits: bits,
        level,
        ..EncodeOptions::default()
    };
    encode(&MESH, &options).expect("the bench mesh encodes")
}

static RAW16: LazyLock<Vec<u8>> = LazyLock::new(|| container(Some(16), 0));
static BLOCKED16: LazyLock<Vec<u8>> = LazyLock::new(|| container(Some(16), 6));
static RAW_F32: LazyLock<Vec<u8>> = LazyLock::new(|| container(None, 0));
static BLOCKED_F32: LazyLock<Vec<u8>> = LazyLock::new(|| container(None, 6));

/// Pseudo-random container vertices (SplitMix64), the same for every bench.
static VERTICES: LazyLock<Vec<Vertex>> = LazyLock::new(|| {
    let m = open(&RAW16, &Limits::default())
        .unwrap()
        .connectivity_vertex_count() as u64;
    let mut state = 0x5EED_u64;
    (0..LOOKUPS)
        .map(|_| {
            state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
            let mut z = state;
            z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
            Vertex(((z ^ (z >> 31)) % m) as u32)
        })
        .collect()
});

/// The `GEOM` payload's encoding and length.
fn geom(bytes: &[u8]) -> (u32, usize) {
    let sections = Sections::parse(bytes, &Limits::default()).unwrap();
    let p = sections.section(Tag::GEOM).unwrap().bytes;
    (u32::from_le_bytes(p[..4].try_into().unwrap()), p.len())
}

/// The `GEOM` sizes of the meshes of `folder` (more than 1000 vertices) at 11, 14, 16 bits.
fn sizes(folder: &Path) {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(folder)
        .expect("LRMESH_BENCH_SIZES: a folder")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "off"))
        .collect();
    paths.sort();
    println!(
        "{:<24} {:>7}  GEOM bytes/vertex (ratio to 6) at 11, 14, 16 bits",
        "mesh", "V"
    );
    for path in paths {
        let mesh = read_mesh(&path, &ReadOptions::default()).unwrap().mesh;
        if mesh.positions.len() <= 1000 {
            continue;
        }
        let mut line = String::new();
        let mut m = 0;
        for bits in [11, 14, 16] {
            let options = EncodeOptions {
                position_bits: Some(bits),
                ..EncodeOptions::default()
            };
            let bytes = encode(&mesh, &options).unwrap();
            m = open(&bytes, &Limits::default())
                .unwrap()
                .connectivity_vertex_count();
            let (encoding, len) = geom(&bytes);
            let per_vertex = len as f64 / m as f64;
            line += &format!(
                "  {per_vertex:5.2} ({:.3}, enc. {encoding})",
                per_vertex / 6.0
            );
        }
        let name = path.file_name().unwrap().to_string_lossy();
        println!("{name:<24} {m:>7}{line}");
    }
    println!();
}

fn main() {
    if let Some(folder) = std::env::var_os("LRMESH_BENCH_SIZES") {
        sizes(Path::new(&folder));
    }
    let m = open(&RAW16, &Limits::default())
        .unwrap()
        .connectivity_vertex_count();
    println!(
        "mesh: {m} container vertices, {} triangles",
        MESH.triangles.len()
    );
    for (name, bytes, raw) in [
        ("16-bit, level 0", &*RAW16, 6.0),
        ("16-bit, level 6", &*BLOCKED16, 6.0),
        ("f32, level 0", &*RAW_F32, 12.0),
        ("f32, level 6", &*BLOCKED_F32, 12.0),
    ] {
        let (encoding, len) = geom(bytes);
        let per_vertex = len as f64 / m as f64;
        println!(
            "{name:<16} GEOM encoding {encoding}: {len} bytes, {per_vertex:.2} bytes/vertex, {:.3} of {raw} bytes/vertex",
            per_vertex / raw
        );
    }
    divan::main();
}

/// The sum of the looked-up coordinates, so that no lookup is optimized away.
fn lookups(bencher: Bencher, bytes: &[u8]) {
    let file = open(bytes, &Limits::default()).unwrap();
    let vertices = &*VERTICES;
    bencher.counter(ItemsCount::new(LOOKUPS)).bench(|| {
        vertices
            .iter()
            .map(|&v| {
                let p = file.position(black_box(v));
                p[0] + p[1] + p[2]
            })
            .sum::<f32>()
    });
}

/// Encoding 1: three u16 per vertex.
#[divan::bench]
fn raw_16_bit(bencher: Bencher) {
    lookups(bencher, &RAW16);
}

/// Encoding 4: the 16-bit grid in blocks.
#[divan::bench]
fn blocked_16_bit(bencher: Bencher) {
    lookups(bencher, &BLOCKED16);
}

/// Encoding 0: three f32 per vertex.
#[divan::bench]
fn raw_f32(bencher: Bencher) {
    lookups(bencher, &RAW_F32);
}

/// Encoding 5 (or 0 when blocks are not smaller): the f32s as ordered integers in blocks.
#[divan::bench]
fn blocked_f32(bencher: Bencher) {
    lookups(bencher, &BLOCKED_F32);
}
