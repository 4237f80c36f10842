//! Position coding (FORMAT.md §3.3, GEOMETRY.md): the quantization grid every lossy
//! encoding shares, the prediction in Edgebreaker decode order with its range-coded residuals
//! (on the grid, or on the f32 bits for lossless files), and the random-access blocks of the
//! LR kinds and strips.

pub(crate) mod anchored;
pub mod blocked;
pub(crate) mod float;
pub(crate) mod predict;
pub(crate) mod prefix;
pub(crate) mod residual;
pub(crate) mod seams;
pub(crate) mod traversal;
pub(crate) mod values;

/// The largest number of bits per coordinate of a grid.
pub const MAX_GRID_BITS: u8 = 30;

/// A quantization grid: a cube of side `size` from `lo`, with `2^bits` levels per axis, so
/// that every axis has the same step `size / (2^bits - 1)` and a coordinate is stored within
/// half a step of its value (as Draco's grid: the error does not depend on the axis).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Minimum corner of the bounding box.
    pub lo: [f32; 3],
    /// Side of the cube: the largest extent of the box, rounded up to an f32.
    pub size: f32,
    /// Bits per coordinate, 1 to [`MAX_GRID_BITS`].
    pub bits: u8,
}

impl Grid {
    /// The grid of `bits` bits over the bounding box of `positions` (all zero when empty).
    pub fn of(positions: impl IntoIterator<Item = [f32; 3]>, bits: u8) -> Grid {
        let (lo, size) = bounding_cube(3, positions);
        Grid {
            lo: [lo[0], lo[1], lo[2]],
            size,
            bits,
        }
    }

    /// The largest level, `2^bits - 1`.
    pub fn max_level(&self) -> u32 {
        ((1u64 << self.bits) - 1) as u32
    }

    /// The level of coordinate `k` nearest to `x` (FORMAT.md §3.3): in binary64,
    /// `clamp(round((x − lo[k]) / size · max), 0, max)`, 0 when the size is 0.
    pub fn quantize_axis(&self, k: usize, x: f32) -> u32 {
        to_level(x, self.lo[k], self.size, self.max_level())
    }

    /// The levels of `p`.
    pub fn quantize(&self, p: [f32; 3]) -> [u32; 3] {
        [0, 1, 2].map(|k| self.quantize_axis(k, p[k]))
    }

    /// The coordinate `k` that level `q` stands for (FORMAT.md §3.3): computed in binary64
    /// as `lo[k] + ((q / max) · size)`, then rounded to f32.
    pub fn dequantize_axis(&self, k: usize, q: u32) -> f32 {
        from_level(q, self.lo[k], self.size, self.max_level())
    }

    /// The position that levels `q` stand for.
    pub fn dequantize(&self, q: [u32; 3]) -> [f32; 3] {
        [0, 1, 2].map(|k| self.dequantize_axis(k, q[k]))
    }

    /// The positions that `levels` stand for: [`Grid::dequantize`] of each, in a loop the
    /// compiler can vectorize.
    pub fn dequantize_all(&self, levels: &[[u32; 3]]) -> Vec<[f32; 3]> {
        let max = self.max_level();
        levels
            .iter()
            .map(|q| [0, 1, 2].map(|k| from_level(q[k], self.lo[k], self.size, max)))
            .collect()
    }

    /// The grid step, `size / (2^bits - 1)`: positions come back within half of it on every
    /// axis (plus the f32 rounding of the result).
    pub fn step(&self) -> f64 {
        self.size as f64 / self.max_level() as f64
    }
}

/// The cube over `values` of `c` components each (at most 4), shared by the positions' grid
/// and the quantized attribute values (FORMAT.md §3.3.1, §3.9.1): the minimum of each
/// component (components from `c` on, and all of them without values, 0) and the largest
/// extent rounded up to an f32 (an extent beyond f32's range saturates at MAX, and the
/// levels clamp).
pub(crate) fn bounding_cube<V: AsRef<[f32]>>(
    c: usize,
    values: impl IntoIterator<Item = V>,
) -> ([f32; 4], f32) {
    let mut lo = [f32::MAX; 4];
    let mut hi = [f32::MIN; 4];
    let mut any = false;
    for v in values {
        let v = v.as_ref();
        any = true;
        for k in 0..c {
            lo[k] = lo[k].min(v[k]);
            hi[k] = hi[k].max(v[k]);
        }
    }
    for k in 0..4 {
        if !any || k >= c {
            (lo[k], hi[k]) = (0.0, 0.0);
        }
    }
    let extent = (0..c)
        .map(|k| hi[k] as f64 - lo[k] as f64)
        .fold(0.0, f64::max);
    let mut size = extent as f32;
    if (size as f64) < extent {
        size = f32::from_bits(size.to_bits() + 1).min(f32::MAX);
    }
    (lo, size)
}

/// The level of `x` on a cube side from `lo` of side `size` with levels `0..=max`: in
/// binary64, `clamp(round((x − lo) / size · max), 0, max)`, 0 when the size is 0.
pub(crate) fn to_level(x: f32, lo: f32, size: f32, max: u32) -> u32 {
    let s = size as f64;
    if s > 0.0 {
        let max = max as f64;
        ((x as f64 - lo as f64) / s * max).round().clamp(0.0, max) as u32
    } else {
        0
    }
}

/// The value level `q` stands for: `lo + ((q / max) · size)` in binary64, rounded to f32.
pub(crate) fn from_level(q: u32, lo: f32, size: f32, max: u32) -> f32 {
    (lo as f64 + (q as f64 / max as f64) * size as f64) as f32
}

/// Appends the grid fields of encodings 2 and 4 (FORMAT.md §3.3): `lo` (three f32), `size`
/// (f32), `bits` (u32).
pub(crate) fn write_grid(out: &mut Vec<u8>, grid: Grid) {
    for x in grid.lo.iter().chain([&grid.size]) {
        out.extend_from_slice(&x.to_le_bytes());
    }
    out.extend_from_slice(&(grid.bits as u32).to_le_bytes());
}
