//! The extended Spirale Reversi pass, shared by encoder and decoder: it reads (decoder) or
//! writes (encoder) the CLERS stream backwards and rebuilds the connectivity as it goes.
//!
//! Corners of decode triangle `t` are `3t` (the tip, facing the gate), `3t + 1` and `3t + 2`.
//! The right edge of `t` faces `3t + 1`, the left edge `3t + 2`. Around a vertex, `D1` is the
//! step `x -> x.n.o.n` (across the edge facing `x.n`) and `D2` the step `x -> x.p.o.p`.
//!
//! Every gluing must join two free edges of two different triangles, and at most `3 nt`
//! corners are given a vertex (each exactly once in a valid stream, checked at the end; a
//! walk closing a star is charged after it, and ends within `3 nt` steps anyway), so the pass
//! is linear and never loops, whatever the input.
//!
//! The decoder spends most of its time here; what makes it fast: walks around a vertex cost
//! one load per corner (`Slot::d1`), each symbol's decisions branch straight to its action,
//! chain entries fit in the same 8 bytes per corner as the walk links, and mature models adapt
//! without counting.
//!
//! The pass is split by responsibility: the adaptive model of the CLERS stream and the hole
//! lengths (`model`), the per-corner storage with its gluing and fan-chain bookkeeping
//! (`chain`), and the walks that number vertices together with the pass itself (`walk`).

mod chain;
mod model;
mod walk;

use super::coder::Bits;
use super::Topology;
use crate::error::Result;
use chain::ChainWord;
use walk::run;

/// What the encoder knows and the decoder decodes: the symbol of each triangle and the length
/// of the hole each boundary `S` reaches.
pub(crate) trait Known {
    /// The symbol of decode triangle `t`.
    fn symbol(&mut self, t: u32) -> u8;
    /// The length of the hole that the `S` at `t` reaches first, 0 if none. Called with
    /// decreasing `t`.
    fn hole(&mut self, t: u32) -> u32;
}

/// The decoder's side of [`Known`]: nothing is known.
pub(crate) struct Unknown;

impl Known for Unknown {
    #[inline(always)]
    fn symbol(&mut self, _: u32) -> u8 {
        0
    }
    #[inline(always)]
    fn hole(&mut self, _: u32) -> u32 {
        0
    }
}

/// Counts of what the pass met, for statistics.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Tally {
    /// Boundary `S` met.
    pub holes: u64,
}

/// What the pass rebuilds: the triangles in decode order and the edges it glued.
pub(crate) struct Rebuilt {
    pub triangles: Vec<[u32; 3]>,
    /// `c.o` of every corner `c` of the triangles, [`crate::ids::NONE`] at an edge left
    /// free (empty unless asked for).
    pub opposites: Vec<u32>,
    pub tally: Tally,
}

/// Runs the reverse pass over `nt` triangles and `referenced` vertices with topology `topo`;
/// the opposites only if `opposites` (else left empty).
pub(crate) fn rebuild<B: Bits, K: Known>(
    b: &mut B,
    k: &mut K,
    topo: &Topology,
    (nt, referenced): (u32, u32),
    opposites: bool,
) -> Result<Rebuilt> {
    if u32::fits(3 * nt as u64) && !force_wide() {
        run::<B, K, u32>(b, k, topo, (nt, referenced), opposites)
    } else {
        run::<B, K, [u32; 2]>(b, k, topo, (nt, referenced), opposites)
    }
}

#[cfg(test)]
thread_local! {
    /// Makes [`rebuild`] use two-word chain entries on this thread, for tests.
    static FORCE_WIDE: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

#[cfg(test)]
fn force_wide() -> bool {
    FORCE_WIDE.with(|f| f.get())
}

#[cfg(not(test))]
#[inline(always)]
fn force_wide() -> bool {
    false
}

#[cfg(all(test, feature = "generate"))]
mod tests {
    use super::FORCE_WIDE;
    use crate::edgebreaker::{decode, decode_glued, encode, Limits};
    use crate::generate::{self, Rng};
    use crate::ids::NONE;
    use crate::CornerTable;

    /// Both chain-entry widths give the same bytes and the same triangles, on meshes with
    /// handles, holes, several components and defects.
    /// An irregular torus of about `triangles` triangles beside a small torus, with
    /// `handles` handles, `holes` holes and `defects` defects (seeded by `seed`).
    fn hard_table(seed: u64, triangles: u32, [handles, holes, defects]: [usize; 3]) -> CornerTable {
        let mut rng = Rng::new(seed);
        let mut mesh = generate::irregular_torus(triangles, 5);
        generate::append(&mut mesh, &generate::torus(5, 7));
        for _ in 0..handles {
            let t = rng.below(mesh.triangles.len() as u32) as usize;
            if let Some(u) = generate::far_triangle(&mesh, t, &mut rng) {
                generate::add_handle(&mut mesh, t, u);
            }
        }
        generate::punch_holes(&mut mesh, holes, &mut rng);
        generate::add_defects(&mut mesh, defects, &mut rng);
        CornerTable::from_mesh(&mesh).unwrap()
    }

    #[test]
    fn chain_words_agree() {
        let table = hard_table(11, 3000, [3, 6, 4]);
        let narrow = encode(&table).unwrap();
        assert!(narrow.stats.handle_s > 0 && narrow.stats.boundary_s > 0);
        let narrow_dec = decode(&narrow.bytes, &Limits::default()).unwrap();
        FORCE_WIDE.with(|f| f.set(true));
        let wide = encode(&table).unwrap();
        let wide_dec = decode(&narrow.bytes, &Limits::default()).unwrap();
        FORCE_WIDE.with(|f| f.set(false));
        assert_eq!(narrow.bytes, wide.bytes);
        assert_eq!(narrow_dec, wide_dec);
    }

    /// The table from the decoder's glued edges is the table built from its triangles, on
    /// meshes with handles, holes, components and defects, and when the glued edges are
    /// damaged (then it is built from the triangles).
    #[test]
    fn glued_table_is_the_built_table() {
        let table = hard_table(5, 2000, [2, 4, 3]);
        let bytes = encode(&table).unwrap().bytes;
        let (decoded, o) = decode_glued(&bytes, &Limits::default()).unwrap();
        let nv = decoded.vertex_count;
        let built = CornerTable::build(nv as usize, &decoded.triangles).unwrap();
        let glued = CornerTable::from_glued(nv, decoded.triangles.clone(), o.clone()).unwrap();
        assert_eq!(glued, built);
        // The encoder's pass hands over what decoding its stream gives.
        let (_, from_encoder) = crate::edgebreaker::encode_glued(&table, true).unwrap();
        assert_eq!(from_encoder, Some((decoded.clone(), o.clone())));
        // An edge left unglued, every edge unglued, a pair glued across the wrong corners.
        let c = o.iter().position(|&d| d != NONE).unwrap();
        let mut one = o.clone();
        (one[c], one[o[c] as usize]) = (NONE, NONE);
        let mut wrong = o.clone();
        let d = o[c] as usize;
        let (c2, d2) = (c - c % 3 + (c + 1) % 3, d - d % 3 + (d + 1) % 3);
        (wrong[c], wrong[d], wrong[c2], wrong[d2]) = (c2 as u32, c as u32, NONE, NONE);
        for damaged in [one, vec![NONE; o.len()], wrong] {
            let t = CornerTable::from_glued(nv, decoded.triangles.clone(), damaged).unwrap();
            assert_eq!(t, built);
        }
    }
}
