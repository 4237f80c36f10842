//! Construction of the bit-efficient LR from a standard LR: [`CompactLr::build`] picks the
//! HYBRID-RING-EXPANDER period whose rings promise the smallest encoding ([`choose_period`])
//! and builds the LR once with it; the encoder lays out the pair words, records, blocks and
//! T0 rows (ordered by [`t0_order`]), then checks that the result answers every corner
//! operator exactly as the standard LR does.

use super::tables::CompactTables;
use super::{
    plain, CompactLr, CompactOptions, BLOCK_SHIFT, BY_LEFT_RULE, BY_RIGHT_RULE, ESCAPE, EXTENDED,
    FIELD13, GROUP_SHIFT, HEAD_TIP_SHIFT, IN_ADJACENT_ROW, NO_OPPOSITE, OVERFLOW_FLAG,
    OVERFLOW_ROW_WORDS, PLAIN, RECORD_SHIFT, RIGHT_LONG, SHORT_MAX, T0_ROW_UNITS, TAG_T0,
    WART_LEFT, WART_RIGHT, X_IRREGULAR, X_WART,
};
use crate::corner_table::{CornerTable, NONE};
use crate::error::{Error, Result};
use crate::ids::Corner;
use crate::lr::ring::Prepared;
use crate::lr::tables::{LrLayout, LrTables, LEFT, NULL, RIGHT};
use crate::lr::{Lr, LrOptions};
use crate::ops::CornerOps;
use crate::words::{Units, Words};

impl CompactLr {
    /// Builds the bit-efficient LR with the period of `options` whose rings promise the
    /// smallest encoding (`choose_period`).
    ///
    /// # Errors
    /// [`Error::Unsupported`] when the mesh exceeds the LR's id space.
    pub fn build(ct: &CornerTable, options: &CompactOptions) -> Result<CompactLr> {
        let prepared = Prepared::new(ct)?;
        let period = choose_period(&prepared, &options.periods, &options.lr);
        let rings = prepared.rings(period, &options.lr);
        let lr = Lr::for_encoding_from_rings(ct, prepared, rings, &options.lr)?;
        CompactLr::encode(lr, period, options.tip_bases)
    }

    /// Encodes a standard LR built with period `period`, with tip bases as `tip_bases` says
    /// ([`CompactOptions::tip_bases`]).
    fn encode(lr: Lr, period: u32, tip_bases: Option<bool>) -> Result<CompactLr> {
        let t = lr.tables();
        let m_r = t.m_r;
        let blocks = (m_r as usize).div_ceil(1 << BLOCK_SHIFT);

        // T0 rows: rotated to start at their anchor, sorted by it.
        let n0 = t.t0_count() as usize;
        let mut rotation = vec![0usize; n0];
        let mut anchors = Vec::with_capacity(n0);
        for (j, r) in rotation.iter_mut().enumerate() {
            let vs = [0, 1, 2].map(|i| t.vo_v[3 * j + i]);
            *r = (0..3)
                .filter(|&i| vs[i] < m_r)
                .min_by_key(|&i| vs[i])
                .unwrap_or(0);
            anchors.push((vs[*r], j as u32));
        }
        anchors.sort_unstable();
        let anchor_of: Vec<u32> = {
            let mut a = vec![0; n0];
            for &(anchor, j) in &anchors {
                a[j as usize] = anchor;
            }
            a
        };
        let t0_standard = t0_order(t, &anchors);
        let mut t0_compact = vec![0u32; n0];
        for (jc, &j) in t0_standard.iter().enumerate() {
            t0_compact[j as usize] = jc as u32;
        }
        let base = 8 * m_r;
        let map_corner = |c: u32| {
            if c == NONE || c < base {
                return c;
            }
            let (j, i) = (((c - base) / 4) as usize, ((c - base) % 4) as usize);
            base + 4 * t0_compact[j] + ((i + 3 - rotation[j]) % 3) as u32
        };

        // Blocks: the first row anchored in each (the reference of T0 corner fields in its
        // records; their first record comes with the pairs).
        let mut block_words = vec![0u32; 2 * blocks];
        let mut first_row = vec![u32::MAX; blocks + 1];
        first_row[blocks] = n0 as u32;
        for (jc, &j) in t0_standard.iter().enumerate() {
            let block = (anchor_of[j as usize] >> BLOCK_SHIFT).min(blocks as u32) as usize;
            first_row[block] = first_row[block].min(jc as u32);
        }
        for b in (0..blocks).rev() {
            first_row[b] = first_row[b].min(first_row[b + 1]);
            block_words[2 * b + 1] = first_row[b];
        }

        // Tip bases (see `plain`): per block and side, the base of the tips too far for a
        // near field; kept when the pairs they make plain save more bytes than they take.
        let bases: Vec<i32> = (0..blocks)
            .flat_map(|b| {
                let vs = (b << BLOCK_SHIFT) as u32..m_r.min(((b + 1) << BLOCK_SHIFT) as u32);
                [LEFT, RIGHT].map(|side| {
                    plain::choose_base(vs.clone().filter_map(|v| {
                        let tip = t.tip(v, side);
                        (tip != NULL).then(|| tip as i64 - v as i64)
                    }))
                })
            })
            .collect();
        let plain_word = |v: u32, tip_bases: bool| -> Option<u32> {
            let warts = [LEFT, RIGHT].map(|side| t.wart(v, side));
            let config = match warts {
                [false, false] => PLAIN,
                [true, false] => WART_LEFT,
                [false, true] => WART_RIGHT,
                _ => return None,
            };
            let field = |side: usize| {
                let base = tip_bases.then(|| bases[2 * (v >> BLOCK_SHIFT) as usize + side]);
                plain::field(t.tip(v, side), v, side == RIGHT, base)
            };
            Some(config << 30 | field(RIGHT)? << 15 | field(LEFT)?)
        };
        let irregular = |v: u32| t.irregular(v, LEFT) || t.irregular(v, RIGHT);
        let made_plain = || {
            (0..m_r)
                .filter(|&v| !irregular(v))
                .map(|v| {
                    plain_word(v, true).is_some() as i64 - plain_word(v, false).is_some() as i64
                })
                .sum::<i64>()
        };
        // A record for a long tip takes 6 bytes at least; the bases 8 bytes a block.
        let tip_bases = tip_bases.unwrap_or_else(|| 6 * made_plain() > 8 * blocks as i64);

        // Pairs and records.
        let mut pairs = Vec::with_capacity(m_r as usize);
        let mut records: Vec<u16> = Vec::new();
        for v in 0..m_r {
            let block = (v >> BLOCK_SHIFT) as usize;
            if v % (1 << BLOCK_SHIFT) == 0 {
                block_words[2 * block] = records.len() as u32;
            }
            let tips = [LEFT, RIGHT].map(|side| t.tip(v, side));
            let warts = [LEFT, RIGHT].map(|side| t.wart(v, side));
            let stored = stored_corners(t, v);
            if stored == [None; 4] {
                if let Some(word) = plain_word(v, tip_bases) {
                    pairs.push(word);
                    continue;
                }
            }
            let relative = records.len() as u32 - block_words[2 * block];
            let left = match tips[LEFT] as i64 - v as i64 {
                d if d != 0 && d.abs() <= (FIELD13 >> 1) as i64 => Some(d as u32 & FIELD13),
                _ => None,
            };
            let mut word = EXTENDED << 30 | relative << RECORD_SHIFT | left.unwrap_or(0);
            for side in [LEFT, RIGHT] {
                if warts[side] {
                    word |= X_WART[side];
                }
                if stored[2 * side].is_some() || stored[2 * side + 1].is_some() {
                    word |= X_IRREGULAR[side];
                }
            }
            pairs.push(word);
            let right = match tips[RIGHT] {
                NULL => Some(0),
                tip => {
                    let d = tip as i64 - v as i64;
                    (d != 0 && d.abs() < RIGHT_LONG as i64).then_some(d as u16 & 0xFFF)
                }
            };
            let mut head = 0u16;
            for (q, o) in stored.iter().enumerate() {
                head |= (o.is_some() as u16) << q;
            }
            head |= right.unwrap_or(RIGHT_LONG) << HEAD_TIP_SHIFT;
            records.push(head);
            if left.is_none() {
                records.extend([tips[LEFT] as u16, (tips[LEFT] >> 16) as u16]);
            }
            if right.is_none() {
                records.extend([tips[RIGHT] as u16, (tips[RIGHT] >> 16) as u16]);
            }
            let t0_reference = block_words[2 * block + 1];
            for o in stored.into_iter().flatten() {
                let o = map_corner(o);
                match short_corner(o, v, t0_reference, m_r) {
                    Some(unit) => records.push(unit),
                    None => records.extend([ESCAPE, o as u16, (o >> 16) as u16]),
                }
            }
            if relative > FIELD13 {
                return Err(Error::Unsupported("LR record block overflow".into()));
            }
        }
        let several = t.ring_count() > 1;
        let mut tables = CompactTables {
            ring_starts: t.ring_starts.clone(),
            ring_last: if several {
                t.ring_last.clone()
            } else {
                Vec::new()
            },
            ring_rank: if several {
                t.ring_rank.clone()
            } else {
                Vec::new()
            },
            pairs,
            blocks: block_words,
            bases: match tip_bases {
                true => bases.iter().map(|&b| b as u32).collect(),
                false => Vec::new(),
            },
            groups: Vec::new(),
            c: t.c.iter().map(|&x| map_corner(x)).collect(),
            overflow: Vec::new(),
            t0: Vec::new(),
            records,
            m_r,
            m: t.m,
            boundaries_on_ring: t.boundaries_on_ring,
            tip_bases,
        };

        // T0 rows, whose opposites are found with the ring slots and the rows before them.
        let triangle = |jc: usize| {
            let (j, r) = (t0_standard[jc] as usize, rotation[t0_standard[jc] as usize]);
            [0, 1, 2].map(|i| t.vo_v[3 * j + (i + r) % 3])
        };
        tables.groups = t0_standard
            .chunks(1 << GROUP_SHIFT)
            .map(|group| {
                group
                    .iter()
                    .map(|&j| anchor_of[j as usize])
                    .min()
                    .unwrap_or(0)
            })
            .collect();
        for jc in 0..n0 {
            let (j, r) = (t0_standard[jc] as usize, rotation[t0_standard[jc] as usize]);
            let vs = triangle(jc);
            let os = [0, 1, 2].map(|i| map_corner(t.vo_o[3 * j + (i + r) % 3]));
            let group_base = tables.groups[jc >> GROUP_SHIFT];
            let next = (jc + 1 < n0).then(|| triangle(jc + 1));
            let row = vs[0]
                .checked_sub(group_base)
                .and_then(|offset| t0_row(&tables, vs, os, offset, jc as u32, next));
            match row {
                Some(row) => tables.t0.extend(row),
                None => {
                    let index = (tables.overflow.len() / OVERFLOW_ROW_WORDS) as u32;
                    tables
                        .t0
                        .extend([0, index as u16, (index >> 16) as u16, OVERFLOW_FLAG]);
                    tables.overflow.extend(vs.into_iter().chain(os));
                }
            }
        }

        // The encoding must answer exactly as the standard LR does (corner ids mapped).
        for tri in t.triangles() {
            for c in t.triangle_corners(tri) {
                let ours = Corner(map_corner(c.0));
                if tables.vertex(ours) != t.vertex(c)
                    || tables.opposite_raw(ours.0) != map_corner(t.opposite_raw(c.0))
                {
                    return Err(Error::Internal(format!(
                        "bit-efficient LR disagrees with the standard LR at corner {}",
                        c.0
                    )));
                }
            }
        }
        Ok(CompactLr {
            tables,
            lr: lr.into_input_maps(),
            period,
            t0_standard,
        })
    }
}

/// The order of the T0 rows (standard T0 indices): by anchor, except that T0 triangles next
/// to each other follow each other, as paths, so that a row finds its T0 neighbours in the
/// rows before and after it.
fn t0_order(t: &LrTables<Vec<u32>>, anchors: &[(u32, u32)]) -> Vec<u32> {
    let n0 = anchors.len();
    let base = 8 * t.m_r;
    let mut rank = vec![0u32; n0];
    for (k, &(_, j)) in anchors.iter().enumerate() {
        rank[j as usize] = k as u32;
    }
    let neighbours = |j: usize| {
        let mut out = [u32::MAX; 3];
        for (i, slot) in out.iter_mut().enumerate() {
            let o = t.vo_o[3 * j + i];
            if o != NONE && o >= base {
                *slot = (o - base) / 4;
            }
        }
        // Lowest anchor first.
        out.sort_unstable_by_key(|&u| {
            if u == u32::MAX {
                u32::MAX
            } else {
                rank[u as usize]
            }
        });
        out
    };
    let mut placed = vec![false; n0];
    let mut probed = vec![false; n0];
    let mut order = Vec::with_capacity(n0);
    for &(_, start) in anchors {
        if placed[start as usize] {
            continue;
        }
        // Walk to the end of a path through unplaced neighbours, then place from there back.
        let mut end = start;
        let mut probe = vec![start];
        probed[start as usize] = true;
        while let Some(&u) = neighbours(end as usize)
            .iter()
            .find(|&&u| u != u32::MAX && !placed[u as usize] && !probed[u as usize])
        {
            probed[u as usize] = true;
            probe.push(u);
            end = u;
        }
        for u in probe {
            probed[u as usize] = false;
        }
        let mut j = end;
        loop {
            placed[j as usize] = true;
            order.push(j);
            match neighbours(j as usize)
                .iter()
                .find(|&&u| u != u32::MAX && !placed[u as usize])
            {
                Some(&u) => j = u,
                None => break,
            }
        }
    }
    order
}

/// The opposites slot pair `v` must store, in the order left 0, left 2, right 4, right 6:
/// those of irregular slots that the ring rules do not infer. A slot whose tip looks like a
/// redundant T2's keeps both, which marks it canonical.
fn stored_corners(t: &LrTables<Vec<u32>>, v: u32) -> [Option<u32>; 4] {
    let mut out = [None; 4];
    for side in [LEFT, RIGHT] {
        let [a, b] = [0, 1].map(|second| t.stored_opposite(v, side, second));
        let (Some(a), Some(b)) = (a, b) else {
            continue;
        };
        let i = 4 * side as u32;
        let fails = [
            t.inferred_opposite(v, i) != a,
            t.inferred_opposite(v, i + 2) != b,
        ];
        let looks_redundant = !t.wart(v, side) && t.tip(v, side) == t.ring_next_next(v);
        let keep = if looks_redundant || fails == [false, false] {
            [true, true]
        } else {
            fails
        };
        out[2 * side] = keep[0].then_some(a);
        out[2 * side + 1] = keep[1].then_some(b);
    }
    out
}

/// The T0 row `row` of a triangle with vertices `vs` and opposites `os` (anchor first),
/// or `None` when it must overflow. `tables` has its ring slots and the rows before `row`;
/// `next` is the triangle of the next row, if any.
fn t0_row<W: Words, U: Units>(
    tables: &CompactTables<W, U>,
    vs: [u32; 3],
    os: [u32; 3],
    anchor_offset: u32,
    row: u32,
    next: Option<[u32; 3]>,
) -> Option<[u16; T0_ROW_UNITS]> {
    let anchor_offset = u16::try_from(anchor_offset).ok()?;
    let [d1, d2] = [vs[1], vs[2]].map(|x| x as i64 - vs[0] as i64);
    if [d1, d2]
        .iter()
        .any(|d| !(-SHORT_MAX..=SHORT_MAX).contains(d))
    {
        return None;
    }
    let t0_base = 8 * tables.m_r;
    let mut codes = 0u16;
    for i in 0..3 {
        let (x, y) = (vs[(i + 1) % 3], vs[(i + 2) % 3]);
        // The decoder searches the previous row, then the next one.
        let adjacent = || {
            let previous = tables.find_in_adjacent_row(row as usize, x, y);
            if previous != NONE {
                return Some(previous);
            }
            let next = next?;
            (0..3)
                .find(|&k| next[(k + 1) % 3] == y && next[(k + 2) % 3] == x)
                .map(|k| t0_base + 4 * (row + 1) + k as u32)
        };
        let code = if os[i] == NONE {
            NO_OPPOSITE
        } else if tables.find_left(x, y) == os[i] {
            BY_LEFT_RULE
        } else if tables.find_right(x, y) == os[i] {
            BY_RIGHT_RULE
        } else if adjacent() == Some(os[i]) {
            IN_ADJACENT_ROW
        } else {
            return None;
        };
        codes |= code << (2 * i);
    }
    Some([anchor_offset, d1 as u16 & 0x7FFF, d2 as u16 & 0x7FFF, codes])
}

/// A short corner field, if it fits: `NONE`, a ring corner relative to `8·ring_reference`,
/// or a T0 corner relative to the first corner of T0 row `t0_reference`.
fn short_corner(c: u32, ring_reference: u32, t0_reference: u32, m_r: u32) -> Option<u16> {
    let base = 8 * m_r as i64;
    let (d, tag) = match c {
        NONE => return Some(TAG_T0 | ESCAPE),
        c if (c as i64) < base => (c as i64 - 8 * ring_reference as i64, 0),
        c => (c as i64 - base - 4 * t0_reference as i64, TAG_T0),
    };
    (-SHORT_MAX..=SHORT_MAX)
        .contains(&d)
        .then_some(tag | (d as u16 & 0x7FFF))
}

/// Triangles below which the period estimate takes the rings the build makes
/// ([`choose_period`]).
const SMALL_MESH: usize = 1 << 14;

/// The period of `periods` (0 when there is none) whose rings have the smallest
/// [`compact_estimate`](Prepared::compact_estimate): one ring expansion per period instead of
/// a whole LR built and encoded per period, whose sizes it ranks closely enough (README,
/// bit-efficient LR). On a mesh of fewer than [`SMALL_MESH`] triangles the estimate takes
/// the rings the build makes (all its tries and the leaf moves): one T0 triangle weighs much
/// on a small mesh, and the work is small.
fn choose_period(prepared: &Prepared, periods: &[u32], lr: &LrOptions) -> u32 {
    let mut best = (u64::MAX, periods.first().copied().unwrap_or(0));
    if periods.len() < 2 {
        return best.1;
    }
    let exact = prepared.triangle_count() < SMALL_MESH;
    for &period in periods {
        let estimate = prepared.compact_estimate(period, lr, exact, best.0);
        if estimate < best.0 {
            best = (estimate, period);
        }
    }
    best.1
}
