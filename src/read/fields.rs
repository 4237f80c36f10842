//! Reading a section's bytes as fields, with errors that name the section, the offset from
//! the start of the file, and the rule broken.

use super::Section;
use crate::error::{Error, FormatError, Rule};
use crate::format::{le_f32, le_u32};

/// A format error at `offset` of the file.
pub(crate) fn format_error(
    section: &str,
    offset: u64,
    rule: Rule,
    message: impl Into<String>,
) -> Error {
    Error::Format(Box::new(FormatError {
        file: None,
        section: section.to_string(),
        offset,
        rule,
        message: message.into(),
    }))
}

/// A section's bytes, read as fields.
#[derive(Clone, Copy)]
pub(crate) struct Fields<'a> {
    pub section: Section<'a>,
}

impl<'a> Fields<'a> {
    pub fn new(section: Section<'a>) -> Fields<'a> {
        Fields { section }
    }

    pub fn bytes(&self) -> &'a [u8] {
        self.section.bytes
    }

    pub fn len(&self) -> usize {
        self.section.bytes.len()
    }

    /// An error at byte `at` of the section.
    pub fn err(&self, at: usize, rule: Rule, message: impl Into<String>) -> Error {
        format_error(
            &self.section.tag.name(),
            self.section.offset + at as u64,
            rule,
            message,
        )
    }

    /// The u32 at `at`, or a truncation error under `rule`.
    pub fn u32(&self, at: usize, rule: Rule) -> Result<u32, Error> {
        if at + 4 > self.len() {
            return Err(self.err(at, rule, format!("truncated: {} bytes", self.len())));
        }
        Ok(le_u32(self.section.bytes, at))
    }

    /// At least `len` bytes, for a fixed header.
    pub fn expect_at_least(&self, len: usize, rule: Rule) -> Result<(), Error> {
        if self.len() < len {
            return Err(self.err(
                0,
                rule,
                format!("{} bytes, shorter than its {len}-byte header", self.len()),
            ));
        }
        Ok(())
    }

    /// The vertex count `found` at byte `at` is MESH's `m`.
    pub fn expect_vertices(&self, at: usize, found: u32, m: u32, rule: Rule) -> Result<(), Error> {
        if found != m {
            return Err(self.err(at, rule, format!("{found} vertices, section MESH says {m}")));
        }
        Ok(())
    }

    /// The exact length the section must have (`None`: the counts overflow).
    pub fn expect_len(&self, len: Option<u64>, rule: Rule) -> Result<(), Error> {
        match len {
            Some(len) if len == self.len() as u64 => Ok(()),
            Some(len) => Err(self.err(
                0,
                rule,
                format!("{} bytes where the counts call for {len}", self.len()),
            )),
            None => Err(self.err(0, rule, "counts overflow")),
        }
    }

    /// Checks that the f32s in bytes `range` of the section are finite.
    pub fn expect_finite(&self, range: std::ops::Range<usize>, rule: Rule) -> Result<(), Error> {
        for at in range.step_by(4) {
            let x = le_f32(self.section.bytes, at);
            if !x.is_finite() {
                return Err(self.err(at, rule, format!("non-finite value {x}")));
            }
        }
        Ok(())
    }
}
