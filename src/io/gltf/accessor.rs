//! Decoding an accessor into values: dense (with `byteStride`), sparse (over base values or
//! zeros) or without data (zeros), every range checked before anything is allocated.

use super::buffers::Buffers;
use super::document::{Accessor, Document, ElementType};
use super::json_error;
use crate::error::Result;
use crate::mesh::{ComponentType, Values};

/// An accessor's decoded elements.
#[derive(Clone)]
pub(super) struct Decoded {
    pub components: u8,
    pub normalized: bool,
    /// `components` numbers per element.
    pub values: Values,
}

impl Decoded {
    pub fn count(&self) -> usize {
        self.values.len() / usize::from(self.components.max(1))
    }
}

/// What the output may still grow by: every allocation not backed by input bytes one to one
/// (zeros of data-less accessors, and vertices repeated by instancing) is charged here.
pub(super) struct Budget {
    left: u64,
    limit: u64,
}

impl Budget {
    pub fn new(input_bytes: u64) -> Budget {
        let limit = input_bytes
            .saturating_mul(super::OUTPUT_LIMIT_FACTOR)
            .saturating_add(1 << 20);
        Budget { left: limit, limit }
    }

    /// Takes `bytes` from the budget.
    ///
    /// # Errors
    /// When they are not left, naming `what` needs them.
    pub fn charge(&mut self, bytes: u64, what: &str) -> Result<()> {
        if bytes > self.left {
            return Err(json_error(
                what,
                format!(
                    "the mesh would grow past {} bytes ({} times the input's size plus 1 MiB): \
                     too many instances, or accessors whose count no data backs",
                    self.limit,
                    super::OUTPUT_LIMIT_FACTOR
                ),
            ));
        }
        self.left -= bytes;
        Ok(())
    }
}

/// Where elements are in a buffer view: `count` elements of `size` bytes, `stride` apart,
/// from byte `offset` of view `view`.
struct Span {
    view: usize,
    offset: u64,
    count: u64,
    size: u64,
    stride: u64,
}

/// The bytes of a view that hold the elements of `span`.
fn view_bytes<'b>(
    doc: &Document,
    buffers: &'b Buffers,
    span: Span,
    path: &str,
) -> Result<&'b [u8]> {
    let Span {
        view,
        offset,
        count,
        size,
        stride,
    } = span;
    let v = &doc.views[view];
    let need = if count == 0 {
        Some(0)
    } else {
        stride
            .checked_mul(count - 1)
            .and_then(|n| n.checked_add(size))
            .and_then(|n| n.checked_add(offset))
    };
    match need {
        Some(need) if need <= v.byte_length => {
            // `buffers::load` checked the view against its buffer, whose data has exactly
            // byteLength bytes.
            let start = v.byte_offset + offset;
            let end = v.byte_offset + need;
            buffers.data[v.buffer]
                .get(start as usize..end as usize)
                .ok_or_else(|| json_error(path, "the buffer's data ends early"))
        }
        _ => Err(json_error(
            path,
            format!(
                "{count} elements of {size} bytes, {stride} bytes apart from byte {offset}, do \
                 not fit in bufferViews[{view}] of {} bytes",
                v.byte_length
            ),
        )),
    }
}

/// Copies `count` elements of `size` bytes, `stride` apart, into one packed vector.
fn gather(bytes: &[u8], count: usize, size: usize, stride: usize) -> Vec<u8> {
    let mut out = Vec::with_capacity(count * size);
    for i in 0..count {
        out.extend_from_slice(&bytes[i * stride..i * stride + size]);
    }
    out
}

/// Decodes accessor `index` (not a matrix).
///
/// # Errors
/// A view too short for the elements, sparse indices out of order or range, a budget
/// exceeded.
pub(super) fn decode(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    budget: &mut Budget,
) -> Result<Decoded> {
    let path = format!("accessors[{index}]");
    let a: &Accessor = &doc.accessors[index];
    let ElementType::Vector(components) = a.element else {
        return Err(json_error(
            &path,
            "a matrix accessor is not a vertex attribute",
        ));
    };
    let csize = a.component.size() as u64;
    let size = csize * u64::from(components);
    let mut packed = match a.view {
        Some(view) => {
            let stride = doc.views[view].byte_stride.unwrap_or(size);
            if stride < size {
                return Err(json_error(
                    &path,
                    format!(
                        "bufferViews[{view}].byteStride {stride} is smaller than the \
                         {size}-byte elements"
                    ),
                ));
            }
            let span = Span {
                view,
                offset: a.byte_offset,
                count: a.count,
                size,
                stride,
            };
            let bytes = view_bytes(doc, buffers, span, &path)?;
            // The elements fit in the view, so count * size is at most its length.
            let out = gather(bytes, a.count as usize, size as usize, stride as usize);
            budget.charge(out.len() as u64, &path)?;
            out
        }
        None => {
            let bytes = a.count.saturating_mul(size);
            budget.charge(bytes, &path)?;
            vec![0u8; bytes as usize]
        }
    };
    if let Some(s) = &a.sparse {
        let spath = format!("{path}.sparse");
        if s.count > a.count {
            return Err(json_error(
                &spath,
                format!("count {} exceeds the accessor's count {}", s.count, a.count),
            ));
        }
        let index_size = s.indices_type.size() as u64;
        let packed_span = |view, offset, size| Span {
            view,
            offset,
            count: s.count,
            size,
            stride: size,
        };
        let indices = view_bytes(
            doc,
            buffers,
            packed_span(s.indices_view, s.indices_offset, index_size),
            &format!("{spath}.indices"),
        )?;
        let values = view_bytes(
            doc,
            buffers,
            packed_span(s.values_view, s.values_offset, size),
            &format!("{spath}.values"),
        )?;
        let (index_size, size) = (index_size as usize, size as usize);
        let mut previous: Option<u64> = None;
        for k in 0..s.count as usize {
            let b = &indices[k * index_size..k * index_size + index_size];
            let i = match s.indices_type {
                ComponentType::U8 => u64::from(b[0]),
                ComponentType::U16 => u64::from(u16::from_le_bytes([b[0], b[1]])),
                _ => u64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            };
            if i >= a.count || previous.is_some_and(|p| i <= p) {
                return Err(json_error(
                    &format!("{spath}.indices"),
                    format!(
                        "entry {k} is {i}: sparse indices must increase strictly and stay below \
                         the accessor's count {}",
                        a.count
                    ),
                ));
            }
            previous = Some(i);
            let at = i as usize * size;
            packed[at..at + size].copy_from_slice(&values[k * size..k * size + size]);
        }
    }
    let mut values = Values::with_capacity(a.component, packed.len() / csize as usize);
    values.push_le(&packed);
    if let Some(i) = values.first_non_finite() {
        return Err(json_error(
            &path,
            format!(
                "element {} has a non-finite component ({})",
                i / usize::from(components),
                values.get_f64(i)
            ),
        ));
    }
    Ok(Decoded {
        components,
        normalized: a.normalized,
        values,
    })
}

/// Decodes an index accessor: scalar unsigned bytes, shorts or ints, not normalized.
///
/// # Errors
/// Another type, and the errors of [`decode`].
pub(super) fn decode_indices(
    doc: &Document,
    buffers: &Buffers,
    index: usize,
    budget: &mut Budget,
    path: &str,
) -> Result<Vec<u32>> {
    let a = &doc.accessors[index];
    let ok_type = matches!(
        a.component,
        ComponentType::U8 | ComponentType::U16 | ComponentType::U32
    );
    if a.element != ElementType::Vector(1) || !ok_type || a.normalized {
        return Err(json_error(
            path,
            format!(
                "accessors[{index}] is {} of {}{}; indices must be SCALAR of unsigned bytes, \
                 shorts or ints",
                a.element.name(),
                component_name(a.component),
                if a.normalized { ", normalized" } else { "" }
            ),
        ));
    }
    let d = decode(doc, buffers, index, budget)?;
    Ok(match d.values {
        Values::U8(v) => v.into_iter().map(u32::from).collect(),
        Values::U16(v) => v.into_iter().map(u32::from).collect(),
        Values::U32(v) => v,
        _ => Vec::new(),
    })
}

/// The glTF name of a component type.
pub(super) fn component_name(t: ComponentType) -> &'static str {
    match t {
        ComponentType::I8 => "BYTE",
        ComponentType::U8 => "UNSIGNED_BYTE",
        ComponentType::I16 => "SHORT",
        ComponentType::U16 => "UNSIGNED_SHORT",
        ComponentType::U32 => "UNSIGNED_INT",
        ComponentType::F32 => "FLOAT",
    }
}
