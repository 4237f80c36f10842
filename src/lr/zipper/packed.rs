//! The Zipper's lists as bit fields (`ZIPR` flag `PACKED_LISTS`, version 1.10): each element
//! of the exception, record, pair, T0 and `C` lists in as many bits as the mesh's counts
//! call for, instead of a 32-bit word. On a mesh of a few thousand vertices a vertex takes
//! 12 bits, not 32: the lists are most of the Zipper on meshes with borders and T0
//! triangles (FORMAT.md §3.5e).
//!
//! [`Packed`] reads a field and returns the word the unpacked layout stores, so that every
//! operator and every rule reads the same words either way.

use crate::words::Words;

/// How a field maps to the word of the unpacked layout (FORMAT.md §3.5e).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FieldKind {
    /// The word itself.
    Plain,
    /// A vertex with the WART flag in the field's top bit (the word's bit 30).
    Flagged,
    /// A corner plus one, 0 for `NONE` (`0xFFFFFFFF`).
    Corner,
    /// A record's second word: its state in the field's top two bits (the word's bits
    /// 30–31), its value below.
    Stated,
    /// A two's complement number of the field's width, as a 32-bit two's complement word
    /// (a compact head's anchor offset, FORMAT.md §3.5e.3); width 0 is the value 0.
    Signed,
    /// A record's second word with `ROW_RECORDS` (FORMAT.md §3.5e.5): the field's top bit
    /// set for state 3 (a pair), clear for state 1 (a T0 row), the value below.
    RowOrPair,
}

/// One field: its width in bits (0 to 32) and kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Field {
    /// Bits per field.
    pub width: u8,
    /// How it maps to a word.
    pub kind: FieldKind,
}

impl Field {
    /// A 32-bit word of the unpacked layout.
    pub const WORD: Field = Field {
        width: 32,
        kind: FieldKind::Plain,
    };

    /// The word a field's bits stand for.
    #[inline(always)]
    fn decode(self, f: u32) -> u32 {
        match self.kind {
            FieldKind::Plain => f,
            FieldKind::Flagged => {
                let top = self.width as u32 - 1;
                (f & low_bits(top)) | (f >> top & 1) << 30
            }
            FieldKind::Corner => f.wrapping_sub(1),
            FieldKind::Stated => {
                let top = self.width as u32 - 2;
                (f & low_bits(top)) | (f >> top) << 30
            }
            FieldKind::Signed => {
                let shift = 32u32.saturating_sub(self.width as u32);
                (((f as u64) << shift) as u32 as i32)
                    .checked_shr(shift)
                    .unwrap_or(0) as u32
            }
            FieldKind::RowOrPair => {
                let top = self.width as u32 - 1;
                (f & low_bits(top)) | (1 | (f >> top & 1) << 1) << 30
            }
        }
    }

    /// The field for a word, `None` when the word does not fit.
    fn encode(self, word: u32) -> Option<u32> {
        let f = match self.kind {
            FieldKind::Plain => word,
            FieldKind::Flagged => {
                let top = self.width as u32 - 1;
                if word & low_bits(30) > low_bits(top) || word >> 31 != 0 {
                    return None;
                }
                (word & low_bits(30)) | (word >> 30 & 1) << top
            }
            FieldKind::Corner => word.wrapping_add(1),
            FieldKind::Stated => {
                let top = self.width as u32 - 2;
                if word & low_bits(30) > low_bits(top) {
                    return None;
                }
                (word & low_bits(30)) | (word >> 30) << top
            }
            FieldKind::Signed => {
                let f = word & low_bits(self.width as u32);
                if self.decode(f) != word {
                    return None;
                }
                f
            }
            FieldKind::RowOrPair => {
                let top = self.width as u32 - 1;
                if word & low_bits(30) > low_bits(top) || word >> 30 & 1 == 0 {
                    return None;
                }
                (word & low_bits(30)) | (word >> 31) << top
            }
        };
        (f <= low_bits(self.width as u32)).then_some(f)
    }
}

/// Bits `0..n` set (`n` up to 32).
#[inline(always)]
fn low_bits(n: u32) -> u32 {
    ((1u64 << n) - 1) as u32
}

/// Bits needed to write `x`.
fn bits(x: u64) -> u32 {
    64 - x.leading_zeros()
}

/// The fields of the seven lists, in file order: `EXCEPTIONS`, `RECORDS` (word 0, word 1),
/// `PAIRS`, `T0_V`, `T0_CODES`, `EXPLICIT`, `C`; each pair gives the fields of even and odd
/// elements. Words of 32 bits without the header's flag `PACKED_LISTS` (in `flags`); with
/// it, from the header's counts (FORMAT.md §3.5e): `m` vertices, `m_r` ring vertices, `n0`
/// T0 rows, `pairs` opposite pairs, `explicit` explicit T0 opposites, and with
/// `ROW_RECORDS` (version 1.15) a record's second word a T0 row or a pair's index and a
/// bit, with `IMPLIED_WARTS` a tip without the WART flag.
pub fn list_fields(
    flags: u32,
    m: u32,
    m_r: u32,
    n0: u32,
    pairs: u32,
    explicit: u32,
) -> [[Field; 2]; 7] {
    use crate::format::layout::{ZIPPER_IMPLIED_WARTS, ZIPPER_PACKED_LISTS, ZIPPER_ROW_RECORDS};
    if flags & ZIPPER_PACKED_LISTS == 0 {
        return [[Field::WORD; 2]; 7];
    }
    let field = |width: u32, kind| Field {
        width: width as u8,
        kind,
    };
    let vertex = bits((m as u64).saturating_sub(1)).min(30);
    let flagged = match flags & ZIPPER_IMPLIED_WARTS != 0 {
        true => field(vertex, FieldKind::Plain),
        false => field(vertex + 1, FieldKind::Flagged),
    };
    let corner = field(
        bits(8 * m_r as u64 + 4 * n0 as u64).min(32),
        FieldKind::Corner,
    );
    let stated = match flags & ZIPPER_ROW_RECORDS != 0 {
        true => {
            let values = (n0 as u64).max(pairs as u64).saturating_sub(1);
            field(1 + bits(values).min(30), FieldKind::RowOrPair)
        }
        false => {
            let values = (4 * n0 as u64).max(pairs as u64).saturating_sub(1);
            field(2 + bits(values).min(30), FieldKind::Stated)
        }
    };
    let codes = field(6 + bits(explicit as u64).min(26), FieldKind::Plain);
    let vertex = field(vertex, FieldKind::Plain);
    [
        [flagged; 2],
        [flagged, stated],
        [corner; 2],
        [vertex; 2],
        [codes; 2],
        [corner; 2],
        [corner; 2],
    ]
}

/// The field of `RING_BLOCKS` (FORMAT.md §3.5e, version 1.12): a ring index below `rings`,
/// in `bits(rings − 1)` bits.
pub fn ring_block_field(rings: u32) -> Field {
    Field {
        width: bits((rings as u64).saturating_sub(1)) as u8,
        kind: FieldKind::Plain,
    }
}

/// The bits of `parts` (each its words and how many of their bits it uses, from bit 0)
/// one after the other, padded with zeros to a whole word (`JOINED_LISTS`, FORMAT.md
/// §3.5e.6).
pub fn join_bits(parts: &[(&[u32], u64)]) -> Vec<u32> {
    let total: u64 = parts.iter().map(|&(_, bits)| bits).sum();
    let mut out = vec![0u32; total.div_ceil(32) as usize];
    let mut at = 0u64;
    for &(words, bits) in parts {
        for b in 0..bits {
            let bit = words[(b / 32) as usize] >> (b % 32) & 1;
            out[((at + b) / 32) as usize] |= bit << ((at + b) % 32);
        }
        at += bits;
    }
    out
}

/// A compact `ZIPR` section `p` with `JOINED_LISTS` laid out again without it: each of the
/// nine bit lists from a word of its own, as version 1.15 lays them out, the same fields in
/// each (for a reader of that version, or a tool that edits one list). `None` when the
/// section does not have the flag or is shorter than its counts call for.
pub fn unjoined_zipr(p: &[u8]) -> Option<Vec<u8>> {
    use crate::format::layout::{ZiprHeader, ZIPPER_JOINED_LISTS};
    let header = ZiprHeader::read(p);
    let bits = header.joined_bits()?;
    let heads = header.layout()?.arrays[4];
    let stream = p.get(heads.start..heads.end())?;
    let mut out_header = header;
    out_header.flags &= !ZIPPER_JOINED_LISTS;
    let mut out = out_header.to_bytes();
    out.extend_from_slice(p.get(header.header_len()..heads.start)?);
    for q in 0..9 {
        let (from, to) = (bits[q], bits[q + 1]);
        let mut words = vec![0u32; (to - from).div_ceil(32) as usize];
        for b in 0..to - from {
            let at = from + b;
            let bit = (stream[(at / 8) as usize] >> (at % 8) & 1) as u32;
            words[(b / 32) as usize] |= bit << (b % 32);
        }
        out.extend(words.iter().flat_map(|w| w.to_le_bytes()));
    }
    // The seven lists took no words of their own: SUPER follows the stream.
    out.extend_from_slice(&p[heads.end()..]);
    Some(out)
}

/// Words that `count` elements of `fields` take (even elements of `fields[0]`, odd of
/// `fields[1]`).
pub fn packed_words(count: u64, fields: [Field; 2]) -> u64 {
    first_bit(fields, count).div_ceil(32)
}

/// The first bit of element `i` of a list of `fields` (even elements of `fields[0]`, odd of
/// `fields[1]`); for `i` the list's length, the bits it takes.
#[inline(always)]
pub fn first_bit(fields: [Field; 2], i: u64) -> u64 {
    let [a, b] = fields.map(|f| f.width as u64);
    i / 2 * (a + b) + i % 2 * a
}

/// A list of fields over words `W`, read as the words of the unpacked layout.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Packed<W> {
    /// The stored words.
    pub(crate) words: W,
    /// Elements (a list of zero-width fields may have more than 2^32 in a small file).
    len: usize,
    /// Fields of even and odd elements.
    fields: [Field; 2],
    /// The bit of the first word where element 0 starts (below 32; 0 but for the lists of
    /// a stream of `JOINED_LISTS`).
    start: u8,
}

impl<W: Words> Packed<W> {
    /// `len` elements of `fields` in `words`, which must hold [`packed_words`] of them.
    pub fn new(words: W, len: usize, fields: [Field; 2]) -> Packed<W> {
        Packed::new_at(words, 0, len, fields)
    }

    /// As [`Packed::new`], element 0 at bit `start` (below 32) of the first word: `words`
    /// must hold the bits from there.
    pub fn new_at(words: W, start: u8, len: usize, fields: [Field; 2]) -> Packed<W> {
        debug_assert!(start < 32);
        debug_assert_eq!(
            words.count() as u64,
            (start as u64 + first_bit(fields, len as u64)).div_ceil(32)
        );
        Packed {
            words,
            len,
            fields,
            start,
        }
    }

    /// The first bit of element `i` (from bit 0 of the first word).
    #[inline(always)]
    pub fn bit(&self, i: usize) -> u64 {
        self.start as u64 + first_bit(self.fields, i as u64)
    }

    /// Whether the bits of the last word past the last element are 0.
    pub fn padding_is_zero(&self) -> bool {
        let used = (self.bit(self.len) % 32) as u32;
        used == 0 || self.words.at(self.words.count() - 1) >> used == 0
    }

    /// The bits the elements take (from element 0's first bit).
    pub fn bits(&self) -> u64 {
        first_bit(self.fields, self.len as u64)
    }

    /// The stored words.
    pub fn words(&self) -> &W {
        &self.words
    }

    /// The width of the even elements' field.
    pub fn field_width(&self) -> u8 {
        self.fields[0].width
    }

    /// The fields of even and odd elements.
    pub fn fields(&self) -> [Field; 2] {
        self.fields
    }

    /// The words every element stands for, in order: one pass over the stored words, each
    /// read once (the readers' linear checks).
    pub fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        let (mut next_word, mut buffer, mut have) = match self.start {
            0 => (0usize, 0u64, 0u32),
            s => (1, (self.words.at(0) >> s) as u64, 32 - s as u32),
        };
        (0..self.len).map(move |i| {
            let field = self.fields[i % 2];
            let width = field.width as u32;
            if have < width {
                buffer |= (self.words.at(next_word) as u64) << have;
                next_word += 1;
                have += 32;
            }
            let f = buffer as u32 & low_bits(width);
            buffer >>= width;
            have -= width;
            field.decode(f)
        })
    }

    /// The same list over other words (the same fields).
    pub fn map_words<'s, V: Words>(&'s self, f: impl FnOnce(&'s W) -> V) -> Packed<V> {
        Packed {
            words: f(&self.words),
            len: self.len,
            fields: self.fields,
            start: self.start,
        }
    }
}

impl Packed<Vec<u32>> {
    /// Packs the words of the unpacked layout; `None` when one does not fit its field.
    pub fn pack(words: &[u32], fields: [Field; 2]) -> Option<Packed<Vec<u32>>> {
        let count = packed_words(words.len() as u64, fields) as usize;
        let mut out = vec![0u32; count];
        let mut bit = 0u64;
        for (i, &word) in words.iter().enumerate() {
            let field = fields[i % 2];
            let f = field.encode(word)? as u64;
            let (k, s) = ((bit / 32) as usize, bit % 32);
            if field.width > 0 {
                let wide = f << s;
                out[k] |= wide as u32;
                if s + field.width as u64 > 32 {
                    out[k + 1] |= (wide >> 32) as u32;
                }
            }
            bit += field.width as u64;
        }
        Some(Packed {
            words: out,
            len: words.len(),
            fields,
            start: 0,
        })
    }
}

impl<W: Words> Words for Packed<W> {
    /// The word of the unpacked layout that element `i` stands for.
    #[inline(always)]
    fn at(&self, i: usize) -> u32 {
        assert!(i < self.len, "element {i} of a list of {}", self.len);
        let field = self.fields[i % 2];
        if field.width == 0 {
            return field.decode(0);
        }
        let bit = self.bit(i);
        let (k, s) = ((bit / 32) as usize, (bit % 32) as u32);
        // Both words whether or not the field reaches the second (a branch on it is taken
        // at random); the last word has none after it.
        let f = self.words.pair(k) >> s;
        field.decode(f as u32 & low_bits(field.width as u32))
    }

    fn count(&self) -> usize {
        self.len
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::layout::ZIPPER_PACKED_LISTS as P;

    #[test]
    fn packed_lists_give_back_their_words() {
        let lists = list_fields(P, 5000, 4800, 300, 7, 20);
        let samples: [Vec<u32>; 7] = [
            vec![0, 4999, 4999 | 1 << 30, 17],
            vec![4999 | 1 << 30, 3 << 30 | 6, 12, 1 << 30 | 1199, 0, 0],
            vec![0xFFFF_FFFF, 8 * 4800 + 4 * 300 - 1, 0, 5],
            vec![0, 1, 4999],
            vec![0b11_0000 | 20 << 6, 1],
            vec![0xFFFF_FFFF, 3],
            vec![],
        ];
        for (fields, words) in lists.into_iter().zip(samples) {
            let packed = Packed::pack(&words, fields).unwrap();
            let back: Vec<u32> = (0..words.len()).map(|i| packed.at(i)).collect();
            assert_eq!(back, words, "{fields:?}");
            assert_eq!(packed.iter().collect::<Vec<_>>(), words, "{fields:?}");
            assert!(packed.padding_is_zero());
        }
    }

    #[test]
    fn widths_follow_the_counts() {
        let [exceptions, records, pairs, t0_v, codes, explicit, c] =
            list_fields(P, 5000, 4800, 300, 7, 20);
        assert_eq!(exceptions[0].width, 14);
        assert_eq!(records.map(|f| f.width), [14, 2 + 11]);
        assert_eq!(pairs[0].width, 16);
        assert_eq!(t0_v[0].width, 13);
        assert_eq!(codes[0].width, 6 + 5);
        assert_eq!([explicit[0].width, c[0].width], [16, 16]);
        assert_eq!(list_fields(0, 5, 4, 0, 0, 0), [[Field::WORD; 2]; 7]);
    }

    #[test]
    fn words_that_do_not_fit_are_refused() {
        let [exceptions, records, ..] = list_fields(P, 16, 16, 1, 0, 0);
        assert!(Packed::pack(&[16], exceptions).is_none());
        assert!(Packed::pack(&[1 << 31], exceptions).is_none());
        assert!(Packed::pack(&[0, 1 << 30 | 4], records).is_none());
        assert!(Packed::pack(&[0, 1 << 30 | 3], records).is_some());
    }

    #[test]
    fn nonzero_padding_is_seen() {
        let [exceptions, ..] = list_fields(P, 16, 16, 1, 0, 0);
        let mut packed = Packed::pack(&[3, 5], exceptions).unwrap();
        packed.words[0] |= 1 << 20;
        assert!(!packed.padding_is_zero());
    }
}
