//! `COPC` (FORMAT.md §3.6.1): the vertex copies of an Edgebreaker container, range coded
//! instead of `COPY`'s two u32 per copy. Copies come in increasing order and each original
//! is an earlier vertex (the writer makes the first container vertex of an input vertex its
//! original), so a copy is coded as the gap from the copy before and its original as the
//! distance back from the copy.

use crate::edgebreaker::coder::{code_uint, max_decisions, Bits, Decoder, Encoder, UintModel};

/// Bytes before the stream: u32 `k`, u32 `n`.
pub const HEADER_LEN: usize = 8;

/// The adaptive state of one stream (FORMAT.md §3.6.1).
#[derive(Default)]
struct Models {
    gap: UintModel,
    back: UintModel,
}

/// Codes (encoder: `pairs`) or decodes `k` pairs of vertices below `vertices` into `out`.
fn code<B: Bits>(
    b: &mut B,
    pairs: &[(u32, u32)],
    k: u32,
    vertices: u32,
    out: &mut Vec<u32>,
) -> Result<(), (u64, String)> {
    let mut m = Models::default();
    let mut next = 0u64;
    // The copies so far, increasing: an original must not be one of them.
    let mut copies: Vec<u32> = Vec::new();
    for j in 0..k as usize {
        let at = b.offset();
        let (copy, original) = pairs.get(j).copied().unwrap_or_default();
        let gap = u64::from(copy).wrapping_sub(next);
        let copy = code_uint(b, &mut m.gap, gap)
            .map(|g| next + g)
            .filter(|&c| c < u64::from(vertices));
        let Some(copy) = copy else {
            return Err((at, format!("copy {j}: a vertex not below {vertices}")));
        };
        let back = copy.wrapping_sub(u64::from(original) + 1);
        let original = code_uint(b, &mut m.back, back)
            .filter(|&d| d < copy)
            .map(|d| copy - 1 - d);
        let Some(original) = original else {
            return Err((
                at,
                format!("copy {j}: an original not below the copy {copy}"),
            ));
        };
        if copies.binary_search(&(original as u32)).is_ok() {
            return Err((
                at,
                format!("copy {j}: the original {original} is itself a copy"),
            ));
        }
        copies.push(copy as u32);
        if b.overrun() {
            return Err((b.offset(), format!("the stream ends before copy {j}")));
        }
        out.extend_from_slice(&[copy as u32, original as u32]);
        next = copy + 1;
    }
    Ok(())
}

/// Whether `pairs` can be coded: copies increasing, each original before its copy.
pub(crate) fn codable(pairs: &[(u32, u32)]) -> bool {
    pairs.iter().all(|&(c, o)| o < c) && pairs.windows(2).all(|w| w[0].0 < w[1].0)
}

/// The stream of `pairs` ([`codable`] ones).
pub(crate) fn encode(pairs: &[(u32, u32)]) -> Vec<u8> {
    let mut e = Encoder::new();
    code(&mut e, pairs, pairs.len() as u32, u32::MAX, &mut Vec::new())
        .expect("the encoder's own copies");
    e.finish()
}

/// The `(copy, original)` pairs, flattened, of `k` copies from `stream` (at byte `base` of
/// the file, for errors), all below `vertices`; `Err((offset, message))` when the stream
/// breaks [V52].
pub(crate) fn decode(
    stream: &[u8],
    base: usize,
    k: u32,
    vertices: u32,
) -> Result<Vec<u32>, (u64, String)> {
    // Each copy takes at least two decisions, and is a distinct vertex: the bounds keep a
    // forged `k` from sizing the output beyond what the stream and the vertices can hold.
    if u64::from(k) > max_decisions(stream.len()) / 2 || k > vertices {
        return Err((
            base as u64,
            format!("{k} copies cannot be coded in {} bytes", stream.len()),
        ));
    }
    let mut out = Vec::with_capacity(2 * k as usize);
    let mut d = Decoder::new(stream, base);
    code(&mut d, &[], k, vertices, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn copies_round_trip() {
        let pairs = vec![(5, 0), (6, 5 - 5), (9, 8), (40, 2), (41, 39)];
        assert!(codable(&pairs));
        let bytes = encode(&pairs);
        let back = decode(&bytes, 0, pairs.len() as u32, 50).unwrap();
        let flat: Vec<u32> = pairs.iter().flat_map(|&(c, o)| [c, o]).collect();
        assert_eq!(back, flat);
        assert!(bytes.len() < 8 * pairs.len() / 2);
    }

    /// A stream of `(gap, back)` integers as they are coded, valid or not.
    fn raw(pairs: &[(u64, u64)]) -> Vec<u8> {
        let mut e = Encoder::new();
        let mut m = Models::default();
        for &(gap, back) in pairs {
            code_uint(&mut e, &mut m.gap, gap);
            code_uint(&mut e, &mut m.back, back);
        }
        e.finish()
    }

    #[test]
    fn damaged_copies_are_refused() {
        // Copies 5 and 9; the original of 9 is 9 - 1 - 3 = 5, itself a copy.
        let e = decode(&raw(&[(5, 4), (3, 3)]), 0, 2, 50).unwrap_err();
        assert!(e.1.contains("itself a copy"), "{}", e.1);
        // Copy 45 in 40 vertices.
        let e = decode(&raw(&[(45, 0)]), 0, 1, 40).unwrap_err();
        assert!(e.1.contains("not below 40"), "{}", e.1);
        // Copy 5 with an original 5 or more back.
        let e = decode(&raw(&[(5, 5)]), 0, 1, 40).unwrap_err();
        assert!(e.1.contains("an original not below the copy 5"), "{}", e.1);
        assert!(decode(&[], 0, 1000, 50)
            .unwrap_err()
            .1
            .contains("cannot be coded"));
        assert!(decode(&[], 0, 60, 50)
            .unwrap_err()
            .1
            .contains("cannot be coded"));
        assert!(!codable(&[(3, 4)]) && !codable(&[(5, 0), (5, 1)]));
    }
}
