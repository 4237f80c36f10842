//! Positions predicted in Edgebreaker decode order (GEOMETRY.md §3): each vertex from the
//! vertices of lower id, by the mean of every parallelogram it closes, else its latest
//! neighbour, else the vertex before it; the residuals range coded (§4). Encoder and decoder
//! run the same code ([`Bits`]): the encoder passes the values it has and keeps them, the
//! decoder fills them in.

use super::float::{from_ordered, ordered};
use super::residual::{Residuals, KINDS};
use super::traversal::coding_order;
use super::{write_grid, Grid};
use crate::corner_table::CornerTable;
use crate::edgebreaker::coder::{Bits, Decoder, Encoder};
use crate::error::{Error, Result, Rule};
use crate::format::layout::geom;
use crate::format::PositionEncoding;
use crate::ids::NONE;
use crate::read::fields::Fields;
use crate::read::Positions;

/// The coding order, and how each vertex is predicted from the vertices before it: found
/// by walking the vertex's fan when it comes, so that nothing is built for all corners.
pub(crate) struct Plan<'t> {
    v: &'t [u32],
    o: &'t [u32],
    c: &'t [u32],
    /// The vertices in coding order ([`coding_order`]).
    order: Vec<u32>,
    /// The position of each vertex in `order`.
    rank: Vec<u32>,
}

/// The predictor of one vertex.
enum Predictor<'p> {
    /// Corners `c` whose parallelogram `v(c.n) + v(c.p) − v(c.o)` is known.
    Parallelograms(&'p [u32]),
    /// A vertex to copy: the latest neighbour, or the vertex before.
    Copy(u32),
    /// The first vertex with no neighbour: the origin of the grid or of the floats.
    Origin,
}

/// The kind of a copy or of the origin (it selects the residual models).
const KIND_COPY: usize = 0;
/// The kind of one parallelogram chosen among several.
const KIND_CHOSEN: usize = 2;

/// The kind of the middle of `n` parallelograms: 1 for one, and for several
/// `3 + min(⌈bits(spread) / 2⌉, KINDS - 4)`, by how much they disagree (`spread`: the sum
/// over the axes of the largest minus the smallest parallelogram's value).
fn kind(n: usize, spread: u64) -> usize {
    if n == 1 {
        1
    } else {
        let bits = (64 - spread.leading_zeros()) as usize;
        3 + bits.div_ceil(2).min(KINDS - 4)
    }
}

impl<'t> Plan<'t> {
    /// The plan of a corner table whose vertices each have one fan (the decoded
    /// Edgebreaker connectivity).
    pub(crate) fn of(table: &'t CornerTable) -> Plan<'t> {
        let (v, o, c) = (table.v_table(), table.o_table(), table.c_table());
        let order = coding_order(v, o, c.len());
        let mut rank = vec![0u32; c.len()];
        for (i, &x) in order.iter().enumerate() {
            rank[x as usize] = i as u32;
        }
        Plan {
            v,
            o,
            c,
            order,
            rank,
        }
    }

    /// The vertices in coding order.
    fn order(&self) -> &[u32] {
        &self.order
    }

    /// The corners of `x`'s fan, each once: swinging from its stored corner, then, if the fan
    /// is open, unswinging from it.
    fn fan(&self, x: usize, mut each: impl FnMut(usize)) {
        let start = self.c[x];
        if start == NONE {
            return;
        }
        let next = |c: usize| c - c % 3 + (c % 3 + 1) % 3;
        let prev = |c: usize| c - c % 3 + (c % 3 + 2) % 3;
        let start = start as usize;
        let mut c = start;
        loop {
            each(c);
            match self.o[next(c)] {
                NONE => break,
                d => c = next(d as usize),
            }
            if c == start {
                return;
            }
        }
        let mut c = start;
        loop {
            match self.o[prev(c)] {
                NONE => return,
                d => c = prev(d as usize),
            }
            each(c);
        }
    }

    /// The predictor of the `i`-th vertex of the order; `corners` receives its
    /// parallelogram corners in increasing id.
    fn predictor<'s>(&self, i: usize, corners: &'s mut Vec<u32>) -> Predictor<'s> {
        let x = self.order[i] as usize;
        let r = i as u32;
        let (v, o, rank) = (self.v, self.o, &self.rank);
        corners.clear();
        let mut neighbor = NONE;
        self.fan(x, |c| {
            let t = c - c % 3;
            let (a, b) = (v[t + (c % 3 + 1) % 3], v[t + (c % 3 + 2) % 3]);
            let (ra, rb) = (rank[a as usize], rank[b as usize]);
            if ra < r && rb < r && o[c] != NONE && rank[v[o[c] as usize] as usize] < r {
                corners.push(c as u32);
            }
            for (u, ru) in [(a, ra), (b, rb)] {
                if ru < r && (neighbor == NONE || ru > rank[neighbor as usize]) {
                    neighbor = u;
                }
            }
        });
        if !corners.is_empty() {
            corners.sort_unstable();
            Predictor::Parallelograms(corners)
        } else if neighbor != NONE {
            Predictor::Copy(neighbor)
        } else if i > 0 {
            Predictor::Copy(self.order[i - 1])
        } else {
            Predictor::Origin
        }
    }
}

/// The three vertices `(c.n, c.p, c.o)` of a parallelogram corner.
#[inline]
fn parallelogram(v: &[u32], o: &[u32], c: u32) -> [usize; 3] {
    let c = c as usize;
    let t = c - c % 3;
    [
        v[t + (c % 3 + 1) % 3] as usize,
        v[t + (c % 3 + 2) % 3] as usize,
        v[o[c] as usize] as usize,
    ]
}

/// The prediction from several parallelograms' values: their mean (rounded to nearest, halves
/// up) for one or two, their median for three or more (the mean of the two middle ones,
/// rounded so, for an even count), which ignores a parallelogram across a crease.
fn middle_level(values: &mut [i64]) -> i64 {
    let n = values.len() as i64;
    if n <= 2 {
        let s: i64 = values.iter().sum();
        return (2 * s + n).div_euclid(2 * n);
    }
    values.sort_unstable();
    let h = values.len() / 2;
    if n % 2 == 1 {
        values[h]
    } else {
        (values[h - 1] + values[h] + 1).div_euclid(2)
    }
}

/// [`middle_level`] for floats, in binary64: `(a + b) / 2` for two values, the median (or the
/// mean of the two middle ones) for more.
fn middle_float(values: &mut [f64]) -> f64 {
    if values.len() == 1 {
        return values[0];
    }
    if values.len() > 2 {
        values.sort_unstable_by(f64::total_cmp);
    }
    let h = values.len() / 2;
    if values.len() % 2 == 1 {
        values[h]
    } else {
        (values[h - 1] + values[h]) / 2.0
    }
}

/// The largest value minus the smallest.
fn range_of(values: &[i64]) -> i64 {
    let (lo, hi) = values
        .iter()
        .fold((i64::MAX, i64::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    hi - lo
}

/// What went wrong decoding, and where in the stream.
struct Fail {
    at: u64,
    message: String,
}

/// Bits the encoder charges for choosing one parallelogram of several, against their
/// middle (informative: any choice decodes).
const CHOICE_PENALTY: u32 = 3;

/// The encoder's choice for a vertex with several parallelograms: 0 for their middle, `j + 1`
/// for parallelogram `j` alone, whichever leaves the shortest residuals.
fn choose(cost: impl Fn(Option<usize>) -> u32, n: usize) -> usize {
    let mut best = (cost(None), 0);
    for j in 0..n {
        let c = cost(Some(j)) + CHOICE_PENALTY;
        if c < best.0 {
            best = (c, j + 1);
        }
    }
    best.1
}

/// Bits of the magnitude of `r`.
fn bits(r: i64) -> u32 {
    64 - r.unsigned_abs().leading_zeros()
}

/// Codes grid levels `q` (all of them, in coding order) with `plan`; the decoder fills `q`.
/// With `select`, the encoder may choose one parallelogram of several (GEOMETRY.md §3.3).
fn code_grid<B: Bits>(
    b: &mut B,
    plan: &Plan,
    (v, o): (&[u32], &[u32]),
    q: &mut [[u32; 3]],
    max: u32,
    select: bool,
) -> std::result::Result<(), Fail> {
    let mut models = Residuals::new(32 - max.leading_zeros());
    let mut values: Vec<[i64; 3]> = Vec::new();
    let mut scratch: Vec<i64> = Vec::new();
    let clamp = |x: i64| x.clamp(0, max as i64);
    let mut found = Vec::new();
    for (i, &x) in plan.order().iter().enumerate() {
        let x = x as usize;
        let predictor = plan.predictor(i, &mut found);
        let (predicted, kind): ([i64; 3], usize) = match predictor {
            Predictor::Parallelograms(corners) => {
                values.clear();
                values.extend(corners.iter().map(|&c| {
                    let [a, bb, oo] = parallelogram(v, o, c);
                    [0, 1, 2].map(|k| q[a][k] as i64 + q[bb][k] as i64 - q[oo][k] as i64)
                }));
                let mut spread = 0u64;
                let middle = [0, 1, 2].map(|k| {
                    scratch.clear();
                    scratch.extend(values.iter().map(|p| p[k]));
                    spread += range_of(&scratch) as u64;
                    clamp(middle_level(&mut scratch))
                });
                let n = values.len();
                let wanted = if select && n > 1 {
                    let actual = q[x].map(|x| x as i64);
                    choose(
                        |j| {
                            let p = j.map_or(middle, |j| values[j].map(clamp));
                            (0..3).map(|k| bits(actual[k] - p[k])).sum()
                        },
                        n,
                    )
                } else {
                    0
                };
                match if n > 1 {
                    models.choice(b, n, wanted)
                } else {
                    0
                } {
                    0 => (middle, kind(n, spread)),
                    j => (values[j - 1].map(clamp), KIND_CHOSEN),
                }
            }
            Predictor::Copy(u) => (q[u as usize].map(|x| x as i64), KIND_COPY),
            Predictor::Origin => ([0; 3], KIND_COPY),
        };
        for k in 0..3 {
            let r = q[x][k] as i64 - predicted[k];
            let at = b.offset();
            let r = models.code(b, kind, k, r).ok_or_else(|| Fail {
                at,
                message: format!("vertex {x}: a residual longer than the grid's bits"),
            })?;
            let value = predicted[k] + r;
            if !(0..=max as i64).contains(&value) {
                return Err(Fail {
                    at,
                    message: format!("vertex {x}: level {value} outside the grid 0..={max}"),
                });
            }
            q[x][k] = value as u32;
        }
        if b.overrun() {
            return Err(Fail {
                at: b.offset(),
                message: format!("the stream ends before vertex {x}"),
            });
        }
    }
    Ok(())
}

/// Codes f32 positions `p` exactly with `plan`; the decoder fills `p`. `select` as for
/// [`code_grid`].
fn code_f32<B: Bits>(
    b: &mut B,
    plan: &Plan,
    (v, o): (&[u32], &[u32]),
    p: &mut [[f32; 3]],
    select: bool,
) -> std::result::Result<(), Fail> {
    let mut models = Residuals::new(32);
    let mut values: Vec<[f64; 3]> = Vec::new();
    let mut scratch: Vec<f64> = Vec::new();
    let mut found = Vec::new();
    for (i, &x) in plan.order().iter().enumerate() {
        let x = x as usize;
        let predictor = plan.predictor(i, &mut found);
        let (predicted, kind): ([f32; 3], usize) = match predictor {
            Predictor::Parallelograms(corners) => {
                values.clear();
                values.extend(corners.iter().map(|&c| {
                    let [a, bb, oo] = parallelogram(v, o, c);
                    [0, 1, 2].map(|k| (p[a][k] as f64 + p[bb][k] as f64) - p[oo][k] as f64)
                }));
                let mut spread = 0u64;
                let middle = [0, 1, 2].map(|k| {
                    scratch.clear();
                    scratch.extend(values.iter().map(|p| p[k]));
                    let (lo, hi) = scratch
                        .iter()
                        .fold((f64::MAX, f64::MIN), |(lo, hi), &x| (lo.min(x), hi.max(x)));
                    spread += (ordered(hi as f32) - ordered(lo as f32)) as u64;
                    middle_float(&mut scratch) as f32
                });
                let n = values.len();
                let wanted = if select && n > 1 {
                    let actual = p[x].map(ordered);
                    choose(
                        |j| {
                            let e = j.map_or(middle, |j| values[j].map(|x| x as f32));
                            (0..3)
                                .map(|k| bits(actual[k] as i64 - ordered(e[k]) as i64))
                                .sum()
                        },
                        n,
                    )
                } else {
                    0
                };
                match if n > 1 {
                    models.choice(b, n, wanted)
                } else {
                    0
                } {
                    0 => (middle, kind(n, spread)),
                    j => (values[j - 1].map(|x| x as f32), KIND_CHOSEN),
                }
            }
            Predictor::Copy(u) => (p[u as usize], KIND_COPY),
            Predictor::Origin => ([0.0; 3], KIND_COPY),
        };
        for k in 0..3 {
            let base = ordered(predicted[k]) as i64;
            let r = ordered(p[x][k]) as i64 - base;
            let at = b.offset();
            let r = models.code(b, kind, k, r).ok_or_else(|| Fail {
                at,
                message: format!("vertex {x}: a residual longer than 32 bits"),
            })?;
            let value = base + r;
            let x_k = u32::try_from(value)
                .ok()
                .map(from_ordered)
                .filter(|f| f.is_finite())
                .ok_or_else(|| Fail {
                    at,
                    message: format!("vertex {x}: the residual gives no finite f32"),
                })?;
            p[x][k] = x_k;
        }
        if b.overrun() {
            return Err(Fail {
                at: b.offset(),
                message: format!("the stream ends before vertex {x}"),
            });
        }
    }
    Ok(())
}

fn internal(f: Fail) -> Error {
    Error::Internal(format!("position encoder: {}", f.message))
}

/// The `GEOM` payload of encoding 2: positions (container order) on `grid`, predicted with
/// the Edgebreaker decoder's corner table; with `choices`, coded with and without choices
/// among parallelograms, the shorter kept.
pub(crate) fn encode_grid(
    table: &CornerTable,
    positions: &[[f32; 3]],
    grid: Grid,
    choices: bool,
) -> Result<Vec<u8>> {
    let plan = Plan::of(table);
    let mut q: Vec<[u32; 3]> = positions.iter().map(|&p| grid.quantize(p)).collect();
    let tables = (table.v_table(), table.o_table());
    let mut coded = |select| {
        let mut enc = Encoder::new();
        code_grid(&mut enc, &plan, tables, &mut q, grid.max_level(), select)
            .map(|()| enc.finish())
            .map_err(internal)
    };
    let stream = best_stream(&mut coded, choices)?;
    let mut out = Vec::new();
    out.extend_from_slice(&PositionEncoding::PREDICTED_GRID.0.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    write_grid(&mut out, grid);
    out.extend(stream);
    Ok(out)
}

/// The `GEOM` payload of encoding 3: f32 positions (container order), exactly; `choices`
/// as for [`encode_grid`].
pub(crate) fn encode_f32(
    table: &CornerTable,
    positions: &[[f32; 3]],
    choices: bool,
) -> Result<Vec<u8>> {
    let plan = Plan::of(table);
    let mut p = positions.to_vec();
    let tables = (table.v_table(), table.o_table());
    let mut coded = |select| {
        let mut enc = Encoder::new();
        code_f32(&mut enc, &plan, tables, &mut p, select)
            .map(|()| enc.finish())
            .map_err(internal)
    };
    let stream = best_stream(&mut coded, choices)?;
    let mut out = Vec::new();
    out.extend_from_slice(&PositionEncoding::PREDICTED_F32.0.to_le_bytes());
    out.extend_from_slice(&0u32.to_le_bytes());
    out.extend(stream);
    Ok(out)
}

/// The stream coded without choices, or, with `choices`, the shorter of it and the one
/// coded with them (that one on a tie).
fn best_stream(coded: &mut impl FnMut(bool) -> Result<Vec<u8>>, choices: bool) -> Result<Vec<u8>> {
    let plain = coded(false)?;
    if !choices {
        return Ok(plain);
    }
    let chosen = coded(true)?;
    Ok(if plain.len() < chosen.len() {
        plain
    } else {
        chosen
    })
}

/// Decodes a `GEOM` section of encoding 2 or 3 with the Edgebreaker connectivity's table
/// ([V44]). Allocates in proportion to the vertices and corners the table holds.
pub(crate) fn decode_section<'a>(
    f: &Fields,
    encoding: PositionEncoding,
    table: &CornerTable,
) -> Result<Positions<'a>> {
    let rule = Rule(44);
    let m = table.c_table().len();
    let plan = Plan::of(table);
    let tables = (table.v_table(), table.o_table());
    let (grid, stream_at) = if encoding == PositionEncoding::PREDICTED_GRID {
        let grid = crate::read::positions::grid(f, Rule(13))?;
        (Some(grid), geom::HEADER_LEN + geom::GRID_LEN)
    } else {
        (None, geom::HEADER_LEN)
    };
    f.expect_at_least(stream_at, rule)?;
    let stream = &f.bytes()[stream_at..];
    let mut dec = Decoder::new(stream, f.section.offset as usize + stream_at);
    let fail = |e: Fail| {
        let at = (e.at as usize).saturating_sub(f.section.offset as usize);
        f.err(at.min(f.len()), rule, e.message)
    };
    let positions = match grid {
        Some(grid) => {
            let mut q = vec![[0u32; 3]; m];
            code_grid(&mut dec, &plan, tables, &mut q, grid.max_level(), false).map_err(fail)?;
            q.iter().map(|&q| grid.dequantize(q)).collect()
        }
        None => {
            let mut p = vec![[0f32; 3]; m];
            code_f32(&mut dec, &plan, tables, &mut p, false).map_err(fail)?;
            p
        }
    };
    Ok(Positions::Decoded { grid, positions })
}
