//! Reading containers from a byte slice (layout and rules: `spec/FORMAT.md`), in rooms:
//!
//! - [`sections`]: the header and section table, checksums (rules V1–V10);
//! - `fields`: section-relative reads whose errors name the section, offset and rule;
//! - `counts`: `META`, `MESH`, `GEOM`, the version-1.0 attributes, `COPY`, `KEPT`, `PERM`;
//! - [`attributes`], [`parts`]: `ATTR` (per-vertex and per-corner attributes, with their
//!   seams) and `PART`;
//! - `lr`, `lr_compact`, `strips`, `edgebreaker`: each connectivity section's rules, and
//!   `lr_rules` for what every LR layout keeps;
//! - [`view`]: the validated [`Container`], answering corner queries on the buffer;
//! - `decode`: the container back to a [`Mesh`](crate::Mesh);
//! - [`summary`]: what `lrmesh info` reports.
//!
//! [`open`] checks every index and invariant the operators rely on, so that afterwards no
//! operator of the view can panic on a corner of the mesh, read out of bounds, return an id
//! that is not the mesh's, or loop forever. Nothing is allocated beyond a bound of the
//! input's length: the view borrows its tables, and the per-vertex marks that validation
//! needs are bounded by counts already checked against the bytes present.

pub mod attributes;
mod counts;
mod decode;
mod edgebreaker;
pub(crate) mod fields;
mod lr;
mod lr_compact;
mod lr_rules;
pub mod parts;
pub(crate) mod positions;
pub mod sections;
mod strips;
pub mod summary;
pub mod view;

pub use attributes::AttributeView;
pub use parts::PartsView;
pub use positions::Positions;
pub use sections::{Section, Sections};
pub use summary::{ContainerSummary, SectionSummary};
pub use view::{Connectivity, Container};

use crate::error::Result;

/// Limits on what a reader accepts, beyond what the file's length bounds anyway. One value
/// reaches every decoder, Edgebreaker's included.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Most sections in one file.
    pub max_sections: u32,
    /// Largest `META` section, in bytes.
    pub max_metadata_bytes: u64,
    /// Most triangles an Edgebreaker stream may declare.
    pub max_edgebreaker_triangles: u64,
    /// Most vertices an Edgebreaker stream may declare.
    pub max_edgebreaker_vertices: u64,
}

impl Default for Limits {
    fn default() -> Self {
        let eb = crate::edgebreaker::Limits::default();
        Limits {
            max_sections: 64,
            max_metadata_bytes: 1 << 20,
            max_edgebreaker_triangles: eb.max_triangles,
            max_edgebreaker_vertices: eb.max_vertices,
        }
    }
}

/// Parses and fully validates a container.
///
/// # Errors
/// [`Error::Format`](crate::Error::Format) naming the section, byte offset and rule of
/// `spec/FORMAT.md` of the first broken rule; [`Error::UnsupportedVersion`](crate::Error::UnsupportedVersion);
/// [`Error::UnknownRequiredSection`](crate::Error::UnknownRequiredSection);
/// [`Error::LimitExceeded`](crate::Error::LimitExceeded).
pub fn open<'a>(bytes: &'a [u8], limits: &Limits) -> Result<Container<'a>> {
    Container::new(Sections::parse(bytes, limits)?, limits)
}
