//! Where the bytes are: the GLB container's chunks, and each buffer's data (the BIN chunk, a
//! base64 `data:` URI or an external file), checked against the declared lengths so that every
//! buffer view lies inside its buffer.

use std::borrow::Cow;

use super::document::Document;
use super::{base64, byte_error, escape, json_error};
use crate::error::Result;

/// `glTF`, little-endian.
pub(super) const GLB_MAGIC: u32 = 0x4654_6C67;
/// Chunk type `JSON`.
pub(super) const CHUNK_JSON: u32 = 0x4E4F_534A;
/// Chunk type `BIN\0`.
pub(super) const CHUNK_BIN: u32 = 0x004E_4942;

/// The JSON text of a file and, for a GLB, its BIN chunk.
pub(super) struct Parts<'a> {
    pub json: &'a [u8],
    /// Byte offset of the JSON text in the file (20 in a GLB), for messages.
    pub json_offset: u64,
    pub bin: Option<&'a [u8]>,
}

fn u32_at(bytes: &[u8], at: usize) -> Option<u32> {
    let b = bytes.get(at..at.checked_add(4)?)?;
    Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
}

/// Splits a file into its JSON and BIN parts: a GLB (magic `glTF`) into its chunks, anything
/// else taken whole as JSON (a UTF-8 byte-order mark skipped).
///
/// # Errors
/// A bad GLB header (version, declared length) or chunk (length past the end, first chunk not
/// JSON), with its byte offset.
pub(super) fn split(bytes: &[u8]) -> Result<Parts<'_>> {
    if u32_at(bytes, 0) != Some(GLB_MAGIC) {
        let bom = if bytes.starts_with(b"\xEF\xBB\xBF") {
            3
        } else {
            0
        };
        return Ok(Parts {
            json: &bytes[bom..],
            json_offset: bom as u64,
            bin: None,
        });
    }
    let (Some(version), Some(length)) = (u32_at(bytes, 4), u32_at(bytes, 8)) else {
        return Err(byte_error(
            0,
            format!(
                "GLB header: the file has {} bytes, the header needs 12",
                bytes.len()
            ),
        ));
    };
    if version != 2 {
        return Err(byte_error(
            4,
            format!("GLB header: version {version}, only version 2 is read"),
        ));
    }
    if u64::from(length) != bytes.len() as u64 {
        return Err(byte_error(
            8,
            format!(
                "GLB header: the declared length {length} differs from the file's {} bytes",
                bytes.len()
            ),
        ));
    }
    let mut json = None;
    let mut bin = None;
    let mut at = 12usize;
    let mut index = 0usize;
    while at < bytes.len() {
        let (Some(len), Some(kind)) = (u32_at(bytes, at), u32_at(bytes, at + 4)) else {
            return Err(byte_error(
                at as u64,
                format!(
                    "GLB chunk {index}: its 8-byte header runs past the end of the file at {}",
                    bytes.len()
                ),
            ));
        };
        let start = at + 8;
        let end = start as u64 + u64::from(len);
        if end > bytes.len() as u64 {
            return Err(byte_error(
                at as u64,
                format!(
                    "GLB chunk {index}: length {len} runs past the end of the file ({} bytes \
                     left)",
                    bytes.len() - start
                ),
            ));
        }
        let data = &bytes[start..end as usize];
        match (index, kind) {
            (0, CHUNK_JSON) => json = Some((data, start as u64)),
            (0, _) => {
                return Err(byte_error(
                    at as u64 + 4,
                    format!("GLB chunk 0 has type {kind:#010x}; the first chunk must be JSON"),
                ))
            }
            (1, CHUNK_BIN) => bin = Some(data),
            // Later chunks, and chunks of other types, are to be ignored (glTF 2.0 §4.4.3).
            _ => {}
        }
        at = end as usize;
        index += 1;
    }
    let Some((json, json_offset)) = json else {
        return Err(byte_error(12, "GLB: no JSON chunk"));
    };
    Ok(Parts {
        json,
        json_offset,
        bin,
    })
}

/// Each buffer's bytes, exactly `byteLength` of them.
pub(super) struct Buffers<'a> {
    pub data: Vec<Cow<'a, [u8]>>,
    /// Bytes read from external files, counted in the input's size.
    pub external_bytes: u64,
}

/// Finds the data of every buffer that some buffer view uses, and checks every buffer view
/// against its buffer.
///
/// # Errors
/// A buffer that is missing, shorter than its `byteLength`, or in a bad `data:` URI; a view
/// outside its buffer or with a bad stride.
pub(super) fn load<'a>(
    doc: &Document,
    bin: Option<&'a [u8]>,
    external: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>,
) -> Result<Buffers<'a>> {
    // Only buffers that accessors read are loaded: an image's buffer may be left out.
    let mut used = vec![false; doc.buffers.len()];
    for a in &doc.accessors {
        let sparse = a
            .sparse
            .iter()
            .flat_map(|s| [s.indices_view, s.values_view]);
        for view in a.view.into_iter().chain(sparse) {
            used[doc.views[view].buffer] = true;
        }
    }
    let mut data = Vec::with_capacity(doc.buffers.len());
    let mut external_bytes = 0u64;
    for (i, buffer) in doc.buffers.iter().enumerate() {
        let path = format!("buffers[{i}]");
        if !used[i] {
            data.push(Cow::Borrowed(&[][..]));
            continue;
        }
        let bytes: Cow<'a, [u8]> = match (&buffer.uri, bin) {
            (None, Some(bin)) if i == 0 => Cow::Borrowed(bin),
            (None, _) => {
                return Err(json_error(
                    &path,
                    "no `uri` and no GLB BIN chunk to take its data from",
                ))
            }
            (Some(uri), _) => match uri.strip_prefix("data:") {
                Some(rest) => Cow::Owned(data_uri(&path, rest)?),
                None => {
                    if has_scheme(uri) {
                        return Err(json_error(
                            &format!("{path}.uri"),
                            format!(
                                "`{}`: only data: URIs and relative file paths are read",
                                escape(uri)
                            ),
                        ));
                    }
                    let name = base64::percent_decode(uri)
                        .map_err(|m| json_error(&format!("{path}.uri"), m))?;
                    let bytes = external(&name).map_err(|m| json_error(&path, m))?;
                    external_bytes += bytes.len() as u64;
                    Cow::Owned(bytes)
                }
            },
        };
        if (bytes.len() as u64) < buffer.byte_length {
            return Err(json_error(
                &path,
                format!(
                    "byteLength is {} but its data has only {} bytes",
                    buffer.byte_length,
                    bytes.len()
                ),
            ));
        }
        // byteLength fits in the data, so it fits in usize.
        data.push(match bytes {
            Cow::Borrowed(b) => Cow::Borrowed(&b[..buffer.byte_length as usize]),
            Cow::Owned(mut b) => {
                b.truncate(buffer.byte_length as usize);
                Cow::Owned(b)
            }
        });
    }
    for (i, v) in doc.views.iter().enumerate() {
        let path = format!("bufferViews[{i}]");
        let len = doc.buffers[v.buffer].byte_length;
        let end = v.byte_offset.checked_add(v.byte_length);
        if end.is_none_or(|end| end > len) {
            return Err(json_error(
                &path,
                format!(
                    "byteOffset {} + byteLength {} lies outside buffers[{}] of {len} bytes",
                    v.byte_offset, v.byte_length, v.buffer
                ),
            ));
        }
        if let Some(stride) = v.byte_stride {
            if !(4..=252).contains(&stride) || stride % 4 != 0 {
                return Err(json_error(
                    &format!("{path}.byteStride"),
                    format!("{stride} is not a multiple of 4 in 4..=252"),
                ));
            }
        }
    }
    Ok(Buffers {
        data,
        external_bytes,
    })
}

/// Whether a URI starts with a scheme (`http:`, `file:`): letters, digits, `+`, `-`, `.`, then
/// a colon, before any `/`.
fn has_scheme(uri: &str) -> bool {
    match uri.find(':') {
        Some(colon) => {
            let scheme = &uri[..colon];
            scheme.starts_with(|c: char| c.is_ascii_alphabetic())
                && scheme
                    .chars()
                    .all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
        }
        None => false,
    }
}

/// The bytes of a `data:` URI (after `data:`), which must be base64.
fn data_uri(path: &str, rest: &str) -> Result<Vec<u8>> {
    let uri_path = format!("{path}.uri");
    let Some((header, payload)) = rest.split_once(',') else {
        return Err(json_error(&uri_path, "a data: URI without a comma"));
    };
    if !header.ends_with(";base64") {
        return Err(json_error(
            &uri_path,
            format!(
                "data:{},... is not base64; only base64 data URIs are read",
                escape(header)
            ),
        ));
    }
    base64::decode(payload.as_bytes()).map_err(|m| json_error(&uri_path, m))
}
