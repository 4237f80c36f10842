//! Value encoding 1 of `ATTR` records, "quantized packed" (FORMAT.md §3.9.1): f32 attribute
//! values as integers of `b` bits, octahedral for normals, on a cubic grid otherwise, packed
//! LSB-first in u32 words so that any value reads in constant time. Shared by the writer and
//! the reader; every formula is the spec's, in binary64.

use super::attributes::packed;
use crate::geometry::{bounding_cube, from_level, to_level};
use crate::words::Words;

/// Value encoding 0: the values as stored, `c` components of the component type each.
pub const RAW: u8 = 0;
/// Value encoding 1: quantized and bit packed (f32 attributes only).
pub const QUANTIZED: u8 = 1;
/// Value encoding 2: the integers of encoding 1, predicted and range coded (GEOMETRY.md §7).
pub const PREDICTED: u8 = 2;
/// The most bits per component of an octahedral normal.
pub const MAX_NORMAL_BITS: u8 = 24;
/// The most bits per component of a grid-quantized value.
pub const MAX_VALUE_BITS: u8 = 30;

/// How an encoding-1 record maps its values to integers.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Quantizer {
    /// Normals (semantic 1): two integers of `bits` bits per value, the octahedral map.
    Octahedral {
        /// Bits per integer, 1 to [`MAX_NORMAL_BITS`].
        bits: u8,
    },
    /// Any other f32 attribute: `components` integers per value on the cube of side `size`
    /// from `lo`.
    Grid {
        /// Bits per integer, 1 to [`MAX_VALUE_BITS`].
        bits: u8,
        /// Components per value `c`, 1 to 4.
        components: u8,
        /// The cube's minimum corner (components beyond `c` are 0).
        lo: [f32; 4],
        /// The cube's side.
        size: f32,
    },
}

impl Quantizer {
    /// The grid of `bits` bits over the values `values` of `components` components each: `lo`
    /// their minimum per component, `size` their largest extent rounded up to an f32 (all 0
    /// without values), as for positions (FORMAT.md §3.3.1).
    pub fn grid<'v>(components: u8, bits: u8, values: impl IntoIterator<Item = &'v [f32]>) -> Self {
        let (lo, size) = bounding_cube(usize::from(components), values);
        Quantizer::Grid {
            bits,
            components,
            lo,
            size,
        }
    }

    /// Bits per integer `b`.
    pub fn bits(&self) -> u8 {
        match *self {
            Quantizer::Octahedral { bits } | Quantizer::Grid { bits, .. } => bits,
        }
    }

    /// Integers per value `c'`: 2 for octahedral normals, else `c`.
    pub fn fields(&self) -> u32 {
        match *self {
            Quantizer::Octahedral { .. } => 2,
            Quantizer::Grid { components, .. } => u32::from(components),
        }
    }

    /// The largest integer, `2^b − 1`.
    pub fn max_level(&self) -> u32 {
        ((1u64 << self.bits()) - 1) as u32
    }

    /// Bytes of the header before the packed words: `b`, then for a grid `lo` (`c` f32) and
    /// `size` (f32).
    pub fn header_len(&self) -> usize {
        match *self {
            Quantizer::Octahedral { .. } => 1,
            Quantizer::Grid { components, .. } => 1 + 4 * usize::from(components) + 4,
        }
    }

    /// Bytes of the values part for `count` values: the header and `⌈count·c'·b/32⌉` words.
    pub fn values_len(&self, count: u64) -> Option<u64> {
        let bits = count
            .checked_mul(u64::from(self.fields()))?
            .checked_mul(u64::from(self.bits()))?;
        (self.header_len() as u64).checked_add(4 * bits.div_ceil(32))
    }

    /// The grid step `size / (2^b − 1)` (0 for octahedral normals): every component comes
    /// back within half of it, plus the f32 rounding of the result.
    pub fn step(&self) -> f64 {
        match *self {
            Quantizer::Octahedral { .. } => 0.0,
            Quantizer::Grid { size, .. } => size as f64 / self.max_level() as f64,
        }
    }

    /// The integers of `value` (its `c` components), into `out` (`c'` long).
    pub fn quantize(&self, value: &[f32], out: &mut [u32]) {
        match *self {
            Quantizer::Octahedral { bits } => {
                let q = octahedral_encode([value[0], value[1], value[2]], bits);
                out[..2].copy_from_slice(&q);
            }
            Quantizer::Grid {
                components,
                lo,
                size,
                ..
            } => {
                let max = self.max_level();
                for k in 0..usize::from(components) {
                    out[k] = to_level(value[k], lo[k], size, max);
                }
            }
        }
    }

    /// The value integers `levels` (`c'` of them) stand for; components beyond `c` are 0.
    pub fn dequantize(&self, levels: &[u32]) -> [f32; 4] {
        match *self {
            Quantizer::Octahedral { bits } => {
                let [x, y, z] = octahedral_decode([levels[0], levels[1]], bits);
                [x, y, z, 0.0]
            }
            Quantizer::Grid {
                components,
                lo,
                size,
                ..
            } => {
                let max = self.max_level();
                let mut out = [0.0; 4];
                for k in 0..usize::from(components) {
                    out[k] = from_level(levels[k], lo[k], size, max);
                }
                out
            }
        }
    }

    /// Value `i` of the packed words `words`.
    pub fn value_at<W: Words>(&self, words: &W, i: u32) -> [f32; 4] {
        let mut levels = [0u32; 4];
        self.levels_at(words, i, &mut levels);
        self.dequantize(&levels)
    }

    /// The integers of value `i` of the packed words `words`, into `out` (`c'` long).
    pub fn levels_at<W: Words>(&self, words: &W, i: u32, out: &mut [u32]) {
        let n = self.fields();
        for (k, x) in out.iter_mut().take(n as usize).enumerate() {
            *x = packed(words, i * n + k as u32, u32::from(self.bits()));
        }
    }

    /// Appends the header: `b`, then for a grid `lo[0..c]` and `size`.
    pub fn write_header(&self, out: &mut Vec<u8>) {
        out.push(self.bits());
        if let Quantizer::Grid {
            components,
            lo,
            size,
            ..
        } = *self
        {
            for x in lo.iter().take(usize::from(components)).chain([&size]) {
                out.extend_from_slice(&x.to_le_bytes());
            }
        }
    }
}

/// `−1` for a negative `t`, else `1` (so `sgn(−0) = 1`).
fn sgn(t: f64) -> f64 {
    if t < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// The octahedral integers of direction `n` (FORMAT.md §3.9.1), in binary64: `n / |n|₁`
/// folded onto the square when `z < 0`, then each coordinate `u` stored as
/// `clamp(round((u + 1) / 2 · max), 0, max)`. A zero vector is stored as `(0, 0, 1)`.
pub fn octahedral_encode(n: [f32; 3], bits: u8) -> [u32; 2] {
    octahedral_encode_f64(n.map(f64::from), bits)
}

/// [`octahedral_encode`] of a binary64 direction: the predictor of normals (GEOMETRY.md §7)
/// encodes sums of face normals, which an f32 may not hold.
pub fn octahedral_encode_f64(n: [f64; 3], bits: u8) -> [u32; 2] {
    let [mut x, mut y, mut z] = n;
    let mut s = x.abs() + y.abs() + z.abs();
    if s == 0.0 || !s.is_finite() {
        (x, y, z, s) = (0.0, 0.0, 1.0, 1.0);
    }
    let (mut u, mut v) = (x / s, y / s);
    if z < 0.0 {
        (u, v) = ((1.0 - v.abs()) * sgn(u), (1.0 - u.abs()) * sgn(v));
    }
    let max = ((1u64 << bits) - 1) as f64;
    [u, v].map(|t| ((t + 1.0) / 2.0 * max).round().clamp(0.0, max) as u32)
}

/// The unit vector octahedral integers `q` stand for (FORMAT.md §3.9.1), in binary64: each
/// `u = (q / max) · 2 − 1`, `z = 1 − |u| − |v|`, unfolded when `z < 0`, then divided by its
/// length and rounded to f32.
pub fn octahedral_decode(q: [u32; 2], bits: u8) -> [f32; 3] {
    let max = ((1u64 << bits) - 1) as f64;
    let [mut u, mut v] = q.map(|x| (x as f64 / max) * 2.0 - 1.0);
    let z = 1.0 - u.abs() - v.abs();
    if z < 0.0 {
        (u, v) = ((1.0 - v.abs()) * sgn(u), (1.0 - u.abs()) * sgn(v));
    }
    let r = (u * u + v * v + z * z).sqrt();
    [(u / r) as f32, (v / r) as f32, (z / r) as f32]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angle(a: [f32; 3], b: [f64; 3]) -> f64 {
        let a = a.map(f64::from);
        let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
        let cross = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        let c = (cross.iter().map(|x| x * x).sum::<f64>()).sqrt();
        c.atan2(dot)
    }

    /// The octahedral error: within `3·√2 / max` radians (FORMAT.md §3.9.1), and the
    /// measured worst case on a dense sample.
    #[test]
    fn octahedral_error_is_bounded() {
        for bits in [2u8, 4, 6, 8, 10, 12, 16, 24] {
            let max = ((1u64 << bits) - 1) as f64;
            let bound = 3.0 * 2f64.sqrt() / max + 1e-6;
            let mut worst = 0.0f64;
            let n = 200;
            for i in 0..=n {
                for j in 0..2 * n {
                    let theta = std::f64::consts::PI * i as f64 / n as f64;
                    let phi = std::f64::consts::PI * j as f64 / n as f64;
                    let d = [
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    ];
                    let f = d.map(|x| x as f32);
                    let back = octahedral_decode(octahedral_encode(f, bits), bits);
                    let len = back.iter().map(|&x| (x as f64).powi(2)).sum::<f64>();
                    assert!((len - 1.0).abs() < 1e-6, "{back:?}");
                    let e = angle(back, d);
                    worst = worst.max(e);
                    assert!(e <= bound, "{bits} bits: {f:?} → {back:?}, {e} > {bound}");
                }
            }
            if bits <= 16 {
                assert!(worst > 0.5 / max, "{bits} bits: the sample is too sparse");
            }
        }
        // A zero normal comes back a unit vector.
        let z = octahedral_decode(octahedral_encode([0.0; 3], 10), 10);
        assert!((z[2] - 1.0).abs() < 1e-2, "{z:?}");
    }

    #[test]
    fn grid_values_within_half_a_step() {
        let values: Vec<[f32; 2]> = (0..100)
            .map(|i| [i as f32 * 0.013 - 0.2, (i * i) as f32 * 1e-3])
            .collect();
        for bits in [1u8, 5, 12, 30] {
            let q = Quantizer::grid(2, bits, values.iter().map(|v| &v[..]));
            let step = q.step();
            for v in &values {
                let mut l = [0; 2];
                q.quantize(v, &mut l);
                let back = q.dequantize(&l);
                for k in 0..2 {
                    let e = (back[k] as f64 - v[k] as f64).abs();
                    assert!(e <= step / 2.0 * (1.0 + 1e-9) + 1.2e-7 * back[k].abs() as f64);
                }
            }
        }
    }
}
