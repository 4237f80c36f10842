//! Constant time, counted: every operator reads a bounded number of words of the tables,
//! whatever the mesh (OPERATORS.md §8.5); `v.c` too when the boundaries run along the ring
//! (otherwise it walks the vertex's fan, OPERATORS.md §4.2, as the bit-efficient LR does; the
//! standard LR lists its open fans instead, `crate::lr::open_fans`).

use super::{Zipper, ZipperTables};
use crate::generate;
use crate::ids::{Corner, Triangle, Vertex};
use crate::lr::LrOptions;
use crate::ops::CornerOps;
use crate::words::Counting;
use crate::CornerTable;
use std::cell::Cell;

/// The tables of `z` over counting words.
fn counting<'a>(
    z: &'a ZipperTables<Vec<u32>>,
    reads: &'a Cell<usize>,
) -> ZipperTables<Counting<'a>> {
    let w = |words: &'a Vec<u32>| Counting { words, reads };
    ZipperTables {
        ring_starts: w(&z.ring_starts),
        rings: z.rings,
        ring_last: w(&z.ring_last),
        ring_rank: w(&z.ring_rank),
        ring_blocks: z.ring_blocks.map_words(w),
        planes: w(&z.planes),
        heads: w(&z.heads),
        anchors: z.anchors.map_words(w),
        head_counts: z.head_counts.map_words(w),
        exceptions: z.exceptions.map_words(w),
        records: z.records.map_words(w),
        pairs: z.pairs.map_words(w),
        t0_v: z.t0_v.map_words(w),
        t0_codes: z.t0_codes.map_words(w),
        t0_explicit: z.t0_explicit.map_words(w),
        c: z.c.map_words(w),
        super_counts: w(&z.super_counts),
        m_r: z.m_r,
        m: z.m,
        boundaries_on_ring: z.boundaries_on_ring,
        wart_deltas: z.wart_deltas,
        short_heads: z.short_heads,
        compact: z.compact,
        packed_lists: z.packed_lists,
        four_sides: z.four_sides,
        row_records: z.row_records,
        implied_warts: z.implied_warts,
        joined_lists: z.joined_lists,
        inner_ring_starts: z.inner_ring_starts,
        ring_blocks_flag: z.ring_blocks_flag,
    }
}

/// The most words any operator reads on `mesh`'s Zipper: per operator, the largest count
/// over every corner (vertex, for `v.c`; triangle, for `t.c`).
fn most_reads(mesh: &crate::Mesh) -> ([usize; 10], bool) {
    let ct = CornerTable::from_mesh(mesh).unwrap();
    let z = Zipper::build(&ct, &LrOptions::default()).unwrap();
    let reads = Cell::new(0);
    let t = counting(z.tables(), &reads);
    (most_reads_of(&z, &t, &reads), z.tables().boundaries_on_ring)
}

/// [`most_reads`] of the operators of `t`, which reads `z`'s tables counting in `reads`.
fn most_reads_of<L: CornerOps>(z: &Zipper, t: &L, reads: &Cell<usize>) -> [usize; 10] {
    let corners: Vec<Corner> = z.tables().corners().collect();
    let mut most = [0usize; 10];
    let mut count = |k: usize, f: &dyn Fn()| {
        reads.set(0);
        f();
        most[k] = most[k].max(reads.get());
    };
    for &c in &corners {
        count(0, &|| {
            std::hint::black_box(t.vertex(c));
        });
        count(1, &|| {
            std::hint::black_box(t.opposite(c));
        });
        count(2, &|| {
            std::hint::black_box(t.next(c));
        });
        count(3, &|| {
            std::hint::black_box(t.prev(c));
        });
        count(4, &|| {
            std::hint::black_box(t.swing(c));
        });
        count(5, &|| {
            std::hint::black_box(t.left(c));
        });
        count(6, &|| {
            std::hint::black_box(t.right(c));
        });
        count(7, &|| {
            std::hint::black_box(t.triangle(c));
        });
    }
    for tri in z.tables().triangles() {
        count(8, &|| {
            std::hint::black_box(t.triangle_corner(Triangle(tri.0)));
        });
    }
    for v in 0..z.tables().vertex_id_bound() {
        count(9, &|| {
            std::hint::black_box(t.vertex_corner(Vertex(v)));
        });
    }
    most
}

/// The bound OPERATORS.md §8.5 states.
const MOST_WORDS: usize = 200;

#[test]
fn every_operator_reads_a_bounded_number_of_words() {
    let mut rng = generate::Rng::new(9);
    let mut holes = generate::irregular_torus(50_000, 3);
    generate::punch_holes(&mut holes, 40, &mut rng);
    // Rings of four vertices, sixteen to a block: the most ring starts `RING_BLOCKS` makes a
    // vertex's ring walk past (FORMAT.md §3.5e.2).
    let mut tetrahedra = crate::Mesh::new(Vec::new(), Vec::new());
    let tetrahedron = crate::Mesh::new(
        vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    );
    for _ in 0..48 {
        generate::append(&mut tetrahedra, &tetrahedron);
    }
    let meshes = [
        tetrahedra,
        generate::torus(3, 4),
        generate::torus(30, 40),
        generate::irregular_torus(2_000, 1),
        generate::irregular_torus(200_000, 2),
        holes,
        generate::soup(30, 80, &mut rng),
    ];
    let mut largest = [0usize; 10];
    for mesh in &meshes {
        let (most, on_ring) = most_reads(mesh);
        eprintln!("most words read (c.v c.o c.n c.p c.s c.l c.r c.t t.c v.c): {most:?}, boundaries on the ring: {on_ring}");
        for (l, m) in largest
            .iter_mut()
            .zip(most)
            .take(if on_ring { 10 } else { 9 })
        {
            *l = (*l).max(m);
        }
    }
    assert!(largest.iter().all(|&m| m <= MOST_WORDS), "{largest:?}");
}

/// The bound OPERATORS.md §8.6 states for a cursor's operator.
const CURSOR_MOST_WORDS: usize = 4_000;

/// Through a cursor, an operator reads at most what its slot reads decode: a read of a slot
/// in a block not decoded reads as the tables do, the one that decodes the block reads its
/// planes, head, stored words and ring ends. One cursor is kept across the walk, so that
/// each count includes the blocks its operator decoded.
#[test]
fn a_cursor_reads_a_bounded_number_of_words() {
    let mut rng = generate::Rng::new(9);
    let mut holes = generate::irregular_torus(20_000, 3);
    generate::punch_holes(&mut holes, 40, &mut rng);
    let meshes = [
        generate::torus(3, 4),
        generate::irregular_torus(20_000, 2),
        holes,
        generate::soup(30, 80, &mut rng),
    ];
    let mut largest = 0;
    for mesh in &meshes {
        let ct = CornerTable::from_mesh(mesh).unwrap();
        let z = Zipper::build(&ct, &LrOptions::default()).unwrap();
        let reads = Cell::new(0);
        let t = counting(z.tables(), &reads);
        let kept = most_reads_of(&z, &t.cursor(), &reads);
        let on_ring = z.tables().boundaries_on_ring;
        eprintln!("most words read through a cursor: {kept:?}, boundaries on the ring: {on_ring}");
        let counted = kept.iter().take(if on_ring { 10 } else { 9 });
        largest = largest.max(*counted.max().unwrap());
    }
    assert!(largest <= CURSOR_MOST_WORDS, "{largest}");
}

/// The standard LR tables a Zipper is read back as answer every operator as the Zipper
/// does: meshes with borders, several rings, T0 triangles and irregular slots, and a soup.
#[test]
fn read_back_as_standard_tables_the_answers_agree() {
    let mut rng = generate::Rng::new(5);
    let mut holes = generate::irregular_torus(20_000, 3);
    generate::punch_holes(&mut holes, 30, &mut rng);
    let mut meshes = vec![
        generate::torus(3, 4),
        generate::irregular_torus(5_000, 1),
        holes,
        generate::soup(30, 80, &mut rng),
    ];
    for name in ["b9_mesh.off", "blobby_3cc.off", "cheese.off"] {
        meshes.push(crate::io::corpus_mesh(name));
    }
    for mesh in &meshes {
        let ct = CornerTable::from_mesh(mesh).unwrap();
        let z = Zipper::build(&ct, &LrOptions::default()).unwrap();
        let lr = z.tables().to_lr_tables();
        assert!(crate::lr::read_back::answers_agree(z.tables(), &lr));
        assert_eq!(lr.triangles().count(), z.tables().triangles().count());
    }
}

/// A cursor answers a slot of a block it holds decoded without reading the tables, and after
/// `clear` reads them again, as a new cursor (the benchmarks clear it between runs).
#[test]
fn a_cleared_cursor_reads_the_tables_again() {
    use crate::lr::tables::{LrLayout, LEFT};
    let ct = CornerTable::from_mesh(&generate::irregular_torus(5_000, 1)).unwrap();
    let z = Zipper::build(&ct, &LrOptions::default()).unwrap();
    let reads = Cell::new(0);
    let t = counting(z.tables(), &reads);
    let cursor = t.cursor();
    let valences: u32 = cursor
        .vertices()
        .map(|v| crate::ops::valence(&cursor, v))
        .sum();
    let expected: u32 = ct.vertices().map(|v| crate::ops::valence(&ct, v)).sum();
    assert_eq!(valences, expected);
    // A vertex whose block the loop left decoded: read without the tables.
    let read_free = |v: u32| {
        reads.set(0);
        let tip = cursor.tip(v, LEFT);
        (reads.get() == 0).then_some((v, tip))
    };
    let (v, tip) = (0..t.ring_vertices())
        .find_map(read_free)
        .expect("a decoded block");
    assert_eq!(tip, t.tip(v, LEFT));
    cursor.clear();
    reads.set(0);
    assert_eq!(cursor.tip(v, LEFT), tip);
    assert!(reads.get() > 0, "a cleared cursor reads the tables");
}
