//! The rebuild walk: the pass over the CLERS stream from the last triangle to the first
//! ([`run`]), the boundary `S` it hands to [`split`], and the walks around a vertex that give
//! corners their vertex ids (closing a star, numbering a hole or a component's external
//! boundary), charged to the budget that keeps the pass linear on any input.

use super::chain::{next_prev, ChainWord, Slot, State, Step};
use super::model::{Model, HIST};
use super::{Known, Rebuilt, Tally};
use crate::corner_table::NONE;
use crate::edgebreaker::coder::Bits;
use crate::edgebreaker::{malformed, next, prev, sym, Topology};
use crate::error::Result;

impl<W: ChainWord> State<W> {
    /// Gives corner `c` vertex `id`. A valid stream gives every corner its vertex exactly
    /// once; the budget of `3 nt` assignments bounds the work on any other (a corner given a
    /// vertex twice leaves another without one, which the final check reports).
    #[inline(always)]
    fn assign(&mut self, c: u32, id: u32) -> Step {
        if self.budget == 0 {
            return Err("corner reached twice");
        }
        self.budget -= 1;
        if let Some(v) = self.v.as_flattened_mut().get_mut(c as usize) {
            *v = id;
        }
        Ok(())
    }

    #[inline(always)]
    fn take_id(&mut self) -> Step<u32> {
        self.n = self.n.checked_sub(1).ok_or("more vertices than declared")?;
        Ok(self.n)
    }

    /// The D1 successor of `x`, or `NONE`.
    #[inline(always)]
    fn step(&self, x: u32) -> u32 {
        self.slots.get(x as usize).map_or(NONE, |s| s.d1)
    }

    /// Gives vertex `id` to `a` and the corners after it in direction D1; returns the last.
    #[inline(always)]
    fn walk_assign(&mut self, a: u32, id: u32) -> Step<u32> {
        self.assign(a, id)?;
        let mut x = a;
        loop {
            let d = self.step(x);
            if d == NONE {
                return Ok(x);
            }
            x = d;
            self.assign(x, id)?;
        }
    }

    /// The last corner from `a` in direction D1 (without numbering), or `None` if the fan
    /// closes back on `a`. The D1 step is injective, so this ends.
    fn walk_end(&self, a: u32) -> Option<u32> {
        let mut x = a;
        loop {
            let d = self.step(x);
            if d == NONE {
                return Some(x);
            }
            x = d;
            if x == a {
                return None;
            }
        }
    }

    /// Closes the star of the vertex of `a` (given with `a.n`): numbers all its corners `id`
    /// and glues the one free edge pair around it, if any. The budget is charged once per
    /// walk: each walk ends within `3 nt` steps (the D1 step is injective, so a walk either
    /// stops or comes back to `a`; if the D1 walk stops, so does the D2 walk).
    #[inline(always)]
    fn close_star(&mut self, a: u32, na: u32, id: u32) -> Step {
        self.set_vertex(a, id);
        let mut steps = 1u32;
        let mut x = a;
        let mut d = self.step(a);
        // `v` cut to the length of `slots`, so that the bounds check of a step serves both;
        // `NONE` is past the end, so that check also ends the walk.
        let slots = &self.slots[..];
        if let Some(v) = self.v.as_flattened_mut().get_mut(..slots.len()) {
            while let Some(&Slot { d1: dd, .. }) = slots.get(d as usize) {
                if d == a {
                    return self.charge(steps);
                }
                x = d;
                v[x as usize] = id;
                steps += 1;
                d = dd;
            }
        }
        let (mut y, mut ny) = (a, na);
        loop {
            let d = self.step(ny);
            if d == NONE {
                break;
            }
            (y, ny) = (next(d), next(next(d)));
            self.set_vertex(y, id);
            steps += 1;
        }
        self.charge(steps)?;
        let (nx, px) = next_prev(x);
        self.glue_fan((x, nx, px), (y, ny, prev(y)))
    }

    /// Stores the vertex of corner `c`, without charging the budget.
    #[inline(always)]
    fn set_vertex(&mut self, c: u32, id: u32) {
        if let Some(v) = self.v.as_flattened_mut().get_mut(c as usize) {
            *v = id;
        }
    }

    /// Charges `n` corner assignments to the budget.
    #[inline(always)]
    fn charge(&mut self, n: u32) -> Step {
        self.budget = self.budget.checked_sub(n).ok_or("corner reached twice")?;
        Ok(())
    }

    /// A boundary `S` with tip corner `c` reaching a hole of `len` vertices: walks backwards
    /// around the hole from the tip, numbering its vertices, and glues the `S`'s left edge to
    /// the triangle it meets on the tip's other side.
    fn hole(&mut self, c: u32, len: u32) -> Step {
        let x = self.walk_end(c).ok_or("boundary S at a closed fan")?;
        let mut cur = prev(x);
        for _ in 1..len {
            let id = self.take_id()?;
            cur = prev(self.walk_assign(cur, id)?);
        }
        let id = self.take_id()?;
        let end = self.walk_assign(cur, id)?;
        self.glue(next(end), c + 2)?;
        self.walk_assign(c, id)?;
        Ok(())
    }

    /// Numbers the external boundary of a component whose first triangle is `t0`, from its
    /// gate's first vertex on, the way the encoder did.
    fn external(&mut self, t0: u32) -> Step {
        if self.opposite(3 * t0) != NONE {
            return Err("first triangle of a component with boundary glued at its gate");
        }
        let s = 3 * t0 + 1;
        let x = self
            .walk_end(s)
            .ok_or("external boundary at a closed fan")?;
        let mut cur = prev(x);
        while cur != s {
            let id = self.take_id()?;
            cur = prev(self.walk_assign(cur, id)?);
        }
        let id = self.take_id()?;
        self.walk_assign(s, id)?;
        Ok(())
    }
}

/// A non-handle `S` at triangle `t` (tip `3t`) glued to `active`: its hole length, then
/// either the hole (a boundary `S`) or the gate the matching `E` pushed.
#[allow(clippy::too_many_arguments)]
#[inline(never)]
fn split<B: Bits, K: Known, W: ChainWord>(
    b: &mut B,
    k: &mut K,
    st: &mut State<W>,
    model: &mut Model,
    stack: &mut Vec<u32>,
    t: u32,
    active: u32,
    tally: &mut Tally,
) -> Result<()> {
    let c = 3 * t;
    let at = |b: &B, m: &str| malformed(b.offset(), m.to_string());
    st.glue_fresh(c, 1, active).map_err(|m| at(b, m))?;
    let len = k.hole(t);
    let len = model
        .code_hole(b, len)
        .ok_or_else(|| at(b, "hole length too long"))?;
    if len != 0 {
        if len < 2 {
            return Err(at(b, "hole of fewer than 2 vertices"));
        }
        tally.holes += 1;
        st.hole(c, len).map_err(|m| at(b, m))
    } else {
        let g = stack.pop().ok_or_else(|| at(b, "S without a matching E"))?;
        st.glue_new(c, 2, g).map_err(|m| at(b, m))
    }
}

/// [`rebuild`](super::rebuild) with chain entries of type `W`.
pub(super) fn run<B: Bits, K: Known, W: ChainWord>(
    b: &mut B,
    k: &mut K,
    topo: &Topology,
    (nt, referenced): (u32, u32),
    want_opposites: bool,
) -> Result<Rebuilt> {
    let mut st = State::<W> {
        slots: vec![
            Slot {
                d1: NONE,
                chain: W::default(),
            };
            3 * nt as usize
        ],
        v: vec![[NONE; 3]; nt as usize],
        n: referenced,
        budget: 3 * nt,
    };
    let mut tally = Tally::default();
    // Handle edges are glued up front; their chains are joined when the S is rebuilt.
    for &(t, c) in &topo.handles {
        st.glue_early(3 * t + 2, c)
            .map_err(|m| malformed(0, format!("handle at triangle {t}: {m}")))?;
    }
    let mut model = Model::new();
    let mut stack: Vec<u32> = Vec::new();
    let mut hi = topo.handles.len();
    // The triangle of the next handle `S` (going down), or `NONE`.
    let handle_at = |hi: usize| if hi > 0 { topo.handles[hi - 1].0 } else { NONE };
    let mut next_handle = handle_at(hi);
    macro_rules! check {
        ($e:expr) => {
            $e.map_err(|m| malformed(b.offset(), m))?
        };
    }
    for comp in topo.comps.iter().rev() {
        let last = comp.start + comp.size - 1;
        let first = comp.start + comp.closed as u32;
        stack.clear();
        // The last triangle is an uncoded `E`.
        st.create(last);
        model.push(sym::E);
        let mut active = 3 * last;
        if b.overrun() {
            return Err(malformed(b.offset(), "CLERS stream ends early"));
        }
        for t in (first..last).rev() {
            let c = 3 * t;
            st.create(t);
            // The symbol's decisions branch straight to its action: one unpredictable branch
            // per decision, none after.
            if t == next_handle {
                hi -= 1;
                next_handle = handle_at(hi);
                model.push(sym::S);
                check!(st.glue_fresh(c, 1, active));
                let partner = st.opposite(c + 2);
                st.merge_edge(c + 2, partner);
            } else {
                let s = k.symbol(t);
                let n = &mut model.nodes[st.fans(active) * HIST + model.hist];
                if b.bit(&mut n[0], (s != sym::C) as u32) == 0 {
                    model.push(sym::C);
                    check!(st.glue_fresh(c, 1, active));
                    let id = check!(st.take_id());
                    check!(st.close_star(c, c + 1, id));
                } else if b.bit(&mut n[1], (s != sym::R) as u32) == 0 {
                    model.push(sym::R);
                    check!(st.glue_fresh(c, 2, active));
                } else if b.bit(&mut n[2], (s != sym::S) as u32) == 0 {
                    model.push(sym::S);
                    split(b, k, &mut st, &mut model, &mut stack, t, active, &mut tally)?;
                } else if b.bit(&mut n[3], (s != sym::L) as u32) == 0 {
                    model.push(sym::L);
                    check!(st.glue_fresh(c, 1, active));
                } else {
                    model.push(sym::E);
                    stack.push(active);
                }
            }
            active = c;
            if b.overrun() {
                return Err(malformed(b.offset(), "CLERS stream ends early"));
            }
        }
        if !stack.is_empty() {
            return Err(malformed(b.offset(), "E without a matching S"));
        }
        if comp.closed {
            let c0 = 3 * comp.start;
            st.create(comp.start);
            check!(st.glue(c0, active));
            for (corner, next) in [(c0 + 2, c0), (c0 + 1, c0 + 2), (c0, c0 + 1)] {
                let id = check!(st.take_id());
                check!(st.close_star(corner, next, id));
            }
        } else {
            check!(st.external(comp.start));
        }
    }
    if st.n != 0 {
        return Err(malformed(b.offset(), "fewer vertices than declared"));
    }
    if st.v.as_flattened().contains(&NONE) {
        return Err(malformed(b.offset(), "corner without a vertex"));
    }
    // `c.o` is `d1[c.p].p` (see `State`).
    let opposites = if want_opposites {
        (0..st.slots.len() as u32).map(|c| st.opposite(c)).collect()
    } else {
        Vec::new()
    };
    Ok(Rebuilt {
        triangles: st.v,
        opposites,
        tally,
    })
}
