//! STL (stereolithography) reading and writing.
//!
//! A file is binary when its length is exactly `84 + 50 * count`, with `count` the
//! little-endian `u32` at byte 80; otherwise it is ASCII when it starts with `solid` (in any
//! case, after an optional UTF-8 byte-order mark and white space); otherwise it is an error.
//! A file that starts with `solid`, fails to parse as ASCII and holds a NUL byte is reported
//! as a binary file of the wrong length.
//!
//! ASCII files are `solid [name]`, then facets `facet normal nx ny nz`, `outer loop`,
//! `vertex x y z` (three or more; a polygon is fan-triangulated), `endloop`, `endfacet`, and
//! `endsolid [name]`; several solids may follow one another. Keywords are matched without
//! regard to case. A file that ends after a complete facet but before `endsolid` is read with
//! a warning; one that ends after `solid` with no facet is an error (a file that declares an
//! empty solid, `solid` then `endsolid`, is an empty mesh).
//!
//! STL stores no shared vertices: every triangle corner becomes a vertex of its own, unless
//! [`ReadOptions::weld`] merges corners with bit-identical positions (`-0.0` equal to `0.0`)
//! in order of first appearance. The facet normals are ignored (they are per face, and often
//! wrong or zero); the mesh gets no attributes.

use std::collections::HashMap;
use std::io::{BufWriter, Write};

use super::lex::{self, Tokens};
use super::{
    check_writable, perr, push_fan, Float, Loaded, ReadOptions, MAX_TRIANGLES, MAX_VERTICES,
};
use crate::error::{Error, Location, Result};
use crate::mesh::Mesh;

const FORMAT: &str = "STL";

/// Size of the binary header: 80 bytes of free text and the triangle count.
const HEADER: u64 = 84;
/// Size of one binary triangle: normal, three vertices, attribute byte count.
const TRIANGLE: u64 = 50;

/// Vertices as they are found, welded or not.
struct Vertices {
    positions: Vec<[f32; 3]>,
    weld: Option<HashMap<[u32; 3], u32>>,
}

impl Vertices {
    fn new(weld: bool, capacity: usize) -> Vertices {
        Vertices {
            positions: Vec::with_capacity(if weld { 0 } else { capacity }),
            weld: weld.then(HashMap::new),
        }
    }

    /// The vertex at `p`: a new one, or with welding the first one at the same position.
    fn add(&mut self, p: [f32; 3]) -> Result<u32, String> {
        let next = self.positions.len() as u64;
        let push = |positions: &mut Vec<[f32; 3]>| {
            if next >= MAX_VERTICES {
                return Err(format!("more than {MAX_VERTICES} vertices"));
            }
            positions.push(p);
            Ok(next as u32)
        };
        match &mut self.weld {
            None => push(&mut self.positions),
            Some(map) => {
                // Adding 0.0 turns -0.0 into 0.0 and leaves every other finite value alone.
                let key = p.map(|x| (x + 0.0).to_bits());
                if let Some(&v) = map.get(&key) {
                    return Ok(v);
                }
                let v = push(&mut self.positions)?;
                map.insert(key, v);
                Ok(v)
            }
        }
    }
}

/// Reads an STL file, binary or ASCII.
///
/// # Errors
/// [`crate::Error::Parse`] for a malformed file: binary problems with the byte offset, ASCII
/// problems with the line.
pub fn read(bytes: &[u8], opts: &ReadOptions) -> Result<Loaded> {
    let len = bytes.len() as u64;
    let binary = bytes.get(80..84).map(|b| {
        let count = u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        (count, HEADER + TRIANGLE * u64::from(count))
    });
    if let Some((count, size)) = binary {
        if size == len {
            return read_binary(bytes, count, opts);
        }
    }
    let size_error = |count: u32, size: u64| {
        let message = if size > len {
            format!(
                "truncated binary STL: the header declares {count} triangles, which need {size} \
                 bytes, but the file ends at byte {len}"
            )
        } else {
            format!(
                "binary STL with {} bytes after the {count} triangles the header declares",
                len - size
            )
        };
        perr(FORMAT, Location::Byte(size.min(len)), message)
    };
    let text = bytes[lex::bom_len(bytes)..].trim_ascii_start();
    if text.len() >= 5 && text[..5].eq_ignore_ascii_case(b"solid") {
        return read_ascii(&bytes[lex::bom_len(bytes)..], opts).map_err(|e| match binary {
            Some((count, size)) if bytes.contains(&0) => size_error(count, size),
            _ => e,
        });
    }
    match binary {
        Some((count, size)) => Err(size_error(count, size)),
        None => Err(perr(
            FORMAT,
            Location::Whole,
            format!(
                "not an STL file: {len} bytes, shorter than a binary header, and no `solid` at \
                 the start"
            ),
        )),
    }
}

fn read_binary(bytes: &[u8], count: u32, opts: &ReadOptions) -> Result<Loaded> {
    if u64::from(count) > MAX_TRIANGLES {
        return Err(perr(
            FORMAT,
            Location::Byte(80),
            format!("triangle count {count} exceeds the limit of {MAX_TRIANGLES}"),
        ));
    }
    // The caller checked that the file holds exactly `count` triangles.
    let count = count as usize;
    let mut vertices = Vertices::new(opts.weld, 3 * count);
    let mut triangles = Vec::with_capacity(count);
    for (t, record) in bytes[HEADER as usize..]
        .chunks_exact(TRIANGLE as usize)
        .enumerate()
    {
        let mut tri = [0u32; 3];
        for (k, v) in tri.iter_mut().enumerate() {
            let mut p = [0.0f32; 3];
            for (j, x) in p.iter_mut().enumerate() {
                let at = 12 + 12 * k + 4 * j;
                let b = &record[at..at + 4];
                *x = f32::from_le_bytes([b[0], b[1], b[2], b[3]]);
                if !x.is_finite() {
                    let offset = HEADER + TRIANGLE * t as u64 + at as u64;
                    return Err(perr(
                        FORMAT,
                        Location::Byte(offset),
                        format!(
                            "triangle {t}, vertex {k}: coordinate is {}",
                            if x.is_nan() { "NaN" } else { "infinite" }
                        ),
                    ));
                }
            }
            *v = vertices
                .add(p)
                .map_err(|m| perr(FORMAT, Location::Byte(HEADER + TRIANGLE * t as u64), m))?;
        }
        triangles.push(tri);
    }
    Ok(Loaded {
        mesh: Mesh::new(vertices.positions, triangles),
        warnings: Vec::new(),
    })
}

fn read_ascii(bytes: &[u8], opts: &ReadOptions) -> Result<Loaded> {
    let mut tokens = Tokens::new(bytes, 1);
    let mut vertices = Vertices::new(opts.weld, 0);
    let mut triangles = Vec::new();
    let mut warnings = Vec::new();
    let mut poly: Vec<u32> = Vec::new();
    let mut solids = 0u64;
    let keyword = |tok: &[u8], k: &str| tok.eq_ignore_ascii_case(k.as_bytes());
    let unexpected = |expected: &str, found: Option<(&[u8], u64)>, end: u64| -> Error {
        match found {
            Some((tok, line)) => perr(
                FORMAT,
                Location::Line(line),
                format!("expected {expected}, found `{}`", lex::show(tok)),
            ),
            None => perr(
                FORMAT,
                Location::Line(end),
                format!("the file ends where {expected} was expected"),
            ),
        }
    };
    'solids: loop {
        let next = tokens.next_token();
        match next {
            Some((tok, _)) if keyword(tok, "solid") => tokens.skip_line(),
            None if solids > 0 => break,
            _ => return Err(unexpected("`solid`", next, tokens.line())),
        }
        solids += 1;
        loop {
            let next = tokens.next_token();
            let facet_line = match next {
                Some((tok, _)) if keyword(tok, "endsolid") => {
                    tokens.skip_line();
                    break;
                }
                Some((tok, line)) if keyword(tok, "facet") => line,
                None if triangles.is_empty() => {
                    // Nothing but `solid`: text that happens to start with the word.
                    return Err(perr(
                        FORMAT,
                        Location::Line(tokens.line()),
                        "the file ends after `solid` without any `facet` or `endsolid`",
                    ));
                }
                None => {
                    warnings.push("the file ends without `endsolid`".to_string());
                    break 'solids;
                }
                _ => return Err(unexpected("`facet` or `endsolid`", next, tokens.line())),
            };
            let expect = |k: &str, tokens: &mut Tokens| {
                let next = tokens.next_token();
                match next {
                    Some((tok, _)) if keyword(tok, k) => Ok(()),
                    _ => Err(unexpected(&format!("`{k}`"), next, tokens.line())),
                }
            };
            expect("normal", &mut tokens)?;
            for _ in 0..3 {
                // The normal is ignored, whatever it says (some writers put `nan` there).
                if tokens.next_token().is_none() {
                    return Err(unexpected("a normal component", None, tokens.line()));
                }
            }
            expect("outer", &mut tokens)?;
            expect("loop", &mut tokens)?;
            poly.clear();
            loop {
                let next = tokens.next_token();
                match next {
                    Some((tok, _)) if keyword(tok, "endloop") => break,
                    Some((tok, line)) if keyword(tok, "vertex") => {
                        let mut p = [0.0f32; 3];
                        for x in &mut p {
                            let Some((tok, line)) = tokens.next_token() else {
                                return Err(unexpected("a coordinate", None, tokens.line()));
                            };
                            *x = lex::parse_f32(tok, "coordinate")
                                .map_err(|m| perr(FORMAT, Location::Line(line), m))?;
                        }
                        let v = vertices
                            .add(p)
                            .map_err(|m| perr(FORMAT, Location::Line(line), m))?;
                        poly.push(v);
                    }
                    _ => return Err(unexpected("`vertex` or `endloop`", next, tokens.line())),
                }
            }
            if poly.len() < 3 {
                return Err(perr(
                    FORMAT,
                    Location::Line(facet_line),
                    format!(
                        "facet with {} vertices; a facet needs at least 3",
                        poly.len()
                    ),
                ));
            }
            expect("endfacet", &mut tokens)?;
            push_fan(&mut triangles, &poly)
                .map_err(|m| perr(FORMAT, Location::Line(facet_line), m))?;
        }
    }
    Ok(Loaded {
        mesh: Mesh::new(vertices.positions, triangles),
        warnings,
    })
}

/// The unit normal of a triangle, or zero for a degenerate one.
fn face_normal(mesh: &Mesh, t: [u32; 3]) -> [f32; 3] {
    let [a, b, c] = t.map(|v| mesh.positions[v as usize]);
    let u = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
    let w = [c[0] - a[0], c[1] - a[1], c[2] - a[2]];
    let n = [
        u[1] * w[2] - u[2] * w[1],
        u[2] * w[0] - u[0] * w[2],
        u[0] * w[1] - u[1] * w[0],
    ];
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if len > 0.0 && len.is_finite() {
        n.map(|x| x / len)
    } else {
        [0.0; 3]
    }
}

/// Writes a binary STL file: an 80-byte header that does not start with `solid`, the triangle
/// count, and per triangle its unit normal, its three corners and a zero attribute count.
/// Vertex sharing and attributes are lost.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write_binary<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    let mut header = [b' '; 80];
    let text = b"binary STL written by lrmesh";
    header[..text.len()].copy_from_slice(text);
    w.write_all(&header)?;
    // check_writable bounds the triangle count below u32::MAX.
    w.write_all(&(mesh.triangles.len() as u32).to_le_bytes())?;
    for &t in &mesh.triangles {
        for x in face_normal(mesh, t) {
            w.write_all(&x.to_le_bytes())?;
        }
        for v in t {
            for x in mesh.positions[v as usize] {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        w.write_all(&[0, 0])?;
    }
    w.flush()
}

/// Writes an ASCII STL file with one solid named `lrmesh`, floats in the shortest form that
/// reads back to the same bits. Vertex sharing and attributes are lost.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write_ascii<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    writeln!(w, "solid lrmesh")?;
    for &t in &mesh.triangles {
        let n = face_normal(mesh, t);
        writeln!(
            w,
            "  facet normal {} {} {}",
            Float(n[0]),
            Float(n[1]),
            Float(n[2])
        )?;
        writeln!(w, "    outer loop")?;
        for v in t {
            let p = mesh.positions[v as usize];
            writeln!(
                w,
                "      vertex {} {} {}",
                Float(p[0]),
                Float(p[1]),
                Float(p[2])
            )?;
        }
        writeln!(w, "    endloop")?;
        writeln!(w, "  endfacet")?;
    }
    writeln!(w, "endsolid lrmesh")?;
    w.flush()
}
