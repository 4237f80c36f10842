//! The container's on-disk layer, written once for the reader and the writer: the magic and
//! versions, the header and section-table records, tags, flags and kind codes as types, the
//! checksum rule, the metadata record, and for each section the description of its fields
//! and arrays ([`layout`]). The byte layout is specified in `spec/FORMAT.md`.
//!
//! Nothing here validates beyond what a record's shape needs; the rules live in
//! [`crate::read`].

pub mod attributes;
pub mod copied;
pub mod kept;
pub mod labels;
pub mod layout;
mod metadata;
pub mod parts;
pub mod quantized;

pub use metadata::Metadata;

/// The first eight bytes of every container: `\x89LRM\r\n\x1a\n` (a non-ASCII byte, the name,
/// and the line-ending and end-of-file bytes that transfers in text mode would damage).
pub const MAGIC: [u8; 8] = [0x89, b'L', b'R', b'M', b'\r', b'\n', 0x1a, b'\n'];

/// Major version written and read. A reader rejects any other major version.
pub const MAJOR: u16 = 1;
/// Newest minor version written. Readers accept any minor version of their major version.
pub const MINOR: u16 = 17;

/// The minor version a file of these sections (tags and payloads) is written with: 17 with
/// `LRTB` flag `OPEN_FANS`; 16 with
/// `ZIPR` flag `JOINED_LISTS`; 15 with
/// `ZIPR` flag `ROW_RECORDS` or `IMPLIED_WARTS`; 14 with
/// `ZIPR` flag `LEFT_FOURS` or `RIGHT_FOURS`; 13 with `ZIPR` in the compact form; 12 with
/// `ZIPR` flag `INNER_RING_STARTS` or `RING_BLOCKS`; 11 with `LRBE` flag `TIP_BASES`; 10 with
/// `ZIPR` flag `PACKED_LISTS`; 9 with `SHORT_HEADS`; 8 with `ZIPR` flag `WART_DELTAS`; 7 with `ZIPR`; 6 with `GEOM` encoding 6; 5 with `FLIP`; 4 with an LR flags word set; 3 with
/// `PART` labels coded, normals predicted from their neighbours only or `COPC`; 2 with a
/// position encoding of version 1.2 (`GEOM` encodings 2 to 5), an `ATTR` record of value
/// encoding 1 or 2 or of seam encoding 1, `PART` runs or `KEPC`; 1 with a section of version 1.1 (`ATTR`, `PART`), 0 otherwise,
/// so that a file says the oldest version that reads it.
pub fn minor_for<'a>(sections: impl IntoIterator<Item = (Tag, &'a [u8])>) -> u16 {
    let sections: Vec<(Tag, &[u8])> = sections.into_iter().collect();
    let vertices = sections
        .iter()
        .find(|(tag, bytes)| *tag == Tag::MESH && bytes.len() >= 4)
        .map(|(_, bytes)| le_u32(bytes, 0));
    sections
        .iter()
        .map(|&(tag, bytes)| match tag {
            Tag::GEOM if bytes.len() >= 4 && le_u32(bytes, 0) == 6 => 6,
            Tag::GEOM if bytes.len() >= 4 && le_u32(bytes, 0) >= 2 => 2,
            Tag::ATTR => vertices.map_or(1, |v| attributes::minor_version(bytes, v)),
            Tag::PART if bytes.len() >= 11 && bytes[10] == labels::CODED => 3,
            Tag::PART if bytes.len() >= 10 && bytes[9] == parts::RUNS => 2,
            Tag::COPC => 3,
            // The LR flags word (FORMAT.md §3.5 and §3.5d).
            Tag::LRTB if bytes.len() >= 24 && le_u32(bytes, 20) & layout::LR_OPEN_FANS != 0 => 17,
            Tag::LRTB if bytes.len() >= 24 && le_u32(bytes, 20) != 0 => 4,
            Tag::LRBE if bytes.len() >= 32 && le_u32(bytes, 28) & layout::LRBE_TIP_BASES != 0 => 11,
            Tag::LRBE if bytes.len() >= 32 && le_u32(bytes, 28) != 0 => 4,
            Tag::ZIPR
                if bytes.len() >= 4
                    && layout::ZiprHeader::flags_of(bytes) & layout::ZIPPER_JOINED_LISTS != 0 =>
            {
                16
            }
            Tag::ZIPR
                if bytes.len() >= 4
                    && layout::ZiprHeader::flags_of(bytes)
                        & (layout::ZIPPER_ROW_RECORDS | layout::ZIPPER_IMPLIED_WARTS)
                        != 0 =>
            {
                15
            }
            Tag::ZIPR
                if bytes.len() >= 4
                    && layout::ZiprHeader::flags_of(bytes)
                        & (layout::ZIPPER_LEFT_FOURS | layout::ZIPPER_RIGHT_FOURS)
                        != 0 =>
            {
                14
            }
            Tag::ZIPR if bytes.len() >= 4 && layout::ZiprHeader::is_compact(bytes) => 13,
            Tag::ZIPR
                if bytes.len() >= 36
                    && le_u32(bytes, 32)
                        & (layout::ZIPPER_INNER_RING_STARTS | layout::ZIPPER_RING_BLOCKS)
                        != 0 =>
            {
                12
            }
            Tag::ZIPR
                if bytes.len() >= 36 && le_u32(bytes, 32) & layout::ZIPPER_PACKED_LISTS != 0 =>
            {
                10
            }
            Tag::ZIPR
                if bytes.len() >= 36 && le_u32(bytes, 32) & layout::ZIPPER_SHORT_HEADS != 0 =>
            {
                9
            }
            Tag::ZIPR
                if bytes.len() >= 36 && le_u32(bytes, 32) & layout::ZIPPER_WART_DELTAS != 0 =>
            {
                8
            }
            Tag::ZIPR => 7,
            Tag::FLIP => 5,
            Tag::KEPC => 2,
            Tag::PART => 1,
            _ => 0,
        })
        .max()
        .unwrap_or(0)
}

/// Size of the fixed header.
pub const HEADER_LEN: usize = 32;
/// Size of one section-table entry.
pub const ENTRY_LEN: usize = 32;

/// Reads the little-endian u16 at `at`. The caller has checked the range.
pub(crate) fn le_u16(b: &[u8], at: usize) -> u16 {
    u16::from_le_bytes([b[at], b[at + 1]])
}

/// Reads the little-endian u32 at `at`. The caller has checked the range.
pub(crate) fn le_u32(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes([b[at], b[at + 1], b[at + 2], b[at + 3]])
}

/// Reads the little-endian u64 at `at`. The caller has checked the range.
pub(crate) fn le_u64(b: &[u8], at: usize) -> u64 {
    (le_u32(b, at) as u64) | (le_u32(b, at + 4) as u64) << 32
}

/// Reads the little-endian f32 at `at`. The caller has checked the range.
pub(crate) fn le_f32(b: &[u8], at: usize) -> f32 {
    f32::from_bits(le_u32(b, at))
}

/// The fixed 32-byte header (FORMAT.md §2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    /// Major version.
    pub major: u16,
    /// Minor version.
    pub minor: u16,
    /// Number of sections `S`.
    pub sections: u32,
    /// Length of the whole file in bytes.
    pub file_length: u64,
    /// CRC-32 of the header's first 24 bytes and the section table ([`table_checksum`]).
    pub table_crc: u32,
    /// Reserved, 0.
    pub reserved: u32,
}

impl Header {
    /// Offset of the section count.
    pub const SECTIONS_AT: usize = 12;
    /// Offset of the file length.
    pub const FILE_LENGTH_AT: usize = 16;
    /// Offset of the table checksum.
    pub const TABLE_CRC_AT: usize = 24;
    /// Offset of the reserved field.
    pub const RESERVED_AT: usize = 28;

    /// The header fields of `b`, which holds at least [`HEADER_LEN`] bytes; the magic is not
    /// checked here.
    pub fn read(b: &[u8]) -> Header {
        Header {
            major: le_u16(b, 8),
            minor: le_u16(b, 10),
            sections: le_u32(b, Self::SECTIONS_AT),
            file_length: le_u64(b, Self::FILE_LENGTH_AT),
            table_crc: le_u32(b, Self::TABLE_CRC_AT),
            reserved: le_u32(b, Self::RESERVED_AT),
        }
    }

    /// The 32 bytes of the header, magic included.
    pub fn to_bytes(&self) -> [u8; HEADER_LEN] {
        let mut out = [0u8; HEADER_LEN];
        out[..8].copy_from_slice(&MAGIC);
        out[8..10].copy_from_slice(&self.major.to_le_bytes());
        out[10..12].copy_from_slice(&self.minor.to_le_bytes());
        out[12..16].copy_from_slice(&self.sections.to_le_bytes());
        out[16..24].copy_from_slice(&self.file_length.to_le_bytes());
        out[24..28].copy_from_slice(&self.table_crc.to_le_bytes());
        out[28..32].copy_from_slice(&self.reserved.to_le_bytes());
        out
    }
}

/// One 32-byte entry of the section table (FORMAT.md §2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Entry {
    /// The section's tag.
    pub tag: Tag,
    /// Its flags.
    pub flags: Flags,
    /// Offset of its first byte from the start of the file.
    pub offset: u64,
    /// Its length in bytes.
    pub length: u64,
    /// CRC-32 of its bytes.
    pub crc: u32,
    /// Reserved, 0.
    pub reserved: u32,
}

impl Entry {
    /// Offset of the flags within an entry.
    pub const FLAGS_AT: usize = 4;
    /// Offset of the section offset within an entry.
    pub const OFFSET_AT: usize = 8;
    /// Offset of the section length within an entry.
    pub const LENGTH_AT: usize = 16;
    /// Offset of the section checksum within an entry.
    pub const CRC_AT: usize = 24;
    /// Offset of the reserved field within an entry.
    pub const RESERVED_AT: usize = 28;

    /// The entry stored at `b[at..at + 32]`, which the caller has checked is in range.
    pub fn read(b: &[u8], at: usize) -> Entry {
        Entry {
            tag: Tag([b[at], b[at + 1], b[at + 2], b[at + 3]]),
            flags: Flags(le_u32(b, at + Self::FLAGS_AT)),
            offset: le_u64(b, at + Self::OFFSET_AT),
            length: le_u64(b, at + Self::LENGTH_AT),
            crc: le_u32(b, at + Self::CRC_AT),
            reserved: le_u32(b, at + Self::RESERVED_AT),
        }
    }

    /// The 32 bytes of the entry.
    pub fn to_bytes(&self) -> [u8; ENTRY_LEN] {
        let mut out = [0u8; ENTRY_LEN];
        out[..4].copy_from_slice(&self.tag.0);
        out[4..8].copy_from_slice(&self.flags.0.to_le_bytes());
        out[8..16].copy_from_slice(&self.offset.to_le_bytes());
        out[16..24].copy_from_slice(&self.length.to_le_bytes());
        out[24..28].copy_from_slice(&self.crc.to_le_bytes());
        out[28..32].copy_from_slice(&self.reserved.to_le_bytes());
        out
    }
}

/// The checksum rule of the header: CRC-32 (ISO-HDLC) of the header's first 24 bytes
/// followed by the section table.
pub fn table_checksum(header_and_table: &[u8]) -> u32 {
    let mut h = crc32fast::Hasher::new();
    h.update(&header_and_table[..Header::TABLE_CRC_AT]);
    h.update(&header_and_table[HEADER_LEN..]);
    h.finalize()
}

/// The checksum rule of a section: CRC-32 (ISO-HDLC) of its bytes.
pub fn section_checksum(bytes: &[u8]) -> u32 {
    crc32fast::hash(bytes)
}

/// Section flags.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Flags(pub u32);

impl Flags {
    /// No flag.
    pub const NONE: Flags = Flags(0);
    /// A reader that does not know the section must reject the file.
    pub const REQUIRED: Flags = Flags(1);

    /// Whether the REQUIRED bit is set.
    pub fn is_required(self) -> bool {
        self.0 & Flags::REQUIRED.0 != 0
    }

    /// The bits that no version-1 flag defines.
    pub fn unknown_bits(self) -> u32 {
        self.0 & !Flags::REQUIRED.0
    }
}

/// A four-byte section tag. Open: unknown tags still parse and can be reported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Tag(pub [u8; 4]);

impl Tag {
    /// Metadata: a UTF-8 JSON object.
    pub const META: Tag = Tag(*b"META");
    /// Counts and the connectivity kind.
    pub const MESH: Tag = Tag(*b"MESH");
    /// Positions, per vertex.
    pub const GEOM: Tag = Tag(*b"GEOM");
    /// Normals, per vertex.
    pub const NORM: Tag = Tag(*b"NORM");
    /// Texture coordinates, per vertex.
    pub const TEXC: Tag = Tag(*b"TEXC");
    /// Colors, per vertex.
    pub const COLR: Tag = Tag(*b"COLR");
    /// The standard LR tables.
    pub const LRTB: Tag = Tag(*b"LRTB");
    /// An Edgebreaker stream (`spec/EDGEBREAKER.md`).
    pub const EBRK: Tag = Tag(*b"EBRK");
    /// Constrained triangle strips with the adjacent-strips table (`T`, `A`, `C`).
    pub const STRP: Tag = Tag(*b"STRP");
    /// The bit-efficient LR tables.
    pub const LRBE: Tag = Tag(*b"LRBE");
    /// The Zipper tables (version 1.7).
    pub const ZIPR: Tag = Tag(*b"ZIPR");
    /// Vertex copies made by the pseudo-manifold conversion, with their originals.
    pub const COPY: Tag = Tag(*b"COPY");
    /// Degenerate triangles kept aside.
    pub const KEPT: Tag = Tag(*b"KEPT");
    /// Permutations back to the input's vertex and triangle order.
    pub const PERM: Tag = Tag(*b"PERM");
    /// Attributes per vertex or per corner, with their seams (version 1.1).
    pub const ATTR: Tag = Tag(*b"ATTR");
    /// Parts: object, group and material labels of the triangles (version 1.1).
    pub const PART: Tag = Tag(*b"PART");

    /// Kept triangles, range coded (version 1.2, Edgebreaker only).
    pub const KEPC: Tag = Tag(*b"KEPC");
    /// Vertex copies, range coded (Edgebreaker containers, version 1.3).
    pub const COPC: Tag = Tag(*b"COPC");
    /// Triangles the writer reversed to make the orientation consistent (version 1.5).
    pub const FLIP: Tag = Tag(*b"FLIP");

    /// The sections a version-1 reader understands.
    pub const KNOWN: [Tag; 19] = [
        Tag::META,
        Tag::MESH,
        Tag::GEOM,
        Tag::NORM,
        Tag::TEXC,
        Tag::COLR,
        Tag::LRTB,
        Tag::EBRK,
        Tag::STRP,
        Tag::LRBE,
        Tag::ZIPR,
        Tag::COPY,
        Tag::COPC,
        Tag::KEPT,
        Tag::KEPC,
        Tag::PERM,
        Tag::FLIP,
        Tag::ATTR,
        Tag::PART,
    ];

    /// Whether a version-1 reader understands the section.
    pub fn is_known(self) -> bool {
        Tag::KNOWN.contains(&self)
    }

    /// The tag as text, with bytes outside printable ASCII escaped.
    pub fn name(&self) -> String {
        self.0
            .iter()
            .flat_map(|&b| std::ascii::escape_default(b))
            .map(char::from)
            .collect()
    }
}

impl std::fmt::Display for Tag {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.name())
    }
}

/// A connectivity kind (field `kind` of the `MESH` section).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Kind(pub u32);

impl Kind {
    /// Standard LR in section `LRTB`.
    pub const LR: Kind = Kind(1);
    /// Edgebreaker in section `EBRK`.
    pub const EDGEBREAKER: Kind = Kind(2);
    /// Constrained triangle strips and the adjacent-strips table in section `STRP`.
    pub const STRIPS: Kind = Kind(3);
    /// Bit-efficient LR in section `LRBE`.
    pub const LR_COMPACT: Kind = Kind(4);
    /// Zipper in section `ZIPR` (version 1.7).
    pub const ZIPPER: Kind = Kind(5);

    /// Every kind a version-1 reader knows.
    pub const ALL: [Kind; 5] = [
        Kind::LR,
        Kind::EDGEBREAKER,
        Kind::STRIPS,
        Kind::LR_COMPACT,
        Kind::ZIPPER,
    ];

    /// The section that holds this kind's connectivity; `None` for an unknown kind.
    pub fn tag(self) -> Option<Tag> {
        match self {
            Kind::LR => Some(Tag::LRTB),
            Kind::EDGEBREAKER => Some(Tag::EBRK),
            Kind::STRIPS => Some(Tag::STRP),
            Kind::LR_COMPACT => Some(Tag::LRBE),
            Kind::ZIPPER => Some(Tag::ZIPR),
            _ => None,
        }
    }

    /// The kind's name as the command line spells it: `lr`, `edgebreaker`, `strips`,
    /// `lr-compact`, `zipper`; `unknown` otherwise.
    pub fn name(self) -> &'static str {
        match self {
            Kind::LR => "lr",
            Kind::EDGEBREAKER => "edgebreaker",
            Kind::STRIPS => "strips",
            Kind::LR_COMPACT => "lr-compact",
            Kind::ZIPPER => "zipper",
            _ => "unknown",
        }
    }
}

/// A position encoding (first field of the `GEOM` section).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PositionEncoding(pub u32);

impl PositionEncoding {
    /// Three little-endian f32 per vertex.
    pub const F32: PositionEncoding = PositionEncoding(0);
    /// A bounding box (six f32: min xyz, max xyz), then three u16 per vertex. Lossy.
    pub const QUANTIZED16: PositionEncoding = PositionEncoding(1);
    /// A grid of 1 to 30 bits per coordinate, each vertex predicted from the ones before it
    /// in Edgebreaker decode order and the residuals range coded (GEOMETRY.md). Lossy.
    pub const PREDICTED_GRID: PositionEncoding = PositionEncoding(2);
    /// The f32 positions predicted as for encoding 2 and the differences of their bits range
    /// coded (GEOMETRY.md). Lossless.
    pub const PREDICTED_F32: PositionEncoding = PositionEncoding(3);
    /// Random-access blocks of bit-packed levels on a grid (FORMAT.md §3.3). Lossy.
    pub const BLOCKED: PositionEncoding = PositionEncoding(4);
    /// Random-access blocks of the f32 positions as ordered integers (FORMAT.md §3.3).
    /// Lossless.
    pub const BLOCKED_F32: PositionEncoding = PositionEncoding(5);
    /// A grid of 1 to 30 bits per coordinate, each vertex predicted in id order from the
    /// parallelograms at its first corner and the residuals in static prefix codes
    /// (GEOMETRY.md §9): fast to decode. Lossy.
    pub const ANCHORED_GRID: PositionEncoding = PositionEncoding(6);
}
