//! The connectivity sections, each laid out from its description in
//! [`crate::format::layout`], with the maps from container ids back to the input's.

use crate::corner_table::CornerTable;
use crate::edgebreaker;
use crate::error::Result;
use crate::format::layout::{
    write_fields, CompactZipr, Layout, LrbeHeader, LrtbHeader, StrpHeader, ZiprHeader,
    LRBE_TIP_BASES, LR_BOUNDARIES_ON_RING, LR_OPEN_FANS, ZIPPER_IMPLIED_WARTS,
    ZIPPER_INNER_RING_STARTS, ZIPPER_JOINED_LISTS, ZIPPER_LEFT_FOURS, ZIPPER_PACKED_LISTS,
    ZIPPER_RIGHT_FOURS, ZIPPER_RING_BLOCKS, ZIPPER_ROW_RECORDS, ZIPPER_SHORT_HEADS,
    ZIPPER_WART_DELTAS,
};
use crate::format::{Kind, Tag};
use crate::ids::{Triangle, Vertex};
use crate::lr::zipper::count_bytes;
use crate::lr::{CompactLr, Lr, LrLayout, Zipper};
use crate::ops::CornerOps;
use crate::strips::Cts;

/// A connectivity section and how its vertices and triangles relate to the input.
pub(super) struct Encoded {
    pub kind: Kind,
    pub tag: Tag,
    pub payload: Vec<u8>,
    /// Container vertex -> input vertex (several for a split vertex).
    pub input_vertex: Vec<u32>,
    /// The connectivity's triangles, in its order -> input triangle.
    pub input_triangle: Vec<u32>,
    /// The triangles as the container reads them: ids, vertices, and the id bound.
    pub shape: Shape,
    /// Edgebreaker: the corner table the reader builds from the stream, which predicts the
    /// positions (when they are coded).
    pub decoder_table: Option<CornerTable>,
}

/// The connectivity's triangles as a reader sees them (FORMAT.md §4): for each, in order, its
/// triangle id and its container vertices `(t.c.v, t.c.n.v, t.c.p.v)`. The attribute and
/// part sections are indexed by these ids and corners.
#[derive(Debug, Clone, Default)]
pub(super) struct Shape {
    /// One past the largest triangle id (`S` before the kept triangles).
    pub id_bound: u32,
    /// Triangle id of each triangle, in order.
    pub ids: Vec<u32>,
    /// Container vertices of each triangle's corners, in order.
    pub corners: Vec<[u32; 3]>,
}

impl Shape {
    /// The triangles of `ops` with their corners when `wanted` (attributes and parts are
    /// indexed by them), only the id bound otherwise: 16 bytes per triangle not held.
    fn of(ops: &impl CornerOps, wanted: bool) -> Shape {
        let n = if wanted { ops.triangles().count() } else { 0 };
        let mut ids = Vec::with_capacity(n);
        let mut corners = Vec::with_capacity(n);
        for t in ops.triangles().take(n) {
            ids.push(t.0);
            corners.push(ops.triangle_vertices(t).map(|v| v.0));
        }
        Shape {
            id_bound: ops.triangle_id_bound(),
            ids,
            corners,
        }
    }
}

/// The input triangle of each of `ops`'s triangles, in its order, allocated at its final size
/// (counted first: collecting a filtered iterator would double its capacity as it grows).
fn input_triangles(ops: &impl CornerOps, input: impl Fn(Triangle) -> u32) -> Vec<u32> {
    let mut out = Vec::with_capacity(ops.triangles().count());
    out.extend(ops.triangles().map(input));
    out
}

/// Appends each array in layout order, checking that its length is the one the header's
/// counts describe (the reader slices the section with the same layout).
fn write_arrays(out: &mut Vec<u8>, layout: &Layout, words: &[&[u32]], units: &[&[u16]]) {
    let widths = words
        .iter()
        .map(|w| (w.len(), 4))
        .chain(units.iter().map(|u| (u.len(), 2)));
    for (array, (len, width)) in layout.arrays.iter().zip(widths) {
        debug_assert_eq!(
            (array.len, array.width),
            (len, width),
            "array {}",
            array.name
        );
    }
    // At its final size at once: growing by doubling would hold up to twice the section.
    out.reserve_exact((layout.len as usize).saturating_sub(out.len()));
    for w in words {
        write_fields(out, w);
    }
    for u in units {
        for x in u.iter() {
            out.extend_from_slice(&x.to_le_bytes());
        }
    }
    debug_assert_eq!(out.len() as u64, layout.len);
}

/// The header flags of built LR tables of either layout.
fn boundary_flag<T: LrLayout>(tables: &T) -> u32 {
    if tables.boundaries_on_ring() {
        LR_BOUNDARIES_ON_RING
    } else {
        0
    }
}

/// The `LRTB` section of a built LR.
/// With `shape`, the triangles as a reader numbers them (see [`Shape::of`]).
pub(super) fn lr_section(lr: &Lr, shape: bool) -> Encoded {
    let t = lr.tables();
    let header = LrtbHeader {
        m: t.m,
        m_r: t.m_r,
        rings: t.ring_count() as u32,
        t0: t.t0_count(),
        records: t.record_count(),
        flags: boundary_flag(t)
            | if t.open_fans.is_some() {
                LR_OPEN_FANS
            } else {
                0
            },
        open_fans: t.open_fans.as_ref().map_or(0, |f| f.count() as u32),
        reserved: 0,
    };
    let layout = header.layout().expect("a built LR fits its layout");
    let mut p = header.to_bytes();
    write_arrays(
        &mut p,
        &layout,
        &[
            &t.ring_starts,
            &t.ring_last,
            &t.ring_rank,
            &t.lr,
            &t.vo_v,
            &t.vo_o,
            &t.vo_star,
            &t.c,
            t.open_fans.as_ref().map_or(&[], |f| &f.bits),
            t.open_fans.as_ref().map_or(&[], |f| &f.rank),
            t.open_fans.as_ref().map_or(&[], |f| &f.corners),
        ],
        &[],
    );
    Encoded {
        kind: Kind::LR,
        tag: Tag::LRTB,
        payload: p,
        input_vertex: (0..lr.vertex_id_bound())
            .map(|v| lr.input_vertex(Vertex(v)))
            .collect(),
        input_triangle: input_triangles(lr, |t| lr.input_triangle(t)),
        shape: Shape::of(lr, shape),
        decoder_table: None,
    }
}

/// The `LRBE` section of a built bit-efficient LR.
/// With `shape`, the triangles as a reader numbers them (see [`Shape::of`]).
pub(super) fn lr_compact_section(lr: &CompactLr, shape: bool) -> Encoded {
    let t = lr.tables();
    let header = lr_compact_header(lr);
    let layout = header.layout().expect("a built LR fits its layout");
    let mut p = header.to_bytes();
    write_arrays(
        &mut p,
        &layout,
        &[
            &t.ring_starts,
            &t.ring_last,
            &t.ring_rank,
            &t.pairs,
            &t.blocks,
            &t.groups,
            &t.c,
            &t.overflow,
            &t.bases,
        ],
        &[&t.t0, &t.records],
    );
    Encoded {
        kind: Kind::LR_COMPACT,
        tag: Tag::LRBE,
        payload: p,
        input_vertex: (0..t.vertex_id_bound())
            .map(|v| lr.input_vertex(Vertex(v)))
            .collect(),
        input_triangle: input_triangles(t, |tri| lr.input_triangle(tri)),
        shape: Shape::of(t, shape),
        decoder_table: None,
    }
}

/// The `LRBE` header of a built bit-efficient LR.
pub(crate) fn lr_compact_header(lr: &CompactLr) -> LrbeHeader {
    let t = lr.tables();
    LrbeHeader {
        m: t.m,
        m_r: t.m_r,
        rings: t.ring_count() as u32,
        t0: t.t0_count(),
        record_units: t.record_units(),
        overflow_rows: t.overflow_rows(),
        period: lr.period(),
        flags: boundary_flag(t)
            | match t.has_tip_bases() {
                true => LRBE_TIP_BASES,
                false => 0,
            },
    }
}

/// The `ZIPR` section of a built Zipper.
/// With `shape`, the triangles as a reader numbers them (see [`Shape::of`]).
pub(super) fn zipper_section(z: &Zipper, shape: bool) -> Encoded {
    let t = z.tables();
    let header = zipper_header(z);
    let layout = header.layout().expect("a built Zipper fits its layout");
    let mut p = header.to_bytes();
    // In the compact form, HEADS is the anchors' list and then the counts'; with
    // JOINED_LISTS, the one stream of those and the seven lists.
    let lists = t.bit_lists();
    let heads: Vec<u32> = match (t.joined_lists, t.compact) {
        (true, _) => {
            let parts = lists.map(|l| (l.words.as_slice(), l.bits()));
            crate::lr::zipper::join_bits(&parts)
        }
        (false, true) => [t.anchors.words.as_slice(), t.head_counts.words.as_slice()].concat(),
        (false, false) => t.heads.clone(),
    };
    // Joined, the seven lists after the heads take no words of their own.
    let seven = lists[2..].iter().map(|l| {
        if t.joined_lists {
            &[][..]
        } else {
            &l.words[..]
        }
    });
    let ring_last: &[u32] = match t.ring_blocks_flag && t.ring_count() > 1 {
        true => &t.ring_blocks.words,
        false => &t.ring_last,
    };
    let mut arrays: Vec<&[u32]> = vec![&t.ring_starts, ring_last, &t.ring_rank, &t.planes, &heads];
    arrays.extend(seven);
    arrays.push(&t.super_counts);
    write_arrays(&mut p, &layout, &arrays, &[]);
    Encoded {
        kind: Kind::ZIPPER,
        tag: Tag::ZIPR,
        payload: p,
        input_vertex: (0..t.vertex_id_bound())
            .map(|v| z.input_vertex(Vertex(v)))
            .collect(),
        input_triangle: input_triangles(t, |tri| z.input_triangle(tri)),
        shape: Shape::of(t, shape),
        decoder_table: None,
    }
}

/// The `ZIPR` header of a built Zipper.
pub(crate) fn zipper_header(z: &Zipper) -> ZiprHeader {
    let t = z.tables();
    ZiprHeader {
        m: t.m,
        m_r: t.m_r,
        rings: t.ring_count() as u32,
        t0: t.t0_count(),
        exceptions: t.exception_count() as u32,
        records: t.record_count() as u32,
        pairs: t.pair_count() as u32,
        explicit: t.explicit_count() as u32,
        flags: boundary_flag(t)
            | if t.wart_deltas { ZIPPER_WART_DELTAS } else { 0 }
            | if t.short_heads { ZIPPER_SHORT_HEADS } else { 0 }
            | if t.packed_lists {
                ZIPPER_PACKED_LISTS
            } else {
                0
            }
            | if t.inner_ring_starts {
                ZIPPER_INNER_RING_STARTS
            } else {
                0
            }
            | if t.ring_blocks_flag {
                ZIPPER_RING_BLOCKS
            } else {
                0
            }
            | if t.fours()[0] { ZIPPER_LEFT_FOURS } else { 0 }
            | if t.fours()[1] { ZIPPER_RIGHT_FOURS } else { 0 }
            | if t.row_records_and_implied_warts()[0] {
                ZIPPER_ROW_RECORDS
            } else {
                0
            }
            | if t.row_records_and_implied_warts()[1] {
                ZIPPER_IMPLIED_WARTS
            } else {
                0
            }
            | if t.joined_lists() {
                ZIPPER_JOINED_LISTS
            } else {
                0
            },
        reserved: 0,
        compact: t.compact.then(|| CompactZipr {
            count_bytes: count_bytes(&t.header_counts()),
            anchor_bits: t.anchors.field_width(),
            count_bits: t.head_counts.fields().map(|f| f.width),
        }),
    }
}

/// The `EBRK` section of a corner table; with `shape` or `predicted`, the corner table a
/// reader builds (the stream is decoded again: only the decoder fixes each triangle's first
/// corner), for the triangles as the reader numbers them and to predict positions.
pub(super) fn edgebreaker_section(
    table: &CornerTable,
    shape: bool,
    predicted: bool,
) -> Result<Encoded> {
    // The table a reader decodes, from the pass that wrote the stream (the same triangles
    // and glued edges as decoding it).
    let (encoded, glued) = edgebreaker::encode_glued(table, shape || predicted)?;
    let decoder_table = match glued {
        Some((decoded, opposites)) => Some(CornerTable::from_glued(
            decoded.vertex_count,
            decoded.triangles,
            opposites,
        )?),
        None => None,
    };
    let shape = if let (true, Some(decoded)) = (shape, &decoder_table) {
        Shape::of(decoded, true)
    } else {
        Shape {
            id_bound: encoded.triangle_order.len() as u32,
            ids: (0..encoded.triangle_order.len() as u32).collect(),
            corners: Vec::new(),
        }
    };
    Ok(Encoded {
        kind: Kind::EDGEBREAKER,
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
        shape,
        decoder_table,
    })
}

/// The `STRP` section of built strips.
/// With `shape`, the triangles as a reader numbers them (see [`Shape::of`]).
pub(super) fn strips_section(cts: &Cts, shape: bool) -> Encoded {
    let header = StrpHeader {
        m: cts.vertex_id_bound(),
        len: cts.t().len() as u32,
        reserved: [0; 2],
    };
    let layout = header.layout().expect("built strips fit their layout");
    let mut p = header.to_bytes();
    write_arrays(&mut p, &layout, &[cts.t(), cts.a(), cts.c()], &[]);
    Encoded {
        kind: Kind::STRIPS,
        tag: Tag::STRP,
        payload: p,
        input_vertex: cts.vertices().map(|v| cts.input_vertex(v)).collect(),
        input_triangle: input_triangles(cts, |t| cts.input_triangle(t)),
        shape: Shape::of(cts, shape),
        decoder_table: None,
    }
}
