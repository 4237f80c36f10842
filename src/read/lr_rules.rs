//! The rules every LR layout keeps, standard or bit-efficient: rings (V16, V34), the slots
//! the operators jump to (V19), non-degenerate triangles (V21), `c.o` an involution across
//! one edge (V22), `v.c` a corner of `v` (V23) that starts its fan (V38). Together they make
//! every operator answer a valid id and every swing and contour walk terminate.

use super::fields::Fields;
use crate::error::{Error, Result, Rule};
use crate::ids::{Corner, Vertex};
use crate::lr::{LrLayout, LrTables, OpenFans, NULL};
use crate::ops::CornerOps;
use crate::words::{BitsSet, Words};

/// [V16] ring starts increase by at least 4 from 0 to `m_r`, and the ring-end bits and ranks
/// (when the layout stores them) are the ones the starts imply. `err(array, word, message)`
/// locates an error in array 0 (starts), 1 (bits) or 2 (ranks).
pub(super) fn check_rings<S: Words, W: Words>(
    ring_starts: &S,
    bits: Option<(&W, &W)>,
    m_r: u32,
    err: impl Fn(usize, usize, String) -> Error,
) -> Result<()> {
    if m_r == 0 {
        return match ring_starts.at(0) {
            0 => Ok(()),
            _ => Err(err(
                0,
                0,
                "ring starts of an empty ring set must be [0]".into(),
            )),
        };
    }
    let starts: Vec<u32> = (0..ring_starts.count())
        .map(|i| ring_starts.at(i))
        .collect();
    for i in 0..starts.len() {
        let ok = if i == 0 {
            starts[0] == 0
        } else {
            starts[i] >= starts[i - 1].saturating_add(4)
                && (i + 1 < starts.len() || starts[i] == m_r)
        };
        if !ok {
            return Err(err(
                0,
                i,
                format!("ring start {} breaks the ring rules", starts[i]),
            ));
        }
    }
    let Some((ring_last, ring_rank)) = bits else {
        return Ok(());
    };
    let (last, rank) = crate::lr::ring_bits(&starts);
    for (i, &w) in last.iter().enumerate() {
        if ring_last.at(i) != w {
            return Err(err(
                1,
                i,
                "ring-end bits do not match the ring starts".into(),
            ));
        }
        if ring_rank.at(i) != rank[i] {
            return Err(err(
                2,
                i,
                "ring ranks do not match the ring-end bits".into(),
            ));
        }
    }
    Ok(())
}

/// What one pass over the ring slots of any LR layout finds: which slots hold a canonical
/// triangle ([`CANONICAL`]) and which jump to the same side of `v.n` ([`JUMPS`]: redundant T2
/// copies and wart slots). [V19] and the corner checks of [V20] and [V37] then look the flags
/// up instead of decoding slots again at random.
pub(super) struct SlotMap {
    flags: SlotFlags,
    /// Canonical triangles in ring slots.
    pub triangles: u64,
    m_r: u32,
    t0: u32,
}

/// The flags of every ring slot, in slot order, as the pass that found them made them.
enum SlotFlags {
    /// A byte per slot: the passes of the LR layouts are plain maps the compiler vectorizes.
    Bytes(Vec<u8>),
    /// Two bit vectors, interleaved per 64 slots ([`SlotBits`]; bits past the last slot 0):
    /// the Zipper's pass finds the flags as masks of its blocks, and a quarter of the bytes
    /// to write made a tenth of its open.
    Bits(SlotBits),
}

/// The canonical and jumping slots as bit vectors ([`SlotFlags::Bits`]), interleaved: word
/// `2i` holds slots `64i .. 64i + 63` canonical, word `2i + 1` those that jump (one
/// allocation, and [V19] reads both words of a slot together).
pub(super) struct SlotBits {
    pub words: Vec<u64>,
    /// Slots (`2 m_r`).
    pub len: usize,
}

impl SlotBits {
    /// Whether slot `k` has `flag` ([`CANONICAL`] or [`JUMPS`]; false past the end).
    #[inline]
    fn has(&self, k: usize, flag: u8) -> bool {
        let word = 2 * (k / 64) + (flag == JUMPS) as usize;
        self.words.get(word).is_some_and(|w| w >> (k % 64) & 1 != 0)
    }

    /// On one ring, where slot `t` jumps to slot `t + 2` (mod `len`): whether every jumping
    /// slot lands on a canonical one, a word at a time.
    fn jumps_land_on_one_ring(&self) -> bool {
        let (w, n) = (&self.words, self.len);
        // The words before the one of slot n - 2: slot t + 2 is bit t of the pair's shift.
        let split = (n - 2) / 64;
        let words = (0..split).fold(true, |ok, i| {
            let target = w[2 * i] >> 2 | w[2 * i + 2] << 62;
            ok & (w[2 * i + 1] & !target == 0)
        });
        words && (64 * split..n).all(|t| !self.has(t, JUMPS) || self.has((t + 2) % n, CANONICAL))
    }
}

pub(super) const CANONICAL: u8 = 1;
pub(super) const JUMPS: u8 = 2;

/// The flags of a ring slot in a [`SlotMap`], from its tip (any value with IRREGULAR), its
/// WART and IRREGULAR flags (0 or 1) and `nn = v.n.n`: a redundant T2 copy (tip `v.n.n`,
/// neither flag) and a wart slot jump to the same side of `v.n`; the slot holds a canonical
/// triangle unless it is such a copy or a missing right triangle (`NULL`). An IRREGULAR slot
/// is never redundant, and its tip (checked below `m` by V17 or V35) never `NULL`. Bitwise
/// rather than short-circuit logic: the flags follow no pattern a branch predictor could
/// learn, and the passes over every slot vectorize.
#[inline(always)]
pub(super) fn ring_slot_flags(tip: u32, wart: u32, irregular: u32, nn: u32) -> u8 {
    let redundant = (1 ^ wart) & (1 ^ irregular) & (tip == nn) as u32;
    let canonical = irregular | ((tip != NULL) as u32 & (1 ^ redundant));
    (canonical as u8 * CANONICAL) | ((redundant | wart) as u8 * JUMPS)
}

/// [`ring_slot_flags`] of many slots at once, one bit each (bit `k` of every mask for slot
/// `k`): from whether the tip is `v.n.n` and whether it is not `NULL`, and the WART and
/// IRREGULAR flags, the slots whose flags have [`CANONICAL`] and those with [`JUMPS`], so
/// that a pass over a block of slots takes them from bit planes without a loop per slot.
#[inline(always)]
pub(super) fn slot_flag_masks(
    next_next: u128,
    not_null: u128,
    wart: u128,
    irregular: u128,
) -> (u128, u128) {
    let redundant = !wart & !irregular & next_next;
    let canonical = irregular | (not_null & !redundant);
    (canonical, redundant | wart)
}

/// The flags of slot `(v, side)` read through the layout's operators; `nn` is `v.n.n`.
#[inline]
pub(super) fn layout_slot_flags<T: LrLayout>(tables: &T, v: u32, side: usize, nn: u32) -> u8 {
    // No need to read an IRREGULAR slot's record for its tip.
    let irregular = tables.irregular(v, side);
    let tip = if irregular { 0 } else { tables.tip(v, side) };
    ring_slot_flags(tip, tables.wart(v, side) as u32, irregular as u32, nn)
}

impl SlotMap {
    /// One pass over the slots of any layout (rings checked by [V16] first).
    pub(super) fn new<T: LrLayout>(tables: &T) -> SlotMap {
        let m_r = tables.ring_vertices();
        let flags: Vec<u8> = (0..2 * m_r as usize)
            .map(|t| {
                let v = (t / 2) as u32;
                layout_slot_flags(tables, v, t % 2, tables.ring_next_next(v))
            })
            .collect();
        SlotMap::with_flags(flags, m_r, tables.t0_count())
    }

    /// The map of flags made by [`ring_slot_flags`], one per ring slot in slot order.
    pub(super) fn with_flags(flags: Vec<u8>, m_r: u32, t0: u32) -> SlotMap {
        let triangles = flags.iter().map(|&f| (f & CANONICAL) as u64).sum();
        SlotMap::with_counted_flags(flags, triangles, m_r, t0)
    }

    /// [`SlotMap::with_flags`] when the pass that made the flags counted the canonical ones
    /// (`triangles`), as the LR reader's does.
    pub(super) fn with_counted_flags(flags: Vec<u8>, triangles: u64, m_r: u32, t0: u32) -> SlotMap {
        SlotMap {
            flags: SlotFlags::Bytes(flags),
            triangles,
            m_r,
            t0,
        }
    }

    /// The map of flags as bit vectors, with the canonical slots counted.
    pub(super) fn with_bits(bits: SlotBits, triangles: u64, m_r: u32, t0: u32) -> SlotMap {
        debug_assert_eq!(bits.len, 2 * m_r as usize);
        SlotMap {
            flags: SlotFlags::Bits(bits),
            triangles,
            m_r,
            t0,
        }
    }

    /// Slots.
    fn len(&self) -> usize {
        match &self.flags {
            SlotFlags::Bytes(bytes) => bytes.len(),
            SlotFlags::Bits(bits) => bits.len,
        }
    }

    /// The flags of slot `k` ([`CANONICAL`], [`JUMPS`]); `k` below [`SlotMap::len`].
    #[inline]
    fn flag(&self, k: usize) -> u8 {
        match &self.flags {
            SlotFlags::Bytes(bytes) => bytes[k],
            SlotFlags::Bits(bits) => {
                (bits.has(k, CANONICAL) as u8 * CANONICAL) | (bits.has(k, JUMPS) as u8 * JUMPS)
            }
        }
    }

    /// Whether two maps flag the same slots and count the same triangles (a fast pass's map
    /// against [`SlotMap::new`]'s, in tests and fuzzing), whichever form each has.
    #[cfg(any(test, fuzzing))]
    pub(super) fn agrees_with(&self, other: &SlotMap) -> bool {
        (self.len(), self.triangles, self.m_r, self.t0)
            == (other.len(), other.triangles, other.m_r, other.t0)
            && (0..self.len()).all(|k| self.flag(k) == other.flag(k))
    }

    /// Whether `c` is a corner of a canonical triangle ([`LrLayout::is_corner`]).
    #[inline]
    pub(super) fn is_corner(&self, c: u32) -> bool {
        let t = (c >> 2) as usize;
        c & 3 != 3
            && match t < self.len() {
                true => self.flag(t) & CANONICAL != 0,
                false => t - 2 * (self.m_r as usize) < self.t0 as usize,
            }
    }

    /// [V19]: every slot that jumps lands on a canonical triangle, so that every corner an
    /// operator computes is a corner of the mesh. `corner_at` gives the section offset that
    /// stores a corner's triangle, for errors.
    pub(super) fn check_jumps<T: LrLayout>(
        &self,
        tables: &T,
        f: &Fields,
        corner_at: impl Fn(Corner) -> usize,
    ) -> Result<()> {
        let n = self.len();
        if tables.ring_count() == 1 && n >= 2 {
            // One ring: slot `t` jumps to slot `t + 2` (mod 2 m_r). A branch-free pass; the
            // slot at fault is looked for only when it fails.
            let landed = match &self.flags {
                SlotFlags::Bytes(flags) => {
                    let lands = |(&x, &y): (&u8, &u8)| x & JUMPS == 0 || y & CANONICAL != 0;
                    let tail = flags[n - 2..].iter().zip(&flags[..2]);
                    let all = flags.iter().zip(&flags[2..]).chain(tail);
                    all.fold(true, |ok, pair| ok & lands(pair))
                }
                SlotFlags::Bits(bits) => bits.jumps_land_on_one_ring(),
            };
            if landed {
                return Ok(());
            }
        }
        let jumping: Box<dyn Iterator<Item = usize> + '_> = match &self.flags {
            SlotFlags::Bytes(flags) => Box::new((0..n).filter(|&k| flags[k] & JUMPS != 0)),
            SlotFlags::Bits(bits) => Box::new(
                (bits.words.iter().skip(1).step_by(2).enumerate())
                    .flat_map(|(i, &w)| BitsSet(w).map(move |k| 64 * i + k as usize)),
            ),
        };
        for slot in jumping {
            let (v, side) = ((slot / 2) as u32, slot % 2);
            let target = 2 * tables.ring_next(v) as usize + side;
            if self.flag(target) & CANONICAL == 0 {
                return Err(f.err(
                    corner_at(Corner(8 * v + 4 * side as u32)),
                    Rule(19),
                    format!(
                        "slot {slot} points to slot {target} which holds no canonical triangle"
                    ),
                ));
            }
        }
        Ok(())
    }
}

/// [V61] the list of open fans: the bits of the ring vertices listed, padding bits 0, as many
/// set as fans listed, the ranks those the bits imply, and every listed corner a corner of a
/// canonical triangle. `fault(array, word, message)` locates a fault in array 0 (bits), 1
/// (ranks) or 2 (corners).
pub(super) fn check_open_fans<W: Words>(
    list: &OpenFans<W>,
    slots: &SlotMap,
    m_r: u32,
    fault: impl Fn(usize, usize, String) -> Error,
) -> Result<()> {
    let words = list.bits.count();
    if m_r % 32 != 0 && words > 0 && list.bits.at(words - 1) >> (m_r % 32) != 0 {
        return Err(fault(
            0,
            words - 1,
            "bits past the last ring vertex are set".into(),
        ));
    }
    let mut count = 0u64;
    for k in 0..words {
        if list.rank.at(k) as u64 != count {
            return Err(fault(
                1,
                k,
                format!(
                    "rank {} where the bits before count {count}",
                    list.rank.at(k)
                ),
            ));
        }
        count += list.bits.at(k).count_ones() as u64;
    }
    if count != list.count() as u64 {
        return Err(fault(
            0,
            0,
            format!(
                "{count} ring vertices marked for {} fans listed",
                list.count()
            ),
        ));
    }
    for i in 0..list.count() {
        let c = list.corners.at(i);
        if !slots.is_corner(c) {
            return Err(fault(
                2,
                i,
                format!("open fan {i} starts at {c}, not a corner of the mesh"),
            ));
        }
    }
    Ok(())
}

/// [V21] and [V22] for any LR layout (a verifying reader's rules). `corner_at` gives the
/// section offset that stores a corner's triangle, for errors. Returns the number of corners
/// without an opposite, from which the reader tells whether the boundaries run along the ring
/// before it checks the vertex corners ([`check_vertex_corners`]).
pub(super) fn check_lr_opposites<T: LrLayout>(
    tables: &T,
    f: &Fields,
    corner_at: impl Fn(Corner) -> usize,
) -> Result<usize> {
    let mut without_opposite = 0;
    let corner_err = |c: Corner, rule: Rule, message: String| f.err(corner_at(c), rule, message);
    // c.o is an involution across the same edge: checked at every corner that has one, so
    // that an error names the corner whose opposite does not point back.
    for t in tables.triangles() {
        let corners = tables.triangle_corners(t);
        let vertices = corners.map(|c| tables.vertex(c));
        if vertices[0] == vertices[1] || vertices[1] == vertices[2] || vertices[0] == vertices[2] {
            return Err(corner_err(
                corners[0],
                Rule(21),
                format!("triangle {} is degenerate {vertices:?}", t.0),
            ));
        }
        for c in corners {
            let Some(o) = tables.opposite(c) else {
                without_opposite += 1;
                continue;
            };
            // Each corner checks that its opposite points back; the shared edge is checked
            // once, from the smaller corner of the pair (or a corner that is its own opposite).
            let points_back = tables.is_corner(o) && tables.opposite(o) == Some(c);
            if !points_back
                || o.0 >= c.0
                    && (tables.vertex(tables.next(o)) != tables.vertex(tables.prev(c))
                        || tables.vertex(tables.prev(o)) != tables.vertex(tables.next(c)))
            {
                return Err(corner_err(
                    c,
                    Rule(22),
                    format!(
                        "corner {} and its opposite {} do not face each other across one edge",
                        c.0, o.0
                    ),
                ));
            }
        }
    }
    Ok(without_opposite)
}

/// [V21], [V22] and [V53] for a verifying reader: returns whether every boundary runs along
/// the ring, derived from the tables, after checking that the header's flag (`flag`, stored
/// at section offset `flag_at`) claims it only when it holds.
pub(super) fn verified_boundaries<T: LrLayout>(
    tables: &T,
    f: &Fields,
    corner_at: impl Fn(Corner) -> usize,
    flag: bool,
    flag_at: usize,
) -> Result<bool> {
    let without_opposite = check_lr_opposites(tables, f, corner_at)?;
    let on_ring = crate::lr::boundaries_on_ring_given(tables, without_opposite);
    if flag && !on_ring {
        return Err(f.err(
            flag_at,
            Rule(53),
            "the flags say every boundary runs along the ring, but a corner off the ring has no opposite",
        ));
    }
    Ok(on_ring)
}

/// The verifying reader's rules ([V21]–[V23], [V38], [V53]) for layout `t`, checked on the
/// standard tables `lr` it reads back as ([`crate::lr::read_back`]: the same answers, each a
/// few reads instead of a slot's decode; asserted in tests and fuzzing). Faults are reported
/// at `t`'s offsets: `corner_at` for a corner, `vertex_at` for a vertex, `flag_at` for the
/// header's flags. Returns whether every boundary runs along the ring.
pub(super) fn verify_read_back<T: LrLayout>(
    t: &T,
    mut lr: LrTables<Vec<u32>>,
    f: &Fields,
    corner_at: impl Fn(Corner) -> usize,
    vertex_at: impl Fn(u32) -> usize,
    flag: bool,
    flag_at: usize,
) -> Result<bool> {
    #[cfg(any(test, fuzzing))]
    assert!(
        crate::lr::read_back::answers_agree(t, &lr),
        "the standard tables read back answer as the layout does"
    );
    #[cfg(not(any(test, fuzzing)))]
    let _ = t;
    lr.boundaries_on_ring = verified_boundaries(&lr, f, corner_at, flag, flag_at)?;
    check_vertex_corners(&lr, Rule(23), |v, rule, message| {
        f.err(vertex_at(v), rule, message)
    })?;
    Ok(lr.boundaries_on_ring)
}

/// [V23] (strips: [V32]) `v.c.v = v` and [V38] `v.c` is `NONE` exactly for a vertex no triangle uses,
/// starts the vertex's fan when the fan is open, and the vertex has one fan: the walk from
/// `v.c` meets all its corners. Needs [V22] first: swing is injective and keeps to the
/// vertex, so the walk forward from `v.c` comes back to it (a closed fan) or ends (an open
/// one, then walked back from `v.c` too), each corner once.
pub(super) fn check_vertex_corners<M: CornerOps>(
    mesh: &M,
    corner_rule: Rule,
    err: impl Fn(u32, Rule, String) -> Error,
) -> Result<()> {
    let mut corners = vec![0u32; mesh.vertex_id_bound() as usize];
    for c in mesh.corners() {
        corners[mesh.vertex(c).idx()] += 1;
    }
    // More steps than corners: swing does not form fans (only without [V22]).
    let limit = 3 * mesh.triangle_id_bound() as usize;
    for v in mesh.vertices() {
        let count = corners[v.idx()] as usize;
        let Some(c) = mesh.vertex_corner(v) else {
            if count != 0 {
                return Err(err(
                    v.0,
                    Rule(38),
                    format!("vertex {v} has triangles but no corner"),
                ));
            }
            continue;
        };
        if mesh.vertex(c) != Vertex(v.0) {
            return Err(err(
                v.0,
                corner_rule,
                format!(
                    "the corner of vertex {v} is a corner of vertex {}",
                    mesh.vertex(c).0
                ),
            ));
        }
        let (mut fan, mut d) = (1, c);
        let open = loop {
            match mesh.swing(d) {
                Some(e) if e == c => break false,
                Some(_) if fan > limit => break false,
                Some(e) => (fan, d) = (fan + 1, e),
                None => break true,
            }
        };
        if open && mesh.unswing(c).is_some() {
            return Err(err(
                v.0,
                Rule(38),
                format!("corner {c} of vertex {v} does not start its open fan"),
            ));
        }
        if fan != count {
            return Err(err(
                v.0,
                Rule(38),
                format!(
                    "vertex {v} has {count} corners but the fan from its corner {c} has \
                     {fan}: more than one fan"
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flags as bit masks are the 32-bit ones, for every kind of tip and flag.
    #[test]
    fn slot_flag_masks_are_ring_slot_flags() {
        let nn = 7;
        for tip in [nn, NULL, 3, 0] {
            for wart in 0..2 {
                for irregular in 0..2 {
                    let bit = |x: bool| (x as u128) << 77;
                    let (canonical, jumps) = slot_flag_masks(
                        bit(tip == nn),
                        bit(tip != NULL),
                        bit(wart == 1),
                        bit(irregular == 1),
                    );
                    let flags =
                        ((canonical >> 77) as u8 * CANONICAL) | ((jumps >> 77) as u8 * JUMPS);
                    assert_eq!(
                        flags,
                        ring_slot_flags(tip, wart, irregular, nn),
                        "tip {tip}, wart {wart}, irregular {irregular}"
                    );
                }
            }
        }
    }
}
