//! [`summarize`]: what `lrmesh info` reports of a container, read from its header, its section
//! table, its small sections and the headers of its connectivity and positions sections, not
//! their data. On a file of hundreds of millions of triangles it reads a few pages where
//! [`open`](super::open) reads every byte (checksums, every id in range).

use super::fields::Fields;
use super::summary::{self, ContainerSummary, PositionsSummary};
use super::{counts, positions, Limits, Sections};
use crate::error::{Result, Rule};
use crate::format::layout::{LrbeHeader, LrtbHeader, StrpHeader};
use crate::format::{Kind, PositionEncoding, Tag};

/// The sections read by their headers alone: neither their checksums nor their data.
const DATA: [Tag; 6] = [
    Tag::LRTB,
    Tag::LRBE,
    Tag::ZIPR,
    Tag::STRP,
    Tag::EBRK,
    Tag::GEOM,
];

/// Sections whose figures need their data (attributes, parts, reversed triangles): a file
/// with one is opened whole.
const WHOLE: [Tag; 6] = [
    Tag::ATTR,
    Tag::PART,
    Tag::FLIP,
    Tag::NORM,
    Tag::TEXC,
    Tag::COLR,
];

/// The summary of the container `bytes`, equal to [`open`](super::open)`(bytes)?.summary()`
/// on a well-formed file, read without the data of its connectivity and positions: their
/// headers and lengths are checked, their checksums and contents are not (a fault there is
/// `lrmesh verify`'s to find). Every other section is read and checked as `open` reads it; a
/// file with attributes, parts or reversed triangles is opened whole.
///
/// # Errors
/// As [`open`](super::open), for the parts read.
pub fn summarize(bytes: &[u8], limits: &Limits) -> Result<ContainerSummary> {
    let sections = Sections::parse_checking(bytes, limits, |tag| !DATA.contains(&tag))?;
    if WHOLE.iter().any(|&tag| sections.section(tag).is_some()) {
        return Ok(super::open(bytes, limits)?.summary());
    }
    let metadata = counts::metadata(&sections, limits)?;
    let (mesh, _) = counts::mesh_record(&sections)?;
    let m = mesh.vertices;
    let triangles = mesh.triangles as u64 + mesh.kept as u64;
    let per_triangle = |x: f64| summary::per_triangle(x, triangles);
    let connectivity_bytes = summary::connectivity_bytes(&sections);
    let rings = rings(&sections, mesh.kind, m)?;
    let rpt = match (mesh.kind, rings) {
        (Kind::LR, Some(r)) => {
            let refs = summary::lr_references(m, r.m_r, r.t0, r.records.unwrap_or(0));
            Some(per_triangle(refs as f64))
        }
        (Kind::STRIPS, _) => {
            let f = header_fields(&sections, Tag::STRP, StrpHeader::LEN, Rule(28))?;
            let h = StrpHeader::read(f.bytes());
            f.expect_vertices(0, h.m, m, Rule(28))?;
            f.expect_len(h.layout().map(|l| l.len), Rule(28))?;
            Some(per_triangle(summary::strips_references(h.len, h.m) as f64))
        }
        _ => None,
    };
    let positions = positions_summary(&sections, m)?;
    Ok(ContainerSummary {
        version: summary::version(&sections),
        bytes: summary::file_bytes(&sections),
        sections: summary::section_summaries(&sections),
        connectivity: mesh.kind.name(),
        vertices: mesh.output_vertices,
        connectivity_vertices: m,
        triangles,
        kept_triangles: mesh.kept,
        vertex_copies: m - mesh.output_vertices,
        ring_vertices: rings.map(|r| r.m_r),
        rings: rings.map(|r| r.rings),
        t0_triangles: rings.map(|r| r.t0),
        irregular_triangles: rings.and_then(|r| r.records),
        connectivity_bytes,
        connectivity_bpt: per_triangle(8.0 * connectivity_bytes as f64),
        rpt,
        quantized: positions.bits.is_some(),
        positions,
        attributes: Vec::new(),
        attribute_details: Vec::new(),
        parts: None,
        keeps_order: sections.section(Tag::PERM).is_some(),
        reversed_triangles: 0,
        metadata,
    })
}

/// The ring figures of an LR header.
#[derive(Clone, Copy)]
struct Rings {
    m_r: u32,
    rings: u32,
    t0: u32,
    /// Irregular-triangle records: the standard LR's (the bit-efficient one has none).
    records: Option<u32>,
}

/// The section `tag` with at least `header` bytes.
fn header_fields<'a>(
    sections: &Sections<'a>,
    tag: Tag,
    header: usize,
    rule: Rule,
) -> Result<Fields<'a>> {
    let f = Fields::new(sections.required(tag)?);
    f.expect_at_least(header, rule)?;
    Ok(f)
}

/// The ring figures of an LR kind's header, its vertex count and its section's length
/// checked as the reader checks them ([V15], [V33]).
fn rings(sections: &Sections, kind: Kind, m: u32) -> Result<Option<Rings>> {
    Ok(match kind {
        Kind::LR => {
            let f = header_fields(sections, Tag::LRTB, LrtbHeader::LEN, Rule(15))?;
            let h = LrtbHeader::read(f.bytes());
            f.expect_vertices(0, h.m, m, Rule(15))?;
            f.expect_len(h.layout().map(|l| l.len), Rule(15))?;
            Some(Rings {
                m_r: h.m_r,
                rings: h.rings,
                t0: h.t0,
                records: Some(h.records),
            })
        }
        Kind::LR_COMPACT => {
            let f = header_fields(sections, Tag::LRBE, LrbeHeader::LEN, Rule(33))?;
            let h = LrbeHeader::read(f.bytes());
            f.expect_vertices(0, h.m, m, Rule(33))?;
            f.expect_len(h.layout().map(|l| l.len), Rule(33))?;
            Some(Rings {
                m_r: h.m_r,
                rings: h.rings,
                t0: h.t0,
                records: None,
            })
        }
        Kind::ZIPPER => {
            let f = Fields::new(sections.required(Tag::ZIPR)?);
            let h = super::zipper::zipr_header(&f, m)?;
            f.expect_len(h.layout().map(|l| l.len), Rule(56))?;
            Some(Rings {
                m_r: h.m_r,
                rings: h.rings,
                t0: h.t0,
                records: Some(h.records),
            })
        }
        _ => None,
    })
}

/// The positions figures from the `GEOM` header: its encoding and grid.
fn positions_summary(sections: &Sections, m: u32) -> Result<PositionsSummary> {
    let rule = Rule(13);
    let f = Fields::new(sections.required(Tag::GEOM)?);
    let encoding = PositionEncoding(f.u32(0, rule)?);
    let Some(name) = summary::encoding_name(encoding) else {
        return Err(f.err(0, rule, format!("unknown position encoding {}", encoding.0)));
    };
    let bits = match encoding {
        PositionEncoding::QUANTIZED16 => Some(16),
        PositionEncoding::PREDICTED_GRID
        | PositionEncoding::ANCHORED_GRID
        | PositionEncoding::BLOCKED => Some(positions::grid(&f, rule)?.bits),
        _ => None,
    };
    let bytes = f.len() as u64;
    Ok(PositionsSummary {
        encoding: name,
        bits,
        bytes,
        bits_per_vertex: 8.0 * bytes as f64 / m.max(1) as f64,
    })
}
