//! The `ZIPR` section (connectivity kind 5): the Zipper, validated once by rules V56–V60 of
//! `spec/FORMAT.md` (V60 brings in the LR rules every layout keeps) and read in place as
//! [`ZipperTables`] over the buffer's little-endian words.

use super::fields::Fields;
use super::lr_rules::{check_rings, verify_read_back, SlotMap};
use super::zipper_scan::scan_slots;
use super::Sections;
use crate::corner_table::NONE;
use crate::error::{Result, Rule};
use crate::format::layout::{
    ZiprHeader, LR_BOUNDARIES_ON_RING, ZIPPER_IMPLIED_WARTS, ZIPPER_INNER_RING_STARTS,
    ZIPPER_JOINED_LISTS, ZIPPER_LEFT_FOURS, ZIPPER_PACKED_LISTS, ZIPPER_RIGHT_FOURS,
    ZIPPER_RING_BLOCKS, ZIPPER_ROW_RECORDS, ZIPPER_SHORT_HEADS, ZIPPER_WART_DELTAS,
};
use crate::format::Tag;
use crate::ids::Corner;
use crate::lr::zipper::{
    compact_header_len, first_bit, four_sides, plane_array_words, ring_block_field, Field, Packed,
    BLOCK_SHIFT, EXPLICIT, EXPLICIT_SHIFT, MAX_HEAD_WIDTH, PLANE_WORDS, RECORD_WORDS, STATE_SHIFT,
    STORES_FIRST, STORES_SECOND,
};
use crate::lr::{ZipperTables, NULL};
use crate::words::{LeWords, Words};
use check_slots::check_slots;

mod check_slots;

/// Array indices in the section, in file order.
const PLANES: usize = 3;
const HEADS: usize = 4;
const EXCEPTIONS: usize = 5;
const RECORDS: usize = 6;
const PAIRS: usize = 7;
const T0_V: usize = 8;
const T0_CODES: usize = 9;
const EXPLICIT_OPPOSITES: usize = 10;
const C: usize = 11;

/// The `ZIPR` section as tables and the number of canonical triangles they hold, after
/// checking the rules that keep every operator's answer in range; with `verify`, every rule
/// (FORMAT.md §3.5e, §5.1).
pub(super) fn zipper_tables<'a>(
    sections: &Sections<'a>,
    m: u32,
    verify: bool,
) -> Result<(ZipperTables<LeWords<'a>>, u64)> {
    let f = Fields::new(sections.required(Tag::ZIPR)?);
    let b = f.bytes();
    let h = zipr_header(&f, m)?;
    let count_at = |i: usize| h.count_offset(i);
    let compact = h.compact.is_some();
    let (m_r, rings, n0) = (h.m_r, h.rings, h.t0);
    // SHORT_HEADS has no meaning in the compact form, whose heads are bit fields.
    let known = LR_BOUNDARIES_ON_RING
        | ZIPPER_WART_DELTAS
        | if compact { 0 } else { ZIPPER_SHORT_HEADS }
        | ZIPPER_PACKED_LISTS
        | ZIPPER_INNER_RING_STARTS
        | ZIPPER_RING_BLOCKS
        | ZIPPER_LEFT_FOURS
        | ZIPPER_RIGHT_FOURS
        | ZIPPER_ROW_RECORDS
        | ZIPPER_IMPLIED_WARTS
        | ZIPPER_JOINED_LISTS;
    if h.flags & !known != 0 || h.reserved != 0 {
        return Err(f.err(
            if compact { 0 } else { 32 },
            Rule(56),
            "unknown flag bits or reserved bits are set",
        ));
    }
    // Their fields only exist as bit fields; the joined stream only in the compact form.
    let bit_flags = ZIPPER_ROW_RECORDS | ZIPPER_IMPLIED_WARTS | ZIPPER_JOINED_LISTS;
    if h.flags & bit_flags != 0 && h.flags & ZIPPER_PACKED_LISTS == 0 {
        return Err(f.err(
            if compact { 0 } else { 32 },
            Rule(56),
            "ROW_RECORDS, IMPLIED_WARTS or JOINED_LISTS without PACKED_LISTS",
        ));
    }
    if h.flags & ZIPPER_JOINED_LISTS != 0 && !compact {
        return Err(f.err(32, Rule(56), "JOINED_LISTS without the compact form"));
    }
    if m >= NULL {
        return Err(f.err(
            0,
            Rule(56),
            format!("{m} vertices exceed the LR limit of {}", NULL - 1),
        ));
    }
    if m_r > m || (m_r == 0) != (rings == 0) || rings as u64 > m_r as u64 / 4 {
        return Err(f.err(
            count_at(1),
            Rule(56),
            format!("{m_r} ring vertices in {rings} rings for {m} vertices (rings have at least 4 vertices)"),
        ));
    }
    if 8 * m_r as u64 + 4 * n0 as u64 >= NONE as u64 {
        return Err(f.err(count_at(3), Rule(56), "corner ids exceed 32 bits"));
    }
    let layout = h.layout();
    f.expect_len(layout.as_ref().map(|l| l.len), Rule(56))?;
    let layout = layout.expect("checked by expect_len");
    let arrays: [_; 13] = std::array::from_fn(|i| layout.arrays[i]);
    let words: [_; 13] = std::array::from_fn(|i| LeWords(&b[arrays[i].start..arrays[i].end()]));
    let starts = arrays.map(|a| a.start);
    let [ring_starts, ring_last, ring_rank, planes, heads, exceptions, records, pairs, t0_v, t0_codes, t0_explicit, c, super_counts] =
        words;
    // The seven lists, words or bit fields (PACKED_LISTS), read as words.
    let lengths = h.list_lengths().expect("m_r <= m: checked above");
    let Ok(lengths) = lengths
        .map(usize::try_from)
        .into_iter()
        .collect::<Result<Vec<_>, _>>()
    else {
        return Err(f.err(
            count_at(4),
            Rule(56),
            "list lengths exceed the address space",
        ));
    };
    let fields = h.list_fields();
    // JOINED_LISTS: list q of the nine (anchors, counts, then the seven) from bit
    // `joined[q]` of HEADS' stream, over the words that hold it.
    let joined = h.joined_bits();
    let stream = |q: usize, fields: [Field; 2], len: usize| {
        let bits = joined.expect("joined");
        let (from, to) = (bits[q], bits[q + 1]);
        let words = &heads.0[4 * (from / 32) as usize..4 * to.div_ceil(32) as usize];
        Packed::new_at(LeWords(words), (from % 32) as u8, len, fields)
    };
    let list = |i: usize, words: LeWords<'a>| match joined {
        Some(_) => stream(2 + i, fields[i], lengths[i]),
        None => Packed::new(words, lengths[i], fields[i]),
    };
    let lists = [
        list(0, exceptions),
        list(1, records),
        list(2, pairs),
        list(3, t0_v),
        list(4, t0_codes),
        list(5, t0_explicit),
        list(6, c),
    ];
    // In the compact form, HEADS is two lists: the anchors' and the counts'.
    let anchor_bytes = 4 * h.anchor_words() as usize;
    let head_fields = h.head_fields();
    let (anchors, head_counts, heads) = match head_fields {
        Some((anchor, counts)) if joined.is_some() => {
            let blocks = 2 * h.blocks() as usize;
            let anchors = stream(0, anchor, blocks);
            let head_counts = stream(1, counts, blocks);
            (anchors, head_counts, LeWords(&[]))
        }
        Some((anchor, counts)) => {
            let (a, c) = heads.0.split_at(anchor_bytes);
            let blocks = 2 * h.blocks() as usize;
            let anchors = Packed::new(LeWords(a), blocks, anchor);
            let head_counts = Packed::new(LeWords(c), blocks, counts);
            for (k, list) in [&anchors, &head_counts].into_iter().enumerate() {
                if !list.padding_is_zero() {
                    let end = [starts[HEADS] + anchor_bytes, arrays[HEADS].end()][k];
                    return Err(f.err(
                        end - 4,
                        Rule(56),
                        format!(
                            "HEADS: bits past the last {} field are set",
                            ["anchor", "count"][k]
                        ),
                    ));
                }
            }
            (anchors, head_counts, LeWords(&[]))
        }
        None => {
            let none = || Packed::new(LeWords(&[]), 0, [Field::WORD; 2]);
            (none(), none(), heads)
        }
    };
    let count_fields = head_fields.map(|(_, counts)| counts);
    // Where element `i` of an array starts (an error names its byte); in the compact form,
    // HEADS' element `i` is the counts' list's.
    let offset_of = |array: usize, i: usize| match (array, count_fields, joined) {
        (EXCEPTIONS..=C, _, Some(bits)) => {
            let (q, fields) = (2 + array - EXCEPTIONS, fields[array - EXCEPTIONS]);
            starts[HEADS] + ((bits[q] + first_bit(fields, i as u64)) / 8) as usize
        }
        (HEADS, Some(counts), Some(bits)) => {
            starts[HEADS] + ((bits[1] + first_bit(counts, i as u64)) / 8) as usize
        }
        (EXCEPTIONS..=C, _, None) => {
            starts[array] + (first_bit(fields[array - EXCEPTIONS], i as u64) / 8) as usize
        }
        (HEADS, Some(counts), None) => {
            starts[HEADS] + anchor_bytes + (first_bit(counts, i as u64) / 8) as usize
        }
        _ => starts[array] + 4 * i,
    };
    let word_err = |array: usize, i: usize, rule: Rule, message: String| {
        f.err(offset_of(array, i), rule, message)
    };
    // Joined, the bits past one list are the next's: only the stream's end is padding
    // (where the last list, C, ends).
    let padded = |k: usize| joined.is_none() || k == 6;
    if let Some(k) = (0..7).find(|&k| padded(k) && !lists[k].padding_is_zero()) {
        let array = EXCEPTIONS + k;
        let end = match joined {
            Some(_) => arrays[HEADS].end(),
            None => arrays[array].end(),
        };
        return Err(f.err(
            end - 4,
            Rule(56),
            format!(
                "{}: bits past its last field are set",
                ZiprHeader::ARRAYS[array]
            ),
        ));
    }
    let [exceptions, records, pairs, t0_v, t0_codes, t0_explicit, c] = lists;

    // [V57] rings, as for the standard LR; the bit vectors only with several rings. The
    // tables keep the inner starts (rings 1 to R − 1) whether or not the file stores the
    // first and last.
    let bits = h.has_ring_bits().then_some((&ring_last, &ring_rank));
    // Every start, 0 and m_r included (R + 1), for these rules and those of RING_BLOCKS.
    let all: Vec<u32> = (0..=rings as usize)
        .map(|r| match r {
            _ if !h.inner_ring_starts() => ring_starts.at(r),
            0 => 0,
            r if r == rings as usize => m_r,
            r => ring_starts.at(r - 1),
        })
        .collect();
    let ring_starts = if h.inner_ring_starts() {
        // The implied end at fault: the last stored start leaves the last ring too short.
        // (The implied first start, 0, cannot be; with one ring [V56] keeps 4 ≤ m_r.)
        check_rings(&all, bits, m_r, |array, i, message| match (array, i) {
            (0, i) if i >= rings as usize && i >= 2 => word_err(
                0,
                i - 2,
                Rule(57),
                format!(
                    "ring start {} leaves fewer than 4 vertices to the last ring (m_r = {m_r})",
                    all[i - 1]
                ),
            ),
            (0, i) if i == 0 || i >= rings as usize => f.err(4, Rule(57), message),
            (0, i) => word_err(0, i - 1, Rule(57), message),
            (array, i) => word_err(array, i, Rule(57), message),
        })?;
        ring_starts
    } else {
        check_rings(&all, bits, m_r, |array, i, message| {
            word_err(array, i, Rule(57), message)
        })?;
        // Words 1 to R − 1 of the R + 1 (none with fewer than two rings).
        let inner = 4 * (rings as usize).saturating_sub(1);
        LeWords(&ring_starts.0[4..4 + inner])
    };

    // With RING_BLOCKS, array 1 holds the ring of each block's first vertex.
    let (ring_last, ring_blocks) = match h.ring_blocks() {
        true => {
            let field = ring_block_field(rings);
            let count = h.ring_block_count() as usize;
            let blocks = Packed::new(ring_last, count, [field; 2]);
            check_ring_blocks(&blocks, &all, |k, message| {
                let bit = first_bit([field; 2], k as u64);
                f.err(starts[1] + (bit / 8) as usize, Rule(57), message)
            })?;
            (LeWords(&[]), blocks)
        }
        false => (ring_last, Packed::new(LeWords(&[]), 0, [Field::WORD; 2])),
    };

    let mut tables = ZipperTables {
        ring_starts,
        rings,
        ring_last,
        ring_rank,
        ring_blocks,
        planes,
        heads,
        anchors,
        head_counts,
        exceptions,
        records,
        pairs,
        t0_v,
        t0_codes,
        t0_explicit,
        c,
        super_counts,
        m_r,
        m,
        boundaries_on_ring: false,
        wart_deltas: h.flags & ZIPPER_WART_DELTAS != 0,
        short_heads: h.flags & ZIPPER_SHORT_HEADS != 0,
        compact,
        packed_lists: h.flags & ZIPPER_PACKED_LISTS != 0,
        inner_ring_starts: h.inner_ring_starts(),
        ring_blocks_flag: h.flags & ZIPPER_RING_BLOCKS != 0,
        four_sides: four_sides(
            h.flags & ZIPPER_LEFT_FOURS != 0,
            h.flags & ZIPPER_RIGHT_FOURS != 0,
        ),
        row_records: h.flags & ZIPPER_ROW_RECORDS != 0,
        implied_warts: h.flags & ZIPPER_IMPLIED_WARTS != 0,
        joined_lists: joined.is_some(),
    };
    debug_assert_eq!(tables.planes.count(), plane_array_words(m_r));

    // [V58] symbols, heads, exceptions and records: a fast pass first; the slot at fault is
    // looked for only when it fails. Tests and fuzzing check that both passes agree.
    let fast =
        scan_slots(&tables).map(|(bits, canonical)| SlotMap::with_bits(bits, canonical, m_r, n0));
    #[cfg(any(test, fuzzing))]
    {
        let slow = check_slots(&tables, &word_err)
            .ok()
            .map(|flags| SlotMap::with_flags(flags, m_r, n0));
        let agree = match (&fast, &slow) {
            (Some(fast), Some(slow)) => fast.agrees_with(slow),
            (fast, slow) => fast.is_none() && slow.is_none(),
        };
        assert!(agree, "the fast pass and the slot loop agree");
    }
    let slots = match fast {
        Some(slots) => slots,
        None => SlotMap::with_flags(check_slots(&tables, &word_err)?, m_r, n0),
    };
    // [V59] T0 rows.
    let n_explicit = tables.t0_explicit.count();
    let mut explicit = 0usize;
    let (mut t0_vertices, mut t0_codes) = (tables.t0_v.iter(), tables.t0_codes.iter());
    for j in 0..n0 as usize {
        for i in 0..3 {
            let x = t0_vertices.next().expect("3 n0 T0 vertices");
            if x >= m {
                return Err(word_err(
                    T0_V,
                    3 * j + i,
                    Rule(59),
                    format!("T0 row {j}: vertex {x} out of range ({m} vertices)"),
                ));
            }
        }
        let word = t0_codes.next().expect("n0 T0 code words");
        if (word >> EXPLICIT_SHIFT) as usize != explicit {
            return Err(word_err(
                T0_CODES,
                j,
                Rule(59),
                format!(
                    "T0 row {j}: its explicit opposites start at {}, not {explicit}",
                    word >> EXPLICIT_SHIFT
                ),
            ));
        }
        explicit += (0..3).filter(|i| word >> (2 * i) & 3 == EXPLICIT).count();
        if explicit > n_explicit {
            return Err(word_err(
                T0_CODES,
                j,
                Rule(59),
                format!("T0 row {j}: more explicit opposites than the {n_explicit} stored"),
            ));
        }
    }
    drop((t0_vertices, t0_codes));
    if explicit != n_explicit {
        return Err(word_err(
            EXPLICIT_OPPOSITES,
            explicit,
            Rule(59),
            format!(
                "{} explicit opposites not used by any T0 row",
                n_explicit - explicit
            ),
        ));
    }

    // [V60] C, the stored opposites and the explicit T0 opposites are corners; then the LR
    // rules every layout keeps (V19; V21–V23, V38 and V53 when verifying).
    let corner_ok = |x: u32| x == NONE || slots.is_corner(x);
    let corner_arrays = [
        (C, &tables.c),
        (PAIRS, &tables.pairs),
        (EXPLICIT_OPPOSITES, &tables.t0_explicit),
    ];
    for (array, words) in corner_arrays {
        if let Some((i, x)) = words.iter().enumerate().find(|&(_, x)| !corner_ok(x)) {
            return Err(word_err(
                array,
                i,
                Rule(60),
                format!("{x} is not a corner of the mesh"),
            ));
        }
    }
    // With ROW_RECORDS a record names a row ([V58]), whose corners are all T0 corners.
    let offsets = !tables.row_records;
    let stored = tables.records.iter().skip(1).step_by(RECORD_WORDS);
    for (r, word) in stored.enumerate().filter(|_| offsets) {
        let state = word >> STATE_SHIFT;
        if (state == STORES_FIRST || state == STORES_SECOND)
            && !corner_ok((8 * m_r).wrapping_add(word & ((1 << STATE_SHIFT) - 1)))
        {
            return Err(word_err(
                RECORDS,
                RECORD_WORDS * r + 1,
                Rule(60),
                format!("record {r} stores an opposite that is not a T0 corner"),
            ));
        }
    }
    let corner_at = |c: Corner| {
        if c.0 >= 8 * m_r {
            offset_of(T0_V, 3 * ((c.0 - 8 * m_r) / 4) as usize)
        } else {
            starts[PLANES] + 4 * PLANE_WORDS * (c.0 >> (3 + BLOCK_SHIFT)) as usize
        }
    };
    let vertex_at = |v: u32| {
        if v < m_r {
            starts[PLANES] + 4 * PLANE_WORDS * (v >> BLOCK_SHIFT) as usize
        } else {
            offset_of(C, (v - m_r) as usize)
        }
    };
    slots.check_jumps(&tables, &f, corner_at)?;
    let flag = h.flags & LR_BOUNDARIES_ON_RING != 0;
    tables.boundaries_on_ring = flag;
    if verify {
        let lr = tables.to_lr_tables();
        tables.boundaries_on_ring =
            verify_read_back(&tables, lr, &f, corner_at, vertex_at, flag, 32)?;
    }
    Ok((tables, slots.triangles + n0 as u64))
}

/// [V56] on the header: its length, the compact form's count and field widths (version
/// 1.13), and `m`.
pub(super) fn zipr_header(f: &Fields, m: u32) -> Result<ZiprHeader> {
    let b = f.bytes();
    f.expect_at_least(4, Rule(56))?;
    if ZiprHeader::is_compact(b) {
        f.expect_at_least(8, Rule(56))?;
        let k = b[4];
        if !(1..=4).contains(&k) {
            return Err(f.err(
                4,
                Rule(56),
                format!("counts of {k} bytes (the compact header's are 1 to 4)"),
            ));
        }
        if let Some(i) = (5..8).find(|&i| b[i] > MAX_HEAD_WIDTH) {
            return Err(f.err(
                i,
                Rule(56),
                format!("a head field of {} bits (at most {MAX_HEAD_WIDTH})", b[i]),
            ));
        }
        f.expect_at_least(compact_header_len(k), Rule(56))?;
    } else {
        f.expect_at_least(ZiprHeader::LEN, Rule(56))?;
    }
    let h = ZiprHeader::read(b);
    f.expect_vertices(h.count_offset(0), h.m, m, Rule(56))?;
    Ok(h)
}

/// [V57] with `RING_BLOCKS`: each field is the ring of its block's first vertex (the ring
/// starts after 0 at or below it), and the bits past the last field are 0. `starts` are every
/// ring's start, then `m_r`, checked already; `err(k, message)` locates field `k`.
fn check_ring_blocks(
    blocks: &Packed<LeWords>,
    starts: &[u32],
    err: impl Fn(usize, String) -> crate::Error,
) -> Result<()> {
    let expected = crate::lr::zipper::ring_blocks(starts);
    for (k, (got, want)) in blocks.iter().zip(expected).enumerate() {
        if got != want {
            return Err(err(
                k,
                format!(
                    "RING_BLOCKS field {k} says ring {got}, but vertex {} is on ring {want}",
                    k << BLOCK_SHIFT
                ),
            ));
        }
    }
    if !blocks.padding_is_zero() {
        let last = blocks.count().saturating_sub(1);
        return Err(err(
            last,
            "RING_BLOCKS: bits past its last field are set".into(),
        ));
    }
    Ok(())
}
