//! The `PART` section (FORMAT.md §3.10): the parts' labels as JSON or coded (`labels`), then the part of every
//! triangle slot, as packed indices (index encoding 0) or as range-coded runs (1).

use super::attributes::{bits_for, packed};
use super::le_u32;
use crate::words::Words;

/// Bytes of the header: `P`, `S`, `b`, the index and labels encodings, `J`.
pub const HEADER_LEN: usize = 16;
/// Index encoding 0: `b` bits per slot, read in place.
pub const PACKED: u8 = 0;
/// Index encoding 1 (version 1.2): runs of slots with one part, range coded.
pub const RUNS: u8 = 1;

/// The `PART` header, as stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PartsHeader {
    /// Parts (`P`), at least 1.
    pub parts: u32,
    /// Triangle slots (`S`), as in `ATTR`.
    pub slots: u32,
    /// Bits per index (`b`): the fewest that hold `P − 1`.
    pub bits: u32,
    /// How the indices are stored: [`PACKED`] or [`RUNS`].
    pub encoding: u8,
    /// How the labels are stored: [`super::labels::JSON`] or [`super::labels::CODED`]
    /// (byte 10, version 1.3).
    pub labels: u8,
    /// Byte 11, reserved: 0.
    pub reserved: u8,
    /// Bytes of the JSON (`J`).
    pub json_len: u32,
}

impl PartsHeader {
    /// The header at the start of `bytes` (at least [`HEADER_LEN`] long).
    pub fn parse(bytes: &[u8]) -> PartsHeader {
        PartsHeader {
            parts: le_u32(bytes, 0),
            slots: le_u32(bytes, 4),
            bits: u32::from(bytes[8]),
            encoding: bytes[9],
            labels: bytes[10],
            reserved: bytes[11],
            json_len: le_u32(bytes, 12),
        }
    }

    /// The 16 bytes of the header.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(HEADER_LEN);
        out.extend_from_slice(&self.parts.to_le_bytes());
        out.extend_from_slice(&self.slots.to_le_bytes());
        out.extend_from_slice(&[self.bits as u8, self.encoding, self.labels, self.reserved]);
        out.extend_from_slice(&self.json_len.to_le_bytes());
        out
    }

    /// The bits an index needs for `parts` parts.
    pub fn bits_for_parts(parts: u32) -> u32 {
        bits_for(parts.saturating_sub(1))
    }

    /// The section's exact length with packed indices (encoding 0), `None` beyond the
    /// address space.
    pub fn len(&self) -> Option<usize> {
        let words = (u64::from(self.slots) * u64::from(self.bits)).div_ceil(32);
        usize::try_from(HEADER_LEN as u64 + u64::from(self.json_len) + 4 * words).ok()
    }

    /// Whether the section would be empty (never: the header is 16 bytes).
    pub fn is_empty(&self) -> bool {
        false
    }
}

/// The part of slot `t` from the packed indices.
#[inline]
pub fn part_of<W: Words>(indices: &W, bits: u32, t: u32) -> u32 {
    if bits == 0 {
        0
    } else {
        packed(indices, t, bits)
    }
}

/// The runs stream of `index` (FORMAT.md §3.10.1): per run of slots with one part, its part
/// and its length − 1 as adaptive Elias gamma integers.
pub(crate) fn encode_runs(index: &[u32]) -> Vec<u8> {
    use crate::edgebreaker::coder::{code_uint, Encoder, UintModel};
    let (mut e, mut part, mut run) = (Encoder::new(), UintModel::default(), UintModel::default());
    let mut at = 0;
    while at < index.len() {
        let p = index[at];
        let len = index[at..].iter().take_while(|&&x| x == p).count();
        code_uint(&mut e, &mut part, u64::from(p));
        code_uint(&mut e, &mut run, len as u64 - 1);
        at += len;
    }
    e.finish()
}

/// The part of each of `slots` slots from a runs stream (at byte `base` of the file, for
/// errors); `Err((offset, message))` for a part not below `parts`, a run past the last
/// slot, or an overrun.
pub(crate) fn decode_runs(
    stream: &[u8],
    base: usize,
    slots: u32,
    parts: u32,
) -> Result<Vec<u32>, (u64, String)> {
    use crate::edgebreaker::coder::{code_uint, Bits, Decoder, UintModel};
    let (mut d, mut part, mut run) = (
        Decoder::new(stream, base),
        UintModel::default(),
        UintModel::default(),
    );
    let mut index = Vec::with_capacity(slots as usize);
    while index.len() < slots as usize {
        let at = d.offset();
        let p = code_uint(&mut d, &mut part, 0).filter(|&p| p < u64::from(parts));
        let Some(p) = p else {
            return Err((
                at,
                format!("slot {}: a part not below {parts}", index.len()),
            ));
        };
        let left = slots as usize - index.len();
        let len = code_uint(&mut d, &mut run, 0).filter(|&l| l < left as u64);
        let Some(len) = len else {
            return Err((
                at,
                format!("slot {}: a run past the last of {slots} slots", index.len()),
            ));
        };
        if d.overrun() {
            return Err((
                d.offset(),
                format!("the stream ends before slot {}", index.len()),
            ));
        }
        index.extend(std::iter::repeat_n(p as u32, len as usize + 1));
    }
    Ok(index)
}
