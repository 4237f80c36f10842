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
//! Read a shipped mesh, build its LR, store it, and walk a vertex's neighbours on the stored
//! bytes; the answers are the corner table's.
//!
//! ```
//! use lrmesh::io::{read_mesh, ReadOptions};
//! use lrmesh::lr::{Lr, LrOptions};
//! use lrmesh::ops::{self, CornerOps};
//! use lrmesh::read::{self, Limits};
//! use lrmesh::write::{self, EncodeOptions};
//! use lrmesh::{CornerTable, Vertex};
//!
//! # fn main() -> Result<(), lrmesh::Error> {
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/corpus/meshes/knot1.off");
//! let mesh = read_mesh(path.as_ref(), &ReadOptions::default())?.mesh;
//! assert_eq!(mesh.triangle_count(), 6400);
//!
//! // Corner table (3 V + 3 O references per triangle) and LR (about 1 per triangle).
//! let table = CornerTable::from_mesh(&mesh)?;
//! let lr = Lr::build(&table, &LrOptions::default())?;
//! assert!(lr.counts().references_per_triangle() < 1.5);
//!
//! // The container, validated once, then queried in place.
//! let bytes = write::encode(&mesh, &EncodeOptions::default())?;
//! let view = read::open(&bytes, &Limits::default())?;
//! let stored = view.lr().expect("LR connectivity");
//!
//! // The same vertex has the same neighbours in the corner table and in the file.
//! let v = Vertex(17);
//! let input = lr.input_vertex(v);
//! let mut from_file: Vec<u32> = ops::star(stored, v)
//!     .map(|c| lr.input_vertex(stored.vertex(stored.next(c))))
//!     .collect();
//! let mut from_table: Vec<u32> = ops::star(&table, Vertex(input))
//!     .map(|c| table.vertex(table.next(c)).0)
//!     .collect();
//! from_file.sort();
//! from_table.sort();
//! assert_eq!(from_file, from_table);
//! # Ok(())
//! # }
//! ```
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod bench;
pub mod corner_table;
pub mod edgebreaker;
pub mod error;
pub mod format;
pub mod generate;
pub mod ids;
pub mod io;
pub mod lr;
pub mod mesh;
pub mod ops;
pub mod read;
pub mod render;
pub mod strips;
pub mod topology;
pub mod write;

pub use corner_table::CornerTable;
pub use error::{Error, FormatError, Location, ParseError, Result};
pub use ids::{Corner, Triangle, Vertex};
pub use mesh::Mesh;
pub use ops::CornerOps;
pub use topology::TopologyReport;

/// The README's code compiles (`cargo test --doc`).
#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
