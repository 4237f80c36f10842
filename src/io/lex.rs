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
    /// Lines of `bytes`, starting at line 1.
    pub(crate) fn new(bytes: &'a [u8]) -> Lines<'a> {
        Lines {
            bytes,
            pos: 0,
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

/// A token for an error message: lossy UTF-8, cut to a readable length.
pub(crate) fn show(tok: &[u8]) -> String {
    const MAX: usize = 40;
    let s = String::from_utf8_lossy(&tok[..tok.len().min(MAX)]);
    if tok.len() > MAX {
        format!("{s}...")
    } else {
        s.into_owned()
    }
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
