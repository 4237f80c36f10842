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
//! Two levels of checking (`spec/FORMAT.md` §5.1), as robust readers have:
//!
//! - [`open`] checks that the file is well formed (header, section table, checksums, counts,
//!   every stored id and offset in range, the slots the operators jump to) in one pass, so
//!   that afterwards no operator of the view can panic on a corner of the mesh, read out of
//!   bounds or answer an id out of range, and every walk ends;
//! - [`open_verified`] (or [`Container::verify`] later) also checks the semantic rules, so
//!   that the answers are the mesh's: opposites face each other, vertex corners start their
//!   fans, walks stay within a fan.
//!
//! Nothing is allocated beyond a bound of the input's length: the view borrows its tables,
//! and the per-vertex marks that validation needs are bounded by counts already checked
//! against the bytes present.

pub mod attributes;
mod counts;
mod decode;
mod edgebreaker;
pub(crate) mod fields;
mod lr;
mod lr_compact;
mod lr_compact_scan;
mod lr_rules;
pub mod parts;
pub(crate) mod positions;
mod quick;
pub mod sections;
mod strips;
pub mod summary;
pub mod view;
mod zipper;
mod zipper_scan;

pub use attributes::AttributeView;
pub use parts::PartsView;
pub use positions::Positions;
pub use quick::summarize;
pub use sections::{Section, Sections};
pub use summary::{ContainerSummary, SectionSummary};
pub use view::{Connectivity, Container};

use crate::error::Result;

/// The rules that [`open`] leaves, wholly or in part, to [`open_verified`] (FORMAT.md
/// §5.1): whether opposites face each other, fans start where `v.c` says, the LR flags hold,
/// each LR record is used once and the decoded values of blocked positions are in range. A
/// file that breaks only these still answers every operator with an id in range.
pub const SEMANTIC_RULES: [crate::Rule; 9] = [
    crate::Rule(17),
    crate::Rule(21),
    crate::Rule(22),
    crate::Rule(23),
    crate::Rule(31),
    crate::Rule(32),
    crate::Rule(38),
    crate::Rule(45),
    crate::Rule(53),
];

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

/// Parses a container and checks that it is well formed (FORMAT.md §5.1: every rule but the
/// semantic ones), at close to the speed of reading its bytes. Every operator of the view
/// answers ids in range and every walk ends; on a file that breaks a semantic rule the
/// answers are unspecified. [`open_verified`] checks every rule.
///
/// # Errors
/// [`Error::Format`](crate::Error::Format) naming the section, byte offset and rule of
/// `spec/FORMAT.md` of the first broken rule; [`Error::UnsupportedVersion`](crate::Error::UnsupportedVersion);
/// [`Error::UnknownRequiredSection`](crate::Error::UnknownRequiredSection);
/// [`Error::LimitExceeded`](crate::Error::LimitExceeded).
pub fn open<'a>(bytes: &'a [u8], limits: &Limits) -> Result<Container<'a>> {
    Container::new(Sections::parse(bytes, limits)?, limits, false)
}

/// `mesh` encoded with `options`, as its sections `(tag, flags, payload)`, and the index of
/// the one tagged `tag`: the file that the readers' fast-pass tests forge.
#[cfg(test)]
pub(crate) fn encoded_sections(
    mesh: &crate::mesh::Mesh,
    options: &crate::write::EncodeOptions,
    tag: crate::format::Tag,
) -> (Vec<crate::write::SectionBytes>, usize) {
    let bytes = crate::write::encode(mesh, options).expect("a generated mesh encodes");
    let sections = open(&bytes, &Limits::default())
        .expect("what we write opens")
        .sections
        .to_section_bytes();
    let at = sections
        .iter()
        .position(|s| s.0 == tag)
        .unwrap_or_else(|| panic!("a {tag:?} section"));
    (sections, at)
}

/// Reads `cases` containers of connectivity kind `kind` (bits 0–2 of the fuzz targets' first
/// byte; the other bits, chosen from `seed`, pick the mesh and options) forged as the fuzz
/// targets forge them: units copied over others (`operators`) or bytes overwritten
/// (`container_forged`), the checksums recomputed. For the tests of the readers' fast
/// passes, which the readers check against their fault-finding loops under `cfg(test)`.
#[cfg(all(test, feature = "fuzz-checks"))]
pub(crate) fn read_forged_files(kind: u8, seed: u64, cases: usize) {
    let mut rng = crate::rng::Rng::new(seed);
    for case in 0..cases {
        let choice = kind | (rng.below(32) as u8) << 3;
        let mut data = vec![choice];
        for _ in 0..4 * (1 + rng.below(4)) {
            data.push(rng.below(256) as u8);
        }
        if case % 2 == 0 {
            crate::fuzz_checks::operators(&data);
        } else {
            crate::fuzz_checks::container_forged(&data);
        }
    }
}

/// Parses a container and checks every rule of FORMAT.md, the semantic ones included: the
/// operators' answers are the mesh's.
///
/// # Errors
/// As [`open`], and the semantic rules' [`Error::Format`](crate::Error::Format).
pub fn open_verified<'a>(bytes: &'a [u8], limits: &Limits) -> Result<Container<'a>> {
    Container::new(Sections::parse(bytes, limits)?, limits, true)
}
