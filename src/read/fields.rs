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
        // A pass without branches first (exponent bits all set: infinite or NaN), 64 values
        // at a time so that it vectorizes; the value at fault is looked for only when it fails.
        let bytes = &self.section.bytes[range.start..range.end.max(range.start)];
        let exponent = |w: &[u8]| {
            let bits = u32::from_le_bytes(w.try_into().expect("four bytes"));
            (bits & 0x7F80_0000 == 0x7F80_0000) as u32
        };
        let none_bad =
            |values: &[u8]| values.chunks_exact(4).fold(0, |bad, w| bad | exponent(w)) == 0;
        // Exact chunks: a loop of a fixed count unrolls, with no tail to handle per chunk.
        let chunks = bytes.chunks_exact(4 * 64);
        let all_finite = none_bad(chunks.remainder()) && chunks.into_iter().all(none_bad);
        if all_finite && bytes.len() % 4 == 0 {
            return Ok(());
        }
        for at in range.step_by(4) {
            let x = le_f32(self.section.bytes, at);
            if !x.is_finite() {
                return Err(self.err(at, rule, format!("non-finite value {x}")));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::format::Tag;

    /// The branch-free pass and the value-by-value loop agree: a non-finite value is found
    /// wherever it lies (first value, the end of a 64-value chunk, the next chunk, the last
    /// value) and named at its offset; every finite value passes.
    #[test]
    fn non_finite_values_are_found_wherever_they_lie() {
        let finite = [
            0.0f32,
            -0.0,
            1.5,
            f32::MAX,
            f32::MIN,
            f32::MIN_POSITIVE,
            1e-45,
        ];
        let values: Vec<f32> = (0..1000).map(|i| finite[i % finite.len()]).collect();
        let bytes_of =
            |values: &[f32]| -> Vec<u8> { values.iter().flat_map(|x| x.to_le_bytes()).collect() };
        let check = |bytes: &[u8]| {
            let section = Section {
                tag: Tag::MESH,
                flags: Default::default(),
                offset: 100,
                bytes,
            };
            Fields::new(section).expect_finite(8..bytes.len(), Rule(14))
        };
        assert!(check(&bytes_of(&values)).is_ok());
        for at in [2, 65, 66, 130, 999] {
            for bad in [f32::INFINITY, f32::NEG_INFINITY, f32::NAN] {
                let mut v = values.clone();
                v[at] = bad;
                match check(&bytes_of(&v)) {
                    Err(Error::Format(e)) => assert_eq!(e.offset, 100 + 4 * at as u64),
                    other => panic!("{at}: {other:?}"),
                }
            }
        }
        // Before the range: not checked.
        let mut v = values.clone();
        v[1] = f32::NAN;
        assert!(check(&bytes_of(&v)).is_ok());
    }
}
