//! Edgebreaker connectivity compression for every mesh the corner table accepts, after Lewiner,
//! Lopes, Rossignac and Vieira, "Efficient Edgebreaker for surfaces of arbitrary topology"
//! (SIBGRAPI 2004).
//!
//! # What is coded
//!
//! The encoder walks each connected component of the [`CornerTable`] with the Edgebreaker
//! traversal and labels every triangle with one of the five symbols of the *CLERS* string. Like
//! the paper, it needs no other symbol for handles, boundaries or components:
//!
//! * **Components** are coded one after the other. Components with a boundary come first; the
//!   *topology stream* gives the number of triangles of each.
//! * **Closed components** start from an implicit first triangle (the paper's `P`), whose three
//!   vertices are the first of the component.
//! * **Boundaries** use the paper's *infinite face*: in a component with boundary, one boundary
//!   curve, the *external* one, is the face the traversal starts from; its vertices come first,
//!   and the first triangle is the one behind a boundary edge of it. All boundary vertices are
//!   marked visited from the start, so the first triangle to reach another boundary curve (a
//!   *hole*) is always an `S` whose left triangle the traversal of its right branch reaches:
//!   a *boundary S*. Instead of the paper's corner pair we code, with that `S`, a flag and the
//!   length of the hole: the decoder finds the left neighbour by walking around the hole.
//! * **Handles**: an `S` whose left triangle was reached by its right branch is a *handle S*
//!   (Lopes et al.); the topology stream gives its position and the corner glued to its left
//!   edge. A handle `S` needs no symbol in the CLERS stream.
//! * The last triangle of every component is an `E` and is not coded either.
//!
//! Vertices are numbered in the order the traversal first reaches them (the order in which a
//! geometry coder would write them): per component, the start triangle's three vertices or the
//! external boundary in order, then the tip of each `C`, and the whole curve of each hole when
//! its boundary `S` is met. Unreferenced vertices come last.
//!
//! # Decoding
//!
//! The decoder is the paper's extended Spirale Reversi: it reads the CLERS string backwards,
//! glues each new triangle to the active gate, closes the star of a `C`'s tip (which numbers
//! the vertex), pops the gate an `E` pushed for a normal `S`, walks around a hole for a boundary
//! `S`, and numbers the external boundary or the first triangle's vertices at the start of each
//! component. The CLERS symbols are coded backwards too, with an adaptive binary range coder
//! whose contexts are the symbols decoded just before; decoding is one linear pass.
//!
//! # Byte layout
//!
//! | field | coding |
//! |---|---|
//! | magic `0xEB`, version `1` | 2 bytes |
//! | vertex count, unreferenced vertex count, triangle count, topology stream length | LEB128 each |
//! | topology stream | range coded: component counts and sizes, handle positions and corners |
//! | CLERS stream | range coded, to the end of the input |
//!
//! # Hostile input
//!
//! [`decode`] never panics. Declared counts are checked against [`Limits`] and against what the
//! input can hold (each coded decision costs at least 1/180 bit) before anything is allocated,
//! every index read from the stream is bounds-checked, every gluing must join two free edges of
//! two triangles, and at most `3T` corner numberings are allowed (a valid stream numbers each
//! corner exactly once, which is checked at the end), so the work is linear too.

pub(crate) mod coder;
mod decode;
mod encode;
mod rebuild;
mod topology;

use crate::error::{Error, Location, ParseError, Result};
use crate::CornerTable;

pub use decode::decode;
pub(crate) use decode::decode_glued;
pub use encode::encode;
pub(crate) use encode::encode_glued;

/// Edgebreaker symbols as stored internally (not an on-disk code: symbols are range coded).
pub(crate) mod sym {
    /// Tip vertex not visited.
    pub const C: u8 = 0;
    /// Left neighbour visited, right not.
    pub const L: u8 = 1;
    /// Both neighbours visited.
    pub const E: u8 = 2;
    /// Right neighbour visited, left not.
    pub const R: u8 = 3;
    /// Neither neighbour visited, tip visited.
    pub const S: u8 = 4;
    /// First triangle of a closed component (implicit, never coded).
    pub const P: u8 = 5;
}

/// First byte of an Edgebreaker stream.
pub const MAGIC: u8 = 0xEB;
/// Format version written by [`encode`] and read by [`decode`].
pub const VERSION: u8 = 1;

/// The output of [`encode`].
#[derive(Debug, Clone)]
pub struct Encoded {
    /// The self-contained Edgebreaker stream.
    pub bytes: Vec<u8>,
    /// For each decoded vertex, in decode order, the corner table's vertex id. Vertices no
    /// triangle uses come last, in increasing id order.
    pub vertex_order: Vec<u32>,
    /// For each decoded triangle, in decode order, the corner table's triangle id.
    pub triangle_order: Vec<u32>,
    /// Sizes and symbol counts.
    pub stats: EdgebreakerStats,
}

/// The output of [`decode`]: the connectivity, with triangles and vertices in decode order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decoded {
    /// Number of vertices, unreferenced ones included.
    pub vertex_count: u32,
    /// The triangles as vertex triples, oriented as in the encoded table.
    pub triangles: Vec<[u32; 3]>,
}

/// Bounds on what [`decode`] accepts, checked before allocating.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most triangles a stream may declare.
    pub max_triangles: u64,
    /// Most vertices a stream may declare.
    pub max_vertices: u64,
}

impl Default for Limits {
    /// 2^27 triangles and 2^28 vertices. The decoder needs 36 bytes per triangle up to 89M
    /// triangles, 48 beyond (about 6.4 GB at this limit).
    fn default() -> Limits {
        Limits {
            max_triangles: 1 << 27,
            max_vertices: 1 << 28,
        }
    }
}

/// Sizes of an Edgebreaker encoding and its symbol counts.
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct EdgebreakerStats {
    /// Triangles coded.
    pub triangles: u64,
    /// Vertices, unreferenced ones included.
    pub vertices: u64,
    /// Whole stream, bytes.
    pub bytes: u64,
    /// Connectivity bits per triangle: all bytes of the stream, times 8, over the triangles.
    pub bpt: f64,
    /// Bits per triangle of the CLERS stream alone (symbols, boundary flags, hole lengths).
    pub clers_bpt: f64,
    /// Bytes of the header and the topology stream.
    pub topology_bytes: u64,
    /// `C` triangles.
    pub c: u64,
    /// `L` triangles.
    pub l: u64,
    /// `E` triangles (including the uncoded last one of each component).
    pub e: u64,
    /// `R` triangles.
    pub r: u64,
    /// `S` triangles, all kinds.
    pub s: u64,
    /// Of the `S`, handle `S` (in the topology stream, not in the CLERS stream).
    pub handle_s: u64,
    /// Of the `S`, boundary `S` (first to reach a hole).
    pub boundary_s: u64,
    /// Implicit first triangles of closed components (`P`).
    pub p: u64,
    /// Connected components.
    pub components: u64,
    /// Components with a boundary.
    pub boundary_components: u64,
}

impl EdgebreakerStats {
    /// Encodes `table` and returns the statistics of the encoding.
    ///
    /// # Errors
    /// As [`encode`].
    pub fn of(table: &CornerTable) -> Result<EdgebreakerStats> {
        Ok(encode(table)?.stats)
    }
}

/// A malformed-stream error at byte `offset`.
pub(crate) fn malformed(offset: u64, message: impl Into<String>) -> Error {
    Error::Parse(Box::new(ParseError::new(
        "Edgebreaker",
        Location::Byte(offset),
        message,
    )))
}

/// `c.n`.
#[inline(always)]
pub(crate) fn next(c: u32) -> u32 {
    if c % 3 == 2 {
        c - 2
    } else {
        c + 1
    }
}

/// `c.p`.
#[inline(always)]
pub(crate) fn prev(c: u32) -> u32 {
    if c % 3 == 0 {
        c + 2
    } else {
        c - 1
    }
}

/// One connected component in decode order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Comp {
    /// First decode triangle.
    pub start: u32,
    /// Triangles, the implicit first one of a closed component included.
    pub size: u32,
    /// Closed (starts with `P`) or with boundary (starts at its external boundary).
    pub closed: bool,
}

/// Everything the topology stream carries.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub(crate) struct Topology {
    /// Components in decode order: those with boundary first.
    pub comps: Vec<Comp>,
    /// Handle `S`: (decode triangle, decode corner glued to its left edge), increasing.
    pub handles: Vec<(u32, u32)>,
}

impl std::fmt::Display for EdgebreakerStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "Edgebreaker")?;
        writeln!(
            f,
            "  bits per triangle        {:.3} ({} bytes)",
            self.bpt, self.bytes
        )?;
        writeln!(f, "  CLERS bits per triangle  {:.3}", self.clers_bpt)?;
        writeln!(
            f,
            "  topology stream          {} bytes",
            self.topology_bytes
        )?;
        writeln!(
            f,
            "  symbols                  C {} L {} E {} R {} S {} (handle S {}, boundary S {})",
            self.c, self.l, self.e, self.r, self.s, self.handle_s, self.boundary_s
        )?;
        writeln!(
            f,
            "  components               {} ({} with a boundary)",
            self.components, self.boundary_components
        )
    }
}
