//! Forged containers for the rules of `EBRK`, the Edgebreaker stream (§3.5b of
//! `spec/FORMAT.md`), **[V27]**, and of `STRP`, the strips and adjacent-strips tables (§3.5c),
//! **[V28]**..**[V32]**. How a rule is broken and what the reader must report:
//! `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::StrpHeader;
use lrmesh::format::Tag;
use lrmesh::read::{open, Limits};
use lrmesh::write::Connectivity;
use lrmesh::{Corner, CornerOps, Rule, Vertex};

// ---------------------------------------------------------------------------------------
// §3.5b EBRK.

/// [V27] The stream is valid by EDGEBREAKER.md, decodes to `V` vertices, and to no
/// degenerate triangle. (Decoded ids are below `nv − nu ≤ V` in any valid stream, so that
/// clause cannot break alone; `N` is [V12]'s, tested there.)
#[test]
fn v27_edgebreaker_stream() {
    let hedra = lrmesh::load(common::corpus_dir().join("hedra_open.off")).unwrap();
    let bytes = encoded(&hedra, Connectivity::Edgebreaker);
    let at = section_at(&bytes, Tag::EBRK);
    let stream = payload(&bytes, Tag::EBRK);
    // Invalid streams: the stream's own offset is added to the section's.
    let bad = forge(&bytes, Tag::EBRK, |p| p[0] = 0xEA);
    breaks(&bad, 27, "EBRK", at, "magic");
    let bad = forge(&bytes, Tag::EBRK, |p| p[1] = 2);
    breaks(&bad, 27, "EBRK", at + 1, "version");
    let bad = forge(&bytes, Tag::EBRK, |p| p.truncate(4));
    breaks(
        &bad,
        27,
        "EBRK",
        at + 4,
        "header ends inside the triangle count",
    );
    // A valid stream of V + 1 vertices (one more unreferenced).
    assert!(stream[2] < 0x7F && stream[3] < 0x7F);
    let bad = forge(&bytes, Tag::EBRK, |p| {
        p[2] += 1;
        p[3] += 1;
    });
    assert!(lrmesh::edgebreaker::decode(&payload(&bad, Tag::EBRK), &Default::default()).is_ok());
    let e = format_error(&bad);
    assert_eq!(
        (e.rule, e.section.as_str()),
        (Rule(27), "EBRK"),
        "{}",
        e.message
    );
    assert!(e.message.contains("section MESH says 6"), "{}", e.message);
    // A valid stream decoding to a degenerate triangle (tests/container.rs).
    let degenerate = [0xeb, 0x01, 0x06, 0x00, 0x06, 0x02, 0x86, 0xa0, 0x2a];
    let bad = forge(&bytes, Tag::EBRK, |p| *p = degenerate.to_vec());
    breaks(&bad, 27, "EBRK", at, "degenerate");
}

/// [V27] A stream with the wrong vertex count is located at its vertex count `nv`, byte 2
/// of the stream.
#[test]

fn v27_vertex_count_located() {
    let hedra = lrmesh::load(common::corpus_dir().join("hedra_open.off")).unwrap();
    let bytes = encoded(&hedra, Connectivity::Edgebreaker);
    let bad = forge(&bytes, Tag::EBRK, |p| {
        p[2] += 1;
        p[3] += 1;
    });
    breaks(&bad, 27, "EBRK", section_at(&bytes, Tag::EBRK) + 2, "");
}

// ---------------------------------------------------------------------------------------
// §3.5c STRP.

/// [V28] `STRP` counts and length. (`m < 0xFFFFFFFF` cannot break alone: `m = V`.)
#[test]
fn v28_strips_counts() {
    let bytes = vector("closed_tetrahedron.strips.lrm"); // m = 4, L = 8
    let at = section_at(&bytes, Tag::STRP);
    let field = |f: usize, x: u32| forge(&bytes, Tag::STRP, |p| put(p, f, x));
    breaks(&field(0, 5), 28, "STRP", at, "section MESH says 4");
    breaks(&field(8, 1), 28, "STRP", at + 8, "reserved");
    // Odd, or 3 L ≥ 2^32 − 1.
    for len in [7, 9, 0x5555_5556] {
        breaks(&field(4, len), 28, "STRP", at + 4, "even");
    }
    breaks(&field(4, 10), 28, "STRP", at, "counts call for");
    let bad = forge(&bytes, Tag::STRP, |p| p.extend([0; 4]));
    breaks(&bad, 28, "STRP", at, "counts call for");
    let bad = forge(&bytes, Tag::STRP, |p| p.truncate(15));
    breaks(&bad, 28, "STRP", at, "header");
}

/// [V28] The second reserved word is located at offset 12.
#[test]

fn v28_reserved_located() {
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| put(p, 12, 1));
    breaks(&bad, 28, "STRP", section_at(&bytes, Tag::STRP) + 12, "");
}

/// [V29] `T`: strips of at least three vertex ids below `m`, from even positions, each
/// followed by exactly its one or two delimiters; first and last windows triangles; never
/// two swaps in a row.
#[test]
fn v29_strip_layout() {
    // T = 2 0 1 3 2 0 D D.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let t = |i: usize| strp_at(&bytes, "T", i);
    let with = |entries: &[(usize, u32)]| {
        forge(&bytes, Tag::STRP, |p| {
            for &(i, x) in entries {
                let at = strp_word(p, "T", i);
                put(p, at, x)
            }
        })
    };
    breaks(&with(&[(0, NONE)]), 29, "STRP", t(0), "found a delimiter");
    for x in [4, NONE - 1] {
        breaks(&with(&[(3, x)]), 29, "STRP", t(3), "out of range");
    }
    let bad = with(&[(2, NONE), (3, NONE)]);
    breaks(&bad, 29, "STRP", t(0), "fewer than 3");
    let bad = with(&[(7, 1)]);
    breaks(&bad, 29, "STRP", t(7), "followed by 2 delimiters");
    // A strip running to the end of T: its padding would lie past it.
    let a0 = strp_at(&bytes, "A", 0);
    breaks(&with(&[(6, 1), (7, 3)]), 29, "STRP", a0, "padding");
    // First window a swap: 2 2 1 ...
    let bad = with(&[(1, 2)]);
    breaks(&bad, 29, "STRP", t(0), "start and end with a triangle");
    // Two swaps in a row, in a mesh whose strips have swaps.
    let torus = vector("torus_with_t0.strips.lrm");
    let p = payload(&torus, Tag::STRP);
    let len = StrpHeader::read(&p).len as usize;
    let t_of = |i: usize| get(&p, strp_word(&p, "T", i));
    // A swap at w (T[w] = T[w+2]) inside a strip, with a triangle after it: make w + 1 a
    // swap as well (T[w+3] = T[w+1]).
    let w = (0..len - 5)
        .find(|&w| {
            (w..w + 6).all(|i| t_of(i) != NONE)
                && t_of(w) == t_of(w + 2)
                && t_of(w + 1) != t_of(w + 3)
                && w >= 1
                && t_of(w - 1) != NONE
        })
        .expect("a swap inside a strip");
    let bad = forge(&torus, Tag::STRP, |p| {
        let x = get(p, strp_word(p, "T", w + 1));
        set_strp(p, "T", w + 3, x)
    });
    breaks(
        &bad,
        29,
        "STRP",
        strp_at(&torus, "T", w),
        "two swaps in a row",
    );
}

/// [V29] A strip whose last window is a swap is located at that window.
#[test]

fn v29_last_window_located() {
    let bytes = vector("closed_tetrahedron.strips.lrm"); // T = 2 0 1 3 2 0 D D
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "T", 5, 3));
    breaks(&bad, 29, "STRP", strp_at(&bytes, "T", 3), "");
}

/// [V30] Entries of `A` that the operators read are `DELIMITER` or a triangle's position;
/// the others are `DELIMITER`.
#[test]
fn v30_adjacent_strips() {
    // T = 2 0 1 3 2 0 D D, triangles at 0..4; A = 3 2 3 0 1 0 D D.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let a = |i: usize| strp_at(&bytes, "A", i);
    let set = |i: usize, x: u32| forge(&bytes, Tag::STRP, |p| set_strp(p, "A", i, x));
    for (i, x) in [(0, 4), (1, 5), (5, 8), (2, NONE - 1)] {
        let bad = set(i, x);
        breaks(&bad, 30, "STRP", a(i), "not the position of a triangle");
    }
    for (i, x) in [(6, 0), (7, 3)] {
        breaks(&set(i, x), 30, "STRP", a(i), "no operator reads");
    }
}

/// [V31] Strips opposites are an involution across one edge.
#[test]
fn v31_strips_opposites() {
    // A[1] = 2 (triangle 0 across {2, 1}) made 3: corner 1's opposite becomes a corner of
    // triangle 3, which faces another edge. Triangle 0 is at T[0].
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 1, 3));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&bytes, "T", 0),
        "do not face each other",
    );
    // A[0] = 3 made 0: corner 2 of triangle 0 is its own opposite (o.o = c, but the
    // vertices do not match).
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 0, 0));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&bytes, "T", 0),
        "corner 2 and its opposite 2",
    );
    // A vertex changed: T = 1 0 4 0 3 2 5 2 1 0 D D with T[3] = 0 made 5, triangle 3
    // (window 0 3 2) no longer shares its edges' vertices with its neighbours. Window 1 stops
    // being a swap and holds a seventh triangle: MESH says so too (without PERM, whose counts
    // would then differ), so that the counts of a well-formed file agree.
    let open_hedra = forge_sections(&vector("boundary_hedra_open.strips.lrm"), |s| {
        s.retain(|section| section.0 != Tag::PERM)
    });
    let bad = forge(&open_hedra, Tag::STRP, |p| set_strp(p, "T", 3, 5));
    let bad = forge(&bad, Tag::MESH, |p| put(p, 8, 7));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&open_hedra, "T", 3),
        "corner 9 and its opposite",
    );
}

/// [V31] A corner whose opposite is smaller and does not point back is located at a
/// triangle.
#[test]

fn v31_opposite_not_pointing_back_is_located() {
    // A[0] = 3 made DELIMITER: corner 2 of triangle 0 loses its opposite, corner 10 of
    // triangle 3 (at T[3]) still names corner 2.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 0, NONE));
    breaks(&bad, 31, "STRP", strp_at(&bytes, "T", 3), "");
}

/// [V32] `C[v]` is `NONE` for an unused vertex and otherwise a corner of `v`.
#[test]
fn v32_strips_vertex_corners() {
    let bytes = vector("boundary_hedra_open.strips.lrm"); // m = 6, L = 12
    let view = open(&bytes, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let set = |v: usize, x: u32| forge(&bytes, Tag::STRP, |p| set_strp(p, "C", v, x));
    // Not a corner: T = 1 0 4 0 3 2 5 2 1 0 D D has swaps at 1 and 5, no window at 8.
    for x in [3, 3 * 5 + 1, 3 * 8, 3 * 12, NONE - 1] {
        assert!(!strips.is_corner(Corner(x)));
        let bad = set(2, x);
        breaks(&bad, 32, "STRP", strp_at(&bytes, "C", 2), "not a corner");
    }
    // A corner of another vertex.
    for v in 0..6u32 {
        let c = strips.corners().find(|&c| strips.vertex(c).0 != v).unwrap();
        let bad = set(v as usize, c.0);
        breaks(
            &bad,
            32,
            "STRP",
            strp_at(&bytes, "C", v as usize),
            "is a corner of vertex",
        );
    }
    // The unreferenced vertex of nonmanifold_vertex given a corner.
    let unused = vector("nonmanifold_vertex.strips.lrm");
    let view = open(&unused, &Limits::default()).unwrap();
    let s = view.strips().unwrap();
    let v = (0..s.vertex_id_bound())
        .find(|&v| s.vertex_corner(Vertex(v)).is_none())
        .unwrap();
    let bad = forge(&unused, Tag::STRP, |p| set_strp(p, "C", v as usize, 0));
    breaks(
        &bad,
        32,
        "STRP",
        strp_at(&unused, "C", v as usize),
        "is a corner of vertex",
    );
}
