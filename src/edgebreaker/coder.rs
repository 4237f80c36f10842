//! An adaptive binary range coder of our own (the carry-propagating coder of LZMA, with 16-bit
//! probabilities and a count-driven adaptation rate), and adaptive Elias-gamma integers on top.
//!
//! Encoder and decoder implement one trait, [`Bits`], so that every piece of the format is
//! written once, generically: the encoder passes the value it codes and gets it back, the
//! decoder ignores the value passed and returns the one it decodes.
//!
//! Probabilities never leave `[P_MIN, 1 - P_MIN]` (with `P_MIN = 1/256`): every decision costs at
//! least `-log2(1 - 1/256) > 0.0056` bits, so a stream of `n` bytes holds fewer than
//! `8 * (n + 4) / 0.0056 < 1430 * (n + 4)` decisions. The decoder relies on that bound to refuse
//! declared counts that the input cannot hold.

use crate::error::Result;

/// Probabilities are in units of `1 / PROB_ONE`.
const PROB_ONE: u32 = 1 << 16;
/// Smallest probability a model can reach (see the module documentation).
const P_MIN: u32 = 256;
const P_MAX: u32 = PROB_ONE - P_MIN;
/// The range is renormalised (a byte shifted out) whenever it drops below this.
const TOP: u32 = 1 << 24;

/// Upper bound on the decisions a stream of `bytes` bytes can hold (module documentation).
pub(crate) fn max_decisions(bytes: usize) -> u64 {
    1430 * (bytes as u64 + 4)
}

/// Adaptation shift for a model that has seen `n` bits: about `log2(n + 2)`, so that a young
/// model follows the running frequency and an old one a window of `2^RATE_LIMIT` bits.
const fn rate_table<const LIMIT: u8>() -> [u8; 64] {
    let mut t = [0u8; 64];
    let mut n = 0;
    while n < 64 {
        let mut s = 0u8;
        while (1u32 << (s + 1)) <= n as u32 + 2 {
            s += 1;
        }
        t[n] = if s > LIMIT { LIMIT } else { s };
        n += 1;
    }
    t
}

const RATE_LIMIT: u8 = 6;
static RATE: [u8; 64] = rate_table::<RATE_LIMIT>();
/// The count from which the rate is [`RATE_LIMIT`]: a model past it no longer counts.
const MATURE: u8 = 62;
const _: () = assert!(rate_table::<RATE_LIMIT>()[MATURE as usize] == RATE_LIMIT);
const _: () = assert!(rate_table::<RATE_LIMIT>()[MATURE as usize - 1] < RATE_LIMIT);

/// One adaptive binary model: the probability of a 0 and how many bits it has seen.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bit {
    p: u16,
    n: u8,
}

impl Default for Bit {
    fn default() -> Bit {
        Bit {
            p: (PROB_ONE / 2) as u16,
            n: 0,
        }
    }
}

impl Bit {
    #[inline(always)]
    fn p0(self) -> u32 {
        self.p as u32
    }

    #[inline(always)]
    fn update(&mut self, bit: u32) {
        // Most decisions go to mature models: a predictable branch, no table, no count.
        let shift = if self.n < MATURE {
            let s = RATE[self.n as usize];
            self.n += 1;
            s
        } else {
            RATE_LIMIT
        };
        let p = self.p as u32;
        let towards_zero = p + ((P_MAX - p) >> shift);
        let towards_one = p - ((p - P_MIN) >> shift);
        self.p = if bit == 0 { towards_zero } else { towards_one } as u16;
    }
}

/// A binary coder: the range encoder or the range decoder.
pub(crate) trait Bits {
    /// Codes `bit` with model `m` (encoder), or decodes a bit (decoder, which ignores `bit`);
    /// returns the bit coded, 0 or 1, and adapts `m`.
    fn bit(&mut self, m: &mut Bit, bit: u32) -> u32;
    /// A bit of probability one half, without a model.
    fn raw(&mut self, bit: u32) -> u32;
    /// Whether the decoder has read past the end of its input by more than the final flush
    /// can explain: the stream is corrupt (always false for the encoder).
    fn overrun(&self) -> bool;
    /// Byte offset of the decoder in the whole input, for error messages.
    fn offset(&self) -> u64;
}

/// The range encoder.
pub(crate) struct Encoder {
    low: u64,
    range: u32,
    cache: u8,
    pending: u64,
    out: Vec<u8>,
}

impl Encoder {
    /// An empty encoder.
    pub(crate) fn new() -> Encoder {
        Encoder {
            low: 0,
            range: u32::MAX,
            cache: 0,
            pending: 1,
            out: Vec::new(),
        }
    }

    fn shift_low(&mut self) {
        if self.low < 0xFF00_0000 || self.low >= 1 << 32 {
            let carry = (self.low >> 32) as u8;
            let mut b = self.cache;
            loop {
                self.out.push(b.wrapping_add(carry));
                b = 0xFF;
                self.pending -= 1;
                if self.pending == 0 {
                    break;
                }
            }
            self.cache = (self.low >> 24) as u8;
        }
        self.pending += 1;
        self.low = (self.low & 0x00FF_FFFF) << 8;
    }

    #[inline(always)]
    fn normalize(&mut self) {
        while self.range < TOP {
            self.range <<= 8;
            self.shift_low();
        }
    }

    /// Flushes the coder and returns its bytes. The final value is chosen with as many trailing
    /// zero bits as the interval allows, and up to four trailing zero bytes are dropped (the
    /// decoder reads zeros past the end). The first byte of this coder is always zero and is
    /// not written.
    pub(crate) fn finish(mut self) -> Vec<u8> {
        let hi = self.low + self.range as u64;
        for k in (0..40).rev() {
            let mask = (1u64 << k) - 1;
            let v = (self.low + mask) & !mask;
            if v < hi {
                self.low = v;
                break;
            }
        }
        for _ in 0..5 {
            self.shift_low();
        }
        debug_assert_eq!(self.out.first(), Some(&0));
        let mut out = self.out.split_off(1);
        for _ in 0..4 {
            if out.last() == Some(&0) {
                out.pop();
            }
        }
        out
    }
}

impl Bits for Encoder {
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit, bit: u32) -> u32 {
        let bound = (self.range >> 16) * m.p0();
        if bit == 0 {
            self.range = bound;
        } else {
            self.low += bound as u64;
            self.range -= bound;
        }
        m.update(bit);
        self.normalize();
        bit
    }

    fn raw(&mut self, bit: u32) -> u32 {
        self.range >>= 1;
        if bit != 0 {
            self.low += self.range as u64;
        }
        self.normalize();
        bit
    }

    fn overrun(&self) -> bool {
        false
    }

    fn offset(&self) -> u64 {
        0
    }
}

/// The range decoder over one stream, `base` bytes into the whole input.
pub(crate) struct Decoder<'a> {
    data: &'a [u8],
    pos: usize,
    base: usize,
    range: u32,
    code: u32,
}

impl<'a> Decoder<'a> {
    /// A decoder over `data`, which starts `base` bytes into the input.
    pub(crate) fn new(data: &'a [u8], base: usize) -> Decoder<'a> {
        let mut d = Decoder {
            data,
            pos: 0,
            base,
            range: u32::MAX,
            code: 0,
        };
        for _ in 0..4 {
            d.code = (d.code << 8) | d.byte();
        }
        d
    }

    #[inline(always)]
    fn byte(&mut self) -> u32 {
        let b = match self.data.get(self.pos) {
            Some(&b) => b as u32,
            None => 0,
        };
        self.pos += 1;
        b
    }

    #[inline(always)]
    fn normalize(&mut self) {
        while self.range < TOP {
            self.range <<= 8;
            self.code = (self.code << 8) | self.byte();
        }
    }
}

impl Bits for Decoder<'_> {
    #[inline(always)]
    fn bit(&mut self, m: &mut Bit, _bit: u32) -> u32 {
        let bound = (self.range >> 16) * m.p0();
        // Without a branch: an adaptive decision is as hard to predict as its probability.
        let bit = (self.code >= bound) as u32;
        let mask = bit.wrapping_neg();
        self.code -= bound & mask;
        self.range = (bound & !mask) | (self.range.wrapping_sub(bound) & mask);
        m.update(bit);
        self.normalize();
        bit
    }

    #[inline(always)]
    fn raw(&mut self, _bit: u32) -> u32 {
        self.range >>= 1;
        // Without a branch: raw bits are coin flips.
        let bit = (self.code >= self.range) as u32;
        self.code -= self.range & bit.wrapping_neg();
        self.normalize();
        bit
    }

    #[inline(always)]
    fn overrun(&self) -> bool {
        self.pos > self.data.len() + 4
    }

    fn offset(&self) -> u64 {
        (self.base + self.pos.min(self.data.len())) as u64
    }
}

/// Adaptive models for an unsigned integer coded as Elias gamma: the length of `value + 1` in
/// unary, each unary position with its own model, the two leading mantissa bits modelled by
/// length, the rest raw.
#[derive(Debug, Clone)]
pub(crate) struct UintModel {
    prefix: [Bit; MAX_UINT_BITS as usize + 1],
    mantissa: [[Bit; 3]; MAX_UINT_BITS as usize + 1],
}

/// Values coded by [`code_uint`] are below `2^MAX_UINT_BITS - 1`.
pub(crate) const MAX_UINT_BITS: u32 = 40;

impl Default for UintModel {
    fn default() -> UintModel {
        UintModel {
            prefix: [Bit::default(); MAX_UINT_BITS as usize + 1],
            mantissa: [[Bit::default(); 3]; MAX_UINT_BITS as usize + 1],
        }
    }
}

/// Codes `value` (encoder) or decodes an integer (decoder); `None` when the decoder reads a
/// length beyond [`MAX_UINT_BITS`].
pub(crate) fn code_uint<B: Bits>(b: &mut B, m: &mut UintModel, value: u64) -> Option<u64> {
    let v1 = value.wrapping_add(1);
    let len = 64 - v1.leading_zeros(); // bits of value + 1 (encoder side)
    let mut k = 0u32;
    loop {
        let more = (k + 1 < len) as u32;
        if b.bit(&mut m.prefix[k as usize], more) == 0 {
            break;
        }
        k += 1;
        if k >= MAX_UINT_BITS {
            return None;
        }
    }
    // k mantissa bits below the leading one.
    let mut x = 1u64;
    let mut node = 1usize;
    for i in (0..k).rev() {
        let bit = ((v1 >> i) & 1) as u32;
        let got = if node < 3 {
            let g = b.bit(&mut m.mantissa[k as usize][node], bit);
            node = node * 2 + g as usize;
            g
        } else {
            b.raw(bit)
        };
        x = (x << 1) | got as u64;
    }
    Some(x - 1)
}

/// Result-flavoured helper: the decoder's error when [`code_uint`] fails.
pub(crate) fn uint_or<B: Bits>(
    b: &mut B,
    m: &mut UintModel,
    value: u64,
    err: impl FnOnce(u64) -> crate::Error,
) -> Result<u64> {
    let off = b.offset();
    code_uint(b, m, value).ok_or_else(|| err(off))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_and_uints_round_trip() {
        let mut rng = crate::rng::Rng::new(7);
        let bits: Vec<(u32, u32)> = (0..20_000)
            .map(|i| {
                let ctx = (i % 3) as u32;
                let skew = [2, 50, 97][ctx as usize];
                (ctx, (rng.below(100) >= skew) as u32)
            })
            .collect();
        let uints: Vec<u64> = (0..500)
            .map(|i| (rng.next_u64() >> (i % 64)) & ((1u64 << 38) - 1))
            .collect();
        let mut enc = Encoder::new();
        let mut models = [Bit::default(); 3];
        let mut um = UintModel::default();
        for &(c, b) in &bits {
            enc.bit(&mut models[c as usize], b);
        }
        for &u in &uints {
            code_uint(&mut enc, &mut um, u).unwrap();
            enc.raw((u & 1) as u32);
        }
        let bytes = enc.finish();
        let mut dec = Decoder::new(&bytes, 0);
        let mut models = [Bit::default(); 3];
        let mut um = UintModel::default();
        for &(c, b) in &bits {
            assert_eq!(dec.bit(&mut models[c as usize], 0), b);
        }
        for &u in &uints {
            assert_eq!(code_uint(&mut dec, &mut um, 0), Some(u));
            assert_eq!(dec.raw(0), (u & 1) as u32);
        }
        assert!(!dec.overrun());
    }

    #[test]
    fn empty_stream() {
        let enc = Encoder::new();
        let bytes = enc.finish();
        assert!(bytes.len() <= 4);
    }
}
