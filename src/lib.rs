//! lrmesh: compact, random-access connectivity for triangle meshes.
//!
//! The crate reads and writes indexed triangle meshes ([`io`]), builds a corner table for any
//! triangle set, however broken ([`corner_table`]), reports its topology ([`topology`]), and
//! offers the standard corner operators through one trait ([`ops::CornerOps`]) that every
//! connectivity representation implements.
//!
//! No input makes the library panic: malformed files and meshes give an [`Error`].
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
