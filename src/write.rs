//! Writing containers: a mesh in, `.lrm` bytes out (layout: `spec/FORMAT.md`).
//!
//! Encoding is deterministic: the same mesh and options give the same bytes, and no Cargo
//! feature changes them.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::corner_table::CornerTable;
use crate::edgebreaker;
use crate::error::{Error, Result};
use crate::format::{self, geometry, kind, Tag, ENTRY_LEN, FLAG_REQUIRED, HEADER_LEN};
use crate::ids::{Triangle, Vertex};
use crate::lr::{CompactLr, CompactOptions, Lr, LrLayout, LrOptions};
use crate::ops::CornerOps;
use crate::strips::{Cts, StripOptions};
use crate::Mesh;

/// The `META` section: who wrote the file and from what, plus free key/values.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Metadata {
    /// The program that wrote the file.
    pub generator: String,
    /// The file the mesh came from, if any.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub source: Option<String>,
    /// Free key/values.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub extra: BTreeMap<String, String>,
}

/// The connectivity representation a container holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Connectivity {
    /// Standard LR (section `LRTB`): random access, corner queries on the buffer.
    #[default]
    Lr,
    /// Edgebreaker (section `EBRK`): the smallest, decoded sequentially.
    Edgebreaker,
    /// Constrained triangle strips with the adjacent-strips table (section `STRP`): a
    /// rendering index list that also answers corner queries on the buffer.
    Strips,
    /// Bit-efficient LR (section `LRBE`): about 16 bits per triangle plus the irregular
    /// ones, corner queries on the buffer.
    LrCompact,
}

/// How to encode.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncodeOptions {
    /// The connectivity representation.
    pub connectivity: Connectivity,
    /// Options of the LR construction.
    pub lr: LrOptions,
    /// Periods of HYBRID-RING-EXPANDER tried for [`Connectivity::LrCompact`] (0: depth
    /// first); the smallest result is stored.
    pub periods: Vec<u32>,
    /// Options of the stripper, for [`Connectivity::Strips`] (fans are never used).
    pub strips: StripOptions,
    /// Store the permutations back to the input's vertex and triangle order.
    pub keep_order: bool,
    /// Store positions as 16-bit integers in the bounding box (lossy) instead of f32.
    pub quantize16: bool,
    /// The metadata to store.
    pub metadata: Metadata,
}

impl Default for EncodeOptions {
    fn default() -> Self {
        EncodeOptions {
            connectivity: Connectivity::Lr,
            lr: LrOptions::default(),
            periods: CompactOptions::default().periods,
            strips: StripOptions::default(),
            keep_order: false,
            quantize16: false,
            metadata: Metadata {
                generator: format!("lrmesh {}", env!("CARGO_PKG_VERSION")),
                ..Metadata::default()
            },
        }
    }
}

/// Little-endian section payload builder.
#[derive(Default)]
struct Payload(Vec<u8>);

impl Payload {
    fn u32(&mut self, x: u32) -> &mut Self {
        self.0.extend_from_slice(&x.to_le_bytes());
        self
    }
    fn u32s(&mut self, xs: impl IntoIterator<Item = u32>) -> &mut Self {
        for x in xs {
            self.u32(x);
        }
        self
    }
    fn f32s(&mut self, xs: impl IntoIterator<Item = f32>) -> &mut Self {
        for x in xs {
            self.0.extend_from_slice(&x.to_le_bytes());
        }
        self
    }
}

/// A connectivity section and how its vertices and triangles relate to the input.
struct Encoded {
    kind: u32,
    tag: Tag,
    payload: Vec<u8>,
    /// Container vertex -> input vertex (several for a split vertex).
    input_vertex: Vec<u32>,
    /// The connectivity's triangles, in its order -> input triangle.
    input_triangle: Vec<u32>,
}

fn encode_lr(table: &CornerTable, options: &LrOptions) -> Result<Encoded> {
    let lr = Lr::build(table, options)?;
    let tables = lr.tables();
    let mut p = Payload::default();
    p.u32s([
        tables.m,
        tables.m_r,
        tables.ring_count() as u32,
        tables.t0_count(),
        tables.record_count(),
        0,
        0,
        0,
    ]);
    for words in [
        &tables.ring_starts,
        &tables.ring_last,
        &tables.ring_rank,
        &tables.lr,
        &tables.vo_v,
        &tables.vo_o,
        &tables.vo_star,
        &tables.c,
    ] {
        p.u32s(words.iter().copied());
    }
    Ok(Encoded {
        kind: kind::LR,
        tag: Tag::LRTB,
        payload: p.0,
        input_vertex: (0..lr.vertex_id_bound())
            .map(|v| lr.input_vertex(Vertex(v)))
            .collect(),
        input_triangle: lr.triangles().map(|t| lr.input_triangle(t)).collect(),
    })
}

fn encode_edgebreaker(table: &CornerTable) -> Result<Encoded> {
    let encoded = edgebreaker::encode(table)?;
    Ok(Encoded {
        kind: kind::EDGEBREAKER,
        tag: Tag::EBRK,
        payload: encoded.bytes,
        input_vertex: encoded
            .vertex_order
            .iter()
            .map(|&v| table.original_vertex(Vertex(v)).0)
            .collect(),
        input_triangle: encoded
            .triangle_order
            .iter()
            .map(|&t| table.input_triangle(Triangle(t)))
            .collect(),
    })
}

fn encode_lr_compact(table: &CornerTable, options: &CompactOptions) -> Result<Encoded> {
    let lr = CompactLr::build(table, options)?;
    let t = lr.tables();
    let mut p = Payload::default();
    p.u32s([
        t.m,
        t.m_r,
        t.ring_count() as u32,
        t.t0_count(),
        t.record_units(),
        t.overflow_rows(),
        lr.period(),
        0,
    ]);
    for words in [
        &t.ring_starts,
        &t.ring_last,
        &t.ring_rank,
        &t.pairs,
        &t.blocks,
        &t.groups,
        &t.c,
        &t.overflow,
    ] {
        p.u32s(words.iter().copied());
    }
    for units in [&t.t0, &t.records] {
        for &u in units.iter() {
            p.0.extend_from_slice(&u.to_le_bytes());
        }
    }
    debug_assert_eq!(p.0.len() as u64, lr.stored_bytes());
    Ok(Encoded {
        kind: kind::LR_COMPACT,
        tag: Tag::LRBE,
        payload: p.0,
        input_vertex: (0..t.vertex_id_bound())
            .map(|v| lr.input_vertex(Vertex(v)))
            .collect(),
        input_triangle: t.triangles().map(|tri| lr.input_triangle(tri)).collect(),
    })
}

fn encode_strips(table: &CornerTable, options: &StripOptions) -> Result<Encoded> {
    let cts = Cts::build(table, options)?;
    let mut p = Payload::default();
    p.u32s([cts.vertex_id_bound(), cts.t().len() as u32, 0, 0]);
    p.u32s(cts.t().iter().copied());
    p.u32s(cts.a().iter().copied());
    p.u32s(cts.c().iter().copied());
    Ok(Encoded {
        kind: kind::STRIPS,
        tag: Tag::STRP,
        payload: p.0,
        input_vertex: cts.vertices().map(|v| cts.input_vertex(v)).collect(),
        input_triangle: cts.triangles().map(|t| cts.input_triangle(t)).collect(),
    })
}

/// Encodes `mesh` with the connectivity `options` choose.
///
/// # Errors
/// [`Error::InvalidMesh`] for a mesh that breaks [`Mesh::validate`] or exceeds the
/// representation's limits.
pub fn encode(mesh: &Mesh, options: &EncodeOptions) -> Result<Vec<u8>> {
    mesh.validate()?;
    let table = CornerTable::from_mesh(mesh)?;
    let encoded = match options.connectivity {
        Connectivity::Lr => encode_lr(&table, &options.lr)?,
        Connectivity::Edgebreaker => encode_edgebreaker(&table)?,
        Connectivity::Strips => encode_strips(&table, &options.strips)?,
        Connectivity::LrCompact => encode_lr_compact(
            &table,
            &CompactOptions {
                lr: options.lr,
                periods: options.periods.clone(),
            },
        )?,
    };
    let m = encoded.input_vertex.len() as u32;
    let per_vertex = |v: u32| encoded.input_vertex[v as usize] as usize;

    // The first container vertex of each input vertex is its original; later ones are copies.
    let mut primary = vec![u32::MAX; mesh.positions.len()];
    for (v, &input) in encoded.input_vertex.iter().enumerate() {
        if primary[input as usize] == u32::MAX {
            primary[input as usize] = v as u32;
        }
    }
    let copies: Vec<(u32, u32)> = (0..m)
        .map(|v| (v, primary[per_vertex(v)]))
        .filter(|&(v, original)| original != v)
        .collect();

    let mut sections: Vec<(Tag, u32, Vec<u8>)> = Vec::new();
    let meta = serde_json::to_vec(&options.metadata)
        .map_err(|e| Error::InvalidMesh(format!("metadata: {e}")))?;
    sections.push((Tag::META, 0, meta));

    let output_vertices = m - copies.len() as u32;
    let kept = table.kept_aside();
    let mut p = Payload::default();
    p.u32s([
        m,
        output_vertices,
        encoded.input_triangle.len() as u32,
        kept.len() as u32,
        encoded.kind,
        0,
    ]);
    sections.push((Tag::MESH, FLAG_REQUIRED, p.0));

    let mut p = Payload::default();
    if options.quantize16 {
        let (lo, hi) = bounding_box(&mesh.positions);
        p.u32s([geometry::QUANTIZED16, 0]).f32s(lo).f32s(hi);
        for v in 0..m {
            let q = quantize(mesh.positions[per_vertex(v)], lo, hi);
            for x in q {
                p.0.extend_from_slice(&x.to_le_bytes());
            }
        }
    } else {
        p.u32s([geometry::F32, 0]);
        p.f32s((0..m).flat_map(|v| mesh.positions[per_vertex(v)]));
    }
    sections.push((Tag::GEOM, FLAG_REQUIRED, p.0));

    if let Some(normals) = &mesh.normals {
        let mut p = Payload::default();
        p.f32s((0..m).flat_map(|v| normals[per_vertex(v)]));
        sections.push((Tag::NORM, 0, p.0));
    }
    if let Some(texcoords) = &mesh.texcoords {
        let mut p = Payload::default();
        p.f32s((0..m).flat_map(|v| texcoords[per_vertex(v)]));
        sections.push((Tag::TEXC, 0, p.0));
    }
    if let Some(colors) = &mesh.colors {
        let bytes = (0..m).flat_map(|v| colors[per_vertex(v)]).collect();
        sections.push((Tag::COLR, 0, bytes));
    }

    sections.push((encoded.tag, FLAG_REQUIRED, encoded.payload));

    if !copies.is_empty() {
        let mut p = Payload::default();
        p.u32(copies.len() as u32);
        p.u32s(copies.iter().flat_map(|&(c, o)| [c, o]));
        sections.push((Tag::COPY, FLAG_REQUIRED, p.0));
    }
    if !kept.is_empty() {
        let mut p = Payload::default();
        p.u32(kept.len() as u32);
        p.u32s(
            kept.iter()
                .flat_map(|&(_, tri)| tri.map(|x| primary[x as usize])),
        );
        sections.push((Tag::KEPT, FLAG_REQUIRED, p.0));
    }
    if options.keep_order {
        // Output order: non-copy vertices in container order; the connectivity's triangles in
        // its order, then the kept ones.
        let mut p = Payload::default();
        let triangles = (encoded.input_triangle.len() + kept.len()) as u32;
        p.u32s([output_vertices, triangles]);
        p.u32s(
            (0..m)
                .filter(|&v| primary[per_vertex(v)] == v)
                .map(|v| per_vertex(v) as u32),
        );
        p.u32s(encoded.input_triangle.iter().copied());
        p.u32s(kept.iter().map(|&(input, _)| input));
        sections.push((Tag::PERM, 0, p.0));
    }
    Ok(assemble(&sections))
}

/// A container of the given sections `(tag, flags, payload)`, in this order: header, section
/// table and payloads with their checksums. For tools that add sections of their own (an
/// optional section unknown to readers is skipped by them).
pub fn assemble(sections: &[(Tag, u32, Vec<u8>)]) -> Vec<u8> {
    let table_end = HEADER_LEN + ENTRY_LEN * sections.len();
    let total = table_end + sections.iter().map(|s| s.2.len()).sum::<usize>();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(&format::MAGIC);
    out.extend_from_slice(&format::MAJOR.to_le_bytes());
    out.extend_from_slice(&format::MINOR.to_le_bytes());
    out.extend_from_slice(&(sections.len() as u32).to_le_bytes());
    out.extend_from_slice(&(total as u64).to_le_bytes());
    out.extend_from_slice(&[0; 8]); // table CRC (filled below) and reserved
    let mut offset = table_end as u64;
    for (tag, flags, bytes) in sections {
        out.extend_from_slice(&tag.0);
        out.extend_from_slice(&flags.to_le_bytes());
        out.extend_from_slice(&offset.to_le_bytes());
        out.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
        out.extend_from_slice(&crc32fast::hash(bytes).to_le_bytes());
        out.extend_from_slice(&[0; 4]);
        offset += bytes.len() as u64;
    }
    let table_crc = table_checksum(&out[..table_end]);
    out[24..28].copy_from_slice(&table_crc.to_le_bytes());
    for (_, _, bytes) in sections {
        out.extend_from_slice(bytes);
    }
    out
}

/// CRC-32 of the header's first 24 bytes followed by the section table.
pub(crate) fn table_checksum(header_and_table: &[u8]) -> u32 {
    let mut h = crc32fast::Hasher::new();
    h.update(&header_and_table[..24]);
    h.update(&header_and_table[HEADER_LEN..]);
    h.finalize()
}

fn bounding_box(positions: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    if positions.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [0, 1, 2].map(|i| lo[i].min(p[i])),
                [0, 1, 2].map(|i| hi[i].max(p[i])),
            )
        })
}

/// 16-bit coordinates of `p` in the box: `round((p - lo) / (hi - lo) * 65535)`, 0 where the
/// box is flat.
fn quantize(p: [f32; 3], lo: [f32; 3], hi: [f32; 3]) -> [u16; 3] {
    [0, 1, 2].map(|i| {
        let extent = hi[i] as f64 - lo[i] as f64;
        if extent > 0.0 {
            ((p[i] as f64 - lo[i] as f64) / extent * 65535.0)
                .round()
                .clamp(0.0, 65535.0) as u16
        } else {
            0
        }
    })
}
