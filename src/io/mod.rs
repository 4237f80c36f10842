//! Mesh importers and exporters: OBJ, OFF, PLY, STL, glTF 2.0 (`.gltf` and `.glb`).
//!
//! Every reader follows the same rules:
//!
//! - **Vertex identity is the file's.** One mesh vertex per vertex record, in file order;
//!   unreferenced vertices are kept and nothing is merged unless asked: [`ReadOptions::weld`]
//!   merges vertices at equal positions in every format (for STL, which has no shared
//!   vertices, and glTF, which splits vertices at seams, and for files written that way).
//! - **Polygons are fan-triangulated** in file order: `(v0, v1, ..., vk)` gives
//!   `(v0, vi, vi+1)`. Repeated vertices inside a polygon are kept, so degenerate triangles
//!   survive; no triangle is dropped or reordered. A face with fewer than 3 vertices is an error.
//! - **Bad input is a [`ParseError`]** naming the format, the 1-based line (text) or byte
//!   offset from the start of the file (binary) and the problem: an index out of range, a count
//!   the file cannot hold, a truncated body, a NaN or infinite coordinate, normal or texture
//!   coordinate, an unparsable number, an unsupported header item. No input makes a reader
//!   panic or hang, and no allocation is sized by a header count that the bytes present cannot
//!   back. Things that are read but not used or adjusted (skipped PLY properties and header
//!   lines, values added for OBJ corners without one, trailing content) are reported in
//!   [`Loaded::warnings`], and messages quote file content with control bytes escaped.
//! - **No input is an empty mesh by accident**: a file with no vertex or face statement (OBJ),
//!   or with `solid` and nothing after it (ASCII STL), is an error; OFF, PLY and STL files
//!   that declare zero vertices or facets in their header are empty meshes. A UTF-8
//!   byte-order mark at the start of a text file is skipped.
//! - Vertex and triangle counts stay inside the limits of [`Mesh::validate`], so a mesh that
//!   a reader returns always validates.
//!
//! Colors given as numbers in `0..=1` are scaled to `0..=255` with `(c * 255).round()` after
//! clamping; the format modules say when a color counts as such a fraction.
//!
//! The writers produce files that the readers read back to an equal [`Mesh`]: floats are
//! written in the shortest form that parses back to the same bits (including `-0` and
//! subnormals).

pub mod gltf;
mod lex;
pub mod obj;
pub mod off;
pub mod ply;
pub mod stl;

use std::fmt;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::{Error, Location, ParseError, Result};
use crate::mesh::Mesh;

/// A mesh file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MeshFormat {
    /// Wavefront OBJ (text).
    Obj,
    /// Object File Format (text), with the `ST`, `C` and `N` prefixes of Geomview.
    Off,
    /// Polygon File Format, ASCII or binary of either byte order.
    Ply,
    /// Stereolithography, ASCII or binary; written binary.
    Stl,
    /// glTF 2.0 JSON (`.gltf`), buffers in `data:` URIs or external files; written
    /// self-contained.
    Gltf,
    /// glTF 2.0 binary container (`.glb`).
    Glb,
    /// This crate's container (`.lrm`), read fully validated and written with default
    /// [`EncodeOptions`](crate::write::EncodeOptions).
    Lrm,
}

impl MeshFormat {
    /// The format named by a file's extension (`.obj`, `.off`, `.ply`, `.stl`, `.gltf`, `.glb`,
    /// `.lrm`, in any case).
    ///
    /// # Errors
    /// [`Error::UnknownFormat`] when the extension is missing or not one of those.
    pub fn from_path(path: &Path) -> Result<MeshFormat> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("obj") => Ok(MeshFormat::Obj),
            Some("off") => Ok(MeshFormat::Off),
            Some("ply") => Ok(MeshFormat::Ply),
            Some("stl") => Ok(MeshFormat::Stl),
            Some("gltf") => Ok(MeshFormat::Gltf),
            Some("glb") => Ok(MeshFormat::Glb),
            Some("lrm") => Ok(MeshFormat::Lrm),
            Some(other) => Err(Error::UnknownFormat {
                path: path.to_path_buf(),
                reason: format!(
                    "unknown extension `.{other}`; expected .obj, .off, .ply, .stl, .gltf, \
                     .glb or .lrm"
                ),
            }),
            None => Err(Error::UnknownFormat {
                path: path.to_path_buf(),
                reason: "no file extension; expected .obj, .off, .ply, .stl, .gltf, .glb or .lrm"
                    .to_string(),
            }),
        }
    }

    /// The format's name as used in error messages, such as `"OFF"`.
    pub fn name(self) -> &'static str {
        match self {
            MeshFormat::Obj => "OBJ",
            MeshFormat::Off => "OFF",
            MeshFormat::Ply => "PLY",
            MeshFormat::Stl => "STL",
            MeshFormat::Gltf => "glTF",
            MeshFormat::Glb => "GLB",
            MeshFormat::Lrm => "LRM",
        }
    }
}

impl fmt::Display for MeshFormat {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A mesh with the per-vertex attributes of the formats that have only those (OFF, PLY).
pub(crate) fn vertex_mesh(
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    normals: Option<Vec<[f32; 3]>>,
    texcoords: Option<Vec<[f32; 2]>>,
    colors: Option<Vec<[u8; 4]>>,
) -> Mesh {
    use crate::mesh::{Attribute, Semantic};
    let mut mesh = Mesh::new(positions, triangles);
    if let Some(n) = normals {
        mesh.attributes
            .push(Attribute::per_vertex(Semantic::Normal, &n));
    }
    if let Some(t) = texcoords {
        mesh.attributes
            .push(Attribute::per_vertex(Semantic::TexCoord(0), &t));
    }
    if let Some(c) = colors {
        mesh.attributes.push(Attribute::rgba8(&c));
    }
    mesh
}

/// Options for the readers.
#[derive(Debug, Clone, Default)]
pub struct ReadOptions {
    /// Merge vertices whose positions are bit-identical (with `-0.0` equal to `0.0`) into one
    /// vertex, numbered in order of first appearance, in every format. Without it every
    /// triangle corner of an STL file is a vertex of its own, a glTF file keeps its vertices
    /// as stored (split wherever an attribute changes), and OBJ, OFF and PLY keep theirs. But
    /// for STL (which has no attributes) the merge is [`Mesh::weld`]: attributes that differ
    /// between merged vertices become per corner, so every corner keeps its values.
    pub weld: bool,
}

/// A mesh read from a file, with what the reader noticed but did not refuse.
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The mesh.
    pub mesh: Mesh,
    /// Human-readable notes about data that was skipped or adjusted, one per kind of issue.
    pub warnings: Vec<String>,
}

/// Reads a mesh file, choosing the format by the file's extension. A `.gltf`'s external
/// buffers are read from the file's directory ([`gltf::read_file`]).
///
/// # Errors
/// [`Error::UnknownFormat`] for an unknown extension, [`Error::Io`] when the file cannot be
/// read, [`Error::Parse`] (with the file name attached) when it is malformed.
pub fn read_mesh(path: &Path, opts: &ReadOptions) -> Result<Loaded> {
    let format = MeshFormat::from_path(path)?;
    if matches!(format, MeshFormat::Gltf | MeshFormat::Glb) {
        return gltf::read_file(path, opts);
    }
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    read_mesh_bytes(&bytes, format, opts).map_err(|e| e.with_file(path))
}

/// Reads a mesh from the bytes of a file in the given format. A `.gltf` must hold its buffers
/// in `data:` URIs (with bytes alone, there is no directory to find external ones in; see
/// [`gltf::read_with`]).
///
/// # Errors
/// [`Error::Parse`] when the bytes are not a valid file of that format ([`Error::Format`] and
/// the container reader's errors for `.lrm`).
pub fn read_mesh_bytes(bytes: &[u8], format: MeshFormat, opts: &ReadOptions) -> Result<Loaded> {
    let loaded = match format {
        MeshFormat::Obj => obj::read(bytes, opts).map(|l| welded(l, opts)),
        MeshFormat::Off => off::read(bytes, opts).map(|l| welded(l, opts)),
        MeshFormat::Ply => ply::read(bytes, opts).map(|l| welded(l, opts)),
        MeshFormat::Stl => stl::read(bytes, opts),
        MeshFormat::Gltf | MeshFormat::Glb => gltf::read(bytes, opts),
        MeshFormat::Lrm => Ok(Loaded {
            mesh: crate::read::open_verified(bytes, &crate::read::Limits::default())?.to_mesh(),
            warnings: Vec::new(),
        }),
    }?;
    debug_assert!(loaded.mesh.validate().is_ok());
    Ok(loaded)
}

/// `loaded`, welded ([`Mesh::weld`]) when `opts` ask for it: the OBJ, OFF and PLY readers
/// read vertices as stored; STL and glTF weld as they read.
fn welded(mut loaded: Loaded, opts: &ReadOptions) -> Loaded {
    if opts.weld {
        loaded.mesh = loaded.mesh.weld();
    }
    loaded
}

/// Writes a mesh to a file, choosing the format by the file's extension: OBJ, OFF, binary
/// little-endian PLY, binary STL (positions only: every triangle its own corners, attributes and
/// parts lost; [`stl::write_ascii`] writes ASCII), self-contained glTF ([`gltf::write_gltf`]),
/// GLB ([`gltf::write_glb`]) or a container.
///
/// # Errors
/// [`Error::UnknownFormat`] for an unknown extension; [`Error::InvalidMesh`] when the mesh does
/// not validate; [`Error::Io`] when writing fails.
pub fn write_mesh(path: &Path, mesh: &Mesh) -> Result<()> {
    let format = MeshFormat::from_path(path)?;
    mesh.validate()?;
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::create(path).map_err(io_err)?;
    if format == MeshFormat::Lrm {
        let mut out = std::io::BufWriter::new(file);
        return crate::write::encode_to(&mut out, mesh, &Default::default())
            .and_then(|()| {
                out.flush().map_err(|source| Error::Io {
                    path: path.to_path_buf(),
                    source,
                })
            })
            .map_err(|e| match e {
                Error::Io { source, .. } => io_err(source),
                other => other,
            });
    }
    write_format(file, mesh, format).map_err(io_err)
}

/// Writes a mesh in the given format to a writer, as [`write_mesh`] does.
///
/// # Errors
/// [`Error::InvalidMesh`] when the mesh does not validate; [`Error::Io`] (with the path
/// `<output>`) when writing fails.
pub fn write_mesh_to<W: Write>(w: W, mesh: &Mesh, format: MeshFormat) -> Result<()> {
    mesh.validate()?;
    let io_err = |source| Error::Io {
        path: PathBuf::from("<output>"),
        source,
    };
    if format == MeshFormat::Lrm {
        let mut w = w;
        return crate::write::encode_to(&mut w, mesh, &Default::default()).map_err(|e| match e {
            Error::Io { source, .. } => io_err(source),
            other => other,
        });
    }
    write_format(w, mesh, format).map_err(io_err)
}

fn write_format<W: Write>(w: W, mesh: &Mesh, format: MeshFormat) -> std::io::Result<()> {
    match format {
        MeshFormat::Obj => obj::write(w, mesh),
        MeshFormat::Off => off::write(w, mesh),
        MeshFormat::Ply => ply::write(w, mesh),
        MeshFormat::Stl => stl::write_binary(w, mesh),
        MeshFormat::Gltf => gltf::write_gltf(w, mesh),
        MeshFormat::Glb => gltf::write_glb(w, mesh),
        // Containers are written by `write::encode_to`, before this is reached.
        MeshFormat::Lrm => Err(std::io::Error::other(
            "containers are not a text mesh format",
        )),
    }
}

/// Largest vertex count a reader may produce (see [`Mesh::validate`]).
pub(crate) const MAX_VERTICES: u64 = u32::MAX as u64 - 1;
/// Largest triangle count a reader may produce (see [`Mesh::validate`]).
pub(crate) const MAX_TRIANGLES: u64 = (u32::MAX / 3) as u64 - 1;

/// A parse error as an [`Error`].
pub(crate) fn perr(format: &'static str, location: Location, message: impl Into<String>) -> Error {
    Error::from(ParseError::new(format, location, message))
}

/// Appends the fan triangulation of `poly` to `tris`. `poly` has at least 3 vertices.
///
/// # Errors
/// A message when the triangle count would pass [`MAX_TRIANGLES`].
pub(crate) fn push_fan(tris: &mut Vec<[u32; 3]>, poly: &[u32]) -> Result<(), String> {
    debug_assert!(poly.len() >= 3);
    let new = poly.len().saturating_sub(2) as u64;
    if tris.len() as u64 + new > MAX_TRIANGLES {
        return Err(format!(
            "the mesh would have more than {MAX_TRIANGLES} triangles"
        ));
    }
    let v0 = poly[0];
    tris.extend(poly[1..].windows(2).map(|w| [v0, w[0], w[1]]));
    Ok(())
}

/// A color channel given as a fraction in `0..=1` (clamped) as an 8-bit value.
pub(crate) fn unit_to_u8(x: f64) -> u8 {
    (x.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// An 8-bit color channel as the fraction that [`unit_to_u8`] maps back to it.
pub(crate) fn u8_to_unit(c: u8) -> f32 {
    f32::from(c) / 255.0
}

/// Colors as read from a text file, before the file-wide choice between integers in `0..=255`
/// and fractions in `0..=1`: fractions when any component is written with a decimal point or
/// exponent or when no component exceeds 1, integers otherwise (then a component above 255 is
/// an error).
pub(crate) struct RawColors {
    format: &'static str,
    /// RGBA values; a missing alpha is `None`.
    values: Vec<([f32; 4], bool)>,
    /// Vertex lines that had a color.
    pub(crate) count: u64,
    /// Some component was written with a decimal point or exponent.
    float_syntax: bool,
    /// Largest component, with its line.
    max: Option<(f32, u64)>,
}

impl RawColors {
    pub(crate) fn new(format: &'static str) -> RawColors {
        RawColors {
            format,
            values: Vec::new(),
            count: 0,
            float_syntax: false,
            max: None,
        }
    }

    /// Adds the color of a vertex line (3 or 4 components).
    pub(crate) fn push(&mut self, toks: &[&[u8]], line: u64, vertex: u64) -> Result<()> {
        let mut c = [0.0f32; 4];
        for (k, tok) in toks.iter().enumerate() {
            let v = lex::parse_f32(tok, "color component").map_err(|m| {
                perr(
                    self.format,
                    Location::Line(line),
                    format!("vertex {vertex}: {m}"),
                )
            })?;
            if v < 0.0 {
                return Err(perr(
                    self.format,
                    Location::Line(line),
                    format!(
                        "vertex {vertex}: negative color component `{}`",
                        lex::show(tok)
                    ),
                ));
            }
            if !lex::is_integer_syntax(tok) {
                self.float_syntax = true;
            }
            if self.max.is_none_or(|(m, _)| v > m) {
                self.max = Some((v, line));
            }
            c[k] = v;
        }
        self.values.push((c, toks.len() == 4));
        self.count += 1;
        Ok(())
    }

    /// The colors as RGBA bytes, by the file-wide rule above; a missing alpha is 255.
    pub(crate) fn finish(self, warnings: &mut Vec<String>) -> Result<Vec<[u8; 4]>> {
        let max = self.max.map_or(0.0, |(m, _)| m);
        let fractions = self.float_syntax || max <= 1.0;
        if !fractions {
            if let Some((m, line)) = self.max.filter(|&(m, _)| m > 255.0) {
                return Err(perr(
                    self.format,
                    Location::Line(line),
                    format!("integer color component {m} is outside 0..=255"),
                ));
            }
        }
        let mut clamped = 0u64;
        let colors = self
            .values
            .into_iter()
            .map(|(c, has_alpha)| {
                let mut out = [255u8; 4];
                let n = if has_alpha { 4 } else { 3 };
                for k in 0..n {
                    out[k] = if fractions {
                        if c[k] > 1.0 {
                            clamped += 1;
                        }
                        unit_to_u8(f64::from(c[k]))
                    } else {
                        c[k] as u8
                    };
                }
                out
            })
            .collect();
        if clamped > 0 {
            warnings.push(format!(
                "{clamped} color components above 1 were clamped (colors are read as fractions \
                 in 0..1 because some component has a decimal point)"
            ));
        }
        Ok(colors)
    }
}

/// Formats an `f32` in the shortest text that parses back to the same bits: plain decimal for
/// ordinary magnitudes, scientific notation for very large and very small ones.
pub(crate) struct Float(pub f32);

impl fmt::Display for Float {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let a = self.0.abs();
        if a == 0.0 || (1e-5..1e7).contains(&a) {
            write!(f, "{}", self.0)
        } else {
            write!(f, "{:e}", self.0)
        }
    }
}

/// Checks a mesh before a format writer indexes into it, so that a writer handed an invalid
/// mesh returns an error instead of panicking.
pub(crate) fn check_writable(mesh: &Mesh) -> std::io::Result<()> {
    mesh.validate()
        .map_err(|e| std::io::Error::new(std::io::ErrorKind::InvalidInput, e.to_string()))
}

/// The mesh of `corpus/meshes/NAME`, read with the default options (the unit tests' real
/// meshes).
#[cfg(test)]
pub(crate) fn corpus_mesh(name: &str) -> Mesh {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("corpus/meshes")
        .join(name);
    read_mesh(&path, &Default::default()).unwrap().mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn float_text_round_trips() {
        let xs = [
            0.0f32,
            -0.0,
            1.0,
            -1.5,
            0.1,
            1e-5,
            9.999_999e-6,
            1e7,
            f32::MAX,
            f32::MIN_POSITIVE,
            1e-45,
            -3.4e-40,
            123_456.79,
        ];
        for x in xs {
            let s = Float(x).to_string();
            let y: f32 = s.parse().unwrap();
            assert_eq!(x.to_bits(), y.to_bits(), "{x} written as {s}");
        }
        assert_eq!(Float(-0.0).to_string(), "-0");
        assert_eq!(Float(1e-45).to_string(), "1e-45");
    }

    #[test]
    fn colors_round_trip() {
        for c in 0..=255u8 {
            assert_eq!(unit_to_u8(f64::from(u8_to_unit(c))), c);
            let s = Float(u8_to_unit(c)).to_string();
            assert_eq!(unit_to_u8(s.parse::<f32>().unwrap().into()), c);
        }
    }

    #[test]
    fn format_from_path() {
        assert_eq!(
            MeshFormat::from_path(Path::new("a/B.OfF")).unwrap(),
            MeshFormat::Off
        );
        assert!(MeshFormat::from_path(Path::new("a/b")).is_err());
        assert_eq!(
            MeshFormat::from_path(Path::new("a/b.GLB")).unwrap(),
            MeshFormat::Glb
        );
        assert_eq!(
            MeshFormat::from_path(Path::new("b.gltf")).unwrap(),
            MeshFormat::Gltf
        );
        assert!(MeshFormat::from_path(Path::new("a/b.fbx")).is_err());
    }
}
