//! lrmesh: compact, random-access connectivity for triangle meshes.
//!
//! The crate reads and writes indexed triangle meshes ([`io`]), builds a corner table for any
//! triangle set, however broken ([`corner_table`]), reports its topology ([`topology`]), and
//! offers the standard corner operators through one trait ([`ops::CornerOps`]) that every
//! connectivity representation implements: the Laced Ring ([`lr`], about one reference per
//! triangle), Edgebreaker ([`edgebreaker`], about one bit per triangle, decoded
//! sequentially) and triangle strips ([`strips`]). The `.lrm` container
//! ([`write`](mod@write), [`read`]) stores an LR so that the operators run on the file's
//! bytes, with no copy. [`render`] draws an LR as a PNG; [`bench`](mod@bench) compares the
//! representations in one run.
//!
//! No input makes the library panic: malformed files and meshes give an [`Error`].
//!
//! # Example
//!
//! Save a mesh, load it back, open the file's bytes and walk a vertex's star on them:
//!
//! ```
//! # fn main() -> Result<(), lrmesh::Error> {
//! # let dir = std::env::temp_dir().join(format!("lrmesh-doc-{}", std::process::id()));
//! # std::fs::create_dir_all(&dir).unwrap();
//! # let path = dir.join("knot.lrm");
//! let mesh = lrmesh::load(concat!(env!("CARGO_MANIFEST_DIR"), "/corpus/meshes/knot1.off"))?;
//! lrmesh::save(&path, &mesh)?;                        // format by extension: .lrm
//! let bytes = std::fs::read(&path).unwrap();
//! let file = lrmesh::open(&bytes)?;                   // validated once, then zero-copy
//! for c in lrmesh::ops::star(file.connectivity(), lrmesh::Vertex(17)) { /* c.v, c.o, ... */ }
//! # assert_eq!(lrmesh::load(&path)?.triangle_count(), mesh.triangle_count());
//! # std::fs::remove_dir_all(&dir).ok();
//! # Ok(())
//! # }
//! ```
//!
//! The representations are there to use directly too: [`CornerTable::from_mesh`],
//! [`lr::Lr::build`], [`write::encode_built`] to store what was built without building it
//! again, and [`read::open`] with [`read::Limits`] of one's own.
#![deny(missing_docs)]
#![forbid(unsafe_code)]

#[cfg(feature = "bench")]
pub mod bench;
pub mod corner_table;
pub mod edgebreaker;
pub mod error;
pub mod format;
#[cfg(feature = "fuzz-checks")]
#[doc(hidden)]
pub mod fuzz_checks;
#[cfg(feature = "generate")]
pub mod generate;
pub mod geometry;
pub mod ids;
pub mod io;
pub mod lr;
pub mod mesh;
pub mod ops;
pub mod progress;
pub mod read;
#[cfg(feature = "render")]
pub mod render;
mod rng;
pub mod strips;
pub mod topology;
pub mod write;

pub mod words;

pub use corner_table::CornerTable;
pub use error::{Error, FormatError, Location, ParseError, Result, Rule};
pub use ids::{Corner, Triangle, Vertex};
pub use mesh::Mesh;
pub use ops::CornerOps;
pub use read::Container;
pub use topology::TopologyReport;

/// Reads a mesh file of any supported format, chosen by its extension: `.obj`, `.off`,
/// `.ply`, `.stl`, `.gltf`, `.glb` or `.lrm` (a container, fully validated and decoded).
///
/// # Errors
/// [`Error::UnknownFormat`], [`Error::Io`], [`Error::Parse`] or the container reader's
/// errors, with the file named.
pub fn load(path: impl AsRef<std::path::Path>) -> Result<Mesh> {
    Ok(io::read_mesh(path.as_ref(), &io::ReadOptions::default())?.mesh)
}

/// Writes a mesh file in the format its extension names: `.lrm` with default
/// [`write::EncodeOptions`], or `.obj`, `.off`, `.ply`, `.stl`, `.gltf`, `.glb`.
///
/// # Errors
/// [`Error::UnknownFormat`], [`Error::InvalidMesh`], [`Error::Io`].
pub fn save(path: impl AsRef<std::path::Path>, mesh: &Mesh) -> Result<()> {
    io::write_mesh(path.as_ref(), mesh)
}

/// Writes a container (whatever the extension) with the given options.
///
/// # Errors
/// As [`write::encode`], and [`Error::Io`] naming the file.
pub fn save_with(
    path: impl AsRef<std::path::Path>,
    mesh: &Mesh,
    options: &write::EncodeOptions,
) -> Result<()> {
    use std::io::Write as _;
    let path = path.as_ref();
    let io_err = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::create(path).map_err(io_err)?;
    let mut out = std::io::BufWriter::new(file);
    write::encode_to(&mut out, mesh, options).map_err(|e| match e {
        Error::Io { source, .. } => io_err(source),
        other => other,
    })?;
    out.flush().map_err(io_err)
}

/// Checks that a container's bytes are well formed, in one pass at close to memory speed,
/// and gives the zero-copy view: the connectivity answering [`CornerOps`] for every kind,
/// positions and attributes, and the map back to the input's vertex ids. Every answer is
/// in range; the semantic rules (opposites that face each other, fans) are checked by
/// [`open_verified`] or [`Container::verify`]. With default [`read::Limits`].
///
/// # Errors
/// [`Error::Format`] naming the section, offset and rule broken, and the other errors of
/// [`read::open`].
pub fn open(bytes: &[u8]) -> Result<Container<'_>> {
    read::open(bytes, &read::Limits::default())
}

/// [`open`], and every semantic rule checked too: the operators' answers are the mesh's.
///
/// # Errors
/// As [`read::open_verified`].
pub fn open_verified(bytes: &[u8]) -> Result<Container<'_>> {
    read::open_verified(bytes, &read::Limits::default())
}

/// The README's code compiles (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
