//! The `PART` section (rule V43): the parts' labels, and the part of every triangle slot
//! read in place.

use super::attributes::Context;
use super::fields::Fields;
use super::Sections;
use crate::error::{Result, Rule};
use crate::format::parts::{part_of, PartsHeader, HEADER_LEN};
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
    bits: u32,
    indices: LeWords<'a>,
}

impl PartsView<'_> {
    /// The part index of triangle slot `t` (0 for a slot without a triangle).
    pub fn part_of_slot(&self, t: u32) -> u32 {
        part_of(&self.indices, self.bits, t)
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
    f.expect_len(h.len().map(|l| l as u64), rule)?;
    let json_end = HEADER_LEN + h.json_len as usize;
    let labels: Parts = serde_json::from_slice(&f.bytes()[HEADER_LEN..json_end]).map_err(|e| {
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
    let view = PartsView {
        labels,
        bits: h.bits,
        indices: LeWords(&f.bytes()[json_end..]),
    };
    for t in 0..h.slots {
        let p = view.part_of_slot(t);
        let triangle = cx.holds_triangle(u64::from(t));
        if (triangle && p >= h.parts) || (!triangle && p != 0) {
            let at = json_end + (u64::from(t) * u64::from(h.bits) / 32) as usize * 4;
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
    if used != 0 && view.indices.0.len() >= 4 {
        let last = crate::format::le_u32(view.indices.0, view.indices.0.len() - 4);
        if last >> used != 0 {
            return Err(f.err(f.len() - 4, rule, "bits past the last index are not 0"));
        }
    }
    Ok(Some(view))
}
