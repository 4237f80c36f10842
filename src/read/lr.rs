//! The `LRTB` section (connectivity kind 1): the standard LR tables, validated once by rules
//! V15–V23 and V38 of `spec/FORMAT.md` and read in place as [`LrTables`] over the buffer's
//! little-endian words.

use super::fields::Fields;
use super::lr_rules::{
    check_open_fans, check_rings, check_vertex_corners, ring_slot_flags, verified_boundaries,
    SlotMap, CANONICAL,
};
use super::Sections;
use crate::corner_table::NONE;
use crate::error::{Result, Rule};
use crate::format::layout::{LrtbHeader, LR_BOUNDARIES_ON_RING, LR_OPEN_FANS};
use crate::format::Tag;
use crate::ids::Corner;
use crate::lr::one_ring_next_next;
use crate::lr::{LrTables, OpenFans, IRREGULAR, NULL, VALUE, WART};
use crate::words::{LeWords, Words};

/// The `LRTB` section as tables and the number of canonical triangles they hold, after
/// checking the rules that keep every operator's answer in range; with `verify`, every rule
/// (FORMAT.md §3.5, §5.1).
pub(super) fn lr_tables<'a>(
    sections: &Sections<'a>,
    m: u32,
    verify: bool,
) -> Result<(LrTables<LeWords<'a>>, u64)> {
    let f = Fields::new(sections.required(Tag::LRTB)?);
    // [V15] counts and length.
    f.expect_at_least(LrtbHeader::LEN, Rule(15))?;
    let h = LrtbHeader::read(f.bytes());
    let (m_r, rings, records) = (h.m_r, h.rings, h.records);
    f.expect_vertices(0, h.m, m, Rule(15))?;
    if h.flags & !(LR_BOUNDARIES_ON_RING | LR_OPEN_FANS) != 0 {
        return Err(f.err(20, Rule(15), "unknown flag bits are set"));
    }
    if h.reserved != 0 {
        return Err(f.err(28, Rule(15), "reserved field is not zero"));
    }
    if m >= NULL {
        return Err(f.err(
            0,
            Rule(15),
            format!("{m} vertices exceed the LR limit of {}", NULL - 1),
        ));
    }
    if m_r > m || (m_r == 0) != (rings == 0) || rings as u64 > m_r as u64 / 4 {
        return Err(f.err(4, Rule(15), format!("{m_r} ring vertices in {rings} rings for {m} vertices (rings have at least 4 vertices)")));
    }
    if 8 * m_r as u64 + 4 * h.t0 as u64 >= NONE as u64 {
        return Err(f.err(12, Rule(15), "corner ids exceed 32 bits"));
    }
    if records >= NULL {
        return Err(f.err(
            16,
            Rule(15),
            format!("{records} records exceed the LR limit"),
        ));
    }
    // [V61] the fan count, before the length it decides.
    let listed = h.flags & LR_OPEN_FANS != 0;
    if !listed && h.open_fans != 0 {
        return Err(f.err(24, Rule(61), "open fans counted without the flag OPEN_FANS"));
    }
    if h.open_fans > m_r {
        return Err(f.err(
            24,
            Rule(61),
            format!("{} open fans listed for {m_r} ring vertices", h.open_fans),
        ));
    }
    let layout = h.layout();
    f.expect_len(layout.as_ref().map(|l| l.len), Rule(15))?;
    let layout = layout.expect("checked by expect_len");
    let arrays: [_; 11] = std::array::from_fn(|i| layout.arrays[i]);
    let [ring_starts, ring_last, ring_rank, lr, vo_v, vo_o, vo_star, c, fan_bits, fan_rank, fans] =
        arrays.map(|a| LeWords(&f.bytes()[a.start..a.end()]));
    let word_err = |array: usize, i: usize, rule: Rule, message: String| {
        f.err(arrays[array].at(i), rule, message)
    };
    // Where a corner's triangle is stored: its LR entry, or its VO row.
    let corner_at = |c: Corner| {
        if c.0 >= 8 * m_r {
            arrays[4].at((c.0 - c.0 / 4 - 6 * m_r) as usize)
        } else {
            arrays[3].at(2 * (c.0 as usize >> 3) + ((c.0 as usize >> 2) & 1))
        }
    };

    // [V16] rings: starts increasing by at least 4 from 0 to m_r; bits and ranks as derived.
    check_rings(
        &ring_starts,
        Some((&ring_last, &ring_rank)),
        m_r,
        |array, i, message| word_err(array, i, Rule(16), message),
    )?;

    let mut tables = LrTables {
        lr,
        vo_v,
        vo_o,
        vo_star,
        c,
        ring_starts,
        ring_last,
        ring_rank,
        m_r,
        m,
        boundaries_on_ring: false,
        open_fans: None,
    };

    // [V17] entries: values in range, NULL only as a right tip, the records they use with
    // tips in range. A branch-light pass first; the slot at fault is looked for only when it
    // fails. That each record is used once is a semantic clause, checked when verifying.
    // With one ring, the same pass also flags the slots for [V19] and [V20].
    let (entries_ok, one_ring_flags) = scan_entries(lr, vo_star, m, records, m_r, rings == 1);
    let slots_to_search = if entries_ok { 0 } else { 2 * m_r as usize };
    for slot in 0..slots_to_search {
        let e = lr.at(slot);
        let value = e & VALUE;
        let bad = |message: String| {
            Err(word_err(
                3,
                slot,
                Rule(17),
                format!("entry {e:#x} of slot {slot}: {message}"),
            ))
        };
        if e & IRREGULAR != 0 {
            if value >= records {
                return bad(format!("record {value} missing ({records} records)"));
            }
            let tip = vo_star.at(3 * value as usize);
            if tip >= m {
                return Err(word_err(
                    6,
                    3 * value as usize,
                    Rule(17),
                    format!("record {value} has tip {tip} out of range ({m} vertices)"),
                ));
            }
        } else if value >= m && !(value == NULL && slot % 2 == 1 && e & WART == 0) {
            return bad(format!("vertex {value} out of range ({m} vertices)"));
        }
    }
    // [V18]
    if let Some(i) = (0..vo_v.count()).find(|&i| vo_v.at(i) >= m) {
        return Err(word_err(
            4,
            i,
            Rule(18),
            format!("vertex {} out of range ({m} vertices)", vo_v.at(i)),
        ));
    }
    // [V20] stored corners are canonical corners or NONE.
    let slots = match one_ring_flags {
        Some((flags, canonical)) => SlotMap::with_counted_flags(flags, canonical, m_r, h.t0),
        None => SlotMap::new(&tables),
    };
    let corner_ok = |x: u32| x == NONE || slots.is_corner(x);
    for (array, words) in [(5, vo_o), (6, vo_star), (7, c)] {
        for i in 0..words.count() {
            // VO* records start with a tip vertex, checked above.
            let is_tip = array == 6 && i % 3 == 0;
            if !is_tip && !corner_ok(words.at(i)) {
                return Err(word_err(
                    array,
                    i,
                    Rule(20),
                    format!("{} is not a corner of the mesh", words.at(i)),
                ));
            }
        }
    }

    // [V61] the list of open fans: the bits, their ranks and count, corners of the mesh.
    if listed {
        let list = OpenFans {
            bits: fan_bits,
            rank: fan_rank,
            corners: fans,
        };
        check_open_fans(&list, &slots, m_r, |array, i, message| {
            word_err(8 + array, i, Rule(61), message)
        })?;
        tables.open_fans = Some(list);
    }

    // [V19], then the verifying reader's rules: [V21], [V22], [V53]; [V23] and [V38] with
    // the fan rule the file allows.
    slots.check_jumps(&tables, &f, corner_at)?;
    let flag = h.flags & LR_BOUNDARIES_ON_RING != 0;
    tables.boundaries_on_ring = flag;
    if verify {
        check_records_used_once(lr, records, |array, i, message| {
            word_err(array, i, Rule(17), message)
        })?;
        tables.boundaries_on_ring = verified_boundaries(&tables, &f, corner_at, flag, 20)?;
        check_vertex_corners(&tables, Rule(23), |v, rule, message| {
            let at = if v < m_r {
                arrays[3].at(2 * v as usize)
            } else {
                arrays[7].at((v - m_r) as usize)
            };
            f.err(at, rule, message)
        })?;
    }
    Ok((tables, slots.triangles + h.t0 as u64))
}

/// [V17]'s clauses that keep every answer in range, in one pass without early exits or
/// branches: every plain entry's value below `m` or a right `NULL` without WART, every
/// IRREGULAR entry's value below `ni`, every record's tip below `m` (the slow search looks
/// only at the records that entries use). With `one_ring`, the same pass gives the slot
/// flags of [`SlotMap`] and the number of canonical triangles: on one ring `v.n.n` is
/// `v + 2` but at the ring's end. Bitwise rather than short-circuit logic, since the flags
/// follow no pattern a branch predictor could learn; no stores but the flags', so that it
/// vectorizes.
fn scan_entries(
    lr: LeWords,
    vo_star: LeWords,
    m: u32,
    records: u32,
    m_r: u32,
    one_ring: bool,
) -> (bool, Option<(Vec<u8>, u64)>) {
    let mut bad = 0u32;
    let mut check = |slot: usize, e: u32| {
        let value = e & VALUE;
        let is_irregular = e >> 31;
        let wart = e >> 30 & 1;
        let plain = (value < m) as u32 | ((value == NULL) as u32 & slot as u32 & (1 ^ wart));
        let ok = (is_irregular & (value < records) as u32) | ((1 ^ is_irregular) & plain);
        bad |= 1 ^ ok;
        (value, is_irregular, wart)
    };
    let words =
        lr.0.chunks_exact(4)
            .map(|w| u32::from_le_bytes(w.try_into().expect("four bytes")));
    let flags = if one_ring {
        let mut flags = vec![0u8; lr.count()];
        let mut canonical = 0u32;
        for ((slot, e), flag) in words.enumerate().zip(&mut flags) {
            let (value, is_irregular, wart) = check(slot, e);
            let v = (slot / 2) as u32;
            let nn = one_ring_next_next(v, m_r);
            *flag = ring_slot_flags(value, wart, is_irregular, nn);
            canonical += (*flag & CANONICAL) as u32;
        }
        Some((flags, canonical as u64))
    } else {
        for (slot, e) in words.enumerate() {
            check(slot, e);
        }
        None
    };
    let tips = (0..records as usize).all(|i| vo_star.at(3 * i) < m);
    (bad == 0 && tips, flags)
}

/// [V17]'s semantic clause: each of the `records` records is used by exactly one IRREGULAR
/// entry (whose values are below `records`, as the well-formed check found). A fault is
/// reported through `fault(array, word, message)`: at the second entry that uses a record
/// (`LR`), or at the tip word of the first record no entry uses (`VO*`).
fn check_records_used_once(
    lr: LeWords,
    records: u32,
    fault: impl Fn(usize, usize, String) -> crate::Error,
) -> Result<()> {
    let mut used = vec![false; records as usize];
    for slot in 0..lr.count() {
        let e = lr.at(slot);
        if e & IRREGULAR != 0 {
            let value = e & VALUE;
            let entry = format!("entry {e:#x} of slot {slot}: record {value}");
            let seen = used
                .get_mut(value as usize)
                .ok_or_else(|| fault(3, slot, format!("{entry} missing")))?;
            if *seen {
                return Err(fault(3, slot, format!("{entry} used twice")));
            }
            *seen = true;
        }
    }
    match used.iter().position(|&u| !u) {
        Some(i) => Err(fault(
            6,
            3 * i,
            format!("record {i} is not used by any entry"),
        )),
        None => Ok(()),
    }
}
