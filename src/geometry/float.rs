//! f32 values as ordered integers (GEOMETRY.md §2): the map keeps the order of the floats
//! (−0 just below +0), so that the difference of two mapped values is small when the floats
//! are close, and every bit pattern maps to a distinct integer and back.

/// The ordered integer of `x`: the bits with the sign bit flipped for a positive float, all
/// bits flipped for a negative one.
#[inline]
pub(crate) fn ordered(x: f32) -> u32 {
    let b = x.to_bits();
    if b & 0x8000_0000 != 0 {
        !b
    } else {
        b | 0x8000_0000
    }
}

/// The float whose ordered integer is `u` (the inverse of [`ordered`]).
#[inline]
pub(crate) fn from_ordered(u: u32) -> f32 {
    f32::from_bits(if u & 0x8000_0000 != 0 {
        u & 0x7FFF_FFFF
    } else {
        !u
    })
}

/// Whether ordered integer `u` stands for a finite f32 (its exponent not all ones), without
/// building the float.
#[inline(always)]
pub(crate) fn ordered_is_finite(u: u32) -> bool {
    // `from_ordered` keeps the exponent of `u` when bit 31 is set and flips it otherwise.
    let exponent = (u >> 23) & 0xFF;
    exponent != if u & 0x8000_0000 != 0 { 0xFF } else { 0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ordered_is_monotone_and_invertible() {
        let xs = [
            f32::NEG_INFINITY,
            -f32::MAX,
            -1.5,
            -f32::MIN_POSITIVE,
            -1e-45,
            -0.0,
            0.0,
            1e-45,
            1.0,
            f32::MAX,
            f32::INFINITY,
        ];
        for w in xs.windows(2) {
            assert!(ordered(w[0]) < ordered(w[1]), "{} {}", w[0], w[1]);
        }
        for bits in [0u32, 1, 0x7F80_0000, 0x8000_0000, 0xFFFF_FFFF, 0x3F80_0001] {
            assert_eq!(from_ordered(ordered(f32::from_bits(bits))).to_bits(), bits);
        }
    }

    #[test]
    fn ordered_is_finite_agrees_with_the_float() {
        let edges = [
            0u32,
            1,
            0x007F_FFFF,
            0x0080_0000,
            0x7F7F_FFFF,
            0x7F80_0000,
            0x7FFF_FFFF,
        ];
        let around = edges
            .into_iter()
            .flat_map(|e| [e, e | 0x8000_0000, !e, !e & 0x7FFF_FFFF]);
        let mut x = 0x9E37_79B9u32;
        let spread = (0..100_000).map(|_| {
            x ^= x << 13;
            x ^= x >> 17;
            x ^= x << 5;
            x
        });
        for u in around.chain(spread) {
            assert_eq!(ordered_is_finite(u), from_ordered(u).is_finite(), "{u:#x}");
        }
    }
}
