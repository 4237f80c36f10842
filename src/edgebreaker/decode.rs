//! Decompression: header, topology stream, then the reverse pass over the CLERS stream.

use super::coder::{max_decisions, Bits, Decoder};
use super::rebuild::{rebuild, Unknown};
use super::topology::code_topology;
use super::{malformed, Decoded, Limits, MAGIC, VERSION};
use crate::error::Result;

/// Reads a LEB128 integer at `*pos`.
fn leb128(bytes: &[u8], pos: &mut usize, what: &str) -> Result<u64> {
    let start = *pos;
    let mut x = 0u64;
    for shift in (0..64).step_by(7) {
        let Some(&byte) = bytes.get(*pos) else {
            return Err(malformed(
                start as u64,
                format!("header ends inside the {what}"),
            ));
        };
        *pos += 1;
        let bits = (byte & 0x7F) as u64;
        if shift == 63 && bits > 1 {
            break;
        }
        x |= bits << shift;
        if byte & 0x80 == 0 {
            return Ok(x);
        }
    }
    Err(malformed(
        start as u64,
        format!("{what} does not fit 64 bits"),
    ))
}

/// Decodes an Edgebreaker stream made by [`super::encode`].
///
/// Triangles and vertices come in decode order, which is the order of
/// [`super::Encoded::triangle_order`] and [`super::Encoded::vertex_order`].
///
/// Never panics, whatever the bytes. Memory is allocated only after the declared counts have
/// passed `limits` and a bound from the input length (at most 4290 triangles per input byte:
/// every coded decision costs at least 1/180 bit, and every triangle but the first and last
/// of each component and the handle `S` needs one); decoding time is linear in the triangles.
///
/// # Errors
/// [`crate::Error::Parse`] (format `"Edgebreaker"`) with the byte offset and what is wrong,
/// when the stream is malformed, truncated or exceeds `limits`.
pub fn decode(bytes: &[u8], limits: &Limits) -> Result<Decoded> {
    decode_glued(bytes, limits).map(|(decoded, _)| decoded)
}

/// [`decode`], with the opposite of every corner as the pass glued it (`NONE` at a free
/// edge): what [`crate::CornerTable::from_glued`] needs.
pub(crate) fn decode_glued(bytes: &[u8], limits: &Limits) -> Result<(Decoded, Vec<u32>)> {
    if bytes.len() < 2 || bytes[0] != MAGIC {
        return Err(malformed(0, "not an Edgebreaker stream (bad magic byte)"));
    }
    if bytes[1] != VERSION {
        return Err(malformed(
            1,
            format!(
                "unsupported version {} (this decoder reads {VERSION})",
                bytes[1]
            ),
        ));
    }
    let mut pos = 2;
    let nv = leb128(bytes, &mut pos, "vertex count")?;
    let unreferenced = leb128(bytes, &mut pos, "unreferenced vertex count")?;
    let nt = leb128(bytes, &mut pos, "triangle count")?;
    let topo_len = leb128(bytes, &mut pos, "topology stream length")?;
    if nv > limits.max_vertices || nv >= u32::MAX as u64 {
        return Err(malformed(2, format!("{nv} vertices exceed the limit")));
    }
    if nt > limits.max_triangles || nt >= (u32::MAX / 3) as u64 {
        return Err(malformed(2, format!("{nt} triangles exceed the limit")));
    }
    if unreferenced > nv {
        return Err(malformed(2, "more unreferenced vertices than vertices"));
    }
    let referenced = nv - unreferenced;
    if referenced > 3 * nt || (nt > 0 && referenced < 3) {
        return Err(malformed(
            2,
            format!("{referenced} referenced vertices cannot belong to {nt} triangles"),
        ));
    }
    let rest = bytes.len() - pos;
    if topo_len > rest as u64 {
        return Err(malformed(pos as u64, "topology stream runs past the end"));
    }
    // Each triangle but the implicit ones costs a decision; each component and handle several.
    if nt > 3 * max_decisions(rest) {
        return Err(malformed(
            2,
            format!("{nt} triangles cannot be coded in {rest} bytes"),
        ));
    }
    let (topo_bytes, clers_bytes) = bytes[pos..].split_at(topo_len as usize);
    let mut td = Decoder::new(topo_bytes, pos);
    let topology = code_topology(&mut td, None, nt as u32)?;
    if td.overrun() {
        return Err(malformed(td.offset(), "topology stream ends early"));
    }
    let mut cd = Decoder::new(clers_bytes, pos + topo_len as usize);
    let rebuilt = rebuild(
        &mut cd,
        &mut Unknown,
        &topology,
        (nt as u32, referenced as u32),
        true,
    )?;
    let decoded = Decoded {
        vertex_count: nv as u32,
        triangles: rebuilt.triangles,
    };
    Ok((decoded, rebuilt.opposites))
}
