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

use super::coder::{code_uint, Bit, Bits, UintModel};
use super::{malformed, next, prev, sym, Topology};
use crate::corner_table::NONE;
use crate::error::Result;

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

/// Symbols of context: the last `ORDER` symbols coded.
const ORDER: u32 = 1;
const HIST: usize = 5usize.pow(ORDER);
/// Fan lengths are counted up to this.
const FAN_CAP: u32 = 8;
const _: () = assert!(FAN_CAP < 16, "chain lengths are stored in 4 bits");
const CONTEXTS: usize = HIST * (FAN_CAP as usize + 1) * (FAN_CAP as usize + 1);

/// The adaptive model of the CLERS stream.
struct Model {
    /// Binary decisions per context: C or not, R or not, S or not, L or E.
    nodes: Box<[[Bit; 4]; CONTEXTS]>,
    hist: usize,
    hole: [Bit; 1],
    hole_len: UintModel,
}

impl Model {
    fn new() -> Model {
        Model {
            nodes: Box::new([[Bit::default(); 4]; CONTEXTS]),
            hist: 0,
            hole: [Bit::default()],
            hole_len: UintModel::default(),
        }
    }

    #[inline(always)]
    fn push(&mut self, s: u8) {
        self.hist = if ORDER == 1 {
            s as usize // symbols are below 5
        } else {
            (self.hist * 5 + s as usize) % HIST
        };
    }

    /// Codes whether a non-handle `S` is a boundary `S`, and the length of its hole (at least 2).
    fn code_hole<B: Bits>(&mut self, b: &mut B, len: u32) -> Option<u32> {
        if b.bit(&mut self.hole[0], (len != 0) as u32) == 0 {
            return Some(0);
        }
        let l = code_uint(b, &mut self.hole_len, len.wrapping_sub(2) as u64)?;
        u32::try_from(l).ok()?.checked_add(2)
    }
}

/// The connectivity being rebuilt.
///
/// Opposites are not stored as such: for every corner `x` whose edge facing `x.n` is glued,
/// `d1[x]` is the next corner around its vertex in direction D1 (`x.n.o.n`), else `NONE`. The
/// walks around a vertex, most of the decoding time, then cost one load per corner;
/// `x.n.o` is `d1[x].p`, and the D2 step `y.p.o.p` is `d1[y.n].n`.
struct State<W> {
    slots: Vec<Slot<W>>,
    /// Vertices of each triangle.
    v: Vec<[u32; 3]>,
    /// Corner assignments left (see [`State::assign`]).
    budget: u32,
    /// Vertex ids still to give, counting down.
    n: u32,
}

/// What the pass keeps per corner, side by side so that one bounds check serves both.
#[derive(Debug, Clone, Copy)]
struct Slot<W> {
    /// See [`State`].
    d1: u32,
    /// For a corner at either end of a chain of corners of one vertex linked by glued edges
    /// (a fan being rebuilt), the corner at the other end and the chain's number of corners,
    /// capped at [`FAN_CAP`] (all the context needs). Maintained at every gluing, so that the
    /// context needs no walk.
    chain: W,
}

type Step<T = ()> = std::result::Result<T, &'static str>;

/// A chain entry: the corner at the other end and the length, in one word. Most meshes use
/// [`u32`] entries (corner ids below 2^28, lengths in the top 4 bits), larger ones two words:
/// the decoder's memory is mostly fresh pages, so every byte per corner costs time. Corners
/// of triangles not created yet read as other end 0, length 0.
trait ChainWord: Copy + Default {
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
fn next_prev(c: u32) -> (u32, u32) {
    match c % 3 {
        0 => (c + 1, c + 2),
        1 => (c + 1, c - 1),
        _ => (c - 2, c - 1),
    }
}

impl<W: ChainWord> State<W> {
    /// `c.o`, or `NONE`.
    #[inline(always)]
    fn opposite(&self, c: u32) -> u32 {
        match self.slots.get(prev(c) as usize) {
            Some(&Slot { d1: d, .. }) if d != NONE => prev(d),
            _ => NONE,
        }
    }

    /// Glues without chain bookkeeping (for handle edges, before their triangles exist).
    fn glue_early(&mut self, a: u32, b: u32) -> Step {
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
    fn glue(&mut self, a: u32, b: u32) -> Step {
        if a / 3 == b / 3 {
            return Err("edge glued to its own triangle");
        }
        self.glue3((prev(a), a, next(a)), (prev(b), b, next(b)))
    }

    /// Glues the edge facing `x.n` to the edge facing `y.p` (closing a fan from its D1 end
    /// `x` to its D2 end `y`), given `x.p` and `y.n`.
    #[inline(always)]
    fn glue_fan(&mut self, (x, nx, px): (u32, u32, u32), (y, ny, py): (u32, u32, u32)) -> Step {
        if x / 3 == y / 3 {
            return Err("edge glued to its own triangle");
        }
        self.glue3((x, nx, px), (ny, py, y))
    }

    /// Glues edge `k` (1: right, 2: left) of the new triangle whose tip is `c` to the gate
    /// facing `g`, the tip of an earlier triangle (so never of the same triangle).
    #[inline(always)]
    fn glue_new(&mut self, c: u32, k: u32, g: u32) -> Step {
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
    fn glue_fresh(&mut self, c: u32, k: u32, g: u32) -> Step {
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
    fn create(&mut self, t: u32) {
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
    fn merge_edge(&mut self, a: u32, b: u32) {
        self.link(prev(b), next(a));
        self.link(prev(a), next(b));
    }

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

    /// Context of the symbol of the triangle glued to `active` (a tip corner): how many
    /// triangles are already around the vertex a `C`, `L` or `S` would have as tip (the chain
    /// that starts at `active.n`), and around the tip of an `R` (the chain that ends at
    /// `active.p`), capped.
    #[inline(always)]
    fn fans(&self, active: u32) -> usize {
        let a = active as usize;
        let (f1, f2) = match self.slots.get(a + 1..a + 3) {
            Some(&[e1, e2]) => (e1.chain.len(), e2.chain.len()),
            _ => (0, 0),
        };
        (f1 * (FAN_CAP + 1) + f2) as usize
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

/// Counts of what the pass met, for statistics.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Tally {
    /// Boundary `S` met.
    pub holes: u64,
}

/// Runs the reverse pass over `nt` triangles and `referenced` vertices with topology `topo`;
/// returns the triangles in decode order.
pub(crate) fn rebuild<B: Bits, K: Known>(
    b: &mut B,
    k: &mut K,
    topo: &Topology,
    nt: u32,
    referenced: u32,
) -> Result<(Vec<[u32; 3]>, Tally)> {
    if u32::fits(3 * nt as u64) && !force_wide() {
        run::<B, K, u32>(b, k, topo, nt, referenced)
    } else {
        run::<B, K, [u32; 2]>(b, k, topo, nt, referenced)
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

/// [`rebuild`] with chain entries of type `W`.
fn run<B: Bits, K: Known, W: ChainWord>(
    b: &mut B,
    k: &mut K,
    topo: &Topology,
    nt: u32,
    referenced: u32,
) -> Result<(Vec<[u32; 3]>, Tally)> {
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
    Ok((st.v, tally))
}

#[cfg(all(test, feature = "generate"))]
mod tests {
    use super::FORCE_WIDE;
    use crate::edgebreaker::{decode, encode, Limits};
    use crate::generate::{self, Rng};
    use crate::CornerTable;

    /// Both chain-entry widths give the same bytes and the same triangles, on meshes with
    /// handles, holes, several components and defects.
    #[test]
    fn chain_words_agree() {
        let mut rng = Rng::new(11);
        let mut mesh = generate::irregular_torus(3000, 5);
        generate::append(&mut mesh, &generate::torus(5, 7));
        for _ in 0..3 {
            let t = rng.below(mesh.triangles.len() as u32) as usize;
            if let Some(u) = generate::far_triangle(&mesh, t, &mut rng) {
                generate::add_handle(&mut mesh, t, u);
            }
        }
        generate::punch_holes(&mut mesh, 6, &mut rng);
        generate::add_defects(&mut mesh, 4, &mut rng);
        let table = CornerTable::from_mesh(&mesh).unwrap();
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
}
