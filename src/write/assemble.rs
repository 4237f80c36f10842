//! Header, section table and payloads, with their checksums (FORMAT.md §2), into a buffer
//! or any writer.

use crate::format::{self, Entry, Flags, Header, Tag, ENTRY_LEN, HEADER_LEN};

/// One section to write: its tag, flags and bytes.
pub type SectionBytes = (Tag, Flags, Vec<u8>);

/// The header and section table of `sections`, checksums included.
fn header_and_table(sections: &[SectionBytes]) -> Vec<u8> {
    let table_end = HEADER_LEN + ENTRY_LEN * sections.len();
    let total = table_end as u64 + sections.iter().map(|s| s.2.len() as u64).sum::<u64>();
    let mut header = Header {
        major: format::MAJOR,
        minor: format::minor_for(sections.iter().map(|s| (s.0, s.2.as_slice()))),
        sections: sections.len() as u32,
        file_length: total,
        table_crc: 0,
        reserved: 0,
    };
    let mut out = Vec::with_capacity(table_end);
    out.extend_from_slice(&header.to_bytes());
    let mut offset = table_end as u64;
    for (tag, flags, bytes) in sections {
        let entry = Entry {
            tag: *tag,
            flags: *flags,
            offset,
            length: bytes.len() as u64,
            crc: format::section_checksum(bytes),
            reserved: 0,
        };
        out.extend_from_slice(&entry.to_bytes());
        offset += bytes.len() as u64;
    }
    header.table_crc = format::table_checksum(&out);
    out[..HEADER_LEN].copy_from_slice(&header.to_bytes());
    out
}

/// A container of the given sections, in this order: header, section table and payloads
/// with their checksums. For tools that add sections of their own (an optional section
/// unknown to readers is skipped by them) and for tests that forge files.
pub fn assemble(sections: &[SectionBytes]) -> Vec<u8> {
    let mut out = header_and_table(sections);
    for (_, _, bytes) in sections {
        out.extend_from_slice(bytes);
    }
    out
}

/// Writes the container of `sections` to `out`, without a copy of the whole file.
pub fn write_sections(
    out: &mut impl std::io::Write,
    sections: &[SectionBytes],
) -> std::io::Result<()> {
    out.write_all(&header_and_table(sections))?;
    for (_, _, bytes) in sections {
        out.write_all(bytes)?;
    }
    Ok(())
}
