//! What an encoding takes: the connectivity kind, the orientation repair, the compression
//! level and the options of each part ([`EncodeOptions`]).

use crate::format::Metadata;
use crate::lr::{CompactOptions, LrOptions};
use crate::strips::StripOptions;

/// The connectivity representation a container holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Connectivity {
    /// Standard LR (section `LRTB`): random access, corner queries on the buffer.
    #[default]
    Lr,
    /// Edgebreaker (section `EBRK`): the smallest, decoded sequentially.
    Edgebreaker,
    /// Constrained triangle strips with the adjacent-strips table (section `STRP`): a
    /// rendering index list that also answers corner queries on the buffer.
    Strips,
    /// Bit-efficient LR (section `LRBE`): about 16 bits per triangle plus the irregular
    /// ones, corner queries on the buffer.
    LrCompact,
    /// Zipper (section `ZIPR`): the LR's slots in 3-bit symbols, corner queries on the
    /// buffer.
    Zipper,
}

impl Connectivity {
    /// Every kind, for a caller that tries them all.
    pub const ALL: [Connectivity; 5] = [
        Connectivity::Lr,
        Connectivity::LrCompact,
        Connectivity::Zipper,
        Connectivity::Strips,
        Connectivity::Edgebreaker,
    ];
}

/// Whether the writer makes the triangles' orientation consistent first (`lrmesh encode
/// --orient`): an edge two triangles use in the same direction cuts the surface there, so
/// a mesh with mixed orientations costs every representation more.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Orient {
    /// [`Orient::Repair`] when it makes the file smaller: a mesh whose corner table cuts an
    /// edge two triangles use in the same direction is also encoded repaired, with `FLIP`
    /// (one bit per triangle), and the smaller file is kept (such a mesh is encoded twice);
    /// any other mesh as given, at no cost. Either way decoding gives back the input's
    /// triangles. (A connectivity built already, [`encode_built`](super::encode_built), is
    /// stored as given.)
    #[default]
    Auto,
    /// The triangles as given.
    AsGiven,
    /// Reverse triangles as [`crate::mesh::orient`] says, and record them in section `FLIP`
    /// so that decoding gives back the input's triangles; the corner operators answer on
    /// the repaired surface.
    Repair,
    /// The same without `FLIP`: decoding gives the repaired triangles.
    RepairAndKeep,
}

/// The compression level of [`EncodeOptions::default`].
pub const DEFAULT_LEVEL: u8 = 6;

/// How to encode.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct EncodeOptions {
    /// The connectivity representation.
    pub connectivity: Connectivity,
    /// Options of the LR construction.
    pub lr: LrOptions,
    /// Periods of HYBRID-RING-EXPANDER tried for [`Connectivity::LrCompact`] (0: depth
    /// first); the smallest result is stored.
    pub periods: Vec<u32>,
    /// Tip bases of [`Connectivity::LrCompact`] ([`CompactOptions::tip_bases`]): `None` when
    /// they make the section smaller.
    pub tip_bases: Option<bool>,
    /// Options of the stripper, for [`Connectivity::Strips`] (fans are never used).
    pub strips: StripOptions,
    /// Store the permutations back to the input's vertex and triangle order.
    pub keep_order: bool,
    /// Make the orientation consistent first ([`Orient`]).
    pub orient: Orient,
    /// Positions on a grid of this many bits per coordinate (1 to 30) in their bounding box,
    /// within half a step of their value (lossy); `None` keeps the f32s exactly.
    pub position_bits: Option<u8>,
    /// Compression level, 0 to 9. Level 0 stores positions raw (f32, or 16-bit words), the
    /// fastest to write and to open; from level 1 they are coded: predicted and range coded
    /// for Edgebreaker, in random-access blocks for the other kinds. From level 6 the Zipper
    /// of a small mesh is the smallest of several seeds'
    /// ([`zipper_seeds`](super::zipper_seeds)).
    pub level: u8,
    /// f32 normals stored octahedral, two integers of this many bits (1 to 24) per normal
    /// (FORMAT.md §3.9.1): lossy; `None` keeps the f32s exactly.
    pub normal_bits: Option<u8>,
    /// f32 texture coordinates and custom attributes on a grid of this many bits per
    /// component (1 to 30) over their range, within half a step (lossy); `None` keeps them.
    pub texcoord_bits: Option<u8>,
    /// f32 colors on a grid of this many bits per component (1 to 30); integer colors are
    /// always stored as they are. `None` keeps them.
    pub color_bits: Option<u8>,
    /// The metadata to store.
    pub metadata: Metadata,
}

impl Default for EncodeOptions {
    fn default() -> Self {
        EncodeOptions {
            connectivity: Connectivity::Lr,
            lr: LrOptions::default(),
            periods: CompactOptions::default().periods,
            tip_bases: None,
            strips: StripOptions::default(),
            keep_order: false,
            orient: Orient::Auto,
            position_bits: None,
            level: DEFAULT_LEVEL,
            normal_bits: None,
            texcoord_bits: None,
            color_bits: None,
            metadata: Metadata {
                generator: format!("lrmesh {}", env!("CARGO_PKG_VERSION")),
                ..Metadata::default()
            },
        }
    }
}
