//! The residual coder of the predicted encodings (GEOMETRY.md §4): a signed integer as its
//! class (bit length of the magnitude) through a binary tree of adaptive models chosen by the
//! predictor's kind, the axis and the class of the residuals just before; then the sign, the
//! two bits below the leading one with models of their own, and the remaining bits raw.

use crate::edgebreaker::coder::{Bit, Bits};

/// Leaves of the class tree: classes 0 to 63.
const TREE_LEVELS: u32 = 6;
const TREE: usize = 1 << TREE_LEVELS;
/// Predictor kinds that select models: 0 no parallelogram, 1 one, 2 one chosen of several,
/// then the middle of several by how much they disagree (`predict`).
pub(crate) const KINDS: usize = 7;
/// Parallelogram counts that select the choice models: 2, 3, 4 or more.
const COUNTS: usize = 3;
/// Context buckets: the class of the residuals before, up to this many.
const BUCKETS: usize = 8;
/// Adaptive bits below the leading one (a tree of 3 models); the rest are raw.
const HIGH_MODELS: usize = 4;

/// Components a coded value may have: 3 for positions, 1 to 4 for attribute values.
pub(crate) const MAX_AXES: usize = 4;

/// The adaptive state of one stream of residuals: of positions (3 axes), or of an
/// attribute's values (1 to 4 components, ATTR.md).
pub(crate) struct Residuals {
    axes: usize,
    class: Vec<[Bit; TREE]>,
    sign: [[Bit; MAX_AXES]; KINDS],
    high: Vec<[Bit; HIGH_MODELS]>,
    /// Whether one parallelogram is chosen, and which (`choice`).
    single: [Bit; COUNTS],
    which: [[Bit; 3]; COUNTS],
    /// The largest class a residual may have (the decoder rejects larger ones).
    max_class: u32,
    /// Classes of the current vertex's residuals so far, and of the previous vertex's.
    current: [u32; MAX_AXES],
    previous: [u32; MAX_AXES],
}

impl Residuals {
    /// Fresh models for position residuals of at most `max_class` bits (at most 63).
    pub(crate) fn new(max_class: u32) -> Residuals {
        Residuals::with_axes(max_class, 3)
    }

    /// Fresh models for values of `axes` components (1 to 4).
    pub(crate) fn with_axes(max_class: u32, axes: usize) -> Residuals {
        debug_assert!(max_class < TREE as u32 && (1..=MAX_AXES).contains(&axes));
        Residuals {
            axes,
            class: vec![[Bit::default(); TREE]; KINDS * axes * BUCKETS],
            sign: [[Bit::default(); MAX_AXES]; KINDS],
            high: vec![[Bit::default(); HIGH_MODELS]; axes * TREE],
            single: [Bit::default(); COUNTS],
            which: [[Bit::default(); 3]; COUNTS],
            max_class,
            current: [0; MAX_AXES],
            previous: [0; MAX_AXES],
        }
    }

    /// The context bucket of axis `k` (GEOMETRY.md §4.2): with `n` axes, the mean class of
    /// the previous value's residuals for the first axis (rounded up); of the current value's
    /// so far and the previous value's same axis for the others (rounded half up). For
    /// positions: x from the previous x, y, z; y from x and the previous y; z from x, y and
    /// the previous z.
    fn bucket(&self, k: usize) -> usize {
        let n = self.axes as u32;
        let c = if k == 0 {
            self.previous[..self.axes].iter().sum::<u32>().div_ceil(n)
        } else {
            let k32 = k as u32;
            (self.current[..k].iter().sum::<u32>() + self.previous[k] + k32.div_ceil(2)) / (k32 + 1)
        };
        (c as usize).min(BUCKETS - 1)
    }

    /// Codes the choice among `n ≥ 2` parallelograms (encoder: `wanted`), or decodes it:
    /// 0 for their middle, `j + 1` for parallelogram `j` alone. A bit says whether one is
    /// chosen; then, for `j = 0, 1, …, n − 2`, a bit says whether it is `j` (the last one
    /// needs none).
    pub(crate) fn choice<B: Bits>(&mut self, b: &mut B, n: usize, wanted: usize) -> usize {
        let m = n.min(COUNTS + 1) - 2;
        if b.bit(&mut self.single[m], (wanted > 0) as u32) == 0 {
            return 0;
        }
        for j in 0..n - 1 {
            let this = (wanted.wrapping_sub(1) == j) as u32;
            if b.bit(&mut self.which[m][j.min(2)], this) == 1 {
                return j + 1;
            }
        }
        n
    }

    /// Codes residual `r` of axis `k` (encoder), or decodes one (decoder); `None` when the
    /// decoder reads a class above the maximum. After the last axis, the value is complete.
    #[inline]
    pub(crate) fn code<B: Bits>(
        &mut self,
        b: &mut B,
        kind: usize,
        k: usize,
        r: i64,
    ) -> Option<i64> {
        let magnitude = r.unsigned_abs();
        let class = 64 - magnitude.leading_zeros();
        let bucket = self.bucket(k);
        let tree = &mut self.class[(kind * self.axes + k) * BUCKETS + bucket];
        let mut node = 1usize;
        for i in (0..TREE_LEVELS).rev() {
            let bit = (class >> i) & 1;
            node = 2 * node + b.bit(&mut tree[node], bit) as usize;
        }
        let class = (node - TREE) as u32;
        if class > self.max_class {
            return None;
        }
        self.current[k] = class;
        if k + 1 == self.axes {
            self.previous = self.current;
        }
        if class == 0 {
            return Some(0);
        }
        let negative = b.bit(&mut self.sign[kind][k], (r < 0) as u32) == 1;
        let high = &mut self.high[k * TREE + class as usize];
        let mut x = 1u64;
        let mut node = 1usize;
        for i in (0..class - 1).rev() {
            let bit = ((magnitude >> i) & 1) as u32;
            let got = if node < HIGH_MODELS {
                let g = b.bit(&mut high[node], bit);
                node = 2 * node + g as usize;
                g
            } else {
                b.raw(bit)
            };
            x = (x << 1) | got as u64;
        }
        let x = x as i64;
        Some(if negative { -x } else { x })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::edgebreaker::coder::{Decoder, Encoder};

    #[test]
    fn residuals_round_trip() {
        let mut rng = crate::rng::Rng::new(3);
        let values: Vec<(usize, i64)> = (0..3000)
            .map(|i| {
                let bits = rng.below(34);
                let m = (rng.next_u64() & ((1u64 << bits) - 1)) as i64;
                ((i / 3) % KINDS, if rng.below(2) == 0 { -m } else { m })
            })
            .collect();
        let mut enc = Encoder::new();
        let mut models = Residuals::new(33);
        for (i, &(kind, r)) in values.iter().enumerate() {
            assert_eq!(models.code(&mut enc, kind, i % 3, r), Some(r));
        }
        let bytes = enc.finish();
        let mut dec = Decoder::new(&bytes, 0);
        let mut models = Residuals::new(33);
        for (i, &(kind, r)) in values.iter().enumerate() {
            assert_eq!(models.code(&mut dec, kind, i % 3, 0), Some(r));
        }
        assert!(!dec.overrun());
    }

    #[test]
    fn a_class_above_the_maximum_is_refused() {
        let mut enc = Encoder::new();
        Residuals::new(33).code(&mut enc, 0, 0, 1 << 20);
        let bytes = enc.finish();
        let mut dec = Decoder::new(&bytes, 0);
        assert_eq!(Residuals::new(10).code(&mut dec, 0, 0, 0), None);
    }
}
