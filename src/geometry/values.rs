//! Predicted attribute values (`ATTR` value encoding 2, GEOMETRY.md §7): the quantized
//! integers of an Edgebreaker container's attribute, coded in the order the triangles first
//! use them, each predicted from what is already known (the positions, and the values coded
//! before it), the residuals through the positions' coder (§4) with kinds of their own.
//!
//! Normals are predicted from the surface alone: the sum of the normals of the triangles
//! whose corners use the value, so that a flat-shaded face's value is its face normal and a
//! smooth vertex's the mean around it. Other values take the parallelogram across the
//! triangle's known edge when no seam cuts it, else the mean of the known corners. (A
//! projection of the triangle's shape into the texture, as Draco predicts texture
//! coordinates, was measured and did worse than the parallelogram and mean on every corpus
//! mesh, so it is not used.)

use super::residual::Residuals;
use crate::corner_table::CornerTable;
use crate::edgebreaker::coder::{Bits, Decoder, Encoder};
use crate::format::quantized::{octahedral_encode_f64, Quantizer};
use crate::ops::CornerOps;
use crate::{Corner, Triangle};

/// Kinds of predictions (GEOMETRY.md §7.3): they select the residual models.
const KIND_PREVIOUS: usize = 0;
const KIND_ONE: usize = 1;
const KIND_MEAN: usize = 2;
const KIND_PARALLELOGRAM: usize = 3;
const KIND_SURFACE: usize = 4;

/// No corner: a value no triangle uses.
const UNUSED: u32 = u32::MAX;

/// What the predictor needs of the container, every slot holding a triangle.
pub(crate) struct Uses<'a> {
    /// The container vertex at each corner of every triangle slot, in slot order.
    pub vertices: &'a [[u32; 3]],
    /// The value index at each of those corners (below `count`).
    pub values: &'a [[u32; 3]],
    /// The corner across from each corner (`3·slot + k`, or `u32::MAX` on a border and in
    /// kept triangles): Edgebreaker's corner table.
    pub opposites: &'a [[u32; 3]],
    /// The container's positions as a reader decodes them.
    pub positions: &'a [[f32; 3]],
    /// Values of the attribute, `V + E`.
    pub count: u32,
}

/// The container vertex and the opposite corner of every corner of every slot.
pub(crate) type SlotCorners = (Vec<[u32; 3]>, Vec<[u32; 3]>);

/// The container vertices and the opposite corners (`3·slot + k`) of every slot: the
/// triangles of Edgebreaker's corner table, corner `k` of triangle `t` being `t.c`, `t.c.n`,
/// `t.c.p` (FORMAT.md §4), then the kept triangles, with no opposites.
pub(crate) fn slots(table: &CornerTable, kept: &[[u32; 3]]) -> SlotCorners {
    let n = table.triangle_id_bound();
    let corners = |t: u32| {
        let c = table.triangle_corner(Triangle(t));
        [c, table.next(c), table.prev(c)]
    };
    let slot_corner = |c: Corner| {
        let t = table.triangle(c);
        let k = corners(t.0).iter().position(|&x| x == c).unwrap_or(0);
        3 * t.0 + k as u32
    };
    let mut vertices = Vec::with_capacity(n as usize + kept.len());
    let mut opposites = Vec::with_capacity(n as usize + kept.len());
    for t in 0..n {
        let cs = corners(t);
        vertices.push(cs.map(|c| table.vertex(c).0));
        opposites.push(cs.map(|c| table.opposite(c).map_or(UNUSED, slot_corner)));
    }
    vertices.extend_from_slice(kept);
    opposites.resize(vertices.len(), [UNUSED; 3]);
    (vertices, opposites)
}

/// The coding order (GEOMETRY.md §7.2): each used value with the first corner that uses it
/// (`3·slot + k`), then the unused ones in index order.
fn order(uses: &Uses) -> Vec<(u32, u32)> {
    let mut seen = vec![false; uses.count as usize];
    let mut out = Vec::with_capacity(uses.count as usize);
    for (t, values) in uses.values.iter().enumerate() {
        for (k, &x) in values.iter().enumerate() {
            if !std::mem::replace(&mut seen[x as usize], true) {
                out.push((x, 3 * t as u32 + k as u32));
            }
        }
    }
    out.extend(
        (0..uses.count)
            .filter(|&x| !seen[x as usize])
            .map(|x| (x, UNUSED)),
    );
    out
}

fn position(uses: &Uses, v: u32) -> [f64; 3] {
    uses.positions[v as usize].map(f64::from)
}

fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// Per value, the sum of the normals `(p1 − p0) × (p2 − p0)` of the triangles at its
/// corners, in slot then corner order (GEOMETRY.md §7.3).
fn surface_normals(uses: &Uses) -> Vec<[f64; 3]> {
    let mut sums = vec![[0.0f64; 3]; uses.count as usize];
    for (tri, values) in uses.vertices.iter().zip(uses.values) {
        let p0 = position(uses, tri[0]);
        let a = sub(position(uses, tri[1]), p0);
        let b = sub(position(uses, tri[2]), p0);
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        for &x in values {
            let s = &mut sums[x as usize];
            for k in 0..3 {
                s[k] += n[k];
            }
        }
    }
    sums
}

/// Codes (encoder) or decodes (decoder) the `c'` integers of every value of `levels` (value
/// `x` at `levels[c'·x ..]`). The decoder's `levels` start at 0 and are filled; `Err` says
/// where and which value failed, and why.
fn code<B: Bits>(
    b: &mut B,
    uses: &Uses,
    (q, surface): (&Quantizer, bool),
    levels: &mut [u32],
) -> Result<(), (u64, String)> {
    let n = q.fields() as usize;
    let max = q.max_level();
    let mut models = Residuals::with_axes(u32::from(q.bits()), n);
    let octahedral = matches!(q, Quantizer::Octahedral { .. });
    let normals = (octahedral && surface).then(|| surface_normals(uses));
    let mut known = vec![false; uses.count as usize];
    let mut previous = [0u32; 4];
    for (x, corner) in order(uses) {
        let at = |levels: &[u32], y: u32| -> [u32; 4] {
            let mut out = [0; 4];
            out[..n].copy_from_slice(&levels[n * y as usize..n * y as usize + n]);
            out
        };
        let (pred, kind) = predict(uses, q, normals.as_deref(), (x, corner), |y| {
            known[y as usize].then(|| at(levels, y))
        })
        .unwrap_or((previous, KIND_PREVIOUS));
        let offset = b.offset();
        for k in 0..n {
            let actual = i64::from(levels[n * x as usize + k]);
            let r = models
                .code(b, kind, k, actual - i64::from(pred[k]))
                .ok_or_else(|| {
                    let bits = q.bits();
                    (
                        offset,
                        format!("value {x}: a residual longer than {bits} bits"),
                    )
                })?;
            let got = i64::from(pred[k]) + r;
            if !(0..=i64::from(max)).contains(&got) {
                return Err((
                    offset,
                    format!("value {x}: integer {got} outside 0 ..= {max}"),
                ));
            }
            levels[n * x as usize + k] = got as u32;
        }
        if b.overrun() {
            return Err((b.offset(), format!("the stream ends before value {x}")));
        }
        known[x as usize] = true;
        previous = at(levels, x);
    }
    Ok(())
}

/// The prediction of value `x`, first used at `corner`, and its kind (GEOMETRY.md §7.3);
/// `None` when nothing about it is known (the previous value is then the prediction).
/// `normals`: the surface's sums, for octahedral normals; `known(y)` gives the integers of a
/// value already coded.
fn predict(
    uses: &Uses,
    q: &Quantizer,
    normals: Option<&[[f64; 3]]>,
    (x, corner): (u32, u32),
    known: impl Fn(u32) -> Option<[u32; 4]>,
) -> Option<([u32; 4], usize)> {
    if corner == UNUSED {
        return None;
    }
    if let Some(sums) = normals {
        let s = sums[x as usize];
        if s != [0.0; 3] {
            let [u, v] = octahedral_encode_f64(s, q.bits());
            return Some(([u, v, 0, 0], KIND_SURFACE));
        }
    }
    let (t, k) = ((corner / 3) as usize, (corner % 3) as usize);
    let [ka, kb] = [(k + 1) % 3, (k + 2) % 3];
    let values = uses.values[t];
    let (a, bv) = (known(values[ka]), known(values[kb]));
    if let (Some(a), Some(bv), Some(o)) = (a, bv, across(uses, t, k).and_then(&known)) {
        let mut p = [0u32; 4];
        for i in 0..q.fields() as usize {
            let x = i64::from(a[i]) + i64::from(bv[i]) - i64::from(o[i]);
            p[i] = x.clamp(0, i64::from(q.max_level())) as u32;
        }
        return Some((p, KIND_PARALLELOGRAM));
    }
    match (a, bv) {
        (Some(a), Some(bv)) => {
            let mut mean = [0u32; 4];
            for i in 0..q.fields() as usize {
                mean[i] = ((u64::from(a[i]) + u64::from(bv[i])) / 2) as u32;
            }
            Some((mean, KIND_MEAN))
        }
        (Some(one), None) | (None, Some(one)) => Some((one, KIND_ONE)),
        (None, None) => None,
    }
}

/// The value across the edge opposite corner `k` of slot `t`, when the triangle there has
/// the same values as `t` at the edge's two vertices (no seam on the edge).
fn across(uses: &Uses, t: usize, k: usize) -> Option<u32> {
    let o = uses.opposites[t][k];
    if o == UNUSED {
        return None;
    }
    let (u, j) = ((o / 3) as usize, (o % 3) as usize);
    let (tri, other) = (uses.vertices[t], uses.vertices[u]);
    for m in [(k + 1) % 3, (k + 2) % 3] {
        let at = (0..3).find(|&i| i != j && other[i] == tri[m])?;
        if uses.values[u][at] != uses.values[t][m] {
            return None;
        }
    }
    Some(uses.values[u][j])
}

/// The stream of `levels` (`c'` integers per value, `V + E` values); octahedral normals
/// predicted from the surface first when `surface` (GEOMETRY.md §7.3, rule 2).
pub(crate) fn encode(uses: &Uses, q: &Quantizer, surface: bool, levels: &[u32]) -> Vec<u8> {
    let mut e = Encoder::new();
    let mut copy = levels.to_vec();
    code(&mut e, uses, (q, surface), &mut copy).expect("the encoder's own integers are in range");
    e.finish()
}

/// The integers coded in `stream` (which starts at byte `base` of the file, for errors):
/// `c'` per value; `Err((offset, message))` when the stream breaks [V47].
pub(crate) fn decode(
    uses: &Uses,
    (q, surface): (&Quantizer, bool),
    stream: &[u8],
    base: usize,
) -> Result<Vec<u32>, (u64, String)> {
    let mut levels = vec![0u32; uses.count as usize * q.fields() as usize];
    let mut d = Decoder::new(stream, base);
    code(&mut d, uses, (q, surface), &mut levels)?;
    Ok(levels)
}
