//! glTF 2.0 reading and writing: `.gltf` (JSON, with buffers in `data:` URIs or in files next
//! to it) and `.glb` (the binary container: a JSON chunk and a BIN chunk).
//!
//! # Why a reader of our own
//!
//! The `gltf` crate (1.4.1, its latest release) was considered and not taken: its buffer
//! loading (feature `import`) pulls in the `image` crate, and its accessor reader slices buffers with ranges it does not check
//! (`&slice[start..end]`, `count() - 1` on an empty accessor, an `unwrap` on short sparse
//! values), so a malformed file panics unless every accessor, view and buffer is validated
//! first anyway. That validation is most of a reader; with it, decoding an accessor is a few
//! lines. So the document is parsed with `serde_json` (already a dependency) into a
//! `serde_json::Value` and checked field by field, every error naming its JSON path
//! (`accessors[3].count`); glTF costs the library no new dependency.
//!
//! # What is read
//!
//! - **The default scene** (`scene`, else `scenes[0]`; a file without scenes: every node that
//!   is no node's child; without nodes either: every mesh once, untransformed). Each node that
//!   holds a mesh is an instance of it: a mesh used by several nodes is read once per node.
//! - **Node transforms are applied**: positions by the node's world matrix (`matrix`, or
//!   `translation` × `rotation` × `scale`, parents first); normals by the inverse transpose
//!   of its 3×3 part (computed as the cofactor matrix times the sign of the determinant, so a
//!   singular matrix needs no division) and renormalized, a zero normal staying zero. Under
//!   an identity world matrix nothing is computed, so the values keep their exact bits. A
//!   negative determinant mirrors the geometry, and glTF then defines the triangles as
//!   clockwise: their second and third corners are swapped so that they stay
//!   counter-clockwise. Texture coordinates, colors and custom attributes are not
//!   transformed.
//! - **Primitives**: `TRIANGLES`, and `TRIANGLE_STRIP` and `TRIANGLE_FAN` converted to
//!   triangles by the spec's formulas (degenerate triangles kept). `POINTS` and the line modes
//!   are dropped with a warning; their vertices are kept, unreferenced (so a point cloud
//!   reads as vertices without triangles). Indices may be 8, 16 or 32 bits; a primitive
//!   without indices uses its vertices in order. A primitive without `POSITION` is skipped
//!   with a warning.
//! - **Attributes**: `POSITION` (f32; with `KHR_mesh_quantization`, integers, converted to
//!   f32), `NORMAL` (f32, quantized ones converted), `TEXCOORD_n` and `COLOR_n` (f32, or
//!   normalized `u8`/`u16`, kept as given: component type, `VEC3` or `VEC4`), and every
//!   application-specific `_NAME` as [`Semantic::Custom`]`("NAME")`, of any component type and
//!   one to four components. `TANGENT`, `JOINTS_n`, `WEIGHTS_n`, matrix-typed custom
//!   attributes and morph targets are skipped with a warning. Accessors may interleave
//!   (`byteStride`), be sparse (the base values, or zeros without a `bufferView`, then the
//!   sparse values at their indices) or have no data at all (zeros). `min` and `max` are
//!   ignored.
//! - **One mesh**: the primitives are concatenated, each one's vertices after the previous
//!   ones. Primitives that use the very same attribute accessors under the same world matrix
//!   share their vertices (glTF writers, this one included, share them between primitives
//!   that differ only in their indices and material). An attribute that some primitives have and others
//!   lack is given to all: the others get zeros (colors: ones, i.e. opaque white, glTF's
//!   meaning of a missing color), with a warning. When primitives store one attribute with
//!   different component types or counts, all of it is converted to f32 (normalized integers
//!   mapped to fractions; a missing alpha is 1), with a warning.
//! - **Parts**: every triangle belongs to a [`Part`] with `object` the node's name (else the
//!   mesh's), `material` the material's name (else `material<i>`) and `group` the primitive's
//!   `extras.group` string when present (the writer stores OBJ groups there). Two primitives
//!   of one mesh with the same material are one part. Without any label the mesh has no parts.
//! - **Welding**: with [`ReadOptions::weld`] the mesh is welded ([`Mesh::weld`]): vertices at
//!   equal positions merge, and attributes that differ between them (glTF splits a vertex at
//!   every seam) become per corner.
//!
//! Images, textures, materials beyond their names, animations, cameras and skins are not
//! read. A GLB's BIN chunk is buffer 0 when that buffer has no `uri`.
//!
//! # Bad input
//!
//! Every error names its JSON path or, for a GLB's header and chunks, its byte offset: an index
//! out of range, a component type a semantic does not allow, a buffer that is missing or
//! shorter than its `byteLength`, a view outside its buffer, an accessor outside its view, a
//! non-finite value, bad base64, a bad GLB header or chunk length. No input makes the reader
//! panic, and no allocation exceeds what the input backs: a dense accessor's count is checked
//! against its view before anything is allocated, and what instancing and data-less (sparse or
//! zero) accessors produce is limited to [`OUTPUT_LIMIT_FACTOR`] times the input's size plus one
//! MiB.
//!
//! # External buffers
//!
//! A `.gltf` may keep its buffers in files named by relative URIs. [`read_file`] (and so
//! [`crate::io::read_mesh`]) opens them next to the file; [`read`] (and so
//! [`crate::io::read_mesh_bytes`]), which has only bytes, refuses them with an error that says
//! so; [`read_with`] takes a function that supplies them.
//!
//! # Writing
//!
//! [`write_gltf`] writes one self-contained `.gltf` (its buffer in a base64 `data:` URI) and
//! [`write_glb`] a `.glb`; [`write_gltf`] says what they hold.
//!
//! [`Semantic::Custom`]: crate::mesh::Semantic::Custom
//! [`Part`]: crate::mesh::Part
//! [`ReadOptions::weld`]: crate::io::ReadOptions::weld
//! [`Mesh::weld`]: crate::mesh::Mesh::weld

mod accessor;
mod assemble;
mod base64;
mod buffers;
mod document;
mod json;
mod read;
mod semantics;
mod transform;
mod write;

use std::path::Path;

pub use write::{write_glb, write_gltf};

use super::{Loaded, ReadOptions};
use crate::error::{Error, Location, ParseError, Result};

/// The format name in error messages.
const FORMAT: &str = "glTF";

/// What instancing and accessors without data may produce: this many bytes of output per byte
/// of input (file and external buffers), plus one MiB.
pub const OUTPUT_LIMIT_FACTOR: u64 = 1024;

/// Reads a `.glb` or a `.gltf` from its bytes (a GLB is told by its magic `glTF`, anything
/// else is read as JSON). Buffers must be in the GLB's BIN chunk or in `data:` URIs.
///
/// # Errors
/// [`Error::Parse`] naming the JSON path or byte offset of the problem, also for a buffer in
/// an external file (use [`read_file`] or [`read_with`] for those).
pub fn read(bytes: &[u8], opts: &ReadOptions) -> Result<Loaded> {
    read_with(bytes, opts, &mut |uri: &str| {
        Err(format!(
            "the buffer is the external file `{}`, which cannot be opened from bytes alone: \
             read the file by its path (lrmesh::io::read_mesh) or supply it \
             (lrmesh::io::gltf::read_with)",
            escape(uri)
        ))
    })
}

/// Reads a `.glb` or a `.gltf`, with `external` supplying the bytes of a buffer stored in an
/// external file: it is called with the buffer's URI, percent-decoded (a relative path), and
/// returns the bytes or a message saying why it cannot.
///
/// # Errors
/// As [`read`]; an error of `external` becomes a parse error naming the buffer.
pub fn read_with(
    bytes: &[u8],
    opts: &ReadOptions,
    external: &mut dyn FnMut(&str) -> std::result::Result<Vec<u8>, String>,
) -> Result<Loaded> {
    read::read(bytes, opts, external)
}

/// Reads a `.glb` or `.gltf` file, opening external buffers relative to its directory. URIs
/// with a scheme (other than `data:`) and absolute paths are refused.
///
/// # Errors
/// [`Error::Io`] when the file cannot be read, and the errors of [`read`] with the file named.
pub fn read_file(path: &Path, opts: &ReadOptions) -> Result<Loaded> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let dir = path.parent().unwrap_or(Path::new("")).to_path_buf();
    read_with(&bytes, opts, &mut |uri: &str| {
        let relative = Path::new(uri);
        if relative.is_absolute() || relative.has_root() {
            return Err(format!(
                "`{}` is an absolute path; glTF buffers are relative to the file",
                escape(uri)
            ));
        }
        let file = dir.join(relative);
        std::fs::read(&file).map_err(|e| format!("cannot read {}: {e}", file.display()))
    })
    .map_err(|e| e.with_file(path))
}

/// A parse error of the JSON document, at its path.
fn json_error(path: &str, message: impl std::fmt::Display) -> Error {
    Error::from(ParseError::new(
        FORMAT,
        Location::Whole,
        format!("{path}: {message}"),
    ))
}

/// A parse error at a byte offset (GLB header and chunks).
fn byte_error(offset: u64, message: impl Into<String>) -> Error {
    Error::from(ParseError::new(FORMAT, Location::Byte(offset), message))
}

/// Text from the file, made safe to print: control characters escaped, at most 60 characters.
fn escape(text: &str) -> String {
    const MAX: usize = 60;
    let mut out: String = text
        .chars()
        .take(MAX)
        .flat_map(char::escape_debug)
        .collect();
    if text.chars().nth(MAX).is_some() {
        out.push_str("...");
    }
    out
}
