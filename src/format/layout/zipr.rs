//! The `ZIPR` section's header (FORMAT.md §3.5e): its fields, flags and array layout in
//! every form (plain, packed lists, compact), described once for the writer and the reader.

use super::{le_u32, read_fields, write_fields, Layout};

/// `ZIPR` (§3.5e): ten u32, then thirteen u32 arrays (`SUPER` empty before version 1.9; the
/// seven lists bit fields in words with `PACKED_LISTS`, version 1.10; `ring_starts` the inner
/// starts with `INNER_RING_STARTS` and `ring_last` the fields of `RING_BLOCKS` with
/// `RING_BLOCKS`, version 1.12).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct ZiprHeader {
    /// `m`: vertices.
    pub m: u32,
    /// `m_r`: ring vertices.
    pub m_r: u32,
    /// `R`: rings.
    pub rings: u32,
    /// `n0`: T0 rows.
    pub t0: u32,
    /// `X`: exception words.
    pub exceptions: u32,
    /// `I`: records of irregular slots.
    pub records: u32,
    /// `P`: opposite pairs.
    pub pairs: u32,
    /// `E`: explicit T0 opposites.
    pub explicit: u32,
    /// Flags: [`LR_BOUNDARIES_ON_RING`](super::LR_BOUNDARIES_ON_RING), [`ZIPPER_WART_DELTAS`],
    /// [`ZIPPER_SHORT_HEADS`], [`ZIPPER_PACKED_LISTS`], [`ZIPPER_INNER_RING_STARTS`],
    /// [`ZIPPER_RING_BLOCKS`], [`ZIPPER_LEFT_FOURS`], [`ZIPPER_RIGHT_FOURS`] (in the compact
    /// form, bits 0–30 of its first word).
    pub flags: u32,
    /// Reserved, 0 (the 40-byte header only).
    pub reserved: u32,
    /// The compact form (version 1.13, §3.5e.3); `None` for the 40-byte header.
    pub compact: Option<CompactZipr>,
}

/// What a compact `ZIPR` header (version 1.13, FORMAT.md §3.5e.3) holds besides the counts
/// and flags: the counts' byte width and the compact heads' field widths.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CompactZipr {
    /// `k`: bytes per count, 1 to 4.
    pub count_bytes: u8,
    /// `w_a`: bits of an anchor offset (signed), 0 to 16.
    pub anchor_bits: u8,
    /// `w_x`, `w_i`: bits of a head's exception and record counts, 0 to 16.
    pub count_bits: [u8; 2],
}

/// Bit 31 of a `ZIPR` section's first word: the compact form (version 1.13). The 40-byte
/// header's first word is `m`, below 2^30.
pub const ZIPPER_COMPACT: u32 = 1 << 31;

/// `ZIPR` flag (FORMAT.md §3.5e, version 1.8): a delta slot followed on its side by a
/// canonical T2 is a wart. That slot can hold nothing else (the T2 covers its ring edge on
/// that side), so the flag costs no symbol, and a wart whose tip is a small decrement of the
/// chain needs no exception word.
pub const ZIPPER_WART_DELTAS: u32 = 2;

/// `ZIPR` flag (FORMAT.md §3.5e, version 1.9): each block's head is two words (the anchors
/// as 16-bit offsets from the block's first vertex, the counts as 16-bit offsets from its
/// superblock's in `SUPER`) instead of four: half a bit per triangle less on a scan.
pub const ZIPPER_SHORT_HEADS: u32 = 4;

/// `ZIPR` flag (FORMAT.md §3.5e, version 1.10): the seven lists (`EXCEPTIONS` to `C`) are bit
/// fields as wide as the counts call for (a vertex of a mesh of 5,000 in 13 bits, not 32).
pub const ZIPPER_PACKED_LISTS: u32 = 8;

/// `ZIPR` flag (FORMAT.md §3.5e, version 1.12): `ring_starts` holds the starts of rings 1 to
/// `R − 1` only (`R − 1` words): ring 0 starts at 0 and the last ring ends at `m_r`, which the
/// header says already. Eight bytes less in every file, the most a tiny mesh's Zipper has above
/// the bit-efficient LR's.
pub const ZIPPER_INNER_RING_STARTS: u32 = 16;

/// `ZIPR` flag (FORMAT.md §3.5e, version 1.12): with several rings, `ring_last` and
/// `ring_rank` (two bits per ring vertex) give way to `RING_BLOCKS`, the ring of each block's
/// first vertex in `bits(R − 1)` bits; a vertex's ring is then that plus the ring starts
/// between (at most 16: a ring has 4 vertices or more). A bit per triangle less on a mesh of
/// several components.
pub const ZIPPER_RING_BLOCKS: u32 = 32;

/// `ZIPR` flag (FORMAT.md §3.5e.4, version 1.14): a left slot of symbol 5 is a *four*, a delta
/// slot whose tip is the chain value minus 4, unless the left slot of the next vertex in its
/// block has symbol 4 (then it is the T2's redundant copy, as before). A left symbol 5
/// anywhere else was never written, and a chain's step of 4 (a vertex with four edges to the
/// turn of the ring beside it) took an exception word: 40–60% of all exception words.
pub const ZIPPER_LEFT_FOURS: u32 = 64;

/// `ZIPR` flag (FORMAT.md §3.5e.4, version 1.14): as [`ZIPPER_LEFT_FOURS`] on the right side,
/// where symbol 5 otherwise stands for `NULL` (no triangle): a writer sets it only when no
/// right slot is `NULL` (a mesh without a border edge on the ring).
pub const ZIPPER_RIGHT_FOURS: u32 = 128;

/// `ZIPR` flag (FORMAT.md §3.5e.5, version 1.15; with `PACKED_LISTS` only): a record's
/// second word is a T0 row (state 1), the T0 corner found in it by the slot's edges, or a
/// pair's index (state 3), in `1 + bits(max(n0, P) − 1)` bits instead of a state of two bits
/// and a T0 corner's offset (`4 n0` values).
pub const ZIPPER_ROW_RECORDS: u32 = 256;

/// `ZIPR` flag (FORMAT.md §3.5e.5, version 1.15; with `PACKED_LISTS` only): exception words
/// and records' first words hold the tip alone; the WART flag of such a slot is that the next
/// slot of its side has symbol 4 and the tip is not `v.n.n` (a wart's far vertex skips a
/// T2's tip; a redundant copy's tip is it), one bit less in each.
pub const ZIPPER_IMPLIED_WARTS: u32 = 512;

/// `ZIPR` flag (FORMAT.md §3.5e.6, version 1.16; in the compact form with `PACKED_LISTS`
/// only): the nine bit lists (the compact heads' two, then `EXCEPTIONS` to `C`) are one bit
/// stream, each from the bit where the one before ends, padded to a word only at its end:
/// up to 31 bits saved per list, 3–5% of a Zipper of a few hundred triangles.
pub const ZIPPER_JOINED_LISTS: u32 = 1024;

impl ZiprHeader {
    /// Bytes of the header.
    pub const LEN: usize = 40;
    /// The arrays, in file order.
    pub const ARRAYS: [&'static str; 13] = [
        "ring_starts",
        "ring_last",
        "ring_rank",
        "PLANES",
        "HEADS",
        "EXCEPTIONS",
        "RECORDS",
        "PAIRS",
        "T0_V",
        "T0_CODES",
        "EXPLICIT",
        "C",
        "SUPER",
    ];

    /// Whether the section `b` (at least 4 bytes) begins with a compact header.
    pub fn is_compact(b: &[u8]) -> bool {
        le_u32(b, 0) & ZIPPER_COMPACT != 0
    }

    /// The flags word of the section `b` (at least 4 bytes), in either form: 0 when the
    /// 40-byte header is cut before it.
    pub fn flags_of(b: &[u8]) -> u32 {
        match Self::is_compact(b) {
            true => le_u32(b, 0) & !ZIPPER_COMPACT,
            false if b.len() >= 36 => le_u32(b, 32),
            false => 0,
        }
    }

    /// The header at the start of `b`: at least [`ZiprHeader::LEN`] bytes, or in the compact
    /// form ([`ZiprHeader::is_compact`]) 8 bytes with a count width `k` of 1 to 4 and then
    /// `8k` bytes.
    pub fn read(b: &[u8]) -> ZiprHeader {
        if Self::is_compact(b) {
            let k = b[4];
            let count = |i: usize| {
                let at = 8 + i * k as usize;
                b[at..at + k as usize]
                    .iter()
                    .rev()
                    .fold(0u32, |x, &byte| x << 8 | byte as u32)
            };
            return ZiprHeader {
                m: count(0),
                m_r: count(1),
                rings: count(2),
                t0: count(3),
                exceptions: count(4),
                records: count(5),
                pairs: count(6),
                explicit: count(7),
                flags: le_u32(b, 0) & !ZIPPER_COMPACT,
                reserved: 0,
                compact: Some(CompactZipr {
                    count_bytes: k,
                    anchor_bits: b[5],
                    count_bits: [b[6], b[7]],
                }),
            };
        }
        let [m, m_r, rings, t0, exceptions, records, pairs, explicit, flags, reserved] =
            read_fields(b);
        ZiprHeader {
            m,
            m_r,
            rings,
            t0,
            exceptions,
            records,
            pairs,
            explicit,
            flags,
            reserved,
            compact: None,
        }
    }

    /// The eight counts, in header order.
    pub fn counts(&self) -> [u32; 8] {
        [
            self.m,
            self.m_r,
            self.rings,
            self.t0,
            self.exceptions,
            self.records,
            self.pairs,
            self.explicit,
        ]
    }

    /// Where count `i` (in [`ZiprHeader::counts`] order) lies in the header.
    pub fn count_offset(&self, i: usize) -> usize {
        match self.compact {
            Some(c) => 8 + i * c.count_bytes as usize,
            None => 4 * i,
        }
    }

    /// Bytes of the header: 40, or `8 + 8k` in the compact form.
    pub fn header_len(&self) -> usize {
        match self.compact {
            Some(c) => crate::lr::zipper::compact_header_len(c.count_bytes),
            None => Self::LEN,
        }
    }

    /// The header's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(self.header_len());
        match self.compact {
            Some(c) => {
                write_fields(&mut out, &[self.flags | ZIPPER_COMPACT]);
                out.extend([
                    c.count_bytes,
                    c.anchor_bits,
                    c.count_bits[0],
                    c.count_bits[1],
                ]);
                for x in self.counts() {
                    out.extend_from_slice(&x.to_le_bytes()[..c.count_bytes as usize]);
                }
            }
            None => {
                write_fields(&mut out, &self.counts());
                write_fields(&mut out, &[self.flags, self.reserved]);
            }
        }
        out
    }

    /// In the compact form, the fields of the two head lists: the anchors' (signed, both
    /// sides alike) and the counts' (exceptions, records).
    pub fn head_fields(
        &self,
    ) -> Option<([crate::lr::zipper::Field; 2], [crate::lr::zipper::Field; 2])> {
        use crate::lr::zipper::{Field, FieldKind};
        let c = self.compact?;
        let anchor = Field {
            width: c.anchor_bits,
            kind: FieldKind::Signed,
        };
        let count = |width| Field {
            width,
            kind: FieldKind::Plain,
        };
        Some(([anchor; 2], c.count_bits.map(count)))
    }

    /// Blocks of 64 ring vertices.
    pub fn blocks(&self) -> u64 {
        (self.m_r as u64).div_ceil(1 << crate::lr::zipper::BLOCK_SHIFT)
    }

    /// With [`ZIPPER_JOINED_LISTS`] (in the compact form), the first bit of each of the
    /// nine bit lists (the anchors, the head counts, then `EXCEPTIONS` to `C`) from the
    /// start of `HEADS`, then the bits of the whole stream; `None` otherwise or when the
    /// counts overflow.
    pub fn joined_bits(&self) -> Option<[u64; 10]> {
        use crate::lr::zipper::first_bit;
        if self.flags & ZIPPER_JOINED_LISTS == 0 {
            return None;
        }
        let (anchor, counts) = self.head_fields()?;
        let lists = self.list_lengths()?;
        let fields = self.list_fields();
        let heads = 2 * self.blocks();
        let bits: [u64; 9] = std::array::from_fn(|q| match q {
            0 => first_bit(anchor, heads),
            1 => first_bit(counts, heads),
            _ => first_bit(fields[q - 2], lists[q - 2]),
        });
        let mut starts = [0u64; 10];
        for q in 0..9 {
            starts[q + 1] = starts[q].checked_add(bits[q])?;
        }
        Some(starts)
    }

    /// In the compact form, the words of the anchors' list (the first part of `HEADS`).
    pub fn anchor_words(&self) -> u64 {
        match self.head_fields() {
            Some((anchor, _)) => crate::lr::zipper::packed_words(2 * self.blocks(), anchor),
            None => 0,
        }
    }

    /// Whether the ring-end bits and ranks are stored (only with several rings).
    pub fn has_ring_bits(&self) -> bool {
        self.rings > 1 && !self.ring_blocks()
    }

    /// Whether `RING_BLOCKS` stands for the ring-end bits ([`ZIPPER_RING_BLOCKS`], with
    /// several rings).
    pub fn ring_blocks(&self) -> bool {
        self.rings > 1 && self.flags & ZIPPER_RING_BLOCKS != 0
    }

    /// Fields of `RING_BLOCKS`: one per block of 64 ring vertices (none without the flag).
    pub fn ring_block_count(&self) -> u64 {
        match self.ring_blocks() {
            true => self.blocks(),
            false => 0,
        }
    }

    /// Whether `ring_starts` holds the inner starts only ([`ZIPPER_INNER_RING_STARTS`]).
    pub fn inner_ring_starts(&self) -> bool {
        self.flags & ZIPPER_INNER_RING_STARTS != 0
    }

    /// Elements of the seven lists (`EXCEPTIONS` to `C`, FORMAT.md §3.5e); `None` when
    /// `m_r > m`.
    pub fn list_lengths(&self) -> Option<[u64; 7]> {
        use crate::lr::zipper::RECORD_WORDS;
        Some([
            self.exceptions as u64,
            RECORD_WORDS as u64 * self.records as u64,
            2 * self.pairs as u64,
            3 * self.t0 as u64,
            self.t0 as u64,
            self.explicit as u64,
            (self.m as u64).checked_sub(self.m_r as u64)?,
        ])
    }

    /// The fields of the seven lists: 32-bit words, or with [`ZIPPER_PACKED_LISTS`] bit
    /// fields as wide as the counts call for.
    pub fn list_fields(&self) -> [[crate::lr::zipper::Field; 2]; 7] {
        crate::lr::zipper::list_fields(
            self.flags,
            self.m,
            self.m_r,
            self.t0,
            self.pairs,
            self.explicit,
        )
    }

    /// The arrays the counts call for; `None` when `m_r > m` or the sizes overflow.
    pub fn layout(&self) -> Option<Layout> {
        use crate::lr::zipper::{
            packed_words, plane_array_words, HEAD_WORDS, SHORT_HEAD_WORDS, SUPER_SHIFT,
        };
        let short = self.flags & ZIPPER_SHORT_HEADS != 0;
        let heads = match self.head_fields() {
            Some((_, counts)) => self.anchor_words() + packed_words(2 * self.blocks(), counts),
            None => (if short { SHORT_HEAD_WORDS } else { HEAD_WORDS }) as u64 * self.blocks(),
        };
        let superblocks = |shift: u32| 2 * self.blocks().div_ceil(1 << shift).saturating_sub(1);
        let super_words = match (self.compact, short) {
            (Some(_), _) => superblocks(crate::lr::zipper::COMPACT_SUPER_SHIFT),
            (None, true) => superblocks(SUPER_SHIFT),
            (None, false) => 0,
        };
        let bits = if self.has_ring_bits() {
            (self.m_r as u64).div_ceil(32)
        } else {
            0
        };
        let lists = self.list_lengths()?;
        let fields = self.list_fields();
        let mut list_words: [u64; 7] = std::array::from_fn(|i| packed_words(lists[i], fields[i]));
        // JOINED_LISTS: HEADS holds the one stream of the nine lists.
        let heads = match self.flags & ZIPPER_JOINED_LISTS != 0 {
            true => {
                list_words = [0; 7];
                self.joined_bits()?[9].div_ceil(32)
            }
            false => heads,
        };
        let ring_blocks = crate::lr::zipper::ring_block_field(self.rings);
        let counts = [
            match self.inner_ring_starts() {
                true => (self.rings as u64).saturating_sub(1),
                false => self.rings as u64 + 1,
            },
            match self.ring_blocks() {
                true => packed_words(self.ring_block_count(), [ring_blocks; 2]),
                false => bits,
            },
            bits,
            plane_array_words(self.m_r) as u64,
            heads,
            list_words[0],
            list_words[1],
            list_words[2],
            list_words[3],
            list_words[4],
            list_words[5],
            list_words[6],
            super_words,
        ];
        let arrays: Vec<_> = Self::ARRAYS
            .iter()
            .zip(counts)
            .map(|(&name, count)| (name, count, 4))
            .collect();
        Layout::new(self.header_len(), &arrays)
    }
}
