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

/// What is predicted: grid levels or f32 bits. Both are coded as integers, the *images* of
/// the coordinates (a level, or the ordered integer of an f32), so that one coder serves
/// both; they differ in how a parallelogram is computed and how a value becomes an image.
trait Domain {
    /// A parallelogram's value on one axis, before it becomes an image.
    type Value: Copy;
    /// The image of coordinate `k` of vertex `x` (garbage in the decoder, which ignores it).
    fn image(&self, x: usize, k: usize) -> i64;
    /// The image the origin predicts.
    fn origin(&self) -> i64;
    /// Parallelogram `a + b − o` on axis `k`.
    fn parallelogram(&self, abo: [usize; 3], k: usize) -> Self::Value;
    /// The middle of several parallelograms' values (reorders them).
    fn middle(values: &mut [Self::Value]) -> Self::Value;
    /// The image of a value, for the spread: monotone, not clamped.
    fn spread_image(v: Self::Value) -> i64;
    /// The image a predicted value gives.
    fn base(&self, v: Self::Value) -> i64;
    /// The largest class a residual may have.
    fn max_class(&self) -> u32;
    /// What a residual above [`Domain::max_class`] is called.
    fn too_long(&self) -> &'static str;
    /// Stores image `image` as coordinate `k` of vertex `x`, or says why it is invalid.
    fn set(&mut self, x: usize, k: usize, image: i64) -> std::result::Result<(), String>;
}

/// Grid levels (encoding 2).
struct Levels<'q> {
    q: &'q mut [[u32; 3]],
    max: u32,
}

impl Domain for Levels<'_> {
    type Value = i64;
    fn image(&self, x: usize, k: usize) -> i64 {
        self.q[x][k] as i64
    }
    fn origin(&self) -> i64 {
        0
    }
    fn parallelogram(&self, [a, b, o]: [usize; 3], k: usize) -> i64 {
        self.q[a][k] as i64 + self.q[b][k] as i64 - self.q[o][k] as i64
    }
    fn middle(values: &mut [i64]) -> i64 {
        middle_level(values)
    }
    fn spread_image(v: i64) -> i64 {
        v
    }
    fn base(&self, v: i64) -> i64 {
        v.clamp(0, self.max as i64)
    }
    fn max_class(&self) -> u32 {
        32 - self.max.leading_zeros()
    }
    fn too_long(&self) -> &'static str {
        "a residual longer than the grid's bits"
    }
    fn set(&mut self, x: usize, k: usize, image: i64) -> std::result::Result<(), String> {
        let max = self.max;
        if !(0..=max as i64).contains(&image) {
            return Err(format!("level {image} outside the grid 0..={max}"));
        }
        self.q[x][k] = image as u32;
        Ok(())
    }
}

/// Exact f32 positions (encoding 3), predicted in binary64.
struct Floats<'p> {
    p: &'p mut [[f32; 3]],
}

impl Domain for Floats<'_> {
    type Value = f64;
    fn image(&self, x: usize, k: usize) -> i64 {
        ordered(self.p[x][k]) as i64
    }
    fn origin(&self) -> i64 {
        ordered(0.0) as i64
    }
    fn parallelogram(&self, [a, b, o]: [usize; 3], k: usize) -> f64 {
        (self.p[a][k] as f64 + self.p[b][k] as f64) - self.p[o][k] as f64
    }
    fn middle(values: &mut [f64]) -> f64 {
        middle_float(values)
    }
    fn spread_image(v: f64) -> i64 {
        ordered(v as f32) as i64
    }
    fn base(&self, v: f64) -> i64 {
        ordered(v as f32) as i64
    }
    fn max_class(&self) -> u32 {
        32
    }
    fn too_long(&self) -> &'static str {
        "a residual longer than 32 bits"
    }
    fn set(&mut self, x: usize, k: usize, image: i64) -> std::result::Result<(), String> {
        self.p[x][k] = u32::try_from(image)
            .ok()
            .map(from_ordered)
            .filter(|f| f.is_finite())
            .ok_or("the residual gives no finite f32")?;
        Ok(())
    }
}

/// Codes every coordinate of `d` in coding order with `plan`; the decoder fills `d`. With
/// `select`, the encoder may choose one parallelogram of several (GEOMETRY.md §3.3).
fn code<B: Bits, D: Domain>(
    b: &mut B,
    plan: &Plan,
    (v, o): (&[u32], &[u32]),
    d: &mut D,
    select: bool,
) -> std::result::Result<(), Fail> {
    let mut models = Residuals::new(d.max_class());
    let mut values: Vec<[D::Value; 3]> = Vec::new();
    let mut scratch: Vec<D::Value> = Vec::new();
    let mut found = Vec::new();
    let phase = match select {
        true => "positions, choosing parallelograms",
        false => "positions",
    };
    crate::progress::phase(phase, plan.order().len() as u64);
    for (i, &x) in plan.order().iter().enumerate() {
        crate::progress::tick(i);
        let x = x as usize;
        let (base, kind): ([i64; 3], usize) = match plan.predictor(i, &mut found) {
            Predictor::Parallelograms(corners) => {
                values.clear();
                values.extend(corners.iter().map(|&c| {
                    let abo = parallelogram(v, o, c);
                    [0, 1, 2].map(|k| d.parallelogram(abo, k))
                }));
                let mut spread = 0u64;
                let middle = [0, 1, 2].map(|k| {
                    scratch.clear();
                    scratch.extend(values.iter().map(|p| p[k]));
                    let images = scratch.iter().map(|&v| D::spread_image(v));
                    let (lo, hi) =
                        images.fold((i64::MAX, i64::MIN), |(lo, hi), x| (lo.min(x), hi.max(x)));
                    spread += (hi - lo) as u64;
                    d.base(D::middle(&mut scratch))
                });
                let n = values.len();
                let wanted = if select && n > 1 {
                    let actual = [0, 1, 2].map(|k| d.image(x, k));
                    choose(
                        |j| {
                            let p = j.map_or(middle, |j| values[j].map(|v| d.base(v)));
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
                    j => (values[j - 1].map(|v| d.base(v)), KIND_CHOSEN),
                }
            }
            Predictor::Copy(u) => ([0, 1, 2].map(|k| d.image(u as usize, k)), KIND_COPY),
            Predictor::Origin => ([d.origin(); 3], KIND_COPY),
        };
        for (k, base) in base.into_iter().enumerate() {
            let r = d.image(x, k) - base;
            let at = b.offset();
            let r = models.code(b, kind, k, r).ok_or_else(|| Fail {
                at,
                message: format!("vertex {x}: {}", d.too_long()),
            })?;
            d.set(x, k, base + r).map_err(|m| Fail {
                at,
                message: format!("vertex {x}: {m}"),
            })?;
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
        let mut levels = Levels {
            q: &mut q,
            max: grid.max_level(),
        };
        code(&mut enc, &plan, tables, &mut levels, select)
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
        code(&mut enc, &plan, tables, &mut Floats { p: &mut p }, select)
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
            let mut levels = Levels {
                q: &mut q,
                max: grid.max_level(),
            };
            code(&mut dec, &plan, tables, &mut levels, false).map_err(fail)?;
            grid.dequantize_all(&q)
        }
        None => {
            let mut p = vec![[0f32; 3]; m];
            code(&mut dec, &plan, tables, &mut Floats { p: &mut p }, false).map_err(fail)?;
            p
        }
    };
    Ok(Positions::Decoded { grid, positions })
}
