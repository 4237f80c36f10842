//! The container's on-disk constants: magic, versions, section tags and flags, field sizes.
//! The byte layout is specified in `spec/FORMAT.md`; this module only names its parts.

/// The first eight bytes of every container: `\x89LRM\r\n\x1a\n` (a non-ASCII byte, the name,
/// and the line-ending and end-of-file bytes that transfers in text mode would damage).
pub const MAGIC: [u8; 8] = [0x89, b'L', b'R', b'M', b'\r', b'\n', 0x1a, b'\n'];

/// Major version written and read. A reader rejects any other major version.
pub const MAJOR: u16 = 1;
/// Minor version written. Readers accept any minor version of their major version.
pub const MINOR: u16 = 0;

/// Size of the fixed header.
pub const HEADER_LEN: usize = 32;
/// Size of one section-table entry.
pub const ENTRY_LEN: usize = 32;

/// Section flag: a reader that does not know the section must reject the file.
pub const FLAG_REQUIRED: u32 = 1;

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
    /// Vertex copies made by the pseudo-manifold conversion, with their originals.
    pub const COPY: Tag = Tag(*b"COPY");
    /// Degenerate triangles kept aside.
    pub const KEPT: Tag = Tag(*b"KEPT");
    /// Permutations back to the input's vertex and triangle order.
    pub const PERM: Tag = Tag(*b"PERM");

    /// The tag as text, with bytes outside printable ASCII escaped.
    pub fn name(&self) -> String {
        self.0
            .iter()
            .flat_map(|&b| std::ascii::escape_default(b))
            .map(char::from)
            .collect()
    }
}

/// Connectivity kinds (field `kind` of the `MESH` section).
pub mod kind {
    /// Standard LR in section `LRTB`.
    pub const LR: u32 = 1;
    /// Edgebreaker in section `EBRK`.
    pub const EDGEBREAKER: u32 = 2;
    /// Constrained triangle strips and the adjacent-strips table in section `STRP`.
    pub const STRIPS: u32 = 3;
    /// Bit-efficient LR in section `LRBE`.
    pub const LR_COMPACT: u32 = 4;
}

/// Position encodings (first field of the `GEOM` section).
pub mod geometry {
    /// Three little-endian f32 per vertex.
    pub const F32: u32 = 0;
    /// A bounding box (six f32: min xyz, max xyz), then three u16 per vertex. Lossy.
    pub const QUANTIZED16: u32 = 1;
}

/// Size of the `MESH` section.
pub const MESH_LEN: usize = 24;
/// Size of the fixed part of the `LRTB` section (eight u32).
pub const LRTB_HEADER_LEN: usize = 32;
/// Size of the fixed part of the `STRP` section (four u32).
pub const STRP_HEADER_LEN: usize = 16;
/// Size of the fixed part of the `LRBE` section (eight u32).
pub const LRBE_HEADER_LEN: usize = 32;
