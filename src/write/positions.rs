//! The `GEOM` section (FORMAT.md §3.3): which position encoding a container gets, and the
//! raw ones.

use super::EncodeOptions;
use crate::corner_table::CornerTable;
use crate::error::{Error, Result};
use crate::format::layout::{geom, write_fields};
use crate::format::PositionEncoding;
use crate::geometry::{anchored, blocked, predict, Grid, MAX_GRID_BITS};

/// From this level on, Edgebreaker positions are coded twice, with and without choices among
/// parallelograms (GEOMETRY.md §5), and the smaller kept: twice the position coding time
/// for a few percent on meshes with creases.
const CHOICES_LEVEL: u8 = 4;

/// Up to this level, Edgebreaker positions on a grid take encoding 6 (GEOMETRY.md §9):
/// several times faster to decode than encoding 2, for files a few percent larger.
const ANCHORED_LEVEL: u8 = 2;

/// The `GEOM` payload of `positions` (container order). `table` is the Edgebreaker
/// decoder's corner table, for the predicted encodings.
pub(super) fn section(
    positions: &[[f32; 3]],
    options: &EncodeOptions,
    table: Option<&CornerTable>,
) -> Result<Vec<u8>> {
    let grid = match options.position_bits {
        Some(bits) if !(1..=MAX_GRID_BITS).contains(&bits) => {
            return Err(Error::InvalidArgument(format!(
                "{bits} bits per coordinate: quantization takes 1 to {MAX_GRID_BITS}"
            )))
        }
        Some(bits) => Some(Grid::of(positions.iter().copied(), bits)),
        None => None,
    };
    let raw = options.level == 0;
    Ok(match (grid, table) {
        (Some(grid), Some(table)) if !raw && options.level <= ANCHORED_LEVEL => {
            anchored::encode(table, positions, grid)
        }
        (Some(grid), Some(table)) if !raw => {
            predict::encode_grid(table, positions, grid, options.level >= CHOICES_LEVEL)?
        }
        (None, Some(table)) if !raw => {
            predict::encode_f32(table, positions, options.level >= CHOICES_LEVEL)?
        }
        (Some(grid), _) if grid.bits == 16 && raw => quantized16(positions),
        // Blocks, unless a raw encoding is smaller: vertex ids in an order without locality
        // (the input order of strips may be one) cost more than raw in blocks.
        (Some(grid), _) if grid.bits == 16 => smaller(
            blocked::encode(positions, Some(grid)),
            quantized16(positions),
        ),
        (Some(grid), _) => blocked::encode(positions, Some(grid)),
        (None, _) if !raw => smaller(blocked::encode(positions, None), f32s(positions)),
        (None, _) => f32s(positions),
    })
}

/// `positions` as a reader decodes them from the predicted encodings (2 and 3): on the grid
/// of `options.position_bits`, or exact.
pub(super) fn as_decoded(positions: &[[f32; 3]], options: &EncodeOptions) -> Vec<[f32; 3]> {
    match options.position_bits {
        Some(bits) if (1..=MAX_GRID_BITS).contains(&bits) => {
            let grid = Grid::of(positions.iter().copied(), bits);
            positions
                .iter()
                .map(|&p| grid.dequantize(grid.quantize(p)))
                .collect()
        }
        _ => positions.to_vec(),
    }
}

/// The shorter payload, `a` on a tie.
fn smaller(a: Vec<u8>, b: Vec<u8>) -> Vec<u8> {
    if b.len() < a.len() {
        b
    } else {
        a
    }
}

/// Encoding 0: the f32s as they are.
fn f32s(positions: &[[f32; 3]]) -> Vec<u8> {
    let mut p = Vec::with_capacity(geom::HEADER_LEN + 12 * positions.len());
    write_fields(&mut p, &[PositionEncoding::F32.0, 0]);
    p.extend(positions.iter().flatten().flat_map(|x| x.to_le_bytes()));
    p
}

/// Encoding 1: the box, then three u16 per vertex.
/// The box is the bounding box and each axis has its own step (the 1.0 encoding; written
/// only at level 0).
fn quantized16(positions: &[[f32; 3]]) -> Vec<u8> {
    let (lo, hi) = bounding_box(positions);
    let mut p = Vec::with_capacity(geom::HEADER_LEN + geom::BOX_LEN + 6 * positions.len());
    write_fields(&mut p, &[PositionEncoding::QUANTIZED16.0, 0]);
    p.extend(lo.iter().chain(&hi).flat_map(|x| x.to_le_bytes()));
    for &x in positions {
        for k in 0..3 {
            let e = hi[k] as f64 - lo[k] as f64;
            let q = if e > 0.0 {
                ((x[k] as f64 - lo[k] as f64) / e * 65535.0)
                    .round()
                    .clamp(0.0, 65535.0) as u16
            } else {
                0
            };
            p.extend_from_slice(&q.to_le_bytes());
        }
    }
    p
}

fn bounding_box(positions: &[[f32; 3]]) -> ([f32; 3], [f32; 3]) {
    if positions.is_empty() {
        return ([0.0; 3], [0.0; 3]);
    }
    positions
        .iter()
        .fold(([f32::MAX; 3], [f32::MIN; 3]), |(lo, hi), p| {
            (
                [0, 1, 2].map(|i| lo[i].min(p[i])),
                [0, 1, 2].map(|i| hi[i].max(p[i])),
            )
        })
}
