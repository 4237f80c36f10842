//! Tests of the Zipper's fast pass over the slots: under `cfg(test)` the reader asserts
//! that it agrees with the slot loop on every file it opens, so these tests forge files
//! where the two could part.

use crate::format::layout::ZiprHeader;
use crate::format::Tag;
use crate::generate::{self, Rng};
use crate::lr::zipper::{Field, FieldKind, Packed, BLOCK_SHIFT};
use crate::lr::LrLayout;
use crate::read::{open, Container, Limits};
use crate::words::LeWords;
use crate::write::{assemble, encode, Connectivity, EncodeOptions, SectionBytes};

/// 1,500 Zipper files forged (see [`read_forged_files`]): under `cfg(test)`
/// `zipper_tables` asserts that this fast pass and the slot loop agree on every one, and
/// the fuzz targets check it under `cfg(fuzzing)`.
///
/// [`read_forged_files`]: crate::read::read_forged_files
#[cfg(feature = "fuzz-checks")]
#[test]
fn the_fast_pass_and_the_slot_loop_agree_on_forged_files() {
    crate::read::read_forged_files(0b101, 58, 1500);
}

/// A Zipper file of 30 blocks with holes and defects (the forged files of the fuzz
/// targets have one block): its sections, and the index of `ZIPR`, whose anchors are
/// rewritten 16 bits wide (so that any 16-bit offset can be forged).
fn base(rng: &mut Rng) -> (Vec<SectionBytes>, usize) {
    let mut mesh = generate::torus(48, 40);
    generate::punch_holes(&mut mesh, 4, rng);
    generate::add_defects(&mut mesh, 4, rng);
    let options = EncodeOptions {
        connectivity: Connectivity::Zipper,
        ..EncodeOptions::default()
    };
    let (mut sections, z) = crate::read::encoded_sections(&mesh, &options, Tag::ZIPR);
    sections[z].2 = with_wide_anchors(&sections[z].2);
    (sections, z)
}

/// A compact `ZIPR` section with its anchors rewritten as 16-bit fields (the same values),
/// its lists no longer joined.
pub(crate) fn with_wide_anchors(p: &[u8]) -> Vec<u8> {
    let unjoined = crate::lr::zipper::unjoined_zipr(p);
    let p = unjoined.as_deref().unwrap_or(p);
    let h = ZiprHeader::read(p);
    let (anchor, _) = h.head_fields().expect("the compact form");
    let heads = h.layout().expect("a valid layout").arrays[4];
    let end = heads.start + 4 * h.anchor_words() as usize;
    let old = Packed::new(
        LeWords(&p[heads.start..end]),
        2 * h.blocks() as usize,
        anchor,
    );
    let wide = Field {
        width: 16,
        kind: FieldKind::Signed,
    };
    let values: Vec<u32> = old.iter().collect();
    let wide = Packed::pack(&values, [wide; 2]).expect("anchors fit 16 bits");
    let mut header = h;
    header.compact.as_mut().expect("compact").anchor_bits = 16;
    let mut out = header.to_bytes();
    out.extend_from_slice(&p[h.header_len()..heads.start]);
    for word in &wide.words {
        out.extend_from_slice(&word.to_le_bytes());
    }
    out.extend_from_slice(&p[end..]);
    out
}

/// Where the anchors of `ZIPR` (section `z` of `view`) start in the section.
fn heads_at(view: &Container, z: usize) -> usize {
    let t = view.zipper().expect("Zipper tables");
    assert_eq!(t.anchors.field_width(), 16, "the anchors are 16 bits wide");
    t.anchors.words.0.as_ptr() as usize - view.sections.sections[z].bytes.as_ptr() as usize
}

/// Opens `base` with the chain anchor of `side` in `block` set to `offset` from the block's
/// first vertex (16-bit anchors, which start at `heads_at` in `ZIPR`, section `z`).
fn open_with_anchor(
    base: &[SectionBytes],
    (z, heads_at): (usize, usize),
    block: usize,
    side: usize,
    offset: i16,
) -> bool {
    let at = heads_at + 4 * block + 2 * side;
    let mut sections = base.to_vec();
    sections[z].2[at..at + 2].copy_from_slice(&offset.to_le_bytes());
    open(&assemble(&sections), &Limits::default()).is_ok()
}

/// Units of `ZIPR` copied over others: under `cfg(test)` `open` runs this fast pass and
/// the slot loop on each file and asserts that their flags agree. Copied units keep most
/// fields plausible, so both verdicts occur.
#[test]
fn the_fast_pass_and_the_slot_loop_agree_on_forged_multi_block_files() {
    let mut rng = Rng::new(24);
    let (base, z) = base(&mut rng);
    let units = base[z].2.len() as u32 / 2;
    let (mut opened, mut refused) = (0, 0);
    for _ in 0..3000 {
        let mut sections = base.clone();
        let section = &mut sections[z].2;
        for _ in 0..1 + rng.below(4) {
            let (from, to) = (rng.below(units) as usize, rng.below(units) as usize);
            let unit = [section[2 * from], section[2 * from + 1]];
            section[2 * to..2 * to + 2].copy_from_slice(&unit);
        }
        match open(&assemble(&sections), &Limits::default()) {
            Ok(_) => opened += 1,
            Err(_) => refused += 1,
        }
    }
    assert!(
        opened > 0 && refused > 0,
        "{opened} opened, {refused} refused"
    );
}

/// Every block's anchors set in turn to `m + d` (`d` 0 to 3), so that a first delta
/// slot of symbol `d` chains to `m` exactly, one past the last vertex: the edge of
/// [V58]'s range, which random copies rarely reach. The two passes must agree there too.
#[test]
fn the_fast_pass_and_the_slot_loop_agree_at_the_edge_of_the_range() {
    let (base, z) = base(&mut Rng::new(25));
    let bytes = assemble(&base);
    let view = open(&bytes, &Limits::default()).expect("what we write opens");
    let section = (z, heads_at(&view, z));
    let t = view.zipper().expect("Zipper tables");
    let (m, blocks) = (t.m, t.m_r.div_ceil(1 << BLOCK_SHIFT));
    let mut refused = 0;
    for block in 0..blocks {
        let first = block << BLOCK_SHIFT;
        for (side, d) in (0..2).flat_map(|side| (0..4).map(move |d| (side, d))) {
            let offset = (m + d - first) as i16;
            refused += !open_with_anchor(&base, section, block as usize, side, offset) as usize;
        }
    }
    assert!(refused > 0, "no chain reached m");
}

/// Every block's anchors set in turn near the block's own vertices (where a chain meets
/// a slot's `v.n.n`, which makes the slot a redundant copy) and near 0 (where a chain
/// passes below the first vertex): the edges of `chains_clear` and `runs_clear`, where
/// the open must still agree with the slot loop (asserted under `cfg(test)`). Both
/// verdicts occur, and on the file as written most blocks skip their chains.
#[test]
fn the_fast_pass_and_the_slot_loop_agree_where_chains_meet_their_slots() {
    let (base, z) = base(&mut Rng::new(26));
    let bytes = assemble(&base);
    let view = open(&bytes, &Limits::default()).expect("what we write opens");
    let section = (z, heads_at(&view, z));
    let t = view.zipper().expect("Zipper tables");
    let blocks = t.m_r.div_ceil(1 << BLOCK_SHIFT) as usize;
    let clear = (0..blocks)
        .filter(|&block| block_is_clear(t, block))
        .count();
    assert!(
        2 * clear > blocks,
        "{clear} of {blocks} blocks skip their chains"
    );
    let (mut opened, mut refused) = (0, 0);
    for block in 0..blocks {
        let first = (block << BLOCK_SHIFT) as i32;
        let near_own = (-4..72).step_by(3);
        let near_zero = [0, 1, 2, 3, 5, 9].map(|x| x - first);
        for (side, offset) in
            (0..2).flat_map(|side| near_own.clone().chain(near_zero).map(move |d| (side, d)))
        {
            match open_with_anchor(&base, section, block, side, offset as i16) {
                true => opened += 1,
                false => refused += 1,
            }
        }
    }
    assert!(
        opened > 0 && refused > 0,
        "{opened} opened, {refused} refused"
    );
}

/// Whether block `block` of `t` passes `chains_clear`, as the open's scan calls it.
fn block_is_clear(t: &super::Tables, block: usize) -> bool {
    let slot = t.block_planes(block);
    let first = (block << BLOCK_SHIFT) as u32;
    let used = 2 * ((t.m_r - first) as usize).min(1 << BLOCK_SHIFT);
    let mut chained = [0u32; 128];
    for bit in super::Bits128(slot.stored()) {
        chained[bit] = t.tip(first + bit as u32 / 2, bit % 2);
    }
    let n = super::Neighbours::of_block(t, first, used, &slot);
    let fours = t.block_fours(&slot);
    super::chains_clear(t, (&slot, fours), block, &chained, &n, t.m)
        || super::runs_clear(t, (&slot, fours), block, &chained, &n.nn(t)[..used], t.m)
}

/// `pack_bits` is the inverse of spreading bits over bytes, on random patterns.
#[test]
fn pack_bits_gathers_the_low_bit_of_every_byte() {
    let mut rng = Rng::new(27);
    for _ in 0..1000 {
        let bits = (rng.next_u64() as u128) << 64 | rng.next_u64() as u128;
        let bytes: [u8; 128] = std::array::from_fn(|k| (bits >> k & 1) as u8);
        assert_eq!(super::pack_bits(&bytes), bits);
    }
}

/// `Neighbours`' range of `v.n.n` holds every slot's, the wrapped ones at a ring's end
/// included, on every block of files with one ring and with many (small components of
/// a few blocks each, and tiny ones, whose rings end inside blocks).
#[test]
fn the_range_of_next_next_holds_every_slots() {
    let mut rng = Rng::new(28);
    let (one_ring, _) = base(&mut rng);
    let mut many = generate::torus(12, 10);
    for (around, along) in [(30, 20), (4, 3), (5, 4), (24, 16), (3, 3)] {
        generate::append(&mut many, &generate::torus(around, along));
    }
    let options = EncodeOptions {
        connectivity: Connectivity::Zipper,
        ..EncodeOptions::default()
    };
    let many = encode(&many, &options).expect("tori encode");
    for bytes in [assemble(&one_ring), many] {
        let view = open(&bytes, &Limits::default()).expect("what we write opens");
        let t = view.zipper().expect("Zipper tables");
        for block in 0..t.m_r.div_ceil(1 << BLOCK_SHIFT) as usize {
            let first = (block << BLOCK_SHIFT) as u32;
            let used = 2 * ((t.m_r - first) as usize).min(1 << BLOCK_SHIFT);
            let n = super::Neighbours::of_block(t, first, used, &t.block_planes(block));
            let nn = n.nn(t);
            for (bit, &x) in nn[..used].iter().enumerate() {
                let v = first + bit as u32 / 2;
                assert_eq!(
                    x,
                    t.ring_next(t.ring_next(v)),
                    "slot {bit} of block {block}"
                );
                assert!(
                    (n.nn_low..=n.nn_high).contains(&x),
                    "block {block}: {x} outside {}..={}",
                    n.nn_low,
                    n.nn_high
                );
            }
        }
    }
}
