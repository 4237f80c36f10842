//! Forged containers for the rules of `LRTB`, the standard LR tables (§3.5 of
//! `spec/FORMAT.md`), **[V15]**..**[V23]**, and for **[V38]**, the vertex corner starting its
//! fan, in every kind that stores one (`LRTB`, `LRBE`, `STRP`). How a rule is broken and what
//! the reader must report: `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::{LrtbHeader, LR_OPEN_FANS};
use lrmesh::format::Tag;
use lrmesh::generate::{self, Rng};
use lrmesh::lr::{LrLayout, IRREGULAR, NULL, VALUE, WART};
use lrmesh::read::{open, Limits};
use lrmesh::write::Connectivity;
use lrmesh::{Corner, CornerOps, Mesh, Rule, Vertex};

// ---------------------------------------------------------------------------------------
// §3.5 LRTB.

/// [V15] `LRTB` counts and length. (`m < 0x3FFFFFFF` cannot be broken alone: `m = V`, and
/// `GEOM` would need `12 V` bytes first.)
#[test]
fn v15_lrtb_counts() {
    let bytes = vector("closed_tetrahedron.lrm"); // m = m_r = 4, R = 1, n0 = ni = 0
    let at = section_at(&bytes, Tag::LRTB);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRTB, |p| put(p, f, x));
    breaks(&field(0, 5), 15, "LRTB", at, "section MESH says 4");
    breaks(&field(0, 3), 15, "LRTB", at, "section MESH says 4");
    breaks(&field(20, 4), 15, "LRTB", at + 20, "unknown flag bits");
    // m_r > m; R = 0 iff m_r = 0; 4R ≤ m_r.
    for m_r in [5, 0, 3] {
        breaks(&field(4, m_r), 15, "LRTB", at + 4, "ring vertices");
    }
    // 8 m_r + 4 n0 < 2^32 − 1.
    breaks(&field(12, 0x4000_0000), 15, "LRTB", at + 12, "32 bits");
    breaks(&field(12, 0x3FFF_FFF8), 15, "LRTB", at + 12, "32 bits");
    // Length: 32 + 4 (R + 1 + 2⌈m_r/32⌉ + 2 m_r + 6 n0 + 3 ni + m − m_r).
    let bad = forge(&bytes, Tag::LRTB, |p| p.extend([0; 4]));
    breaks(&bad, 15, "LRTB", at, "counts call for");
    let bad = forge(&bytes, Tag::LRTB, |p| p.truncate(76));
    breaks(&bad, 15, "LRTB", at, "counts call for");
    let bad = forge(&bytes, Tag::LRTB, |p| p.truncate(31));
    breaks(&bad, 15, "LRTB", at, "header");
    breaks(&field(12, 1), 15, "LRTB", at, "counts call for");
}

/// [V15] The reserved word at 28 and the record count at 16 are located at their own fields
/// (the fan count at 24: [V61]).
#[test]
fn v15_lrtb_fields_located_exactly() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::LRTB);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRTB, |p| put(p, f, x));
    breaks(&field(28, 1), 15, "LRTB", at + 28, "");
    breaks(&field(16, NULL), 15, "LRTB", at + 16, "");
}

/// [V16] Rings: starts from 0 by at least 4 to `m_r`; `ring_last`, `ring_rank` as implied,
/// padding bits 0; `[0]` without ring vertices.
#[test]
fn v16_rings() {
    let two = vector("two_components.lrm"); // ring_starts [0, 4, 8], ring_last [0x88]
    let starts = |i: usize| lrtb_at(&two, "ring_starts", i);
    let word = |bytes: &[u8], name: &str, i: usize, x: u32| {
        forge(bytes, Tag::LRTB, |p| {
            let at = LrtbHeader::read(p).layout().unwrap().array(name).at(i);
            put(p, at, x)
        })
    };
    let bad = word(&two, "ring_starts", 0, 1);
    breaks(&bad, 16, "LRTB", starts(0), "ring start 1");
    let bad = word(&two, "ring_starts", 1, 3);
    breaks(&bad, 16, "LRTB", starts(1), "ring start 3");
    let bad = word(&two, "ring_starts", 1, 5);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 8");
    let bad = word(&two, "ring_starts", 2, 9);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 9");
    let bad = word(&two, "ring_starts", 2, 7);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 7");
    let last = lrtb_at(&two, "ring_last", 0);
    for bits in [0x08, 0x80, 0x89, 0x88 | 1 << 8, 0x88 | 1 << 31] {
        let bad = word(&two, "ring_last", 0, bits);
        breaks(&bad, 16, "LRTB", last, "ring-end bits");
    }
    let rank = lrtb_at(&two, "ring_rank", 0);
    let bad = word(&two, "ring_rank", 0, 1);
    breaks(&bad, 16, "LRTB", rank, "ring ranks");
    // No ring vertices: ring_starts is [0].
    let empty = encoded(&Mesh::new(vec![[0.0; 3]; 3], vec![]), Connectivity::Lr);
    assert_eq!(LrtbHeader::read(&payload(&empty, Tag::LRTB)).m_r, 0);
    let at = lrtb_at(&empty, "ring_starts", 0);
    breaks(&word(&empty, "ring_starts", 0, 3), 16, "LRTB", at, "[0]");
}

/// [V17] LR entries: records in range, used once, tips below `m`; plain values below `m` or
/// `NULL` in a right entry without WART; every record used.
#[test]
fn v17_lr_entries() {
    let bytes = vector("torus_with_t0.lrm"); // m = m_r = 25, 9 records
    let p = payload(&bytes, Tag::LRTB);
    let h = LrtbHeader::read(&p);
    let entry = |slot: usize| get(&p, lrtb_word(&p, LR, slot));
    let entry_at = |slot: usize| lrtb_at(&bytes, "LR", slot);
    let set = |slot: usize, x: u32| forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, slot, x));
    let irregular: Vec<usize> = (0..50).filter(|&s| entry(s) & IRREGULAR != 0).collect();
    let plain: Vec<usize> = (0..50)
        .filter(|&s| entry(s) & (IRREGULAR | WART) == 0)
        .collect();
    assert!(irregular.len() >= 2);
    let (s1, s2) = (irregular[0], irregular[1]);
    // A record beyond ni; one used twice (reported at its second user), which only a
    // verifying reader sees (a semantic clause: every answer stays in range).
    let bad = set(s1, IRREGULAR | h.records);
    breaks(&bad, 17, "LRTB", entry_at(s1), "missing");
    let bad = set(s2, (entry(s2) & WART) | IRREGULAR | (entry(s1) & VALUE));
    breaks(&bad, 17, "LRTB", entry_at(s2), "used twice");
    assert!(open(&bad, &Limits::default()).is_ok());
    // Plain values out of range; NULL on the left, or with WART on the right.
    let (left, right) = (
        *plain.iter().find(|&&s| s % 2 == 0).unwrap(),
        *plain.iter().find(|&&s| s % 2 == 1).unwrap(),
    );
    for x in [25, 26, NULL - 1] {
        breaks(&set(left, x), 17, "LRTB", entry_at(left), "out of range");
        breaks(&set(right, x), 17, "LRTB", entry_at(right), "out of range");
    }
    breaks(&set(left, NULL), 17, "LRTB", entry_at(left), "out of range");
    let bad = set(right, WART | NULL);
    breaks(&bad, 17, "LRTB", entry_at(right), "out of range");
    // A record no entry uses: one appended to VO*.
    let mut t = Tables::lrtb(&p);
    t.head[4] += 1;
    t.array(VO_STAR).extend([0, NONE, NONE]);
    let bad = forge(&bytes, Tag::LRTB, |p| *p = t.join());
    let at = lrtb_at(&bad, "VO*", 3 * h.records as usize);
    breaks(&bad, 17, "LRTB", at, "not used by any entry");
    assert!(open(&bad, &Limits::default()).is_ok());
}

/// [V17] A record's tip out of range is located at the record's tip word.
#[test]

fn v17_record_tip_located_at_the_record() {
    let bytes = vector("torus_with_t0.lrm");
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_STAR, 0, 25));
    breaks(&bad, 17, "LRTB", lrtb_at(&bytes, "VO*", 0), "");
}

/// [V18] `VO_V` entries are below `m`.
#[test]
fn v18_t0_vertices() {
    let bytes = vector("torus_with_t0.lrm"); // 3 T0 triangles
    for (i, x) in [(0, 25), (5, 26), (8, NONE)] {
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_V, i, x));
        breaks(&bad, 18, "LRTB", lrtb_at(&bytes, "VO_V", i), "out of range");
    }
}

/// [V19] A redundant or WART slot's next slot on the same side holds a canonical triangle.
#[test]
fn v19_redundant_and_wart_slots() {
    // Ring 0 → 1 → 2 → 3: L = [3, 3, 1, 1]; L[1] and L[3] are redundant copies.
    let bytes = vector("closed_tetrahedron.lrm");
    let at = lrtb_at(&bytes, "LR", 0);
    // L[0] = 2 = 0.n.n: slot 0 turns redundant, and slot (1, LEFT) is redundant too.
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, 2));
    breaks(&bad, 19, "LRTB", at, "slot 0 points to slot 2");
    // A WART on slot 0, whose next slot (1, LEFT) is redundant.
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, WART | 3));
    breaks(&bad, 19, "LRTB", at, "slot 0 points to slot 2");
    // A WART on a right slot whose next right slot is NULL (a boundary ring edge).
    let open_hedra = vector("boundary_hedra_open.lrm");
    let view = open(&open_hedra, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let v = (0..6)
        .find(|&v| lr.tip(v, 1) != NULL && lr.tip(lr.ring_next(v), 1) == NULL)
        .unwrap() as usize;
    let bad = forge(&open_hedra, Tag::LRTB, |p| {
        let at = lrtb_word(p, LR, 2 * v + 1);
        let x = get(p, at) | WART;
        put(p, at, x)
    });
    breaks(
        &bad,
        19,
        "LRTB",
        lrtb_at(&open_hedra, "LR", 2 * v + 1),
        "holds no canonical triangle",
    );
}

/// [V20] `VO_O`, `C` and the opposites of `VO*` hold `NONE` or canonical corners.
#[test]
fn v20_stored_corners() {
    let bytes = vector("defective_torus.lrm"); // m_r = 16: corners 0..128 and T0 corners
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    // 3 (c & 3 = 3), a corner of a redundant or missing slot, one past the last T0 corner.
    let redundant = (0..128)
        .find(|&c| c & 3 != 3 && !lr.is_corner(Corner(c)))
        .unwrap();
    let past = 8 * 16 + 4 * 5;
    for x in [3, redundant, past, NONE - 1] {
        for (index, name, i) in [
            (VO_O, "VO_O", 4),
            (VO_STAR, "VO*", 1),
            (VO_STAR, "VO*", 5),
            (LRTB_C, "C", 0),
        ] {
            let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, index, i, x));
            breaks(&bad, 20, "LRTB", lrtb_at(&bytes, name, i), "not a corner");
        }
    }
}

/// [V21] No canonical triangle has two equal vertices.
#[test]
fn v21_degenerate_triangles() {
    // Slot 0 of the tetrahedron is (0, L[0], 1): its tip made 1 or 0.
    let bytes = vector("closed_tetrahedron.lrm");
    for tip in [0, 1] {
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, tip));
        breaks(&bad, 21, "LRTB", lrtb_at(&bytes, "LR", 0), "degenerate");
    }
    // A T0 triangle with its second vertex made its first: one whose corners all lack an
    // opposite (a triangle left alone by the cuts), so that no opposite check sees it first.
    let t0 = vector("defective_torus.lrm");
    let j = lone_t0_triangle(&t0);
    let p = payload(&t0, Tag::LRTB);
    let first = get(&p, lrtb_word(&p, VO_V, 3 * j));
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_V, 3 * j + 1, first));
    breaks(&bad, 21, "LRTB", lrtb_at(&t0, "VO_V", 3 * j), "degenerate");
}

/// [V22] `c.o` is an involution across one edge: `o.o = c`, `o.n.v = c.p.v`,
/// `o.p.v = c.n.v`. (`o` is a canonical corner whenever [V17], [V19] and [V20] hold.)
#[test]
fn v22_opposites() {
    // The tetrahedron's L[1] = 3 made 0: slot 2 becomes (1, 0, 2), whose corner 10 the
    // ring rules pair with corner 12 of slot 3 across an edge they do not share. Slot 2 was
    // a redundant copy and now holds a fifth triangle: MESH says so too (without PERM, whose
    // counts would then differ), so that the counts of a well-formed file agree.
    let bytes = forge_sections(&vector("closed_tetrahedron.lrm"), |s| {
        s.retain(|section| section.0 != Tag::PERM)
    });
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 2, 0));
    let bad = forge(&bad, Tag::MESH, |p| put(p, 8, 5));
    breaks(
        &bad,
        22,
        "LRTB",
        lrtb_at(&bytes, "LR", 2),
        "corner 10 and its opposite 12",
    );
    // o.o ≠ c: a T0 corner's stored opposite replaced by a later corner that is not paired
    // with it; the pair is checked from the smaller corner, the T0 corner.
    let t0 = vector("genus3_torus.lrm"); // T0 triangles next to one another
    let view = open(&t0, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let first_t0 = 8 * lr.ring_vertices();
    let t0_corners = 3 * (lr.triangle_id_bound() - 2 * lr.ring_vertices());
    let (k, c) = (0..t0_corners)
        .map(|k| (k, Corner(first_t0 + k / 3 * 4 + k % 3)))
        .find(|&(_, c)| lr.opposite(c).is_some_and(|o| o.0 > c.0))
        .unwrap();
    let other = lr
        .corners()
        .find(|&o| o.0 > c.0 && lr.opposite(o) != Some(c) && lr.opposite(c) != Some(o))
        .unwrap();
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, other.0));
    breaks(
        &bad,
        22,
        "LRTB",
        lrtb_at(&t0, "VO_V", k as usize),
        "do not face each other",
    );
    // o.o = c but not across one edge: a T0 corner made its own opposite.
    let (k, c) = (0..t0_corners)
        .map(|k| (k, Corner(first_t0 + k / 3 * 4 + k % 3)))
        .find(|&(_, c)| lr.opposite(c).is_none_or(|o| o.0 > c.0))
        .unwrap();
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, c.0));
    let message = format!("corner {} and its opposite {}", c.0, c.0);
    breaks(&bad, 22, "LRTB", lrtb_at(&t0, "VO_V", k as usize), &message);
}

/// [V22] A corner whose opposite is a smaller corner that does not point back is located
/// at that corner.
#[test]

fn v22_opposite_not_pointing_back_is_located() {
    // A T0 corner c whose opposite o is larger, given NONE: o.o = c no longer points back,
    // and o is the corner at fault.
    let bytes = vector("genus3_torus.lrm"); // T0 triangles next to one another
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let m_r = lr.ring_vertices();
    let t0_corners = 3 * (lr.triangle_id_bound() - 2 * m_r);
    let (k, o) = (0..t0_corners)
        .map(|k| (k, Corner(8 * m_r + k / 3 * 4 + k % 3)))
        .find_map(|(k, c)| lr.opposite(c).filter(|o| o.0 > c.0).map(|o| (k, o)))
        .unwrap();
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, NONE));
    let at = if o.0 >= 8 * m_r {
        lrtb_at(&bytes, "VO_V", (o.0 - o.0 / 4 - 6 * m_r) as usize)
    } else {
        lrtb_at(
            &bytes,
            "LR",
            2 * (o.0 as usize >> 3) + (o.0 as usize >> 2 & 1),
        )
    };
    breaks(&bad, 22, "LRTB", at, "");
}

/// [V23] `v.c.v = v`.
#[test]
fn v23_vertex_corner_is_its_own() {
    let bytes = vector("defective_torus.lrm"); // off-ring vertices 16..23, C at their words
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    for i in [0, 2, 6] {
        let v = 16 + i as u32;
        let c = lr.corners().find(|&c| lr.vertex(c).0 != v).unwrap();
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, i, c.0));
        breaks(
            &bad,
            23,
            "LRTB",
            lrtb_at(&bytes, "C", i),
            "is a corner of vertex",
        );
    }
    // An unreferenced vertex (C[1] = NONE) given a corner: of another vertex, necessarily.
    let c = lr.corners().next().unwrap();
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, 1, c.0));
    breaks(
        &bad,
        23,
        "LRTB",
        lrtb_at(&bytes, "C", 1),
        "the corner of vertex 17",
    );
}

// ---------------------------------------------------------------------------------------
// §3.5 (all kinds) vertex corners and fans.

/// Ten vertices and fourteen random triangles: its LR has off-ring vertices with open fans
/// of two corners.
fn soup() -> Mesh {
    generate::soup(10, 14, &mut Rng::new(31))
}

/// The corners of `v`, and the one that starts its fan if the fan is open.
fn fan_of<M: CornerOps>(mesh: &M, v: u32) -> (Vec<Corner>, Option<Corner>) {
    let corners: Vec<Corner> = mesh
        .corners()
        .filter(|&c| mesh.vertex(c) == Vertex(v))
        .collect();
    let start = corners.iter().copied().find(|&c| mesh.unswing(c).is_none());
    (corners, start)
}

/// A vertex of `mesh` among `vertices` whose fan is open and has a corner other than its
/// start: `(v, that corner)`.
fn open_fan<M: CornerOps>(mesh: &M, vertices: std::ops::Range<u32>) -> (u32, Corner) {
    vertices
        .filter_map(|v| {
            let (corners, start) = fan_of(mesh, v);
            let start = start?;
            corners.into_iter().find(|&c| c != start).map(|c| (v, c))
        })
        .next()
        .expect("a vertex with an open fan of two corners")
}

/// [V53] The flag that every boundary runs along the ring, set on a mesh whose LR has
/// corners off the ring without an opposite (the writer leaves it clear there): a verifying
/// reader refuses it, in `LRTB` and `LRBE`; a well-formed open takes it at its word and
/// answers in range.
#[test]
fn v53_boundary_flag_holds() {
    for (connectivity, tag, at) in [
        (Connectivity::Lr, Tag::LRTB, 20),
        (Connectivity::LrCompact, Tag::LRBE, 28),
    ] {
        let bytes = encoded(&soup(), connectivity);
        assert_eq!(
            get(&payload(&bytes, tag), at) & 1,
            0,
            "the writer leaves the flag clear"
        );
        let bad = forge(&bytes, tag, |p| {
            let flags = get(p, at) | 1;
            put(p, at, flags)
        });
        breaks(
            &bad,
            53,
            &tag.name(),
            section_at(&bytes, tag) + at as u64,
            "every boundary runs along the ring",
        );
    }
    // The writer sets the flag where it holds, as on closed meshes.
    for name in ["closed_tetrahedron.lrm", "torus_with_t0.lrm"] {
        let bytes = vector(name);
        assert_eq!(get(&payload(&bytes, Tag::LRTB), 20), 1, "{name}");
    }
}

/// [V61] The list of open fans (`LRTB` flag `OPEN_FANS`): a fan count only with the flag and
/// at most `m_r`, no bit past the last ring vertex, the ranks the bits imply, as many bits
/// as fans, each fan's corner a corner of the mesh. A listed corner of another vertex, or an
/// open fan left out, is caught by the verifying reader ([V23], [V38]), and a well-formed
/// open still answers in range.
#[test]
fn v61_open_fans_listed() {
    // Without the flag, the count is 0.
    let closed = vector("closed_tetrahedron.lrm");
    let bad = forge(&closed, Tag::LRTB, |p| put(p, 24, 1));
    breaks(
        &bad,
        61,
        "LRTB",
        section_at(&closed, Tag::LRTB) + 24,
        "without the flag",
    );

    let bytes = vector("boundary_hedra_open.lrm");
    let p = payload(&bytes, Tag::LRTB);
    let h = LrtbHeader::read(&p);
    assert_eq!(
        h.flags & LR_OPEN_FANS,
        LR_OPEN_FANS,
        "the writer lists the open fans"
    );
    assert_eq!(
        (h.m_r, h.open_fans),
        (6, 1),
        "one fan of six ring vertices listed"
    );
    let at = section_at(&bytes, Tag::LRTB);
    let (bits, rank, fans) = (FAN_BITS, FAN_RANK, FANS);
    let word = |i: usize, k: usize| get(&p, lrtb_word(&p, i, k));
    let listed = word(bits, 0).trailing_zeros();
    breaks(
        &forge(&bytes, Tag::LRTB, |p| put(p, 24, 7)),
        61,
        "LRTB",
        at + 24,
        "7 open fans listed for 6 ring vertices",
    );
    let set_bits = |x: u32| forge(&bytes, Tag::LRTB, |p| set_lrtb(p, bits, 0, x));
    breaks(
        &set_bits(word(bits, 0) | 1 << 6),
        61,
        "LRTB",
        lrtb_at(&bytes, "fan_bits", 0),
        "past the last ring vertex",
    );
    breaks(
        &set_bits(0),
        61,
        "LRTB",
        lrtb_at(&bytes, "fan_bits", 0),
        "0 ring vertices marked for 1 fans",
    );
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, rank, 0, 1));
    breaks(
        &bad,
        61,
        "LRTB",
        lrtb_at(&bytes, "fan_rank", 0),
        "rank 1 where the bits before count 0",
    );
    // Corner 3 is in no triangle (corners 8v + 3 are unused).
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, fans, 0, 3));
    breaks(
        &bad,
        61,
        "LRTB",
        lrtb_at(&bytes, "FANS", 0),
        "not a corner of the mesh",
    );

    // Semantic: the fan listed for another vertex, whose v.c then is a corner of `listed`.
    let other = (listed + 1) % 6;
    let bad = set_bits(1 << other);
    let rule = format_error(&bad).rule;
    assert!([Rule(23), Rule(38)].contains(&rule), "{rule}");
    // The fan's corner moved to another corner of the same vertex, not its start.
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let start = lr.vertex_corner(Vertex(listed)).unwrap();
    let (corners, first) = fan_of(lr, listed);
    assert_eq!(first, Some(start));
    let later = corners
        .into_iter()
        .find(|&c| c != start)
        .expect("a second corner");
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, fans, 0, later.0));
    assert_eq!(format_error(&bad).rule, Rule(38));
}

/// [V38] `v.c = NONE` iff no triangle has `v`; an open fan's `v.c` starts it. For `LRTB`
/// and `LRBE` on an off-ring vertex's `C`, for `STRP` on `C[v]`. (A `C` naming a corner for
/// an unused vertex names another vertex's corner: [V23] or [V32] catches it first.)
#[test]
fn v38_vertex_corner_starts_its_fan() {
    // A used off-ring vertex with C = NONE (LRTB, LRBE), a used vertex with C[v] = NONE (STRP).
    let lrtb = vector("defective_torus.lrm");
    let bad = forge(&lrtb, Tag::LRTB, |p| set_lrtb(p, LRTB_C, 0, NONE));
    breaks(
        &bad,
        38,
        "LRTB",
        lrtb_at(&lrtb, "C", 0),
        "vertex 16 has triangles but no corner",
    );
    let lrbe = vector("defective_torus.lr-compact.lrm");
    let bad = forge(&lrbe, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 0, NONE));
    breaks(
        &bad,
        38,
        "LRBE",
        lrbe_at(&lrbe, "C", 0),
        "vertex 16 has triangles but no corner",
    );
    let strp = vector("boundary_hedra_open.strips.lrm");
    for v in 0..6 {
        let bad = forge(&strp, Tag::STRP, |p| set_strp(p, "C", v, NONE));
        breaks(
            &bad,
            38,
            "STRP",
            strp_at(&strp, "C", v),
            "has triangles but no corner",
        );
    }
    // An open fan whose stored corner is another corner of the vertex than its start.
    let bytes = encoded(&soup(), Connectivity::Lr);
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let m_r = lr.ring_vertices();
    let (v, c) = open_fan(lr, m_r..lr.vertex_id_bound());
    let i = (v - m_r) as usize;
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, i, c.0));
    breaks(
        &bad,
        38,
        "LRTB",
        lrtb_at(&bytes, "C", i),
        "does not start its open fan",
    );
    let bytes = encoded(&soup(), Connectivity::LrCompact);
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let m_r = lr.ring_vertices();
    let (v, c) = open_fan(lr, m_r..lr.vertex_id_bound());
    let i = (v - m_r) as usize;
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, i, c.0));
    breaks(
        &bad,
        38,
        "LRBE",
        lrbe_at(&bytes, "C", i),
        "does not start its open fan",
    );
    let view = open(&strp, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let (v, c) = open_fan(strips, 0..6);
    let bad = forge(&strp, Tag::STRP, |p| set_strp(p, "C", v as usize, c.0));
    breaks(
        &bad,
        38,
        "STRP",
        strp_at(&strp, "C", v as usize),
        "does not start its open fan",
    );
    // A closed fan may store any of its corners.
    let tetra = vector("closed_tetrahedron.strips.lrm");
    let view = open(&tetra, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let (corners, start) = fan_of(strips, 0);
    assert!(start.is_none());
    for c in corners {
        let other = forge(&tetra, Tag::STRP, |p| set_strp(p, "C", 0, c.0));
        open(&other, &Limits::default()).unwrap();
    }
}

/// [V38] one fan per vertex. The `operators` fuzz target's base 148 (an LR of a torus with
/// holes and defects) with one 16-bit unit of `LRTB` copied over another: well formed, every
/// other rule kept, and a vertex whose corners form two fans (`v.c` starts one); it verified
/// before [V38] asked for one fan (`corpus/fuzz/regressions/operators/lr_vertex_with_two_fans`).
#[test]
fn v38_one_fan_per_vertex() {
    let bytes = lrmesh::fuzz_checks::forged_base(148);
    let bad = forge(&bytes, Tag::LRTB, |p| {
        let units = p.len() / 2;
        let (from, to) = (1 % units, 256 % units);
        let unit = [p[2 * from], p[2 * from + 1]];
        p[2 * to..2 * to + 2].copy_from_slice(&unit);
    });
    let view = open(&bad, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let mut corners = vec![0usize; lr.vertex_id_bound() as usize];
    for c in lr.corners() {
        corners[lr.vertex(c).idx()] += 1;
    }
    let v = lr
        .vertices()
        .find(|&v| lrmesh::ops::star(lr, v).count() != corners[v.idx()])
        .expect("a vertex with two fans");
    assert!(v.0 < lr.ring_vertices());
    breaks(
        &bad,
        38,
        "LRTB",
        lrtb_at(&bytes, "LR", 2 * v.idx()),
        "more than one fan",
    );
    // The same base as written verifies.
    lrmesh::read::open_verified(&bytes, &Limits::default()).unwrap();
}

/// `Container::verify` on a container opened as well formed: the semantic rules checked
/// later, with the error `open_verified` gives; a valid file verifies and says so.
#[test]
fn verify_after_a_well_formed_open() {
    let bytes = forge_sections(&vector("closed_tetrahedron.lrm"), |s| {
        s.retain(|section| section.0 != Tag::PERM)
    });
    let mut view = open(&bytes, &Limits::default()).unwrap();
    assert!(!view.is_verified());
    view.verify().unwrap();
    assert!(view.is_verified());
    // The tetrahedron with L[1] made 0 and MESH's count to match (v22_opposites).
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 2, 0));
    let bad = forge(&bad, Tag::MESH, |p| put(p, 8, 5));
    let mut view = open(&bad, &Limits::default()).unwrap();
    let late = view.verify().unwrap_err().to_string();
    let early = lrmesh::read::open_verified(&bad, &Limits::default())
        .unwrap_err()
        .to_string();
    assert_eq!(late, early);
    assert!(late.contains("[V22]"), "{late}");
}
