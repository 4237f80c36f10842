//! The `LRBE` section (connectivity kind 4): the bit-efficient LR, validated once by rules
//! V33–V38 of `spec/FORMAT.md` (V37 brings in the LR rules every layout keeps) and read in
//! place as [`CompactTables`] over the buffer's little-endian words and units.

use super::fields::Fields;
use super::lr_compact_scan::{scan_pairs, stored_opposites};
use super::lr_rules::{check_rings, verify_read_back, SlotMap};
use super::Sections;
use crate::corner_table::NONE;
use crate::error::{Result, Rule};
use crate::format::layout::{LrbeHeader, LRBE_TIP_BASES, LR_BOUNDARIES_ON_RING};
use crate::format::Tag;
use crate::ids::Corner;
use crate::lr::compact::{plain, BLOCK_SHIFT, EXTENDED, OVERFLOW_ROW_WORDS, T0_ROW_UNITS};
use crate::lr::{CompactTables, LrLayout, NULL};
use crate::words::{LeUnits, LeWords, Units, Words};

/// The `LRBE` section as tables and the number of canonical triangles they hold, after
/// checking the rules that keep every operator's answer in range; with `verify`, every rule
/// (FORMAT.md §3.5d, §5.1).
pub(super) fn lr_compact_tables<'a>(
    sections: &Sections<'a>,
    m: u32,
    verify: bool,
) -> Result<(CompactTables<LeWords<'a>, LeUnits<'a>>, u64)> {
    let f = Fields::new(sections.required(Tag::LRBE)?);
    let b = f.bytes();
    // [V33] counts and length.
    f.expect_at_least(LrbeHeader::LEN, Rule(33))?;
    let h = LrbeHeader::read(b);
    let (m_r, rings, n0, overflow_rows) = (h.m_r, h.rings, h.t0, h.overflow_rows);
    f.expect_vertices(0, h.m, m, Rule(33))?;
    if h.flags & !(LR_BOUNDARIES_ON_RING | LRBE_TIP_BASES) != 0 {
        return Err(f.err(28, Rule(33), "unknown flag bits are set"));
    }
    if m >= NULL {
        return Err(f.err(
            0,
            Rule(33),
            format!("{m} vertices exceed the LR limit of {}", NULL - 1),
        ));
    }
    if m_r > m || (m_r == 0) != (rings == 0) || rings as u64 > m_r as u64 / 4 {
        return Err(f.err(
            4,
            Rule(33),
            format!("{m_r} ring vertices in {rings} rings for {m} vertices (rings have at least 4 vertices)"),
        ));
    }
    if 8 * m_r as u64 + 4 * n0 as u64 >= NONE as u64 {
        return Err(f.err(12, Rule(33), "corner ids exceed 32 bits"));
    }
    let layout = h.layout();
    f.expect_len(layout.as_ref().map(|l| l.len), Rule(33))?;
    let layout = layout.expect("checked by expect_len");
    let arrays: [_; 11] = std::array::from_fn(|i| layout.arrays[i]);
    let words: [_; 9] = std::array::from_fn(|i| LeWords(&b[arrays[i].start..arrays[i].end()]));
    let units: [_; 2] =
        std::array::from_fn(|i| LeUnits(&b[arrays[9 + i].start..arrays[9 + i].end()]));
    let starts = arrays.map(|a| a.start);
    let [ring_starts, ring_last, ring_rank, pairs, blocks, groups, c, overflow, bases] = words;
    let [t0, records] = units;
    let word_err = |array: usize, i: usize, rule: Rule, message: String| {
        f.err(starts[array] + 4 * i, rule, message)
    };
    let unit_err = |array: usize, i: usize, rule: Rule, message: String| {
        f.err(starts[array] + 2 * i, rule, message)
    };

    // [V34] rings, as for the standard LR; the bit vectors only with several rings.
    check_rings(
        &ring_starts,
        h.has_ring_bits().then_some((&ring_last, &ring_rank)),
        m_r,
        |array, i, message| word_err(array, i, Rule(34), message),
    )?;

    let mut tables = CompactTables {
        ring_starts,
        ring_last,
        ring_rank,
        pairs,
        blocks,
        bases,
        groups,
        c,
        overflow,
        t0,
        records,
        m_r,
        m,
        boundaries_on_ring: false,
        tip_bases: h.has_tip_bases(),
    };

    // [V35] pairs and records: records tile the record units in ring order, each block's
    // first record where the block says, every field inside its record; tips in range.
    // A fast pass first; the pair at fault is looked for only when it fails. With one ring
    // it also flags the slots for [V19] and [V37].
    let scan = scan_pairs(&tables, m, rings == 1);
    #[cfg(any(test, fuzzing))]
    assert_eq!(
        scan.pairs_hold,
        check_pairs(&tables, m, &word_err, &unit_err).is_ok(),
        "the fast pass and the pair loop agree"
    );
    if !scan.pairs_hold {
        check_pairs(&tables, m, &word_err, &unit_err)?;
    }

    // [V36] T0 rows: codes, overflow rows used once each and in order, vertices in range.
    let mut next_overflow = 0u32;
    for j in 0..n0 as usize {
        let at = T0_ROW_UNITS * j;
        let codes = t0.at(at + 3);
        let overflow_index = t0.at(at + 1) as u32 | (t0.at(at + 2) as u32) << 16;
        let overflows = codes & 0x8000 != 0;
        if overflows {
            let fault = if codes != 0x8000 {
                Some(3)
            } else if t0.at(at) != 0 {
                Some(0)
            } else if overflow_index != next_overflow {
                Some(1)
            } else {
                None
            };
            if let Some(i) = fault {
                return Err(unit_err(
                    9,
                    at + i,
                    Rule(36),
                    format!("T0 row {j}: malformed overflow row (overflow row {next_overflow} expected)"),
                ));
            }
            next_overflow += 1;
        } else if codes & !0x3F != 0 {
            return Err(unit_err(
                9,
                at + 3,
                Rule(36),
                format!("T0 row {j}: reserved bits set"),
            ));
        } else if let Some(i) = [1, 2].into_iter().find(|&i| t0.at(at + i) & 0x8000 != 0) {
            // A vertex field is 15 bits.
            return Err(unit_err(
                9,
                at + i,
                Rule(36),
                format!("T0 row {j}: vertex field out of range"),
            ));
        }
        for i in 0..3 {
            let x = tables.t0_vertex(3 * j as u32 + i);
            if x >= m {
                let message = format!("T0 row {j}: vertex {x} out of range ({m} vertices)");
                return Err(if overflows {
                    let word = OVERFLOW_ROW_WORDS * overflow_index as usize + i as usize;
                    word_err(7, word, Rule(36), message)
                } else {
                    unit_err(9, at + i as usize, Rule(36), message)
                });
            }
        }
    }
    if next_overflow != overflow_rows {
        return Err(word_err(
            7,
            0,
            Rule(36),
            format!(
                "{} overflow rows not used by any T0 row",
                overflow_rows - next_overflow
            ),
        ));
    }

    // [V37] C, the opposites that records store and the overflow rows' opposites hold
    // corners; then the LR rules every layout keeps (V19; V21–V23 and V38 when verifying).
    // The fast pass's flags only when it found V35 to hold: it stops at a fault.
    let slots = match scan.flags.filter(|_| scan.pairs_hold) {
        Some((flags, canonical)) => SlotMap::with_counted_flags(flags, canonical, m_r, n0),
        None => SlotMap::new(&tables),
    };
    #[cfg(any(test, fuzzing))]
    assert!(
        slots.agrees_with(&SlotMap::new(&tables)),
        "the fast pass's slot flags are the slot loop's"
    );
    let corner_ok = |x: u32| x == NONE || slots.is_corner(x);
    for i in 0..(m - m_r) as usize {
        let x = tables.isolated_corner(i as u32);
        if !corner_ok(x) {
            return Err(word_err(
                6,
                i,
                Rule(37),
                format!("{x} is not a corner of the mesh"),
            ));
        }
    }
    let stored = match scan.pairs_hold {
        true => scan.stored,
        false => stored_opposites(&tables),
    };
    for (v, x) in stored {
        if !corner_ok(x) {
            return Err(word_err(
                3,
                v as usize,
                Rule(37),
                format!("pair {v}: its record stores opposite {x}, not a corner of the mesh"),
            ));
        }
    }
    for i in 0..overflow.count() {
        let x = overflow.at(i);
        if i % OVERFLOW_ROW_WORDS >= 3 && !corner_ok(x) {
            return Err(word_err(
                7,
                i,
                Rule(37),
                format!("overflow opposite {x} is not a corner of the mesh"),
            ));
        }
    }
    let corner_at = |c: Corner| {
        if c.0 >= 8 * m_r {
            starts[9] + 2 * T0_ROW_UNITS * ((c.0 - 8 * m_r) / 4) as usize
        } else {
            starts[3] + 4 * (c.0 >> 3) as usize
        }
    };
    let vertex_at = |v: u32| {
        if v < m_r {
            starts[3] + 4 * v as usize
        } else {
            starts[6] + 4 * (v - m_r) as usize
        }
    };
    slots.check_jumps(&tables, &f, corner_at)?;
    let flag = h.flags & LR_BOUNDARIES_ON_RING != 0;
    tables.boundaries_on_ring = flag;
    if verify {
        let lr = crate::lr::read_back::standard_tables(&tables);
        tables.boundaries_on_ring =
            verify_read_back(&tables, lr, &f, corner_at, vertex_at, flag, 28)?;
    }
    Ok((tables, slots.triangles + n0 as u64))
}

/// [V35] pair by pair, so that the first fault is named: the reader runs it when the fast
/// pass (`scan_pairs`) has found one.
fn check_pairs(
    t: &CompactTables<LeWords, LeUnits>,
    m: u32,
    word_err: &impl Fn(usize, usize, Rule, String) -> crate::Error,
    unit_err: &impl Fn(usize, usize, Rule, String) -> crate::Error,
) -> Result<()> {
    let mut next_record = 0usize;
    for v in 0..t.m_r {
        let p = t.pairs.at(v as usize);
        let block = (v >> BLOCK_SHIFT) as usize;
        if v % (1 << BLOCK_SHIFT) == 0 && t.blocks.at(2 * block) as usize != next_record {
            return Err(word_err(
                4,
                2 * block,
                Rule(35),
                format!(
                    "block {block} starts its records at {}, not {next_record}",
                    t.blocks.at(2 * block)
                ),
            ));
        }
        if p >> 30 == EXTENDED {
            let start = t.record_start(v, p);
            if start != next_record {
                return Err(word_err(
                    3,
                    v as usize,
                    Rule(35),
                    format!("record of pair {v} at {start}, expected {next_record}"),
                ));
            }
            let record = t
                .decode_extended(v, p)
                .filter(|x| start + x.len <= t.records.count())
                .ok_or_else(|| {
                    unit_err(
                        10,
                        start.min(t.records.count()),
                        Rule(35),
                        format!("record of pair {v} runs past the record units"),
                    )
                })?;
            if !record.flags_agree {
                return Err(word_err(
                    3,
                    v as usize,
                    Rule(35),
                    format!("pair {v}: IRREGULAR flag and stored opposites disagree"),
                ));
            }
            next_record += record.len;
        }
        for side in [0, 1] {
            let tip = t.tip(v, side);
            // A plain pair's tip is NULL only by field 0 (with tip bases, a far field may
            // add up to NULL's value).
            let field = (p >> (15 * side)) & 0x7FFF;
            let null_field = p >> 30 == EXTENDED || field == plain::NULL_FIELD;
            let ok = tip < m || (tip == NULL && side == 1 && !t.wart(v, side) && null_field);
            if !ok {
                let base = match t.base(v, side) {
                    Some(base) if p >> 30 != EXTENDED && field & plain::FAR != 0 => {
                        format!(", from block {}'s base {base}", v >> BLOCK_SHIFT)
                    }
                    _ => String::new(),
                };
                return Err(word_err(
                    3,
                    v as usize,
                    Rule(35),
                    format!(
                        "slot {} has tip {tip:#x} ({m} vertices){base}",
                        2 * v as usize + side
                    ),
                ));
            }
            if tip == NULL && t.irregular(v, side) {
                return Err(word_err(
                    3,
                    v as usize,
                    Rule(35),
                    format!("missing right triangle of pair {v} stores opposites"),
                ));
            }
        }
    }
    if next_record != t.records.count() {
        return Err(unit_err(
            10,
            next_record,
            Rule(35),
            format!(
                "{} record units not used by any pair",
                t.records.count() - next_record
            ),
        ));
    }
    Ok(())
}
