//! Labels encoding 1 of `PART` (FORMAT.md §3.10.2): the parts' names range coded instead
//! of JSON. Most of a small file's labels are JSON syntax and repeated names (every part
//! spells `"material":` and its material again), so each name is spelled once, where it is
//! first used, and referred to by number afterwards.

use crate::edgebreaker::coder::{code_uint, Bit, Bits, Decoder, Encoder, UintModel};
use crate::mesh::{Part, Parts};

/// Labels encoding 0: JSON (FORMAT.md §3.10).
pub const JSON: u8 = 0;
/// Labels encoding 1: range coded (FORMAT.md §3.10.2).
pub const CODED: u8 = 1;

/// The most bytes the labels of a `J`-byte coded stream may decode to (V51): a coded name
/// may be referred to many times, and this keeps what a reader allocates in proportion to
/// the input.
pub fn decoded_bound(coded_len: u32) -> u64 {
    16 * u64::from(coded_len) + 4096
}

/// The adaptive state of one stream: a reference model per key (object, group, material,
/// library), the count of libraries, name lengths, and an order-0 tree of 255 byte models.
struct Models {
    reference: [UintModel; 4],
    libraries: UintModel,
    length: UintModel,
    byte: [Bit; 256],
}

impl Models {
    fn new() -> Models {
        Models {
            reference: Default::default(),
            libraries: UintModel::default(),
            length: UintModel::default(),
            byte: [Bit::default(); 256],
        }
    }
}

/// Reference codes: 0 no name, 1 a new name spelled next, `2 + i` name `i` of the table.
const ABSENT: u64 = 0;
const NEW: u64 = 1;

/// Codes one byte, most significant bit first, through the byte tree.
fn code_byte<B: Bits>(b: &mut B, tree: &mut [Bit; 256], byte: u8) -> u8 {
    let mut node = 1usize;
    for i in (0..8).rev() {
        node = 2 * node + b.bit(&mut tree[node], u32::from(byte >> i) & 1) as usize;
    }
    (node - 256) as u8
}

/// The coded labels of `parts` (the parts and the material libraries, not `of_triangle`).
pub(crate) fn encode<'a>(parts: &'a Parts) -> Vec<u8> {
    let mut e = Encoder::new();
    let mut m = Models::new();
    let mut table: Vec<&str> = Vec::new();
    let mut name = |e: &mut Encoder, m: &mut Models, key: usize, s: Option<&'a str>| {
        let Some(s) = s else {
            code_uint(e, &mut m.reference[key], ABSENT);
            return;
        };
        match table.iter().position(|&t| t == s) {
            Some(i) => {
                code_uint(e, &mut m.reference[key], 2 + i as u64);
            }
            None => {
                code_uint(e, &mut m.reference[key], NEW);
                code_uint(e, &mut m.length, s.len() as u64);
                for &byte in s.as_bytes() {
                    code_byte(e, &mut m.byte, byte);
                }
                table.push(s);
            }
        }
    };
    for p in &parts.parts {
        for (key, s) in [&p.object, &p.group, &p.material].into_iter().enumerate() {
            name(&mut e, &mut m, key, s.as_deref());
        }
    }
    code_uint(
        &mut e,
        &mut m.libraries,
        parts.material_libraries.len() as u64,
    );
    for lib in &parts.material_libraries {
        name(&mut e, &mut m, 3, Some(lib.as_str()));
    }
    e.finish()
}

/// The bytes the labels decode to, as [`decoded_bound`] counts them: one per part and per
/// library, and the bytes of every name each refers to.
pub(crate) fn decoded_size(parts: &Parts) -> u64 {
    let len = |s: &Option<String>| s.as_ref().map_or(0, |s| s.len() as u64);
    let of_parts: u64 = parts
        .parts
        .iter()
        .map(|p| 1 + len(&p.object) + len(&p.group) + len(&p.material))
        .sum();
    let of_libraries: u64 = parts
        .material_libraries
        .iter()
        .map(|l| 1 + l.len() as u64)
        .sum();
    of_parts + of_libraries
}

/// Decodes the labels of `count` parts from `stream` (at byte `base` of the file, for
/// errors); `Err((offset, message))` for a reference to no name, a library without one, a
/// name that is not UTF-8, labels beyond [`decoded_bound`], or an overrun.
pub(crate) fn decode(stream: &[u8], base: usize, count: u32) -> Result<Parts, (u64, String)> {
    let bound = decoded_bound(stream.len() as u32);
    let mut size = u64::from(count);
    if size > bound {
        return Err((
            base as u64,
            format!("{count} parts exceed the {bound} bytes the labels may decode to"),
        ));
    }
    let mut d = Decoder::new(stream, base);
    let mut m = Models::new();
    let mut table: Vec<String> = Vec::new();
    let mut name = |d: &mut Decoder, m: &mut Models, key: usize, size: &mut u64| {
        let at = d.offset();
        let fail = |message: String| Err((at, message));
        let r = match code_uint(d, &mut m.reference[key], 0) {
            Some(r) if r <= table.len() as u64 + 1 => r,
            _ => return fail(format!("a reference to none of the {} names", table.len())),
        };
        let s = match r {
            ABSENT => return Ok(None),
            NEW => {
                let len = code_uint(d, &mut m.length, 0).unwrap_or(u64::MAX);
                if len > bound.saturating_sub(*size) {
                    return fail(format!("a name beyond the {bound} bytes of labels"));
                }
                let mut bytes = Vec::with_capacity(len as usize);
                for _ in 0..len {
                    bytes.push(code_byte(d, &mut m.byte, 0));
                    if d.overrun() {
                        return Err((d.offset(), "the stream ends inside a name".into()));
                    }
                }
                let Ok(s) = String::from_utf8(bytes) else {
                    return fail("a name that is not UTF-8".into());
                };
                table.push(s.clone());
                s
            }
            i => table[(i - 2) as usize].clone(),
        };
        *size += s.len() as u64;
        if *size > bound {
            return fail(format!("labels beyond {bound} bytes"));
        }
        Ok(Some(s))
    };
    let mut parts = Parts::default();
    for _ in 0..count {
        let mut part = Part::default();
        for key in 0..3 {
            let s = name(&mut d, &mut m, key, &mut size)?;
            *[&mut part.object, &mut part.group, &mut part.material][key] = s;
        }
        parts.parts.push(part);
        if d.overrun() {
            return Err((d.offset(), "the stream ends inside the parts".into()));
        }
    }
    let at = d.offset();
    let libraries = code_uint(&mut d, &mut m.libraries, 0).unwrap_or(u64::MAX);
    if libraries > bound - size {
        return Err((at, format!("{libraries} material libraries")));
    }
    for _ in 0..libraries {
        let at = d.offset();
        size += 1;
        match name(&mut d, &mut m, 3, &mut size)? {
            Some(lib) => parts.material_libraries.push(lib),
            None => return Err((at, "a material library without a name".into())),
        }
    }
    if d.overrun() {
        return Err((d.offset(), "the stream ends inside the libraries".into()));
    }
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parts() -> Parts {
        let mut parts = Parts::default();
        for (o, g, mat) in [
            (Some("Cube"), None, Some("Material.001")),
            (Some("Cube"), Some("legs é"), Some("Material.003")),
            (None, None, None),
            (None, Some(""), Some("Material.001")),
        ] {
            parts.parts.push(Part {
                object: o.map(str::to_string),
                group: g.map(str::to_string),
                material: mat.map(str::to_string),
            });
        }
        parts.material_libraries = vec!["a.mtl".into(), "Cube".into()];
        parts
    }

    #[test]
    fn labels_round_trip_and_are_smaller_than_json() {
        let parts = parts();
        let coded = encode(&parts);
        let json = serde_json::to_vec(&parts).unwrap();
        assert!(
            coded.len() < json.len() / 2,
            "{} vs {}",
            coded.len(),
            json.len()
        );
        assert!(decoded_size(&parts) <= decoded_bound(coded.len() as u32));
        let back = decode(&coded, 0, parts.parts.len() as u32).unwrap();
        assert_eq!(back, parts);
    }

    #[test]
    fn no_labels_round_trip() {
        let parts = Parts {
            parts: vec![Part::default()],
            ..Parts::default()
        };
        let coded = encode(&parts);
        assert_eq!(decode(&coded, 0, 1).unwrap(), parts);
    }

    /// A stream of one part without names, then `libraries` material libraries coded with
    /// reference `r` each (1: a new name of `bytes`).
    fn stream(libraries: u64, r: u64, bytes: &[u8]) -> Vec<u8> {
        let mut e = Encoder::new();
        let mut m = Models::new();
        for key in 0..3 {
            code_uint(&mut e, &mut m.reference[key], ABSENT);
        }
        code_uint(&mut e, &mut m.libraries, libraries);
        for _ in 0..libraries {
            code_uint(&mut e, &mut m.reference[3], r);
            if r == NEW {
                code_uint(&mut e, &mut m.length, bytes.len() as u64);
                for &b in bytes {
                    code_byte(&mut e, &mut m.byte, b);
                }
            }
        }
        e.finish()
    }

    #[test]
    fn damaged_names_are_refused() {
        let ok = decode(&stream(1, NEW, b"a.mtl"), 0, 1).unwrap();
        assert_eq!(ok.material_libraries, ["a.mtl"]);
        let message = |s: Vec<u8>| decode(&s, 0, 1).unwrap_err().1;
        assert!(message(stream(1, ABSENT, b"")).contains("without a name"));
        assert!(message(stream(1, NEW, &[0xC3, 0x28])).contains("not UTF-8"));
        assert!(message(stream(1, 3, b"")).contains("none of the 0 names"));
        assert!(message(stream(1 << 20, NEW, b"")).contains("material libraries"));
        // One long name, then references to it: the bound stops them.
        let long = vec![b'x'; 3000];
        let mut e = Encoder::new();
        let mut m = Models::new();
        for key in 0..3 {
            code_uint(&mut e, &mut m.reference[key], ABSENT);
        }
        code_uint(&mut e, &mut m.libraries, 200);
        code_uint(&mut e, &mut m.reference[3], NEW);
        code_uint(&mut e, &mut m.length, long.len() as u64);
        for &b in &long {
            code_byte(&mut e, &mut m.byte, b);
        }
        for _ in 1..200 {
            code_uint(&mut e, &mut m.reference[3], 2);
        }
        assert!(message(e.finish()).contains("labels beyond"));
    }

    #[test]
    fn too_many_parts_are_refused_before_decoding() {
        let err = decode(&[], 0, 5000).unwrap_err();
        assert!(err.1.contains("exceed"), "{}", err.1);
    }
}
