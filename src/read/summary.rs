//! What a container holds, for reports (`lrmesh info FILE.lrm`).

use super::{Connectivity, Container, Positions, Sections};
use crate::format::{Metadata, PositionEncoding, Tag, HEADER_LEN};
use crate::lr::LrLayout;
use crate::mesh::Semantic;
use crate::ops::CornerOps;
use crate::words::Words;

/// One line of a container's section table, for reports.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct SectionSummary {
    /// The section's tag.
    pub tag: String,
    /// Whether readers must understand it.
    pub required: bool,
    /// Offset of its first byte.
    pub offset: u64,
    /// Its length in bytes.
    pub length: u64,
}

/// What a container holds (`lrmesh info FILE.lrm`). JSON keys are the field names.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ContainerSummary {
    /// `major.minor`.
    pub version: String,
    /// Total size in bytes.
    pub bytes: u64,
    /// The section table.
    pub sections: Vec<SectionSummary>,
    /// Connectivity kind: `lr`, `edgebreaker` or `strips`.
    pub connectivity: &'static str,
    /// Vertices once copies are merged back (the input's vertex count).
    pub vertices: u32,
    /// Vertices of the connectivity, pseudo-manifold copies included.
    pub connectivity_vertices: u32,
    /// Triangles, kept-aside degenerate ones included.
    pub triangles: u64,
    /// Degenerate triangles kept aside.
    pub kept_triangles: u32,
    /// Vertex copies made by the pseudo-manifold conversion.
    pub vertex_copies: u32,
    /// LR only: ring vertices.
    pub ring_vertices: Option<u32>,
    /// LR only: rings.
    pub rings: Option<u32>,
    /// LR only: T0 triangles in VO.
    pub t0_triangles: Option<u32>,
    /// LR only: VO* records (irregular triangles).
    pub irregular_triangles: Option<u32>,
    /// Bytes of connectivity: the connectivity section, COPY, KEPT and FLIP.
    pub connectivity_bytes: u64,
    /// Connectivity bits per triangle.
    pub connectivity_bpt: f64,
    /// References per triangle: of the LR tables (LR paper, section 8), or of the strips'
    /// `T`, `A` and `C`; none for Edgebreaker.
    pub rpt: Option<f64>,
    /// Positions stored quantized (lossy).
    pub quantized: bool,
    /// How positions are stored: their encoding, precision and size.
    pub positions: PositionsSummary,
    /// Attributes present: `normals`, `texcoords`, `colors` (set 0), `texcoords<n>`,
    /// `colors<n>`, or a custom attribute's name.
    pub attributes: Vec<String>,
    /// Each attribute in detail, in the same order.
    pub attribute_details: Vec<AttributeSummary>,
    /// Number of parts (objects, groups, materials), when the file has them.
    pub parts: Option<u32>,
    /// Whether the input's vertex and triangle order is stored.
    pub keeps_order: bool,
    /// Triangles the writer reversed to repair the orientation, which decoding reverses back
    /// (`FLIP`; 0 without it).
    pub reversed_triangles: u32,
    /// The metadata, if any.
    pub metadata: Option<Metadata>,
}

/// The positions, for reports.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PositionsSummary {
    /// `f32`, `grid16` (the 1.0 encoding), `predicted-grid`, `predicted-f32`,
    /// `anchored-grid` (encoding 6), `blocked-grid` or `blocked-f32`.
    pub encoding: &'static str,
    /// Bits per coordinate of a grid; none for exact f32.
    pub bits: Option<u8>,
    /// Bytes of the `GEOM` section.
    pub bytes: u64,
    /// Bits per container vertex.
    pub bits_per_vertex: f64,
}

/// One attribute, for reports.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct AttributeSummary {
    /// As in [`ContainerSummary::attributes`].
    pub name: String,
    /// `vertex` or `corner`.
    pub binding: &'static str,
    /// Component type and count, e.g. `f32x3`, `u8x4 normalized`.
    pub format: String,
    /// Values stored: one per container vertex, then the extra ones.
    pub values: u32,
    /// Values beyond one per vertex: one per extra value a seam needs.
    pub extra_values: u32,
    /// Triangles flagged for having a corner on an extra value.
    pub seam_triangles: u32,
    /// Bytes the attribute takes in the file.
    pub bytes: u64,
    /// Bits per container vertex.
    pub bits_per_vertex: f64,
}

/// The report name of `semantic`.
fn attribute_name(semantic: &Semantic) -> String {
    match semantic {
        Semantic::Normal => "normals".into(),
        Semantic::TexCoord(0) => "texcoords".into(),
        Semantic::Color(0) => "colors".into(),
        Semantic::TexCoord(n) => format!("texcoords{n}"),
        Semantic::Color(n) => format!("colors{n}"),
        Semantic::Custom(name) => name.clone(),
    }
}

/// The sections of the connectivity (`connectivity_bytes`): its tables, copies, kept
/// triangles and the triangles reversed on decoding (their orientation is connectivity too).
const CONNECTIVITY: [Tag; 10] = [
    Tag::LRTB,
    Tag::EBRK,
    Tag::STRP,
    Tag::LRBE,
    Tag::ZIPR,
    Tag::COPY,
    Tag::COPC,
    Tag::KEPT,
    Tag::KEPC,
    Tag::FLIP,
];

/// Bytes of the connectivity's sections.
pub(super) fn connectivity_bytes(sections: &Sections) -> u64 {
    CONNECTIVITY
        .iter()
        .filter_map(|&tag| sections.section(tag))
        .map(|s| s.bytes.len() as u64)
        .sum()
}

/// The container version, `major.minor`.
pub(super) fn version(sections: &Sections) -> String {
    format!("{}.{}", sections.major, sections.minor)
}

/// The file's length, from its last section's end.
pub(super) fn file_bytes(sections: &Sections) -> u64 {
    sections
        .sections
        .last()
        .map_or(HEADER_LEN as u64, |s| s.offset + s.bytes.len() as u64)
}

/// The section table, for reports.
pub(super) fn section_summaries(sections: &Sections) -> Vec<SectionSummary> {
    sections
        .sections
        .iter()
        .map(|s| SectionSummary {
            tag: s.tag.name(),
            required: s.flags.is_required(),
            offset: s.offset,
            length: s.bytes.len() as u64,
        })
        .collect()
}

/// `x` per triangle, 0 without triangles.
pub(super) fn per_triangle(x: f64, triangles: u64) -> f64 {
    if triangles == 0 {
        0.0
    } else {
        x / triangles as f64
    }
}

/// References of the LR tables of `m` vertices (`rpt`): two per ring vertex, six per T0
/// triangle, three per irregular-triangle record, one per vertex off the rings.
pub(super) fn lr_references(m: u32, m_r: u32, t0: u32, records: u32) -> u64 {
    2 * m_r as u64 + 6 * t0 as u64 + 3 * records as u64 + (m - m_r) as u64
}

/// References of strips with `len` entries of `T` (and of `A`) over `m` vertices (`rpt`):
/// `T`, `A` and `C`, one reference an entry.
pub(super) fn strips_references(len: u32, m: u32) -> u64 {
    2 * len as u64 + m as u64
}

/// The name reports give position encoding `e` (`positions.encoding`), `None` when unknown.
pub(super) fn encoding_name(e: PositionEncoding) -> Option<&'static str> {
    Some(match e {
        PositionEncoding::F32 => "f32",
        PositionEncoding::QUANTIZED16 => "grid16",
        PositionEncoding::PREDICTED_GRID => "predicted-grid",
        PositionEncoding::ANCHORED_GRID => "anchored-grid",
        PositionEncoding::PREDICTED_F32 => "predicted-f32",
        PositionEncoding::BLOCKED => "blocked-grid",
        PositionEncoding::BLOCKED_F32 => "blocked-f32",
        _ => return None,
    })
}

impl Container<'_> {
    fn positions_summary(&self) -> PositionsSummary {
        let stored = self.stored_positions();
        let section = self.sections.section(Tag::GEOM);
        let encoding = section
            .and_then(|s| s.bytes.get(..4))
            .map(|b| PositionEncoding(u32::from_le_bytes(b.try_into().expect("four bytes"))))
            .and_then(encoding_name)
            .unwrap_or("f32");
        let bytes = section.map_or(0, |s| s.bytes.len() as u64);
        PositionsSummary {
            encoding,
            bits: match stored {
                Positions::Quantized16 { .. } => Some(16),
                other => other.grid().map(|g| g.bits),
            },
            bytes,
            bits_per_vertex: 8.0 * bytes as f64 / (self.vertices.max(1)) as f64,
        }
    }

    /// A summary of the container for reports.
    pub fn summary(&self) -> ContainerSummary {
        let connectivity_bytes = connectivity_bytes(&self.sections);
        let triangles = self.triangles as u64 + (self.kept.count() / 3) as u64;
        let per_triangle = |x: f64| per_triangle(x, triangles);
        let lr = self.lr();
        let compact = self.lr_compact();
        let zipper = self.zipper();
        let rpt = match &self.connectivity {
            Connectivity::Lr(lr) => {
                let refs =
                    lr_references(lr.m, lr.ring_vertices(), lr.t0_count(), lr.record_count());
                Some(per_triangle(refs as f64))
            }
            Connectivity::Strips(strips) => Some(per_triangle(strips_references(
                strips.len() as u32,
                strips.vertex_id_bound(),
            ) as f64)),
            Connectivity::Edgebreaker(_) | Connectivity::LrCompact(_) | Connectivity::Zipper(_) => {
                None
            }
        };
        let attribute_details: Vec<AttributeSummary> = self
            .attributes()
            .iter()
            .map(|a| AttributeSummary {
                name: attribute_name(&a.semantic),
                binding: if a.per_corner { "corner" } else { "vertex" },
                format: format!(
                    "{}x{}{}{}{}{}",
                    format!("{:?}", a.component_type).to_lowercase(),
                    a.components,
                    if a.normalized { " normalized" } else { "" },
                    match a.quantizer() {
                        Some(crate::format::quantized::Quantizer::Octahedral { bits }) => {
                            format!(" octahedral {bits}-bit")
                        }
                        Some(q) => format!(" quantized {}-bit", q.bits()),
                        None => String::new(),
                    },
                    match (a.value_encoding(), a.normal_predictor()) {
                        (crate::format::quantized::PREDICTED, 0) => " predicted",
                        (crate::format::quantized::PREDICTED, _) => " predicted-from-neighbours",
                        _ => "",
                    },
                    if a.seam_encoding() == crate::format::attributes::CODED_SEAMS {
                        " coded-seams"
                    } else {
                        ""
                    }
                ),
                values: a.value_count(),
                extra_values: a.extra_values(),
                seam_triangles: a.flagged_triangles(),
                bytes: a.stored_bytes(),
                bits_per_vertex: 8.0 * a.stored_bytes() as f64 / self.vertices.max(1) as f64,
            })
            .collect();
        let attributes = attribute_details.iter().map(|a| a.name.clone()).collect();
        ContainerSummary {
            version: version(&self.sections),
            bytes: file_bytes(&self.sections),
            sections: section_summaries(&self.sections),
            connectivity: self.connectivity.name(),
            vertices: self.output_vertices,
            connectivity_vertices: self.vertices,
            triangles,
            kept_triangles: (self.kept.count() / 3) as u32,
            vertex_copies: (self.copies.count() / 2) as u32,
            ring_vertices: lr
                .map(|lr| lr.ring_vertices())
                .or(compact.map(|lr| lr.ring_vertices()))
                .or(zipper.map(|z| z.ring_vertices())),
            rings: lr
                .map(|lr| lr.ring_count() as u32)
                .or(compact.map(|lr| lr.ring_count() as u32))
                .or(zipper.map(|z| z.ring_count() as u32)),
            t0_triangles: lr
                .map(|lr| lr.t0_count())
                .or(compact.map(|lr| lr.t0_count()))
                .or(zipper.map(|z| z.t0_count())),
            irregular_triangles: lr
                .map(|lr| lr.record_count())
                .or(zipper.map(|z| z.record_count() as u32)),
            connectivity_bytes,
            connectivity_bpt: per_triangle(8.0 * connectivity_bytes as f64),
            rpt,
            quantized: self.is_quantized(),
            positions: self.positions_summary(),
            attributes,
            attribute_details,
            parts: self.parts().map(|p| p.labels.parts.len() as u32),
            keeps_order: self.perm.is_some(),
            reversed_triangles: self.flips.as_ref().map_or(0, |f| f.len() as u32),
            metadata: self.metadata.clone(),
        }
    }
}

impl std::fmt::Display for ContainerSummary {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(
            f,
            "lrmesh container, version {}, {} bytes",
            self.version, self.bytes
        )?;
        writeln!(f, "sections:")?;
        for s in &self.sections {
            let required = if s.required { "required" } else { "optional" };
            writeln!(
                f,
                "  {:<4}  {required}  offset {:>10}  length {:>10}",
                s.tag, s.offset, s.length
            )?;
        }
        writeln!(f, "connectivity             {}", self.connectivity)?;
        writeln!(
            f,
            "vertices                 {} ({} in the connectivity, {} copies)",
            self.vertices, self.connectivity_vertices, self.vertex_copies
        )?;
        writeln!(
            f,
            "triangles                {} ({} kept aside)",
            self.triangles, self.kept_triangles
        )?;
        if let (Some(rings), Some(ring_vertices)) = (self.rings, self.ring_vertices) {
            writeln!(
                f,
                "rings                    {rings} through {ring_vertices} vertices"
            )?;
        }
        if let (Some(t0), Some(irregular)) = (self.t0_triangles, self.irregular_triangles) {
            writeln!(f, "T0 / irregular           {t0} / {irregular}")?;
        }
        write!(
            f,
            "connectivity             {} bytes, {:.2} bits/triangle",
            self.connectivity_bytes, self.connectivity_bpt
        )?;
        match self.rpt {
            Some(rpt) => writeln!(f, ", {rpt:.3} references/triangle")?,
            None => writeln!(f)?,
        }
        let p = &self.positions;
        writeln!(
            f,
            "positions                {}{}, {} bytes, {:.2} bits/vertex",
            p.encoding,
            p.bits.map_or(" (exact)".to_string(), |b| format!(
                ", {b}-bit grid (lossy)"
            )),
            p.bytes,
            p.bits_per_vertex
        )?;
        if self.attribute_details.is_empty() {
            writeln!(f, "attributes               none")?;
        }
        for a in &self.attribute_details {
            write!(
                f,
                "attribute                {} per {}, {}, {} values, {} bytes, {:.2} bits/vertex",
                a.name, a.binding, a.format, a.values, a.bytes, a.bits_per_vertex
            )?;
            if a.binding == "corner" {
                write!(
                    f,
                    " ({} for seams, {} triangles flagged)",
                    a.extra_values, a.seam_triangles
                )?;
            }
            writeln!(f)?;
        }
        if let Some(parts) = self.parts {
            writeln!(f, "parts                    {parts}")?;
        }
        writeln!(f, "input order kept         {}", self.keeps_order)?;
        if self.reversed_triangles > 0 {
            writeln!(f, "reversed on decoding     {}", self.reversed_triangles)?;
        }
        if let Some(m) = &self.metadata {
            writeln!(f, "generator                {}", m.generator)?;
            if let Some(source) = &m.source {
                writeln!(f, "source                   {source}")?;
            }
            for (k, v) in &m.extra {
                writeln!(f, "  {k}: {v}")?;
            }
        }
        Ok(())
    }
}
