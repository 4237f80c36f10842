//! The `PART` section (rules V43, V48, V51): the parts' labels, and the part of every triangle
//! slot, read in place (packed) or decoded when the container is opened (runs).

use super::attributes::Context;
use super::fields::Fields;
use super::Sections;
use crate::error::{Result, Rule};
use crate::format::labels;
use crate::format::parts::{decode_runs, part_of, PartsHeader, HEADER_LEN, PACKED, RUNS};
use crate::format::Tag;
use crate::mesh::Parts;
use crate::ops::CornerOps;
use crate::words::LeWords;

/// The parts of a container: labels parsed once, indices borrowed from the file.
#[derive(Debug, Clone, PartialEq)]
pub struct PartsView<'a> {
    /// The labels and material libraries (`of_triangle` is left empty: see
    /// [`PartsView::part_of_slot`]).
    pub labels: Parts,
    indices: Indices<'a>,
}

/// The parts of the slots: packed in the file (index encoding 0), or decoded (1).
#[derive(Debug, Clone, PartialEq)]
enum Indices<'a> {
    Packed { bits: u32, words: LeWords<'a> },
    Decoded(Vec<u32>),
}

impl PartsView<'_> {
    /// The part index of triangle slot `t` (0 for a slot without a triangle).
    pub fn part_of_slot(&self, t: u32) -> u32 {
        match &self.indices {
            Indices::Packed { bits, words } => part_of(words, *bits, t),
            Indices::Decoded(parts) => parts[t as usize],
        }
    }
}

/// The `PART` section, if present, checked.
pub(super) fn parts<'a>(
    sections: &Sections<'a>,
    cx: &Context<'_, 'a>,
) -> Result<Option<PartsView<'a>>> {
    let Some(section) = sections.section(Tag::PART) else {
        return Ok(None);
    };
    let f = Fields::new(*section);
    let rule = Rule(43);
    f.expect_at_least(HEADER_LEN, rule)?;
    let h = PartsHeader::parse(f.bytes());
    let bound = cx.connectivity.triangle_id_bound();
    let slots = u64::from(bound) + u64::from(cx.kept);
    if u64::from(h.slots) != slots {
        return Err(f.err(
            4,
            rule,
            format!("{} triangle slots, the container has {slots}", h.slots),
        ));
    }
    if h.bits != PartsHeader::bits_for_parts(h.parts) {
        return Err(f.err(
            8,
            rule,
            format!(
                "{} bits per index for {} parts, which need {}",
                h.bits,
                h.parts,
                PartsHeader::bits_for_parts(h.parts)
            ),
        ));
    }
    if h.encoding > RUNS {
        return Err(f.err(
            9,
            Rule(48),
            format!("unknown index encoding {}", h.encoding),
        ));
    }
    if h.labels > labels::CODED {
        return Err(f.err(
            10,
            Rule(51),
            format!("unknown labels encoding {}", h.labels),
        ));
    }
    if h.reserved != 0 {
        return Err(f.err(11, Rule(48), "reserved field is not zero"));
    }
    let json_end = HEADER_LEN + h.json_len as usize;
    let runs_len = if h.encoding == PACKED {
        f.expect_len(h.len().map(|l| l as u64), rule)?;
        0
    } else {
        let n = f.u32(json_end, Rule(48))?;
        f.expect_len(Some(json_end as u64 + 4 + u64::from(n)), Rule(48))?;
        n as usize
    };
    let text = &f.bytes()[HEADER_LEN..json_end];
    let labels: Parts = if h.labels == labels::CODED {
        let base = f.section.offset as usize + HEADER_LEN;
        labels::decode(text, base, h.parts).map_err(|(at, m)| {
            let at = (at as usize).saturating_sub(f.section.offset as usize);
            f.err(at.min(f.len()), Rule(51), m)
        })?
    } else {
        let labels: Parts = serde_json::from_slice(text).map_err(|e| {
            f.err(
                HEADER_LEN,
                rule,
                format!("the labels are not a JSON object of parts: {e}"),
            )
        })?;
        if labels.parts.len() as u64 != u64::from(h.parts) {
            return Err(f.err(
                0,
                rule,
                format!("{} parts, the JSON lists {}", h.parts, labels.parts.len()),
            ));
        }
        labels
    };
    let indices = if h.encoding == PACKED {
        Indices::Packed {
            bits: h.bits,
            words: LeWords(&f.bytes()[json_end..]),
        }
    } else {
        let start = json_end + 4;
        let stream = &f.bytes()[start..start + runs_len];
        let base = f.section.offset as usize + start;
        let parts = decode_runs(stream, base, h.slots, h.parts).map_err(|(at, m)| {
            let at = (at as usize).saturating_sub(f.section.offset as usize);
            f.err(at.min(f.len()), Rule(48), m)
        })?;
        Indices::Decoded(parts)
    };
    let view = PartsView { labels, indices };
    for t in 0..h.slots {
        let p = view.part_of_slot(t);
        let triangle = cx.holds_triangle(u64::from(t));
        if (triangle && p >= h.parts) || (!triangle && p != 0) {
            let at = match h.encoding {
                PACKED => json_end + (u64::from(t) * u64::from(h.bits) / 32) as usize * 4,
                _ => json_end + 4,
            };
            return Err(f.err(
                at,
                rule,
                format!(
                    "slot {t} has part {p}: {}",
                    if triangle {
                        format!("there are {} parts", h.parts)
                    } else {
                        "it holds no triangle, so 0".into()
                    }
                ),
            ));
        }
    }
    let used = u64::from(h.slots) * u64::from(h.bits) % 32;
    if let (Indices::Packed { words, .. }, true) = (&view.indices, used != 0) {
        let last = crate::format::le_u32(words.0, words.0.len() - 4);
        if last >> used != 0 {
            return Err(f.err(f.len() - 4, rule, "bits past the last index are not 0"));
        }
    }
    Ok(Some(view))
}
