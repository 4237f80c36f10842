//! Forging containers for `tests/forged_*.rs`: one test per validity rule **[V1]**..**[V39]**
//! of `spec/FORMAT.md`, each in the file of its section. A valid container is changed so that
//! exactly that rule breaks, its checksums are recomputed (so that the rule itself, not a CRC,
//! must catch the change), and the reader must name the rule, the section and the byte offset
//! of the field at fault ([`breaks`]). `every_rule_has_a_forged_test` (in
//! `forged_container.rs`) keeps the `forged_*.rs` files in step with the spec.
//!
//! Expected offsets are computed from the spec's layouts, never read back from the
//! reader. The field at fault is the header field, table entry field, section word or unit
//! that a clause names. Rules about corners or triangles as a whole (V19, V21, V22, V31)
//! have no single field; for them the field at fault is where the
//! spec stores the triangle of the failing corner: the LR entry of its slot (`LRTB`) or the
//! pair word of its ring vertex (`LRBE`); for a T0 corner `c`, `VO_V[c - c/4 - 6 m_r]`
//! (`LRTB`) or the first unit of its row (`LRBE`); for a strips corner, the first `T` entry
//! of its triangle's window. A clause where the reader points elsewhere is tested in a
//! separate `#[ignore]`d function that says so.

use super::sections_of;
use lrmesh::format::layout::{Layout, LrbeHeader, LrtbHeader, StrpHeader};
use lrmesh::format::{table_checksum, Tag};
use lrmesh::lr::LrLayout;
use lrmesh::read::{open, open_verified, Limits, Sections, SEMANTIC_RULES};
use lrmesh::write::{assemble, encode, Connectivity, EncodeOptions};
use lrmesh::{Corner, CornerOps, Error, FormatError, Mesh, Rule};

pub const NONE: u32 = u32::MAX;

// ---------------------------------------------------------------------------------------
// Containers and forgeries.

pub fn manifest() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A container of `spec/vectors/`.
pub fn vector(name: &str) -> Vec<u8> {
    std::fs::read(manifest().join("spec/vectors").join(name)).unwrap()
}

/// `mesh` encoded with `connectivity`, keeping the input order (so with `PERM`).
pub fn encoded(mesh: &Mesh, connectivity: Connectivity) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity,
        keep_order: true,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

/// Offset in the file of the payload of `tag`.
pub fn section_at(bytes: &[u8], tag: Tag) -> u64 {
    let sections = Sections::parse(bytes, &Limits::default()).unwrap();
    sections.section(tag).unwrap().offset
}

/// Index of `tag` in the section table.
pub fn index_of(bytes: &[u8], tag: Tag) -> usize {
    sections_of(bytes).iter().position(|s| s.0 == tag).unwrap()
}

pub fn payload(bytes: &[u8], tag: Tag) -> Vec<u8> {
    sections_of(bytes)
        .into_iter()
        .find(|s| s.0 == tag)
        .unwrap()
        .2
}

pub fn get(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

pub fn put(b: &mut [u8], at: usize, x: u32) {
    b[at..at + 4].copy_from_slice(&x.to_le_bytes());
}

pub fn get16(b: &[u8], at: usize) -> u32 {
    u16::from_le_bytes([b[at], b[at + 1]]) as u32
}

pub fn put16(b: &mut [u8], at: usize, x: u32) {
    b[at..at + 2].copy_from_slice(&(x as u16).to_le_bytes());
}

/// The container with the payload of `tag` changed by `edit`, checksums recomputed.
pub fn forge(bytes: &[u8], tag: Tag, edit: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut sections = sections_of(bytes);
    let section = sections.iter_mut().find(|s| s.0 == tag).unwrap();
    edit(&mut section.2);
    assemble(&sections)
}

/// The container with the section list changed by `edit`, checksums recomputed.
pub fn forge_sections(
    bytes: &[u8],
    edit: impl FnOnce(&mut Vec<lrmesh::write::SectionBytes>),
) -> Vec<u8> {
    let mut sections = sections_of(bytes);
    edit(&mut sections);
    assemble(&sections)
}

/// The bytes changed by `edit` (header or section table), with the table CRC recomputed
/// when the patched section count leaves the table inside the file.
pub fn patch(bytes: &[u8], edit: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut b = bytes.to_vec();
    edit(&mut b);
    let end = 32 + 32 * get(&b, 12) as usize;
    if end <= b.len() {
        let crc = table_checksum(&b[..end]);
        put(&mut b, 24, crc);
    }
    b
}

/// Offset in the file of the section-table entry `i`, plus `field`.
pub fn entry_at(i: usize, field: u64) -> u64 {
    32 + 32 * i as u64 + field
}

/// The error by which [`open_verified`] refuses `bytes`. The well-formed check ([`open`])
/// must refuse them with the same error, unless the rule is one it leaves to the verifying
/// reader: then the file opens and every operator answers in range.
#[track_caller]
pub fn format_error(bytes: &[u8]) -> FormatError {
    let e = match open_verified(bytes, &Limits::default()) {
        Err(Error::Format(e)) => *e,
        Err(e) => panic!("expected a format error, got {e}"),
        Ok(_) => panic!("the forged container was accepted"),
    };
    match open(bytes, &Limits::default()) {
        Err(Error::Format(quick)) => assert_eq!(*quick, e, "both levels name the same error"),
        Err(other) => panic!("the well-formed check fails otherwise: {other}"),
        Ok(view) => {
            assert!(
                SEMANTIC_RULES.contains(&e.rule),
                "a well-formed open misses {e}"
            );
            lrmesh::fuzz_checks::walk_in_range(&view);
        }
    }
    e
}

/// The message of the error by which opening `bytes` fails, which must be rule `rule` in
/// `section`; `None` if it opens. Any other error fails the test. For range-coded streams,
/// whose damaged bytes may or may not break a rule.
#[track_caller]
pub fn rule_message(bytes: &[u8], rule: u8, section: &str) -> Option<String> {
    match open_verified(bytes, &Limits::default()) {
        Ok(_) => None,
        Err(Error::Format(e)) => {
            assert_eq!((e.rule, e.section.as_str()), (Rule(rule), section), "{e}");
            Some(e.message)
        }
        Err(e) => panic!("{e}"),
    }
}

/// Asserts that opening `bytes` fails by rule `rule` in `section` at file offset `offset`,
/// with `words` in the message.
#[track_caller]
pub fn breaks(bytes: &[u8], rule: u8, section: &str, offset: u64, words: &str) {
    let e = format_error(bytes);
    assert_eq!(
        (e.rule, e.section.as_str(), e.offset),
        (Rule(rule), section, offset),
        "{}",
        e.message
    );
    assert!(e.message.contains(words), "{:?} lacks {words:?}", e.message);
}

/// [V13] for the grid of `GEOM` encodings 2 and 4 (FORMAT.md §3.3.1), which one parser
/// reads: `bytes` has such a section; each field is broken in turn (bits 0, 31 and beyond,
/// a negative size, a non-finite minimum or size, the reserved field, a section cut inside
/// the grid) and must be named.
pub fn grid_breaks(bytes: &[u8]) {
    let at = section_at(bytes, Tag::GEOM);
    for bits in [0, 31, u32::MAX] {
        let bad = forge(bytes, Tag::GEOM, |p| put(p, 24, bits));
        breaks(&bad, 13, "GEOM", at + 24, "bits per coordinate");
    }
    let bad = forge(bytes, Tag::GEOM, |p| put(p, 20, (-1.0f32).to_bits()));
    breaks(&bad, 13, "GEOM", at + 20, "negative");
    for field in [8, 12, 16, 20] {
        for x in [f32::NAN, f32::INFINITY] {
            let bad = forge(bytes, Tag::GEOM, |p| put(p, field, x.to_bits()));
            breaks(&bad, 13, "GEOM", at + field as u64, "non-finite");
        }
    }
    let bad = forge(bytes, Tag::GEOM, |p| put(p, 4, 7));
    breaks(&bad, 13, "GEOM", at + 4, "reserved");
    let bad = forge(bytes, Tag::GEOM, |p| p.truncate(20));
    breaks(&bad, 13, "GEOM", at, "");
}

// ---------------------------------------------------------------------------------------
// Section tables: header words and arrays as u32 values, to change counts and join again.

pub struct Tables {
    pub head: Vec<u32>,
    arrays: Vec<Vec<u32>>,
    widths: Vec<usize>,
}

impl Tables {
    pub fn split(p: &[u8], head_len: usize, layout: &Layout) -> Tables {
        let head = (0..head_len / 4).map(|i| get(p, 4 * i)).collect();
        let arrays = layout
            .arrays
            .iter()
            .map(|a| {
                (0..a.len)
                    .map(|i| match a.width {
                        4 => get(p, a.at(i)),
                        _ => get16(p, a.at(i)),
                    })
                    .collect()
            })
            .collect();
        let widths = layout.arrays.iter().map(|a| a.width).collect();
        Tables {
            head,
            arrays,
            widths,
        }
    }

    pub fn lrtb(p: &[u8]) -> Tables {
        Tables::split(p, LrtbHeader::LEN, &LrtbHeader::read(p).layout().unwrap())
    }

    pub fn lrbe(p: &[u8]) -> Tables {
        Tables::split(p, LrbeHeader::LEN, &LrbeHeader::read(p).layout().unwrap())
    }

    pub fn array(&mut self, index: usize) -> &mut Vec<u32> {
        &mut self.arrays[index]
    }

    pub fn join(&self) -> Vec<u8> {
        let mut out = Vec::new();
        for x in &self.head {
            out.extend_from_slice(&x.to_le_bytes());
        }
        for (array, &width) in self.arrays.iter().zip(&self.widths) {
            for &x in array {
                out.extend_from_slice(&x.to_le_bytes()[..width]);
            }
        }
        out
    }
}

// Array indices of `LrtbHeader::ARRAYS` and `LrbeHeader::ARRAYS`.
pub const LR: usize = 3;
pub const VO_V: usize = 4;
pub const VO_O: usize = 5;
pub const VO_STAR: usize = 6;
pub const LRTB_C: usize = 7;
pub const FAN_BITS: usize = 8;
pub const FAN_RANK: usize = 9;
pub const FANS: usize = 10;
pub const PAIRS: usize = 3;
pub const BLOCKS: usize = 4;
pub const LRBE_C: usize = 6;
pub const OVERFLOW: usize = 7;
pub const BASES: usize = 8;
pub const ROWS: usize = 9;
pub const RECORDS: usize = 10;

/// File offset of element `i` of array `name` of `LRTB`.
pub fn lrtb_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::LRTB);
    section_at(bytes, Tag::LRTB) + LrtbHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// File offset of element `i` of array `name` of `LRBE`.
pub fn lrbe_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::LRBE);
    section_at(bytes, Tag::LRBE) + LrbeHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// File offset of element `i` of array `name` of `STRP`.
pub fn strp_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::STRP);
    section_at(bytes, Tag::STRP) + StrpHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// Byte offset within `LRTB` of element `i` of array `index`.
pub fn lrtb_word(p: &[u8], index: usize, i: usize) -> usize {
    LrtbHeader::read(p).layout().unwrap().arrays[index].at(i)
}

/// Byte offset within `LRBE` of element `i` of array `index`.
pub fn lrbe_word(p: &[u8], index: usize, i: usize) -> usize {
    LrbeHeader::read(p).layout().unwrap().arrays[index].at(i)
}

/// Byte offset within `STRP` of `T[i]`, `A[i]` or `C[i]`.
pub fn strp_word(p: &[u8], name: &str, i: usize) -> usize {
    StrpHeader::read(p).layout().unwrap().array(name).at(i)
}

pub fn set_lrtb(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrtb_word(p, index, i);
    put(p, at, x)
}

pub fn set_lrbe(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrbe_word(p, index, i);
    put(p, at, x)
}

pub fn set_lrbe16(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrbe_word(p, index, i);
    put16(p, at, x)
}

pub fn set_strp(p: &mut [u8], name: &str, i: usize, x: u32) {
    let at = strp_word(p, name, i);
    put(p, at, x)
}

/// The T0 triangle (row) `j` of an LR container whose three corners have no opposite.
pub fn lone_t0_triangle(bytes: &[u8]) -> usize {
    let view = open(bytes, &Limits::default()).unwrap();
    let lr = view.connectivity();
    let m_r = view
        .lr()
        .map(|l| l.ring_vertices())
        .unwrap_or_else(|| view.lr_compact().unwrap().ring_vertices());
    (0..)
        .find(|&j| (0..3).all(|i| lr.opposite(Corner(8 * m_r + 4 * j as u32 + i)).is_none()))
        .unwrap()
}

/// The container with attribute `i`'s coded seams (seam encoding 1; its record at `at` of
/// `ATTR`, its seam part at `part`) replaced by the tables of seam encoding 0 that say the
/// same, made from the corners' values as the reader gives them (an Edgebreaker container
/// without kept triangles). With `extra`, the header says that many extra values instead
/// (and the entries take the bits it needs), the values part unchanged.
pub fn with_seam_tables(
    bytes: &[u8],
    i: usize,
    at: usize,
    part: usize,
    extra: Option<u32>,
) -> Vec<u8> {
    use lrmesh::format::attributes::{bits_for, tables_of, AttributeHeader};
    let file = open(bytes, &Limits::default()).unwrap();
    let a = &file.attributes()[i];
    let end = at + a.stored_bytes() as usize;
    let h = AttributeHeader::parse(&payload(bytes, Tag::ATTR)[at..]);
    assert_eq!(h.seam_encoding(), 1);
    let conn = file.connectivity();
    let v = file.connectivity_vertex_count();
    let mut flagged = Vec::new();
    for t in 0..h.slots {
        let c = conn.triangle_corner(lrmesh::Triangle(t));
        let values = [c, conn.next(c), conn.prev(c)].map(|c| file.value_index(a, c));
        if values.iter().any(|&x| x >= v) {
            flagged.push((t, values.map(|x| if x < v { 0 } else { x - v + 1 })));
        }
    }
    let e = extra.unwrap_or(h.extra);
    let bits = bits_for(e);
    let [flags, rank, words] = tables_of(h.slots, &flagged, bits);
    forge(bytes, Tag::ATTR, |p| {
        p[at + 21] = 0;
        p[at + 5] = bits as u8;
        p[at + 8..at + 12].copy_from_slice(&e.to_le_bytes());
        let tables: Vec<u8> = flags
            .iter()
            .chain(&rank)
            .chain(&words)
            .flat_map(|w| w.to_le_bytes())
            .collect();
        p.splice(part..end, tables);
    })
}
