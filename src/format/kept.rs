//! `KEPC` (FORMAT.md §3.7.1): the kept-aside triangles of an Edgebreaker container, range
//! coded instead of `KEPT`'s three u32 per triangle. Most kept triangles are degenerate
//! (a vertex repeated) and come in runs from one strip or fan of the input, so each is coded
//! as which of its corners repeat, then its distinct vertices as differences: the first from
//! the previous triangle's first, each other from the one before it.

use crate::edgebreaker::coder::{code_uint, max_decisions, Bit, Bits, Decoder, Encoder, UintModel};

/// Bytes before the stream: u32 `k`, u32 `n`.
pub const HEADER_LEN: usize = 8;

/// Which corners of a triangle share a vertex: 0 none, 1 corners 0 and 1, 2 corners 1 and 2,
/// 3 corners 0 and 2, 4 all three.
const PATTERNS: u32 = 5;

fn pattern(t: [u32; 3]) -> u32 {
    match (t[0] == t[1], t[1] == t[2], t[0] == t[2]) {
        (true, true, _) => 4,
        (true, false, _) => 1,
        (false, true, _) => 2,
        (false, false, true) => 3,
        (false, false, false) => 0,
    }
}

/// Which corners take the triangle's distinct vertices, in order (the others repeat one).
fn distinct_corners(p: u32) -> &'static [usize] {
    match p {
        0 => &[0, 1, 2],
        1 => &[0, 2],
        2 | 3 => &[0, 1],
        _ => &[0],
    }
}

/// The adaptive state of one stream (FORMAT.md §3.7.1).
#[derive(Default)]
struct Models {
    pattern: [[Bit; 8]; PATTERNS as usize],
    first: UintModel,
    first_sign: Bit,
    next: UintModel,
    next_sign: Bit,
}

/// Codes a signed difference as its magnitude, then its sign when not 0.
fn code_signed<B: Bits>(b: &mut B, m: &mut UintModel, sign: &mut Bit, d: i64) -> Option<i64> {
    let magnitude = code_uint(b, m, d.unsigned_abs())? as i64;
    if magnitude == 0 {
        return Some(0);
    }
    let negative = b.bit(sign, u32::from(d < 0)) == 1;
    Some(if negative { -magnitude } else { magnitude })
}

/// Codes (encoder: `tris`) or decodes `k` triangles of vertices below `vertices` into `out`.
fn code<B: Bits>(
    b: &mut B,
    tris: &[[u32; 3]],
    k: u32,
    vertices: u32,
    out: &mut Vec<u32>,
) -> Result<(), (u64, String)> {
    let mut m = Models::default();
    let (mut before, mut previous_first) = (0usize, 0i64);
    for j in 0..k as usize {
        let at = b.offset();
        let want = tris.get(j).copied().unwrap_or_default();
        let wanted = pattern(want);
        let mut node = 1usize;
        for i in (0..3).rev() {
            node = 2 * node + b.bit(&mut m.pattern[before][node], (wanted >> i) & 1) as usize;
        }
        let p = (node - 8) as u32;
        if p >= PATTERNS {
            return Err((at, format!("kept triangle {j}: pattern {p}, at most 4")));
        }
        let mut tri = [0u32; 3];
        let mut last = previous_first;
        for (i, &corner) in distinct_corners(p).iter().enumerate() {
            let d = i64::from(want[corner]) - last;
            let got = if i == 0 {
                code_signed(b, &mut m.first, &mut m.first_sign, d)
            } else {
                code_signed(b, &mut m.next, &mut m.next_sign, d).filter(|&d| d != 0)
            };
            let v = got.map(|d| last + d);
            let Some(v) = v.filter(|&v| (0..i64::from(vertices)).contains(&v)) else {
                return Err((
                    at,
                    format!("kept triangle {j}: a vertex not below {vertices}, or repeated"),
                ));
            };
            tri[corner] = v as u32;
            if i == 0 {
                previous_first = v;
            }
            last = v;
        }
        match p {
            1 => tri[1] = tri[0],
            2 => tri[2] = tri[1],
            3 => tri[2] = tri[0],
            4 => tri = [tri[0]; 3],
            _ => {}
        }
        if p == 0 && tri[0] == tri[2] {
            return Err((at, format!("kept triangle {j}: a vertex repeated")));
        }
        if b.overrun() {
            return Err((
                b.offset(),
                format!("the stream ends before kept triangle {j}"),
            ));
        }
        out.extend_from_slice(&tri);
        before = p as usize;
    }
    Ok(())
}

/// The stream of `tris` (every vertex below `u32::MAX`).
pub(crate) fn encode(tris: &[[u32; 3]]) -> Vec<u8> {
    let mut e = Encoder::new();
    code(&mut e, tris, tris.len() as u32, u32::MAX, &mut Vec::new())
        .expect("the encoder's own triangles");
    e.finish()
}

/// The vertices of `k` kept triangles from `stream` (at byte `base` of the file, for errors),
/// three each, all below `vertices`; `Err((offset, message))` when the stream breaks [V50].
pub(crate) fn decode(
    stream: &[u8],
    base: usize,
    k: u32,
    vertices: u32,
) -> Result<Vec<u32>, (u64, String)> {
    // Each triangle takes at least four decisions: the bound keeps a forged `k` from sizing
    // the output beyond what the stream can hold.
    if u64::from(k) > max_decisions(stream.len()) / 4 {
        return Err((
            base as u64,
            format!(
                "{k} kept triangles, more than {} bytes can hold",
                stream.len()
            ),
        ));
    }
    let mut out = Vec::with_capacity(3 * k as usize);
    code(&mut Decoder::new(stream, base), &[], k, vertices, &mut out)?;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_pattern_round_trips() {
        let tris = [
            [5, 5, 7],
            [7, 9, 9],
            [3, 4, 3],
            [8, 8, 8],
            [0, 1, 2],
            [2, 1, 0],
            [100, 100, 4],
        ];
        let stream = encode(&tris);
        let back = decode(&stream, 0, tris.len() as u32, 101).unwrap();
        assert_eq!(back, tris.concat());
        assert!(decode(&stream, 0, tris.len() as u32, 100).is_err());
        assert!(decode(&stream, 0, 1 << 30, 101).is_err());
    }
}
