//! The `GEOM` section (FORMAT.md §3.3): positions stored raw or in random-access blocks are
//! read in place; the predicted encodings of Edgebreaker (GEOMETRY.md) are decoded once,
//! when the container is opened, with the decoded connectivity.

use super::fields::Fields;
use super::Sections;
use crate::corner_table::CornerTable;
use crate::error::{Result, Rule};
use crate::format::layout::geom;
use crate::format::{le_f32, PositionEncoding, Tag};
use crate::geometry::blocked::BlockedView;
use crate::geometry::{self, Grid};

/// Positions as stored.
#[derive(Debug, Clone, PartialEq)]
pub enum Positions<'a> {
    /// Three f32 per vertex (encoding 0).
    F32(&'a [u8]),
    /// A bounding box and three u16 per vertex (encoding 1, lossy).
    Quantized16 {
        /// Minimum corner of the box.
        lo: [f32; 3],
        /// Maximum corner of the box.
        hi: [f32; 3],
        /// The coordinates.
        data: &'a [u8],
    },
    /// Predicted and range coded in Edgebreaker decode order (encodings 2 and 3), decoded
    /// when the container was opened.
    Decoded {
        /// The grid of a lossy file (encoding 2); `None` for exact f32 (encoding 3).
        grid: Option<Grid>,
        /// Every container vertex's position.
        positions: Vec<[f32; 3]>,
    },
    /// Random-access blocks (encodings 4 and 5).
    Blocked(BlockedView<'a>),
}

impl Positions<'_> {
    /// The position of container vertex `i` (below the vertex count).
    #[inline]
    pub fn get(&self, i: usize) -> [f32; 3] {
        match self {
            Positions::F32(b) => [0, 1, 2].map(|k| le_f32(b, 12 * i + 4 * k)),
            Positions::Quantized16 { lo, hi, data } => [0, 1, 2].map(|k| {
                let at = 6 * i + 2 * k;
                let q = u16::from_le_bytes([data[at], data[at + 1]]) as f64;
                (lo[k] as f64 + q / 65535.0 * (hi[k] as f64 - lo[k] as f64)) as f32
            }),
            Positions::Decoded { positions, .. } => positions[i],
            Positions::Blocked(b) => b.position(i),
        }
    }

    /// The grid of a lossy encoding but encoding 1 (whose step differs per axis); `None`
    /// for exact positions.
    pub fn grid(&self) -> Option<Grid> {
        match self {
            Positions::F32(_) | Positions::Quantized16 { .. } => None,
            Positions::Decoded { grid, .. } => *grid,
            Positions::Blocked(b) => b.grid(),
        }
    }

    /// Whether the positions are lossy (quantized).
    pub fn is_quantized(&self) -> bool {
        matches!(self, Positions::Quantized16 { .. }) || self.grid().is_some()
    }
}

/// The `GEOM` section's encoding, and its positions unless they need the connectivity to
/// decode (`None`: call [`decode`] once it is built).
pub(super) fn positions<'a>(
    sections: &Sections<'a>,
    m: u32,
    verify: bool,
) -> Result<(PositionEncoding, Option<Positions<'a>>)> {
    let f = Fields::new(sections.required(Tag::GEOM)?);
    let rule = Rule(13);
    let encoding = PositionEncoding(f.u32(0, rule)?);
    if f.u32(4, rule)? != 0 {
        return Err(f.err(4, rule, "reserved field is not zero"));
    }
    let m = m as u64;
    let positions = match encoding {
        PositionEncoding::F32 => {
            let len = m
                .checked_mul(geom::F32_VERTEX_LEN)
                .and_then(|x| x.checked_add(geom::HEADER_LEN as u64));
            f.expect_len(len, rule)?;
            f.expect_finite(geom::HEADER_LEN..f.len(), rule)?;
            Some(Positions::F32(&f.bytes()[geom::HEADER_LEN..]))
        }
        PositionEncoding::QUANTIZED16 => {
            let data_at = geom::HEADER_LEN + geom::BOX_LEN;
            let len = m
                .checked_mul(geom::Q16_VERTEX_LEN)
                .and_then(|x| x.checked_add(data_at as u64));
            f.expect_len(len, rule)?;
            let (lo, hi) = bounding_box(&f, rule)?;
            Some(Positions::Quantized16 {
                lo,
                hi,
                data: &f.bytes()[data_at..],
            })
        }
        PositionEncoding::PREDICTED_GRID
        | PositionEncoding::PREDICTED_F32
        | PositionEncoding::ANCHORED_GRID => None,
        PositionEncoding::BLOCKED | PositionEncoding::BLOCKED_F32 => {
            Some(Positions::Blocked(BlockedView::parse(&f, m, verify)?))
        }
        other => {
            return Err(f.err(0, rule, format!("unknown position encoding {}", other.0)));
        }
    };
    Ok((encoding, positions))
}

/// The grid of encodings 2 and 4 at offset 8 of the section: the box minimum (three f32),
/// the size (f32), the bits (u32). [V13]: finite, size at least 0, bits 1 to 30.
pub(crate) fn grid(f: &Fields, rule: Rule) -> Result<Grid> {
    let at = geom::HEADER_LEN;
    f.expect_at_least(at + geom::GRID_LEN, rule)?;
    f.expect_finite(at..at + 16, rule)?;
    let b = f.bytes();
    let lo: [f32; 3] = std::array::from_fn(|i| le_f32(b, at + 4 * i));
    let size = le_f32(b, at + 12);
    if size < 0.0 {
        return Err(f.err(at + 12, rule, format!("grid size {size} is negative")));
    }
    let bits = f.u32(at + 16, rule)?;
    if !(1..=geometry::MAX_GRID_BITS as u32).contains(&bits) {
        return Err(f.err(
            at + 16,
            rule,
            format!("{bits} bits per coordinate, not 1 to 30"),
        ));
    }
    Ok(Grid {
        lo,
        size,
        bits: bits as u8,
    })
}

/// The bounding box at offset 8 of the section: finite, minimum at most maximum ([V13]).
pub(crate) fn bounding_box(f: &Fields, rule: Rule) -> Result<([f32; 3], [f32; 3])> {
    let at = geom::HEADER_LEN;
    f.expect_at_least(at + geom::BOX_LEN, rule)?;
    f.expect_finite(at..at + geom::BOX_LEN, rule)?;
    let b = f.bytes();
    let lo: [f32; 3] = std::array::from_fn(|i| le_f32(b, at + 4 * i));
    let hi: [f32; 3] = std::array::from_fn(|i| le_f32(b, at + 12 + 4 * i));
    if let Some(i) = (0..3).find(|&i| lo[i] > hi[i]) {
        return Err(f.err(at + 4 * i, rule, "bounding box minimum above its maximum"));
    }
    Ok((lo, hi))
}

/// Decodes a predicted encoding (2, 3 or 6) with the Edgebreaker connectivity's corner table.
pub(super) fn decode<'a>(
    sections: &Sections<'a>,
    encoding: PositionEncoding,
    table: Option<&CornerTable>,
) -> Result<Positions<'a>> {
    let f = Fields::new(sections.required(Tag::GEOM)?);
    let anchored = encoding == PositionEncoding::ANCHORED_GRID;
    let rule = Rule(if anchored { 55 } else { 44 });
    let Some(table) = table else {
        return Err(f.err(
            0,
            rule,
            format!(
                "position encoding {} needs the Edgebreaker connectivity",
                encoding.0
            ),
        ));
    };
    if anchored {
        geometry::anchored::decode_section(&f, table)
    } else {
        geometry::predict::decode_section(&f, encoding, table)
    }
}
