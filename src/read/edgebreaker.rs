//! The `EBRK` section (connectivity kind 2): an Edgebreaker stream, decoded once by the
//! crate's hardened decoder with the reader's limits (rule V27), then held as a corner
//! table so that it answers the same operators as the other kinds.

use super::fields::Fields;
use super::{Limits, Sections};
use crate::corner_table::CornerTable;
use crate::error::{Error, Location, Result, Rule};
use crate::format::Tag;

/// The `EBRK` section decoded into a corner table over the container's vertices.
pub(super) fn edgebreaker_table(
    sections: &Sections,
    m: u32,
    limits: &Limits,
) -> Result<CornerTable> {
    let f = Fields::new(sections.required(Tag::EBRK)?);
    let rule = Rule(27);
    let eb_limits = crate::edgebreaker::Limits {
        max_triangles: limits.max_edgebreaker_triangles,
        max_vertices: limits.max_edgebreaker_vertices,
    };
    let (decoded, opposites) =
        crate::edgebreaker::decode_glued(f.bytes(), &eb_limits).map_err(|e| match e {
            Error::Parse(p) => {
                let at = match p.location {
                    Location::Byte(b) => b as usize,
                    _ => 0,
                };
                f.err(at, rule, p.message)
            }
            other => other,
        })?;
    // The vertex count is the first LEB128 field, after the magic and version bytes.
    f.expect_vertices(2, decoded.vertex_count, m, rule)?;
    // A stream can decode to triangles the encoder never writes; the container takes only
    // what it could have written: vertices in range, no repeated vertex in a triangle, and a
    // pseudo-manifold (one fan per vertex).
    let bad =
        |t: &[u32; 3]| t.iter().any(|&v| v >= m) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if let Some(t) = decoded.triangles.iter().position(bad) {
        return Err(f.err(
            0,
            rule,
            format!(
                "decoded triangle {t} {:?} is degenerate or out of range",
                decoded.triangles[t]
            ),
        ));
    }
    let table = CornerTable::from_glued(m, decoded.triangles, opposites)?;
    if table.conversion().vertex_copies != 0 {
        return Err(f.err(
            0,
            rule,
            "the decoded triangles are not a pseudo-manifold: a vertex has several fans",
        ));
    }
    Ok(table)
}
