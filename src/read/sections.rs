//! The header and the section table (FORMAT.md §2, rules V1–V10): a container whose sections
//! are located and checksummed, their contents not yet read.

use super::fields::format_error;
use super::Limits;
use crate::error::{Error, Result, Rule};
use crate::format::{self, Entry, Flags, Header, Tag, ENTRY_LEN, HEADER_LEN};

/// One section of a container.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Section<'a> {
    /// Its tag.
    pub tag: Tag,
    /// Its flags.
    pub flags: Flags,
    /// Offset of its first byte in the file.
    pub offset: u64,
    /// Its bytes.
    pub bytes: &'a [u8],
}

/// A container whose header and section table are valid, with every section's checksum
/// verified. The sections' contents are not yet checked (see [`super::open`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Sections<'a> {
    /// Major version.
    pub major: u16,
    /// Minor version.
    pub minor: u16,
    /// The sections, in file order.
    pub sections: Vec<Section<'a>>,
}

/// Checksums are skipped when fuzzing, so that the fuzzer reaches the section parsers.
fn checksum_matches(expected: u32, actual: u32) -> bool {
    cfg!(fuzzing) || expected == actual
}

impl<'a> Sections<'a> {
    /// Parses the header and the section table and verifies the checksums.
    ///
    /// # Errors
    /// [`Error::Format`] naming the part, byte offset and rule; [`Error::UnsupportedVersion`];
    /// [`Error::UnknownRequiredSection`]; [`Error::LimitExceeded`].
    pub fn parse(bytes: &'a [u8], limits: &Limits) -> Result<Sections<'a>> {
        Sections::parse_checking(bytes, limits, |_| true)
    }

    /// As [`Sections::parse`], verifying the checksum of a section only when `check` says
    /// so of its tag (a reader of headers alone need not read every byte).
    pub(crate) fn parse_checking(
        bytes: &'a [u8],
        limits: &Limits,
        check: impl Fn(Tag) -> bool,
    ) -> Result<Sections<'a>> {
        let header_err = |at: usize, rule: Rule, message: String| {
            format_error("header", at as u64, rule, message)
        };
        if bytes.len() < HEADER_LEN {
            return Err(header_err(
                0,
                Rule(1),
                format!(
                    "{} bytes, shorter than the {HEADER_LEN}-byte header",
                    bytes.len()
                ),
            ));
        }
        if bytes[..8] != format::MAGIC {
            return Err(header_err(
                0,
                Rule(1),
                "not an lrmesh container (bad magic)".into(),
            ));
        }
        let header = Header::read(bytes);
        if header.major != format::MAJOR {
            return Err(Error::UnsupportedVersion {
                major: header.major,
                minor: header.minor,
                supported: format::MAJOR,
            });
        }
        if header.file_length != bytes.len() as u64 {
            return Err(header_err(
                Header::FILE_LENGTH_AT,
                Rule(3),
                format!(
                    "file length field says {}, the file has {}",
                    header.file_length,
                    bytes.len()
                ),
            ));
        }
        if header.reserved != 0 {
            return Err(header_err(
                Header::RESERVED_AT,
                Rule(3),
                "reserved field is not zero".into(),
            ));
        }
        let count = header.sections;
        if count > limits.max_sections {
            return Err(Error::LimitExceeded {
                what: "section count",
                value: count as u64,
                limit: limits.max_sections as u64,
            });
        }
        let table_end = HEADER_LEN as u64 + ENTRY_LEN as u64 * count as u64;
        if table_end > bytes.len() as u64 {
            return Err(format_error(
                "section table",
                HEADER_LEN as u64,
                Rule(4),
                format!(
                    "{count} entries need {table_end} bytes, the file has {}",
                    bytes.len()
                ),
            ));
        }
        let table_end = table_end as usize;
        let table_crc = format::table_checksum(&bytes[..table_end]);
        if !checksum_matches(header.table_crc, table_crc) {
            return Err(header_err(
                Header::TABLE_CRC_AT,
                Rule(5),
                "header and section table checksum mismatch".into(),
            ));
        }
        let mut sections: Vec<Section<'a>> = Vec::with_capacity(count as usize);
        let mut expected_offset = table_end as u64;
        for i in 0..count as usize {
            let at = HEADER_LEN + ENTRY_LEN * i;
            let e = Entry::read(bytes, at);
            let name = e.tag.name();
            let entry_err = |field: usize, rule: Rule, message: String| {
                format_error("section table", (at + field) as u64, rule, message)
            };
            if e.flags.unknown_bits() != 0 {
                return Err(entry_err(
                    Entry::FLAGS_AT,
                    Rule(7),
                    format!("section {name}: unknown flags {:#x}", e.flags.0),
                ));
            }
            if e.reserved != 0 {
                return Err(entry_err(
                    Entry::RESERVED_AT,
                    Rule(7),
                    format!("section {name}: reserved field is not zero"),
                ));
            }
            if e.offset != expected_offset {
                return Err(entry_err(
                    Entry::OFFSET_AT,
                    Rule(6),
                    format!("section {name} starts at {}, expected {expected_offset} (sections are contiguous, in table order)", e.offset),
                ));
            }
            let end = e
                .offset
                .checked_add(e.length)
                .filter(|&end| end <= bytes.len() as u64)
                .ok_or_else(|| {
                    entry_err(
                        Entry::LENGTH_AT,
                        Rule(6),
                        format!(
                            "section {name} of {} bytes runs past the end of the file",
                            e.length
                        ),
                    )
                })?;
            let body = &bytes[e.offset as usize..end as usize];
            if check(e.tag) && !checksum_matches(e.crc, format::section_checksum(body)) {
                return Err(format_error(&name, e.offset, Rule(8), "checksum mismatch"));
            }
            if sections.iter().any(|s| s.tag == e.tag) {
                return Err(entry_err(
                    0,
                    Rule(9),
                    format!("section {name} appears twice"),
                ));
            }
            if e.flags.is_required() && !e.tag.is_known() {
                return Err(Error::UnknownRequiredSection {
                    tag: name,
                    index: i as u32,
                });
            }
            sections.push(Section {
                tag: e.tag,
                flags: e.flags,
                offset: e.offset,
                bytes: body,
            });
            expected_offset = end;
        }
        if expected_offset != bytes.len() as u64 {
            return Err(format_error(
                "file",
                expected_offset,
                Rule(6),
                format!(
                    "{} bytes after the last section",
                    bytes.len() as u64 - expected_offset
                ),
            ));
        }
        Ok(Sections {
            major: header.major,
            minor: header.minor,
            sections,
        })
    }

    /// The section with `tag`, if present.
    pub fn section(&self, tag: Tag) -> Option<&Section<'a>> {
        self.sections.iter().find(|s| s.tag == tag)
    }

    /// The sections as `(tag, flags, payload)`, in file order, to change and
    /// [`assemble`](crate::write::assemble) again.
    pub fn to_section_bytes(&self) -> Vec<crate::write::SectionBytes> {
        self.sections
            .iter()
            .map(|s| (s.tag, s.flags, s.bytes.to_vec()))
            .collect()
    }

    /// The section with `tag`, which rule V39 requires.
    pub(crate) fn required(&self, tag: Tag) -> Result<Section<'a>> {
        self.section(tag)
            .copied()
            .ok_or_else(|| format_error(&tag.name(), 0, Rule(39), "required section is missing"))
    }
}
