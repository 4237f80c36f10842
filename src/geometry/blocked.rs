//! Random-access position blocks (GEOM encodings 4 and 5, FORMAT.md §3.3), read in place.
//!
//! Container ids of the LR kinds run along the rings, so a vertex lies about one edge from
//! the vertices just before and after it. A block of `2^L` vertices stores its first vertex
//! whole (the *anchor*) and every other one as a residual from the midpoint of two vertices
//! of the block already known, coarse to fine: vertex 16 of a 32-vertex block from the
//! anchors of this block and the next, vertex 8 from vertices 0 and 16, …, every odd vertex
//! from its two neighbours. A vertex is found by halving its block's interval `L` times, one
//! residual per halving: constant time, nothing decoded but its path. Each level of each
//! block has a width per axis, the bits its largest residual needs, so that long jumps cost
//! only where they occur. On the shared meshes at 16 bits this takes 0.79 of the raw size
//! (median), where a block minimum with one width per axis takes 0.91.

mod writer;

#[cfg(test)]
mod tests;

pub(crate) use writer::encode;

use super::{float, Grid};
use crate::error::{Result, Rule};
use crate::format::PositionEncoding;
use crate::read::fields::Fields;

/// The largest `L`: blocks of at most 256 vertices.
pub const MAX_LEVELS: u32 = 8;
/// The largest width of the record field that holds a block's data start.
pub const MAX_START_BITS: u32 = 56;
/// Bytes from the end of the grid (or of the common header) to the directory: `L`, `S`.
const SHAPE_LEN: usize = 8;

/// The fixed parameters of a section: what its header says and what its encoding implies.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Shape {
    /// `L`: a block holds `2^L` vertices.
    levels: u32,
    /// `S`: bits of the data start of each record.
    start_bits: u32,
    /// Bits of each anchor coordinate: the grid's bits, or 32 for f32.
    anchor_bits: u32,
    /// Bits of each width field: 5 on a grid, 6 for f32.
    width_bits: u32,
    /// The largest valid width: the grid's bits plus 1 (a zigzag of `-max..=max`), or 33.
    max_width: u32,
}

impl Shape {
    fn new(grid: Option<Grid>, levels: u32, start_bits: u32) -> Shape {
        let (anchor_bits, width_bits, max_width) = match grid {
            Some(g) => (g.bits as u32, 5, g.bits as u32 + 1),
            None => (32, 6, 33),
        };
        Shape {
            levels,
            start_bits,
            anchor_bits,
            width_bits,
            max_width,
        }
    }

    /// Vertices per block.
    fn block(&self) -> u64 {
        1 << self.levels
    }

    /// Bits of one record: the data start, the anchor, `3L` widths.
    fn record_bits(&self) -> u64 {
        (self.start_bits + 3 * self.anchor_bits + 3 * self.levels * self.width_bits) as u64
    }

    /// Records of `m` vertices: one per block and the end record, none without vertices.
    fn records(&self, m: u64) -> u64 {
        match m {
            0 => 0,
            _ => m.div_ceil(self.block()) + 1,
        }
    }
}

/// Positions in random-access blocks, read in place.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockedView<'a> {
    grid: Option<Grid>,
    shape: Shape,
    /// The records, bit-packed.
    dir: &'a [u8],
    /// The residuals of every block, bit-packed.
    data: &'a [u8],
}

impl<'a> BlockedView<'a> {
    /// Validates the section ([V45], the grid by [V13]) for `m` vertices; the decoded values
    /// (a verifying reader's clause of V45, FORMAT.md §5.1) only with `verify`.
    pub(crate) fn parse(f: &Fields<'a>, m: u64, verify: bool) -> Result<BlockedView<'a>> {
        let rule = Rule(45);
        let (grid, at) = match PositionEncoding(f.u32(0, rule)?) {
            PositionEncoding::BLOCKED => (Some(crate::read::positions::grid(f, Rule(13))?), 28),
            _ => (None, 8),
        };
        let levels = f.u32(at, rule)?;
        if !(1..=MAX_LEVELS).contains(&levels) {
            return Err(f.err(at, rule, format!("{levels} levels, not 1 to {MAX_LEVELS}")));
        }
        let start_bits = f.u32(at + 4, rule)?;
        if start_bits > MAX_START_BITS {
            return Err(f.err(
                at + 4,
                rule,
                format!("data starts of {start_bits} bits, more than {MAX_START_BITS}"),
            ));
        }
        let shape = Shape::new(grid, levels, start_bits);
        let dir_at = at + SHAPE_LEN;
        let records = shape.records(m);
        let dir_bits = records.checked_mul(shape.record_bits());
        let dir_len = dir_bits.map(|b| b.div_ceil(8));
        let room = (f.len() - dir_at) as u64;
        let Some(dir_len) = dir_len.filter(|&l| l <= room) else {
            return Err(f.err(
                0,
                rule,
                format!(
                    "{} bytes, too short for a directory of {records} records",
                    f.len()
                ),
            ));
        };
        let (dir, data) = f.bytes()[dir_at..].split_at(dir_len as usize);
        let view = BlockedView {
            grid,
            shape,
            dir,
            data,
        };
        let total = records.checked_sub(1).map_or(0, |last| view.start(last));
        f.expect_len(Some(dir_at as u64 + dir_len + total.div_ceil(8)), rule)?;
        view.check_directory(f, dir_at, records)?;
        if verify {
            view.check_blocks(f, dir_at + dir.len(), m)?;
        }
        check_padding(f, dir_at, dir, records * shape.record_bits())?;
        check_padding(f, dir_at + dir.len(), data, total)?;
        Ok(view)
    }

    /// The position of container vertex `i`.
    #[inline]
    pub fn position(&self, i: usize) -> [f32; 3] {
        let q = self.levels_of(i as u64);
        match self.grid {
            Some(g) => [
                g.dequantize_axis(0, q[0] as u32),
                g.dequantize_axis(1, q[1] as u32),
                g.dequantize_axis(2, q[2] as u32),
            ],
            None => [
                float::from_ordered(q[0] as u32),
                float::from_ordered(q[1] as u32),
                float::from_ordered(q[2] as u32),
            ],
        }
    }

    /// The grid, for quantized positions.
    pub fn grid(&self) -> Option<Grid> {
        self.grid
    }

    /// The stored integers of vertex `i` (grid levels or ordered integers): its block's
    /// interval halved until `i` is a midpoint, one residual per halving. The path follows
    /// the bits of `i`'s place in the block, so nothing depends on a comparison.
    #[inline]
    fn levels_of(&self, i: u64) -> [i64; 3] {
        let levels = self.shape.levels;
        let j = i >> levels;
        let t = i & (self.shape.block() - 1);
        let mut a = self.anchor(j);
        if t == 0 {
            return a;
        }
        let mut b = self.anchor(j + 1);
        let mut pos = self.start(j);
        let mut v = a;
        // `t` is a midpoint of level `L - 1 - tz(t)`: visit levels 0 to that one.
        for l in 0..levels - t.trailing_zeros() {
            let w = self.widths(j, l);
            let triple = (w[0] + w[1] + w[2]) as u64;
            v = midpoint(a, b, self.residuals(pos + (t >> (levels - l)) * triple, w));
            // The right half when the bit of this level is set.
            let right = (t >> (levels - 1 - l)) & 1 != 0;
            (a, b) = if right { (v, b) } else { (a, v) };
            pos += triple << l;
        }
        v
    }

    /// Bit offset of record `j` in the directory.
    #[inline]
    fn record(&self, j: u64) -> u64 {
        j.wrapping_mul(self.shape.record_bits())
    }

    /// The data start of record `j`.
    #[inline]
    fn start(&self, j: u64) -> u64 {
        field(self.dir, self.record(j), self.shape.start_bits)
    }

    /// The anchor of record `j`: the first vertex of block `j`.
    #[inline]
    fn anchor(&self, j: u64) -> [i64; 3] {
        let s = &self.shape;
        let at = self.record(j) + s.start_bits as u64;
        let u = unpack(self.dir, at, [s.anchor_bits; 3]);
        [u[0] as i64, u[1] as i64, u[2] as i64]
    }

    /// The widths of level `l` of record `j`, per axis.
    #[inline]
    fn widths(&self, j: u64, l: u32) -> [u32; 3] {
        let s = &self.shape;
        let at = self.record(j) + (s.start_bits + 3 * s.anchor_bits + 3 * l * s.width_bits) as u64;
        let w = unpack(self.dir, at, [s.width_bits; 3]);
        [w[0] as u32, w[1] as u32, w[2] as u32]
    }

    /// The residuals of the triple at bit `at` of the data, of widths `w`.
    #[inline]
    fn residuals(&self, at: u64, w: [u32; 3]) -> [i64; 3] {
        let z = unpack(self.data, at, w);
        [unzigzag(z[0]), unzigzag(z[1]), unzigzag(z[2])]
    }

    /// Whether `v` is a valid stored integer: a grid level, or the ordered integer of a
    /// finite f32.
    fn in_range(&self, v: i64) -> bool {
        match self.grid {
            Some(g) => (0..=g.max_level() as i64).contains(&v),
            None => (0..=u32::MAX as i64).contains(&v) && float::from_ordered(v as u32).is_finite(),
        }
    }

    /// [V45] on the records: the data starts tile the data, widths at most the maximum (0
    /// in the end record), f32 anchors finite (grid anchors cannot leave the grid). Each
    /// record is read from one window of its bytes, its fields at offsets fixed by the
    /// shape, and checked without branching on them; the field at fault is looked for only
    /// when one fails.
    fn check_directory(&self, f: &Fields, dir_at: usize, records: u64) -> Result<()> {
        // Width fields of 5 bits on a grid, 6 for f32; the writer's levels unrolled.
        let checked = match (self.shape.width_bits, self.shape.levels) {
            (5, 4) => self.check_records::<5, 4>(records),
            (5, 5) => self.check_records::<5, 5>(records),
            (5, 6) => self.check_records::<5, 6>(records),
            (5, _) => self.check_records::<5, 0>(records),
            (_, 4) => self.check_records::<6, 4>(records),
            (_, 5) => self.check_records::<6, 5>(records),
            (_, 6) => self.check_records::<6, 6>(records),
            _ => self.check_records::<6, 0>(records),
        };
        checked.map_err(|j| self.directory_fault(f, dir_at, j, records))
    }

    /// [`check_directory`](Self::check_directory)'s loop for width fields of `WB` bits
    /// (5: a grid, whose anchors cannot leave it; 6: f32, 32-bit anchors that must be
    /// finite) and `LEVELS` levels (0: the shape's): the first record that fails.
    #[inline(always)]
    fn check_records<const WB: u32, const LEVELS: u32>(&self, records: u64) -> Result<(), u64> {
        let s = &self.shape;
        let levels = if LEVELS == 0 { s.levels } else { LEVELS };
        let anchor_bits = if WB == 6 { 32 } else { s.anchor_bits };
        let widths_at = s.start_bits + 3 * anchor_bits;
        let mut next = 0;
        let mut tail = [0u8; WINDOW_LEN];
        for j in 0..records {
            let at = self.record(j);
            let window = RecordWindow::new(self.dir, at, &mut tail);
            let bit = (at % 8) as u32;
            let mut ok = window.bits(bit, s.start_bits) == next;
            if WB == 6 {
                // Spelled out: through an array's `map` and `all` the closures were not
                // inlined (a fifth of the check's time).
                let anchor = |k: u32| window.bits(bit + s.start_bits + 32 * k, 32) as u32;
                ok &= float::ordered_is_finite(anchor(0))
                    & float::ordered_is_finite(anchor(1))
                    & float::ordered_is_finite(anchor(2));
            }
            let limit = if j + 1 == records { 0 } else { s.max_width };
            let (fit, bits) = window.widths::<WB>(bit + widths_at, levels, limit);
            ok &= fit;
            next += bits;
            if !ok {
                return Err(j);
            }
        }
        Ok(())
    }

    /// The error for record `j`, which breaks [V45].
    #[cold]
    fn directory_fault(&self, f: &Fields, dir_at: usize, j: u64, records: u64) -> crate::Error {
        let (s, rule) = (&self.shape, Rule(45));
        let byte = |bit: u64| dir_at + (bit / 8) as usize;
        let at = self.record(j);
        let next: u64 = (0..j)
            .flat_map(|i| (0..s.levels).map(move |l| (i, l)))
            .map(|(i, l)| {
                let w = self.widths(i, l);
                ((w[0] + w[1] + w[2]) as u64) << l
            })
            .sum();
        let start = self.start(j);
        if start != next {
            let message = format!("block {j} starts at data bit {start}, not {next}");
            return f.err(byte(at), rule, message);
        }
        let anchor = self.anchor(j);
        if let Some(k) = (0..3).find(|&k| !self.in_range(anchor[k])) {
            let at = at + (s.start_bits + k as u32 * s.anchor_bits) as u64;
            let message = format!("anchor of block {j}, axis {k}: no finite f32");
            return f.err(byte(at), rule, message);
        }
        let end = j + 1 == records;
        for l in 0..s.levels {
            let w = self.widths(j, l);
            if let Some(k) = (0..3).find(|&k| w[k] > s.max_width || (end && w[k] > 0)) {
                let at = at + (s.start_bits + 3 * s.anchor_bits) as u64;
                let at = at + ((3 * l + k as u32) * s.width_bits) as u64;
                let message = match end {
                    true => format!("the end record has width {} (level {l})", w[k]),
                    false => format!(
                        "block {j}, level {l}, axis {k}: width {}, more than {}",
                        w[k], s.max_width
                    ),
                };
                return f.err(byte(at), rule, message);
            }
        }
        f.err(byte(at), rule, format!("block {j}: malformed record"))
    }

    /// [V45] on the residuals: every vertex decodes in range, and the positions of the last
    /// block past the vertex count have residual 0.
    fn check_blocks(&self, f: &Fields, data_at: usize, m: u64) -> Result<()> {
        let (s, rule) = (&self.shape, Rule(45));
        let block = s.block();
        let mut values = [[0i64; 3]; (1 << MAX_LEVELS) + 1];
        for j in 0..m.div_ceil(block) {
            values[0] = self.anchor(j);
            values[block as usize] = self.anchor(j + 1);
            let mut pos = self.start(j);
            for l in 0..s.levels {
                let w = self.widths(j, l);
                let triple = (w[0] + w[1] + w[2]) as u64;
                let h = block >> (l + 1);
                for idx in 0..1u64 << l {
                    let p = ((2 * idx + 1) * h) as usize;
                    let at = pos + idx * triple;
                    let r = self.residuals(at, w);
                    let v = midpoint(values[p - h as usize], values[p + h as usize], r);
                    let vertex = j * block + p as u64;
                    let at = data_at + (at / 8) as usize;
                    if vertex >= m && r != [0; 3] {
                        let message =
                            format!("padding position {p} of the last block has a residual");
                        return Err(f.err(at, rule, message));
                    }
                    if let Some(k) = (0..3).find(|&k| vertex < m && !self.in_range(v[k])) {
                        let message = match self.grid {
                            Some(g) => format!(
                                "vertex {vertex}, axis {k}: level {} outside the grid 0..={}",
                                v[k],
                                g.max_level()
                            ),
                            None => format!(
                                "vertex {vertex}, axis {k}: {} is the ordered integer of no finite f32",
                                v[k]
                            ),
                        };
                        return Err(f.err(at, rule, message));
                    }
                    values[p] = v;
                }
                pos += triple << l;
            }
        }
        Ok(())
    }
}

/// Bytes of a [`RecordWindow`]: enough for any shape (a start of up to 56 bits, three 32-bit
/// anchors, 24 widths of 6 bits, 7 bits of offset in the first byte) and an 8-byte read at
/// the last field.
const WINDOW_LEN: usize = 48;

/// Bytes of a directory record from its first byte; bytes past the directory read as 0. The
/// directory's own bytes where it has [`WINDOW_LEN`] of them (a copy to the stack cost a
/// stalled load per field, eight-byte reads straddling the copy's stores), else a copy of
/// its tail padded with 0.
struct RecordWindow<'a>(&'a [u8; WINDOW_LEN]);

impl<'a> RecordWindow<'a> {
    /// The window at bit `at` of `dir`; `tail` holds it when the directory ends within it.
    #[inline(always)]
    fn new(dir: &'a [u8], at: u64, tail: &'a mut [u8; WINDOW_LEN]) -> RecordWindow<'a> {
        let byte = (at / 8) as usize;
        match dir.get(byte..byte + WINDOW_LEN) {
            Some(bytes) => RecordWindow(bytes.try_into().expect("WINDOW_LEN bytes")),
            None => {
                *tail = [0u8; WINDOW_LEN];
                let rest = dir.get(byte..).unwrap_or_default();
                tail[..rest.len()].copy_from_slice(rest);
                RecordWindow(tail)
            }
        }
    }

    /// The `levels` triples of `WB`-bit widths from bit `at`: whether every width is at most
    /// `limit`, and the bits of data they describe (a triple of level `l` stands for `2^l`
    /// residuals). Three levels are read at once, each triple a lane of `3·WB` bits: the
    /// widths of one axis in every lane by one mask, a width above `limit` found by the
    /// carry into bit `WB` of its lane when `2^WB − 1 − limit` is added (`WB` a constant,
    /// so that every shift and mask is; about a third of the instructions of a loop over
    /// the widths one by one).
    #[inline(always)]
    fn widths<const WB: u32>(&self, at: u32, levels: u32, limit: u32) -> (bool, u64) {
        let lane = 3 * WB;
        let lanes = |x: u64| x | x << lane | x << (2 * lane);
        let (axis, carry) = (lanes(mask(WB)), lanes(1 << WB));
        let raise = lanes(mask(WB).saturating_sub(limit as u64));
        let (mut over, mut bits) = (0u64, 0u64);
        let mut l = 0;
        while l < levels {
            let x = self.bits(at + lane * l, lane * (levels - l).min(3));
            let (a, b, c) = (x & axis, x >> WB & axis, x >> (2 * WB) & axis);
            over |= (a + raise) | (b + raise) | (c + raise);
            let sum = a + b + c;
            let lane_sum = |k: u32| (sum >> (k * lane)) & mask(lane);
            bits += (lane_sum(0) + (lane_sum(1) << 1) + (lane_sum(2) << 2)) << l;
            l += 3;
        }
        (over & carry == 0, bits)
    }

    /// The `width`-bit field (at most 57 bits) at bit `at` of the window: [`field`]'s read
    /// without its path for a short tail, which a window never has (through `field` the
    /// directory check took 10% more instructions).
    #[inline(always)]
    fn bits(&self, at: u32, width: u32) -> u64 {
        let byte = (at / 8) as usize;
        let word = self
            .0
            .get(byte..byte + 8)
            .and_then(|b| b.try_into().ok())
            .map_or(0, u64::from_le_bytes);
        (word >> (at % 8)) & mask(width)
    }
}

/// `⌊(a + b) / 2⌋ + r` on each axis.
#[inline]
fn midpoint(a: [i64; 3], b: [i64; 3], r: [i64; 3]) -> [i64; 3] {
    [
        ((a[0] + b[0]) >> 1) + r[0],
        ((a[1] + b[1]) >> 1) + r[1],
        ((a[2] + b[2]) >> 1) + r[2],
    ]
}

/// [V45]: the bits of `bytes` from `used` to the end are 0.
fn check_padding(f: &Fields, at: usize, bytes: &[u8], used: u64) -> Result<()> {
    let (byte, bit) = ((used / 8) as usize, used % 8);
    match bytes.get(byte) {
        Some(&last) if bit > 0 && last >> bit != 0 => Err(f.err(
            at + byte,
            Rule(45),
            "padding bits after the last field are not 0",
        )),
        _ => Ok(()),
    }
}

/// The `width`-bit field (at most 57 bits) at bit `at` of `bytes`, least significant bit
/// first; bits past the end read as 0.
#[inline(always)]
fn field(bytes: &[u8], at: u64, width: u32) -> u64 {
    let byte = usize::try_from(at / 8).unwrap_or(usize::MAX);
    let whole = byte.checked_add(8).and_then(|end| bytes.get(byte..end));
    let word = match whole.and_then(|b| <[u8; 8]>::try_from(b).ok()) {
        Some(b) => u64::from_le_bytes(b),
        None => bytes
            .get(byte..)
            .unwrap_or_default()
            .iter()
            .rev()
            .fold(0u64, |w, &x| w << 8 | x as u64),
    };
    (word >> (at % 8)) & mask(width)
}

/// Three consecutive fields of widths `w` at bit `at`: one read when they fit in one.
#[inline(always)]
fn unpack(bytes: &[u8], at: u64, w: [u32; 3]) -> [u64; 3] {
    let (y, z) = (at + w[0] as u64, at + (w[0] + w[1]) as u64);
    if w[0] + w[1] + w[2] <= 57 {
        let all = field(bytes, at, w[0] + w[1] + w[2]);
        [
            all & mask(w[0]),
            (all >> w[0]) & mask(w[1]),
            all >> (w[0] + w[1]),
        ]
    } else {
        [
            field(bytes, at, w[0]),
            field(bytes, y, w[1]),
            field(bytes, z, w[2]),
        ]
    }
}

/// The `width` low bits set (`width` below 64).
#[inline]
fn mask(width: u32) -> u64 {
    (1u64 << width) - 1
}

/// The signed value of a zigzag code: 0, -1, 1, -2, … for 0, 1, 2, 3, …
#[inline]
fn unzigzag(z: u64) -> i64 {
    (z >> 1) as i64 ^ -((z & 1) as i64)
}
