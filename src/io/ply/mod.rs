//! PLY (Polygon File Format) reading and writing.
//!
//! The reader takes `format ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`,
//! `comment` and `obj_info` lines (a header line with no known keyword, such as Blender 2.4's
//! `Created by Blender3D 247 ...`, is skipped with a warning that quotes it), a UTF-8
//! byte-order mark before `ply`, and any elements with any scalar or list properties of the
//! types `char`/`int8`, `uchar`/`uint8`, `short`/`int16`, `ushort`/`uint16`, `int`/`int32`,
//! `uint`/`uint32`, `float`/`float32`, `double`/`float64`, in any order.
//!
//! What becomes part of the mesh:
//! - element `vertex`: `x y z` (required, any scalar type), `nx ny nz`, texture coordinates
//!   from the first complete pair of `s t`, `u v`, `texture_u texture_v`,
//!   `texture_s texture_t`, and colors from `red green blue [alpha]` (or the same with a
//!   `diffuse_` prefix). Integer colors are clamped to `0..=255`; float colors are fractions
//!   in `0..=1`, clamped and scaled by 255 with rounding. A missing alpha is 255.
//! - element `face`: the list property `vertex_indices` (or `vertex_index`) with integer
//!   items. Negative or out-of-range indices are errors.
//!
//! Every other element and property is parsed, so that binary offsets stay right, and
//! skipped with one warning that names them. Binary errors give the byte offset from the start
//! of the file, ASCII errors the line. Data after the last element is ignored with a warning.
//!
//! The writer produces binary little-endian PLY with `float` positions, normals (`nx ny nz`)
//! and texture coordinates (`s t`), `uchar` colors (`red green blue alpha`) and faces as
//! `list uchar uint vertex_indices`.

mod header;
mod read;
mod write;

use super::{Loaded, ReadOptions};
use crate::error::Result;

pub use self::write::write;

const FORMAT: &str = "PLY";

/// A scalar type of the PLY header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// The value range of an integer type.
    fn int_range(self) -> (i64, i64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (i64::MIN, i64::MAX),
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

/// What a property contributes to the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Skip,
    Position(usize),
    Normal(usize),
    Texcoord(usize),
    Color(usize),
    Indices,
}

#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
    role: Role,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
    /// Header line of the `element` statement.
    line: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body: usize,
    /// Line on which the body starts (for ASCII).
    body_line: u64,
    /// What the header parser skipped (lines with no known keyword).
    warnings: Vec<String>,
}

/// Which mesh data the file provides.
#[derive(Debug, Default)]
struct Layout {
    vertex: Option<usize>,
    face: Option<usize>,
    normals: bool,
    texcoords: bool,
    colors: bool,
}

/// Reads a PLY file.
///
/// # Errors
/// [`crate::Error::Parse`] for a malformed file: header problems with their line, body
/// problems with their line (ASCII) or byte offset from the start of the file (binary).
pub fn read(bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    let mut header = header::parse_header(bytes)?;
    let (layout, skipped) = header::assign_roles(&mut header.elements)?;
    let mut warnings = std::mem::take(&mut header.warnings);
    warnings.extend(skipped);
    read::body(bytes, &header, &layout, &mut warnings).map(|mesh| Loaded { mesh, warnings })
}
