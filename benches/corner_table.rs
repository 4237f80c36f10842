//! Corner-table construction and the generic algorithms on a large irregular mesh.
//!
//! `cargo bench --bench corner_table` prints, before divan's table, the mesh used and the
//! peak heap memory of one construction (measured by a counting allocator). Set
//! `LRMESH_BENCH_TRIANGLES` to change the mesh size (default 2,000,000), or
//! `LRMESH_BENCH_MESH=path` for a mesh file. The Fig. 10 loops are those of `lrmesh bench`
//! (`lrmesh::bench`), here one divan bench each.

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::sync::LazyLock;

mod common;

use divan::counter::ItemsCount;
use divan::{black_box, Bencher};
use lrmesh::bench::contour_starts;
use lrmesh::ops::{self, Plane};
use lrmesh::{CornerOps, CornerTable, Mesh, TopologyReport, Triangle};

/// The system allocator, counting the bytes in use and their high-water mark.
struct PeakAlloc;

static IN_USE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: every call is forwarded unchanged to the system allocator; we only count bytes.
unsafe impl GlobalAlloc for PeakAlloc {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = IN_USE.fetch_add(layout.size(), Relaxed) + layout.size();
            PEAK.fetch_max(now, Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) };
        IN_USE.fetch_sub(layout.size(), Relaxed);
    }
}

#[global_allocator]
static ALLOC: PeakAlloc = PeakAlloc;

static MESH: LazyLock<Mesh> = LazyLock::new(common::bench_mesh);
static TABLE: LazyLock<CornerTable> = LazyLock::new(|| CornerTable::from_mesh(&MESH).unwrap());

/// Positions by corner-table vertex (copies of split vertices included).
static POSITIONS: LazyLock<Vec<[f32; 3]>> =
    LazyLock::new(|| TABLE.extend_to_copies(&MESH.positions));

/// The planes of the contour walks, each with a triangle it cuts (the same as `lrmesh bench`).
static CONTOUR_STARTS: LazyLock<Vec<(Plane, Triangle)>> =
    LazyLock::new(|| contour_starts(&*TABLE, &POSITIONS));

fn triangles() -> usize {
    MESH.triangles.len()
}

fn corners() -> usize {
    MESH.triangles.len() * 3
}

fn main() {
    let mesh = &*MESH;
    let report = TopologyReport::of(mesh);
    let before = IN_USE.load(Relaxed);
    PEAK.store(before, Relaxed);
    let table = CornerTable::from_mesh(mesh).unwrap();
    let peak = PEAK.load(Relaxed) - before;
    let kept = IN_USE.load(Relaxed) - before;
    println!(
        "mesh: {} vertices, {} triangles, genus {:?}, {:.1}% valence 6, max valence {}",
        report.vertices, report.triangles, report.genus, report.valence6_pct, report.max_valence
    );
    println!(
        "corner table construction: peak heap {:.1} MiB ({:.1} bytes/triangle), table itself {:.1} MiB",
        peak as f64 / (1 << 20) as f64,
        peak as f64 / report.triangles as f64,
        kept as f64 / (1 << 20) as f64
    );
    drop(table);
    let walked: usize = CONTOUR_STARTS
        .iter()
        .map(|(plane, t)| ops::contour(&*TABLE, &POSITIONS, plane, *t).len())
        .sum();
    println!(
        "contour bench: {} planes, {walked} triangles walked",
        CONTOUR_STARTS.len()
    );
    divan::main();
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn build(bencher: Bencher) {
    let mesh = &*MESH;
    bencher
        .counter(ItemsCount::new(triangles()))
        .bench(|| CornerTable::from_mesh(black_box(mesh)).unwrap());
}

#[divan::bench(sample_count = 10, sample_size = 1)]
fn topology_report(bencher: Bencher) {
    let mesh = &*MESH;
    bencher
        .counter(ItemsCount::new(triangles()))
        .bench(|| TopologyReport::of(black_box(mesh)));
}

/// c.v over every corner (LR paper, Fig. 10).
#[divan::bench(sample_count = 20)]
fn vertex_of_every_corner(bencher: Bencher) {
    let table = &*TABLE;
    bencher
        .counter(ItemsCount::new(corners()))
        .bench(|| table.corners().fold(0u32, |acc, c| acc ^ table.vertex(c).0));
}

/// c.o over every corner (LR paper, Fig. 10).
#[divan::bench(sample_count = 20)]
fn opposite_of_every_corner(bencher: Bencher) {
    let table = &*TABLE;
    bencher.counter(ItemsCount::new(corners())).bench(|| {
        table
            .corners()
            .fold(0u32, |acc, c| acc ^ table.opposite(c).map_or(0, |o| o.0))
    });
}

/// Valence of every vertex, by swinging (LR paper, Fig. 10).
#[divan::bench(sample_count = 20)]
fn valence_of_every_vertex(bencher: Bencher) {
    let table = &*TABLE;
    bencher
        .counter(ItemsCount::new(table.vertex_id_bound() as usize))
        .bench(|| {
            table
                .vertices()
                .map(|v| ops::valence(table, v))
                .sum::<u32>()
        });
}

/// Normal of every vertex from its star (LR paper, Fig. 10).
#[divan::bench(sample_count = 20)]
fn normal_of_every_vertex(bencher: Bencher) {
    let table = &*TABLE;
    let positions = &*POSITIONS;
    bencher
        .counter(ItemsCount::new(table.vertex_id_bound() as usize))
        .bench(|| ops::vertex_normals(table, positions));
}

/// Contour traversal: triangles walked across cut edges (LR paper, section 8 and Fig. 10).
#[divan::bench(sample_count = 20)]
fn contour_walk(bencher: Bencher) {
    let table = &*TABLE;
    let positions = &*POSITIONS;
    let walked: usize = CONTOUR_STARTS
        .iter()
        .map(|(plane, t)| ops::contour(table, positions, plane, *t).len())
        .sum();
    bencher.counter(ItemsCount::new(walked)).bench(|| {
        CONTOUR_STARTS
            .iter()
            .map(|(plane, t)| ops::contour(table, positions, plane, *t).len())
            .sum::<usize>()
    });
}
