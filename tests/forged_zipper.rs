//! Forged containers for the rules of `ZIPR`, the Zipper tables (§3.5e of `spec/FORMAT.md`),
//! **[V56]**..**[V60]**. How a rule is broken and what the reader must report:
//! `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::{ZiprHeader, ZIPPER_COMPACT, ZIPPER_LEFT_FOURS, ZIPPER_RIGHT_FOURS};
use lrmesh::format::Tag;
use lrmesh::read::{open, open_verified, Limits, SEMANTIC_RULES};
use lrmesh::{Error, Rule};

// Array indices of `ZiprHeader::ARRAYS`.
const PLANES: usize = 3;
const HEADS: usize = 4;
const EXCEPTIONS: usize = 5;
const RECORDS: usize = 6;
const T0_V: usize = 8;
const T0_CODES: usize = 9;
const EXPLICIT: usize = 10;
const C: usize = 11;
const SUPER: usize = 12;
/// Not an array: in the compact form (version 1.13) the anchors' list, the first part of
/// `HEADS` (whose elements [`zipr_bits`] then gives as the counts' list's).
const ANCHORS: usize = 13;

/// Where element `i` of array `index` lies within `ZIPR`: its first bit and its width. The
/// seven lists (`EXCEPTIONS` to `C`) are bit fields with `PACKED_LISTS` (FORMAT.md §3.5e),
/// the other arrays and every array of an older file 32-bit words.
fn zipr_bits(p: &[u8], index: usize, i: usize) -> (usize, u32) {
    let header = ZiprHeader::read(p);
    let heads = 8 * header.layout().unwrap().arrays[HEADS].start;
    // JOINED_LISTS: the nine bit lists are one stream from HEADS' start.
    if let (Some(bits), true) = (header.joined_bits(), index >= HEADS && index != SUPER) {
        let (anchor, counts) = header.head_fields().unwrap();
        let (q, fields) = match index {
            ANCHORS => (0, anchor),
            HEADS => (1, counts),
            _ => (
                2 + index - EXCEPTIONS,
                header.list_fields()[index - EXCEPTIONS],
            ),
        };
        let bit = lrmesh::lr::zipper::first_bit(fields, i as u64) as usize;
        return (heads + bits[q] as usize + bit, fields[i % 2].width as u32);
    }
    if let (HEADS | ANCHORS, Some((anchor, counts))) = (index, header.head_fields()) {
        let (start, fields) = match index {
            ANCHORS => (heads, anchor),
            _ => (heads + 32 * header.anchor_words() as usize, counts),
        };
        let bit = lrmesh::lr::zipper::first_bit(fields, i as u64) as usize;
        return (start + bit, fields[i % 2].width as u32);
    }
    let start = 8 * header.layout().unwrap().arrays[index].start;
    if !(EXCEPTIONS..=C).contains(&index) {
        return (start + 32 * i, 32);
    }
    let fields = header.list_fields()[index - EXCEPTIONS];
    let bit = lrmesh::lr::zipper::first_bit(fields, i as u64) as usize;
    (start + bit, fields[i % 2].width as u32)
}

/// The width in bits of element `i` of array `index`.
fn zipr_width(bytes: &[u8], index: usize, i: usize) -> u32 {
    zipr_bits(&payload(bytes, Tag::ZIPR), index, i).1
}

/// File offset of the byte holding the first bit of element `i` of array `index` of `ZIPR`.
fn zipr_at(bytes: &[u8], index: usize, i: usize) -> u64 {
    let bit = zipr_bits(&payload(bytes, Tag::ZIPR), index, i).0;
    section_at(bytes, Tag::ZIPR) + (bit / 8) as u64
}

/// Asserts that element `i` of array `index` set to `x` breaks `rule`, named at that element.
fn field_breaks(bytes: &[u8], index: usize, i: usize, x: u32, rule: u8, words: &str) {
    let bad = zipr_set(bytes, index, i, x);
    breaks(&bad, rule, "ZIPR", zipr_at(bytes, index, i), words);
}

/// Element `i` of array `index`: a word, or a list's field as stored.
fn zipr_get(bytes: &[u8], index: usize, i: usize) -> u32 {
    let p = payload(bytes, Tag::ZIPR);
    let (bit, width) = zipr_bits(&p, index, i);
    (0..width as usize).fold(0, |x, k| {
        x | ((p[(bit + k) / 8] >> ((bit + k) % 8)) as u32 & 1) << k
    })
}

/// `bytes` with element `i` of array `index` set to `x` (a list's field as stored).
fn zipr_set(bytes: &[u8], index: usize, i: usize, x: u32) -> Vec<u8> {
    forge(bytes, Tag::ZIPR, |p| {
        let (bit, width) = zipr_bits(p, index, i);
        assert!(
            width == 32 || x >> width == 0,
            "{x} does not fit {width} bits"
        );
        for k in 0..width as usize {
            let (byte, b) = ((bit + k) / 8, (bit + k) % 8);
            p[byte] = p[byte] & !(1 << b) | ((x >> k) as u8 & 1) << b;
        }
    })
}

/// Where the flags of `ZIPR` lie in the section and their value: word 0 less bit 31 in
/// the compact form, word 8 in the 40-byte header.
fn zipr_flags(bytes: &[u8]) -> (usize, u32) {
    let p = payload(bytes, Tag::ZIPR);
    match ZiprHeader::is_compact(&p) {
        true => (0, get(&p, 0) & !ZIPPER_COMPACT),
        false => (32, get(&p, 32)),
    }
}

/// `bytes` with the flags of `ZIPR` set to `flags` (either header form).
fn with_zipr_flags(bytes: &[u8], flags: u32) -> Vec<u8> {
    let (at, _) = zipr_flags(bytes);
    let compact = if at == 0 { ZIPPER_COMPACT } else { 0 };
    forge(bytes, Tag::ZIPR, |p| put(p, at, flags | compact))
}

/// `corpus/zipper-1.13/NAME`, a Zipper file of version 1.13 (without `LEFT_FOURS`) of
/// `mesh`, which it must decode to.
fn version_1_13(name: &str, mesh: &lrmesh::Mesh) -> Vec<u8> {
    let path = manifest().join("corpus/zipper-1.13").join(name);
    let bytes = std::fs::read(&path).unwrap();
    assert_eq!(u16::from_le_bytes([bytes[10], bytes[11]]), 13, "{name}");
    let view = open_verified(&bytes, &Limits::default()).unwrap();
    assert_eq!(
        view.summary().triangles,
        mesh.triangles.len() as u64,
        "{name}"
    );
    assert_eq!(
        zipr_flags(&bytes).1 & (ZIPPER_LEFT_FOURS | ZIPPER_RIGHT_FOURS),
        0
    );
    bytes
}

/// `bytes` with the compact header of `ZIPR` rewritten by `edit` (the arrays kept).
fn with_header(bytes: &[u8], edit: impl FnOnce(&mut ZiprHeader)) -> Vec<u8> {
    forge(bytes, Tag::ZIPR, |p| {
        let old = ZiprHeader::read(p);
        let mut header = old;
        edit(&mut header);
        let mut out = header.to_bytes();
        out.extend_from_slice(&p[old.header_len()..]);
        *p = out;
    })
}

/// `bytes` with the anchors of its compact `ZIPR` rewritten `width` bits wide (the same
/// values; the writer's are 0 bits wide).
fn with_anchor_bits(bytes: &[u8], width: u8) -> Vec<u8> {
    use lrmesh::lr::zipper::{unjoined_zipr, Field, FieldKind, Packed};
    // The lists no longer joined (JOINED_LISTS), so that the anchors' list has words of its
    // own.
    let unjoined = unjoined_zipr(&payload(bytes, Tag::ZIPR));
    let joined = unjoined.map(|u| forge(bytes, Tag::ZIPR, |p| *p = u));
    let bytes = joined.as_deref().unwrap_or(bytes);
    let p = payload(bytes, Tag::ZIPR);
    let header = ZiprHeader::read(&p);
    let n = 2 * header.blocks() as usize;
    let values: Vec<u32> = (0..n).map(|i| zipr_get(bytes, ANCHORS, i)).collect();
    let anchor = header.head_fields().unwrap().0[0];
    let signed = |x: u32| match anchor.width {
        0 => 0,
        w => ((x << (32 - w)) as i32 >> (32 - w)) as u32,
    };
    let values: Vec<u32> = values.into_iter().map(signed).collect();
    let wide = Field {
        width,
        kind: FieldKind::Signed,
    };
    let packed = Packed::pack(&values, [wide; 2]).unwrap();
    let words = packed.words().clone();
    let heads = header.layout().unwrap().arrays[HEADS].start;
    let end = heads + 4 * header.anchor_words() as usize;
    forge(bytes, Tag::ZIPR, |p| {
        let mut h = header;
        h.compact.as_mut().unwrap().anchor_bits = width;
        let mut out = h.to_bytes();
        out.extend_from_slice(&p[header.header_len()..heads]);
        out.extend(words.iter().flat_map(|w| w.to_le_bytes()));
        out.extend_from_slice(&p[end..]);
        *p = out;
    })
}

/// The symbol of slot `slot` (groups of 32 slots, three words each).
fn symbol(bytes: &[u8], slot: usize) -> u32 {
    (0..3)
        .map(|k| (zipr_get(bytes, PLANES, 3 * (slot / 32) + k) >> (slot % 32) & 1) << k)
        .sum()
}

/// `bytes` with the symbol of slot `slot` set to `s`.
fn set_symbol(bytes: &[u8], slot: usize, s: u32) -> Vec<u8> {
    let bit = slot;
    let mut out = bytes.to_vec();
    for k in 0..3 {
        let i = 3 * (bit / 32) + k;
        let w = zipr_get(&out, PLANES, i) & !(1 << (bit % 32)) | ((s >> k) & 1) << (bit % 32);
        out = zipr_set(&out, PLANES, i, w);
    }
    out
}

/// The rule by which the verifying reader refuses `bytes` (any level).
fn verified_rule(bytes: &[u8]) -> Rule {
    match open_verified(bytes, &Limits::default()) {
        Err(Error::Format(e)) => e.rule,
        Err(e) => panic!("expected a format error, got {e}"),
        Ok(_) => panic!("the forged container was accepted"),
    }
}

/// [V56] `ZIPR` counts and length, in the 40-byte header (a file of version 1.12).
/// (`m < 0x3FFFFFFF` cannot break alone: `m = V`.)
#[test]
fn v56_zipr_counts() {
    // m = m_r = 25, R = 1, n0 = 3, P = 1, E = 0.
    let bytes = vector("torus_with_t0.zipper-1.12.lrm");
    let at = section_at(&bytes, Tag::ZIPR);
    let field = |f: usize, x: u32| forge(&bytes, Tag::ZIPR, |p| put(p, f, x));
    breaks(&field(0, 24), 56, "ZIPR", at, "section MESH says 25");
    breaks(&field(32, 2048), 56, "ZIPR", at + 32, "unknown flag bits");
    let (_, flags12) = zipr_flags(&bytes);
    let joined = with_zipr_flags(&bytes, flags12 | 1024);
    breaks(
        &joined,
        56,
        "ZIPR",
        at + 32,
        "JOINED_LISTS without the compact form",
    );
    // ROW_RECORDS and IMPLIED_WARTS only change bit fields: not without PACKED_LISTS.
    let words = vector("torus_with_t0.zipper-1.9.lrm");
    let at9 = section_at(&words, Tag::ZIPR);
    let (_, flags9) = zipr_flags(&words);
    assert_eq!(flags9 & 8, 0);
    for flag in [256, 512] {
        let bad = with_zipr_flags(&words, flags9 | flag);
        breaks(&bad, 56, "ZIPR", at9 + 32, "without PACKED_LISTS");
    }
    // INNER_RING_STARTS cleared: the counts then call for two more ring-start words.
    let flags = u32::from_le_bytes(payload(&bytes, Tag::ZIPR)[32..36].try_into().unwrap());
    assert_ne!(flags & 16, 0);
    breaks(&field(32, flags & !16), 56, "ZIPR", at, "counts call for");
    // RING_BLOCKS cleared with four rings: the counts then call for the ring-end bits and
    // ranks (two words of 200 vertices each) instead of one word of four 2-bit fields.
    let four = vector("four_spheres.zipper-1.12.lrm");
    let at4 = section_at(&four, Tag::ZIPR);
    let flags = u32::from_le_bytes(payload(&four, Tag::ZIPR)[32..36].try_into().unwrap());
    assert_ne!(flags & 32, 0);
    let bad = forge(&four, Tag::ZIPR, |p| put(p, 32, flags & !32));
    breaks(&bad, 56, "ZIPR", at4, "counts call for");
    breaks(&field(36, 1), 56, "ZIPR", at + 32, "reserved bits");
    for m_r in [26, 0, 3] {
        breaks(&field(4, m_r), 56, "ZIPR", at + 4, "ring vertices");
    }
    breaks(&field(12, 0x4000_0000), 56, "ZIPR", at + 12, "32 bits");
    // Each count made larger than the file's.
    let count =
        |f: usize| u32::from_le_bytes(payload(&bytes, Tag::ZIPR)[f..f + 4].try_into().unwrap());
    for (f, more) in [(12, 2), (16, 16), (20, 16), (24, 16), (28, 3), (8, 1)] {
        breaks(
            &field(f, count(f) + more),
            56,
            "ZIPR",
            at,
            "counts call for",
        );
    }
    let bad = forge(&bytes, Tag::ZIPR, |p| p.push(0));
    breaks(&bad, 56, "ZIPR", at, "counts call for");
    let bad = forge(&bytes, Tag::ZIPR, |p| p.truncate(36));
    breaks(&bad, 56, "ZIPR", at, "header");
    // PACKED_LISTS: the bits of a list's last word past its last field are 0. Exceptions
    // of 6 bits (a vertex of 25 and the WART flag) leave bits of their last word free.
    assert_eq!(zipr_width(&bytes, EXCEPTIONS, 0), 6);
    let used = (6 * count(16)) % 32;
    assert_ne!(used, 0);
    let last_word = zipr_at(&bytes, RECORDS, 0) - 4;
    let bad = forge(&bytes, Tag::ZIPR, |p| {
        let i = (last_word - at) as usize;
        p[i + 3] |= 0x80;
    });
    breaks(
        &bad,
        56,
        "ZIPR",
        last_word,
        "EXCEPTIONS: bits past its last field",
    );
}

/// [V56] in the compact header (version 1.13, FORMAT.md §3.5e.3): the count width, the
/// head fields' widths, the flags, the counts, the length, and the bits past the head lists'
/// last fields.
#[test]
fn v56_compact_header() {
    // m = m_r = 25, one block: counts of one byte, head fields of 0 bits.
    let bytes = vector("torus_with_t0.zipper.lrm");
    let at = section_at(&bytes, Tag::ZIPR);
    let header = ZiprHeader::read(&payload(&bytes, Tag::ZIPR));
    assert_eq!(header.compact.unwrap().count_bytes, 1);
    let byte = |i: usize, x: u8| forge(&bytes, Tag::ZIPR, |p| p[i] = x);
    for k in [0, 5, 255] {
        breaks(&byte(4, k), 56, "ZIPR", at + 4, "counts of");
    }
    for i in 5..8 {
        breaks(
            &byte(i, 17),
            56,
            "ZIPR",
            at + i as u64,
            "a head field of 17 bits",
        );
    }
    let (_, flags) = zipr_flags(&bytes);
    // ROW_RECORDS or IMPLIED_WARTS cleared: fields one or more bits wider, so the length
    // no longer fits, or where the padding absorbs it, the words read otherwise break [V58].
    for flag in [256, 512] {
        assert_eq!(flags & flag, flag);
        let rule = format_error(&with_zipr_flags(&bytes, flags & !flag)).rule;
        assert!(matches!(rule, Rule(56) | Rule(58)), "{flag}: {rule:?}");
    }
    // SHORT_HEADS has no meaning in the compact form; bits 11 to 30 are 0.
    for bad_flags in [flags | 4, flags | 2048, flags | 1 << 30] {
        breaks(
            &with_zipr_flags(&bytes, bad_flags),
            56,
            "ZIPR",
            at,
            "unknown flag bits",
        );
    }
    breaks(&byte(8, 24), 56, "ZIPR", at + 8, "section MESH says 25");
    breaks(&byte(9, 26), 56, "ZIPR", at + 9, "ring vertices");
    // Each count made larger than the file's: the layout no longer fits the length.
    for i in 11..16 {
        let more = with_header(&bytes, |h| match i {
            11 => h.t0 += 8,
            12 => h.exceptions += 8,
            13 => h.records += 8,
            14 => h.pairs += 8,
            _ => h.explicit += 8,
        });
        breaks(&more, 56, "ZIPR", at, "counts call for");
    }
    for len in [3, 7, 15] {
        let bad = forge(&bytes, Tag::ZIPR, |p| p.truncate(len));
        breaks(&bad, 56, "ZIPR", at, "header");
    }
    // Counts wider than they need and anchors of 9 and 16 bits are laid out as the header
    // says: the file opens and verifies.
    let wide = with_header(&bytes, |h| h.compact.as_mut().unwrap().count_bytes = 4);
    let spheres = vector("four_spheres.zipper.lrm");
    for (same, wider) in [
        (&bytes, wide),
        (&spheres, with_anchor_bits(&spheres, 9)),
        (&spheres, with_anchor_bits(&spheres, 16)),
    ] {
        assert_ne!(same, &wider);
        let [a, b] = [same, &wider].map(|x| open_verified(x, &Limits::default()).unwrap());
        assert_eq!(a.summary().triangles, b.summary().triangles);
        lrmesh::fuzz_checks::walk_in_range(&b);
    }
    // Four blocks (version 1.15, before JOINED_LISTS; one seed's ring): 6-bit anchors
    // (eight fields, 48 bits of two words), 6- and 5-bit counts (44 bits of two words); a
    // bit set past the last field of either list.
    let anchored = vector("four_spheres.zipper-1.15.lrm");
    let h = ZiprHeader::read(&payload(&anchored, Tag::ZIPR));
    let c = h.compact.unwrap();
    assert_eq!((c.anchor_bits, c.count_bits), (6, [6, 5]));
    let at4 = section_at(&anchored, Tag::ZIPR);
    let heads = h.layout().unwrap().arrays[HEADS];
    for (end, words) in [(heads.start + 8, "anchor"), (heads.end(), "count")] {
        let bad = forge(&anchored, Tag::ZIPR, |p| p[end - 1] |= 0x80);
        let message = format!("HEADS: bits past the last {words} field");
        breaks(&bad, 56, "ZIPR", at4 + end as u64 - 4, &message);
    }
    // JOINED_LISTS: the nine lists are one stream in HEADS, padded only at its end (the last
    // list's, C's); a bit set past it breaks the rule.
    let h = ZiprHeader::read(&payload(&spheres, Tag::ZIPR));
    let end_bit = h.joined_bits().unwrap()[9];
    assert_ne!(end_bit % 32, 0);
    let heads = h.layout().unwrap().arrays[HEADS];
    assert_eq!(heads.end() - heads.start, 4 * end_bit.div_ceil(32) as usize);
    let bad = forge(&spheres, Tag::ZIPR, |p| p[heads.end() - 1] |= 0x80);
    let at_spheres = section_at(&spheres, Tag::ZIPR);
    let end = at_spheres + heads.end() as u64 - 4;
    breaks(&bad, 56, "ZIPR", end, "C: bits past its last field");
}

/// [V57] `ZIPR` rings satisfy [V16], the bit vectors only with several rings; with
/// `INNER_RING_STARTS` (version 1.12), over the stored inner starts and the implied first
/// (0) and last (`m_r`).
#[test]
fn v57_zipr_rings() {
    // R = 2, m_r = 8: the inner start [4] (the starts [0, 4, 8]), and the bit vectors.
    let two = vector("two_components.zipper.lrm");
    assert_eq!(zipr_get(&two, 0, 0), 4);
    let bad = zipr_set(&two, 0, 0, 3);
    breaks(&bad, 57, "ZIPR", zipr_at(&two, 0, 0), "ring start 3");
    for x in [5, 9, u32::MAX] {
        let bad = zipr_set(&two, 0, 0, x);
        let words = format!("ring start {x} leaves fewer than 4 vertices to the last ring");
        breaks(&bad, 57, "ZIPR", zipr_at(&two, 0, 0), &words);
    }
    // RING_BLOCKS: R = 4, m_r = 200, the starts [0, 50, 100, 150, 200]; four blocks, the
    // rings 0, 1, 2, 3 of their first vertices in 2-bit fields (one word, 0xE4).
    let four = vector("four_spheres.zipper.lrm");
    assert_eq!(zipr_get(&four, 1, 0), 0xE4);
    for (k, ring) in [(0, 1), (1, 0), (1, 2), (3, 2), (2, 3)] {
        let word = 0xE4 & !(3 << (2 * k)) | ring << (2 * k);
        let bad = zipr_set(&four, 1, 0, word);
        let words = format!("RING_BLOCKS field {k} says ring {ring}");
        breaks(&bad, 57, "ZIPR", zipr_at(&four, 1, 0), &words);
    }
    let bad = zipr_set(&four, 1, 0, 0xE4 | 1 << 8);
    breaks(
        &bad,
        57,
        "ZIPR",
        zipr_at(&four, 1, 0),
        "RING_BLOCKS: bits past",
    );
    // Ring-end bits and ranks (version 1.10, two rings): the starts [0, 4, 8].
    let old_two = vector("two_components.zipper-1.10.lrm");
    for (i, x) in [(0, 1), (1, 3), (2, 9)] {
        let bad = zipr_set(&old_two, 0, i, x);
        breaks(&bad, 57, "ZIPR", zipr_at(&old_two, 0, i), "ring start");
    }
    let bad = zipr_set(&old_two, 1, 0, 0x8);
    breaks(&bad, 57, "ZIPR", zipr_at(&old_two, 1, 0), "ring-end bits");
    let bad = zipr_set(&old_two, 2, 0, 2);
    breaks(&bad, 57, "ZIPR", zipr_at(&old_two, 2, 0), "ring ranks");
    // Every start stored (version 1.10): R = 1, m_r = 25, the starts [0, 25].
    let old = vector("torus_with_t0.zipper-1.10.lrm");
    for (i, x) in [(0, 1), (1, 5)] {
        let bad = zipr_set(&old, 0, i, x);
        let words = format!("ring start {x}");
        breaks(&bad, 57, "ZIPR", zipr_at(&old, 0, i), &words);
    }
}

/// [V58] with `ROW_RECORDS` (version 1.15): a record's second word names a T0 row below
/// `n0` (its field's top bit clear) or is a pair's index; a row past the last breaks the
/// rule, any row of the file keeps it well formed (`open` answers every operator in range)
/// and verification finds the corners it gives wrong.
#[test]
fn v58_row_records() {
    // n0 = 3, no pairs: record word 1 is 1 + 2 bits, a row 0 to 3.
    let bytes = vector("torus_with_t0.zipper.lrm");
    let header = ZiprHeader::read(&payload(&bytes, Tag::ZIPR));
    assert_ne!(header.flags & 256, 0);
    assert_eq!((header.t0, header.pairs), (3, 0));
    assert_eq!(zipr_width(&bytes, RECORDS, 1), 3);
    field_breaks(&bytes, RECORDS, 1, 3, 58, "stores no valid opposite");
    let row = zipr_get(&bytes, RECORDS, 1);
    assert!(row < 3);
    let mut refused = 0;
    for other in (0..3).filter(|&r| r != row) {
        let bad = zipr_set(&bytes, RECORDS, 1, other);
        lrmesh::fuzz_checks::walk_in_range(&open(&bad, &Limits::default()).unwrap());
        refused += open_verified(&bad, &Limits::default()).is_err() as usize;
    }
    assert!(refused > 0, "another row gave the same corners");
}

/// [V58] Heads, symbols, exception and record words, tips.
#[test]
fn v58_symbols_and_heads() {
    let bytes = vector("torus_with_t0.zipper.lrm");
    // 25 ring vertices: 50 slots, two groups of three words; one block, whose head is two
    // words in the version 1.12 file (SHORT_HEADS): the anchors, then the counts before it
    // (16 bits each).
    let old12 = vector("torus_with_t0.zipper-1.12.lrm");
    field_breaks(&old12, HEADS, 1, 1, 58, "exceptions");
    field_breaks(&old12, HEADS, 1, 1 << 16, 58, "records");
    // Four blocks in the compact form: a count of block 2 off by one.
    let four = vector("four_spheres.zipper.lrm");
    for k in [4, 5] {
        let x = zipr_get(&four, HEADS, k);
        let bad = zipr_set(&four, HEADS, k, x ^ 1);
        breaks(&bad, 58, "ZIPR", zipr_at(&four, HEADS, 4), "block 2 counts");
    }
    // A symbol past the last slot.
    let w = zipr_get(&bytes, PLANES, 3);
    let bad = zipr_set(&bytes, PLANES, 3, w | 1 << 20);
    breaks(
        &bad,
        58,
        "ZIPR",
        zipr_at(&bytes, PLANES, 0),
        "past the last ring vertex",
    );
    // Exception words: bit 31, a tip out of range (32-bit words, version 1.9); packed, a
    // tip out of range (6-bit fields: the WART flag at bit 5).
    let old = vector("torus_with_t0.zipper-1.9.lrm");
    let x = zipr_get(&old, EXCEPTIONS, 0);
    for word in [x | 1 << 31, 25, 0x3FFF_FFFF] {
        field_breaks(&old, EXCEPTIONS, 0, word, 58, "WART flag and a vertex");
    }
    // With the WART flag in the field (version 1.14), and without (IMPLIED_WARTS, 5 bits).
    let old14 = vector("torus_with_t0.zipper-1.14.lrm");
    assert_eq!(zipr_width(&old14, EXCEPTIONS, 0), 6);
    for field in [25, 31, 1 << 5 | 30] {
        field_breaks(&old14, EXCEPTIONS, 0, field, 58, "WART flag and a vertex");
    }
    assert_eq!(zipr_width(&bytes, EXCEPTIONS, 0), 5);
    for field in [25, 31] {
        field_breaks(&bytes, EXCEPTIONS, 0, field, 58, "WART flag and a vertex");
    }
    // Record word 0 likewise; word 1: each state with a value it does not allow (packed:
    // the state in the top two bits of a 6-bit field, values below 4 n0 = 12; with
    // ROW_RECORDS, v58_row_records).
    field_breaks(&old, RECORDS, 0, 1 << 31, 58, "WART flag and a vertex");
    field_breaks(&old14, RECORDS, 0, 27, 58, "WART flag and a vertex");
    field_breaks(&bytes, RECORDS, 0, 27, 58, "WART flag and a vertex");
    for state_word in [1, 1 << 30 | 16, 1 << 30 | 3, 3 << 30 | 1] {
        field_breaks(&old, RECORDS, 1, state_word, 58, "no valid opposite");
    }
    assert_eq!(zipr_width(&old14, RECORDS, 1), 6);
    for state_field in [1, 1 << 4 | 12, 1 << 4 | 3, 3 << 4 | 1] {
        field_breaks(&old14, RECORDS, 1, state_field, 58, "no valid opposite");
    }
    // A delta tip out of range: the left anchor's offset from vertex 0 made negative (in
    // the 1.12 file, and with the compact vector's anchors rewritten 16 bits wide).
    for file in [old12.clone(), with_anchor_bits(&bytes, 16)] {
        let index = if ZiprHeader::is_compact(&payload(&file, Tag::ZIPR)) {
            ANCHORS
        } else {
            HEADS
        };
        let bad = zipr_set(&file, index, 0, 0x8000);
        if symbol(&file, 0) < 4 {
            breaks(&bad, 58, "ZIPR", zipr_at(&file, PLANES, 0), "has tip");
        }
    }
    // An exception slot turned into a delta: its word is left over, or a tip breaks.
    let exception_bit = (0..50).find(|&b| symbol(&bytes, b) == 6).unwrap();
    let bad = set_symbol(&bytes, exception_bit, 0);
    assert_eq!(verified_rule(&bad), Rule(58));
    let bad = set_symbol(&bytes, exception_bit, 4);
    assert_eq!(verified_rule(&bad), Rule(58));
}

/// [V59] T0 rows: vertices below `m`, explicit opposites counted in order, all used.
#[test]
fn v59_t0_rows() {
    let bytes = vector("genus3_torus.zipper.lrm"); // m = 19, 10 rows, 12 explicit opposites
    field_breaks(&bytes, T0_V, 4, 19, 59, "out of range");
    let codes: Vec<u32> = (0..10).map(|j| zipr_get(&bytes, T0_CODES, j)).collect();
    let bad = zipr_set(&bytes, T0_CODES, 0, codes[0] + (1 << 6));
    breaks(
        &bad,
        59,
        "ZIPR",
        zipr_at(&bytes, T0_CODES, 0),
        "explicit opposites start",
    );
    // A row's explicit code made a boundary code: an explicit opposite is left over, or a
    // later row's start is off.
    let (j, i) = (0..10)
        .flat_map(|j| (0..3).map(move |i| (j, i)))
        .find(|&(j, i)| codes[j] >> (2 * i) & 3 == 3)
        .unwrap();
    let bad = zipr_set(&bytes, T0_CODES, j, codes[j] & !(1 << (2 * i)));
    assert_eq!(format_error(&bad).rule, Rule(59));
}

/// [V60] `C`, pairs, explicit opposites and the T0 corners of records are corners; then the
/// LR rules every layout keeps.
#[test]
fn v60_corners_and_lr_rules() {
    let defective = vector("defective_torus.zipper.lrm"); // 7 off-ring vertices, 4 T0 rows
    let width = zipr_width(&defective, C, 0);
    // Packed corners are stored plus one (0 for NONE): corner 3, a corner past the T0
    // rows, the largest the field holds.
    for x in [4, 8 * 16 + 4 * 4 + 2, (1 << width) - 1] {
        field_breaks(&defective, C, 0, x, 60, "not a corner");
    }
    let bytes = vector("genus3_torus.zipper.lrm"); // m = 19, explicit T0 opposites
    field_breaks(&bytes, EXPLICIT, 0, 8, 60, "not a corner");
    // An exception's tip moved to another vertex: the triangles no longer fit together,
    // which only the verifying reader sees.
    let x = zipr_get(&bytes, EXCEPTIONS, 0);
    let wart = 1 << (zipr_width(&bytes, EXCEPTIONS, 0) - 1);
    let mut semantic = 0;
    for tip in 0..19u32 {
        let bad = zipr_set(&bytes, EXCEPTIONS, 0, x & wart | tip);
        if bad == bytes {
            continue;
        }
        match open_verified(&bad, &Limits::default()) {
            Err(Error::Format(e)) => {
                assert!(
                    [
                        Rule(12),
                        Rule(19),
                        Rule(21),
                        Rule(22),
                        Rule(23),
                        Rule(38),
                        Rule(53),
                        Rule(58)
                    ]
                    .contains(&e.rule),
                    "{e}"
                );
                if SEMANTIC_RULES.contains(&e.rule) {
                    semantic += 1;
                    // The well-formed open accepts it, and every operator answers in range.
                    let view = open(&bad, &Limits::default()).unwrap();
                    lrmesh::fuzz_checks::walk_in_range(&view);
                }
            }
            Err(e) => panic!("{e}"),
            Ok(_) => {}
        }
    }
    assert!(semantic > 0);
}

/// `WART_DELTAS` (bit 1 of the flags, version 1.8) cleared on files that need it: the
/// slots before canonical T2 triangles read as 1.7 does (their warts as plain triangles,
/// right redundant copies as missing), which is well formed but not the mesh: `open`
/// accepts it with every operator in range, verification fails.
#[test]
fn wart_deltas_cleared() {
    for name in [
        "torus_with_t0",
        "genus3_torus",
        "four_spheres",
        "bent_normals",
    ] {
        let bytes = vector(&format!("{name}.zipper.lrm"));
        let (_, flags) = zipr_flags(&bytes);
        assert_eq!(flags & 2, 2, "{name}: the vector sets WART_DELTAS");
        let bad = with_zipr_flags(&bytes, flags & !2);
        let view = open(&bad, &Limits::default()).unwrap();
        lrmesh::fuzz_checks::walk_in_range(&view);
        assert!(
            open_verified(&bad, &Limits::default()).is_err(),
            "{name}: verified without WART_DELTAS"
        );
    }
}

/// `LEFT_FOURS` and `RIGHT_FOURS` (bits 6 and 7, version 1.14) cleared on the vectors, and
/// `RIGHT_FOURS` set on those without it (meshes with `NULL` right slots): the slots of
/// symbol 5 then read otherwise (a four as a redundant copy or `NULL`, a `NULL` as a four),
/// which is not the mesh where such a slot exists: `open` refuses the file by a format error
/// (the triangle count, when a slot reads as `NULL` or no longer does) or accepts it with
/// every operator in range, and verification refuses it, unless the file has no such slot
/// (two vectors with a border and no four): then it decodes to the same mesh.
#[test]
fn fours_flipped() {
    let dir = manifest().join("spec/vectors");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.ends_with(".zipper.lrm"))
        .collect();
    names.sort();
    let (mut refused, mut right_set, mut read_alike) = (0, 0, 0);
    for name in &names {
        let bytes = vector(name);
        let (_, flags) = zipr_flags(&bytes);
        assert_ne!(
            flags & ZIPPER_LEFT_FOURS,
            0,
            "{name}: the writer sets LEFT_FOURS"
        );
        let mut forged = vec![with_zipr_flags(
            &bytes,
            flags & !(ZIPPER_LEFT_FOURS | ZIPPER_RIGHT_FOURS),
        )];
        if flags & ZIPPER_RIGHT_FOURS == 0 {
            forged.push(with_zipr_flags(&bytes, flags | ZIPPER_RIGHT_FOURS));
            right_set += 1;
        }
        for bad in forged {
            match open(&bad, &Limits::default()) {
                Ok(view) => {
                    lrmesh::fuzz_checks::walk_in_range(&view);
                    match open_verified(&bad, &Limits::default()) {
                        Err(_) => refused += 1,
                        Ok(alike) => {
                            // Only a file with no four and no NULL right slot reads so.
                            let original = open_verified(&bytes, &Limits::default()).unwrap();
                            assert_eq!(alike.to_mesh(), original.to_mesh(), "{name}");
                            read_alike += 1;
                        }
                    }
                }
                // A slot read as NULL, or no longer, changes the triangle count ([V12]).
                Err(Error::Format(_)) => refused += 1,
                Err(e) => panic!("{name}: {e}"),
            }
        }
    }
    assert!(right_set >= 2, "{right_set} vectors without RIGHT_FOURS");
    assert_eq!(refused + read_alike, names.len() + right_set);
    assert!(
        refused > 2 * read_alike,
        "{refused} refused, {read_alike} read alike"
    );
}

/// [V58] with superblocks: in the compact form a mesh of more than 16 blocks (1,024 ring
/// vertices) has `SUPER` entries; a count there that is not the exceptions (or records)
/// before its superblock breaks the first block's sum, and moving the difference into that
/// superblock's offsets keeps the file valid (only the sums are the rule).
#[test]
fn v58_superblock_counts() {
    const PER_SUPER: usize = 16;
    let mesh = lrmesh::generate::irregular_torus(6_000, 7);
    let options = lrmesh::write::EncodeOptions {
        connectivity: lrmesh::write::Connectivity::Zipper,
        ..Default::default()
    };
    let bytes = lrmesh::write::encode(&mesh, &options).unwrap();
    open_verified(&bytes, &Limits::default()).unwrap();
    let header = ZiprHeader::read(&payload(&bytes, Tag::ZIPR));
    let blocks = (header.m_r as usize).div_ceil(64);
    assert!(blocks > 2 * PER_SUPER, "{blocks} blocks");
    let count_bits = header.compact.unwrap().count_bits;
    // A superblock whose exception offsets all have room for one more.
    let s = (1..blocks / PER_SUPER)
        .find(|&s| {
            (s * PER_SUPER..(s + 1) * PER_SUPER)
                .all(|b| zipr_get(&bytes, HEADS, 2 * b) + 1 < 1 << count_bits[0])
        })
        .expect("a superblock with room");
    let (exceptions, records) = (
        zipr_get(&bytes, SUPER, 2 * s - 2),
        zipr_get(&bytes, SUPER, 2 * s - 1),
    );
    assert!(exceptions > 0 && records > 0, "{exceptions} {records}");
    // Its first block's counts are offsets 0 from SUPER.
    let first = s * PER_SUPER;
    assert_eq!(zipr_get(&bytes, HEADS, 2 * first), 0);
    assert_eq!(zipr_get(&bytes, HEADS, 2 * first + 1), 0);
    let at = zipr_at(&bytes, HEADS, 2 * first);
    let bad = zipr_set(&bytes, SUPER, 2 * s - 2, exceptions + 1);
    breaks(&bad, 58, "ZIPR", at, &format!("block {first} counts"));
    let bad = zipr_set(&bytes, SUPER, 2 * s - 1, records - 1);
    breaks(&bad, 58, "ZIPR", at, "records");
    let moved = zipr_set(&bytes, SUPER, 2 * s - 2, exceptions - 1);
    let moved = (first..blocks.min(first + PER_SUPER)).fold(moved, |b, block| {
        let w = zipr_get(&b, HEADS, 2 * block);
        zipr_set(&b, HEADS, 2 * block, w + 1)
    });
    open_verified(&moved, &Limits::default()).unwrap();
}

/// A file with `SHORT_HEADS` cleared is laid out with four-word heads (version 1.12), one
/// with `PACKED_LISTS` cleared with 32-bit lists, a compact one with `SHORT_HEADS` set is
/// refused: either way its length no longer fits its counts, or the flag has no meaning. A
/// compact file with the compact bit cleared reads its flags word as `m`.
#[test]
fn layout_flags_cleared() {
    let old = vector("torus_with_t0.zipper-1.12.lrm");
    let old14 = vector("torus_with_t0.zipper-1.14.lrm");
    let bytes = vector("torus_with_t0.zipper.lrm");
    for (file, flag, name) in [
        (&old, 4, "SHORT_HEADS"),
        (&old, 8, "PACKED_LISTS"),
        (&old14, 8, "PACKED_LISTS"),
    ] {
        let (_, flags) = zipr_flags(file);
        assert_eq!(flags & flag, flag, "the vector sets {name}");
        let bad = with_zipr_flags(file, flags & !flag);
        breaks(
            &bad,
            56,
            "ZIPR",
            section_at(file, Tag::ZIPR),
            "counts call for",
        );
    }
    let (_, flags) = zipr_flags(&bytes);
    let bad = forge(&bytes, Tag::ZIPR, |p| put(p, 0, flags));
    assert_eq!(format_error(&bad).rule, Rule(56));
}

/// The fuzz targets `container_forged` and `operators` start from Zipper containers too
/// (kind bits 1 with bit 2 set), with holes, seams and quantized positions among them.
#[test]
fn the_fuzz_targets_reach_the_zipper() {
    let zipper: Vec<u8> = (0..=255u8)
        .filter(|&choice| {
            let bytes = lrmesh::fuzz_checks::forged_base(choice);
            open(&bytes, &Limits::default())
                .unwrap()
                .summary()
                .connectivity
                == "zipper"
        })
        .collect();
    assert!(zipper.contains(&0x05) && zipper.contains(&0x95) && zipper.contains(&0x55));
    assert_eq!(zipper.len(), 32);
}

/// A mesh without triangles has no ring and no T0 rows: its corner fields are zero bits
/// wide, so a header may claim billions of opposite pairs in a file of a few bytes. The
/// reader neither panics nor walks them: the pairs are not used by any slot ([V58]).
#[test]
fn zero_width_lists_of_any_length() {
    let mesh = lrmesh::Mesh {
        positions: vec![[0.0; 3], [1.0, 0.0, 0.0]],
        ..Default::default()
    };
    let options = lrmesh::write::EncodeOptions {
        connectivity: lrmesh::write::Connectivity::Zipper,
        ..Default::default()
    };
    let bytes = lrmesh::write::encode(&mesh, &options).unwrap();
    open_verified(&bytes, &Limits::default()).unwrap();
    let header = ZiprHeader::read(&payload(&bytes, Tag::ZIPR));
    assert_eq!((header.m_r, header.t0), (0, 0));
    for pairs in [1, 0x8000_0000, u32::MAX] {
        let bad = with_header(&bytes, |h| {
            h.compact.as_mut().unwrap().count_bytes = 4;
            h.pairs = pairs;
        });
        assert_eq!(format_error(&bad).rule, Rule(58), "{pairs} pairs");
    }
}

/// `bytes` with left slots `t` and `t + 2` of a ring of `slots` slots (mod `slots`, `t`
/// not at the ring's end otherwise) made redundant copies (symbol 5, tip `v.n.n`, read so
/// without `LEFT_FOURS`, which `bytes` must not have), so that the first jumps to a slot with
/// no canonical triangle, the next delta slot of the side taking their deltas so that every
/// chain stays as it was; `None` when their symbols do not allow it.
fn jump_to_a_redundant_slot(bytes: &[u8], t: usize, slots: usize) -> Option<Vec<u8>> {
    let block = |t: usize| t / 128;
    let [a, b, c] = [t, t + 2, t + 4].map(|x| x % slots);
    let s = [a, b, c].map(|x| symbol(bytes, x));
    // The deltas the third slot takes: those of the first two in its block (a block's chain
    // starts from its anchor).
    let taken: u32 = [(a, s[0]), (b, s[1])]
        .iter()
        .filter(|&&(x, _)| block(x) == block(c))
        .map(|&(_, d)| d)
        .sum();
    if s.iter().any(|&d| d > 3) || s[2] + taken > 3 {
        return None;
    }
    let bad = set_symbol(&set_symbol(bytes, a, 5), b, 5);
    Some(set_symbol(&bad, c, s[2] + taken))
}

/// [V19]: a slot that jumps to one with no canonical triangle. On one ring the well-formed
/// open checks it on the slots' bit vectors a word at a time, the last two slots with the
/// wrap: pairs within a word, across words and blocks, and across the end. With two rings
/// it follows each jumping slot to its ring's next: a pair in each ring.
#[test]
fn v19_jump_to_a_redundant_slot() {
    use lrmesh::generate::{append, torus};
    let bytes = version_1_13("torus_24x30.lrm", &torus(24, 30));
    let slots = 2 * ZiprHeader::read(&payload(&bytes, Tag::ZIPR)).m_r as usize;
    assert!(slots > 3 * 128, "several blocks");
    let mut tested = 0;
    for t in [4, 10, 20, 60, 62, 94, 126, 254, 382, slots - 2, slots - 4] {
        if let Some(bad) = jump_to_a_redundant_slot(&bytes, t, slots) {
            assert_eq!(format_error(&bad).rule, Rule(19), "slot {t}");
            tested += 1;
        }
    }
    assert!(tested >= 4, "only {tested} slots tested on one ring");
    let mut two = torus(20, 24);
    append(&mut two, &torus(16, 20));
    let bytes = version_1_13("two_tori.lrm", &two);
    let header = ZiprHeader::read(&payload(&bytes, Tag::ZIPR));
    assert_eq!(header.rings, 2);
    let second = 2 * zipr_get(&bytes, 0, 1) as usize; // ring_starts[1], as a slot
    let slots = 2 * header.m_r as usize;
    let mut tested = 0;
    for t in [20, 130, second + 40, second + 200] {
        if let Some(bad) = jump_to_a_redundant_slot(&bytes, t, slots) {
            assert_eq!(format_error(&bad).rule, Rule(19), "slot {t} of two rings");
            tested += 1;
        }
    }
    assert!(tested >= 2, "only {tested} slots tested on two rings");
}
