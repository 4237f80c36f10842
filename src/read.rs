//! Reading containers from a byte slice: parsing, one linear validation pass, and a view that
//! answers corner queries on the buffer itself (layout and rules: `spec/FORMAT.md`).
//!
//! [`open`] checks every index and invariant the operators rely on, so that afterwards no
//! operator of the view can panic, read out of bounds, return an id that is not the mesh's, or
//! loop forever. Nothing is allocated beyond a bound of the input's length: the view borrows
//! its tables, and the per-vertex marks that validation needs are bounded by counts already
//! checked against the bytes present.

use crate::corner_table::NONE;
use crate::error::{Error, FormatError, Result};
use crate::format::{self, geometry, kind, Tag, ENTRY_LEN, FLAG_REQUIRED, HEADER_LEN};
use crate::ids::{Corner, Vertex};
use crate::lr::{
    CompactTables, LeUnits, LeWords, LrLayout, LrTables, Words, IRREGULAR, NULL, VALUE, WART,
};
use crate::ops::CornerOps;
use crate::strips::CtsTables;
use crate::write::Metadata;
use crate::Mesh;

mod lr_compact;
mod strips;

/// Limits on what a reader accepts, beyond what the file's length bounds anyway.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most sections in one file.
    pub max_sections: u32,
    /// Largest `META` section, in bytes.
    pub max_metadata_bytes: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_sections: 64,
            max_metadata_bytes: 1 << 20,
        }
    }
}

/// One section of a container.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Section<'a> {
    /// Its tag.
    pub tag: Tag,
    /// Its flags ([`format::FLAG_REQUIRED`]).
    pub flags: u32,
    /// Offset of its first byte in the file.
    pub offset: u64,
    /// Its bytes.
    pub bytes: &'a [u8],
}

/// A container whose header and section table are valid, with every section's checksum
/// verified. The sections' contents are not yet checked (see [`open`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Container<'a> {
    /// Major version.
    pub major: u16,
    /// Minor version.
    pub minor: u16,
    /// The sections, in file order.
    pub sections: Vec<Section<'a>>,
}

fn error(section: &str, offset: u64, message: impl Into<String>) -> Error {
    Error::Format(Box::new(FormatError {
        file: None,
        section: section.to_string(),
        offset,
        message: message.into(),
    }))
}

fn le_u16(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

fn le_u32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

fn le_u64(b: &[u8], at: usize) -> u64 {
    (le_u32(b, at) as u64) | (le_u32(b, at + 4) as u64) << 32
}

/// Section checksums are skipped when fuzzing, so that the fuzzer reaches the section parsers.
fn checksum_matches(expected: u32, actual: u32) -> bool {
    cfg!(fuzzing) || expected == actual
}

impl<'a> Container<'a> {
    /// Parses the header and the section table and verifies the checksums.
    ///
    /// # Errors
    /// [`Error::Format`] naming the part and byte offset; [`Error::UnsupportedVersion`];
    /// [`Error::UnknownRequiredSection`]; [`Error::LimitExceeded`].
    pub fn parse(bytes: &'a [u8], limits: &Limits) -> Result<Container<'a>> {
        if bytes.len() < HEADER_LEN {
            return Err(error(
                "header",
                0,
                format!(
                    "{} bytes, shorter than the {HEADER_LEN}-byte header",
                    bytes.len()
                ),
            ));
        }
        if bytes[..8] != format::MAGIC {
            return Err(error("header", 0, "not an lrmesh container (bad magic)"));
        }
        let (major, minor) = (le_u16(bytes, 8), le_u16(bytes, 10));
        if major != format::MAJOR {
            return Err(Error::UnsupportedVersion {
                major,
                minor,
                supported: format::MAJOR,
            });
        }
        let count = le_u32(bytes, 12);
        if count > limits.max_sections {
            return Err(Error::LimitExceeded {
                what: "section count",
                value: count as u64,
                limit: limits.max_sections as u64,
            });
        }
        let file_length = le_u64(bytes, 16);
        if file_length != bytes.len() as u64 {
            return Err(error(
                "header",
                16,
                format!(
                    "file length field says {file_length}, the file has {}",
                    bytes.len()
                ),
            ));
        }
        if le_u32(bytes, 28) != 0 {
            return Err(error("header", 28, "reserved field is not zero"));
        }
        let table_end = HEADER_LEN + ENTRY_LEN * count as usize;
        if table_end > bytes.len() {
            return Err(error(
                "section table",
                HEADER_LEN as u64,
                format!(
                    "{count} entries need {table_end} bytes, the file has {}",
                    bytes.len()
                ),
            ));
        }
        let table_crc = crate::write::table_checksum(&bytes[..table_end]);
        if !checksum_matches(le_u32(bytes, 24), table_crc) {
            return Err(error(
                "header",
                24,
                "header and section table checksum mismatch",
            ));
        }
        let mut sections: Vec<Section<'a>> = Vec::with_capacity(count as usize);
        let mut expected_offset = table_end as u64;
        for i in 0..count as usize {
            let at = HEADER_LEN + ENTRY_LEN * i;
            let tag = Tag([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
            let flags = le_u32(bytes, at + 4);
            let offset = le_u64(bytes, at + 8);
            let length = le_u64(bytes, at + 16);
            let crc = le_u32(bytes, at + 24);
            let entry = |field: usize, message: String| {
                error("section table", (at + field) as u64, message)
            };
            if flags & !FLAG_REQUIRED != 0 {
                return Err(entry(
                    4,
                    format!("section {}: unknown flags {flags:#x}", tag.name()),
                ));
            }
            if le_u32(bytes, at + 28) != 0 {
                return Err(entry(
                    28,
                    format!("section {}: reserved field is not zero", tag.name()),
                ));
            }
            if offset != expected_offset {
                return Err(entry(
                    8,
                    format!("section {} starts at {offset}, expected {expected_offset} (sections are contiguous, in table order)", tag.name()),
                ));
            }
            let end = offset
                .checked_add(length)
                .filter(|&end| end <= bytes.len() as u64)
                .ok_or_else(|| {
                    entry(
                        16,
                        format!(
                            "section {} of {length} bytes runs past the end of the file",
                            tag.name()
                        ),
                    )
                })?;
            let body = &bytes[offset as usize..end as usize];
            if !checksum_matches(crc, crc32fast::hash(body)) {
                return Err(error(&tag.name(), offset, "checksum mismatch"));
            }
            if sections.iter().any(|s| s.tag == tag) {
                return Err(entry(0, format!("section {} appears twice", tag.name())));
            }
            if flags & FLAG_REQUIRED != 0 && !KNOWN.contains(&tag) {
                return Err(Error::UnknownRequiredSection {
                    tag: tag.name(),
                    index: i as u32,
                });
            }
            sections.push(Section {
                tag,
                flags,
                offset,
                bytes: body,
            });
            expected_offset = end;
        }
        if expected_offset != bytes.len() as u64 {
            return Err(error(
                "file",
                expected_offset,
                format!(
                    "{} bytes after the last section",
                    bytes.len() as u64 - expected_offset
                ),
            ));
        }
        Ok(Container {
            major,
            minor,
            sections,
        })
    }

    /// The section with `tag`, if present.
    pub fn section(&self, tag: Tag) -> Option<&Section<'a>> {
        self.sections.iter().find(|s| s.tag == tag)
    }

    fn required(&self, tag: Tag) -> Result<&Section<'a>> {
        self.section(tag)
            .ok_or_else(|| error(&tag.name(), 0, "required section is missing"))
    }
}

/// The sections this reader understands.
const KNOWN: [Tag; 13] = [
    Tag::META,
    Tag::MESH,
    Tag::GEOM,
    Tag::NORM,
    Tag::TEXC,
    Tag::COLR,
    Tag::LRTB,
    Tag::EBRK,
    Tag::STRP,
    Tag::LRBE,
    Tag::COPY,
    Tag::KEPT,
    Tag::PERM,
];

/// Positions as stored.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Positions<'a> {
    /// Three f32 per vertex.
    F32(&'a [u8]),
    /// A bounding box and three u16 per vertex (lossy).
    Quantized16 {
        /// Minimum corner of the box.
        lo: [f32; 3],
        /// Maximum corner of the box.
        hi: [f32; 3],
        /// The coordinates.
        data: &'a [u8],
    },
}

/// The connectivity of a validated container.
#[derive(Debug, Clone)]
pub enum ConnectivityView<'a> {
    /// Standard LR tables, answering the corner operators on the buffer.
    Lr(LrTables<LeWords<'a>>),
    /// Edgebreaker, decoded when the container was opened: triangles in decode order.
    Edgebreaker(Vec<[u32; 3]>),
    /// Constrained triangle strips and the adjacent-strips table, answering the corner
    /// operators on the buffer.
    Strips(CtsTables<LeWords<'a>>),
    /// Bit-efficient LR tables, answering the corner operators on the buffer.
    LrCompact(CompactTables<LeWords<'a>, LeUnits<'a>>),
}

impl ConnectivityView<'_> {
    /// The connectivity kind's name: `lr`, `edgebreaker` or `strips`.
    pub fn name(&self) -> &'static str {
        match self {
            ConnectivityView::Lr(_) => "lr",
            ConnectivityView::Edgebreaker(_) => "edgebreaker",
            ConnectivityView::Strips(_) => "strips",
            ConnectivityView::LrCompact(_) => "lr-compact",
        }
    }

    /// Number of triangles the connectivity holds.
    fn triangle_count(&self) -> u64 {
        match self {
            ConnectivityView::Lr(lr) => lr.triangles().count() as u64,
            ConnectivityView::Edgebreaker(triangles) => triangles.len() as u64,
            ConnectivityView::Strips(strips) => strips.triangle_count() as u64,
            ConnectivityView::LrCompact(lr) => lr.triangles().count() as u64,
        }
    }

    /// The triangles as container vertex ids, in the order of `spec/FORMAT.md` section 4.
    fn for_each_triangle(&self, mut f: impl FnMut([u32; 3])) {
        match self {
            ConnectivityView::Lr(lr) => lr
                .triangles()
                .for_each(|t| f(lr.triangle_vertices(t).map(|v| v.0))),
            ConnectivityView::Edgebreaker(decoded) => decoded.iter().for_each(|&t| f(t)),
            ConnectivityView::Strips(strips) => strips
                .triangles()
                .for_each(|t| f(strips.triangle_vertices(t).map(|v| v.0))),
            ConnectivityView::LrCompact(lr) => lr
                .triangles()
                .for_each(|t| f(lr.triangle_vertices(t).map(|v| v.0))),
        }
    }
}

/// A validated container: every table borrowed from the buffer, the LR tables answering the
/// corner operators in place.
#[derive(Debug, Clone)]
pub struct MeshView<'a> {
    /// The container's sections.
    pub container: Container<'a>,
    /// The metadata, if the file has a `META` section.
    pub metadata: Option<Metadata>,
    connectivity: ConnectivityView<'a>,
    /// Container vertices (copies included).
    vertices: u32,
    positions: Positions<'a>,
    normals: Option<&'a [u8]>,
    texcoords: Option<&'a [u8]>,
    colors: Option<&'a [u8]>,
    /// `(copy, original)` pairs.
    copies: LeWords<'a>,
    /// Kept-aside triangles, three vertices each.
    kept: LeWords<'a>,
    /// Vertex then triangle permutations to the input order.
    perm: Option<(LeWords<'a>, LeWords<'a>)>,
    output_vertices: u32,
    triangles: u32,
}

/// Parses and fully validates a container.
///
/// # Errors
/// As [`Container::parse`], and [`Error::Format`] naming the section and byte offset of the
/// first broken rule of `spec/FORMAT.md`.
pub fn open<'a>(bytes: &'a [u8], limits: &Limits) -> Result<MeshView<'a>> {
    let container = Container::parse(bytes, limits)?;
    MeshView::new(container, limits)
}

/// Reads section bytes as fields, with errors naming the section and file offset.
struct Fields<'a> {
    section: Section<'a>,
}

impl<'a> Fields<'a> {
    fn name(&self) -> String {
        self.section.tag.name()
    }
    fn err(&self, at: usize, message: impl Into<String>) -> Error {
        error(&self.name(), self.section.offset + at as u64, message)
    }
    fn u32(&self, at: usize) -> Result<u32> {
        if at + 4 > self.section.bytes.len() {
            return Err(self.err(at, format!("truncated: {} bytes", self.section.bytes.len())));
        }
        Ok(le_u32(self.section.bytes, at))
    }
    /// The exact length the section must have.
    fn expect_len(&self, len: Option<u64>) -> Result<()> {
        match len {
            Some(len) if len == self.section.bytes.len() as u64 => Ok(()),
            Some(len) => Err(self.err(
                0,
                format!(
                    "{} bytes where the counts call for {len}",
                    self.section.bytes.len()
                ),
            )),
            None => Err(self.err(0, "counts overflow")),
        }
    }
}

/// Checks that the f32s in bytes `range` of the section are finite.
fn check_finite(fields: &Fields, range: std::ops::Range<usize>) -> Result<()> {
    let b = fields.section.bytes;
    for at in range.step_by(4) {
        let x = f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
        if !x.is_finite() {
            return Err(fields.err(at, format!("non-finite value {x}")));
        }
    }
    Ok(())
}

impl<'a> MeshView<'a> {
    fn new(container: Container<'a>, limits: &Limits) -> Result<MeshView<'a>> {
        let metadata = match container.section(Tag::META) {
            None => None,
            Some(s) => {
                if s.bytes.len() as u64 > limits.max_metadata_bytes {
                    return Err(Error::LimitExceeded {
                        what: "metadata size",
                        value: s.bytes.len() as u64,
                        limit: limits.max_metadata_bytes,
                    });
                }
                Some(serde_json::from_slice::<Metadata>(s.bytes).map_err(|e| {
                    error("META", s.offset, format!("not a metadata JSON object: {e}"))
                })?)
            }
        };

        let mesh = Fields {
            section: *container.required(Tag::MESH)?,
        };
        mesh.expect_len(Some(format::MESH_LEN as u64))?;
        let m = mesh.u32(0)?;
        let output_vertices = mesh.u32(4)?;
        let triangles = mesh.u32(8)?;
        let kept_count = mesh.u32(12)?;
        let connectivity_kind = mesh.u32(16)?;
        if ![kind::LR, kind::EDGEBREAKER, kind::STRIPS, kind::LR_COMPACT]
            .contains(&connectivity_kind)
        {
            return Err(mesh.err(16, format!("unknown connectivity kind {connectivity_kind}")));
        }
        if mesh.u32(20)? != 0 {
            return Err(mesh.err(20, "reserved field is not zero"));
        }
        if output_vertices > m {
            return Err(mesh.err(4, format!("{output_vertices} output vertices of {m}")));
        }
        let m64 = m as u64;

        let geom = Fields {
            section: *container.required(Tag::GEOM)?,
        };
        let positions = match geom.u32(0)? {
            geometry::F32 => {
                geom.expect_len(m64.checked_mul(12).and_then(|x| x.checked_add(8)))?;
                check_finite(&geom, 8..geom.section.bytes.len())?;
                Positions::F32(&geom.section.bytes[8..])
            }
            geometry::QUANTIZED16 => {
                geom.expect_len(m64.checked_mul(6).and_then(|x| x.checked_add(32)))?;
                check_finite(&geom, 8..32)?;
                let b = geom.section.bytes;
                let f = |at: usize| f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]]);
                let lo = [f(8), f(12), f(16)];
                let hi = [f(20), f(24), f(28)];
                if (0..3).any(|i| lo[i] > hi[i]) {
                    return Err(geom.err(8, "bounding box minimum above its maximum"));
                }
                Positions::Quantized16 {
                    lo,
                    hi,
                    data: &b[32..],
                }
            }
            other => return Err(geom.err(0, format!("unknown position encoding {other}"))),
        };
        if geom.u32(4)? != 0 {
            return Err(geom.err(4, "reserved field is not zero"));
        }
        let attribute = |tag: Tag, size: u64, floats: bool| -> Result<Option<&'a [u8]>> {
            let Some(section) = container.section(tag) else {
                return Ok(None);
            };
            let fields = Fields { section: *section };
            fields.expect_len(m64.checked_mul(size))?;
            if floats {
                check_finite(&fields, 0..section.bytes.len())?;
            }
            Ok(Some(section.bytes))
        };
        let normals = attribute(Tag::NORM, 12, true)?;
        let texcoords = attribute(Tag::TEXC, 8, true)?;
        let colors = attribute(Tag::COLR, 4, false)?;

        let connectivity = match connectivity_kind {
            kind::LR => ConnectivityView::Lr(lr_tables(&container, m)?),
            kind::STRIPS => ConnectivityView::Strips(strips::strips_tables(&container, m)?),
            kind::LR_COMPACT => {
                ConnectivityView::LrCompact(lr_compact::lr_compact_tables(&container, m)?)
            }
            _ => ConnectivityView::Edgebreaker(edgebreaker_triangles(&container, m)?),
        };
        let held = connectivity.triangle_count();
        if held != triangles as u64 {
            return Err(mesh.err(
                8,
                format!("{triangles} triangles, the connectivity holds {held}"),
            ));
        }

        let copies = match container.section(Tag::COPY) {
            None => LeWords::default(),
            Some(section) => {
                let f = Fields { section: *section };
                let k = f.u32(0)? as u64;
                f.expect_len(k.checked_mul(8).and_then(|x| x.checked_add(4)))?;
                let words = LeWords(&section.bytes[4..]);
                let mut is_copy = vec![false; m as usize];
                let mut previous = None;
                for i in 0..k as usize {
                    let (copy, original) = (words.at(2 * i), words.at(2 * i + 1));
                    if copy >= m || original >= m || previous.is_some_and(|p| copy <= p) {
                        return Err(f.err(4 + 8 * i, format!("bad copy pair ({copy}, {original}): ids must be below {m}, copies increasing")));
                    }
                    is_copy[copy as usize] = true;
                    previous = Some(copy);
                }
                for i in 0..k as usize {
                    if is_copy[words.at(2 * i + 1) as usize] {
                        return Err(f.err(8 + 8 * i, "the original of a copy is itself a copy"));
                    }
                }
                words
            }
        };
        if m - (copies.count() / 2) as u32 != output_vertices {
            return Err(mesh.err(
                4,
                format!(
                    "{output_vertices} output vertices, but {m} vertices with {} copies",
                    copies.count() / 2
                ),
            ));
        }

        let kept = match container.section(Tag::KEPT) {
            None => LeWords::default(),
            Some(section) => {
                let f = Fields { section: *section };
                let k = f.u32(0)? as u64;
                f.expect_len(k.checked_mul(12).and_then(|x| x.checked_add(4)))?;
                let words = LeWords(&section.bytes[4..]);
                if let Some(i) = (0..words.count()).find(|&i| words.at(i) >= m) {
                    return Err(f.err(
                        4 + 4 * i,
                        format!("vertex {} out of range ({m} vertices)", words.at(i)),
                    ));
                }
                words
            }
        };
        if (kept.count() / 3) as u32 != kept_count {
            return Err(mesh.err(
                12,
                format!(
                    "{kept_count} kept triangles, section KEPT holds {}",
                    kept.count() / 3
                ),
            ));
        }

        let perm = match container.section(Tag::PERM) {
            None => None,
            Some(section) => {
                let f = Fields { section: *section };
                let (nv, nt) = (f.u32(0)?, f.u32(4)?);
                let total = triangles as u64 + kept_count as u64;
                if nv != output_vertices || nt as u64 != total {
                    return Err(f.err(0, format!("permutations of {nv} vertices and {nt} triangles, the mesh has {output_vertices} and {total}")));
                }
                f.expect_len(Some(8 + 4 * (nv as u64 + nt as u64)))?;
                let vertices = LeWords(&section.bytes[8..8 + 4 * nv as usize]);
                let tris = LeWords(&section.bytes[8 + 4 * nv as usize..]);
                check_permutation(&f, 8, vertices)?;
                check_permutation(&f, 8 + 4 * nv as usize, tris)?;
                Some((vertices, tris))
            }
        };

        Ok(MeshView {
            container,
            metadata,
            connectivity,
            vertices: m,
            positions,
            normals,
            texcoords,
            colors,
            copies,
            kept,
            perm,
            output_vertices,
            triangles,
        })
    }

    /// The LR tables, answering the corner operators on the buffer, when the container holds
    /// standard LR.
    pub fn lr(&self) -> Option<&LrTables<LeWords<'a>>> {
        match &self.connectivity {
            ConnectivityView::Lr(lr) => Some(lr),
            _ => None,
        }
    }

    /// The bit-efficient LR tables, answering the corner operators on the buffer, when the
    /// container holds them.
    pub fn lr_compact(&self) -> Option<&CompactTables<LeWords<'a>, LeUnits<'a>>> {
        match &self.connectivity {
            ConnectivityView::LrCompact(lr) => Some(lr),
            _ => None,
        }
    }

    /// The constrained strips and adjacent-strips table, answering the corner operators on
    /// the buffer, when the container holds them.
    pub fn strips(&self) -> Option<&CtsTables<LeWords<'a>>> {
        match &self.connectivity {
            ConnectivityView::Strips(strips) => Some(strips),
            _ => None,
        }
    }

    /// The connectivity.
    pub fn connectivity(&self) -> &ConnectivityView<'a> {
        &self.connectivity
    }

    /// The position of vertex `v` (dequantized when stored as 16-bit).
    pub fn position(&self, v: Vertex) -> [f32; 3] {
        let i = v.idx();
        match self.positions {
            Positions::F32(b) => [0, 1, 2].map(|k| {
                let at = 12 * i + 4 * k;
                f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
            }),
            Positions::Quantized16 { lo, hi, data } => [0, 1, 2].map(|k| {
                let at = 6 * i + 2 * k;
                let q = u16::from_le_bytes([data[at], data[at + 1]]) as f64;
                (lo[k] as f64 + q / 65535.0 * (hi[k] as f64 - lo[k] as f64)) as f32
            }),
        }
    }

    /// Whether positions are stored quantized (lossy).
    pub fn is_quantized(&self) -> bool {
        matches!(self.positions, Positions::Quantized16 { .. })
    }

    /// Number of canonical LR triangles (kept-aside ones not included).
    pub fn triangle_count(&self) -> u32 {
        self.triangles
    }

    /// Number of container vertices: those of the connectivity, copies included.
    pub fn connectivity_vertex_count(&self) -> u32 {
        self.vertices
    }

    /// Number of vertices once copies are merged back.
    pub fn output_vertex_count(&self) -> u32 {
        self.output_vertices
    }

    /// Decodes the mesh: copies merged back into their originals, canonical triangles in id
    /// order then the kept-aside ones, attributes; in the input's order when the file keeps it.
    pub fn to_mesh(&self) -> Mesh {
        let m = self.vertices as usize;
        // Output id of every container vertex: non-copies in order, copies share their original's.
        let mut output = vec![NONE; m];
        for i in 0..self.copies.count() / 2 {
            output[self.copies.at(2 * i) as usize] = u32::MAX - 1;
        }
        let mut next = 0u32;
        let mut order = Vec::with_capacity(self.output_vertices as usize);
        for (v, slot) in output.iter_mut().enumerate() {
            if *slot == NONE {
                *slot = next;
                next += 1;
                order.push(v as u32);
            }
        }
        for i in 0..self.copies.count() / 2 {
            let (copy, original) = (self.copies.at(2 * i), self.copies.at(2 * i + 1));
            output[copy as usize] = output[original as usize];
        }
        let mut triangles: Vec<[u32; 3]> =
            Vec::with_capacity(self.triangles as usize + self.kept.count() / 3);
        self.connectivity
            .for_each_triangle(|t| triangles.push(t.map(|v| output[v as usize])));
        for i in 0..self.kept.count() / 3 {
            triangles.push([0, 1, 2].map(|k| output[self.kept.at(3 * i + k) as usize]));
        }
        let floats = |b: &[u8], v: u32, n: usize, k: usize| {
            let at = 4 * (n * v as usize + k);
            f32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
        };
        let mut mesh = Mesh {
            positions: order.iter().map(|&v| self.position(Vertex(v))).collect(),
            triangles,
            normals: self.normals.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1, 2].map(|k| floats(b, v, 3, k)))
                    .collect()
            }),
            texcoords: self.texcoords.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1].map(|k| floats(b, v, 2, k)))
                    .collect()
            }),
            colors: self.colors.map(|b| {
                order
                    .iter()
                    .map(|&v| [0, 1, 2, 3].map(|k| b[4 * v as usize + k]))
                    .collect()
            }),
        };
        if let Some((vertices, tris)) = self.perm {
            mesh = reorder(mesh, vertices, tris);
        }
        mesh
    }
}

/// Puts vertices and triangles back in the input order: output vertex `k` was input vertex
/// `vertices[k]`, output triangle `j` input triangle `tris[j]`.
fn reorder(mesh: Mesh, vertices: LeWords, tris: LeWords) -> Mesh {
    fn permute<T: Copy + Default>(items: &[T], to: impl Fn(usize) -> usize) -> Vec<T> {
        let mut out = vec![T::default(); items.len()];
        for (k, item) in items.iter().enumerate() {
            out[to(k)] = *item;
        }
        out
    }
    let to_v = |k: usize| vertices.at(k) as usize;
    let renamed: Vec<[u32; 3]> = mesh
        .triangles
        .iter()
        .map(|t| t.map(|v| vertices.at(v as usize)))
        .collect();
    Mesh {
        positions: permute(&mesh.positions, to_v),
        triangles: permute(&renamed, |j| tris.at(j) as usize),
        normals: mesh.normals.as_deref().map(|n| permute(n, to_v)),
        texcoords: mesh.texcoords.as_deref().map(|t| permute(t, to_v)),
        colors: mesh.colors.as_deref().map(|c| permute(c, to_v)),
    }
}

fn check_permutation(fields: &Fields, at: usize, words: LeWords) -> Result<()> {
    let n = words.count();
    let mut seen = vec![false; n];
    for i in 0..n {
        let x = words.at(i) as usize;
        if x >= n || seen[x] {
            return Err(fields.err(at + 4 * i, format!("{x} breaks a permutation of 0..{n}")));
        }
        seen[x] = true;
    }
    Ok(())
}

/// The `EBRK` section decoded, with errors placed in the file and the counts checked.
fn edgebreaker_triangles(container: &Container, m: u32) -> Result<Vec<[u32; 3]>> {
    let section = *container.required(Tag::EBRK)?;
    let limits = crate::edgebreaker::Limits::default();
    let decoded = crate::edgebreaker::decode(section.bytes, &limits).map_err(|e| match e {
        Error::Parse(p) => {
            let at = match p.location {
                crate::error::Location::Byte(b) => b,
                _ => 0,
            };
            error("EBRK", section.offset + at, p.message)
        }
        other => other,
    })?;
    if decoded.vertex_count != m {
        return Err(error(
            "EBRK",
            section.offset,
            format!("{} vertices, section MESH says {m}", decoded.vertex_count),
        ));
    }
    // A stream can decode to triangles the encoder never writes; the container takes only
    // what it could have written: vertices in range, no repeated vertex in a triangle.
    let bad =
        |t: &[u32; 3]| t.iter().any(|&v| v >= m) || t[0] == t[1] || t[1] == t[2] || t[0] == t[2];
    if let Some(t) = decoded.triangles.iter().position(bad) {
        return Err(error(
            "EBRK",
            section.offset,
            format!(
                "decoded triangle {t} {:?} is degenerate or out of range",
                decoded.triangles[t]
            ),
        ));
    }
    Ok(decoded.triangles)
}

/// The `LRTB` section as tables, after checking every rule the operators rely on.
fn lr_tables<'a>(container: &Container<'a>, m: u32) -> Result<LrTables<LeWords<'a>>> {
    let section = *container.required(Tag::LRTB)?;
    let f = Fields { section };
    if section.bytes.len() < format::LRTB_HEADER_LEN {
        return Err(f.err(
            0,
            format!(
                "{} bytes, shorter than its {}-byte header",
                section.bytes.len(),
                format::LRTB_HEADER_LEN
            ),
        ));
    }
    let [mm, m_r, rings, t0, records, r0, r1, r2] =
        [0, 1, 2, 3, 4, 5, 6, 7].map(|i| le_u32(section.bytes, 4 * i));
    if mm != m {
        return Err(f.err(0, format!("{mm} vertices, section MESH says {m}")));
    }
    if [r0, r1, r2] != [0; 3] {
        return Err(f.err(20, "reserved fields are not zero"));
    }
    if m >= NULL {
        return Err(f.err(
            0,
            format!("{m} vertices exceed the LR limit of {}", NULL - 1),
        ));
    }
    if m_r > m || (m_r == 0) != (rings == 0) || rings as u64 > m_r as u64 / 4 {
        return Err(f.err(4, format!("{m_r} ring vertices in {rings} rings for {m} vertices (rings have at least 4 vertices)")));
    }
    if 8 * m_r as u64 + 4 * t0 as u64 >= NONE as u64 || records >= NULL {
        return Err(f.err(12, "corner ids exceed 32 bits"));
    }
    let words_per_bits = (m_r as u64).div_ceil(32);
    let lengths = [
        rings as u64 + 1,
        words_per_bits,
        words_per_bits,
        2 * m_r as u64,
        3 * t0 as u64,
        3 * t0 as u64,
        3 * records as u64,
        (m - m_r) as u64,
    ];
    f.expect_len(Some(
        format::LRTB_HEADER_LEN as u64 + 4 * lengths.iter().sum::<u64>(),
    ))?;
    let mut at = format::LRTB_HEADER_LEN;
    let mut starts_of = [0usize; 8];
    let arrays = lengths.map(|len| {
        let words = LeWords(&section.bytes[at..at + 4 * len as usize]);
        at += 4 * len as usize;
        words
    });
    let mut offset = format::LRTB_HEADER_LEN;
    for (i, len) in lengths.iter().enumerate() {
        starts_of[i] = offset;
        offset += 4 * *len as usize;
    }
    let [ring_starts, ring_last, ring_rank, lr, vo_v, vo_o, vo_star, c] = arrays;
    let word_err =
        |array: usize, i: usize, message: String| f.err(starts_of[array] + 4 * i, message);
    // Where a corner's triangle is stored: its LR entry, or its VO row.
    let corner_at = |c: Corner| {
        if c.0 >= 8 * m_r {
            starts_of[4] + 4 * (c.0 - c.0 / 4 - 6 * m_r) as usize
        } else {
            starts_of[3] + 4 * (2 * (c.0 as usize >> 3) + ((c.0 as usize >> 2) & 1))
        }
    };

    // Rings: starts increasing by at least 4 from 0 to m_r; bits and ranks as derived.
    check_rings(&ring_starts, Some((&ring_last, &ring_rank)), m_r, word_err)?;

    let tables = LrTables {
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
    };

    // Entries: values in range, NULL only as a right tip, each record used once.
    let mut record_used = vec![false; records as usize];
    for slot in 0..2 * m_r as usize {
        let e = lr.at(slot);
        let value = e & VALUE;
        let bad = |message: String| {
            Err(word_err(
                3,
                slot,
                format!("entry {e:#x} of slot {slot}: {message}"),
            ))
        };
        if e & IRREGULAR != 0 {
            if value >= records || record_used[value as usize] {
                return bad(format!(
                    "record {value} missing or used twice ({records} records)"
                ));
            }
            record_used[value as usize] = true;
            if vo_star.at(3 * value as usize) >= m {
                return bad(format!(
                    "record tip {} out of range",
                    vo_star.at(3 * value as usize)
                ));
            }
        } else if value >= m && !(value == NULL && slot % 2 == 1 && e & WART == 0) {
            return bad(format!("vertex {value} out of range ({m} vertices)"));
        }
    }
    if let Some(i) = record_used.iter().position(|&u| !u) {
        return Err(word_err(
            6,
            3 * i,
            format!("record {i} is not used by any entry"),
        ));
    }
    if let Some(i) = (0..vo_v.count()).find(|&i| vo_v.at(i) >= m) {
        return Err(word_err(
            4,
            i,
            format!("vertex {} out of range ({m} vertices)", vo_v.at(i)),
        ));
    }
    // Stored corners are canonical corners or NONE.
    let corner_ok = |x: u32| x == NONE || tables.is_corner(Corner(x));
    for (array, words) in [(5, vo_o), (6, vo_star), (7, c)] {
        for i in 0..words.count() {
            // VO* records start with a tip vertex, checked above.
            let is_tip = array == 6 && i % 3 == 0;
            if !is_tip && !corner_ok(words.at(i)) {
                return Err(word_err(
                    array,
                    i,
                    format!("{} is not a corner of the mesh", words.at(i)),
                ));
            }
        }
    }

    check_lr_layout(&tables, &f, corner_at, |v| {
        if v < m_r {
            starts_of[3] + 8 * v as usize
        } else {
            starts_of[7] + 4 * (v - m_r) as usize
        }
    })?;
    Ok(tables)
}

/// [V16] for any LR layout: ring starts increase by at least 4 from 0 to `m_r`, and the
/// ring-end bits and ranks (when the layout stores them) are the ones the starts imply.
/// `err(array, word, message)` locates an error in array 0 (starts), 1 (bits) or 2 (ranks).
fn check_rings<W: Words>(
    ring_starts: &W,
    bits: Option<(&W, &W)>,
    m_r: u32,
    err: impl Fn(usize, usize, String) -> Error,
) -> Result<()> {
    if m_r == 0 {
        return match ring_starts.at(0) {
            0 => Ok(()),
            _ => Err(err(
                0,
                0,
                "ring starts of an empty ring set must be [0]".into(),
            )),
        };
    }
    let starts: Vec<u32> = (0..ring_starts.count())
        .map(|i| ring_starts.at(i))
        .collect();
    for i in 0..starts.len() {
        let ok = if i == 0 {
            starts[0] == 0
        } else {
            starts[i] >= starts[i - 1].saturating_add(4)
                && (i + 1 < starts.len() || starts[i] == m_r)
        };
        if !ok {
            return Err(err(
                0,
                i,
                format!("ring start {} breaks the ring rules", starts[i]),
            ));
        }
    }
    let Some((ring_last, ring_rank)) = bits else {
        return Ok(());
    };
    let (last, rank) = crate::lr::ring_bits(&starts);
    for (i, &w) in last.iter().enumerate() {
        if ring_last.at(i) != w {
            return Err(err(
                1,
                i,
                "ring-end bits do not match the ring starts".into(),
            ));
        }
        if ring_rank.at(i) != rank[i] {
            return Err(err(
                2,
                i,
                "ring ranks do not match the ring-end bits".into(),
            ));
        }
    }
    Ok(())
}

/// The rules every LR layout must keep so that the operators answer valid ids and swings
/// and contour walks terminate (spec/FORMAT.md [V19], [V21]–[V23]): slots that the
/// operators jump to from redundant and wart slots hold canonical triangles; no canonical
/// triangle is degenerate; `c.o` is an involution across the same edge; `v.c` is a corner
/// of `v`. `corner_at` and `vertex_at` give the section offset that stores a corner's
/// triangle and a vertex's corner, for errors.
fn check_lr_layout<T: LrLayout>(
    tables: &T,
    f: &Fields,
    corner_at: impl Fn(Corner) -> usize,
    vertex_at: impl Fn(u32) -> usize,
) -> Result<()> {
    let m = tables.vertex_count();
    let corner_err = |c: Corner, message: String| f.err(corner_at(c), message);
    for slot in 0..2 * tables.ring_vertices() as usize {
        let (v, side) = ((slot / 2) as u32, slot % 2);
        if (tables.redundant(v, side) || tables.wart(v, side))
            && !tables.slot_is_triangle(tables.ring_next(v), side)
        {
            return Err(corner_err(
                Corner(8 * v + 4 * side as u32),
                format!(
                    "slot {slot} points to slot {} which holds no canonical triangle",
                    2 * tables.ring_next(v) as usize + side
                ),
            ));
        }
    }
    // Behaviour: c.o is an involution across the same edge; v.c is a corner of v; triangles
    // are not degenerate. This makes swings and contour walks terminate.
    // c.o is an involution: each pair is checked once, from its smaller corner, and the pairs
    // must account for every corner that has an opposite (a corner whose opposite does not
    // point back would be left over).
    let (mut with_opposite, mut pairs) = (0u64, 0u64);
    for t in tables.triangles() {
        let corners = tables.triangle_corners(t);
        let vertices = corners.map(|c| tables.vertex(c));
        if vertices[0] == vertices[1] || vertices[1] == vertices[2] || vertices[0] == vertices[2] {
            return Err(corner_err(
                corners[0],
                format!("triangle {} is degenerate {vertices:?}", t.0),
            ));
        }
        for c in corners {
            let Some(o) = tables.opposite(c) else {
                continue;
            };
            with_opposite += 1;
            if o.0 < c.0 {
                continue;
            }
            if !tables.is_corner(o)
                || tables.opposite(o) != Some(c)
                || tables.vertex(tables.next(o)) != tables.vertex(tables.prev(c))
                || tables.vertex(tables.prev(o)) != tables.vertex(tables.next(c))
            {
                return Err(corner_err(
                    c,
                    format!(
                        "corner {} and its opposite {} do not face each other across one edge",
                        c.0, o.0
                    ),
                ));
            }
            pairs += 1;
        }
    }
    if with_opposite != 2 * pairs {
        return Err(f.err(
            0,
            format!(
                "{} corners have an opposite that does not point back",
                with_opposite - 2 * pairs
            ),
        ));
    }
    for v in 0..m {
        let Some(c) = tables.vertex_corner(Vertex(v)) else {
            continue;
        };
        if tables.vertex(c) != Vertex(v) {
            let message = format!(
                "the corner of vertex {v} is a corner of vertex {}",
                tables.vertex(c).0
            );
            return Err(f.err(vertex_at(v), message));
        }
    }
    Ok(())
}

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
    /// Bytes of connectivity: the connectivity section, COPY and KEPT.
    pub connectivity_bytes: u64,
    /// Connectivity bits per triangle.
    pub connectivity_bpt: f64,
    /// References per triangle: of the LR tables (LR paper, section 8), or of the strips'
    /// `T`, `A` and `C`; none for Edgebreaker.
    pub rpt: Option<f64>,
    /// Positions stored as 16-bit integers (lossy).
    pub quantized: bool,
    /// Per-vertex attributes present: `normals`, `texcoords`, `colors`.
    pub attributes: Vec<&'static str>,
    /// Whether the input's vertex and triangle order is stored.
    pub keeps_order: bool,
    /// The metadata, if any.
    pub metadata: Option<Metadata>,
}

impl MeshView<'_> {
    /// A summary of the container for reports.
    pub fn summary(&self) -> ContainerSummary {
        let section_len = |tag: Tag| {
            self.container
                .section(tag)
                .map_or(0, |s| s.bytes.len() as u64)
        };
        let connectivity_bytes = section_len(Tag::LRTB)
            + section_len(Tag::EBRK)
            + section_len(Tag::STRP)
            + section_len(Tag::LRBE)
            + section_len(Tag::COPY)
            + section_len(Tag::KEPT);
        let triangles = self.triangles as u64 + (self.kept.count() / 3) as u64;
        let per_triangle = |x: f64| {
            if triangles == 0 {
                0.0
            } else {
                x / triangles as f64
            }
        };
        let lr = self.lr();
        let compact = self.lr_compact();
        let rpt = match &self.connectivity {
            ConnectivityView::Lr(lr) => {
                let m_r = lr.ring_vertices();
                let refs = 2 * m_r as u64
                    + 6 * lr.t0_count() as u64
                    + 3 * lr.record_count() as u64
                    + (lr.m - m_r) as u64;
                Some(per_triangle(refs as f64))
            }
            // T, A and C, one reference an entry.
            ConnectivityView::Strips(strips) => Some(per_triangle(
                (2 * strips.len() as u64 + strips.vertex_id_bound() as u64) as f64,
            )),
            ConnectivityView::Edgebreaker(_) | ConnectivityView::LrCompact(_) => None,
        };
        let mut attributes = Vec::new();
        for (present, name) in [
            (self.normals.is_some(), "normals"),
            (self.texcoords.is_some(), "texcoords"),
            (self.colors.is_some(), "colors"),
        ] {
            if present {
                attributes.push(name);
            }
        }
        ContainerSummary {
            version: format!("{}.{}", self.container.major, self.container.minor),
            bytes: self
                .container
                .sections
                .last()
                .map_or(HEADER_LEN as u64, |s| s.offset + s.bytes.len() as u64),
            sections: self
                .container
                .sections
                .iter()
                .map(|s| SectionSummary {
                    tag: s.tag.name(),
                    required: s.flags & FLAG_REQUIRED != 0,
                    offset: s.offset,
                    length: s.bytes.len() as u64,
                })
                .collect(),
            connectivity: self.connectivity.name(),
            vertices: self.output_vertices,
            connectivity_vertices: self.vertices,
            triangles,
            kept_triangles: (self.kept.count() / 3) as u32,
            vertex_copies: (self.copies.count() / 2) as u32,
            ring_vertices: lr
                .map(|lr| lr.ring_vertices())
                .or(compact.map(|lr| lr.ring_vertices())),
            rings: lr
                .map(|lr| lr.ring_count() as u32)
                .or(compact.map(|lr| lr.ring_count() as u32)),
            t0_triangles: lr
                .map(|lr| lr.t0_count())
                .or(compact.map(|lr| lr.t0_count())),
            irregular_triangles: lr.map(|lr| lr.record_count()),
            connectivity_bytes,
            connectivity_bpt: per_triangle(8.0 * connectivity_bytes as f64),
            rpt,
            quantized: self.is_quantized(),
            attributes,
            keeps_order: self.perm.is_some(),
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
        writeln!(
            f,
            "positions                {}",
            if self.quantized {
                "16-bit quantized (lossy)"
            } else {
                "f32"
            }
        )?;
        let attributes = if self.attributes.is_empty() {
            "none".to_string()
        } else {
            self.attributes.join(", ")
        };
        writeln!(f, "attributes               {attributes}")?;
        writeln!(f, "input order kept         {}", self.keeps_order)?;
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
