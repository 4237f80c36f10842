//! The loops of the LR paper's Fig. 10 (c.v and c.o over every corner, valence and normal
//! of every vertex, contour walks), timed on any [`CornerOps`], alone or in interleaved
//! rounds: once here, for `lrmesh bench` and the bench binaries.

use std::hint::black_box;
use std::time::{Duration, Instant};

use super::record;
use crate::ids::Triangle;
use crate::ops::{self, CornerOps, Plane};

/// Sixteen parallel planes (slightly tilted from the third axis) spread evenly across the
/// positions' extent along their normal, each with a triangle of `mesh` it cuts: the starts
/// of the contour walks. The planes depend on the positions only, so every representation
/// walks the same contours. (Spread along the third coordinate alone, the tilted planes
/// missed every triangle of a mesh far from the origin, such as polygon_mesh, whose contour
/// loop then timed nothing.)
pub fn contour_starts<M: CornerOps>(mesh: &M, positions: &[[f32; 3]]) -> Vec<(Plane, Triangle)> {
    let normal = [0.05, 0.02, 1.0];
    let along = |p: &[f32; 3]| normal[0] * p[0] + normal[1] * p[1] + normal[2] * p[2];
    let (lo, hi) = positions
        .iter()
        .map(along)
        .filter(|d| d.is_finite())
        .fold((f32::MAX, f32::MIN), |(lo, hi), d| (lo.min(d), hi.max(d)));
    if lo > hi {
        return Vec::new();
    }
    (0..16)
        .filter_map(|k| {
            let plane = Plane {
                normal,
                offset: lo + (hi - lo) * (k as f32 + 0.5) / 16.0,
            };
            let t = mesh.triangles().find(|&t| {
                let above = mesh
                    .triangle_vertices(t)
                    .map(|v| positions.get(v.idx()).is_some_and(|&p| plane.above(p)));
                above[0] != above[1] || above[1] != above[2]
            })?;
            Some((plane, t))
        })
        .collect()
}

/// Names of the Fig. 10 loops, in the order of [`LoopTimes`].
pub const LOOP_NAMES: [&str; 5] = ["c.v", "c.o", "valence", "normals", "contour"];

/// Times of the Fig. 10 loops on one representation, with the items each visits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopTimes {
    /// Items per loop: corners, corners, vertices, vertices, triangles walked.
    pub items: [usize; 5],
    /// Median time per loop.
    pub times: [Duration; 5],
}

impl LoopTimes {
    /// Nanoseconds per item of loop `i`.
    pub fn ns_per_item(&self, i: usize) -> f64 {
        self.times[i].as_secs_f64() * 1e9 / self.items[i].max(1) as f64
    }

    /// Time per item of each loop as a ratio to `baseline`'s.
    pub fn ratios(&self, baseline: &LoopTimes) -> [f64; 5] {
        [0, 1, 2, 3, 4].map(|i| self.ns_per_item(i) / baseline.ns_per_item(i))
    }
}

/// Runs the Fig. 10 loops on `mesh` (`positions` indexed by its vertex ids), each `runs`
/// times, and keeps the medians.
pub fn fig10_loops<M: CornerOps>(mesh: &M, positions: &[[f32; 3]], runs: usize) -> LoopTimes {
    let subject = [("", Fig10::new(mesh, positions))];
    let mut timed = interleaved_loops(&subject, runs);
    timed.swap_remove(0).0
}

/// The Fig. 10 loops of one representation, ready to be timed a run at a time
/// ([`interleaved_loops`]).
pub struct Fig10<'a> {
    /// Items per loop, as in [`LoopTimes`].
    items: [usize; 5],
    /// Runs loop `i` once and returns its time.
    once: Box<dyn Fn(usize) -> Duration + 'a>,
}

impl<'a> Fig10<'a> {
    /// The loops on `mesh`, `positions` indexed by its vertex ids; the contour walks' starts
    /// are found now.
    pub fn new<M: CornerOps>(mesh: &'a M, positions: &'a [[f32; 3]]) -> Fig10<'a> {
        Fig10::with_reset(mesh, positions, || {})
    }

    /// [`Fig10::new`] for a representation with state that a run leaves behind (the Zipper
    /// cursor's decoded blocks): `reset` runs before each timed run, untimed, so that every
    /// run starts as the first.
    pub fn with_reset<M: CornerOps>(
        mesh: &'a M,
        positions: &'a [[f32; 3]],
        reset: impl Fn() + 'a,
    ) -> Fig10<'a> {
        let starts = contour_starts(mesh, positions);
        let walk = move || {
            starts
                .iter()
                .map(|(plane, t)| ops::contour(mesh, positions, plane, *t).len())
                .sum::<usize>()
        };
        let corners = mesh.corners().count();
        let vertices = mesh.vertices().count();
        let walked = walk();
        let once = move |i: usize| {
            reset();
            let start = Instant::now();
            match i {
                0 => {
                    black_box(mesh.corners().fold(0u32, |a, c| a ^ mesh.vertex(c).0));
                }
                1 => {
                    black_box(
                        mesh.corners()
                            .fold(0u32, |a, c| a ^ mesh.opposite(c).map_or(0, |o| o.0)),
                    );
                }
                2 => {
                    black_box(mesh.vertices().map(|v| ops::valence(mesh, v)).sum::<u32>());
                }
                3 => {
                    black_box(ops::vertex_normals(mesh, positions));
                }
                _ => {
                    black_box(walk());
                }
            }
            start.elapsed()
        };
        Fig10 {
            items: [corners, corners, vertices, vertices, walked],
            once: Box::new(once),
        }
    }
}

/// Times the loops of `subjects` (named for the report's timings) in `runs` rounds, each
/// round running every loop once on every subject, one loop after the other: a machine whose
/// speed drifts during the run (a busy neighbour, a clock that changes) slows every subject
/// alike instead of the one being timed. Returns each subject's median times, and its ratios
/// of time per item to the first subject's: for each loop, the median over the rounds of the
/// ratio within a round.
pub fn interleaved_loops(subjects: &[(&str, Fig10)], runs: usize) -> Vec<(LoopTimes, [f64; 5])> {
    let runs = runs.max(1);
    // times[s][i][r]: subject s, loop i, round r.
    let mut times = vec![[(); 5].map(|_| Vec::with_capacity(runs)); subjects.len()];
    for _ in 0..runs {
        for i in 0..5 {
            for ((_, subject), times) in subjects.iter().zip(&mut times) {
                // Once untimed first: every subject is timed with its tables in cache, as
                // when its runs follow one another, not after the other subjects' evicted them.
                (subject.once)(i);
                times[i].push((subject.once)(i));
            }
        }
    }
    let per_item = |s: usize, i: usize, r: usize| {
        times[s][i][r].as_secs_f64() / subjects[s].1.items[i].max(1) as f64
    };
    let ratios: Vec<[f64; 5]> = (0..subjects.len())
        .map(|s| {
            [0, 1, 2, 3, 4].map(|i| {
                let mut r: Vec<f64> = (0..runs)
                    .map(|r| per_item(s, i, r) / per_item(0, i, r).max(1e-15))
                    .collect();
                r.sort_by(f64::total_cmp);
                r[runs / 2]
            })
        })
        .collect();
    subjects
        .iter()
        .zip(times)
        .zip(ratios)
        .map(|(((name, subject), times), ratios)| {
            let mut i = 0;
            let medians = times.map(|t| {
                let step = (!name.is_empty()).then(|| format!("{name}: {}", LOOP_NAMES[i]));
                i += 1;
                record(step, t)
            });
            let loops = LoopTimes {
                items: subject.items,
                times: medians,
            };
            (loops, ratios)
        })
        .collect()
}
