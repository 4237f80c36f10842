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
    for levels in LEVELS_TRIED {
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
        for x in blocks.anchor(j) {
            dir.put(x as u64, shape.anchor_bits);
        }
        // The end record (no block of its own) has widths 0.
        let widths = blocks.widths.get(j).copied().unwrap_or_default();
        for w in widths.iter().take(levels as usize).flatten() {
            dir.put(*w as u64, shape.width_bits);
        }
    }
    let mut data = BitWriter::new(dir.finish());
    let per_block = (1usize << levels) - 1;
    for (residuals, widths) in blocks.residuals.chunks(per_block).zip(&blocks.widths) {
        let mut at = 0;
        for (l, w) in widths.iter().take(levels as usize).enumerate() {
            for triple in &residuals[at..at + (1 << l)] {
                for k in 0..3 {
                    data.put(triple[k], w[k]);
                }
            }
            at += 1 << l;
        }
    }
    data.finish()
}

/// The blocks of a section, computed before anything is written (the start field's width
/// depends on the total).
struct Blocks<'a> {
    values: &'a [[i64; 3]],
    levels: u32,
    /// Zigzag residuals, per block `2^L - 1` triples in data order (level by level).
    residuals: Vec<[u64; 3]>,
    /// Widths per block, level and axis.
    widths: Vec<[[u32; 3]; MAX_LEVELS as usize]>,
    /// The data start of every record, the end record's being the total.
    starts: Vec<u64>,
}

impl<'a> Blocks<'a> {
    fn of(values: &'a [[i64; 3]], levels: u32) -> Blocks<'a> {
        let block = 1usize << levels;
        let count = values.len().div_ceil(block);
        let mut blocks = Blocks {
            values,
            levels,
            residuals: Vec::with_capacity(count * (block - 1)),
            widths: Vec::with_capacity(count),
            starts: Vec::with_capacity(count + 1),
        };
        let mut total = 0;
        let mut known = [[0i64; 3]; (1 << MAX_LEVELS) + 1];
        for j in 0..count {
            blocks.starts.push(total);
            known[0] = blocks.anchor(j);
            known[block] = blocks.anchor(j + 1);
            let mut widths = [[0u32; 3]; MAX_LEVELS as usize];
            for (l, w) in widths.iter_mut().enumerate().take(levels as usize) {
                let h = block >> (l + 1);
                for idx in 0..1 << l {
                    let p = (2 * idx + 1) * h;
                    let guess = [0, 1, 2].map(|k| (known[p - h][k] + known[p + h][k]) >> 1);
                    // Past the last vertex the guess stands: residual 0.
                    let actual = values.get(j * block + p).copied().unwrap_or(guess);
                    let z = [0, 1, 2].map(|k| zigzag(actual[k] - guess[k]));
                    for k in 0..3 {
                        w[k] = w[k].max(u64::BITS - z[k].leading_zeros());
                    }
                    blocks.residuals.push(z);
                    known[p] = actual;
                }
                total += ((w[0] + w[1] + w[2]) as u64) << l;
            }
            blocks.widths.push(widths);
        }
        if count > 0 {
            blocks.starts.push(total);
        }
        blocks
    }

    /// The anchor of record `j`: the first vertex of block `j`, and for the end record the
    /// last vertex (the interval of the last block ends near it).
    fn anchor(&self, j: usize) -> [i64; 3] {
        let at = (j << self.levels).min(self.values.len().saturating_sub(1));
        self.values.get(at).copied().unwrap_or_default()
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
