//! One test per validity rule **[V1]**..**[V39]** of `spec/FORMAT.md`: a valid container is
//! changed so that exactly that rule breaks, its checksums are recomputed (so that the rule
//! itself, not a CRC, must catch the change), and the reader must name the rule, the section
//! and the byte offset of the field at fault. `every_rule_has_a_forged_test` keeps this file
//! in step with the spec.
//!
//! Expected offsets are computed here from the spec's layouts, never read back from the
//! reader. The field at fault is the header field, table entry field, section word or unit
//! that a clause names. Rules about corners or triangles as a whole (V19, V21, V22, V31)
//! have no single field; for them the field at fault is where the
//! spec stores the triangle of the failing corner: the LR entry of its slot (`LRTB`) or the
//! pair word of its ring vertex (`LRBE`); for a T0 corner `c`, `VO_V[c - c/4 - 6 m_r]`
//! (`LRTB`) or the first unit of its row (`LRBE`); for a strips corner, the first `T` entry
//! of its triangle's window. A clause where the reader points elsewhere is tested in a
//! separate `#[ignore]`d function that says so.

mod common;

use common::sections_of;
use lrmesh::format::layout::{Layout, LrbeHeader, LrtbHeader, MeshRecord, StrpHeader};
use lrmesh::format::{table_checksum, Flags, Tag};
use lrmesh::generate::{self, Rng};
use lrmesh::lr::{LrLayout, IRREGULAR, NULL, VALUE, WART};
use lrmesh::read::{open, Limits, Sections};
use lrmesh::write::{assemble, encode, Connectivity, EncodeOptions};
use lrmesh::{Corner, CornerOps, Error, FormatError, Mesh, Rule, Vertex};

const NONE: u32 = u32::MAX;

// ---------------------------------------------------------------------------------------
// Containers and forgeries.

fn manifest() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// A container of `spec/vectors/`.
fn vector(name: &str) -> Vec<u8> {
    std::fs::read(manifest().join("spec/vectors").join(name)).unwrap()
}

/// `mesh` encoded with `connectivity`, keeping the input order (so with `PERM`).
fn encoded(mesh: &Mesh, connectivity: Connectivity) -> Vec<u8> {
    let options = EncodeOptions {
        connectivity,
        keep_order: true,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    bytes
}

fn torus() -> Mesh {
    generate::torus(4, 5)
}

/// Ten vertices and fourteen random triangles: its LR has off-ring vertices with open fans
/// of two corners.
fn soup() -> Mesh {
    generate::soup(10, 14, &mut Rng::new(31))
}

/// Offset in the file of the payload of `tag`.
fn section_at(bytes: &[u8], tag: Tag) -> u64 {
    let sections = Sections::parse(bytes, &Limits::default()).unwrap();
    sections.section(tag).unwrap().offset
}

/// Index of `tag` in the section table.
fn index_of(bytes: &[u8], tag: Tag) -> usize {
    sections_of(bytes).iter().position(|s| s.0 == tag).unwrap()
}

fn payload(bytes: &[u8], tag: Tag) -> Vec<u8> {
    sections_of(bytes)
        .into_iter()
        .find(|s| s.0 == tag)
        .unwrap()
        .2
}

fn get(b: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(b[at..at + 4].try_into().unwrap())
}

fn put(b: &mut [u8], at: usize, x: u32) {
    b[at..at + 4].copy_from_slice(&x.to_le_bytes());
}

fn get16(b: &[u8], at: usize) -> u32 {
    u16::from_le_bytes([b[at], b[at + 1]]) as u32
}

fn put16(b: &mut [u8], at: usize, x: u32) {
    b[at..at + 2].copy_from_slice(&(x as u16).to_le_bytes());
}

/// The container with the payload of `tag` changed by `edit`, checksums recomputed.
fn forge(bytes: &[u8], tag: Tag, edit: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
    let mut sections = sections_of(bytes);
    let section = sections.iter_mut().find(|s| s.0 == tag).unwrap();
    edit(&mut section.2);
    assemble(&sections)
}

/// The container with the section list changed by `edit`, checksums recomputed.
fn forge_sections(
    bytes: &[u8],
    edit: impl FnOnce(&mut Vec<lrmesh::write::SectionBytes>),
) -> Vec<u8> {
    let mut sections = sections_of(bytes);
    edit(&mut sections);
    assemble(&sections)
}

/// The bytes changed by `edit` (header or section table), with the table CRC recomputed
/// when the patched section count leaves the table inside the file.
fn patch(bytes: &[u8], edit: impl FnOnce(&mut Vec<u8>)) -> Vec<u8> {
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
fn entry_at(i: usize, field: u64) -> u64 {
    32 + 32 * i as u64 + field
}

#[track_caller]
fn format_error(bytes: &[u8]) -> FormatError {
    match open(bytes, &Limits::default()) {
        Err(Error::Format(e)) => *e,
        Err(e) => panic!("expected a format error, got {e}"),
        Ok(_) => panic!("the forged container was accepted"),
    }
}

/// Asserts that opening `bytes` fails by rule `rule` in `section` at file offset `offset`,
/// with `words` in the message.
#[track_caller]
fn breaks(bytes: &[u8], rule: u8, section: &str, offset: u64, words: &str) {
    let e = format_error(bytes);
    assert_eq!(
        (e.rule, e.section.as_str(), e.offset),
        (Rule(rule), section, offset),
        "{}",
        e.message
    );
    assert!(e.message.contains(words), "{:?} lacks {words:?}", e.message);
}

// ---------------------------------------------------------------------------------------
// Section tables: header words and arrays as u32 values, to change counts and join again.

struct Tables {
    head: Vec<u32>,
    arrays: Vec<Vec<u32>>,
    widths: Vec<usize>,
}

impl Tables {
    fn split(p: &[u8], head_len: usize, layout: &Layout) -> Tables {
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

    fn lrtb(p: &[u8]) -> Tables {
        Tables::split(p, LrtbHeader::LEN, &LrtbHeader::read(p).layout().unwrap())
    }

    fn lrbe(p: &[u8]) -> Tables {
        Tables::split(p, LrbeHeader::LEN, &LrbeHeader::read(p).layout().unwrap())
    }

    fn array(&mut self, index: usize) -> &mut Vec<u32> {
        &mut self.arrays[index]
    }

    fn join(&self) -> Vec<u8> {
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
const LR: usize = 3;
const VO_V: usize = 4;
const VO_O: usize = 5;
const VO_STAR: usize = 6;
const LRTB_C: usize = 7;
const PAIRS: usize = 3;
const BLOCKS: usize = 4;
const LRBE_C: usize = 6;
const OVERFLOW: usize = 7;
const ROWS: usize = 8;
const RECORDS: usize = 9;

/// File offset of element `i` of array `name` of `LRTB`.
fn lrtb_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::LRTB);
    section_at(bytes, Tag::LRTB) + LrtbHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// File offset of element `i` of array `name` of `LRBE`.
fn lrbe_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::LRBE);
    section_at(bytes, Tag::LRBE) + LrbeHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// File offset of element `i` of array `name` of `STRP`.
fn strp_at(bytes: &[u8], name: &str, i: usize) -> u64 {
    let p = payload(bytes, Tag::STRP);
    section_at(bytes, Tag::STRP) + StrpHeader::read(&p).layout().unwrap().array(name).at(i) as u64
}

/// Byte offset within `LRTB` of element `i` of array `index`.
fn lrtb_word(p: &[u8], index: usize, i: usize) -> usize {
    LrtbHeader::read(p).layout().unwrap().arrays[index].at(i)
}

/// Byte offset within `LRBE` of element `i` of array `index`.
fn lrbe_word(p: &[u8], index: usize, i: usize) -> usize {
    LrbeHeader::read(p).layout().unwrap().arrays[index].at(i)
}

/// Byte offset within `STRP` of `T[i]`, `A[i]` or `C[i]`.
fn strp_word(p: &[u8], name: &str, i: usize) -> usize {
    StrpHeader::read(p).layout().unwrap().array(name).at(i)
}

fn set_lrtb(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrtb_word(p, index, i);
    put(p, at, x)
}

fn set_lrbe(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrbe_word(p, index, i);
    put(p, at, x)
}

fn set_lrbe16(p: &mut [u8], index: usize, i: usize, x: u32) {
    let at = lrbe_word(p, index, i);
    put16(p, at, x)
}

fn set_strp(p: &mut [u8], name: &str, i: usize, x: u32) {
    let at = strp_word(p, name, i);
    put(p, at, x)
}

/// The T0 triangle (row) `j` of an LR container whose three corners have no opposite.
fn lone_t0_triangle(bytes: &[u8]) -> usize {
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

/// The corners of `v`, and the one that starts its fan if the fan is open.
fn fan_of<M: CornerOps>(mesh: &M, v: u32) -> (Vec<Corner>, Option<Corner>) {
    let corners: Vec<Corner> = mesh
        .corners()
        .filter(|&c| mesh.vertex(c) == Vertex(v))
        .collect();
    let start = corners.iter().copied().find(|&c| mesh.unswing(c).is_none());
    (corners, start)
}

/// A vertex of `mesh` among `vertices` whose fan is open and has a corner other than its
/// start: `(v, that corner)`.
fn open_fan<M: CornerOps>(mesh: &M, vertices: std::ops::Range<u32>) -> (u32, Corner) {
    vertices
        .filter_map(|v| {
            let (corners, start) = fan_of(mesh, v);
            let start = start?;
            corners.into_iter().find(|&c| c != start).map(|c| (v, c))
        })
        .next()
        .expect("a vertex with an open fan of two corners")
}

// ---------------------------------------------------------------------------------------
// §2.1 Header.

/// [V1] At least 32 bytes, starting with the magic.
#[test]
fn v01_short_file_or_bad_magic() {
    let bytes = vector("closed_tetrahedron.lrm");
    breaks(&bytes[..31], 1, "header", 0, "shorter");
    breaks(&[], 1, "header", 0, "shorter");
    for at in 0..8 {
        let bad = patch(&bytes, |b| b[at] ^= 0x20);
        breaks(&bad, 1, "header", 0, "magic");
    }
}

/// [V2] Major version 1, with a distinct error; any minor version is accepted.
#[test]
fn v02_other_major_version() {
    let bytes = vector("closed_tetrahedron.lrm");
    for major in [0u16, 2, 0xFFFF] {
        let bad = patch(&bytes, |b| b[8..10].copy_from_slice(&major.to_le_bytes()));
        match open(&bad, &Limits::default()) {
            Err(Error::UnsupportedVersion {
                major: m,
                minor: 0,
                supported: 1,
            }) => assert_eq!(m, major),
            other => panic!("major {major}: {other:?}"),
        }
    }
    let later_minor = patch(&bytes, |b| b[10..12].copy_from_slice(&7u16.to_le_bytes()));
    assert_eq!(
        open(&later_minor, &Limits::default())
            .unwrap()
            .sections
            .minor,
        7
    );
}

/// [V3] The file length field equals the file's length; the reserved field is 0.
#[test]
fn v03_file_length_and_reserved() {
    let bytes = vector("closed_tetrahedron.lrm");
    let len = bytes.len() as u64;
    for wrong in [len - 1, len + 1, 0, u64::MAX] {
        let bad = patch(&bytes, |b| b[16..24].copy_from_slice(&wrong.to_le_bytes()));
        breaks(&bad, 3, "header", 16, "file length");
    }
    let bad = patch(&bytes, |b| put(b, 28, 1));
    breaks(&bad, 3, "header", 28, "reserved");
}

/// [V4] The section table fits the file; this crate reads at most 64 sections.
#[test]
fn v04_section_table_past_the_end() {
    let bytes = vector("closed_tetrahedron.lrm");
    // 427 bytes hold a header and 12 entries, not 13.
    let bad = patch(&bytes, |b| put(b, 12, 13));
    breaks(&bad, 4, "section table", 32, "entries need");
    match open(&patch(&bytes, |b| put(b, 12, 65)), &Limits::default()) {
        Err(Error::LimitExceeded {
            what: "section count",
            value: 65,
            limit: 64,
        }) => {}
        other => panic!("{other:?}"),
    }
}

/// [V5] The header CRC matches.
#[test]
fn v05_header_checksum() {
    let bytes = vector("closed_tetrahedron.lrm");
    let mut bad = bytes.clone();
    bad[24] ^= 1;
    breaks(&bad, 5, "header", 24, "checksum");
    // Bytes the CRC covers, changed without it: the minor version, entry fields.
    for at in [10, 11, 36, 40, 64, 32 + 32 * 4 + 16, 32 + 32 * 4 + 28] {
        let mut bad = bytes.clone();
        bad[at] ^= 0x40;
        breaks(&bad, 5, "header", 24, "checksum");
    }
}

// ---------------------------------------------------------------------------------------
// §2.2 Section table.

/// [V6] Payloads are contiguous, in table order, from the end of the table to the end of
/// the file.
#[test]
fn v06_payloads_contiguous() {
    let bytes = vector("closed_tetrahedron.lrm"); // 5 sections, payloads from 192
    let len = bytes.len() as u64;
    let offset_of =
        |b: &[u8], i: usize| u64::from_le_bytes(b[40 + 32 * i..48 + 32 * i].try_into().unwrap());
    let set_u64 =
        |b: &mut Vec<u8>, at: usize, x: u64| b[at..at + 8].copy_from_slice(&x.to_le_bytes());
    // The first payload does not start at 32 + 32 S.
    let bad = patch(&bytes, |b| set_u64(b, 40, 193));
    breaks(&bad, 6, "section table", entry_at(0, 8), "expected 192");
    // A gap before section 2.
    let bad = patch(&bytes, |b| {
        let x = offset_of(b, 2) + 1;
        set_u64(b, 40 + 64, x)
    });
    breaks(&bad, 6, "section table", entry_at(2, 8), "contiguous");
    // Section 1 overlaps section 2 (its longer body checksummed, so that V8 holds).
    let bad = patch(&bytes, |b| {
        let (start, len) = (offset_of(b, 1) as usize, get(b, 32 + 32 + 16) as usize + 4);
        put(b, 32 + 32 + 16, len as u32);
        let crc = lrmesh::format::section_checksum(&b[start..start + len]);
        put(b, 32 + 32 + 24, crc);
    });
    breaks(&bad, 6, "section table", entry_at(2, 8), "contiguous");
    // The last payload runs past the end of the file.
    let bad = patch(&bytes, |b| put(b, 32 + 4 * 32 + 16, 41));
    breaks(&bad, 6, "section table", entry_at(4, 16), "past the end");
    // Trailing bytes after the last payload.
    let bad = patch(&bytes, |b| {
        b.extend_from_slice(&[0, 0, 0]);
        b[16..24].copy_from_slice(&(len + 3).to_le_bytes());
    });
    breaks(&bad, 6, "file", len, "after the last section");
    // The last payload ends one byte early (its shorter body checksummed).
    let bad = patch(&bytes, |b| {
        put(b, 32 + 4 * 32 + 16, 39);
        let start = offset_of(b, 4) as usize;
        let crc = lrmesh::format::section_checksum(&b[start..start + 39]);
        put(b, 32 + 4 * 32 + 24, crc);
    });
    breaks(&bad, 6, "file", len - 1, "after the last section");
}

/// [V7] No flag but REQUIRED; reserved fields of entries are 0.
#[test]
fn v07_entry_flags_and_reserved() {
    let bytes = vector("closed_tetrahedron.lrm");
    for (i, flags) in [(0, 2u32), (1, 3), (4, 0x8000_0000)] {
        let bad = patch(&bytes, |b| put(b, entry_at(i, 4) as usize, flags));
        breaks(&bad, 7, "section table", entry_at(i, 4), "unknown flags");
    }
    let bad = patch(&bytes, |b| put(b, entry_at(3, 28) as usize, 1));
    breaks(&bad, 7, "section table", entry_at(3, 28), "reserved");
}

/// [V8] Each payload's CRC matches.
#[test]
fn v08_payload_checksum() {
    let bytes = vector("closed_tetrahedron.lrm");
    for tag in [Tag::META, Tag::MESH, Tag::GEOM, Tag::LRTB, Tag::PERM] {
        let at = section_at(&bytes, tag);
        let mut bad = bytes.clone();
        bad[at as usize + 1] ^= 4;
        breaks(&bad, 8, &tag.name(), at, "checksum");
        // Or the stored CRC itself.
        let i = index_of(&bytes, tag);
        let bad = patch(&bytes, |b| b[entry_at(i, 24) as usize] ^= 1);
        breaks(&bad, 8, &tag.name(), at, "checksum");
    }
}

/// [V9] No tag appears twice.
#[test]
fn v09_duplicate_tag() {
    let bytes = vector("closed_tetrahedron.lrm");
    let bad = forge_sections(&bytes, |s| {
        let meta = s[0].clone();
        s.push(meta);
    });
    breaks(&bad, 9, "section table", entry_at(5, 0), "twice");
    let bad = forge_sections(&bytes, |s| s.insert(3, s[2].clone()));
    breaks(
        &bad,
        9,
        "section table",
        entry_at(3, 0),
        "GEOM appears twice",
    );
}

/// [V10] An unknown section is skipped when optional and rejects the file when required;
/// a known section is read whatever its flag.
#[test]
fn v10_unknown_required_section() {
    let bytes = vector("closed_tetrahedron.lrm");
    let unknown = |flags| {
        forge_sections(&bytes, |s| {
            s.insert(2, (Tag(*b"XTRA"), flags, b"later".to_vec()))
        })
    };
    open(&unknown(Flags::NONE), &Limits::default()).unwrap();
    match open(&unknown(Flags::REQUIRED), &Limits::default()) {
        Err(Error::UnknownRequiredSection { tag, index: 2 }) => assert_eq!(tag, "XTRA"),
        other => panic!("{other:?}"),
    }
    // A known section without REQUIRED is still validated; META with it is still read.
    let flags_cleared = forge_sections(&bytes, |s| {
        for section in s.iter_mut() {
            section.1 = Flags::NONE;
        }
        s[0].1 = Flags::REQUIRED;
    });
    assert!(open(&flags_cleared, &Limits::default())
        .unwrap()
        .metadata
        .is_some());
    let bad = forge_sections(&flags_cleared, |s| {
        put(&mut s[1].2, MeshRecord::RESERVED_AT, 1)
    });
    breaks(&bad, 12, "MESH", section_at(&bad, Tag::MESH) + 20, "");
}

// ---------------------------------------------------------------------------------------
// §3 Sections around the connectivity.

/// [V11] `META` is a JSON object with a string `generator`; this crate reads at most 1 MiB.
#[test]
fn v11_metadata() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::META);
    for json in [
        &b"not json"[..],
        b"[1, 2]",
        b"{\"source\": \"x.off\"}",
        b"{\"generator\": 5}",
        b"{\"generator\": \"g\", \"extra\": {\"k\": 1}}",
        b"\xff\xfe",
    ] {
        let bad = forge(&bytes, Tag::META, |p| *p = json.to_vec());
        breaks(&bad, 11, "META", at, "metadata");
    }
    let later = forge(&bytes, Tag::META, |p| {
        *p = b"{\"generator\": \"g\", \"later\": [1]}".to_vec()
    });
    open(&later, &Limits::default()).unwrap();
    let limits = Limits {
        max_metadata_bytes: 10,
        ..Limits::default()
    };
    match open(&bytes, &limits) {
        Err(Error::LimitExceeded {
            what: "metadata size",
            value: 35,
            limit: 10,
        }) => {}
        other => panic!("{other:?}"),
    }
}

/// [V12] `MESH`: length 24, a known kind, reserved 0, `W ≤ V`, `W = V − copies`, `N` the
/// connectivity's triangles, `K` the kept ones.
#[test]
fn v12_mesh_counts() {
    let tetra = vector("closed_tetrahedron.lrm");
    let at = section_at(&tetra, Tag::MESH);
    let mesh_field =
        |bytes: &[u8], field: usize, x: u32| forge(bytes, Tag::MESH, |p| put(p, field, x));
    breaks(&forge(&tetra, Tag::MESH, |p| p.push(0)), 12, "MESH", at, "");
    let bad = forge(&tetra, Tag::MESH, |p| p.truncate(20));
    breaks(&bad, 12, "MESH", at, "");
    for kind in [0, 5, u32::MAX] {
        breaks(&mesh_field(&tetra, 16, kind), 12, "MESH", at + 16, "kind");
    }
    breaks(&mesh_field(&tetra, 20, 1), 12, "MESH", at + 20, "reserved");
    breaks(&mesh_field(&tetra, 4, 5), 12, "MESH", at + 4, "");
    // W = V − copies: one copy in this vector (V = 9, W = 8).
    let copies = vector("nonmanifold_vertex.lrm");
    let at_copies = section_at(&copies, Tag::MESH);
    for w in [9, 7] {
        let bad = mesh_field(&copies, 4, w);
        breaks(&bad, 12, "MESH", at_copies + 4, "copies");
    }
    // K: one kept triangle in that vector, none in the tetrahedron.
    let bad = mesh_field(&copies, 12, 0);
    breaks(&bad, 12, "MESH", at_copies + 12, "KEPT");
    breaks(&mesh_field(&tetra, 12, 1), 12, "MESH", at + 12, "KEPT");
    // N, for every kind (for EBRK, [V27] says the same).
    for connectivity in [
        Connectivity::Lr,
        Connectivity::Edgebreaker,
        Connectivity::Strips,
        Connectivity::LrCompact,
    ] {
        let bytes = encoded(&torus(), connectivity);
        let at = section_at(&bytes, Tag::MESH);
        for n in [39, 41, 0] {
            let bad = mesh_field(&bytes, 8, n);
            breaks(&bad, 12, "MESH", at + 8, "connectivity holds");
        }
    }
}

/// [V13] `GEOM`: its length, finite values, `lo ≤ hi`, a known encoding, reserved 0.
#[test]
fn v13_positions() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::GEOM);
    let bad = forge(&bytes, Tag::GEOM, |p| p.extend([0; 4]));
    breaks(&bad, 13, "GEOM", at, "");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(8 + 12 * 3));
    breaks(&bad, 13, "GEOM", at, "");
    let bad = forge(&bytes, Tag::GEOM, |p| p.truncate(3));
    breaks(&bad, 13, "GEOM", at, "");
    for x in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        // Vertex 2, coordinate 1.
        let bad = forge(&bytes, Tag::GEOM, |p| put(p, 8 + 24 + 4, x.to_bits()));
        breaks(&bad, 13, "GEOM", at + 36, "non-finite");
    }
    let bad = forge(&bytes, Tag::GEOM, |p| put(p, 4, 1));
    breaks(&bad, 13, "GEOM", at + 4, "reserved");
    for encoding in [2, u32::MAX] {
        let bad = forge(&bytes, Tag::GEOM, |p| put(p, 0, encoding));
        breaks(&bad, 13, "GEOM", at, "encoding");
    }
    // Encoding 1: box at 8 (lo) and 20 (hi), then 6 bytes a vertex.
    let q = encode(
        &torus(),
        &EncodeOptions {
            quantize16: true,
            ..EncodeOptions::default()
        },
    )
    .unwrap();
    let at = section_at(&q, Tag::GEOM);
    let bad = forge(&q, Tag::GEOM, |p| p.extend([0; 2]));
    breaks(&bad, 13, "GEOM", at, "");
    for k in 0..3 {
        let bad = forge(&q, Tag::GEOM, |p| {
            put(p, 8 + 4 * k, 5.0f32.to_bits());
            put(p, 20 + 4 * k, (-5.0f32).to_bits());
        });
        breaks(&bad, 13, "GEOM", at + 8 + 4 * k as u64, "minimum above");
        for field in [8, 20] {
            let bad = forge(&q, Tag::GEOM, |p| put(p, field + 4 * k, f32::NAN.to_bits()));
            breaks(&bad, 13, "GEOM", at + (field + 4 * k) as u64, "non-finite");
        }
    }
    let bad = forge(&q, Tag::GEOM, |p| put(p, 4, 1));
    breaks(&bad, 13, "GEOM", at + 4, "reserved");
}

/// [V14] `NORM`, `TEXC`, `COLR`: lengths `12V`, `8V`, `4V`; finite values.
#[test]
fn v14_attributes() {
    let mut mesh = torus();
    let n = mesh.positions.len();
    mesh.normals = Some(vec![[0.0, 0.0, 1.0]; n]);
    mesh.texcoords = Some(vec![[0.5, 0.5]; n]);
    mesh.colors = Some(vec![[1, 2, 3, 4]; n]);
    let bytes = encoded(&mesh, Connectivity::Lr);
    for (tag, size) in [(Tag::NORM, 12), (Tag::TEXC, 8), (Tag::COLR, 4)] {
        let at = section_at(&bytes, tag);
        let bad = forge(&bytes, tag, |p| p.extend([0; 4]));
        breaks(&bad, 14, &tag.name(), at, "");
        let bad = forge(&bytes, tag, |p| p.truncate(size * (n - 1)));
        breaks(&bad, 14, &tag.name(), at, "");
        if tag != Tag::COLR {
            let field = size * 3 + 4;
            let bad = forge(&bytes, tag, |p| put(p, field, f32::INFINITY.to_bits()));
            breaks(&bad, 14, &tag.name(), at + field as u64, "non-finite");
        }
    }
    // Colors are bytes: any value is valid.
    let any_color = forge(&bytes, Tag::COLR, |p| put(p, 8, u32::MAX));
    open(&any_color, &Limits::default()).unwrap();
}

// ---------------------------------------------------------------------------------------
// §3.5 LRTB.

/// [V15] `LRTB` counts and length. (`m < 0x3FFFFFFF` cannot be broken alone: `m = V`, and
/// `GEOM` would need `12 V` bytes first.)
#[test]
fn v15_lrtb_counts() {
    let bytes = vector("closed_tetrahedron.lrm"); // m = m_r = 4, R = 1, n0 = ni = 0
    let at = section_at(&bytes, Tag::LRTB);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRTB, |p| put(p, f, x));
    breaks(&field(0, 5), 15, "LRTB", at, "section MESH says 4");
    breaks(&field(0, 3), 15, "LRTB", at, "section MESH says 4");
    breaks(&field(20, 1), 15, "LRTB", at + 20, "reserved");
    // m_r > m; R = 0 iff m_r = 0; 4R ≤ m_r.
    for m_r in [5, 0, 3] {
        breaks(&field(4, m_r), 15, "LRTB", at + 4, "ring vertices");
    }
    // 8 m_r + 4 n0 < 2^32 − 1.
    breaks(&field(12, 0x4000_0000), 15, "LRTB", at + 12, "32 bits");
    breaks(&field(12, 0x3FFF_FFF8), 15, "LRTB", at + 12, "32 bits");
    // Length: 32 + 4 (R + 1 + 2⌈m_r/32⌉ + 2 m_r + 6 n0 + 3 ni + m − m_r).
    let bad = forge(&bytes, Tag::LRTB, |p| p.extend([0; 4]));
    breaks(&bad, 15, "LRTB", at, "counts call for");
    let bad = forge(&bytes, Tag::LRTB, |p| p.truncate(76));
    breaks(&bad, 15, "LRTB", at, "counts call for");
    let bad = forge(&bytes, Tag::LRTB, |p| p.truncate(31));
    breaks(&bad, 15, "LRTB", at, "header");
    breaks(&field(12, 1), 15, "LRTB", at, "counts call for");
}

/// [V15] The reserved words at 24 and 28 and the record count at 16 are located at their own
/// fields.
#[test]

fn v15_lrtb_fields_located_exactly() {
    let bytes = vector("closed_tetrahedron.lrm");
    let at = section_at(&bytes, Tag::LRTB);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRTB, |p| put(p, f, x));
    breaks(&field(24, 1), 15, "LRTB", at + 24, "");
    breaks(&field(28, 1), 15, "LRTB", at + 28, "");
    breaks(&field(16, NULL), 15, "LRTB", at + 16, "");
}

/// [V16] Rings: starts from 0 by at least 4 to `m_r`; `ring_last`, `ring_rank` as implied,
/// padding bits 0; `[0]` without ring vertices.
#[test]
fn v16_rings() {
    let two = vector("two_components.lrm"); // ring_starts [0, 4, 8], ring_last [0x88]
    let starts = |i: usize| lrtb_at(&two, "ring_starts", i);
    let word = |bytes: &[u8], name: &str, i: usize, x: u32| {
        forge(bytes, Tag::LRTB, |p| {
            let at = LrtbHeader::read(p).layout().unwrap().array(name).at(i);
            put(p, at, x)
        })
    };
    let bad = word(&two, "ring_starts", 0, 1);
    breaks(&bad, 16, "LRTB", starts(0), "ring start 1");
    let bad = word(&two, "ring_starts", 1, 3);
    breaks(&bad, 16, "LRTB", starts(1), "ring start 3");
    let bad = word(&two, "ring_starts", 1, 5);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 8");
    let bad = word(&two, "ring_starts", 2, 9);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 9");
    let bad = word(&two, "ring_starts", 2, 7);
    breaks(&bad, 16, "LRTB", starts(2), "ring start 7");
    let last = lrtb_at(&two, "ring_last", 0);
    for bits in [0x08, 0x80, 0x89, 0x88 | 1 << 8, 0x88 | 1 << 31] {
        let bad = word(&two, "ring_last", 0, bits);
        breaks(&bad, 16, "LRTB", last, "ring-end bits");
    }
    let rank = lrtb_at(&two, "ring_rank", 0);
    let bad = word(&two, "ring_rank", 0, 1);
    breaks(&bad, 16, "LRTB", rank, "ring ranks");
    // No ring vertices: ring_starts is [0].
    let empty = encoded(&Mesh::new(vec![[0.0; 3]; 3], vec![]), Connectivity::Lr);
    assert_eq!(LrtbHeader::read(&payload(&empty, Tag::LRTB)).m_r, 0);
    let at = lrtb_at(&empty, "ring_starts", 0);
    breaks(&word(&empty, "ring_starts", 0, 3), 16, "LRTB", at, "[0]");
}

/// [V17] LR entries: records in range, used once, tips below `m`; plain values below `m` or
/// `NULL` in a right entry without WART; every record used.
#[test]
fn v17_lr_entries() {
    let bytes = vector("torus_with_t0.lrm"); // m = m_r = 25, 10 records
    let p = payload(&bytes, Tag::LRTB);
    let h = LrtbHeader::read(&p);
    let entry = |slot: usize| get(&p, lrtb_word(&p, LR, slot));
    let entry_at = |slot: usize| lrtb_at(&bytes, "LR", slot);
    let set = |slot: usize, x: u32| forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, slot, x));
    let irregular: Vec<usize> = (0..50).filter(|&s| entry(s) & IRREGULAR != 0).collect();
    let plain: Vec<usize> = (0..50)
        .filter(|&s| entry(s) & (IRREGULAR | WART) == 0)
        .collect();
    assert!(irregular.len() >= 2);
    let (s1, s2) = (irregular[0], irregular[1]);
    // A record beyond ni, and one used twice (reported at its second user).
    let bad = set(s1, IRREGULAR | h.records);
    breaks(&bad, 17, "LRTB", entry_at(s1), "missing or used twice");
    let bad = set(s2, (entry(s2) & WART) | IRREGULAR | (entry(s1) & VALUE));
    breaks(&bad, 17, "LRTB", entry_at(s2), "missing or used twice");
    // Plain values out of range; NULL on the left, or with WART on the right.
    let (left, right) = (
        *plain.iter().find(|&&s| s % 2 == 0).unwrap(),
        *plain.iter().find(|&&s| s % 2 == 1).unwrap(),
    );
    for x in [25, 26, NULL - 1] {
        breaks(&set(left, x), 17, "LRTB", entry_at(left), "out of range");
        breaks(&set(right, x), 17, "LRTB", entry_at(right), "out of range");
    }
    breaks(&set(left, NULL), 17, "LRTB", entry_at(left), "out of range");
    let bad = set(right, WART | NULL);
    breaks(&bad, 17, "LRTB", entry_at(right), "out of range");
    // A record no entry uses: one appended to VO*.
    let mut t = Tables::lrtb(&p);
    t.head[4] += 1;
    t.array(VO_STAR).extend([0, NONE, NONE]);
    let bad = forge(&bytes, Tag::LRTB, |p| *p = t.join());
    let at = lrtb_at(&bad, "VO*", 3 * h.records as usize);
    breaks(&bad, 17, "LRTB", at, "not used by any entry");
}

/// [V17] A record's tip out of range is located at the record's tip word.
#[test]

fn v17_record_tip_located_at_the_record() {
    let bytes = vector("torus_with_t0.lrm");
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_STAR, 0, 25));
    breaks(&bad, 17, "LRTB", lrtb_at(&bytes, "VO*", 0), "");
}

/// [V18] `VO_V` entries are below `m`.
#[test]
fn v18_t0_vertices() {
    let bytes = vector("torus_with_t0.lrm"); // 4 T0 triangles
    for (i, x) in [(0, 25), (5, 26), (11, NONE)] {
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_V, i, x));
        breaks(&bad, 18, "LRTB", lrtb_at(&bytes, "VO_V", i), "out of range");
    }
}

/// [V19] A redundant or WART slot's next slot on the same side holds a canonical triangle.
#[test]
fn v19_redundant_and_wart_slots() {
    // Ring 0 → 1 → 2 → 3: L = [3, 3, 1, 1]; L[1] and L[3] are redundant copies.
    let bytes = vector("closed_tetrahedron.lrm");
    let at = lrtb_at(&bytes, "LR", 0);
    // L[0] = 2 = 0.n.n: slot 0 turns redundant, and slot (1, LEFT) is redundant too.
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, 2));
    breaks(&bad, 19, "LRTB", at, "slot 0 points to slot 2");
    // A WART on slot 0, whose next slot (1, LEFT) is redundant.
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, WART | 3));
    breaks(&bad, 19, "LRTB", at, "slot 0 points to slot 2");
    // A WART on a right slot whose next right slot is NULL (a boundary ring edge).
    let open_hedra = vector("boundary_hedra_open.lrm");
    let view = open(&open_hedra, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let v = (0..6)
        .find(|&v| lr.tip(v, 1) != NULL && lr.tip(lr.ring_next(v), 1) == NULL)
        .unwrap() as usize;
    let bad = forge(&open_hedra, Tag::LRTB, |p| {
        let at = lrtb_word(p, LR, 2 * v + 1);
        let x = get(p, at) | WART;
        put(p, at, x)
    });
    breaks(
        &bad,
        19,
        "LRTB",
        lrtb_at(&open_hedra, "LR", 2 * v + 1),
        "holds no canonical triangle",
    );
}

/// [V20] `VO_O`, `C` and the opposites of `VO*` hold `NONE` or canonical corners.
#[test]
fn v20_stored_corners() {
    let bytes = vector("defective_torus.lrm"); // m_r = 16: corners 0..128 and T0 corners
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    // 3 (c & 3 = 3), a corner of a redundant or missing slot, one past the last T0 corner.
    let redundant = (0..128)
        .find(|&c| c & 3 != 3 && !lr.is_corner(Corner(c)))
        .unwrap();
    let past = 8 * 16 + 4 * 5;
    for x in [3, redundant, past, NONE - 1] {
        for (index, name, i) in [
            (VO_O, "VO_O", 4),
            (VO_STAR, "VO*", 1),
            (VO_STAR, "VO*", 5),
            (LRTB_C, "C", 0),
        ] {
            let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, index, i, x));
            breaks(&bad, 20, "LRTB", lrtb_at(&bytes, name, i), "not a corner");
        }
    }
}

/// [V21] No canonical triangle has two equal vertices.
#[test]
fn v21_degenerate_triangles() {
    // Slot 0 of the tetrahedron is (0, L[0], 1): its tip made 1 or 0.
    let bytes = vector("closed_tetrahedron.lrm");
    for tip in [0, 1] {
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 0, tip));
        breaks(&bad, 21, "LRTB", lrtb_at(&bytes, "LR", 0), "degenerate");
    }
    // A T0 triangle with its second vertex made its first: one whose corners all lack an
    // opposite (a triangle left alone by the cuts), so that no opposite check sees it first.
    let t0 = vector("defective_torus.lrm");
    let j = lone_t0_triangle(&t0);
    let p = payload(&t0, Tag::LRTB);
    let first = get(&p, lrtb_word(&p, VO_V, 3 * j));
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_V, 3 * j + 1, first));
    breaks(&bad, 21, "LRTB", lrtb_at(&t0, "VO_V", 3 * j), "degenerate");
}

/// [V22] `c.o` is an involution across one edge: `o.o = c`, `o.n.v = c.p.v`,
/// `o.p.v = c.n.v`. (`o` is a canonical corner whenever [V17], [V19] and [V20] hold.)
#[test]
fn v22_opposites() {
    // The tetrahedron's L[1] = 3 made 0: slot 2 becomes (1, 0, 2), whose corner 10 the
    // ring rules pair with corner 12 of slot 3 across an edge they do not share.
    let bytes = vector("closed_tetrahedron.lrm");
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LR, 2, 0));
    breaks(
        &bad,
        22,
        "LRTB",
        lrtb_at(&bytes, "LR", 2),
        "corner 10 and its opposite 12",
    );
    // o.o ≠ c: a T0 corner's stored opposite replaced by a later corner that is not paired
    // with it; the pair is checked from the smaller corner, the T0 corner.
    let t0 = vector("torus_with_t0.lrm");
    let view = open(&t0, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let first_t0 = 8 * lr.ring_vertices();
    let (k, c) = (0..12u32)
        .map(|k| (k, Corner(first_t0 + k / 3 * 4 + k % 3)))
        .find(|&(_, c)| lr.opposite(c).is_some_and(|o| o.0 > c.0))
        .unwrap();
    let other = lr
        .corners()
        .find(|&o| o.0 > c.0 && lr.opposite(o) != Some(c) && lr.opposite(c) != Some(o))
        .unwrap();
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, other.0));
    breaks(
        &bad,
        22,
        "LRTB",
        lrtb_at(&t0, "VO_V", k as usize),
        "do not face each other",
    );
    // o.o = c but not across one edge: a T0 corner made its own opposite.
    let (k, c) = (0..12u32)
        .map(|k| (k, Corner(first_t0 + k / 3 * 4 + k % 3)))
        .find(|&(_, c)| lr.opposite(c).is_none_or(|o| o.0 > c.0))
        .unwrap();
    let bad = forge(&t0, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, c.0));
    let message = format!("corner {} and its opposite {}", c.0, c.0);
    breaks(&bad, 22, "LRTB", lrtb_at(&t0, "VO_V", k as usize), &message);
}

/// [V22] A corner whose opposite is a smaller corner that does not point back is located
/// at that corner.
#[test]

fn v22_opposite_not_pointing_back_is_located() {
    // A T0 corner c whose opposite o is larger, given NONE: o.o = c no longer points back,
    // and o is the corner at fault.
    let bytes = vector("torus_with_t0.lrm");
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let m_r = lr.ring_vertices();
    let (k, o) = (0..12u32)
        .map(|k| (k, Corner(8 * m_r + k / 3 * 4 + k % 3)))
        .find_map(|(k, c)| lr.opposite(c).filter(|o| o.0 > c.0).map(|o| (k, o)))
        .unwrap();
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, VO_O, k as usize, NONE));
    let at = if o.0 >= 8 * m_r {
        lrtb_at(&bytes, "VO_V", (o.0 - o.0 / 4 - 6 * m_r) as usize)
    } else {
        lrtb_at(
            &bytes,
            "LR",
            2 * (o.0 as usize >> 3) + (o.0 as usize >> 2 & 1),
        )
    };
    breaks(&bad, 22, "LRTB", at, "");
}

/// [V23] `v.c.v = v`.
#[test]
fn v23_vertex_corner_is_its_own() {
    let bytes = vector("defective_torus.lrm"); // off-ring vertices 16..23, C at their words
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    for i in [0, 2, 6] {
        let v = 16 + i as u32;
        let c = lr.corners().find(|&c| lr.vertex(c).0 != v).unwrap();
        let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, i, c.0));
        breaks(
            &bad,
            23,
            "LRTB",
            lrtb_at(&bytes, "C", i),
            "is a corner of vertex",
        );
    }
    // An unreferenced vertex (C[1] = NONE) given a corner: of another vertex, necessarily.
    let c = lr.corners().next().unwrap();
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, 1, c.0));
    breaks(
        &bad,
        23,
        "LRTB",
        lrtb_at(&bytes, "C", 1),
        "the corner of vertex 17",
    );
}

// ---------------------------------------------------------------------------------------
// §3.6–3.8 COPY, KEPT, PERM.

/// [V24] `COPY`: length `4 + 8k`; ids below `V`; copies increasing; originals not copies.
#[test]
fn v24_copies() {
    let bytes = vector("defective_torus.lrm"); // V = 23, three copies
    let at = section_at(&bytes, Tag::COPY);
    let p = payload(&bytes, Tag::COPY);
    assert_eq!(get(&p, 0), 3);
    let word = |f: usize, x: u32| forge(&bytes, Tag::COPY, |p| put(p, f, x));
    let bad = forge(&bytes, Tag::COPY, |p| p.extend([0; 8]));
    breaks(&bad, 24, "COPY", at, "");
    breaks(&word(0, 2), 24, "COPY", at, "");
    breaks(&word(0, 4), 24, "COPY", at, "");
    let bad = forge(&bytes, Tag::COPY, |p| p.truncate(3));
    breaks(&bad, 24, "COPY", at, "");
    // A copy id out of range, copies not increasing (pair 1 given pair 0's copy).
    breaks(&word(4 + 8 * 2, 23), 24, "COPY", at + 4 + 16, "below 23");
    let bad = word(4 + 8, get(&p, 4));
    breaks(&bad, 24, "COPY", at + 4 + 8, "increasing");
    // An original that is itself a copy.
    let bad = word(4 + 8 * 2 + 4, get(&p, 4));
    breaks(&bad, 24, "COPY", at + 4 + 16 + 4, "itself a copy");
}

/// [V24] An original out of range is located at the original's word.
#[test]

fn v24_original_out_of_range_located() {
    let bytes = vector("defective_torus.lrm");
    let at = section_at(&bytes, Tag::COPY);
    let bad = forge(&bytes, Tag::COPY, |p| put(p, 4 + 4, 23));
    breaks(&bad, 24, "COPY", at + 8, "");
}

/// [V25] `KEPT`: length `4 + 12k`; ids below `V`.
#[test]
fn v25_kept_triangles() {
    let bytes = vector("nonmanifold_vertex.lrm"); // V = 9, one kept triangle
    let at = section_at(&bytes, Tag::KEPT);
    let bad = forge(&bytes, Tag::KEPT, |p| p.extend([0; 4]));
    breaks(&bad, 25, "KEPT", at, "");
    let bad = forge(&bytes, Tag::KEPT, |p| put(p, 0, 2));
    breaks(&bad, 25, "KEPT", at, "");
    let bad = forge(&bytes, Tag::KEPT, |p| p.truncate(2));
    breaks(&bad, 25, "KEPT", at, "");
    for (i, x) in [(0, 9), (2, NONE)] {
        let bad = forge(&bytes, Tag::KEPT, |p| put(p, 4 + 4 * i, x));
        breaks(&bad, 25, "KEPT", at + 4 + 4 * i as u64, "out of range");
    }
}

/// [V26] `PERM`: counts `W` and `N + K`; length `8 + 4 (W + T)`; two permutations.
#[test]
fn v26_permutations() {
    let bytes = vector("nonmanifold_vertex.lrm"); // W = 8, N + K = 9
    let at = section_at(&bytes, Tag::PERM);
    let p = payload(&bytes, Tag::PERM);
    let word = |f: usize, x: u32| forge(&bytes, Tag::PERM, |p| put(p, f, x));
    breaks(&word(0, 9), 26, "PERM", at, "permutations of 9 vertices");
    let bad = forge(&bytes, Tag::PERM, |p| p.extend([0; 4]));
    breaks(&bad, 26, "PERM", at, "");
    let bad = forge(&bytes, Tag::PERM, |p| p.truncate(p.len() - 4));
    breaks(&bad, 26, "PERM", at, "");
    // Vertex list: a repeat, a value out of range; triangle list the same.
    let (vertices, triangles) = (8usize, 8 + 4 * 8usize);
    let bad = word(vertices + 4, get(&p, vertices));
    breaks(&bad, 26, "PERM", at + 12, "permutation");
    let bad = word(vertices + 28, 8);
    breaks(&bad, 26, "PERM", at + 8 + 28, "permutation");
    let bad = word(triangles + 8, get(&p, triangles));
    breaks(&bad, 26, "PERM", at + 40 + 8, "permutation");
    breaks(&word(triangles, 9), 26, "PERM", at + 40, "permutation");
}

/// [V26] A wrong triangle count is located at its own field, offset 4.
#[test]

fn v26_triangle_count_located() {
    let bytes = vector("nonmanifold_vertex.lrm");
    let bad = forge(&bytes, Tag::PERM, |p| put(p, 4, 10));
    breaks(&bad, 26, "PERM", section_at(&bytes, Tag::PERM) + 4, "");
}

// ---------------------------------------------------------------------------------------
// §3.5b EBRK.

/// [V27] The stream is valid by EDGEBREAKER.md, decodes to `V` vertices, and to no
/// degenerate triangle. (Decoded ids are below `nv − nu ≤ V` in any valid stream, so that
/// clause cannot break alone; `N` is [V12]'s, tested there.)
#[test]
fn v27_edgebreaker_stream() {
    let hedra = lrmesh::load(common::corpus_dir().join("hedra_open.off")).unwrap();
    let bytes = encoded(&hedra, Connectivity::Edgebreaker);
    let at = section_at(&bytes, Tag::EBRK);
    let stream = payload(&bytes, Tag::EBRK);
    // Invalid streams: the stream's own offset is added to the section's.
    let bad = forge(&bytes, Tag::EBRK, |p| p[0] = 0xEA);
    breaks(&bad, 27, "EBRK", at, "magic");
    let bad = forge(&bytes, Tag::EBRK, |p| p[1] = 2);
    breaks(&bad, 27, "EBRK", at + 1, "version");
    let bad = forge(&bytes, Tag::EBRK, |p| p.truncate(4));
    breaks(
        &bad,
        27,
        "EBRK",
        at + 4,
        "header ends inside the triangle count",
    );
    // A valid stream of V + 1 vertices (one more unreferenced).
    assert!(stream[2] < 0x7F && stream[3] < 0x7F);
    let bad = forge(&bytes, Tag::EBRK, |p| {
        p[2] += 1;
        p[3] += 1;
    });
    assert!(lrmesh::edgebreaker::decode(&payload(&bad, Tag::EBRK), &Default::default()).is_ok());
    let e = format_error(&bad);
    assert_eq!(
        (e.rule, e.section.as_str()),
        (Rule(27), "EBRK"),
        "{}",
        e.message
    );
    assert!(e.message.contains("section MESH says 6"), "{}", e.message);
    // A valid stream decoding to a degenerate triangle (tests/container.rs).
    let degenerate = [0xeb, 0x01, 0x06, 0x00, 0x06, 0x02, 0x86, 0xa0, 0x2a];
    let bad = forge(&bytes, Tag::EBRK, |p| *p = degenerate.to_vec());
    breaks(&bad, 27, "EBRK", at, "degenerate");
}

/// [V27] A stream with the wrong vertex count is located at its vertex count `nv`, byte 2
/// of the stream.
#[test]

fn v27_vertex_count_located() {
    let hedra = lrmesh::load(common::corpus_dir().join("hedra_open.off")).unwrap();
    let bytes = encoded(&hedra, Connectivity::Edgebreaker);
    let bad = forge(&bytes, Tag::EBRK, |p| {
        p[2] += 1;
        p[3] += 1;
    });
    breaks(&bad, 27, "EBRK", section_at(&bytes, Tag::EBRK) + 2, "");
}

// ---------------------------------------------------------------------------------------
// §3.5c STRP.

/// [V28] `STRP` counts and length. (`m < 0xFFFFFFFF` cannot break alone: `m = V`.)
#[test]
fn v28_strips_counts() {
    let bytes = vector("closed_tetrahedron.strips.lrm"); // m = 4, L = 8
    let at = section_at(&bytes, Tag::STRP);
    let field = |f: usize, x: u32| forge(&bytes, Tag::STRP, |p| put(p, f, x));
    breaks(&field(0, 5), 28, "STRP", at, "section MESH says 4");
    breaks(&field(8, 1), 28, "STRP", at + 8, "reserved");
    // Odd, or 3 L ≥ 2^32 − 1.
    for len in [7, 9, 0x5555_5556] {
        breaks(&field(4, len), 28, "STRP", at + 4, "even");
    }
    breaks(&field(4, 10), 28, "STRP", at, "counts call for");
    let bad = forge(&bytes, Tag::STRP, |p| p.extend([0; 4]));
    breaks(&bad, 28, "STRP", at, "counts call for");
    let bad = forge(&bytes, Tag::STRP, |p| p.truncate(15));
    breaks(&bad, 28, "STRP", at, "header");
}

/// [V28] The second reserved word is located at offset 12.
#[test]

fn v28_reserved_located() {
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| put(p, 12, 1));
    breaks(&bad, 28, "STRP", section_at(&bytes, Tag::STRP) + 12, "");
}

/// [V29] `T`: strips of at least three vertex ids below `m`, from even positions, each
/// followed by exactly its one or two delimiters; first and last windows triangles; never
/// two swaps in a row.
#[test]
fn v29_strip_layout() {
    // T = 2 0 1 3 2 0 D D.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let t = |i: usize| strp_at(&bytes, "T", i);
    let with = |entries: &[(usize, u32)]| {
        forge(&bytes, Tag::STRP, |p| {
            for &(i, x) in entries {
                let at = strp_word(p, "T", i);
                put(p, at, x)
            }
        })
    };
    breaks(&with(&[(0, NONE)]), 29, "STRP", t(0), "found a delimiter");
    for x in [4, NONE - 1] {
        breaks(&with(&[(3, x)]), 29, "STRP", t(3), "out of range");
    }
    let bad = with(&[(2, NONE), (3, NONE)]);
    breaks(&bad, 29, "STRP", t(0), "fewer than 3");
    let bad = with(&[(7, 1)]);
    breaks(&bad, 29, "STRP", t(7), "followed by 2 delimiters");
    // A strip running to the end of T: its padding would lie past it.
    let a0 = strp_at(&bytes, "A", 0);
    breaks(&with(&[(6, 1), (7, 3)]), 29, "STRP", a0, "padding");
    // First window a swap: 2 2 1 ...
    let bad = with(&[(1, 2)]);
    breaks(&bad, 29, "STRP", t(0), "start and end with a triangle");
    // Two swaps in a row, in a mesh whose strips have swaps.
    let torus = vector("torus_with_t0.strips.lrm");
    let p = payload(&torus, Tag::STRP);
    let len = StrpHeader::read(&p).len as usize;
    let t_of = |i: usize| get(&p, strp_word(&p, "T", i));
    // A swap at w (T[w] = T[w+2]) inside a strip, with a triangle after it: make w + 1 a
    // swap as well (T[w+3] = T[w+1]).
    let w = (0..len - 5)
        .find(|&w| {
            (w..w + 6).all(|i| t_of(i) != NONE)
                && t_of(w) == t_of(w + 2)
                && t_of(w + 1) != t_of(w + 3)
                && w >= 1
                && t_of(w - 1) != NONE
        })
        .expect("a swap inside a strip");
    let bad = forge(&torus, Tag::STRP, |p| {
        let x = get(p, strp_word(p, "T", w + 1));
        set_strp(p, "T", w + 3, x)
    });
    breaks(
        &bad,
        29,
        "STRP",
        strp_at(&torus, "T", w),
        "two swaps in a row",
    );
}

/// [V29] A strip whose last window is a swap is located at that window.
#[test]

fn v29_last_window_located() {
    let bytes = vector("closed_tetrahedron.strips.lrm"); // T = 2 0 1 3 2 0 D D
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "T", 5, 3));
    breaks(&bad, 29, "STRP", strp_at(&bytes, "T", 3), "");
}

/// [V30] Entries of `A` that the operators read are `DELIMITER` or a triangle's position;
/// the others are `DELIMITER`.
#[test]
fn v30_adjacent_strips() {
    // T = 2 0 1 3 2 0 D D, triangles at 0..4; A = 3 2 3 0 1 0 D D.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let a = |i: usize| strp_at(&bytes, "A", i);
    let set = |i: usize, x: u32| forge(&bytes, Tag::STRP, |p| set_strp(p, "A", i, x));
    for (i, x) in [(0, 4), (1, 5), (5, 8), (2, NONE - 1)] {
        let bad = set(i, x);
        breaks(&bad, 30, "STRP", a(i), "not the position of a triangle");
    }
    for (i, x) in [(6, 0), (7, 3)] {
        breaks(&set(i, x), 30, "STRP", a(i), "no operator reads");
    }
}

/// [V31] Strips opposites are an involution across one edge.
#[test]
fn v31_strips_opposites() {
    // A[1] = 2 (triangle 0 across {2, 1}) made 3: corner 1's opposite becomes a corner of
    // triangle 3, which faces another edge. Triangle 0 is at T[0].
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 1, 3));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&bytes, "T", 0),
        "do not face each other",
    );
    // A[0] = 3 made 0: corner 2 of triangle 0 is its own opposite (o.o = c, but the
    // vertices do not match).
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 0, 0));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&bytes, "T", 0),
        "corner 2 and its opposite 2",
    );
    // A vertex changed: T = 1 0 4 0 3 2 5 2 1 0 D D with T[3] = 0 made 5, triangle 3
    // (window 0 3 2) no longer shares its edges' vertices with its neighbours.
    let open_hedra = vector("boundary_hedra_open.strips.lrm");
    let bad = forge(&open_hedra, Tag::STRP, |p| set_strp(p, "T", 3, 5));
    breaks(
        &bad,
        31,
        "STRP",
        strp_at(&open_hedra, "T", 3),
        "corner 9 and its opposite",
    );
}

/// [V31] A corner whose opposite is smaller and does not point back is located at a
/// triangle.
#[test]

fn v31_opposite_not_pointing_back_is_located() {
    // A[0] = 3 made DELIMITER: corner 2 of triangle 0 loses its opposite, corner 10 of
    // triangle 3 (at T[3]) still names corner 2.
    let bytes = vector("closed_tetrahedron.strips.lrm");
    let bad = forge(&bytes, Tag::STRP, |p| set_strp(p, "A", 0, NONE));
    breaks(&bad, 31, "STRP", strp_at(&bytes, "T", 3), "");
}

/// [V32] `C[v]` is `NONE` for an unused vertex and otherwise a corner of `v`.
#[test]
fn v32_strips_vertex_corners() {
    let bytes = vector("boundary_hedra_open.strips.lrm"); // m = 6, L = 12
    let view = open(&bytes, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let set = |v: usize, x: u32| forge(&bytes, Tag::STRP, |p| set_strp(p, "C", v, x));
    // Not a corner: T = 1 0 4 0 3 2 5 2 1 0 D D has swaps at 1 and 5, no window at 8.
    for x in [3, 3 * 5 + 1, 3 * 8, 3 * 12, NONE - 1] {
        assert!(!strips.is_corner(Corner(x)));
        let bad = set(2, x);
        breaks(&bad, 32, "STRP", strp_at(&bytes, "C", 2), "not a corner");
    }
    // A corner of another vertex.
    for v in 0..6u32 {
        let c = strips.corners().find(|&c| strips.vertex(c).0 != v).unwrap();
        let bad = set(v as usize, c.0);
        breaks(
            &bad,
            32,
            "STRP",
            strp_at(&bytes, "C", v as usize),
            "is a corner of vertex",
        );
    }
    // The unreferenced vertex of nonmanifold_vertex given a corner.
    let unused = vector("nonmanifold_vertex.strips.lrm");
    let view = open(&unused, &Limits::default()).unwrap();
    let s = view.strips().unwrap();
    let v = (0..s.vertex_id_bound())
        .find(|&v| s.vertex_corner(Vertex(v)).is_none())
        .unwrap();
    let bad = forge(&unused, Tag::STRP, |p| set_strp(p, "C", v as usize, 0));
    breaks(
        &bad,
        32,
        "STRP",
        strp_at(&unused, "C", v as usize),
        "is a corner of vertex",
    );
}

// ---------------------------------------------------------------------------------------
// §3.5d LRBE.

/// [V33] `LRBE` counts and length. (`m < 0x3FFFFFFF` cannot break alone: `m = V`.)
#[test]
fn v33_lrbe_counts() {
    let bytes = vector("torus_with_t0.lr-compact.lrm"); // m = m_r = 25, R = 1, n0 = 3
    let at = section_at(&bytes, Tag::LRBE);
    let field = |f: usize, x: u32| forge(&bytes, Tag::LRBE, |p| put(p, f, x));
    breaks(&field(0, 24), 33, "LRBE", at, "section MESH says 25");
    breaks(&field(28, 1), 33, "LRBE", at + 28, "reserved");
    for m_r in [26, 0, 3] {
        breaks(&field(4, m_r), 33, "LRBE", at + 4, "ring vertices");
    }
    breaks(&field(12, 0x4000_0000), 33, "LRBE", at + 12, "32 bits");
    for (f, x) in [(12, 4), (16, 17), (20, 1), (8, 2)] {
        breaks(&field(f, x), 33, "LRBE", at, "counts call for");
    }
    let bad = forge(&bytes, Tag::LRBE, |p| p.push(0));
    breaks(&bad, 33, "LRBE", at, "counts call for");
    let bad = forge(&bytes, Tag::LRBE, |p| p.truncate(30));
    breaks(&bad, 33, "LRBE", at, "header");
    // The period k is informative: any value is valid.
    open(&field(24, 12345), &Limits::default()).unwrap();
}

/// [V34] `LRBE` rings satisfy [V16], the bit vectors only with several rings.
#[test]
fn v34_lrbe_rings() {
    let two = vector("two_components.lr-compact.lrm"); // R = 2: starts [0, 4, 8], bits
    let word = |bytes: &[u8], name: &str, i: usize, x: u32| {
        forge(bytes, Tag::LRBE, |p| {
            let at = LrbeHeader::read(p).layout().unwrap().array(name).at(i);
            put(p, at, x)
        })
    };
    for (i, x) in [(0, 1), (1, 3), (2, 9)] {
        let at = lrbe_at(&two, "ring_starts", i);
        let bad = word(&two, "ring_starts", i, x);
        breaks(&bad, 34, "LRBE", at, "ring start");
    }
    let last = lrbe_at(&two, "ring_last", 0);
    let bad = word(&two, "ring_last", 0, 0x8);
    breaks(&bad, 34, "LRBE", last, "ring-end bits");
    let bad = word(&two, "ring_last", 0, 0x188);
    breaks(&bad, 34, "LRBE", last, "ring-end bits");
    let rank = lrbe_at(&two, "ring_rank", 0);
    let bad = word(&two, "ring_rank", 0, 2);
    breaks(&bad, 34, "LRBE", rank, "ring ranks");
    // One ring: no bit vectors, the starts are [0, m_r].
    let one = vector("closed_tetrahedron.lr-compact.lrm");
    let at = lrbe_at(&one, "ring_starts", 1);
    let bad = word(&one, "ring_starts", 1, 5);
    breaks(&bad, 34, "LRBE", at, "ring start 5");
}

/// [V35] Pairs and records: records tile `RECORDS` in ring order from each block's start,
/// IRREGULAR flags agree with heads, no unit left over; tips below `m` or `NULL` in a right
/// slot without WART, and then without stored opposites.
#[test]
fn v35_pairs_and_records() {
    let bytes = vector("torus_with_t0.lr-compact.lrm"); // 9 extended pairs, 18 units
    let p = payload(&bytes, Tag::LRBE);
    let pair = |v: usize| get(&p, lrbe_word(&p, PAIRS, v));
    let pair_at = |v: usize| lrbe_at(&bytes, "PAIRS", v);
    let set_pair = |v: usize, x: u32| forge(&bytes, Tag::LRBE, |p| set_lrbe(p, PAIRS, v, x));
    let extended: Vec<usize> = (0..25).filter(|&v| pair(v) >> 30 == 3).collect();
    let plain: Vec<usize> = (0..25).filter(|&v| pair(v) >> 30 == 0).collect();
    // Block 0 must start its records at 0.
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, BLOCKS, 0, 1));
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bytes, "BLOCKS", 0),
        "block 0 starts its records at 1",
    );
    // The second record starting one unit late, or early.
    let v = extended[1];
    for delta in [1u32 << 13, (1u32 << 13).wrapping_neg()] {
        let bad = set_pair(v, pair(v).wrapping_add(delta));
        breaks(&bad, 35, "LRBE", pair_at(v), "record of pair");
    }
    // An IRREGULAR flag flipped against the head.
    for &v in &extended[..3] {
        for bit in [26, 27] {
            let bad = set_pair(v, pair(v) ^ 1 << bit);
            breaks(
                &bad,
                35,
                "LRBE",
                pair_at(v),
                "IRREGULAR flag and stored opposites disagree",
            );
        }
    }
    // The last record cut short: it runs past RECORDS.
    let last = *extended.last().unwrap();
    let mut t = Tables::lrbe(&p);
    let start = (pair(last) >> 13 & 0x1FFF) as usize;
    t.head[4] -= 1;
    t.array(RECORDS).pop();
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "RECORDS", start),
        "runs past",
    );
    // A unit no record uses.
    let mut t = Tables::lrbe(&p);
    t.head[4] += 1;
    t.array(RECORDS).push(0);
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "RECORDS", 18),
        "not used by any pair",
    );
    // Plain pairs: tips v + d out of range, a NULL left tip, a NULL right tip with WART.
    let v = plain[0];
    let out_of_range = [(25 - v as u32) & 0x7FFF, 0x7FFF & (-(v as i32) - 1) as u32];
    for d in out_of_range {
        let bad = set_pair(v, pair(v) & !0x7FFF | d);
        breaks(&bad, 35, "LRBE", pair_at(v), "has tip");
        let bad = set_pair(v, pair(v) & !(0x7FFF << 15) | d << 15);
        breaks(&bad, 35, "LRBE", pair_at(v), "has tip");
    }
    let bad = set_pair(v, pair(v) & !0x7FFF);
    breaks(&bad, 35, "LRBE", pair_at(v), "has tip 0x3fffffff");
    let wart_null = 2 << 30 | (pair(v) & 0x7FFF);
    let bad = set_pair(v, wart_null);
    breaks(&bad, 35, "LRBE", pair_at(v), "has tip 0x3fffffff");
    // A right slot with tip NULL storing an opposite: boundary_hedra_open's pair 0 (tips 3
    // and NULL) made extended, IRREGULAR on the right, with a record [head 0x0004: the
    // opposite of corner 4 stored, right tip NULL; field 0xC000: NONE].
    let open_hedra = vector("boundary_hedra_open.lr-compact.lrm");
    let q = payload(&open_hedra, Tag::LRBE);
    assert_eq!(get(&q, lrbe_word(&q, PAIRS, 0)), 3);
    let mut t = Tables::lrbe(&q);
    t.head[4] = 2;
    t.array(PAIRS)[0] = 3 << 30 | 1 << 27 | 3;
    t.array(RECORDS).extend([0x0004, 0xC000]);
    let bad = forge(&open_hedra, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        35,
        "LRBE",
        lrbe_at(&bad, "PAIRS", 0),
        "missing right triangle of pair 0 stores opposites",
    );
    // The same record without IRREGULAR on the right and with no opposite is valid.
    t.array(PAIRS)[0] = 3 << 30 | 3;
    t.head[4] = 1;
    t.array(RECORDS).truncate(1);
    t.array(RECORDS)[0] = 0;
    open(
        &forge(&open_hedra, Tag::LRBE, |p| *p = t.join()),
        &Limits::default(),
    )
    .unwrap();
}

/// The `LRBE` container with T0 row `j` moved to `OVERFLOW` (its first and only overflow
/// row, holding the vertices and opposites the row answers).
fn overflow_row(bytes: &[u8], j: usize) -> Vec<u8> {
    let view = open(bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let corners = [0, 1, 2].map(|i| Corner(8 * lr.ring_vertices() + 4 * j as u32 + i));
    let p = payload(bytes, Tag::LRBE);
    let mut t = Tables::lrbe(&p);
    assert_eq!(t.head[5], 0);
    t.head[5] = 1;
    t.array(OVERFLOW).extend(corners.map(|c| lr.vertex(c).0));
    t.array(OVERFLOW)
        .extend(corners.map(|c| lr.opposite(c).map_or(NONE, |o| o.0)));
    t.array(ROWS)[4 * j..4 * j + 4].copy_from_slice(&[0, 0, 0, 0x8000]);
    forge(bytes, Tag::LRBE, |p| *p = t.join())
}

/// [V36] T0 rows: overflow rows exactly `(0, k, 0x8000)` and used once each in order, other
/// rows with reserved bits clear; T0 vertices below `m`.
#[test]
fn v36_t0_rows() {
    let bytes = vector("defective_torus.lr-compact.lrm"); // m = 23, 5 rows, F = 0
    let p = payload(&bytes, Tag::LRBE);
    let unit = |p: &[u8], j: usize, i: usize| lrbe_word(p, ROWS, 4 * j + i);
    let row_at = |bytes: &[u8], j: usize, i: usize| lrbe_at(bytes, "ROWS", 4 * j + i);
    let set = |j: usize, i: usize, x: u32| {
        forge(&bytes, Tag::LRBE, |p| set_lrbe16(p, ROWS, 4 * j + i, x))
    };
    // Reserved bits 6–14 of unit 3.
    for bit in [6, 10, 14] {
        let codes = get16(&p, unit(&p, 2, 3)) | 1 << bit;
        let bad = set(2, 3, codes);
        breaks(&bad, 36, "LRBE", row_at(&bytes, 2, 3), "reserved bits");
    }
    // The anchor out of range (GROUP[0] + a ≥ m).
    let bad = set(1, 0, 0x7FFF);
    breaks(&bad, 36, "LRBE", row_at(&bytes, 1, 0), "out of range");
    // Row 3 moved to OVERFLOW: valid; then its unit 0 made 1.
    let j = 3;
    let overflowing = overflow_row(&bytes, j);
    open(&overflowing, &Limits::default()).unwrap();
    // Its unit 0 must be 0.
    let mut u = Tables::lrbe(&payload(&overflowing, Tag::LRBE));
    u.array(ROWS)[4 * j] = 1;
    let bad = forge(&overflowing, Tag::LRBE, |p| *p = u.join());
    breaks(
        &bad,
        36,
        "LRBE",
        row_at(&bad, j, 0),
        "malformed overflow row",
    );
    // An overflow row no T0 row uses (the first of them: row 0 of OVERFLOW).
    let mut t = Tables::lrbe(&p);
    t.head[5] = 1;
    t.array(OVERFLOW).extend([0; 6]);
    let bad = forge(&bytes, Tag::LRBE, |p| *p = t.join());
    breaks(
        &bad,
        36,
        "LRBE",
        lrbe_at(&bad, "OVERFLOW", 0),
        "not used by any T0 row",
    );
}

/// [V36] Row faults in units 1–2 or in `OVERFLOW` are located at that unit or word.
#[test]

fn v36_row_faults_located_at_their_unit() {
    let bytes = vector("defective_torus.lr-compact.lrm");
    let p = payload(&bytes, Tag::LRBE);
    let unit = |j: usize, i: usize| lrbe_word(&p, ROWS, 4 * j + i);
    let b1 = get16(&p, unit(2, 1));
    let bad = forge(&bytes, Tag::LRBE, |q| put16(q, unit(2, 1), b1 | 0x8000));
    breaks(&bad, 36, "LRBE", lrbe_at(&bytes, "ROWS", 4 * 2 + 1), "");
    let bad = forge(&bytes, Tag::LRBE, |q| put16(q, unit(2, 1), 0x3FFF));
    breaks(&bad, 36, "LRBE", lrbe_at(&bytes, "ROWS", 4 * 2 + 1), "");
    // An overflow row naming OVERFLOW row 1 where it is the first (k = 0).
    let overflowing = overflow_row(&bytes, 3);
    let bad = forge(&overflowing, Tag::LRBE, |q| {
        set_lrbe16(q, ROWS, 4 * 3 + 1, 1)
    });
    breaks(
        &bad,
        36,
        "LRBE",
        lrbe_at(&overflowing, "ROWS", 4 * 3 + 1),
        "",
    );
    // An overflow row's vertex out of range, in OVERFLOW.
    let bad = forge(&overflowing, Tag::LRBE, |q| set_lrbe(q, OVERFLOW, 1, 23));
    breaks(&bad, 36, "LRBE", lrbe_at(&overflowing, "OVERFLOW", 1), "");
}

/// [V37] `LRBE`'s `C` holds `NONE` or canonical corners; then [V19], [V21]–[V23] and [V38]
/// hold for its operators (each reported under its own number).
#[test]
fn v37_lrbe_corners_and_lr_rules() {
    let bytes = vector("defective_torus.lr-compact.lrm"); // off-ring 16..23
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let redundant = (0..128)
        .find(|&c| c & 3 != 3 && !lr.is_corner(Corner(c)))
        .unwrap();
    for x in [3, redundant, 8 * 16 + 4 * 5, NONE - 1] {
        let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 2, x));
        breaks(&bad, 37, "LRBE", lrbe_at(&bytes, "C", 2), "not a corner");
    }
    // [V23]: an off-ring vertex given a corner of another vertex.
    let c = lr.corners().find(|&c| lr.vertex(c).0 != 18).unwrap();
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 2, c.0));
    breaks(
        &bad,
        23,
        "LRBE",
        lrbe_at(&bytes, "C", 2),
        "is a corner of vertex",
    );
    // [V21]: a T0 row whose vertex 1 is its anchor (offset 0), in the row without opposites.
    let j = lone_t0_triangle(&bytes);
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe16(p, ROWS, 4 * j + 1, 0));
    breaks(
        &bad,
        21,
        "LRBE",
        lrbe_at(&bytes, "ROWS", 4 * j),
        "degenerate",
    );
    // [V19] and [V22] on the tetrahedron: pair 0 = 0x10003 (tips 3, 1).
    let tetra = vector("closed_tetrahedron.lr-compact.lrm");
    let set = |v: usize, x: u32| forge(&tetra, Tag::LRBE, |p| set_lrbe(p, PAIRS, v, x));
    // Left tip 2 = 0.n.n: slot 0 redundant, pointing at the redundant slot 2.
    let bad = set(0, 0x10002);
    breaks(
        &bad,
        19,
        "LRBE",
        lrbe_at(&tetra, "PAIRS", 0),
        "slot 0 points to slot 2",
    );
    // Pair 1 = 0x3FFF8002 (offsets +2, −1) made 0x3FFFFFFF (−1, −1): its left tip 3 made 0,
    // and corner 10 pairs with corner 12 across an edge they do not share.
    let bad = set(1, 0x3FFF_FFFF);
    breaks(
        &bad,
        22,
        "LRBE",
        lrbe_at(&tetra, "PAIRS", 1),
        "corner 10 and its opposite 12",
    );
    // [V38] on LRBE: in v38_vertex_corner_starts_its_fan.
}

// ---------------------------------------------------------------------------------------
// §3.5 (all kinds) vertex corners and fans.

/// [V38] `v.c = NONE` iff no triangle has `v`; an open fan's `v.c` starts it. For `LRTB`
/// and `LRBE` on an off-ring vertex's `C`, for `STRP` on `C[v]`. (A `C` naming a corner for
/// an unused vertex names another vertex's corner: [V23] or [V32] catches it first.)
#[test]
fn v38_vertex_corner_starts_its_fan() {
    // A used off-ring vertex with C = NONE (LRTB, LRBE), a used vertex with C[v] = NONE (STRP).
    let lrtb = vector("defective_torus.lrm");
    let bad = forge(&lrtb, Tag::LRTB, |p| set_lrtb(p, LRTB_C, 0, NONE));
    breaks(
        &bad,
        38,
        "LRTB",
        lrtb_at(&lrtb, "C", 0),
        "vertex 16 has triangles but no corner",
    );
    let lrbe = vector("defective_torus.lr-compact.lrm");
    let bad = forge(&lrbe, Tag::LRBE, |p| set_lrbe(p, LRBE_C, 0, NONE));
    breaks(
        &bad,
        38,
        "LRBE",
        lrbe_at(&lrbe, "C", 0),
        "vertex 16 has triangles but no corner",
    );
    let strp = vector("boundary_hedra_open.strips.lrm");
    for v in 0..6 {
        let bad = forge(&strp, Tag::STRP, |p| set_strp(p, "C", v, NONE));
        breaks(
            &bad,
            38,
            "STRP",
            strp_at(&strp, "C", v),
            "has triangles but no corner",
        );
    }
    // An open fan whose stored corner is another corner of the vertex than its start.
    let bytes = encoded(&soup(), Connectivity::Lr);
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr().unwrap();
    let m_r = lr.ring_vertices();
    let (v, c) = open_fan(lr, m_r..lr.vertex_id_bound());
    let i = (v - m_r) as usize;
    let bad = forge(&bytes, Tag::LRTB, |p| set_lrtb(p, LRTB_C, i, c.0));
    breaks(
        &bad,
        38,
        "LRTB",
        lrtb_at(&bytes, "C", i),
        "does not start its open fan",
    );
    let bytes = encoded(&soup(), Connectivity::LrCompact);
    let view = open(&bytes, &Limits::default()).unwrap();
    let lr = view.lr_compact().unwrap();
    let m_r = lr.ring_vertices();
    let (v, c) = open_fan(lr, m_r..lr.vertex_id_bound());
    let i = (v - m_r) as usize;
    let bad = forge(&bytes, Tag::LRBE, |p| set_lrbe(p, LRBE_C, i, c.0));
    breaks(
        &bad,
        38,
        "LRBE",
        lrbe_at(&bytes, "C", i),
        "does not start its open fan",
    );
    let view = open(&strp, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let (v, c) = open_fan(strips, 0..6);
    let bad = forge(&strp, Tag::STRP, |p| set_strp(p, "C", v as usize, c.0));
    breaks(
        &bad,
        38,
        "STRP",
        strp_at(&strp, "C", v as usize),
        "does not start its open fan",
    );
    // A closed fan may store any of its corners.
    let tetra = vector("closed_tetrahedron.strips.lrm");
    let view = open(&tetra, &Limits::default()).unwrap();
    let strips = view.strips().unwrap();
    let (corners, start) = fan_of(strips, 0);
    assert!(start.is_none());
    for c in corners {
        let other = forge(&tetra, Tag::STRP, |p| set_strp(p, "C", 0, c.0));
        open(&other, &Limits::default()).unwrap();
    }
}

/// [V39] `MESH`, `GEOM` and the connectivity section of MESH's kind are present, checked
/// when first needed.
#[test]
fn v39_required_sections() {
    let bytes = vector("closed_tetrahedron.lrm");
    let without = |tags: &[Tag]| forge_sections(&bytes, |s| s.retain(|x| !tags.contains(&x.0)));
    for tag in [Tag::MESH, Tag::GEOM, Tag::LRTB] {
        breaks(&without(&[tag]), 39, &tag.name(), 0, "missing");
    }
    // Kind 3 without STRP (LRTB is then surplus, and ignored).
    let strips_kind = forge(&bytes, Tag::MESH, |p| put(p, MeshRecord::KIND_AT, 3));
    breaks(&strips_kind, 39, "STRP", 0, "missing");
    // Checked when first needed: MESH after META, GEOM after MESH, the connectivity after
    // the attributes.
    let bad_meta = forge(&without(&[Tag::MESH]), Tag::META, |p| p.truncate(3));
    assert_eq!(format_error(&bad_meta).rule, Rule(11));
    let bad_mesh = forge(&without(&[Tag::GEOM]), Tag::MESH, |p| put(p, 20, 1));
    assert_eq!(format_error(&bad_mesh).rule, Rule(12));
    let bad_geom = forge(&without(&[Tag::LRTB]), Tag::GEOM, |p| put(p, 4, 1));
    assert_eq!(format_error(&bad_geom).rule, Rule(13));
    // A surplus connectivity section is not validated.
    let strips = vector("closed_tetrahedron.strips.lrm");
    let surplus = forge_sections(&strips, |s| {
        s.push((Tag::LRTB, Flags::REQUIRED, b"junk".to_vec()))
    });
    open(&surplus, &Limits::default()).unwrap();
}

/// Every rule `[Vnn]` of `spec/FORMAT.md` has a test here whose name starts with `vNN_`
/// and whose doc comment starts with `[Vnn]`.
#[test]
fn every_rule_has_a_forged_test() {
    let spec = std::fs::read_to_string(manifest().join("spec/FORMAT.md")).unwrap();
    let source = include_str!("forged_rules.rs");
    let mut rules = std::collections::BTreeSet::new();
    for piece in spec.split("[V").skip(1) {
        let digits: String = piece.chars().take_while(char::is_ascii_digit).collect();
        if piece[digits.len()..].starts_with(']') && !digits.is_empty() {
            rules.insert(digits.parse::<u32>().unwrap());
        }
    }
    assert!(rules.len() >= 39, "{rules:?}");
    let missing: Vec<u32> = rules
        .iter()
        .copied()
        .filter(|n| {
            !source.contains(&format!("fn v{n:02}_")) || !source.contains(&format!("/// [V{n}]"))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "rules without a forged test: {missing:?}"
    );
    assert_eq!(Rule::LAST.0 as u32, *rules.last().unwrap());
}
