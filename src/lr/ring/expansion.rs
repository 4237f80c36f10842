//! The ring expansions (RING-EXPANDER, HYBRID-RING-EXPANDER) of one component from several
//! seed corners, shared among threads, keeping the best: what [`super::Prepared::rings`] and
//! the bit-efficient LR's period estimates start from.

use super::{reset, t0_after_warts, Component, Marks};
use crate::lr::closed::{next3, prev3, Closed};
use crate::rng::Rng;

/// RING-EXPANDER (section 4.2) from seed corner `s`: marks invaded triangles and visited
/// vertices. Dummy vertices must already be marked visited.
fn ring_expander(mesh: &Closed, s: u32, vm: &mut Marks, tm: &mut Marks) {
    vm.set(mesh.v(next3(s)) as usize);
    vm.set(mesh.v(prev3(s)) as usize);
    let stop = mesh.o(s);
    let mut c = s;
    loop {
        if !vm.get(mesh.v(c) as usize) {
            vm.set(mesh.v(c) as usize);
            tm.set(c as usize / 3);
        } else if !tm.get(c as usize / 3) {
            c = mesh.o(c);
        }
        c = mesh.right(c);
        if c == stop {
            break;
        }
    }
}

/// HYBRID-RING-EXPANDER (section 6.1) with period `period`: the invasion proceeds depth
/// first from a double-ended queue of candidate corners, but after every `period`-th invaded
/// triangle it resumes from the oldest candidate (breadth first), which bounds the length of
/// the corridors and so the ring offsets `v.l - v` and `v.r - v`. `period = 1` is breadth
/// first. Dummy vertices must already be marked visited.
fn hybrid_ring_expander(
    mesh: &Closed,
    s: u32,
    period: u32,
    vm: &mut Marks,
    tm: &mut Marks,
    deque: &mut std::collections::VecDeque<u32>,
) {
    vm.set(mesh.v(next3(s)) as usize);
    vm.set(mesh.v(prev3(s)) as usize);
    deque.clear();
    let mut invaded = 0u32;
    let mut c = s;
    loop {
        if !vm.get(mesh.v(c) as usize) {
            vm.set(mesh.v(c) as usize);
            tm.set(c as usize / 3);
            // c.l and c.r: the corners facing the two edges the invasion exposed.
            deque.push_back(mesh.o(next3(c)));
            deque.push_back(mesh.o(prev3(c)));
            invaded = (invaded + 1) % period;
        }
        let candidate = if invaded == 0 {
            deque.pop_front()
        } else {
            deque.pop_back()
        };
        match candidate {
            Some(next) => c = next,
            None => break,
        }
    }
}

/// Components of fewer triangles than this expand their tries on one thread: a thread costs
/// more than their expansions.
const PARALLEL_TRIANGLES: usize = 1 << 16;

/// What one ring expansion writes: visited vertices (dummies always) and invaded triangles.
pub(super) struct Scratch {
    deque: std::collections::VecDeque<u32>,
    vm: Marks,
    pub(super) tm: Marks,
}

impl Scratch {
    fn new(mesh: &Closed) -> Scratch {
        let mut vm = Marks::new(mesh.total_vertices as usize);
        for x in mesh.real_vertices..mesh.total_vertices {
            vm.set(x as usize);
        }
        Scratch {
            deque: std::collections::VecDeque::new(),
            vm,
            tm: Marks::new(mesh.triangle_count()),
        }
    }

    fn expand(&mut self, mesh: &Closed, period: u32, comp: &Component, s: u32) {
        reset(comp, &mut self.vm, &mut self.tm);
        if period == 0 {
            ring_expander(mesh, s, &mut self.vm, &mut self.tm)
        } else {
            let (vm, tm, deque) = (&mut self.vm, &mut self.tm, &mut self.deque);
            hybrid_ring_expander(mesh, s, period, vm, tm, deque)
        }
    }

    /// The expansion's cost, smaller is better: isolated vertices (counted only when there is
    /// a choice), then T0 triangles left after wart skipping, each of which costs its own six
    /// references and makes its neighbours irregular.
    fn score(&self, mesh: &Closed, comp: &Component, tries: usize) -> (usize, usize) {
        let isolated = match tries {
            0 | 1 => 0,
            _ => comp
                .vertices
                .iter()
                .filter(|&&x| !self.vm.get(x as usize))
                .count(),
        };
        (isolated, t0_after_warts(mesh, comp, &self.tm))
    }

    /// Takes `other`'s expansion of `comp`.
    fn copy_component(&mut self, other: &Scratch, comp: &Component) {
        for &x in &comp.vertices {
            self.vm.put(x as usize, other.vm.get(x as usize));
        }
        for &t in &comp.triangles {
            self.tm.put(t as usize, other.tm.get(t as usize));
        }
    }
}

/// The state of the ring expansions of one period, component after component.
pub(super) struct Expansion<'m> {
    mesh: &'m Closed<'m>,
    period: u32,
    rng: Rng,
    threads: usize,
    /// The expansion kept: the rings are walked from its `tm`.
    pub(super) main: Scratch,
    /// Per thread, a scratch for its tries and one for its best so far (thread 0's best is
    /// `main`): a try that does better is swapped in, so the best is never expanded twice.
    /// Made on first use.
    trying: Vec<Scratch>,
    bests: Vec<Scratch>,
}

impl<'m> Expansion<'m> {
    pub(super) fn new(mesh: &'m Closed<'m>, period: u32, seed: u64, threads: u32) -> Expansion<'m> {
        Expansion {
            mesh,
            period,
            rng: Rng::new(seed),
            threads: threads.max(1) as usize,
            main: Scratch::new(mesh),
            trying: Vec::new(),
            bests: Vec::new(),
        }
    }

    /// Expands `comp` from `tries` seed corners and keeps the best ([`Scratch::score`]; the
    /// first of equals) in `main`; returns its T0 count. With several threads the tries are
    /// shared among them round robin: the seeds are drawn first, in the same order, so the
    /// ring is the same whatever the thread count.
    pub(super) fn best_of(&mut self, comp: &Component, tries: u32) -> usize {
        let seeds: Vec<u32> = (0..tries.max(1))
            .map(|_| {
                let n = comp.real_count() as u32;
                let t = comp.real_triangle(self.rng.below(n) as usize);
                3 * t + self.rng.below(3)
            })
            .collect();
        let (mesh, period) = (self.mesh, self.period);
        let workers = match comp.triangles.len() >= PARALLEL_TRIANGLES {
            true => self.threads.min(seeds.len()),
            false => 1,
        };
        if comp.triangles.len() >= crate::progress::TICK {
            crate::progress::phase("rings", seeds.len() as u64);
        }
        while self.trying.len() < workers {
            self.trying.push(Scratch::new(mesh));
        }
        while self.bests.len() + 1 < workers {
            self.bests.push(Scratch::new(mesh));
        }
        // Worker k tries seeds k, k + workers, ... in `scratch` and swaps each better one
        // into `best`: returns its best (score, seed index).
        let run = |k: usize, scratch: &mut Scratch, best: &mut Scratch| {
            let mut kept: Option<((usize, usize), usize)> = None;
            for i in (k..seeds.len()).step_by(workers) {
                // Only the calling thread (worker 0) has a reporter.
                crate::progress::advance(i as u64);
                scratch.expand(mesh, period, comp, seeds[i]);
                let score = scratch.score(mesh, comp, seeds.len());
                if kept.is_none_or(|(b, _)| score < b) {
                    kept = Some((score, i));
                    std::mem::swap(scratch, best);
                }
            }
            kept.expect("a seed per worker")
        };
        let (trying, bests) = (&mut self.trying[..workers], &mut self.bests[..workers - 1]);
        let (mine, theirs) = trying.split_first_mut().expect("one worker at least");
        let main = &mut self.main;
        let results: Vec<_> = std::thread::scope(|scope| {
            let handles: Vec<_> = theirs
                .iter_mut()
                .zip(bests.iter_mut())
                .enumerate()
                .map(|(k, (scratch, best))| scope.spawn(move || run(k + 1, scratch, best)))
                .collect();
            let first = run(0, mine, main);
            // A worker only panics on a broken invariant: pass it on.
            let others = handles.into_iter().map(|h| h.join().expect("ring worker"));
            std::iter::once(first).chain(others).collect()
        });
        let (k, &((_, t0), _)) = results
            .iter()
            .enumerate()
            .min_by_key(|(_, (score, i))| (*score, *i))
            .expect("one worker at least");
        if k > 0 {
            self.main.copy_component(&self.bests[k - 1], comp);
        }
        t0
    }
}
