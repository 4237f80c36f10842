//! The `PART` section (FORMAT.md §3.10): the parts' labels as JSON, then the part of every
//! triangle slot as a packed index.

use super::attributes::{bits_for, packed};
use super::le_u32;
use crate::words::Words;

/// Bytes of the header: `P`, `S`, `b`, `J`.
pub const HEADER_LEN: usize = 16;

/// The `PART` header, as stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct PartsHeader {
    /// Parts (`P`), at least 1.
    pub parts: u32,
    /// Triangle slots (`S`), as in `ATTR`.
    pub slots: u32,
    /// Bits per index (`b`): the fewest that hold `P − 1`.
    pub bits: u32,
    /// Bytes of the JSON (`J`).
    pub json_len: u32,
}

impl PartsHeader {
    /// The header at the start of `bytes` (at least [`HEADER_LEN`] long).
    pub fn parse(bytes: &[u8]) -> PartsHeader {
        PartsHeader {
            parts: le_u32(bytes, 0),
            slots: le_u32(bytes, 4),
            bits: le_u32(bytes, 8),
            json_len: le_u32(bytes, 12),
        }
    }

    /// The 16 bytes of the header.
    pub fn to_bytes(&self) -> Vec<u8> {
        [self.parts, self.slots, self.bits, self.json_len]
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect()
    }

    /// The bits an index needs for `parts` parts.
    pub fn bits_for_parts(parts: u32) -> u32 {
        bits_for(parts.saturating_sub(1))
    }

    /// The section's exact length, `None` beyond the address space.
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
