//! Line and token scanning shared by the text readers (OFF, OBJ, ASCII PLY, ASCII STL).
//!
//! Everything works on bytes: text formats are ASCII in practice, and a stray non-UTF-8 byte in
//! a comment must not stop a reader. Numbers are parsed with the standard library, which rounds
//! a decimal string correctly to the nearest `f32`.

/// The lines of a byte buffer with their 1-based numbers. `\n` ends a line; a `\r` before it is
/// dropped, so CRLF files read like LF files.
pub(crate) struct Lines<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u64,
}

impl<'a> Lines<'a> {
    /// Lines of `bytes`, starting at line 1, after a UTF-8 byte-order mark if the input
    /// starts with one (offsets still count from the start of `bytes`).
    pub(crate) fn new(bytes: &'a [u8]) -> Lines<'a> {
        Lines {
            bytes,
            pos: bom_len(bytes),
            line: 1,
        }
    }

    /// Byte offset of the first byte not yet returned.
    pub(crate) fn offset(&self) -> usize {
        self.pos
    }

    /// Number that the next line will have; at the end of the input, the line the end is on.
    pub(crate) fn next_number(&self) -> u64 {
        self.line
    }

    /// The next line, without its terminator.
    pub(crate) fn next_line(&mut self) -> Option<(u64, &'a [u8])> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let (mut line, used) = match rest.iter().position(|&b| b == b'\n') {
            Some(i) => (&rest[..i], i + 1),
            None => (rest, rest.len()),
        };
        if let [head @ .., b'\r'] = line {
            line = head;
        }
        let number = self.line;
        self.pos += used;
        if used > line.len() {
            self.line += 1;
        }
        Some((number, line))
    }

    /// The next line that holds something other than white space and a `#` comment, with the
    /// comment removed.
    pub(crate) fn next_content(&mut self) -> Option<(u64, &'a [u8])> {
        loop {
            let (n, line) = self.next_line()?;
            let line = strip_comment(line);
            if words(line).next().is_some() {
                return Some((n, line));
            }
        }
    }
}

/// `line` up to its first `#`.
pub(crate) fn strip_comment(line: &[u8]) -> &[u8] {
    match line.iter().position(|&b| b == b'#') {
        Some(i) => &line[..i],
        None => line,
    }
}

/// The white-space separated words of a line.
pub(crate) fn words(line: &[u8]) -> impl Iterator<Item = &[u8]> {
    line.split(|b| b.is_ascii_whitespace())
        .filter(|w| !w.is_empty())
}

/// A stream of white-space separated tokens that spans lines and knows the line of each token.
pub(crate) struct Tokens<'a> {
    bytes: &'a [u8],
    pos: usize,
    line: u64,
}

impl<'a> Tokens<'a> {
    /// Tokens of `bytes`, whose first byte is on line `first_line`.
    pub(crate) fn new(bytes: &'a [u8], first_line: u64) -> Tokens<'a> {
        Tokens {
            bytes,
            pos: 0,
            line: first_line,
        }
    }

    /// Skips white space, so that [`Tokens::line`] is the line of the next token.
    pub(crate) fn skip_space(&mut self) {
        while let Some(&b) = self.bytes.get(self.pos) {
            if !b.is_ascii_whitespace() {
                break;
            }
            if b == b'\n' {
                self.line += 1;
            }
            self.pos += 1;
        }
    }

    /// The next token and its line.
    pub(crate) fn next_token(&mut self) -> Option<(&'a [u8], u64)> {
        self.skip_space();
        let start = self.pos;
        while let Some(&b) = self.bytes.get(self.pos) {
            if b.is_ascii_whitespace() {
                break;
            }
            self.pos += 1;
        }
        (self.pos > start).then(|| (&self.bytes[start..self.pos], self.line))
    }

    /// Skips the rest of the current line, including its terminator.
    pub(crate) fn skip_line(&mut self) {
        match self.bytes[self.pos..].iter().position(|&b| b == b'\n') {
            Some(i) => {
                self.pos += i + 1;
                self.line += 1;
            }
            None => self.pos = self.bytes.len(),
        }
    }

    /// The line the scanner is on: after the last token, or where the input ends.
    pub(crate) fn line(&self) -> u64 {
        self.line
    }

    /// True when only white space is left.
    pub(crate) fn at_end(&mut self) -> bool {
        self.skip_space();
        self.pos >= self.bytes.len()
    }
}

/// The UTF-8 byte-order mark, which some editors put at the start of text files.
pub(crate) const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Length of the byte-order mark at the start of `bytes`: 3 or 0.
pub(crate) fn bom_len(bytes: &[u8]) -> usize {
    if bytes.starts_with(BOM) {
        BOM.len()
    } else {
        0
    }
}

/// A token for a message, cut to a readable length and [`escape`]d.
pub(crate) fn show(tok: &[u8]) -> String {
    show_at_most(tok, 40)
}

/// At most `max` bytes of `tok` for a message, [`escape`]d, with `...` when cut.
pub(crate) fn show_at_most(tok: &[u8], max: usize) -> String {
    let mut s = escape(&tok[..tok.len().min(max)]);
    if tok.len() > max {
        s.push_str("...");
    }
    s
}

/// File content made safe to print: control characters (`\t`, `\u{1b}`, ...), the
/// invisible characters that reorder or hide text (bidirectional controls, the byte-order
/// mark) and bytes that are not UTF-8 (`\xff`) written as escapes, so that a message never
/// sends raw control bytes to a terminal.
pub(crate) fn escape(bytes: &[u8]) -> String {
    use std::fmt::Write;
    let mut out = String::with_capacity(bytes.len());
    for chunk in bytes.utf8_chunks() {
        for c in chunk.valid().chars() {
            let hidden = matches!(
                c,
                '\u{200b}'..='\u{200f}' | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{feff}'
            );
            if c.is_control() || hidden {
                out.extend(c.escape_default());
            } else {
                out.push(c);
            }
        }
        for b in chunk.invalid() {
            let _ = write!(out, "\\x{b:02x}");
        }
    }
    out
}

/// Parses a finite `f32`. `what` names the value in the error message ("x coordinate").
pub(crate) fn parse_f32(tok: &[u8], what: &str) -> Result<f32, String> {
    let v: f32 = std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("{what} `{}` is not a number", show(tok)))?;
    finite(v, tok, what)
}

fn finite(v: f32, tok: &[u8], what: &str) -> Result<f32, String> {
    if v.is_nan() {
        Err(format!("{what} is NaN (`{}`)", show(tok)))
    } else if v.is_infinite() {
        Err(format!(
            "{what} `{}` is infinite or beyond the f32 range",
            show(tok)
        ))
    } else {
        Ok(v)
    }
}

/// Parses any number the standard library parses, NaN and infinities included.
pub(crate) fn parse_any<T: std::str::FromStr>(tok: &[u8], what: &str) -> Result<T, String> {
    std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| format!("{what} `{}` is not a number", show(tok)))
}

/// Parses an integer; `what` names it in the error message ("vertex index").
pub(crate) fn parse_int(tok: &[u8], what: &str) -> Result<i64, String> {
    std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| {
            if is_integer_syntax(tok) {
                format!("{what} `{}` is out of range", show(tok))
            } else {
                format!("{what} `{}` is not an integer", show(tok))
            }
        })
}

/// Parses a non-negative integer count; `what` names it in the error message.
pub(crate) fn parse_count(tok: &[u8], what: &str) -> Result<u64, String> {
    std::str::from_utf8(tok)
        .ok()
        .and_then(|s| s.parse().ok())
        .ok_or_else(|| match tok {
            [b'-', ..] if is_integer_syntax(tok) => {
                format!("{what} `{}` is negative", show(tok))
            }
            _ if is_integer_syntax(tok) => format!("{what} `{}` is out of range", show(tok)),
            _ => format!("{what} `{}` is not an integer", show(tok)),
        })
}

/// True when the token is written as an integer (no decimal point, exponent, `inf` or `nan`).
pub(crate) fn is_integer_syntax(tok: &[u8]) -> bool {
    let digits = match tok {
        [b'+' | b'-', rest @ ..] => rest,
        _ => tok,
    };
    !digits.is_empty() && digits.iter().all(u8::is_ascii_digit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_number_and_strip_cr() {
        let mut l = Lines::new(b"a\r\n\nb # c\n  # only\nd");
        assert_eq!(l.next_content(), Some((1, &b"a"[..])));
        assert_eq!(l.next_content(), Some((3, &b"b "[..])));
        assert_eq!(l.next_content(), Some((5, &b"d"[..])));
        assert_eq!(l.next_content(), None);
        assert_eq!(l.next_number(), 5);
    }

    #[test]
    fn tokens_track_lines() {
        let mut t = Tokens::new(b" a b\n\n c\nd e\n", 7);
        assert_eq!(t.next_token(), Some((&b"a"[..], 7)));
        assert_eq!(t.next_token(), Some((&b"b"[..], 7)));
        assert_eq!(t.next_token(), Some((&b"c"[..], 9)));
        t.skip_line();
        assert_eq!(t.next_token(), Some((&b"d"[..], 10)));
        t.skip_line();
        assert_eq!(t.next_token(), None);
        assert!(t.at_end());
        assert_eq!(t.line(), 11);
    }

    #[test]
    fn byte_order_mark_is_skipped() {
        let mut l = Lines::new(b"\xEF\xBB\xBFv 1\nf");
        assert_eq!(l.next_line(), Some((1, &b"v 1"[..])));
        assert_eq!(l.offset(), 7);
        assert_eq!(
            Lines::new(b"\xEF\xBB").next_line(),
            Some((1, &b"\xEF\xBB"[..]))
        );
    }

    #[test]
    fn shown_content_has_no_control_bytes() {
        assert_eq!(show(b"a\x1b[31mb\tc\x7f"), "a\\u{1b}[31mb\\tc\\u{7f}");
        assert_eq!(show(b"\xff\xfeok"), "\\xff\\xfeok");
        assert_eq!(show("é\u{202e}x".as_bytes()), "é\\u{202e}x");
        assert_eq!(show_at_most(b"abcdef", 3), "abc...");
        let all: Vec<u8> = (0..=255).collect();
        assert!(!show_at_most(&all, 256).chars().any(char::is_control));
    }

    #[test]
    fn numbers() {
        assert_eq!(
            parse_f32(b"-0", "x").unwrap().to_bits(),
            (-0.0f32).to_bits()
        );
        assert!(parse_f32(b"nan", "x").unwrap_err().contains("NaN"));
        assert!(parse_f32(b"1e39", "x").unwrap_err().contains("infinite"));
        assert!(parse_f32(b"1x", "x").unwrap_err().contains("not a number"));
        assert!(is_integer_syntax(b"-12"));
        assert!(!is_integer_syntax(b"1.0"));
        assert!(!is_integer_syntax(b"-"));
    }
}
