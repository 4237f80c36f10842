//! Writing random-access position blocks (FORMAT.md §3.3, encodings 4 and 5).

use super::{Shape, MAX_LEVELS};
use crate::format::PositionEncoding;
use crate::geometry::{float, write_grid, Grid};

/// The block sizes tried, as `L`, smallest first. Blocks of 16 to 64 vertices come within
/// a few percent of each other on real meshes; each level more costs a lookup one more
/// residual, so a larger block is kept only when it saves [`LARGER_BLOCK_GAIN`].
const LEVELS_TRIED: [u32; 3] = [4, 5, 6];

/// The part of the section a larger block must save (1%).
const LARGER_BLOCK_GAIN: f64 = 0.01;

/// The `GEOM` payload of `positions` (container order) in blocks: on `grid` (encoding 4),
/// or the f32s exactly as ordered integers (encoding 5).
pub(crate) fn encode(positions: &[[f32; 3]], grid: Option<Grid>) -> Vec<u8> {
    let values: Vec<[i64; 3]> = positions
        .iter()
        .map(|&p| match grid {
            Some(g) => g.quantize(p).map(i64::from),
            None => p.map(|x| float::ordered(x) as i64),
        })
        .collect();
    let mut best = Vec::new();
    crate::progress::phase("positions", LEVELS_TRIED.len() as u64);
    for (tried, levels) in LEVELS_TRIED.into_iter().enumerate() {
        crate::progress::advance(tried as u64);
        let bytes = encode_with(&values, grid, levels);
        if best.is_empty() || (bytes.len() as f64) < best.len() as f64 * (1.0 - LARGER_BLOCK_GAIN) {
            best = bytes;
        }
    }
    best
}

/// The section with blocks of `2^levels` vertices.
pub(super) fn encode_with(values: &[[i64; 3]], grid: Option<Grid>, levels: u32) -> Vec<u8> {
    let blocks = Blocks::of(values, levels);
    let total = blocks.starts.last().copied().unwrap_or(0);
    let start_bits = u64::BITS - total.leading_zeros();
    let shape = Shape::new(grid, levels, start_bits);

    let mut out = Vec::new();
    match grid {
        Some(g) => {
            push_u32(&mut out, PositionEncoding::BLOCKED.0);
            push_u32(&mut out, 0);
            write_grid(&mut out, g);
        }
        None => {
            push_u32(&mut out, PositionEncoding::BLOCKED_F32.0);
            push_u32(&mut out, 0);
        }
    }
    push_u32(&mut out, levels);
    push_u32(&mut out, start_bits);

    let mut dir = BitWriter::new(out);
    for (j, &start) in blocks.starts.iter().enumerate() {
        dir.put(start, start_bits);
        for x in anchor(values, levels, j) {
            dir.put(x as u64, shape.anchor_bits);
        }
        // The end record (no block of its own) has widths 0.
        let widths = blocks.widths.get(j).copied().unwrap_or_default();
        for w in widths.iter().take(levels as usize).flatten() {
            dir.put(*w as u64, shape.width_bits);
        }
    }
    // The data at its final size: growing by doubling would hold up to twice the section.
    let mut bytes = dir.finish();
    bytes.reserve_exact(total.div_ceil(8) as usize);
    let mut data = BitWriter::new(bytes);
    for (j, widths) in blocks.widths.iter().enumerate() {
        block_residuals(values, levels, j, |l, z| {
            for k in 0..3 {
                data.put(z[k], widths[l][k]);
            }
        });
    }
    data.finish()
}

/// The zigzag residuals of block `j` of blocks of `2^levels` vertices, level by level, in data
/// order: `each(level, residuals)`. Each vertex is guessed as the mean of the two known
/// vertices around it; past the last vertex the guess stands (residual 0). Run once to size
/// the block and once to write it, so that no residual is stored.
fn block_residuals(
    values: &[[i64; 3]],
    levels: u32,
    j: usize,
    mut each: impl FnMut(usize, [u64; 3]),
) {
    let block = 1usize << levels;
    let mut known = [[0i64; 3]; (1 << MAX_LEVELS) + 1];
    known[0] = anchor(values, levels, j);
    known[block] = anchor(values, levels, j + 1);
    for l in 0..levels as usize {
        let h = block >> (l + 1);
        for idx in 0..1 << l {
            let p = (2 * idx + 1) * h;
            let guess = [0, 1, 2].map(|k| (known[p - h][k] + known[p + h][k]) >> 1);
            let actual = values.get(j * block + p).copied().unwrap_or(guess);
            each(l, [0, 1, 2].map(|k| zigzag(actual[k] - guess[k])));
            known[p] = actual;
        }
    }
}

/// The anchor of record `j`: the first vertex of block `j`, and for the end record the last
/// vertex (the interval of the last block ends near it).
fn anchor(values: &[[i64; 3]], levels: u32, j: usize) -> [i64; 3] {
    let at = (j << levels).min(values.len().saturating_sub(1));
    values.get(at).copied().unwrap_or_default()
}

/// The widths and data starts of a section's blocks, computed before anything is written
/// (the start field's width depends on the total).
struct Blocks {
    /// Widths per block, level and axis.
    widths: Vec<[[u32; 3]; MAX_LEVELS as usize]>,
    /// The data start of every record, the end record's being the total.
    starts: Vec<u64>,
}

impl Blocks {
    fn of(values: &[[i64; 3]], levels: u32) -> Blocks {
        let count = values.len().div_ceil(1 << levels);
        let mut blocks = Blocks {
            widths: Vec::with_capacity(count),
            starts: Vec::with_capacity(count + 1),
        };
        let mut total = 0;
        for j in 0..count {
            blocks.starts.push(total);
            let mut widths = [[0u32; 3]; MAX_LEVELS as usize];
            block_residuals(values, levels, j, |l, z| {
                for k in 0..3 {
                    widths[l][k] = widths[l][k].max(u64::BITS - z[k].leading_zeros());
                }
            });
            for (l, w) in widths.iter().enumerate().take(levels as usize) {
                total += ((w[0] + w[1] + w[2]) as u64) << l;
            }
            blocks.widths.push(widths);
        }
        if count > 0 {
            blocks.starts.push(total);
        }
        blocks
    }
}

/// 0, -1, 1, -2, … as 0, 1, 2, 3, …
pub(super) fn zigzag(r: i64) -> u64 {
    ((r << 1) ^ (r >> 63)) as u64
}

fn push_u32(out: &mut Vec<u8>, x: u32) {
    out.extend_from_slice(&x.to_le_bytes());
}

/// Appends fields to bytes, least significant bit first, from a byte boundary.
struct BitWriter {
    bytes: Vec<u8>,
    acc: u64,
    bits: u32,
}

impl BitWriter {
    fn new(bytes: Vec<u8>) -> BitWriter {
        BitWriter {
            bytes,
            acc: 0,
            bits: 0,
        }
    }

    /// Appends the `width` low bits of `x` (at most 56; `x` has no higher bit).
    fn put(&mut self, x: u64, width: u32) {
        if width == 0 {
            return;
        }
        debug_assert!(width <= 56 && x >> width == 0);
        self.acc |= x << self.bits;
        self.bits += width;
        while self.bits >= 8 {
            self.bytes.push(self.acc as u8);
            self.acc >>= 8;
            self.bits -= 8;
        }
    }

    /// The bytes, the last one padded with 0 bits.
    fn finish(mut self) -> Vec<u8> {
        if self.bits > 0 {
            self.bytes.push(self.acc as u8);
        }
        self.bytes
    }
}
