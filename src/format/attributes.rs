//! The `ATTR` section's records (FORMAT.md §3.9): one per attribute, a 32-byte header, the
//! name, the values, then the seam tables that say which corners do not take their vertex's
//! value. Shared by the writer and the reader, and answering "which value at this corner"
//! from owned tables or from the file's bytes alike.

use super::le_u32;
use crate::mesh::{ComponentType, Semantic};
use crate::words::Words;

/// Bytes of a record's header.
pub const RECORD_HEADER_LEN: usize = 32;
/// Triangles per word of the `RANK` directory: one u32 per 8 words of `FLAGS`.
pub const RANK_SPAN: u32 = 256;
/// Flag bit: integer components stand for fractions (glTF's `normalized`).
pub const NORMALIZED: u8 = 1;
/// Flag bit: the attribute is per corner (otherwise per vertex, with no seams).
pub const PER_CORNER: u8 = 2;

/// Seam encoding 0: the random-access tables `FLAGS`, `RANK` and `ENTRIES`.
pub const TABLE_SEAMS: u8 = 0;
/// Seam encoding 1 (Edgebreaker only): the value of every corner range coded (GEOMETRY.md §8).
pub const CODED_SEAMS: u8 = 1;

/// Normal predictor 0 (byte 22 of a record of predicted octahedral normals): from the
/// surface, then the neighbours (GEOMETRY.md §7.3).
pub const SURFACE_NORMALS: u8 = 0;
/// Normal predictor 1 (version 1.3): from the neighbours only, for surfaces whose coded
/// positions predict their normals badly (small triangles on a coarse grid).
pub const NEIGHBOUR_NORMALS: u8 = 1;

/// A record's header, as stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AttributeHeader {
    /// 0 custom, 1 normal, 2 texture coordinates, 3 color.
    pub semantic: u8,
    /// The set `n` of `TEXCOORD_n` and `COLOR_n`; 0 otherwise.
    pub set: u8,
    /// [`ComponentType`] code.
    pub component_type: u8,
    /// Components per value, 1 to 4.
    pub components: u8,
    /// [`NORMALIZED`] and [`PER_CORNER`].
    pub flags: u8,
    /// Bits per entry of `ENTRIES` (`b`): 0 when no triangle is flagged.
    pub entry_bits: u8,
    /// Bytes of the UTF-8 name (custom attributes only).
    pub name_len: u16,
    /// Extra values beyond the vertices' own (`E`).
    pub extra: u32,
    /// Flagged triangles (`F`).
    pub flagged: u32,
    /// Triangle slots covered (`S`): the connectivity's triangle ids, then the kept ones.
    pub slots: u32,
    /// The first word's low byte is the value encoding (0 raw, 1 quantized: see
    /// [`AttributeHeader::value_encoding`]); the rest is reserved, 0.
    pub reserved: [u32; 3],
}

/// Where a record's parts lie, in bytes from the record's start.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RecordLayout {
    /// The name.
    pub name: std::ops::Range<usize>,
    /// `V + E` values.
    pub values: std::ops::Range<usize>,
    /// `FLAGS`: one bit per slot, `⌈S/32⌉` words, when `F > 0`.
    pub flags: std::ops::Range<usize>,
    /// `RANK`: flagged slots before each span of 256, `⌈S/256⌉` words, when `F > 0`.
    pub rank: std::ops::Range<usize>,
    /// `ENTRIES`: `3F` entries of `b` bits, in `⌈3F·b/32⌉` words; with coded seams (seam
    /// encoding 1), `n` and the stream instead.
    pub entries: std::ops::Range<usize>,
}

impl RecordLayout {
    /// The record's length.
    pub fn len(&self) -> usize {
        self.entries.end
    }

    /// Whether the record is empty (never: the header alone is 32 bytes).
    pub fn is_empty(&self) -> bool {
        false
    }
}

impl AttributeHeader {
    /// The header at the start of `bytes` (at least [`RECORD_HEADER_LEN`] long).
    pub fn parse(bytes: &[u8]) -> AttributeHeader {
        AttributeHeader {
            semantic: bytes[0],
            set: bytes[1],
            component_type: bytes[2],
            components: bytes[3],
            flags: bytes[4],
            entry_bits: bytes[5],
            name_len: u16::from_le_bytes([bytes[6], bytes[7]]),
            extra: le_u32(bytes, 8),
            flagged: le_u32(bytes, 12),
            slots: le_u32(bytes, 16),
            reserved: [le_u32(bytes, 20), le_u32(bytes, 24), le_u32(bytes, 28)],
        }
    }

    /// The 32 bytes of the header.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = vec![
            self.semantic,
            self.set,
            self.component_type,
            self.components,
            self.flags,
            self.entry_bits,
        ];
        out.extend_from_slice(&self.name_len.to_le_bytes());
        for x in [self.extra, self.flagged, self.slots]
            .into_iter()
            .chain(self.reserved)
        {
            out.extend_from_slice(&x.to_le_bytes());
        }
        out
    }

    /// The semantic the codes stand for (`name` for a custom attribute); `None` for an
    /// unknown code.
    pub fn semantic(&self, name: &str) -> Option<Semantic> {
        match self.semantic {
            0 => Some(Semantic::Custom(name.to_string())),
            1 => Some(Semantic::Normal),
            2 => Some(Semantic::TexCoord(self.set)),
            3 => Some(Semantic::Color(self.set)),
            _ => None,
        }
    }

    /// Semantic code and set of `semantic`.
    pub fn codes(semantic: &Semantic) -> (u8, u8) {
        match semantic {
            Semantic::Custom(_) => (0, 0),
            Semantic::Normal => (1, 0),
            Semantic::TexCoord(n) => (2, *n),
            Semantic::Color(n) => (3, *n),
        }
    }

    /// The value encoding (FORMAT.md §3.9): the low byte of the first reserved word, 0 raw
    /// ([`RAW`](super::quantized::RAW)), 1 quantized ([`QUANTIZED`](super::quantized::QUANTIZED)).
    pub fn value_encoding(&self) -> u8 {
        self.reserved[0] as u8
    }

    /// The seam encoding (FORMAT.md §3.9): byte 21, the second byte of the first reserved
    /// word, [`TABLE_SEAMS`] or [`CODED_SEAMS`].
    pub fn seam_encoding(&self) -> u8 {
        (self.reserved[0] >> 8) as u8
    }

    /// The normal predictor (FORMAT.md §3.9): byte 22, the third byte of the first reserved
    /// word, [`SURFACE_NORMALS`] or [`NEIGHBOUR_NORMALS`].
    pub fn normal_predictor(&self) -> u8 {
        (self.reserved[0] >> 16) as u8
    }

    /// Bytes of the values part of a record of raw values (value encoding 0) for
    /// `vertices` container vertices; `None` for an unknown component type or an overflow.
    pub fn raw_values_len(&self, vertices: u32) -> Option<u64> {
        let size = ComponentType::from_code(self.component_type)?.size() as u64;
        (u64::from(vertices) + u64::from(self.extra)).checked_mul(u64::from(self.components) * size)
    }

    /// The layout of a record of raw values (value encoding 0) with the seam tables, for
    /// `vertices` container vertices; `None` for an unknown component type or sizes beyond
    /// the address space.
    pub fn layout(&self, vertices: u32) -> Option<RecordLayout> {
        self.layout_with_values(self.raw_values_len(vertices)?)
    }

    /// The layout of a record with the seam tables when its values part takes `values` bytes.
    pub fn layout_with_values(&self, values: u64) -> Option<RecordLayout> {
        self.layout_with_parts(values, None)
    }

    /// The layout of the record when its values part takes `values` bytes and, for coded
    /// seams (seam encoding 1), the seam part `coded` bytes (its length `n` included): they
    /// take the place of `ENTRIES`, with no `FLAGS` or `RANK`.
    pub fn layout_with_parts(&self, values: u64, coded: Option<u64>) -> Option<RecordLayout> {
        let name_end = RECORD_HEADER_LEN as u64 + u64::from(self.name_len);
        let values_end = name_end + values;
        let (flags, rank, entries) = match coded {
            Some(n) => (0, 0, n),
            None if self.flagged == 0 => (0, 0, 0),
            None => {
                let s = u64::from(self.slots);
                let bits = 3 * u64::from(self.flagged) * u64::from(self.entry_bits);
                (
                    4 * s.div_ceil(32),
                    4 * s.div_ceil(256),
                    4 * bits.div_ceil(32),
                )
            }
        };
        let flags_end = values_end + flags;
        let rank_end = flags_end + rank;
        let entries_end = rank_end + entries;
        let at = |x: u64| usize::try_from(x).ok();
        Some(RecordLayout {
            name: RECORD_HEADER_LEN..at(name_end)?,
            values: at(name_end)?..at(values_end)?,
            flags: at(values_end)?..at(flags_end)?,
            rank: at(flags_end)?..at(rank_end)?,
            entries: at(rank_end)?..at(entries_end)?,
        })
    }
}

/// The seam tables of one attribute: which slots are flagged, and the entries of the
/// flagged ones. Answers in constant time.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Seams<W> {
    /// `FLAGS`.
    pub flags: W,
    /// `RANK`.
    pub rank: W,
    /// `ENTRIES`.
    pub entries: W,
    /// Bits per entry.
    pub bits: u32,
}

impl<W: Words> Seams<W> {
    /// Whether slot `t` is flagged.
    #[inline]
    pub fn is_flagged(&self, t: u32) -> bool {
        self.flags.count() > 0 && self.flags.at(t as usize / 32) >> (t % 32) & 1 == 1
    }

    /// Flagged slots before slot `t`.
    #[inline]
    pub fn rank(&self, t: u32) -> u32 {
        let word = t as usize / 32;
        let span = t / RANK_SPAN;
        let mut r = self.rank.at(span as usize);
        for w in (span as usize * 8)..word {
            r += self.flags.at(w).count_ones();
        }
        r + (self.flags.at(word) & ((1u32 << (t % 32)) - 1)).count_ones()
    }

    /// Entry `j` of `ENTRIES`.
    #[inline]
    pub fn entry(&self, j: u32) -> u32 {
        packed(&self.entries, j, self.bits)
    }

    /// The value index at corner `k` of slot `t`, whose vertex is `v`, among `vertices`
    /// container vertices: `v` unless the slot is flagged and its entry `e` is not 0, then
    /// `vertices + e − 1`.
    #[inline]
    pub fn value_index(&self, t: u32, k: usize, v: u32, vertices: u32) -> u32 {
        if !self.is_flagged(t) {
            return v;
        }
        match self.entry(3 * self.rank(t) + k as u32) {
            0 => v,
            e => vertices + e - 1,
        }
    }
}

/// Field `j` of `bits` bits (1 to 32) packed in little-endian words: bits `j·bits ..
/// j·bits + bits` of the stream where bit `i` is bit `i mod 32` of word `⌊i/32⌋`.
#[inline]
pub fn packed<W: Words>(words: &W, j: u32, bits: u32) -> u32 {
    let bit = u64::from(j) * u64::from(bits);
    let word = (bit / 32) as usize;
    let shift = bit % 32;
    let lo = u64::from(words.at(word));
    let hi = if shift + u64::from(bits) > 32 {
        u64::from(words.at(word + 1))
    } else {
        0
    };
    (((hi << 32 | lo) >> shift) & ((1u64 << bits) - 1)) as u32
}

/// The seam tables of seam encoding 0 for `slots` triangle slots, from the entries of the
/// flagged slots in increasing slot order: `FLAGS`, `RANK`, and `ENTRIES` packed in `bits`
/// bits each. The writer stores them; a reader of coded seams decodes into them.
pub fn tables_of(slots: u32, flagged: &[(u32, [u32; 3])], bits: u32) -> [Vec<u32>; 3] {
    let mut flags = vec![0u32; slots.div_ceil(32) as usize];
    let mut entries = Vec::with_capacity(3 * flagged.len());
    for (slot, triple) in flagged {
        flags[*slot as usize / 32] |= 1 << (slot % 32);
        entries.extend(triple);
    }
    let rank = flags
        .chunks(RANK_SPAN as usize / 32)
        .scan(0u32, |before, words| {
            let r = *before;
            *before += words.iter().map(|w| w.count_ones()).sum::<u32>();
            Some(r)
        })
        .collect();
    let entries = pack(&entries, bits);
    [flags, rank, entries]
}

/// Packs `fields` of `bits` bits each (1 to 32) as [`packed`] reads them.
pub fn pack(fields: &[u32], bits: u32) -> Vec<u32> {
    let total = fields.len() as u64 * u64::from(bits);
    let mut words = vec![0u32; total.div_ceil(32) as usize];
    for (j, &x) in fields.iter().enumerate() {
        let bit = j as u64 * u64::from(bits);
        let (word, shift) = ((bit / 32) as usize, bit % 32);
        let wide = u64::from(x) << shift;
        words[word] |= wide as u32;
        if shift + u64::from(bits) > 32 {
            words[word + 1] |= (wide >> 32) as u32;
        }
    }
    words
}

/// Bits needed to store every number up to `max` (0 for `max = 0`).
pub fn bits_for(max: u32) -> u32 {
    32 - max.leading_zeros()
}

/// The minor version an `ATTR` payload of a container of `vertices` vertices needs: 3 with a
/// record whose normals are predicted from their neighbours only; 2 with value encoding 1
/// or 2 (quantized, predicted) or seam encoding 1 (coded); else 1. Walks the records as far
/// as they are well formed.
pub fn minor_version(payload: &[u8], vertices: u32) -> u16 {
    let count = if payload.len() >= 4 {
        le_u32(payload, 0)
    } else {
        0
    };
    let mut at = 4usize;
    let mut minor = 1;
    for _ in 0..count {
        if payload.len() - at < RECORD_HEADER_LEN {
            break;
        }
        let h = AttributeHeader::parse(&payload[at..]);
        if h.normal_predictor() != SURFACE_NORMALS {
            return 3;
        }
        if h.value_encoding() != super::quantized::RAW || h.seam_encoding() != TABLE_SEAMS {
            minor = 2;
        }
        match record_len(payload, at, vertices) {
            Some(len) => at += len,
            None => break,
        }
    }
    minor
}

/// Bytes of the record at `at` of an `ATTR` payload in a container of `vertices` vertices,
/// whatever its value and seam encodings, read from its header and length fields (FORMAT.md
/// §3.9); `None` when they do not fit the payload or the encoding is unknown.
pub fn record_len(payload: &[u8], at: usize, vertices: u32) -> Option<usize> {
    use super::quantized::{PREDICTED, QUANTIZED, RAW};
    let rest = payload.get(at..)?;
    if rest.len() < RECORD_HEADER_LEN {
        return None;
    }
    let h = AttributeHeader::parse(rest);
    let start = RECORD_HEADER_LEN + usize::from(h.name_len);
    let u32_at = |i: usize| (i + 4 <= rest.len()).then(|| le_u32(rest, i));
    // A quantizer's header: `b`, then for a grid (any semantic but normals) `lo` and `size`.
    let quantizer = if h.semantic == 1 {
        1
    } else {
        1 + 4 * usize::from(h.components) + 4
    };
    let values = match h.value_encoding() {
        RAW => h.raw_values_len(vertices)?,
        QUANTIZED => {
            let bits = u64::from(*rest.get(start)?);
            let fields = if h.semantic == 1 {
                2
            } else {
                u64::from(h.components)
            };
            let count = u64::from(vertices) + u64::from(h.extra);
            quantizer as u64 + 4 * (count * fields * bits).div_ceil(32)
        }
        PREDICTED => quantizer as u64 + 4 + u64::from(u32_at(start + quantizer)?),
        _ => return None,
    };
    let coded = match h.seam_encoding() {
        TABLE_SEAMS => None,
        CODED_SEAMS => {
            let end = usize::try_from(start as u64 + values).ok()?;
            Some(4 + u64::from(u32_at(end)?))
        }
        _ => return None,
    };
    let len = h.layout_with_parts(values, coded)?.len();
    (len <= rest.len()).then_some(len)
}
