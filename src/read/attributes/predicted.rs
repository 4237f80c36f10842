//! Value encoding 2 of an `ATTR` record (FORMAT.md §3.9.2, GEOMETRY.md §7): where its
//! stream lies, and its decoding, when the container is opened, into the packed integers of
//! encoding 1 (rule V47).

use super::rules::Context;
use super::Packed;
use crate::error::{Result, Rule};
use crate::format::attributes::{
    pack, AttributeHeader, Seams, NEIGHBOUR_NORMALS, RECORD_HEADER_LEN, SURFACE_NORMALS,
};
use crate::format::quantized::Quantizer;
use crate::geometry::values::{self, Uses};
use crate::read::fields::Fields;

const RULE: Rule = Rule(47);

/// Bytes of the values part of record `i` at `at`, whose values part starts at `start`
/// (offsets in the record): the quantizer's header, the stream's length `n`, the stream.
pub(super) fn values_len(
    f: &Fields,
    at: usize,
    i: u32,
    start: usize,
    q: &Quantizer,
) -> Result<u64> {
    let n_at = at + start + q.header_len();
    if n_at + 4 > f.len() {
        return Err(f.err(
            at + start,
            RULE,
            format!("attribute {i}: no room for the predicted values' length"),
        ));
    }
    let n = f.u32(n_at, RULE)?;
    Ok(q.header_len() as u64 + 4 + u64::from(n))
}

/// The integers of record `i` (header `h`, values part at `values` of the section),
/// decoded and packed as encoding 1 stores them.
pub(super) fn decode(
    f: &Fields,
    (i, h, values): (u32, &AttributeHeader, std::ops::Range<usize>),
    q: &Quantizer,
    seams: Option<&Seams<Packed>>,
    cx: &Context,
) -> Result<Vec<u32>> {
    let err = |at: usize, message: String| f.err(at, RULE, format!("attribute {i}: {message}"));
    let values_at = values.start;
    let surface = match (h.normal_predictor(), q) {
        (SURFACE_NORMALS, _) => true,
        (NEIGHBOUR_NORMALS, Quantizer::Octahedral { .. }) => false,
        (other, _) => {
            let record = values_at - RECORD_HEADER_LEN - usize::from(h.name_len);
            return Err(err(
                record + 22,
                format!("normal predictor {other} for these values"),
            ));
        }
    };
    let Some((vertices, opposites)) = super::coded::slots(cx) else {
        return Err(err(
            values_at,
            "predicted values need the Edgebreaker connectivity".into(),
        ));
    };
    // Bounds the values by the corners: each extra one could be used once at most.
    if u64::from(h.extra) > 3 * u64::from(h.flagged) {
        return Err(err(
            values_at,
            format!(
                "{} extra values, more than the {} corners of the flagged triangles",
                h.extra,
                3 * u64::from(h.flagged)
            ),
        ));
    }
    let at_corners: Vec<[u32; 3]> = vertices
        .iter()
        .enumerate()
        .map(|(t, tri)| {
            [0, 1, 2].map(|k| match seams {
                Some(s) => s.value_index(t as u32, k, tri[k], cx.vertices),
                None => tri[k],
            })
        })
        .collect();
    let positions: Vec<[f32; 3]> = (0..cx.vertices as usize)
        .map(|v| cx.positions.get(v))
        .collect();
    let uses = Uses {
        vertices,
        values: &at_corners,
        opposites,
        positions: &positions,
        count: cx.vertices + h.extra,
    };
    let start = values_at + q.header_len() + 4;
    let stream = &f.bytes()[start..values.end];
    let base = f.section.offset as usize + start;
    let levels =
        values::decode(&uses, (q, surface), stream, base).map_err(|(offset, message)| {
            f.err(
                (offset as usize)
                    .saturating_sub(f.section.offset as usize)
                    .min(f.len()),
                RULE,
                format!("attribute {i}: {message}"),
            )
        })?;
    Ok(pack(&levels, u32::from(q.bits())))
}
