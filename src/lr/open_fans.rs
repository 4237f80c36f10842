//! The list of open fans (`LRTB` flag `OPEN_FANS`, FORMAT.md §3.5.1, version 1.17): the ring
//! vertices whose fan is open where `v.c`'s ring-edge rule does not see it, each with its
//! fan's first corner.
//!
//! Without it, `v.c` of a ring vertex on a mesh whose boundaries do not all run along the
//! ring walks the fan back to its start (OPERATORS.md §4.2, case 3), on every shared mesh
//! with holes: a vertex of valence 10,000 walks 10,000 corners. With it, `v.c` reads a bit
//! of the vertex and, when set, a rank word and the listed corner: three reads whatever the
//! mesh, as the ring-end bits and ranks are read.

use super::tables::{bits_and_ranks, rank_of_bit};
use crate::words::{BitsSet, Words};

/// Per ring vertex a bit, set when its fan is listed; per 32-bit word of bits the number of
/// bits set before it; the listed fans' first corners in vertex order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OpenFans<W> {
    pub(crate) bits: W,
    pub(crate) rank: W,
    pub(crate) corners: W,
}

impl<W: Words> OpenFans<W> {
    /// The first corner listed for ring vertex `v`, if `v` is listed.
    #[inline(always)]
    pub fn start(&self, v: u32) -> Option<u32> {
        let k = v as usize / 32;
        let word = self.bits.at(k);
        if word >> (v % 32) & 1 == 0 {
            return None;
        }
        Some(
            self.corners
                .at(rank_of_bit(word, self.rank.at(k), v) as usize),
        )
    }

    /// Listed fans.
    pub fn count(&self) -> usize {
        self.corners.count()
    }

    /// The `(vertex, first corner)` pairs in vertex order.
    pub fn iter(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let vertices = (0..self.bits.count())
            .flat_map(move |k| BitsSet(u64::from(self.bits.at(k))).map(move |b| 32 * k as u32 + b));
        vertices.zip((0..self.count()).map(|i| self.corners.at(i)))
    }
}

impl OpenFans<Vec<u32>> {
    /// The list of `pairs` (sorted by vertex, each below `m_r`).
    pub fn from_pairs(pairs: &[(u32, u32)], m_r: u32) -> OpenFans<Vec<u32>> {
        debug_assert!(pairs.windows(2).all(|w| w[0].0 < w[1].0));
        let (bits, rank) = bits_and_ranks(m_r as usize, pairs.iter().map(|p| p.0 as usize));
        OpenFans {
            bits,
            rank,
            corners: pairs.iter().map(|p| p.1).collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::OpenFans;
    use crate::generate;
    use crate::ids::{Corner, Vertex};
    use crate::lr::{Lr, LrOptions, LrTables};
    use crate::ops::CornerOps;
    use crate::words::Counting;
    use crate::CornerTable;
    use std::cell::Cell;

    /// The tables of `t` over counting words, with its list of open fans or without.
    fn counting<'a>(
        t: &'a LrTables<Vec<u32>>,
        reads: &'a Cell<usize>,
        listed: bool,
    ) -> LrTables<Counting<'a>> {
        let w = |words: &'a Vec<u32>| Counting { words, reads };
        LrTables {
            lr: w(&t.lr),
            vo_v: w(&t.vo_v),
            vo_o: w(&t.vo_o),
            vo_star: w(&t.vo_star),
            c: w(&t.c),
            ring_starts: w(&t.ring_starts),
            ring_last: w(&t.ring_last),
            ring_rank: w(&t.ring_rank),
            m_r: t.m_r,
            m: t.m,
            boundaries_on_ring: t.boundaries_on_ring,
            open_fans: t.open_fans.as_ref().filter(|_| listed).map(|f| OpenFans {
                bits: w(&f.bits),
                rank: w(&f.rank),
                corners: w(&f.corners),
            }),
        }
    }

    /// With the list, `v.c` of every vertex reads at most 24 words (the ring steps and slots
    /// before it and its canonical corner, then a bit, a rank and a corner), on meshes with
    /// many holes and several rings, where without the list it
    /// walks fans of many more; the answers are the same.
    #[test]
    fn vertex_corner_reads_a_bounded_number_of_words() {
        let mut rng = generate::Rng::new(17);
        let mut holes = generate::irregular_torus(20_000, 3);
        generate::punch_holes(&mut holes, 60, &mut rng);
        let mut meshes = vec![holes, generate::soup(30, 80, &mut rng)];
        for name in ["elephant-with-holes.off", "b9_mesh.off", "hedra_open.off"] {
            meshes.push(crate::io::corpus_mesh(name));
        }
        for (i, mesh) in meshes.iter().enumerate() {
            let ct = CornerTable::from_mesh(mesh).unwrap();
            let lr = Lr::build(&ct, &LrOptions::default()).unwrap();
            assert!(
                lr.tables().open_fans.is_some(),
                "mesh {i}: the fans are listed"
            );
            let reads = Cell::new(0);
            let (with, without) = (
                counting(lr.tables(), &reads, true),
                counting(lr.tables(), &reads, false),
            );
            let mut most = [0usize; 2];
            for v in 0..lr.vertex_id_bound() {
                let mut answers = [None::<Corner>; 2];
                for (k, t) in [&with, &without].into_iter().enumerate() {
                    reads.set(0);
                    answers[k] = t.vertex_corner(Vertex(v));
                    most[k] = most[k].max(reads.get());
                }
                assert_eq!(answers[0], answers[1], "mesh {i}, vertex {v}");
                assert_eq!(answers[0], lr.vertex_corner(Vertex(v)));
            }
            eprintln!("mesh {i}: most words read by v.c with the list and without: {most:?}");
            assert!(most[0] <= 24, "mesh {i}: {most:?}");
            assert!(
                most[1] > 2 * most[0],
                "mesh {i}: the walk reads more: {most:?}"
            );
        }
    }
}
