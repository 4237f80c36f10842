//! Each section's fields and arrays, described once (FORMAT.md §3): the writer lays a section
//! out from its description and the reader slices it with the same one, so that the array
//! order and the header offsets exist in one place.
//!
//! A section with arrays starts with a header of u32 fields; [`Layout`] gives the arrays'
//! byte ranges from the header's counts, with every size computed in u64 so that hostile
//! counts cannot overflow.

use super::{le_u32, Kind};
use crate::lr::compact::{BLOCK_SHIFT, GROUP_SHIFT, OVERFLOW_ROW_WORDS, T0_ROW_UNITS};

mod zipr;
pub use zipr::*;

/// One array of a section: its name in the spec, where it starts, how many elements of how
/// many bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Array {
    /// The array's name in `spec/FORMAT.md`.
    pub name: &'static str,
    /// Byte offset of its first element within the section.
    pub start: usize,
    /// Number of elements.
    pub len: usize,
    /// Bytes per element: 4 (u32 words) or 2 (u16 units).
    pub width: usize,
}

impl Array {
    /// Byte offset just past the array.
    pub fn end(&self) -> usize {
        self.start + self.len * self.width
    }

    /// Byte offset of element `i` within the section.
    pub fn at(&self, i: usize) -> usize {
        self.start + i * self.width
    }
}

/// The arrays of a section, laid out one after the other after its header, with no padding.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Layout {
    /// The arrays, in file order.
    pub arrays: Vec<Array>,
    /// The section's exact length in bytes.
    pub len: u64,
}

impl Layout {
    /// Lays out arrays of `(name, element count, element width)` after a header of
    /// `header_len` bytes. `None` when the sizes do not fit the address space.
    pub fn new(header_len: usize, arrays: &[(&'static str, u64, usize)]) -> Option<Layout> {
        let mut at = header_len as u64;
        let mut out = Vec::with_capacity(arrays.len());
        for &(name, count, width) in arrays {
            let bytes = count.checked_mul(width as u64)?;
            let end = at.checked_add(bytes)?;
            out.push(Array {
                name,
                start: usize::try_from(at).ok()?,
                len: usize::try_from(count).ok()?,
                width,
            });
            at = end;
        }
        usize::try_from(at).ok()?;
        Some(Layout {
            arrays: out,
            len: at,
        })
    }

    /// The array called `name`.
    ///
    /// # Panics
    /// When the layout has no such array (a programming error: names are constants).
    pub fn array(&self, name: &str) -> Array {
        *self
            .arrays
            .iter()
            .find(|a| a.name == name)
            .unwrap_or_else(|| panic!("no array {name} in this layout"))
    }
}

/// Reads `N` little-endian u32 fields from the start of `b` (at least `4 N` bytes).
pub fn read_fields<const N: usize>(b: &[u8]) -> [u32; N] {
    std::array::from_fn(|i| le_u32(b, 4 * i))
}

/// Appends u32 fields little-endian.
pub fn write_fields(out: &mut Vec<u8>, fields: &[u32]) {
    for x in fields {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// `MESH` (§3.2): six u32.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshRecord {
    /// `V`: container vertices, copies included.
    pub vertices: u32,
    /// `W`: output vertices (`V` minus copies).
    pub output_vertices: u32,
    /// `N`: triangles of the connectivity.
    pub triangles: u32,
    /// `K`: kept-aside triangles.
    pub kept: u32,
    /// The connectivity kind.
    pub kind: Kind,
    /// Reserved, 0.
    pub reserved: u32,
}

impl MeshRecord {
    /// The section's length.
    pub const LEN: usize = 24;
    /// Offsets of the fields, in order.
    pub const VERTICES_AT: usize = 0;
    /// Offset of `W`.
    pub const OUTPUT_VERTICES_AT: usize = 4;
    /// Offset of `N`.
    pub const TRIANGLES_AT: usize = 8;
    /// Offset of `K`.
    pub const KEPT_AT: usize = 12;
    /// Offset of `kind`.
    pub const KIND_AT: usize = 16;
    /// Offset of the reserved field.
    pub const RESERVED_AT: usize = 20;

    /// The record in `b` (exactly [`MeshRecord::LEN`] bytes, checked by the caller).
    pub fn read(b: &[u8]) -> MeshRecord {
        let [vertices, output_vertices, triangles, kept, kind, reserved] = read_fields(b);
        MeshRecord {
            vertices,
            output_vertices,
            triangles,
            kept,
            kind: Kind(kind),
            reserved,
        }
    }

    /// The section's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(Self::LEN);
        write_fields(
            &mut out,
            &[
                self.vertices,
                self.output_vertices,
                self.triangles,
                self.kept,
                self.kind.0,
                self.reserved,
            ],
        );
        out
    }
}

/// `GEOM` (§3.3): encoding and reserved, then the positions.
pub mod geom {
    /// Bytes before the coordinates of encoding 0, and before the box of encoding 1.
    pub const HEADER_LEN: usize = 8;
    /// Bytes of the bounding box of encoding 1 (six f32).
    pub const BOX_LEN: usize = 24;
    /// Bytes per vertex of encoding 0 (x, y, z as f32).
    pub const F32_VERTEX_LEN: u64 = 12;
    /// Bytes per vertex of encoding 1 (x, y, z as u16).
    pub const Q16_VERTEX_LEN: u64 = 6;
    /// Bytes of the grid of encodings 2 and 4, after the header: the box minimum (three
    /// f32), the cube's size (f32), the bits per coordinate (u32).
    pub const GRID_LEN: usize = 20;
}

/// Bytes per vertex of the per-vertex attribute sections (§3.4): `NORM` 3 f32, `TEXC` 2 f32,
/// `COLR` 4 u8.
pub mod attribute {
    /// `NORM`.
    pub const NORMAL_LEN: u64 = 12;
    /// `TEXC`.
    pub const TEXCOORD_LEN: u64 = 8;
    /// `COLR`.
    pub const COLOR_LEN: u64 = 4;
}

/// `LRTB` (§3.5): eight u32, then eight u32 arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LrtbHeader {
    /// `m`: vertices.
    pub m: u32,
    /// `m_r`: ring vertices.
    pub m_r: u32,
    /// `R`: rings.
    pub rings: u32,
    /// `n0`: T0 triangles.
    pub t0: u32,
    /// `ni`: `VO*` records.
    pub records: u32,
    /// Flags: [`LR_BOUNDARIES_ON_RING`], [`LR_OPEN_FANS`].
    pub flags: u32,
    /// `F`: fans in `FANS` with [`LR_OPEN_FANS`] (version 1.17), 0 without (reserved before).
    pub open_fans: u32,
    /// Reserved, 0.
    pub reserved: u32,
}

/// `LRTB` and `LRBE` flag (FORMAT.md §3.5, rule V53): every corner without an opposite is
/// the tip corner of a left slot whose right slot is missing, so that `v.c` of a ring vertex
/// is found without walking its fan. Derived from the tables by a verifying reader; a
/// reader that only checks that a file is well formed takes it from here.
pub const LR_BOUNDARIES_ON_RING: u32 = 1;

/// `LRTB` flag (FORMAT.md §3.5.1, version 1.17, rule V61): the open fans that `v.c` cannot
/// tell from the ring are listed in `FANS`, so that `v.c` never walks a fan.
pub const LR_OPEN_FANS: u32 = 2;

impl LrtbHeader {
    /// Bytes of the header.
    pub const LEN: usize = 32;
    /// The arrays, in file order.
    pub const ARRAYS: [&'static str; 11] = [
        "ring_starts",
        "ring_last",
        "ring_rank",
        "LR",
        "VO_V",
        "VO_O",
        "VO*",
        "C",
        "fan_bits",
        "fan_rank",
        "FANS",
    ];

    /// The header at the start of `b` (at least [`LrtbHeader::LEN`] bytes).
    pub fn read(b: &[u8]) -> LrtbHeader {
        let [m, m_r, rings, t0, records, flags, open_fans, reserved] = read_fields(b);
        LrtbHeader {
            m,
            m_r,
            rings,
            t0,
            records,
            flags,
            open_fans,
            reserved,
        }
    }

    /// The header's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(Self::LEN);
        write_fields(
            &mut out,
            &[
                self.m,
                self.m_r,
                self.rings,
                self.t0,
                self.records,
                self.flags,
                self.open_fans,
                self.reserved,
            ],
        );
        out
    }

    /// The arrays the counts call for; `None` when `m_r > m` or the sizes overflow.
    pub fn layout(&self) -> Option<Layout> {
        let bits = (self.m_r as u64).div_ceil(32);
        let counts = [
            self.rings as u64 + 1,
            bits,
            bits,
            2 * self.m_r as u64,
            3 * self.t0 as u64,
            3 * self.t0 as u64,
            3 * self.records as u64,
            (self.m as u64).checked_sub(self.m_r as u64)?,
        ];
        let listed = self.flags & LR_OPEN_FANS != 0;
        let fans = [bits, bits, self.open_fans as u64].map(|n| if listed { n } else { 0 });
        let counts = counts.into_iter().chain(fans);
        let arrays: Vec<_> = Self::ARRAYS
            .iter()
            .zip(counts)
            .map(|(&name, count)| (name, count, 4))
            .collect();
        Layout::new(Self::LEN, &arrays)
    }
}

/// `LRBE` flag (FORMAT.md §3.5d, version 1.11): plain pairs' tips are 14-bit offsets from the
/// ring vertex or from it plus the base of their side in `BASES` (OPERATORS.md §7.1).
pub const LRBE_TIP_BASES: u32 = 2;

/// `LRBE` (§3.5d): eight u32, nine u32 arrays, then two u16 arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LrbeHeader {
    /// `m`: vertices.
    pub m: u32,
    /// `m_r`: ring vertices.
    pub m_r: u32,
    /// `R`: rings.
    pub rings: u32,
    /// `n0`: T0 triangles.
    pub t0: u32,
    /// `U`: units of `RECORDS`.
    pub record_units: u32,
    /// `F`: T0 overflow rows.
    pub overflow_rows: u32,
    /// The HYBRID-RING-EXPANDER period the writer used (informative).
    pub period: u32,
    /// Flags: [`LR_BOUNDARIES_ON_RING`], [`LRBE_TIP_BASES`].
    pub flags: u32,
}

impl LrbeHeader {
    /// Bytes of the header.
    pub const LEN: usize = 32;
    /// The arrays, in file order: nine of u32, then two of u16.
    pub const ARRAYS: [&'static str; 11] = [
        "ring_starts",
        "ring_last",
        "ring_rank",
        "PAIRS",
        "BLOCKS",
        "GROUPS",
        "C",
        "OVERFLOW",
        "BASES",
        "ROWS",
        "RECORDS",
    ];

    /// Whether the `TIP_BASES` flag is set (the `BASES` array is present).
    pub fn has_tip_bases(&self) -> bool {
        self.flags & LRBE_TIP_BASES != 0
    }

    /// The header at the start of `b` (at least [`LrbeHeader::LEN`] bytes).
    pub fn read(b: &[u8]) -> LrbeHeader {
        let [m, m_r, rings, t0, record_units, overflow_rows, period, flags] = read_fields(b);
        LrbeHeader {
            m,
            m_r,
            rings,
            t0,
            record_units,
            overflow_rows,
            period,
            flags,
        }
    }

    /// The header's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(Self::LEN);
        write_fields(
            &mut out,
            &[
                self.m,
                self.m_r,
                self.rings,
                self.t0,
                self.record_units,
                self.overflow_rows,
                self.period,
                self.flags,
            ],
        );
        out
    }

    /// Whether the ring-end bits and ranks are stored (only with several rings).
    pub fn has_ring_bits(&self) -> bool {
        self.rings > 1
    }

    /// The arrays the counts call for; `None` when `m_r > m` or the sizes overflow.
    pub fn layout(&self) -> Option<Layout> {
        let bits = if self.has_ring_bits() {
            (self.m_r as u64).div_ceil(32)
        } else {
            0
        };
        let counts = [
            (self.rings as u64 + 1, 4),
            (bits, 4),
            (bits, 4),
            (self.m_r as u64, 4),
            (2 * (self.m_r as u64).div_ceil(1 << BLOCK_SHIFT), 4),
            ((self.t0 as u64).div_ceil(1 << GROUP_SHIFT), 4),
            ((self.m as u64).checked_sub(self.m_r as u64)?, 4),
            (OVERFLOW_ROW_WORDS as u64 * self.overflow_rows as u64, 4),
            (
                match self.has_tip_bases() {
                    true => 2 * (self.m_r as u64).div_ceil(1 << BLOCK_SHIFT),
                    false => 0,
                },
                4,
            ),
            (T0_ROW_UNITS as u64 * self.t0 as u64, 2),
            (self.record_units as u64, 2),
        ];
        let arrays: Vec<_> = Self::ARRAYS
            .iter()
            .zip(counts)
            .map(|(&name, (count, width))| (name, count, width))
            .collect();
        Layout::new(Self::LEN, &arrays)
    }
}

/// `STRP` (§3.5c): four u32, then `T`, `A` and `C`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct StrpHeader {
    /// `m`: vertices.
    pub m: u32,
    /// `L`: entries of `T` and of `A`.
    pub len: u32,
    /// Reserved, 0.
    pub reserved: [u32; 2],
}

impl StrpHeader {
    /// Bytes of the header.
    pub const LEN: usize = 16;
    /// The arrays, in file order.
    pub const ARRAYS: [&'static str; 3] = ["T", "A", "C"];

    /// The header at the start of `b` (at least [`StrpHeader::LEN`] bytes).
    pub fn read(b: &[u8]) -> StrpHeader {
        let [m, len, r0, r1] = read_fields(b);
        StrpHeader {
            m,
            len,
            reserved: [r0, r1],
        }
    }

    /// The header's bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::with_capacity(Self::LEN);
        write_fields(
            &mut out,
            &[self.m, self.len, self.reserved[0], self.reserved[1]],
        );
        out
    }

    /// The arrays the counts call for.
    pub fn layout(&self) -> Option<Layout> {
        let (len, m) = (self.len as u64, self.m as u64);
        Layout::new(Self::LEN, &[("T", len, 4), ("A", len, 4), ("C", m, 4)])
    }
}

/// `COPY` (§3.6): u32 `k`, then `k` pairs `(copy, original)`.
pub mod copy {
    /// Bytes before the pairs.
    pub const HEADER_LEN: usize = 4;
    /// Words per pair.
    pub const PAIR_WORDS: u64 = 2;
}

/// `KEPT` (§3.7): u32 `k`, then `k` vertex triples.
pub mod kept {
    /// Bytes before the triples.
    pub const HEADER_LEN: usize = 4;
    /// Words per triangle.
    pub const TRIANGLE_WORDS: u64 = 3;
}

/// `PERM` (§3.8): u32 `W`, u32 `T`, then `W` and `T` u32.
pub mod perm {
    /// Bytes before the permutations.
    pub const HEADER_LEN: usize = 8;
}

/// `FLIP` (§3.11): u32 `T`, then a bit per output triangle.
pub mod flip {
    /// Bytes before the bits.
    pub const HEADER_LEN: usize = 4;
}
