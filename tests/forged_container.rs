//! Forged containers for the rules of the header and the section table, **[V1]**..**[V10]**
//! of `spec/FORMAT.md` (§2.1, §2.2), and `every_rule_has_a_forged_test`, which checks that
//! every rule of the spec has its test in one of `tests/forged_*.rs`. How a rule is broken
//! and what the reader must report: `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::layout::MeshRecord;
use lrmesh::format::{Flags, Tag};
use lrmesh::read::{open, Limits};
use lrmesh::{Error, Rule};

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
    let minor = u16::from_le_bytes([bytes[10], bytes[11]]);
    for major in [0u16, 2, 0xFFFF] {
        let bad = patch(&bytes, |b| b[8..10].copy_from_slice(&major.to_le_bytes()));
        match open(&bad, &Limits::default()) {
            Err(Error::UnsupportedVersion {
                major: m,
                minor: n,
                supported: 1,
            }) => assert_eq!((m, n), (major, minor)),
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

/// Every rule `[Vnn]` of `spec/FORMAT.md` and `spec/GEOMETRY.md` has a test in one of
/// `tests/forged_*.rs` whose name starts with `vNN_` and whose doc comment starts with
/// `[Vnn]`.
#[test]
fn every_rule_has_a_forged_test() {
    let spec = ["spec/FORMAT.md", "spec/GEOMETRY.md"]
        .map(|f| std::fs::read_to_string(manifest().join(f)).unwrap())
        .join("\n");
    // Every `tests/forged_*.rs`, read at run time: a file added later is scanned too.
    let tests = manifest().join("tests");
    let mut files: Vec<String> = std::fs::read_dir(&tests)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|name| name.starts_with("forged_") && name.ends_with(".rs"))
        .collect();
    files.sort();
    let source = files
        .iter()
        .map(|name| std::fs::read_to_string(tests.join(name)).unwrap())
        .collect::<Vec<_>>()
        .join("\n");
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
