//! Seam encoding 1 of an `ATTR` record (FORMAT.md §3.9, GEOMETRY.md §8): where its stream
//! lies, and its decoding, when the container is opened, into the seam tables that
//! encoding 0 stores (rule V49), so that every corner's value is then found as in the file.

use super::rules::Context;
use super::Packed;
use crate::error::{Result, Rule};
use crate::format::attributes::{tables_of, AttributeHeader, Seams};
use crate::geometry::{seams, values};
use crate::read::fields::Fields;
use crate::read::view::Connectivity;
use crate::words::Words;

const RULE: Rule = Rule(49);

/// Bytes of the coded seams of record `i` that start at `part` (section offset): `n`, then
/// the `n` bytes of the stream.
pub(super) fn seams_len(f: &Fields, part: usize, i: u32) -> Result<u64> {
    if part + 4 > f.len() {
        return Err(f.err(
            part.min(f.len()),
            RULE,
            format!("attribute {i}: no room for the coded seams' length"),
        ));
    }
    Ok(4 + u64::from(f.u32(part, RULE)?))
}

/// The vertices and opposite corners of every slot of an Edgebreaker container (GEOMETRY.md
/// §7.1), made once for all its records; `None` for another connectivity.
pub(super) fn slots<'c>(cx: &'c Context) -> Option<&'c values::SlotCorners> {
    let Connectivity::Edgebreaker(table) = cx.connectivity else {
        return None;
    };
    Some(cx.slots.get_or_init(|| {
        let kept: Vec<[u32; 3]> = (0..cx.kept as usize)
            .map(|j| [0, 1, 2].map(|k| cx.kept_triangles.at(3 * j + k)))
            .collect();
        values::slots(table, &kept)
    }))
}

/// The seam tables of record `i` (header `h`) from its coded seams at `part` of the section
/// (`n` and the stream).
pub(super) fn decode<'a>(
    f: &Fields,
    (i, h, part): (u32, &AttributeHeader, std::ops::Range<usize>),
    cx: &Context,
) -> Result<Seams<Packed<'a>>> {
    let err = |at: usize, message: String| f.err(at, RULE, format!("attribute {i}: {message}"));
    let Some((vertices, opposites)) = slots(cx) else {
        return Err(err(
            part.start,
            "coded seams need the Edgebreaker connectivity".into(),
        ));
    };
    if h.flagged == 0 {
        return Err(err(
            part.start,
            "coded seams with no flagged triangle".into(),
        ));
    }
    let s = seams::Slots {
        vertices,
        opposites,
        vertex_count: cx.vertices,
    };
    let start = part.start + 4;
    let stream = &f.bytes()[start..part.end];
    let base = f.section.offset as usize;
    let at_corners = seams::decode(&s, h.extra, stream, base + start)
        .map_err(|(offset, m)| err((offset as usize).saturating_sub(base).min(f.len()), m))?;
    let v = cx.vertices;
    let flagged: Vec<(u32, [u32; 3])> = at_corners
        .iter()
        .enumerate()
        .filter(|(_, tri)| tri.iter().any(|&x| x >= v))
        .map(|(t, tri)| (t as u32, tri.map(|x| if x < v { 0 } else { x - v + 1 })))
        .collect();
    if flagged.len() != h.flagged as usize {
        return Err(err(
            part.start,
            format!(
                "{} flagged triangles, the coded seams give {}",
                h.flagged,
                flagged.len()
            ),
        ));
    }
    let bits = u32::from(h.entry_bits);
    let [flags, rank, entries] = tables_of(h.slots, &flagged, bits);
    Ok(Seams {
        flags: Packed::Decoded(flags),
        rank: Packed::Decoded(rank),
        entries: Packed::Decoded(entries),
        bits,
    })
}
