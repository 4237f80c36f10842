//! The `ATTR` and `PART` sections (FORMAT.md §3.9, §3.10): every attribute's values with
//! the seams of the per-corner ones, and the part of every triangle, indexed by the
//! container's triangle slots and corners.

use std::collections::HashMap;

use super::connectivity::Encoded;
use crate::corner_table::CornerTable;
use crate::error::{Error, Result};
use crate::format::attributes::{
    bits_for, pack, tables_of, AttributeHeader, CODED_SEAMS, NEIGHBOUR_NORMALS, NORMALIZED,
    PER_CORNER, SURFACE_NORMALS,
};
use crate::format::labels;
use crate::format::parts::{encode_runs, PartsHeader, RUNS};
use crate::format::quantized::{Quantizer, MAX_NORMAL_BITS, MAX_VALUE_BITS, PREDICTED, QUANTIZED};
use crate::geometry::seams;
use crate::geometry::values::{self, Uses};
use crate::mesh::{Attribute, Mesh, Semantic, Values};
use crate::ops::CornerOps;

/// Every corner of the container: the slot of its triangle, its container vertex and the
/// input corner (`3·input triangle + k`) it came from, in slot order then corner order.
pub(super) struct Corners {
    /// `S`: the connectivity's triangle ids, then one slot per kept triangle.
    pub slots: u32,
    /// `(slot, container vertices, input corners)` of every triangle, in slot order.
    pub triangles: Vec<(u32, [u32; 3], [u32; 3])>,
}

impl Corners {
    /// The corners of `encoded`'s triangles and of the kept ones (`primary`: the original
    /// container vertex of each input vertex).
    pub fn new(
        mesh: &Mesh,
        encoded: &Encoded,
        kept: &[(u32, [u32; 3])],
        primary: &[u32],
    ) -> Result<Corners> {
        let shape = &encoded.shape;
        let mut triangles = Vec::with_capacity(shape.ids.len() + kept.len());
        for (j, (&t, &cv)) in shape.ids.iter().zip(&shape.corners).enumerate() {
            let input = encoded.input_triangle[j];
            let tri = mesh.triangles[input as usize];
            let mut from = [0u32; 3];
            for k in 0..3 {
                let v = encoded.input_vertex[cv[k] as usize];
                let Some(k_in) = tri.iter().position(|&x| x == v) else {
                    return Err(Error::Internal(format!(
                        "container triangle {t} has vertex {v}, which input triangle {input} lacks"
                    )));
                };
                from[k] = 3 * input + k_in as u32;
            }
            triangles.push((t, cv, from));
        }
        for (j, &(input, tri)) in kept.iter().enumerate() {
            let slot = shape.id_bound + j as u32;
            debug_assert_eq!(tri, mesh.triangles[input as usize]);
            triangles.push((
                slot,
                tri.map(|v| primary[v as usize]),
                [0, 1, 2].map(|k| 3 * input + k),
            ));
        }
        // The connectivity lists its triangles in increasing id, the kept ones follow.
        debug_assert!(triangles.windows(2).all(|w| w[0].0 < w[1].0));
        Ok(Corners {
            slots: shape.id_bound + kept.len() as u32,
            triangles,
        })
    }
}

/// The `ATTR` payload: `A`, then a record per attribute. With `predicted` (the container's
/// positions as a reader decodes them and Edgebreaker's corner table: an Edgebreaker
/// container from level 1), quantized values are predicted (value encoding 2) when that is
/// shorter than packing them.
pub(super) fn attr_section(
    mesh: &Mesh,
    corners: &Corners,
    input_vertex: &[u32],
    options: &super::EncodeOptions,
    predicted: Option<(&[[f32; 3]], &CornerTable)>,
) -> Result<Vec<u8>> {
    let slots = predicted.map(|(positions, table)| {
        let kept: Vec<[u32; 3]> = corners.triangles[table.triangle_id_bound() as usize..]
            .iter()
            .map(|t| t.1)
            .collect();
        let (vertices, opposites) = values::slots(table, &kept);
        (positions, vertices, opposites)
    });
    let mut out = (mesh.attributes.len() as u32).to_le_bytes().to_vec();
    for a in &mesh.attributes {
        let q = quantizer(a, options)?;
        out.extend(record(a, corners, input_vertex, q, slots.as_ref())?);
    }
    Ok(out)
}

/// How `options` quantize `a` (FORMAT.md §3.9.1): f32 normals octahedral with
/// `normal_bits`, f32 texture coordinates and custom attributes on a grid of
/// `texcoord_bits`, f32 colors on a grid of `color_bits`; `None` (raw) for integer
/// attributes and when the option is not set. The grid covers every value of the attribute.
///
/// # Errors
/// [`Error::InvalidArgument`] for bits out of range (1 to 24 for normals, 1 to 30 otherwise).
pub(super) fn quantizer(
    a: &Attribute,
    options: &super::EncodeOptions,
) -> Result<Option<Quantizer>> {
    let Values::F32(values) = &a.values else {
        return Ok(None);
    };
    let (bits, most) = match a.semantic {
        Semantic::Normal => (options.normal_bits, MAX_NORMAL_BITS),
        Semantic::TexCoord(_) | Semantic::Custom(_) => (options.texcoord_bits, MAX_VALUE_BITS),
        Semantic::Color(_) => (options.color_bits, MAX_VALUE_BITS),
    };
    let Some(bits) = bits else {
        return Ok(None);
    };
    if !(1..=most).contains(&bits) {
        return Err(Error::InvalidArgument(format!(
            "{} quantized to {bits} bits: 1 to {most} allowed",
            a.semantic
        )));
    }
    let n = usize::from(a.components).max(1);
    Ok(Some(match a.semantic {
        Semantic::Normal if a.components == 3 => Quantizer::Octahedral { bits },
        _ => Quantizer::grid(a.components, bits, values.chunks_exact(n)),
    }))
}

/// The key of value `i` of `a` as the record stores it: its bytes (raw), or its integers
/// as little-endian u32s (quantized). Equal keys are one value.
fn key(a: &Attribute, q: Option<&Quantizer>, i: usize, out: &mut Vec<u8>) {
    match (q, &a.values) {
        (Some(q), Values::F32(values)) => {
            let n = usize::from(a.components);
            let mut levels = [0u32; 4];
            q.quantize(&values[n * i..n * i + n], &mut levels);
            for x in &levels[..q.fields() as usize] {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
        _ => a.value_bytes(i, out),
    }
}

/// The values part of a quantized record from the keys of its values (u32 integers, `c'`
/// per value): the header, then the integers packed in `b` bits (value encoding 1); or,
/// with `uses`, predicted (encoding 2) when that is shorter, normals with the shorter of
/// their two predictors. Returns the encoding and the normal predictor too.
fn quantized_values(q: &Quantizer, keys: &[u8], uses: Option<&Uses>) -> (u8, u8, Vec<u8>) {
    let levels: Vec<u32> = keys
        .chunks_exact(4)
        .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
        .collect();
    let mut packed = Vec::new();
    q.write_header(&mut packed);
    for w in pack(&levels, u32::from(q.bits())) {
        packed.extend_from_slice(&w.to_le_bytes());
    }
    let Some(uses) = uses else {
        return (QUANTIZED, SURFACE_NORMALS, packed);
    };
    let predictors: &[u8] = if matches!(q, Quantizer::Octahedral { .. }) {
        &[SURFACE_NORMALS, NEIGHBOUR_NORMALS]
    } else {
        &[SURFACE_NORMALS]
    };
    let mut best = (QUANTIZED, SURFACE_NORMALS, packed);
    for &predictor in predictors {
        let stream = values::encode(uses, q, predictor == SURFACE_NORMALS, &levels);
        let mut predicted = Vec::new();
        q.write_header(&mut predicted);
        predicted.extend_from_slice(&(stream.len() as u32).to_le_bytes());
        predicted.extend_from_slice(&stream);
        if predicted.len() < best.2.len() {
            best = (PREDICTED, predictor, predicted);
        }
    }
    best
}

/// What predicted values need: the positions as decoded, the vertices and the opposite
/// corners of every slot ([`values::slots`]).
type Slots<'p> = (&'p [[f32; 3]], Vec<[u32; 3]>, Vec<[u32; 3]>);

/// One attribute's record. Per vertex: the value of each container vertex's input vertex.
/// Per corner: values are equal when their bytes are (their integers, when quantized); with
/// the random-access tables, each container vertex takes the value most of its corners have,
/// the other values its corners have are its extra values, and the triangles with a corner
/// on an extra value are flagged ([`seam_tables`]). In an Edgebreaker container from level
/// 1 (`slots`), the seams are range coded instead when that is shorter (GEOMETRY.md §8).
fn record(
    a: &Attribute,
    corners: &Corners,
    input_vertex: &[u32],
    quantizer: Option<Quantizer>,
    slots: Option<&Slots>,
) -> Result<Vec<u8>> {
    let m = input_vertex.len();
    let n = usize::from(a.components);
    let q = quantizer.as_ref();
    let (semantic, set) = AttributeHeader::codes(&a.semantic);
    let name = match &a.semantic {
        Semantic::Custom(name) => name.as_bytes(),
        _ => &[],
    };
    let name_len = u16::try_from(name.len()).map_err(|_| {
        Error::Unsupported(format!(
            "attribute name of {} bytes (at most 65535)",
            name.len()
        ))
    })?;
    let mut header = AttributeHeader {
        semantic,
        set,
        component_type: a.values.component_type() as u8,
        components: a.components,
        flags: if a.normalized { NORMALIZED } else { 0 },
        name_len,
        slots: corners.slots,
        ..AttributeHeader::default()
    };
    // The values part and its encoding, from the keys and the value at every corner.
    let own: Vec<[u32; 3]> = corners.triangles.iter().map(|t| t.1).collect();
    let finish = |header: &mut AttributeHeader, keys: &[u8], at_corners: &[[u32; 3]]| {
        let Some(q) = q else {
            return keys.to_vec();
        };
        let uses = slots.map(|(positions, vertices, opposites)| {
            debug_assert_eq!(vertices, &own);
            Uses {
                vertices,
                values: at_corners,
                opposites,
                positions,
                count: (keys.len() / (4 * q.fields() as usize)) as u32,
            }
        });
        let (encoding, predictor, bytes) = quantized_values(q, keys, uses.as_ref());
        header.reserved[0] = u32::from(encoding) | u32::from(predictor) << 16;
        bytes
    };
    let mut values = Vec::new();
    let Some(index) = &a.corners else {
        for &v in input_vertex {
            key(a, q, v as usize, &mut values);
        }
        let values = finish(&mut header, &values, &own);
        return Ok(assemble(&header, name, &values, &[], &[], &[]));
    };
    header.flags |= PER_CORNER;

    // One id per distinct value (by bytes, or by integers when quantized), so that equal
    // values under two indices agree.
    let mut ids: HashMap<Vec<u8>, u32> = HashMap::new();
    let mut canonical = Vec::with_capacity(a.value_count());
    let mut first_of = Vec::new();
    for i in 0..a.value_count() {
        let mut bytes = Vec::with_capacity(n * 4);
        key(a, q, i, &mut bytes);
        let next = ids.len() as u32;
        let id = *ids.entry(bytes).or_insert(next);
        if id == next {
            first_of.push(i);
        }
        canonical.push(id);
    }
    let value_at = |from: u32| canonical[index[from as usize] as usize];
    let zero = match q {
        Some(q) => vec![0u8; 4 * q.fields() as usize],
        None => vec![0u8; n * a.values.component_type().size()],
    };
    let value_bytes = |id: u32, out: &mut Vec<u8>| match id {
        u32::MAX => out.extend_from_slice(&zero),
        id => key(a, q, first_of[id as usize], out),
    };
    let tables = {
        let (values, at_corners, entries, extra) =
            seam_tables(corners, m, &value_at, &value_bytes)?;
        let mut header = header;
        let values = finish(&mut header, &values, &at_corners);
        tables_record(header, name, &values, &entries, extra, corners.slots)
    };
    let Some((_, vertices, opposites)) = slots else {
        return Ok(tables);
    };
    // Edgebreaker: the seams range coded (seam encoding 1), when that is shorter.
    let ids: Vec<[u32; 3]> = corners
        .triangles
        .iter()
        .map(|(_, _, from)| from.map(value_at))
        .collect();
    let slots = seams::Slots {
        vertices,
        opposites,
        vertex_count: m as u32,
    };
    let coded = seams::encode(&slots, &ids);
    let extra = coded.ids.len() - m;
    let flagged = coded
        .at_corners
        .iter()
        .filter(|t| t.iter().any(|&x| x as usize >= m))
        .count() as u32;
    if flagged == 0 {
        return Ok(tables);
    }
    let mut values = Vec::new();
    for &id in &coded.ids {
        value_bytes(id, &mut values);
    }
    let values = finish(&mut header, &values, &coded.at_corners);
    header.extra = extra as u32;
    header.flagged = flagged;
    header.entry_bits = bits_for(header.extra) as u8;
    header.reserved[0] |= u32::from(CODED_SEAMS) << 8;
    let mut out = header.to_bytes();
    out.extend_from_slice(name);
    out.extend_from_slice(&values);
    out.extend_from_slice(&(coded.stream.len() as u32).to_le_bytes());
    out.extend_from_slice(&coded.stream);
    Ok(if out.len() < tables.len() {
        out
    } else {
        tables
    })
}

/// The values of the random-access seam tables (FORMAT.md §3.9, "Writing"): each container
/// vertex's own value is the one most of its corners have, its other values are extras in
/// vertex order. Returns the values' bytes, the value index at every corner, the entries of
/// the flagged slots, and `E`.
#[allow(clippy::type_complexity)]
fn seam_tables(
    corners: &Corners,
    m: usize,
    value_at: &dyn Fn(u32) -> u32,
    value_bytes: &dyn Fn(u32, &mut Vec<u8>),
) -> Result<(Vec<u8>, Vec<[u32; 3]>, Vec<(u32, [u32; 3])>, u32)> {
    // (vertex, value) of every corner, sorted: each vertex's run gives its base and extras.
    let mut uses: Vec<(u32, u32)> = corners
        .triangles
        .iter()
        .flat_map(|(_, cv, from)| (0..3).map(move |k| (cv[k], value_at(from[k]))))
        .collect();
    uses.sort_unstable();
    let mut base = vec![u32::MAX; m];
    let mut extras: Vec<(u32, u32)> = Vec::new(); // (vertex, value), in vertex order
    let mut at = 0;
    while at < uses.len() {
        let v = uses[at].0;
        let end = at + uses[at..].partition_point(|u| u.0 == v);
        let mut best = (0, u32::MAX);
        let mut i = at;
        while i < end {
            let run = uses[i..end].partition_point(|u| u.1 == uses[i].1);
            if run > best.0 {
                best = (run, uses[i].1);
            }
            i += run;
        }
        base[v as usize] = best.1;
        let mut i = at;
        while i < end {
            if uses[i].1 != best.1 {
                extras.push((v, uses[i].1));
            }
            i += uses[i..end].partition_point(|u| u.1 == uses[i].1);
        }
        at = end;
    }
    let e = u32::try_from(extras.len())
        .ok()
        .filter(|&e| u64::from(e) + m as u64 <= u64::from(u32::MAX))
        .ok_or_else(|| Error::Unsupported("an attribute with too many values".into()))?;
    let mut values = Vec::new();
    for &id in base.iter().chain(extras.iter().map(|x| &x.1)) {
        value_bytes(id, &mut values);
    }
    let mut entries = Vec::new();
    let mut at_corners = Vec::with_capacity(corners.triangles.len());
    for (slot, cv, from) in &corners.triangles {
        let entry = |k: usize| {
            let (v, id) = (cv[k], value_at(from[k]));
            if base[v as usize] == id {
                0
            } else {
                let at = extras.partition_point(|x| *x < (v, id));
                debug_assert_eq!(extras[at], (v, id));
                at as u32 + 1
            }
        };
        let triple = [entry(0), entry(1), entry(2)];
        at_corners.push([0, 1, 2].map(|k| match triple[k] {
            0 => cv[k],
            e => m as u32 + e - 1,
        }));
        if triple != [0, 0, 0] {
            entries.push((*slot, triple));
        }
    }
    Ok((values, at_corners, entries, e))
}

/// A record with the random-access seam tables (seam encoding 0): `FLAGS`, `RANK` and the
/// entries of the flagged slots.
fn tables_record(
    mut header: AttributeHeader,
    name: &[u8],
    values: &[u8],
    flagged: &[(u32, [u32; 3])],
    extra: u32,
    slots: u32,
) -> Vec<u8> {
    if flagged.is_empty() {
        return assemble(&header, name, values, &[], &[], &[]);
    }
    header.extra = extra;
    header.flagged = flagged.len() as u32;
    header.entry_bits = bits_for(extra) as u8;
    let [flags, rank, packed] = tables_of(slots, flagged, u32::from(header.entry_bits));
    assemble(&header, name, values, &flags, &rank, &packed)
}

fn assemble(
    header: &AttributeHeader,
    name: &[u8],
    values: &[u8],
    flags: &[u32],
    rank: &[u32],
    entries: &[u32],
) -> Vec<u8> {
    let mut out = header.to_bytes();
    out.extend_from_slice(name);
    out.extend_from_slice(values);
    for w in flags.iter().chain(rank).chain(entries) {
        out.extend_from_slice(&w.to_le_bytes());
    }
    out
}

/// The `PART` payload: the header, the labels (JSON, or with `coded`, from level 1, the
/// coded labels of FORMAT.md §3.10.2 when shorter), then the part of every slot: packed
/// (index encoding 0), or with `runs` (an Edgebreaker container from level 1) the
/// range-coded runs of FORMAT.md §3.10.1 when they are shorter.
pub(super) fn part_section(
    mesh: &Mesh,
    corners: &Corners,
    runs: bool,
    coded: bool,
) -> Result<Option<Vec<u8>>> {
    let Some(parts) = &mesh.parts else {
        return Ok(None);
    };
    let mut json = serde_json::to_vec(parts)
        .map_err(|e| Error::Internal(format!("parts do not serialise: {e}")))?;
    let mut label_encoding = labels::JSON;
    if coded {
        let stream = labels::encode(parts);
        let fits = u32::try_from(stream.len())
            .is_ok_and(|n| labels::decoded_size(parts) <= labels::decoded_bound(n));
        if fits && stream.len() < json.len() {
            (json, label_encoding) = (stream, labels::CODED);
        }
    }
    let count = parts.parts.len() as u32;
    let mut header = PartsHeader {
        parts: count,
        slots: corners.slots,
        bits: PartsHeader::bits_for_parts(count),
        labels: label_encoding,
        json_len: u32::try_from(json.len())
            .map_err(|_| Error::Unsupported("part labels beyond 4 GiB of JSON".into()))?,
        ..PartsHeader::default()
    };
    let mut index = vec![0u32; corners.slots as usize];
    for (slot, _, from) in &corners.triangles {
        index[*slot as usize] = parts.of_triangle[from[0] as usize / 3];
    }
    let packed = if header.bits > 0 {
        pack(&index, header.bits)
    } else {
        Vec::new()
    };
    let stream = runs.then(|| encode_runs(&index));
    let mut out = Vec::new();
    match stream {
        Some(stream) if stream.len() + 4 < 4 * packed.len() => {
            header.encoding = RUNS;
            out.extend(header.to_bytes());
            out.extend_from_slice(&json);
            out.extend_from_slice(&(stream.len() as u32).to_le_bytes());
            out.extend_from_slice(&stream);
        }
        _ => {
            out.extend(header.to_bytes());
            out.extend_from_slice(&json);
            for w in packed {
                out.extend_from_slice(&w.to_le_bytes());
            }
            debug_assert_eq!(header.len(), Some(out.len()));
        }
    }
    Ok(Some(out))
}
