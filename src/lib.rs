//! lrmesh: compact, random-access connectivity for triangle meshes.
#![deny(missing_docs)]
#![forbid(unsafe_code)]

pub mod error;
pub mod ids;
pub mod io;
pub mod mesh;

pub use error::{Error, Location, ParseError, Result};
pub use ids::{Corner, Triangle, Vertex};
pub use mesh::Mesh;
