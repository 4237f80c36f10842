//! The `LRBE` section (connectivity kind 4): the bit-efficient LR, validated once by rules
//! V33–V37 of `spec/FORMAT.md` (then the LR rules every layout keeps) and read in place as
//! [`CompactTables`] over the buffer's little-endian words and units.

use super::{check_lr_layout, le_u32, Container, Fields};
use crate::corner_table::NONE;
use crate::error::Result;
use crate::format::{Tag, LRBE_HEADER_LEN};
use crate::ids::Corner;
use crate::lr::compact::{BLOCK_SHIFT, EXTENDED, GROUP_SHIFT, OVERFLOW_ROW_WORDS, T0_ROW_UNITS};
use crate::lr::{CompactTables, LeUnits, LeWords, LrLayout, Units, Words, NULL};

/// The `LRBE` section as tables, after checking every rule the operators rely on.
pub(super) fn lr_compact_tables<'a>(
    container: &Container<'a>,
    m: u32,
) -> Result<CompactTables<LeWords<'a>, LeUnits<'a>>> {
    let section = *container.required(Tag::LRBE)?;
    let f = Fields { section };
    let b = section.bytes;
    if b.len() < LRBE_HEADER_LEN {
        return Err(f.err(
            0,
            format!(
                "{} bytes, shorter than its {LRBE_HEADER_LEN}-byte header",
                b.len()
            ),
        ));
    }
    let [mm, m_r, rings, n0, record_units, overflow_rows, _period, reserved] =
        [0, 1, 2, 3, 4, 5, 6, 7].map(|i| le_u32(b, 4 * i));
    // [V33] counts and length.
    if mm != m {
        return Err(f.err(0, format!("{mm} vertices, section MESH says {m}")));
    }
    if reserved != 0 {
        return Err(f.err(28, "reserved field is not zero"));
    }
    if m >= NULL {
        return Err(f.err(
            0,
            format!("{m} vertices exceed the LR limit of {}", NULL - 1),
        ));
    }
    if m_r > m || (m_r == 0) != (rings == 0) || rings as u64 > m_r as u64 / 4 {
        return Err(f.err(
            4,
            format!("{m_r} ring vertices in {rings} rings for {m} vertices (rings have at least 4 vertices)"),
        ));
    }
    if 8 * m_r as u64 + 4 * n0 as u64 >= NONE as u64 {
        return Err(f.err(12, "corner ids exceed 32 bits"));
    }
    let bit_words = if rings > 1 {
        (m_r as u64).div_ceil(32)
    } else {
        0
    };
    let word_lengths = [
        rings as u64 + 1,
        bit_words,
        bit_words,
        m_r as u64,
        2 * (m_r as u64).div_ceil(1 << BLOCK_SHIFT),
        (n0 as u64).div_ceil(1 << GROUP_SHIFT),
        (m - m_r) as u64,
        OVERFLOW_ROW_WORDS as u64 * overflow_rows as u64,
    ];
    let unit_lengths = [T0_ROW_UNITS as u64 * n0 as u64, record_units as u64];
    f.expect_len(Some(
        LRBE_HEADER_LEN as u64
            + 4 * word_lengths.iter().sum::<u64>()
            + 2 * unit_lengths.iter().sum::<u64>(),
    ))?;
    let mut at = LRBE_HEADER_LEN;
    let mut starts = [0usize; 10];
    let words = std::array::from_fn::<_, 8, _>(|i| {
        starts[i] = at;
        let w = LeWords(&b[at..at + 4 * word_lengths[i] as usize]);
        at += 4 * word_lengths[i] as usize;
        w
    });
    let units = std::array::from_fn::<_, 2, _>(|i| {
        starts[8 + i] = at;
        let u = LeUnits(&b[at..at + 2 * unit_lengths[i] as usize]);
        at += 2 * unit_lengths[i] as usize;
        u
    });
    let [ring_starts, ring_last, ring_rank, pairs, blocks, groups, c, overflow] = words;
    let [t0, records] = units;
    let word_err = |array: usize, i: usize, message: String| f.err(starts[array] + 4 * i, message);
    let unit_err = |array: usize, i: usize, message: String| f.err(starts[array] + 2 * i, message);

    // [V34] rings, as for the standard LR; the bit vectors only with several rings.
    super::check_rings(
        &ring_starts,
        (rings > 1).then_some((&ring_last, &ring_rank)),
        m_r,
        word_err,
    )?;

    let tables = CompactTables {
        ring_starts,
        ring_last,
        ring_rank,
        pairs,
        blocks,
        groups,
        c,
        overflow,
        t0,
        records,
        m_r,
        m,
    };

    // [V35] pairs and records: records tile the record units in ring order, each block's
    // first record where the block says, every field inside its record; tips in range.
    let mut next_record = 0usize;
    for v in 0..m_r {
        let p = pairs.at(v as usize);
        let block = (v >> BLOCK_SHIFT) as usize;
        if v % (1 << BLOCK_SHIFT) == 0 && blocks.at(2 * block) as usize != next_record {
            return Err(word_err(
                4,
                2 * block,
                format!(
                    "block {block} starts its records at {}, not {next_record}",
                    blocks.at(2 * block)
                ),
            ));
        }
        if p >> 30 == EXTENDED {
            let start = tables.record_start(v, p);
            if start != next_record {
                return Err(word_err(
                    3,
                    v as usize,
                    format!("record of pair {v} at {start}, expected {next_record}"),
                ));
            }
            let len = tables
                .record_len(v)
                .filter(|&len| start + len <= records.count())
                .ok_or_else(|| {
                    unit_err(
                        9,
                        start.min(records.count()),
                        format!("record of pair {v} runs past the record units"),
                    )
                })?;
            if !tables.irregular_flags_agree(v) {
                return Err(word_err(
                    3,
                    v as usize,
                    format!("pair {v}: IRREGULAR flag and stored opposites disagree"),
                ));
            }
            next_record += len;
        }
        for side in [0, 1] {
            let tip = tables.tip(v, side);
            let ok = tip < m || (tip == NULL && side == 1 && !tables.wart(v, side));
            if !ok {
                return Err(word_err(
                    3,
                    v as usize,
                    format!(
                        "slot {} has tip {tip:#x} ({m} vertices)",
                        2 * v as usize + side
                    ),
                ));
            }
            if tip == NULL && tables.irregular(v, side) {
                return Err(word_err(
                    3,
                    v as usize,
                    format!("missing right triangle of pair {v} stores opposites"),
                ));
            }
        }
    }
    if next_record != records.count() {
        return Err(unit_err(
            9,
            next_record,
            format!(
                "{} record units not used by any pair",
                records.count() - next_record
            ),
        ));
    }

    // [V36] T0 rows: codes, overflow rows used once each and in order, vertices in range.
    let mut next_overflow = 0u32;
    for j in 0..n0 as usize {
        let at = T0_ROW_UNITS * j;
        let codes = t0.at(at + 3);
        if codes & 0x8000 != 0 {
            let index = t0.at(at + 1) as u32 | (t0.at(at + 2) as u32) << 16;
            if codes != 0x8000 || t0.at(at) != 0 || index != next_overflow {
                return Err(unit_err(
                    8,
                    at,
                    format!("T0 row {j}: malformed overflow row"),
                ));
            }
            next_overflow += 1;
        } else if codes & !0x3F != 0 {
            return Err(unit_err(
                8,
                at + 3,
                format!("T0 row {j}: reserved bits set"),
            ));
        } else if [1, 2].iter().any(|&i| t0.at(at + i) & 0x8000 != 0) {
            // A vertex field is 15 bits.
            return Err(unit_err(
                8,
                at,
                format!("T0 row {j}: vertex field out of range"),
            ));
        }
        for i in 0..3 {
            let x = tables.t0_vertex(3 * j as u32 + i);
            if x >= m {
                return Err(unit_err(
                    8,
                    at,
                    format!("T0 row {j}: vertex {x} out of range ({m} vertices)"),
                ));
            }
        }
    }
    if next_overflow != overflow_rows {
        return Err(word_err(
            7,
            0,
            format!(
                "{} overflow rows not used by any T0 row",
                overflow_rows - next_overflow
            ),
        ));
    }

    // [V37] the LR rules every layout keeps (V19, V21–V23), and C holds corners.
    for i in 0..(m - m_r) as usize {
        let x = tables.isolated_corner(i as u32);
        if x != NONE && !tables.is_corner(Corner(x)) {
            return Err(word_err(6, i, format!("{x} is not a corner of the mesh")));
        }
    }
    let corner_at = |c: Corner| {
        if c.0 >= 8 * m_r {
            starts[8] + 2 * T0_ROW_UNITS * ((c.0 - 8 * m_r) / 4) as usize
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
    check_lr_layout(&tables, &f, corner_at, vertex_at)?;
    Ok(tables)
}
