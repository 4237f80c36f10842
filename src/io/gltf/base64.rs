//! Base64 (RFC 4648, standard alphabet) for `data:` URIs, and percent-decoding for relative
//! ones: small enough not to warrant a dependency.

const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

/// The value of a base64 digit.
fn digit(c: u8) -> Option<u32> {
    match c {
        b'A'..=b'Z' => Some(u32::from(c - b'A')),
        b'a'..=b'z' => Some(u32::from(c - b'a') + 26),
        b'0'..=b'9' => Some(u32::from(c - b'0') + 52),
        b'+' => Some(62),
        b'/' => Some(63),
        _ => None,
    }
}

/// Decodes base64 text; the `=` padding may be present or left out.
///
/// # Errors
/// A message naming the position of a character outside the alphabet, misplaced padding, or a
/// length that no byte string has.
pub(super) fn decode(text: &[u8]) -> Result<Vec<u8>, String> {
    let body_len = text.iter().rposition(|&c| c != b'=').map_or(0, |i| i + 1);
    let padding = text.len() - body_len;
    if padding > 2 || (padding > 0 && text.len() % 4 != 0) {
        return Err(format!(
            "bad base64 padding: {padding} `=` at the end of {} characters",
            text.len()
        ));
    }
    let body = &text[..body_len];
    if body.len() % 4 == 1 {
        return Err(format!(
            "bad base64 length: {} characters leave one over (a byte needs two)",
            body.len()
        ));
    }
    let mut out = Vec::with_capacity(body.len() / 4 * 3 + 2);
    for (chunk_index, chunk) in body.chunks(4).enumerate() {
        let mut bits = 0u32;
        for (k, &c) in chunk.iter().enumerate() {
            let Some(d) = digit(c) else {
                return Err(format!(
                    "invalid base64 character `{}` at position {}",
                    char::from(c).escape_default(),
                    4 * chunk_index + k
                ));
            };
            bits |= d << (18 - 6 * k);
        }
        let bytes = [(bits >> 16) as u8, (bits >> 8) as u8, bits as u8];
        out.extend_from_slice(&bytes[..chunk.len() - 1]);
    }
    Ok(out)
}

/// Encodes bytes as padded base64.
pub(super) fn encode(bytes: &[u8]) -> String {
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            chunk.get(1).copied().unwrap_or(0),
            chunk.get(2).copied().unwrap_or(0),
        ];
        let bits = u32::from(b[0]) << 16 | u32::from(b[1]) << 8 | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(bits >> (18 - 6 * k) & 63) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

/// Decodes `%XX` escapes of a URI (`my%20mesh.bin` names `my mesh.bin`).
///
/// # Errors
/// A message for a `%` not followed by two hexadecimal digits, or a result that is not UTF-8.
pub(super) fn percent_decode(uri: &str) -> Result<String, String> {
    let bytes = uri.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        if bytes[i] == b'%' {
            let hex = bytes
                .get(i + 1..i + 3)
                .and_then(|h| std::str::from_utf8(h).ok())
                .and_then(|h| u8::from_str_radix(h, 16).ok());
            let Some(b) = hex else {
                return Err(format!("bad percent escape at position {i} of the URI"));
            };
            out.push(b);
            i += 3;
        } else {
            out.push(bytes[i]);
            i += 1;
        }
    }
    String::from_utf8(out).map_err(|_| "the percent-decoded URI is not UTF-8".to_string())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_every_length() {
        let data: Vec<u8> = (0..=255u8).collect();
        for n in 0..40 {
            let text = encode(&data[..n]);
            assert_eq!(text.len() % 4, 0);
            assert_eq!(decode(text.as_bytes()).unwrap(), &data[..n]);
            let unpadded = text.trim_end_matches('=');
            assert_eq!(decode(unpadded.as_bytes()).unwrap(), &data[..n]);
        }
        assert_eq!(encode(b"Man"), "TWFu");
        assert_eq!(encode(b"Ma"), "TWE=");
    }

    #[test]
    fn rejects_bad_text() {
        assert!(decode(b"TW!u").unwrap_err().contains("position 2"));
        assert!(decode(b"T").unwrap_err().contains("length"));
        assert!(decode(b"TW===").unwrap_err().contains("padding"));
        assert!(decode(b"TWE=TWE=").is_err());
    }

    #[test]
    fn percent_decodes() {
        assert_eq!(percent_decode("a%20b.bin").unwrap(), "a b.bin");
        assert!(percent_decode("a%2").is_err());
        assert!(percent_decode("a%zz").is_err());
    }
}
