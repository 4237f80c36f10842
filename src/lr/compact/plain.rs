//! The two 15-bit tip fields of a plain pair word (OPERATORS.md §7.1), in one place for the
//! writer, the operators and the reader's fast pass.
//!
//! Without *tip bases* a field is the offset `tip − v`. With them (the `LRBE` flag
//! `TIP_BASES`, version 1.11) bit 14 says where the 14-bit offset starts: from `v` (*near*,
//! the ring neighbours and the tips of a spiral's tight turns) or from `v + base`, the base of
//! the side in the pair's block of 256 ring vertices (*far*: the previous or next turn of
//! the spiral, which sits at about the same distance all along a block). A depth-first ring,
//! with the fewest T0 and irregular triangles, has most of its tips tens of thousands of
//! vertices away on a large mesh: as offsets from `v` they do not fit 15 bits and would each
//! take a record.

use super::SHORT_MAX;
use crate::lr::tables::NULL;

/// The field of a `NULL` tip (a missing right triangle).
pub const NULL_FIELD: u32 = 0;
/// With tip bases: the bit of a field that says its offset starts from the block's base.
pub const FAR: u32 = 1 << 14;
/// With tip bases: the offsets a 14-bit field holds, `−2^13 ..= 2^13 − 1`.
pub const NEAR_MIN: i64 = -(1 << 13);
/// See [`NEAR_MIN`].
pub const NEAR_MAX: i64 = (1 << 13) - 1;

/// Sign-extends the low 14 bits.
#[inline(always)]
pub fn short14(bits: u32) -> i32 {
    ((bits as i32) << 18) >> 18
}

/// Sign-extends the low 15 bits.
#[inline(always)]
pub fn short15(bits: u32) -> i32 {
    ((bits as i32) << 17) >> 17
}

/// The offset `tip − v` (modulo 2^32) of a non-zero field `f` (its low 15 bits): with tip
/// bases `base` being the side's base in the pair's block, `None` without them. Written
/// without branches, for the reader's vectorized pass.
#[inline(always)]
pub fn offset(f: u32, base: Option<i32>) -> i32 {
    match base {
        None => short15(f),
        Some(base) => {
            let far = 0i32.wrapping_sub(((f & FAR) >> 14) as i32);
            short14(f).wrapping_add(base & far)
        }
    }
}

/// The tip field `f` (its low 15 bits) gives ring vertex `v`, in tables with tip bases or
/// not; `base` reads the side's base in the pair's block, only for a far field (one load
/// fewer for the operators on the common near ones).
#[inline(always)]
pub fn tip(v: u32, f: u32, tip_bases: bool, base: impl FnOnce() -> i32) -> u32 {
    let f = f & 0x7FFF;
    if f == NULL_FIELD {
        return NULL;
    }
    if !tip_bases {
        return v.wrapping_add_signed(short15(f));
    }
    let tip = v.wrapping_add_signed(short14(f));
    if f & FAR == 0 {
        tip
    } else {
        tip.wrapping_add_signed(base())
    }
}

/// The field holding `tip` for ring vertex `v`, if it fits (`NULL` only on the right).
pub fn field(tip: u32, v: u32, right: bool, base: Option<i32>) -> Option<u32> {
    if tip == NULL {
        return right.then_some(NULL_FIELD);
    }
    offset_field(tip as i64 - v as i64, base)
}

/// The field holding a tip at offset `d` (not `NULL`: never 0) from its ring vertex, if it
/// fits: near when it can, else far from `base`.
pub fn offset_field(d: i64, base: Option<i32>) -> Option<u32> {
    let Some(base) = base else {
        return (d != 0 && (-SHORT_MAX - 1..=SHORT_MAX).contains(&d)).then_some(d as u32 & 0x7FFF);
    };
    if d != 0 && (NEAR_MIN..=NEAR_MAX).contains(&d) {
        return Some(d as u32 & 0x3FFF);
    }
    let e = d.saturating_sub(base as i64);
    (NEAR_MIN..=NEAR_MAX)
        .contains(&e)
        .then_some(FAR | e as u32 & 0x3FFF)
}

/// The base for a block's tips of one side, given their offsets `tip − v` (of the tips that
/// are not `NULL`): the middle of the window of `2^14` offsets that holds the most of those
/// a near field cannot, 0 when there are none.
pub fn choose_base(offsets: impl Iterator<Item = i64>) -> i32 {
    let mut far: Vec<i64> = offsets
        .filter(|d| !(NEAR_MIN..=NEAR_MAX).contains(d) || *d == 0)
        .collect();
    far.sort_unstable();
    let (mut best, mut base, mut first) = (0, 0i64, 0);
    for last in 0..far.len() {
        while far[last] - far[first] > NEAR_MAX - NEAR_MIN {
            first += 1;
        }
        if last + 1 - first > best {
            best = last + 1 - first;
            // The window [far[first], far[first] + 2^14 − 1] covers first..=last.
            base = far[first] - NEAR_MIN;
        }
    }
    // Any base is valid; one beyond 32 bits (offsets of a ring of 2^31 vertices) is
    // clamped, which only makes some of its tips long.
    base.clamp(i32::MIN as i64, i32::MAX as i64) as i32
}

/// For the period estimate: how many pairs of a ring need a record for a long tip, with
/// `offsets` the two tips' offsets `tip − v` of each ring vertex from 0 on (0 for a `NULL`
/// tip, which always fits; `i64::MAX` for one that never does): without tip bases, and with
/// the bases [`choose_base`] gives each block of `block` vertices.
pub fn long_pairs(offsets: &[[i64; 2]], block: usize) -> [u64; 2] {
    let fits = |d: i64, base: Option<i32>| d == 0 || offset_field(d, base).is_some();
    let mut long = [0u64; 2];
    for chunk in offsets.chunks(block.max(1)) {
        let bases = [0, 1].map(|side| {
            choose_base(
                chunk
                    .iter()
                    .map(|d| d[side])
                    .filter(|&d| d != 0 && d != i64::MAX),
            )
        });
        for d in chunk {
            long[0] += !(fits(d[0], None) && fits(d[1], None)) as u64;
            long[1] += !(fits(d[0], Some(bases[0])) && fits(d[1], Some(bases[1]))) as u64;
        }
    }
    long
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every tip a field can hold decodes back, with and without bases, at the range ends.
    #[test]
    fn fields_decode_to_their_tips() {
        for base in [None, Some(0), Some(-40_000), Some(123_456), Some(i32::MIN)] {
            for v in [0u32, 7, 50_000, 1 << 29] {
                for d in [
                    -40_000i64, -16_384, -16_383, -8_193, -8_192, -2, -1, 1, 2, 8_191,
                ]
                .into_iter()
                .chain([
                    8_192,
                    16_383,
                    16_384,
                    30_000,
                    123_456 - 8_192,
                    123_456 + 8_191,
                ]) {
                    let tip = v as i64 + d;
                    if !(0..NULL as i64).contains(&tip) {
                        continue;
                    }
                    let tip = tip as u32;
                    for right in [false, true] {
                        if let Some(f) = field(tip, v, right, base) {
                            assert_eq!(f & !0x7FFF, 0);
                            let got = self::tip(v, f, base.is_some(), || base.unwrap_or(0));
                            assert_eq!(got, tip, "{v} {d} {base:?}");
                            let f = f | (right as u32) << 15;
                            assert_eq!(v.wrapping_add_signed(offset(f & 0x7FFF, base)), tip);
                        }
                    }
                }
                assert_eq!(field(NULL, v, true, base), Some(NULL_FIELD));
                assert_eq!(field(NULL, v, false, base), None);
                assert_eq!(tip(v, NULL_FIELD, base.is_some(), || 0), NULL);
            }
        }
        // Near offsets always fit; far ones fit within 2^13 of the base.
        assert!(field(100, 100 + 8_192, false, Some(0)).is_some());
        assert_eq!(field(100, 100 + 8_193, false, Some(0)), None);
        assert_eq!(field(100, 100 + 8_193, false, Some(-8_193)), Some(FAR));
        assert!(field(100, 100 + 8_193, false, None).is_some());
    }

    /// The base covers the largest cluster of far offsets.
    #[test]
    fn the_base_covers_the_most_far_offsets() {
        let offsets = [1, -1, 2, -20_000, -21_000, -19_500, 40_000, -20_100];
        let base = choose_base(offsets.into_iter());
        let covered = offsets
            .iter()
            .filter(|&&d| (NEAR_MIN..=NEAR_MAX).contains(&(d - base as i64)))
            .count();
        assert_eq!(covered, 4); // the far cluster around -20_000
        assert_eq!(choose_base([1i64, 5, -3].into_iter()), 0);
    }
}
