//! Forged containers for the rules of `LRBE`, the bit-efficient LR tables (§3.5d of
//! `spec/FORMAT.md`), **[V33]**..**[V37]** (its vertex corners' fans, [V38], are tested in
//! `forged_lr.rs`). How a rule is broken and what the reader must report:
//! `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::LrbeHeader;
use lrmesh::format::Tag;
use lrmesh::lr::LrLayout;
use lrmesh::read::{open, open_verified, Limits};
use lrmesh::{Corner, CornerOps};

// ---------------------------------------------------------------------------------------
// §3.5d LRBE.

/// [V33] `LRBE` counts and length. (`m < 0x3FFFFFFF` cannot break alone: `m = V`.)
#[test]
fn v33_lrbe_counts() {
    let bytes = vector("torus_with_t0.lr-compact.lrm"); // m = m_r = 25, R = 1, n0 = 3
    let at = section_at(&bytes, Tag::LRBE);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRBE, |p| put(p, f, x));
    breaks(&field(0, 24), 33, "LRBE", at, "section MESH says 25");
    breaks(&field(28, 4), 33, "LRBE", at + 28, "unknown flag bits");
    // TIP_BASES calls for the BASES array, which the file lacks.
    breaks(&field(28, 2), 33, "LRBE", at, "counts call for");
    for m_r in [26, 0, 3] {
        breaks(&field(4, m_r), 33, "LRBE", at + 4, "ring vertices");
    }
    breaks(&field(12, 0x4000_0000), 33, "LRBE", at + 12, "32 bits");
    for (f, x) in [(12, 4), (16, 17), (20, 1), (8, 2)] {
        breaks(&field(f, x), 33, "LRBE", at, "counts call for");
    }
    let bad = forge(&bytes, Tag::LRBE, |p| p.push(0));
    breaks(&bad, 33, "LRBE", at, "counts call for");
    let bad = forge(&bytes, Tag::LRBE, |p| p.truncate(30));
    breaks(&bad, 33, "LRBE", at, "header");
    // The period k is informative: any value is valid.
    open(&field(24, 12345), &Limits::default()).unwrap();
}

/// [V34] `LRBE` rings satisfy [V16], the bit vectors only with several rings.
#[test]
fn v34_lrbe_rings() {
    let two = vector("two_components.lr-compact.lrm"); // R = 2: starts [0, 4, 8], bits
    let word = |bytes: &[u8], name: &str, i: usize, x: u32| {
        forge(bytes, Tag::LRBE, |p| {
            let at = LrbeHeader::read(p).layout().unwrap().array(name).at(i);
            put(p, at, x)
        })
    };
    for (i, x) in [(0, 1), (1, 3), (2, 9)] {
        let at = lrbe_at(&two, "ring_starts", i);
        let bad = word(&two, "ring_starts", i, x);
        breaks(&bad, 34, "LRBE", at, "ring start");
    }
    let last = lrbe_at(&two, "ring_last", 0);
    let bad = word(&two, "ring_last", 0, 0x8);
    breaks(&bad, 34, "LRBE", last, "ring-end bits");
    let bad = word(&two, "ring_last", 0, 0x188);
    breaks(&bad, 34, "LRBE", last, "ring-end bits");
    let rank = lrbe_at(&two, "ring_rank", 0);
    let bad = word(&two, "ring_rank", 0, 2);
    breaks(&bad, 34, "LRBE", rank, "ring ranks");
    // One ring: no bit vectors, the starts are [0, m_r].
    let one = vector("closed_tetrahedron.lr-compact.lrm");
    let at = lrbe_at(&one, "ring_starts", 1);
    let bad = word(&one, "ring_starts", 1, 5);
    breaks(&bad, 34, "LRBE", at, "ring start 5");
}

/// [V35] Pairs and records: records tile `RECORDS` in ring order from each block's start,
/// IRREGULAR flags agree with heads, no unit left over; tips below `m` or `NULL` in a right
/// slot without WART, and then without stored opposites.
#[test]
fn v35_pairs_and_records() {
    let bytes = vector("torus_with_t0.lr-compact.lrm"); // 9 extended pairs, 18 units
    let p = payload(&bytes, Tag::LRBE);
    let pair = |v: usize| get(&p, lrbe_word(&p, PAIRS, v));
    let pair_at = |v: usize| lrbe_at(&bytes, "PAIRS", v);
    let set_pair = |v: usize, x: u32| forge(&bytes, Tag::LRBE, |p| set_lrbe(p, PAIRS, v, x));
    let extended: Vec<usize> = (0..25).filter(|&v| pair(v) >> 30 == 3).collect();
    let plain: Vec<usize> = (0..25).filter(|&v| pair(v) >> 30 == 0).collect();
    // Block 0 must start its records at 0.
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, BLOCKS, 0, 1));
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bytes, "BLOCKS", 0),
        "block 0 starts its records at 1",
    );
    // The second record starting one unit late, or early.
    let v = extended[1];
    for delta in [1u32 << 13, (1u32 << 13).wrapping_neg()] {
        let bad = set_pair(v, pair(v).wrapping_add(delta));
        breaks(&bad, 35, "LRBE", pair_at(v), "record of pair");
    }
    // An IRREGULAR flag flipped against the head.
    for &v in &extended[..3] {
        for bit in [26, 27] {
            let bad = set_pair(v, pair(v) ^ 1 << bit);
            breaks(
                &bad,
                35,
                "LRBE",
                pair_at(v),
                "IRREGULAR flag and stored opposites disagree",
            );
        }
    }
    // The last record cut short: it runs past RECORDS.
    let last = *extended.last().unwrap();
    let mut t = Tables::lrbe(&p);
    let start = (pair(last) >> 13 & 0x1FFF) as usize;
    t.head[4] -= 1;
    t.array(RECORDS).pop();
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "RECORDS", start),
        "runs past",
    );
    // A unit no record uses.
    let mut t = Tables::lrbe(&p);
    t.head[4] += 1;
    t.array(RECORDS).push(0);
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "RECORDS", 18),
        "not used by any pair",
    );
    // Plain pairs: tips v + d out of range, a NULL left tip, a NULL right tip with WART.
    let v = plain[0];
    let out_of_range = [(25 - v as u32) & 0x7FFF, 0x7FFF & (-(v as i32) - 1) as u32];
    for d in out_of_range {
        let bad = set_pair(v, pair(v) & !0x7FFF | d);
        breaks(&bad, 35, "LRBE", pair_at(v), "has tip");
        let bad = set_pair(v, pair(v) & !(0x7FFF << 15) | d << 15);
        breaks(&bad, 35, "LRBE", pair_at(v), "has tip");
    }
    let bad = set_pair(v, pair(v) & !0x7FFF);
    breaks(&bad, 35, "LRBE", pair_at(v), "has tip 0x3fffffff");
    let wart_null = 2 << 30 | (pair(v) & 0x7FFF);
    let bad = set_pair(v, wart_null);
    breaks(&bad, 35, "LRBE", pair_at(v), "has tip 0x3fffffff");
    // A right slot with tip NULL storing an opposite: boundary_hedra_open's pair 0 (tips 3
    // and NULL) made extended, IRREGULAR on the right, with a record [head 0x0004: the
    // opposite of corner 4 stored, right tip NULL; field 0xC000: NONE].
    let open_hedra = vector("boundary_hedra_open.lr-compact.lrm");
    let q = payload(&open_hedra, Tag::LRBE);
    assert_eq!(get(&q, lrbe_word(&q, PAIRS, 0)), 3);
    let mut t = Tables::lrbe(&q);
    t.head[4] = 2;
    t.array(PAIRS)[0] = 3 << 30 | 1 << 27 | 3;
    t.array(RECORDS).extend([0x0004, 0xC000]);
    let bad = forge(&open_hedra, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "PAIRS", 0),
        "missing right triangle of pair 0 stores opposites",
    );
    // The same record without IRREGULAR on the right and with no opposite is valid.
    t.array(PAIRS)[0] = 3 << 30 | 3;
    t.head[4] = 1;
    t.array(RECORDS).truncate(1);
    t.array(RECORDS)[0] = 0;
    open(
        &forge(&open_hedra, Tag::LRBE, |p| *p = t.join()),
        &Limits::default(),
    )
    .unwrap();
}

/// The `LRBE` container with T0 row `j` moved to `OVERFLOW` (its first and only overflow
/// row, holding the vertices and opposites the row answers).
fn overflow_row(bytes: &[u8], j: usize) -> Vec<u8> {
    let view = open(bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let corners = [0, 1, 2].map(|i| Corner(8 * lr.ring_vertices() + 4 * j as u32 + i));
    let p = payload(bytes, Tag::LRBE);
    let mut t = Tables::lrbe(&p);
    assert_eq!(t.head[5], 0);
    t.head[5] = 1;
    t.array(OVERFLOW).extend(corners.map(|c| lr.vertex(c).0));
    t.array(OVERFLOW)
        .extend(corners.map(|c| lr.opposite(c).map_or(NONE, |o| o.0)));
    t.array(ROWS)[4 * j..4 * j + 4].copy_from_slice(&[0, 0, 0, 0x8000]);
    forge(bytes, Tag::LRBE, |p| *p = t.join())
}

/// [V36] T0 rows: overflow rows exactly `(0, k, 0x8000)` and used once each in order, other
/// rows with reserved bits clear; T0 vertices below `m`.
#[test]
fn v36_t0_rows() {
    let bytes = vector("defective_torus.lr-compact.lrm"); // m = 23, 5 rows, F = 0
    let p = payload(&bytes, Tag::LRBE);
    let unit = |p: &[u8], j: usize, i: usize| lrbe_word(p, ROWS, 4 * j + i);
    let row_at = |bytes: &[u8], j: usize, i: usize| lrbe_at(bytes, "ROWS", 4 * j + i);
    let set = |j: usize, i: usize, x: u32| {
        forge(&bytes, Tag::LRBE, |p| set_lrbe16(p, ROWS, 4 * j + i, x))
    };
    // Reserved bits 6–14 of unit 3.
    for bit in [6, 10, 14] {
        let codes = get16(&p, unit(&p, 2, 3)) | 1 << bit;
        let bad = set(2, 3, codes);
        breaks(&bad, 36, "LRBE", row_at(&bytes, 2, 3), "reserved bits");
    }
    // The anchor out of range (GROUP[0] + a ≥ m).
    let bad = set(1, 0, 0x7FFF);
    breaks(&bad, 36, "LRBE", row_at(&bytes, 1, 0), "out of range");
    // Row 3 moved to OVERFLOW: valid; then its unit 0 made 1.
    let j = 3;
    let overflowing = overflow_row(&bytes, j);
    open(&overflowing, &Limits::default()).unwrap();
    // Its unit 0 must be 0.
    let mut u = Tables::lrbe(&payload(&overflowing, Tag::LRBE));
    u.array(ROWS)[4 * j] = 1;
    let bad = forge(&overflowing, Tag::LRBE, |p| *p = u.join());
    breaks(
        &bad,
        36,
        "LRBE",
        row_at(&bad, j, 0),
        "malformed overflow row",
    );
    // An overflow row no T0 row uses (the first of them: row 0 of OVERFLOW).
    let mut t = Tables::lrbe(&p);
    t.head[5] = 1;
    t.array(OVERFLOW).extend([0; 6]);
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        36,
        "LRBE",
        lrbe_at(&bad, "OVERFLOW", 0),
        "not used by any T0 row",
    );
}

/// [V36] Row faults in units 1–2 or in `OVERFLOW` are located at that unit or word.
#[test]

fn v36_row_faults_located_at_their_unit() {
    let bytes = vector("defective_torus.lr-compact.lrm");
    let p = payload(&bytes, Tag::LRBE);
    let unit = |j: usize, i: usize| lrbe_word(&p, ROWS, 4 * j + i);
    let b1 = get16(&p, unit(2, 1));
    let bad = forge(&bytes, Tag::LRBE, |q| put16(q, unit(2, 1), b1 | 0x8000));
    breaks(&bad, 36, "LRBE", lrbe_at(&bytes, "ROWS", 4 * 2 + 1), "");
    let bad = forge(&bytes, Tag::LRBE, |q| put16(q, unit(2, 1), 0x3FFF));
    breaks(&bad, 36, "LRBE", lrbe_at(&bytes, "ROWS", 4 * 2 + 1), "");
    // An overflow row naming OVERFLOW row 1 where it is the first (k = 0).
    let overflowing = overflow_row(&bytes, 3);
    let bad = forge(&overflowing, Tag::LRBE, |q| {
        set_lrbe16(q, ROWS, 4 * 3 + 1, 1)
    });
    breaks(
        &bad,
        36,
        "LRBE",
        lrbe_at(&overflowing, "ROWS", 4 * 3 + 1),
        "",
    );
    // An overflow row's vertex out of range, in OVERFLOW.
    let bad = forge(&overflowing, Tag::LRBE, |q| set_lrbe(q, OVERFLOW, 1, 23));
    breaks(&bad, 36, "LRBE", lrbe_at(&overflowing, "OVERFLOW", 1), "");
}

/// [V37] `LRBE`'s `C` holds `NONE` or canonical corners; then [V19], [V21]–[V23] and [V38]
/// hold for its operators (each reported under its own number).
#[test]
fn v37_lrbe_corners_and_lr_rules() {
    let bytes = vector("defective_torus.lr-compact.lrm"); // off-ring 16..23
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let redundant = (0..128)
        .find(|&c| c & 3 != 3 && !lr.is_corner(Corner(c)))
        .unwrap();
    for x in [3, redundant, 8 * 16 + 4 * 5, NONE - 1] {
        let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 2, x));
        breaks(&bad, 37, "LRBE", lrbe_at(&bytes, "C", 2), "not a corner");
    }
    // [V23]: an off-ring vertex given a corner of another vertex.
    let c = lr.corners().find(|&c| lr.vertex(c).0 != 18).unwrap();
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 2, c.0));
    breaks(
        &bad,
        23,
        "LRBE",
        lrbe_at(&bytes, "C", 2),
        "is a corner of vertex",
    );
    // [V21]: a T0 row whose vertex 1 is its anchor (offset 0), in the row without opposites.
    let j = lone_t0_triangle(&bytes);
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe16(p, ROWS, 4 * j + 1, 0));
    breaks(
        &bad,
        21,
        "LRBE",
        lrbe_at(&bytes, "ROWS", 4 * j),
        "degenerate",
    );
    // [V19] and [V22] on the tetrahedron: pair 0 = 0x10003 (tips 3, 1).
    let tetra = vector("closed_tetrahedron.lr-compact.lrm");
    let set = |v: usize, x: u32| forge(&tetra, Tag::LRBE, |p| set_lrbe(p, PAIRS, v, x));
    // Left tip 2 = 0.n.n: slot 0 redundant, pointing at the redundant slot 2.
    let bad = set(0, 0x10002);
    breaks(
        &bad,
        19,
        "LRBE",
        lrbe_at(&tetra, "PAIRS", 0),
        "slot 0 points to slot 2",
    );
    // [V22]: a T0 corner whose opposite the left or right rule finds, coded as having none
    // (the triangle count unchanged): its partner's opposite no longer points back.
    let m_r = lr.ring_vertices();
    let (k, partner) = (8 * m_r..8 * m_r + 4 * lr.t0_count())
        .filter(|c| c & 3 != 3)
        .find_map(|c| {
            let o = lr.opposite(Corner(c))?.0;
            let p = payload(&bytes, Tag::LRBE);
            let row = ((c - 8 * m_r) / 4) as usize;
            let code = get16(&p, lrbe_word(&p, ROWS, 4 * row + 3)) >> (2 * (c & 3)) & 3;
            (o < 8 * m_r && code < 2).then_some((c, o))
        })
        .expect("a T0 corner found by a ring rule");
    let (j, i) = (((k - 8 * m_r) / 4) as usize, k & 3);
    let bad = forge(&bytes, Tag::LRBE, |p| {
        let at = lrbe_word(p, ROWS, 4 * j + 3);
        let codes = get16(p, at) | 3 << (2 * i);
        put16(p, at, codes)
    });
    breaks(
        &bad,
        22,
        "LRBE",
        lrbe_at(&bytes, "PAIRS", (partner >> 3) as usize),
        &format!("corner {partner} and its opposite {k}"),
    );
    // [V38] on LRBE: in v38_vertex_corner_starts_its_fan.
}

/// [V33] and [V35] with `TIP_BASES` (version 1.11), on the vector with both kinds of field:
/// the `BASES` array's length; a far tip out of range, or adding up to `NULL`'s value, by its
/// base or its field (the fault named at the pair, with the base); a near field read with
/// its 14 bits; any base valid while its tips stay in range.
#[test]
fn v33_v35_tip_bases() {
    let bytes = vector("torus_with_t0.lr-compact-bases.lrm"); // m = m_r = 25: one block
    open(&bytes, &Limits::default()).unwrap();
    let at = section_at(&bytes, Tag::LRBE);
    let p = payload(&bytes, Tag::LRBE);
    // BASES holds two words per block of 256 ring vertices.
    for edit in [
        |t: &mut Tables| t.array(BASES).push(0),
        |t: &mut Tables| {
            t.array(BASES).pop();
        },
    ] {
        let mut t = Tables::lrbe(&p);
        edit(&mut t);
        let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
        breaks(&bad, 33, "LRBE", at, "counts call for");
    }
    let pair = |v: usize| get(&p, lrbe_word(&p, PAIRS, v));
    let far = |v: usize, side: usize| pair(v) >> 30 != 3 && pair(v) >> (15 * side) & 0x4000 != 0;
    let v = (0..25).find(|&v| far(v, 0)).expect("a far left field");
    let base = get(&p, lrbe_word(&p, BASES, 0)) as i32;
    // The left base moved so that v's far tip leaves 0..25 (other far tips may fail first,
    // at their own pair: the first far left one is v).
    for moved in [base + 25, base - 25, i32::MAX, i32::MIN] {
        let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, BASES, 0, moved as u32));
        breaks(
            &bad,
            35,
            "LRBE",
            lrbe_at(&bytes, "PAIRS", v),
            &format!("from block 0's base {moved}"),
        );
    }
    // A far field whose tip adds up to NULL's value, on the right: not NULL, out of range.
    let w = (0..25).find(|&w| far(w, 1)).expect("a far right field");
    let e = ((pair(w) >> 15 & 0x3FFF) << 18) as i32 >> 18;
    let null_base = (u32::MAX.wrapping_sub(w as u32) as i32).wrapping_sub(e);
    let bad = forge(&bytes, Tag::LRBE, |p| {
        set_lrbe(p, BASES, 1, null_base as u32)
    });
    let first_right = (0..25).find(|&u| far(u, 1)).unwrap();
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bytes, "PAIRS", first_right),
        "has tip",
    );
    // A near field holds 14 bits: 0x2000 is -8192, out of range at any v below 8192.
    let u = (0..25).find(|&u| pair(u) >> 30 != 3 && !far(u, 0)).unwrap();
    let bad = forge(&bytes, Tag::LRBE, |p| {
        set_lrbe(p, PAIRS, u, pair(u) & !0x7FFF | 0x2000)
    });
    breaks(&bad, 35, "LRBE", lrbe_at(&bytes, "PAIRS", u), "has tip");
    // A base that leaves every far tip in range (here: far fields rewritten near) is valid.
    let mut t = Tables::lrbe(&p);
    for (x, word) in t.array(PAIRS).iter_mut().enumerate() {
        if *word >> 30 == 3 {
            continue;
        }
        for side in 0..2 {
            let f = *word >> (15 * side) & 0x7FFF;
            if f & 0x4000 != 0 {
                let e = ((f & 0x3FFF) << 18) as i32 >> 18;
                let d = get(&p, lrbe_word(&p, BASES, side)) as i32 + e;
                assert!(d != 0 && (-8192..8192).contains(&d), "pair {x}");
                *word = *word & !(0x7FFF << (15 * side)) | (d as u32 & 0x3FFF) << (15 * side);
            }
        }
    }
    *t.array(BASES) = vec![0x8000_0000, 12345];
    let same = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    let (a, b) = (
        open_verified(&same, &Limits::default()).unwrap(),
        open_verified(&bytes, &Limits::default()).unwrap(),
    );
    let corners = |c: &lrmesh::read::Container| {
        let conn = c.connectivity();
        conn.corners()
            .map(|k| (k, conn.vertex(k), conn.opposite(k)))
            .collect::<Vec<_>>()
    };
    assert_eq!(corners(&a), corners(&b));
}
