//! Coded seams (`ATTR` seam encoding 1, GEOMETRY.md §8): which value every corner of an
//! Edgebreaker container's per-corner attribute takes, as two adaptive bits per interior edge
//! (does the value change across the edge at this end?) and a bit per further value of a
//! vertex (a new extra value, or one the vertex already has), instead of the random-access
//! tables' flags, rank and `3·b` bits per flagged triangle. The corners joined across edges
//! with no change form wedges, and each wedge takes one value.

use crate::edgebreaker::coder::{code_uint, Bit, Bits, Decoder, Encoder, UintModel};

/// No corner, no value.
const NONE: u32 = u32::MAX;

/// What the seam coder knows of the container before the stream: every slot's corners.
pub(crate) struct Slots<'a> {
    /// The container vertex at each corner of every slot (GEOMETRY.md §7.1).
    pub vertices: &'a [[u32; 3]],
    /// The corner across from each corner (`3·slot + k`, or `u32::MAX`).
    pub opposites: &'a [[u32; 3]],
    /// Container vertices, `V`.
    pub vertex_count: u32,
}

/// What the encoder made of an attribute: the value index at every corner, and for each
/// value index (`V + E` of them) the caller's id of the value it holds (`u32::MAX` for a
/// vertex no corner uses).
pub(crate) struct Coded {
    pub stream: Vec<u8>,
    pub at_corners: Vec<[u32; 3]>,
    pub ids: Vec<u32>,
}

/// The value index at every corner, and the caller's id of each value index (encoder).
type Wedges = (Vec<[u32; 3]>, Vec<u32>);

/// Union-find over corners, with path halving.
fn find(parent: &mut [u32], mut c: u32) -> u32 {
    while parent[c as usize] != c {
        let p = parent[parent[c as usize] as usize];
        parent[c as usize] = p;
        c = p;
    }
    c
}

fn union(parent: &mut [u32], a: u32, b: u32) {
    let (ra, rb) = (find(parent, a), find(parent, b));
    // The smaller root wins, so that the wedges do not depend on the order of unions.
    parent[ra.max(rb) as usize] = ra.min(rb);
}

/// Codes (encoder, `ids` the caller's value id at every corner) or decodes (decoder, `ids`
/// `None`, at most `extra` new values) the seams: the value index at every corner, and the
/// id behind each value index (encoder).
fn code<B: Bits>(
    b: &mut B,
    s: &Slots,
    ids: Option<&[[u32; 3]]>,
    extra: u32,
) -> Result<Wedges, (u64, String)> {
    let corners = 3 * s.vertices.len();
    let encoding = ids.is_some();
    let ids = ids.unwrap_or(&[]);
    let id = |c: usize| ids.get(c / 3).map_or(0, |t| t[c % 3]);
    let vertex = |c: usize| s.vertices[c / 3][c % 3];
    let (mut first_end, mut second_end) = ([Bit::default(); 2], [Bit::default(); 2]);
    let mut parent: Vec<u32> = (0..corners as u32).collect();
    let mut before = 0usize;
    for c in 0..corners {
        let o = s.opposites[c / 3][c % 3] as usize;
        if o >= corners || o <= c {
            continue;
        }
        let (t, k, u, j) = (c / 3, c % 3, o / 3, o % 3);
        // c.n faces o.p across the edge, c.p faces o.n (FORMAT.md §4).
        let a = [3 * t + (k + 1) % 3, 3 * u + (j + 2) % 3];
        let z = [3 * t + (k + 2) % 3, 3 * u + (j + 1) % 3];
        let sa = b.bit(&mut first_end[before], u32::from(id(a[0]) != id(a[1])));
        let sz = b.bit(
            &mut second_end[sa as usize],
            u32::from(id(z[0]) != id(z[1])),
        );
        if sa == 0 {
            union(&mut parent, a[0] as u32, a[1] as u32);
        }
        if sz == 0 {
            union(&mut parent, z[0] as u32, z[1] as u32);
        }
        before = (sa | sz) as usize;
    }
    if b.overrun() {
        return Err((b.offset(), "the stream ends within the seam bits".into()));
    }
    let v_count = s.vertex_count as usize;
    let (mut repeat, mut which) = (Bit::default(), UintModel::default());
    let mut value_of_root = vec![NONE; corners];
    let mut at_corners = vec![[0u32; 3]; s.vertices.len()];
    let mut ids_out = if encoding {
        vec![NONE; v_count]
    } else {
        Vec::new()
    };
    // Each vertex's values: its own (once used), then its extras in order of creation, as
    // a linked list of extras.
    let mut own = vec![false; v_count];
    let (mut head, mut tail) = (vec![NONE; v_count], vec![NONE; v_count]);
    let mut next: Vec<u32> = Vec::new();
    let mut count = vec![0u32; v_count];
    for c in 0..corners {
        let r = find(&mut parent, c as u32) as usize;
        if value_of_root[r] == NONE {
            let v = vertex(c) as usize;
            if v >= v_count {
                return Err((b.offset(), format!("corner {c}: vertex {v} out of range")));
            }
            let value = if !own[v] {
                own[v] = true;
                v as u32
            } else {
                // The vertex's values in order: its own, then its extras.
                let list = || {
                    std::iter::once(v as u32).chain(
                        std::iter::successors(Some(head[v]).filter(|&e| e != NONE), |&e| {
                            Some(next[e as usize]).filter(|&x| x != NONE)
                        })
                        .map(|e| s.vertex_count + e),
                    )
                };
                let wanted = if !encoding {
                    0
                } else {
                    let want = id(c);
                    list()
                        .position(|x| ids_out[x as usize] == want)
                        .unwrap_or(count[v] as usize + 1)
                };
                let offset = b.offset();
                let n = count[v] as usize + 1;
                if b.bit(&mut repeat, u32::from(wanted < n)) == 1 {
                    let i = if n == 1 {
                        0
                    } else {
                        code_uint(b, &mut which, wanted as u64)
                            .filter(|&i| i < n as u64)
                            .ok_or_else(|| {
                                (
                                    offset,
                                    format!("corner {c}: not one of the {n} values of vertex {v}"),
                                )
                            })? as usize
                    };
                    list().nth(i).expect("index below the list's length")
                } else {
                    let e = next.len() as u32;
                    if e >= extra {
                        return Err((
                            offset,
                            format!("corner {c}: more than {extra} extra values"),
                        ));
                    }
                    next.push(NONE);
                    match tail[v] {
                        NONE => head[v] = e,
                        last => next[last as usize] = e,
                    }
                    tail[v] = e;
                    count[v] += 1;
                    if encoding {
                        ids_out.push(NONE);
                    }
                    s.vertex_count + e
                }
            };
            if encoding && ids_out[value as usize] == NONE {
                ids_out[value as usize] = id(c);
            }
            value_of_root[r] = value;
        }
        at_corners[c / 3][c % 3] = value_of_root[r];
    }
    if b.overrun() {
        return Err((b.offset(), "the stream ends within the values".into()));
    }
    if encoding || next.len() as u32 == extra {
        Ok((at_corners, ids_out))
    } else {
        Err((
            b.offset(),
            format!("{} extra values coded, the header says {extra}", next.len()),
        ))
    }
}

/// The seams of an attribute whose value at corner `k` of slot `t` has the id `ids[t][k]`
/// (equal ids, equal values).
pub(crate) fn encode(s: &Slots, ids: &[[u32; 3]]) -> Coded {
    debug_assert_eq!(ids.len(), s.vertices.len());
    let mut e = Encoder::new();
    let (at_corners, ids) = code(&mut e, s, Some(ids), u32::MAX).expect("the encoder's own seams");
    Coded {
        stream: e.finish(),
        at_corners,
        ids,
    }
}

/// The value index at every corner from a seam stream (at byte `base` of the file, for
/// errors) with exactly `extra` extra values; `Err((offset, message))` when it breaks [V49].
pub(crate) fn decode(
    s: &Slots,
    extra: u32,
    stream: &[u8],
    base: usize,
) -> Result<Vec<[u32; 3]>, (u64, String)> {
    let mut d = Decoder::new(stream, base);
    code(&mut d, s, None, extra).map(|(at, _)| at)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two triangles sharing edge (1, 2): slot 0 = (0, 1, 2), slot 1 = (2, 1, 3), corner 0 of
    /// each across the shared edge.
    fn quad() -> (Vec<[u32; 3]>, Vec<[u32; 3]>) {
        (
            vec![[0, 1, 2], [3, 2, 1]],
            vec![[3, NONE, NONE], [0, NONE, NONE]],
        )
    }

    fn round_trip(ids: &[[u32; 3]]) -> Coded {
        let (vertices, opposites) = quad();
        let s = Slots {
            vertices: &vertices,
            opposites: &opposites,
            vertex_count: 4,
        };
        let coded = encode(&s, ids);
        let extra = coded.ids.len() as u32 - 4;
        let back = decode(&s, extra, &coded.stream, 0).unwrap();
        assert_eq!(back, coded.at_corners);
        for (t, tri) in ids.iter().enumerate() {
            for (k, &id) in tri.iter().enumerate() {
                assert_eq!(coded.ids[coded.at_corners[t][k] as usize], id);
            }
        }
        coded
    }

    #[test]
    fn no_seam_gives_every_vertex_its_own_value() {
        let coded = round_trip(&[[10, 11, 12], [13, 12, 11]]);
        assert_eq!(coded.at_corners, vec![[0, 1, 2], [3, 2, 1]]);
    }

    #[test]
    fn a_seam_gives_extra_values() {
        let coded = round_trip(&[[10, 11, 12], [13, 22, 21]]);
        assert_eq!(coded.at_corners, vec![[0, 1, 2], [3, 4, 5]]);
        let half = round_trip(&[[10, 11, 12], [13, 12, 21]]);
        assert_eq!(half.at_corners, vec![[0, 1, 2], [3, 2, 4]]);
    }

    #[test]
    fn a_wrong_extra_count_is_refused() {
        let (vertices, opposites) = quad();
        let s = Slots {
            vertices: &vertices,
            opposites: &opposites,
            vertex_count: 4,
        };
        let coded = encode(&s, &[[10, 11, 12], [13, 22, 21]]);
        assert!(decode(&s, 1, &coded.stream, 0).is_err());
        assert!(decode(&s, 3, &coded.stream, 0).is_err());
    }
}
