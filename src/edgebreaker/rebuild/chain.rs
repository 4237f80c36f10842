//! The connectivity being rebuilt, corner by corner: the D1 links that stand for opposites,
//! the fan chains that give the model its context without a walk, and the gluing operations
//! that keep both up to date. The pass spends most of its memory and loads here, so the
//! layout of a [`Slot`] (and of its [`ChainWord`]) is what this file is about.

use super::model::FAN_CAP;
use crate::corner_table::NONE;
use crate::edgebreaker::{next, prev};

/// The connectivity being rebuilt.
///
/// Opposites are not stored as such: for every corner `x` whose edge facing `x.n` is glued,
/// `d1[x]` is the next corner around its vertex in direction D1 (`x.n.o.n`), else `NONE`. The
/// walks around a vertex, most of the decoding time, then cost one load per corner;
/// `x.n.o` is `d1[x].p`, and the D2 step `y.p.o.p` is `d1[y.n].n`.
pub(super) struct State<W> {
    pub(super) slots: Vec<Slot<W>>,
    /// Vertices of each triangle.
    pub(super) v: Vec<[u32; 3]>,
    /// Corner assignments left (see [`State::assign`]).
    pub(super) budget: u32,
    /// Vertex ids still to give, counting down.
    pub(super) n: u32,
}

/// What the pass keeps per corner, side by side so that one bounds check serves both.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slot<W> {
    /// See [`State`].
    pub(super) d1: u32,
    /// For a corner at either end of a chain of corners of one vertex linked by glued edges
    /// (a fan being rebuilt), the corner at the other end and the chain's number of corners,
    /// capped at [`FAN_CAP`] (all the context needs). Maintained at every gluing, so that the
    /// context needs no walk.
    pub(super) chain: W,
}

pub(super) type Step<T = ()> = std::result::Result<T, &'static str>;

/// A chain entry: the corner at the other end and the length, in one word. Most meshes use
/// [`u32`] entries (corner ids below 2^28, lengths in the top 4 bits), larger ones two words:
/// the decoder's memory is mostly fresh pages, so every byte per corner costs time. Corners
/// of triangles not created yet read as other end 0, length 0.
pub(super) trait ChainWord: Copy + Default {
    /// Whether corner ids below `corners` fit.
    fn fits(corners: u64) -> bool;
    fn entry(end: u32, len: u32) -> Self;
    fn end(self) -> u32;
    fn len(self) -> u32;
}

impl ChainWord for u32 {
    #[inline(always)]
    fn fits(corners: u64) -> bool {
        corners <= 1 << 28
    }
    #[inline(always)]
    fn entry(end: u32, len: u32) -> u32 {
        (len << 28) | end
    }
    #[inline(always)]
    fn end(self) -> u32 {
        self & ((1 << 28) - 1)
    }
    #[inline(always)]
    fn len(self) -> u32 {
        self >> 28
    }
}

impl ChainWord for [u32; 2] {
    #[inline(always)]
    fn fits(_: u64) -> bool {
        true
    }
    #[inline(always)]
    fn entry(end: u32, len: u32) -> [u32; 2] {
        [end, len]
    }
    #[inline(always)]
    fn end(self) -> u32 {
        self[0]
    }
    #[inline(always)]
    fn len(self) -> u32 {
        self[1]
    }
}

/// `(c.n, c.p)`, with one division.
#[inline(always)]
pub(super) fn next_prev(c: u32) -> (u32, u32) {
    match c % 3 {
        0 => (c + 1, c + 2),
        1 => (c + 1, c - 1),
        _ => (c - 2, c - 1),
    }
}

impl<W: ChainWord> State<W> {
    /// `c.o`, or `NONE`.
    #[inline(always)]
    pub(super) fn opposite(&self, c: u32) -> u32 {
        match self.slots.get(prev(c) as usize) {
            Some(&Slot { d1: d, .. }) if d != NONE => prev(d),
            _ => NONE,
        }
    }

    /// Glues without chain bookkeeping (for handle edges, before their triangles exist).
    pub(super) fn glue_early(&mut self, a: u32, b: u32) -> Step {
        let len = self.slots.len();
        if a as usize >= len || b as usize >= len || a / 3 == b / 3 {
            return Err("handle corner out of range");
        }
        if self.slots[prev(a) as usize].d1 != NONE || self.slots[prev(b) as usize].d1 != NONE {
            return Err("edge glued twice");
        }
        self.slots[prev(a) as usize].d1 = next(b);
        self.slots[prev(b) as usize].d1 = next(a);
        Ok(())
    }

    /// Glues the edges facing `a` and `b`, of two different triangles, given with their `.p`
    /// and `.n` (which the callers often know without a division).
    #[inline(always)]
    fn glue3(&mut self, (pa, a, na): (u32, u32, u32), (pb, b, nb): (u32, u32, u32)) -> Step {
        let len = self.slots.len();
        if a as usize >= len || b as usize >= len {
            return Err("gate out of range");
        }
        let (pai, pbi) = (pa as usize, pb as usize);
        if pai >= len || pbi >= len || self.slots[pai].d1 != NONE || self.slots[pbi].d1 != NONE {
            return Err("edge glued twice");
        }
        self.slots[pai].d1 = nb;
        self.slots[pbi].d1 = na;
        self.link(pb, na);
        self.link(pa, nb);
        Ok(())
    }

    #[inline(always)]
    pub(super) fn glue(&mut self, a: u32, b: u32) -> Step {
        if a / 3 == b / 3 {
            return Err("edge glued to its own triangle");
        }
        self.glue3((prev(a), a, next(a)), (prev(b), b, next(b)))
    }

    /// Glues the edge facing `x.n` to the edge facing `y.p` (closing a fan from its D1 end
    /// `x` to its D2 end `y`), given `x.p` and `y.n`.
    #[inline(always)]
    pub(super) fn glue_fan(
        &mut self,
        (x, nx, px): (u32, u32, u32),
        (y, ny, py): (u32, u32, u32),
    ) -> Step {
        if x / 3 == y / 3 {
            return Err("edge glued to its own triangle");
        }
        self.glue3((x, nx, px), (ny, py, y))
    }

    /// Glues edge `k` (1: right, 2: left) of the new triangle whose tip is `c` to the gate
    /// facing `g`, the tip of an earlier triangle (so never of the same triangle).
    #[inline(always)]
    pub(super) fn glue_new(&mut self, c: u32, k: u32, g: u32) -> Step {
        let a = if k == 1 {
            (c, c + 1, c + 2)
        } else {
            (c + 1, c + 2, c)
        };
        self.glue3(a, (g.wrapping_add(2), g, g.wrapping_add(1)))
    }

    /// [`State::glue_new`] for a triangle just created, whose corners are still chains of
    /// one corner: the first chain join needs no load on the new side.
    #[inline(always)]
    pub(super) fn glue_fresh(&mut self, c: u32, k: u32, g: u32) -> Step {
        let (pa, a, na) = if k == 1 {
            (c, c + 1, c + 2)
        } else {
            (c + 1, c + 2, c)
        };
        let (pb, b, nb) = (g.wrapping_add(2), g, g.wrapping_add(1));
        let len = self.slots.len();
        if a as usize >= len || b as usize >= len {
            return Err("gate out of range");
        }
        let (pai, pbi) = (pa as usize, pb as usize);
        if pai >= len || pbi >= len || self.slots[pai].d1 != NONE || self.slots[pbi].d1 != NONE {
            return Err("edge glued twice");
        }
        self.slots[pai].d1 = nb;
        let ea = self.slots[pbi].chain;
        self.slots[pbi].d1 = na;
        // `link(pb, na)`, `na` being a chain of one corner.
        let a0 = ea.end();
        if a0 != na {
            let l = (ea.len() + 1).min(FAN_CAP);
            if let Some(e) = self.slots.get_mut(a0 as usize) {
                e.chain = W::entry(na, l);
            }
            if let Some(e) = self.slots.get_mut(na as usize) {
                e.chain = W::entry(a0, l);
            }
        }
        self.link(pa, nb);
        Ok(())
    }

    /// A new triangle: three chains of one corner.
    #[inline(always)]
    pub(super) fn create(&mut self, t: u32) {
        let c = 3 * t as usize;
        if let Some(e) = self.slots.get_mut(c..c + 3) {
            for (k, e) in e.iter_mut().enumerate() {
                e.chain = W::entry((c + k) as u32, 1);
            }
        }
    }

    /// Joins the chain that ends (direction D1) at `a` to the chain that starts at `b`.
    #[inline(always)]
    fn link(&mut self, a: u32, b: u32) {
        let (Some(&Slot { chain: ea, .. }), Some(&Slot { chain: eb, .. })) =
            (self.slots.get(a as usize), self.slots.get(b as usize))
        else {
            return;
        };
        let a0 = ea.end();
        if a0 == b {
            return; // the fan closes
        }
        let b1 = eb.end();
        let l = (ea.len() + eb.len()).min(FAN_CAP);
        if let Some(e) = self.slots.get_mut(a0 as usize) {
            e.chain = W::entry(b1, l);
        }
        if let Some(e) = self.slots.get_mut(b1 as usize) {
            e.chain = W::entry(a0, l);
        }
    }

    /// Chain bookkeeping for the edge now glued between the edges facing `a` and `b`.
    #[inline(always)]
    pub(super) fn merge_edge(&mut self, a: u32, b: u32) {
        self.link(prev(b), next(a));
        self.link(prev(a), next(b));
    }

    /// Context of the symbol of the triangle glued to `active` (a tip corner): how many
    /// triangles are already around the vertex a `C`, `L` or `S` would have as tip (the chain
    /// that starts at `active.n`), and around the tip of an `R` (the chain that ends at
    /// `active.p`), capped.
    #[inline(always)]
    pub(super) fn fans(&self, active: u32) -> usize {
        let a = active as usize;
        let (f1, f2) = match self.slots.get(a + 1..a + 3) {
            Some(&[e1, e2]) => (e1.chain.len(), e2.chain.len()),
            _ => (0, 0),
        };
        (f1 * (FAN_CAP + 1) + f2) as usize
    }
}
