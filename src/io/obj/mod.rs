//! Wavefront OBJ reading and writing, with texture coordinates and normals per face corner,
//! objects, groups and materials.
//!
//! # What the reader takes
//!
//! - `v x y z [w]`, `v x y z r g b` and, as an extension that the writer uses for translucent
//!   colors, `v x y z r g b a`. The weight `w` of rational curves is ignored (with a warning
//!   when it is not 1).
//! - `vt u [v [w]]` (a missing `v` is 0) and `vn x y z`.
//! - `f` with at least three corners `i`, `i/t`, `i//n` or `i/t/n`, 1-based or negative
//!   (relative to the records read so far). Faces may refer to records defined later in the
//!   file: indices are checked once the whole file is read, and an error still names the
//!   face's line. Polygons are fan-triangulated (`crate::io` rules).
//! - `o name`, `g name...` (several group names joined with one space), `usemtl name` and
//!   `mtllib file...` (see *Parts*).
//! - `#` starts a comment, a line ending in `\` continues on the next one, a UTF-8
//!   byte-order mark at the start is skipped. `s` (smoothing groups) and the free-form
//!   geometry statements are skipped silently: smoothing groups only say how normals were
//!   meant to be computed, and files that care give `vn`. `l` and `p` elements and unknown
//!   statements are skipped with a warning that names them (escaped, as all file content in
//!   messages).
//! - A file with no `v` and no `f` statement at all is an error, not an empty mesh: OBJ has
//!   no magic number, so this is what tells an OBJ file from random bytes.
//!
//! # Attributes: per vertex or per corner
//!
//! OBJ gives texture coordinates and normals per face corner, through the `vt` and `vn`
//! numbers of each `v/vt/vn` triple. Nothing is lost:
//!
//! - When the file has as many `vt` records as `v` records and every corner's `vt` number is
//!   its vertex's number (the files written by older writers, ours included), the texture
//!   coordinates are per vertex: vertex `i` takes record `i`. Otherwise they are per corner
//!   ([`Semantic::TexCoord`]`(0)`, `Attribute::corners`): the values are the `vt` records in
//!   file order, unreferenced ones included, and each corner's index is the record it names.
//!   Normals ([`Semantic::Normal`]) follow the same rule with `vn`.
//! - A corner without a `vt` (or `vn`) number in a file where other corners have one is not
//!   filled silently: one value (0, 0) (or (0, 0, 0)) is added after the file's records, those
//!   corners point at it, and a warning says how many corners that concerns.
//! - `vt` records that no corner names, in a file without faces, are per-vertex values when
//!   there is one per `v` record (what the writer produces for a mesh without triangles), and
//!   are otherwise ignored with a warning; so are records in a file whose faces name none.
//! - `vt` keeps `u` and `v`. A third component `w` other than 0 (3D textures, rare) is
//!   dropped with a warning that counts such records.
//!
//! **Colors** stay 8 bits per channel ([`Semantic::Color`]`(0)`, per vertex, as OFF and PLY
//! read them and as the container stores them): they are kept when every `v` record has one
//! (otherwise ignored with a warning), as fractions in `0..=1` unless every component is
//! written as an integer and some exceeds 1, in which case they are `0..=255` (the file-wide
//! rule of OFF). Finer fractions are rounded to the nearest 1/255.
//!
//! # Parts
//!
//! `o`, `g` and `usemtl` set the object, group and material labels of the faces that follow;
//! a statement without a name clears its label. Every distinct combination becomes a
//! [`Part`] of [`Mesh::parts`], in order of first use, and each triangle knows its part;
//! faces before any such statement have the part with no label. `mtllib` names are kept in
//! [`Parts::material_libraries`] (each once, in order), and the `.mtl` files are not read.
//! A file whose statements leave every triangle unlabelled and name no library gets no parts.
//!
//! # What the writer writes
//!
//! `mtllib` lines, `v x y z [r g b [a]]` (colors as fractions of 255; `a` only when some
//! alpha is not 255), `vt u v`, `vn x y z` and one `f` per triangle in order, with the corner
//! form for the attributes present, all 1-based. Per-vertex attributes are written one record
//! per vertex with each corner naming its vertex's number, so they read back per vertex.
//! Per-corner attributes are written as their distinct values (compared bit for bit, in order
//! of first use), each corner naming its value; when those records happen to line up one to
//! one with the vertices, one unused copy of the first is added so that the reader keeps the
//! attribute per corner. `o`, `g` and `usemtl` statements are written before a triangle
//! whenever its labels differ from the previous triangle's (a bare keyword for a label that
//! ends), so the triangle order is kept. Reading the written file gives back the same
//! vertices, triangles, per-corner values and parts.
//!
//! OBJ cannot hold everything a [`Mesh`] can: attributes other than normals, texture set 0
//! and color set 0 are not written; per-corner colors are written by splitting the vertices
//! whose corners differ in color (`Mesh::split_seams`); a name is written with each run of
//! white space as one space and `#` as `_`, and an empty name as no name (a name ending in
//! `\` gets a trailing ` #` so that it is not read as a line continuation).
//!
//! # Why not `tobj`
//!
//! `tobj` (4.0) keeps per-corner normals and texture coordinates through separate index
//! arrays, handles `o`/`g`/`usemtl`, vertex colors and negative indices; this reader matches
//! that, and is kept because `tobj` does not fit a connectivity library: it makes one model
//! per object, group or material with its own re-numbered vertices (the shared vertices
//! between parts, and so the connectivity across them, are lost), it keeps a material name
//! only when the `.mtl` file is found and parsed, it reads three color channels, and its
//! errors are unit variants without a line. Ours keeps the file's vertex numbering, names the
//! line of every error, bounds every allocation by the input's length and never panics.

mod assemble;
mod read;
mod write;

pub use self::read::read;
pub use self::write::write;

#[cfg(doc)]
use crate::mesh::{Attribute, Mesh, Part, Parts, Semantic};

const FORMAT: &str = "OBJ";

/// No texture coordinate or normal at a corner.
const NONE: u32 = u32::MAX;
