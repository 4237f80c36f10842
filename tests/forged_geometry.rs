//! Forged containers for the random-access position blocks (`GEOM` encodings 4 and 5,
//! FORMAT.md §3.3: [V45]) and the grid of encoding 4 ([V13]). How a rule is broken and what
//! the reader must report: `tests/common/forge.rs`. The payload is taken apart and put back
//! together here from the spec's layout ([`Blocked`]), never by the crate's reader.

mod common;

use common::forge::*;
use lrmesh::format::Tag;
use lrmesh::generate;
use lrmesh::geometry::Grid;
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, EncodeOptions};
use lrmesh::Mesh;

/// 216 vertices: no block size divides it, so the last block has padding positions. Moved
/// off the origin, so that its f32s share exponents and blocks beat raw f32 on them.
fn torus() -> Mesh {
    let mut mesh = generate::torus(24, 9);
    generate::jitter(&mut mesh, 0.01, &mut generate::Rng::new(3));
    for p in &mut mesh.positions {
        *p = p.map(|x| x + 5.0);
    }
    mesh
}

/// An LR container of `mesh` with blocked positions: on a grid of `bits`, or exact f32.
fn blocked(mesh: &Mesh, bits: Option<u8>) -> Vec<u8> {
    let options = EncodeOptions {
        keep_order: true,
        position_bits: bits,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    let encoding = get(&payload(&bytes, Tag::GEOM), 0);
    assert_eq!(encoding, if bits.is_some() { 4 } else { 5 });
    bytes
}

/// `MESH`'s vertex count.
fn vertices(bytes: &[u8]) -> u64 {
    get(&payload(bytes, Tag::MESH), 0) as u64
}

/// The container with its blocked payload rewritten from `edit`'s changes to it.
fn forge_blocked(bytes: &[u8], edit: impl FnOnce(&mut Blocked)) -> Vec<u8> {
    let mut b = Blocked::read(&payload(bytes, Tag::GEOM), vertices(bytes));
    edit(&mut b);
    forge(bytes, Tag::GEOM, |p| *p = b.write())
}

// ---------------------------------------------------------------------------------------
// The payload as FORMAT.md §3.3 lays it out.

/// The `width` bits at bit `at`, least significant first.
fn bits(p: &[u8], at: u64, width: u32) -> u64 {
    (0..width as u64).fold(0, |x, i| {
        let bit = at + i;
        x | (((p[(bit / 8) as usize] >> (bit % 8)) & 1) as u64) << i
    })
}

fn push_bits(out: &mut Vec<bool>, x: u64, width: u32) {
    out.extend((0..width).map(|i| (x >> i) & 1 != 0));
}

fn pack(bits: &[bool]) -> Vec<u8> {
    bits.chunks(8)
        .map(|c| c.iter().rev().fold(0u8, |b, &x| b << 1 | x as u8))
        .collect()
}

struct Blocked {
    /// Encoding, reserved and, for encoding 4, the grid.
    head: Vec<u8>,
    levels: u32,
    start_bits: u32,
    anchor_bits: u32,
    width_bits: u32,
    starts: Vec<u64>,
    anchors: Vec<[u64; 3]>,
    /// Per record, per level, per axis.
    widths: Vec<Vec<[u32; 3]>>,
    /// Per block, the zigzag triples in data order.
    residuals: Vec<Vec<[u64; 3]>>,
}

impl Blocked {
    fn read(p: &[u8], m: u64) -> Blocked {
        let grid = get(p, 0) == 4;
        let at = if grid { 28 } else { 8 };
        let (levels, start_bits) = (get(p, at), get(p, at + 4));
        let (anchor_bits, width_bits) = if grid { (get(p, 24), 5) } else { (32, 6) };
        let mut b = Blocked {
            head: p[..at].to_vec(),
            levels,
            start_bits,
            anchor_bits,
            width_bits,
            starts: vec![],
            anchors: vec![],
            widths: vec![],
            residuals: vec![],
        };
        let records = m.div_ceil(1 << levels) + 1;
        let dir = &p[b.dir_at()..];
        for j in 0..records {
            let mut at = j * b.record_bits();
            b.starts.push(bits(dir, at, start_bits));
            at += start_bits as u64;
            b.anchors
                .push([0, 1, 2].map(|k| bits(dir, at + k * anchor_bits as u64, anchor_bits)));
            at += 3 * anchor_bits as u64;
            b.widths.push(
                (0..levels as u64)
                    .map(|l| {
                        [0, 1, 2].map(|k| {
                            bits(dir, at + (3 * l + k) * width_bits as u64, width_bits) as u32
                        })
                    })
                    .collect(),
            );
        }
        let data = &p[b.data_at()..];
        for j in 0..records as usize - 1 {
            let mut at = b.starts[j];
            let mut triples = vec![];
            for (l, w) in b.widths[j].iter().enumerate() {
                for _ in 0..1u64 << l {
                    let mut triple = [0; 3];
                    for k in 0..3 {
                        triple[k] = bits(data, at, w[k]);
                        at += w[k] as u64;
                    }
                    triples.push(triple);
                }
            }
            b.residuals.push(triples);
        }
        b
    }

    fn record_bits(&self) -> u64 {
        (self.start_bits + 3 * self.anchor_bits + 3 * self.levels * self.width_bits) as u64
    }

    /// Offset of the directory in the payload.
    fn dir_at(&self) -> usize {
        self.head.len() + 8
    }

    /// Offset of the data in the payload.
    fn data_at(&self) -> usize {
        self.dir_at() + (self.starts.len() as u64 * self.record_bits()).div_ceil(8) as usize
    }

    /// Bits of block `j`'s data.
    fn block_bits(&self, j: usize) -> u64 {
        let w = &self.widths[j];
        (0..w.len())
            .map(|l| ((w[l][0] + w[l][1] + w[l][2]) as u64) << l)
            .sum()
    }

    /// The data starts that the widths imply.
    fn retile(&mut self) {
        let mut next = 0;
        for j in 0..self.starts.len() {
            self.starts[j] = next;
            if j < self.residuals.len() {
                next += self.block_bits(j);
            }
        }
    }

    /// Index in the block's data order of the triple of position `p` (not 0).
    fn triple_of(&self, p: u64) -> usize {
        let tz = p.trailing_zeros();
        let level = self.levels - 1 - tz;
        ((1u64 << level) - 1 + (p >> (tz + 1))) as usize
    }

    /// Bit in the data of the triple of position `p` of block `j`.
    fn residual_bit(&self, j: usize, p: u64) -> u64 {
        let index = self.triple_of(p);
        let level = level_of(index);
        let w = &self.widths[j];
        let before: u64 = (0..level)
            .map(|l| ((w[l][0] + w[l][1] + w[l][2]) as u64) << l)
            .sum();
        let within = (index - ((1 << level) - 1)) as u64;
        self.starts[j] + before + within * (w[level][0] + w[level][1] + w[level][2]) as u64
    }

    fn write(&self) -> Vec<u8> {
        let mut out = self.head.clone();
        out.extend_from_slice(&self.levels.to_le_bytes());
        out.extend_from_slice(&self.start_bits.to_le_bytes());
        let mut dir = vec![];
        for j in 0..self.starts.len() {
            push_bits(&mut dir, self.starts[j], self.start_bits);
            for k in 0..3 {
                push_bits(&mut dir, self.anchors[j][k], self.anchor_bits);
            }
            for w in self.widths[j].iter().flatten() {
                push_bits(&mut dir, *w as u64, self.width_bits);
            }
        }
        out.extend(pack(&dir));
        let mut data = vec![];
        for (j, triples) in self.residuals.iter().enumerate() {
            let mut index = 0;
            for (l, w) in self.widths[j].iter().enumerate() {
                for triple in &triples[index..index + (1 << l)] {
                    for k in 0..3 {
                        push_bits(&mut data, triple[k], w[k]);
                    }
                }
                index += 1 << l;
            }
        }
        out.extend(pack(&data));
        out
    }
}

/// The level of the triple at `index` in a block's data order: level `l` holds indices
/// `2^l - 1 .. 2^(l+1) - 1`.
fn level_of(index: usize) -> usize {
    (index + 1).ilog2() as usize
}

/// The zigzag code of `r`.
fn zigzag(r: i64) -> u64 {
    ((r << 1) ^ (r >> 63)) as u64
}

/// The stored integers of every position of block `j` (padding included).
fn decode_block(b: &Blocked, j: usize) -> Vec<[i64; 3]> {
    let size = 1usize << b.levels;
    let mut values = vec![[0i64; 3]; size + 1];
    values[0] = b.anchors[j].map(|x| x as i64);
    values[size] = b.anchors[j + 1].map(|x| x as i64);
    for l in 0..b.levels {
        let h = size >> (l + 1);
        for idx in 0..1usize << l {
            let p = (2 * idx + 1) * h;
            let z = b.residuals[j][b.triple_of(p as u64)];
            values[p] = [0, 1, 2].map(|k| {
                let r = (z[k] >> 1) as i64 ^ -((z[k] & 1) as i64);
                ((values[p - h][k] + values[p + h][k]) >> 1) + r
            });
        }
    }
    values
}

// ---------------------------------------------------------------------------------------
// [V45].

/// [V45] `L` is 1 to 8 and `S` at most 56.
#[test]
fn v45_levels_and_start_bits() {
    for (bits, at) in [(Some(12), 28usize), (None, 8)] {
        let bytes = blocked(&torus(), bits);
        let geom = section_at(&bytes, Tag::GEOM);
        for levels in [0, 9, u32::MAX] {
            let bad = forge(&bytes, Tag::GEOM, |p| put(p, at, levels));
            breaks(&bad, 45, "GEOM", geom + at as u64, "levels, not 1 to 8");
        }
        let bad = forge(&bytes, Tag::GEOM, |p| put(p, at + 4, 57));
        breaks(&bad, 45, "GEOM", geom + at as u64 + 4, "more than 56");
    }
}

/// [V45] The length is that of the header, the directory and the data.
#[test]
fn v45_length() {
    let bytes = blocked(&torus(), Some(12));
    let geom = section_at(&bytes, Tag::GEOM);
    let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(b.data_at() - 1));
    breaks(&bad, 45, "GEOM", geom, "too short for a directory");
    let bad = forge(&bytes, Tag::GEOM, |p| p.push(0));
    breaks(&bad, 45, "GEOM", geom, "where the counts call for");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(p.len() - 1));
    breaks(&bad, 45, "GEOM", geom, "where the counts call for");
    // A directory for more vertices than MESH has.
    let bad = forge_blocked(&bytes, |b| b.levels -= 1);
    breaks(&bad, 45, "GEOM", geom, "");
}

/// [V45] Record 0's data start is 0 and each next one follows the previous block's data.
#[test]
fn v45_data_starts_tile_the_data() {
    let bytes = blocked(&torus(), Some(12));
    let geom = section_at(&bytes, Tag::GEOM);
    let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
    for j in [0, 2] {
        let bad = forge_blocked(&bytes, |b| b.starts[j] += 1);
        let at = b.dir_at() as u64 + j as u64 * b.record_bits() / 8;
        breaks(
            &bad,
            45,
            "GEOM",
            geom + at,
            &format!("block {j} starts at data bit"),
        );
    }
}

/// [V45] Widths at most the grid's bits plus 1 (33 for f32); the end record's are 0.
#[test]
fn v45_widths() {
    for (bits, max) in [(Some(12), 13), (None, 33)] {
        let bytes = blocked(&torus(), bits);
        let geom = section_at(&bytes, Tag::GEOM);
        let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
        let width_at = |j: usize, l: u32, k: u32| {
            let bit = j as u64 * b.record_bits()
                + (b.start_bits + 3 * b.anchor_bits + (3 * l + k) * b.width_bits) as u64;
            geom + b.dir_at() as u64 + bit / 8
        };
        // Every level and axis: the reader checks several levels' widths at once.
        for l in 0..b.levels {
            let k = (l + 1) % 3;
            let bad = forge_blocked(&bytes, |b| {
                b.widths[1][l as usize][k as usize] = max + 1;
                b.retile();
            });
            breaks(
                &bad,
                45,
                "GEOM",
                width_at(1, l, k),
                &format!("more than {max}"),
            );
            let end = b.starts.len() - 1;
            let bad = forge_blocked(&bytes, |b| b.widths[end][l as usize][2 - k as usize] = 1);
            breaks(
                &bad,
                45,
                "GEOM",
                width_at(end, l, 2 - k),
                "the end record has width 1",
            );
        }
    }
}

/// [V45] An f32 anchor is the ordered integer of a finite f32.
#[test]
fn v45_f32_anchor_is_finite() {
    let bytes = blocked(&torus(), None);
    let geom = section_at(&bytes, Tag::GEOM);
    let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
    // +infinity (0x7F800000) and a NaN, as ordered integers.
    for (j, k, x) in [(0usize, 1u32, 0xFF80_0000u64), (3, 2, 0x0000_0001)] {
        let bad = forge_blocked(&bytes, |b| b.anchors[j][k as usize] = x);
        let bit = j as u64 * b.record_bits() + (b.start_bits + k * b.anchor_bits) as u64;
        let at = geom + b.dir_at() as u64 + bit / 8;
        breaks(
            &bad,
            45,
            "GEOM",
            at,
            &format!("anchor of block {j}, axis {k}"),
        );
    }
}

/// Sets the residual of position `p` of block `j` so that it decodes to `target` on axis
/// `k`, widening that level's width as needed; the starts follow.
fn set_value(b: &mut Blocked, j: usize, p: u64, k: usize, target: i64) {
    let values = decode_block(b, j);
    let h = 1u64 << p.trailing_zeros();
    let guess = (values[(p - h) as usize][k] + values[(p + h) as usize][k]) >> 1;
    let z = zigzag(target - guess);
    let index = b.triple_of(p);
    b.residuals[j][index][k] = z;
    let level = level_of(index);
    let w = &mut b.widths[j][level][k];
    *w = (*w).max(64 - z.leading_zeros());
    b.retile();
}

/// [V45] Every vertex decodes to a level on the grid.
#[test]
fn v45_vertex_outside_the_grid() {
    let bytes = blocked(&torus(), Some(12));
    let geom = section_at(&bytes, Tag::GEOM);
    let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
    let block = 1u64 << b.levels;
    for (j, p, k, target) in [(0usize, block / 2, 0usize, 4096i64), (2, 3, 2, -1)] {
        let bad = forge_blocked(&bytes, |b| set_value(b, j, p, k, target));
        let forged = Blocked::read(&payload(&bad, Tag::GEOM), vertices(&bad));
        let at = geom + forged.data_at() as u64 + forged.residual_bit(j, p) / 8;
        let vertex = j as u64 * block + p;
        let words = format!("vertex {vertex}, axis {k}: level {target} outside the grid 0..=4095");
        breaks(&bad, 45, "GEOM", at, &words);
    }
}

/// [V45] Every f32 vertex decodes to the ordered integer of a finite f32.
#[test]
fn v45_vertex_not_a_finite_f32() {
    let bytes = blocked(&torus(), None);
    let geom = section_at(&bytes, Tag::GEOM);
    let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
    let block = 1u64 << b.levels;
    // -infinity (0x00800000... as ordered: !0xFF800000), a NaN, and out of u32.
    for (j, p, target) in [
        (1usize, 1u64, 0x007F_FFFFi64),
        (0, block / 4, 0xFF80_0001),
        (2, block / 2, 1 << 32),
    ] {
        let bad = forge_blocked(&bytes, |b| set_value(b, j, p, 1, target));
        let forged = Blocked::read(&payload(&bad, Tag::GEOM), vertices(&bad));
        let at = geom + forged.data_at() as u64 + forged.residual_bit(j, p) / 8;
        let vertex = j as u64 * block + p;
        let words =
            format!("vertex {vertex}, axis 1: {target} is the ordered integer of no finite f32");
        breaks(&bad, 45, "GEOM", at, &words);
    }
}

/// [V45] Positions of the last block past the vertex count have residual 0.
#[test]
fn v45_padding_residuals_are_zero() {
    for bits in [Some(12), None] {
        let bytes = blocked(&torus(), bits);
        let geom = section_at(&bytes, Tag::GEOM);
        let m = vertices(&bytes);
        let b = Blocked::read(&payload(&bytes, Tag::GEOM), m);
        let block = 1u64 << b.levels;
        let j = b.residuals.len() - 1;
        let p = block - 1;
        assert!(j as u64 * block + p >= m, "the last block has padding");
        let bad = forge_blocked(&bytes, |b| {
            let values = decode_block(b, j);
            set_value(b, j, p, 0, values[p as usize][0] + 1);
        });
        let forged = Blocked::read(&payload(&bad, Tag::GEOM), m);
        let at = geom + forged.data_at() as u64 + forged.residual_bit(j, p) / 8;
        let words = format!("padding position {p} of the last block has a residual");
        breaks(&bad, 45, "GEOM", at, &words);
    }
}

/// [V45] The bits after the last record and after the last residual, to the byte, are 0.
#[test]
fn v45_padding_bits_are_zero() {
    let mut tested = 0;
    for bits in [Some(12), Some(11), None] {
        let bytes = blocked(&torus(), bits);
        let geom = section_at(&bytes, Tag::GEOM);
        let b = Blocked::read(&payload(&bytes, Tag::GEOM), vertices(&bytes));
        let dir_bits = b.starts.len() as u64 * b.record_bits();
        let data_bits = *b.starts.last().unwrap();
        for (at, used) in [(b.dir_at(), dir_bits), (b.data_at(), data_bits)] {
            if used % 8 == 0 {
                continue;
            }
            let byte = at + (used / 8) as usize;
            let bad = forge(&bytes, Tag::GEOM, |p| p[byte] |= 0x80);
            breaks(&bad, 45, "GEOM", geom + byte as u64, "padding bits");
            tested += 1;
        }
    }
    assert!(tested >= 2, "{tested} paddings");
}

// ---------------------------------------------------------------------------------------
// [V13] and what the tests above forge from.

/// [V13] The grid of blocked positions: finite box minimum and size, size at least 0,
/// 1 to 30 bits, reserved 0.
#[test]
fn v13_grid_of_blocked_positions() {
    grid_breaks(&blocked(&torus(), Some(12)));
}

/// The spec-side reader above agrees with the crate's: taking a payload apart and putting
/// it back gives the same bytes, and its decoded blocks are the positions the reader gives.
#[test]
fn the_spec_side_codec_agrees_with_the_reader() {
    for bits in [Some(12), Some(16), None] {
        let bytes = blocked(&torus(), bits);
        let p = payload(&bytes, Tag::GEOM);
        let b = Blocked::read(&p, vertices(&bytes));
        assert_eq!(b.write(), p);
        let file = open(&bytes, &Limits::default()).unwrap();
        let block = 1usize << b.levels;
        for j in 0..b.residuals.len() {
            let values = decode_block(&b, j);
            for (t, q) in values.iter().enumerate().take(block) {
                let v = j * block + t;
                if v as u64 >= vertices(&bytes) {
                    break;
                }
                let want = file.position(lrmesh::Vertex(v as u32));
                let got = match bits {
                    Some(bits) => {
                        let f = |at| f32::from_bits(get(&p, at));
                        let g = Grid {
                            lo: [f(8), f(12), f(16)],
                            size: f(20),
                            bits,
                        };
                        [0, 1, 2].map(|k| g.dequantize_axis(k, q[k] as u32))
                    }
                    None => q.map(|u| {
                        let u = u as u32;
                        f32::from_bits(if u >> 31 == 1 { u & 0x7FFF_FFFF } else { !u })
                    }),
                };
                assert_eq!(got.map(f32::to_bits), want.map(f32::to_bits), "vertex {v}");
            }
        }
    }
}
