//! OFF (Object File Format) reading and writing.
//!
//! The header keyword is `[ST][C][N]OFF`: `ST` adds texture coordinates, `C` colors and `N`
//! normals to every vertex line. The `4` (four-dimensional) and `n` (dimension in the file)
//! prefixes and binary OFF are rejected. The counts `V F [E]` follow the keyword on the same
//! line or on the next one; the edge count is ignored. `#` starts a comment anywhere; blank
//! lines are skipped. The parser is line-based: one vertex or face per line.
//!
//! A vertex line is `x y z [nx ny nz] [r g b [a]] [s t]`. In a plain `OFF` file a vertex line
//! with 3 or 4 extra values carries a color; colors are kept when every vertex line has one,
//! and ignored with a warning otherwise.
//!
//! **Colors.** The rule applies to all colors of a file together: they are fractions in
//! `0..=1` (scaled by 255 and rounded, values outside clamped with a warning) when any color
//! component in the file is written with a decimal point or exponent, or when no component
//! exceeds 1; otherwise they are integers in `0..=255` and a component outside that range is
//! an error. A missing alpha is 255.
//!
//! A face line is `n i0 ... i(n-1)` followed by an optional face color, which is ignored.
//! Content after the last face is ignored with a warning.

use std::io::{BufWriter, Write};

use super::lex::{self, Lines};
use super::{
    check_writable, perr, push_fan, Float, Loaded, RawColors, ReadOptions, MAX_TRIANGLES,
    MAX_VERTICES,
};
use crate::error::{Location, Result};
use crate::mesh::{Mesh, Semantic};

const FORMAT: &str = "OFF";

/// The smallest vertex line, `0 0 0` and its line end.
const MIN_VERTEX_BYTES: u64 = 6;
/// The smallest face line, `3 0 0 0` and its line end.
const MIN_FACE_BYTES: u64 = 8;

/// Which optional parts the vertex lines have, from the header keyword.
#[derive(Debug, Clone, Copy, Default)]
struct Layout {
    texcoords: bool,
    colors: bool,
    normals: bool,
}

fn parse_keyword(word: &[u8], line: u64) -> Result<Layout> {
    let bad = || {
        perr(
            FORMAT,
            Location::Line(line),
            format!(
                "expected the header keyword `OFF` (optionally prefixed by ST, C, N, as in \
                 `COFF` or `STCNOFF`), found `{}`",
                lex::show(word)
            ),
        )
    };
    let mut rest = word;
    let mut layout = Layout::default();
    if let Some(r) = rest.strip_prefix(b"ST") {
        layout.texcoords = true;
        rest = r;
    }
    if let Some(r) = rest.strip_prefix(b"C") {
        layout.colors = true;
        rest = r;
    }
    if let Some(r) = rest.strip_prefix(b"N") {
        layout.normals = true;
        rest = r;
    }
    if rest.starts_with(b"4") {
        return Err(perr(
            FORMAT,
            Location::Line(line),
            "four-dimensional vertices (`4OFF`) are not supported",
        ));
    }
    if rest.starts_with(b"n") && rest.len() > 3 {
        return Err(perr(
            FORMAT,
            Location::Line(line),
            "vertices of arbitrary dimension (`nOFF`) are not supported",
        ));
    }
    if rest != b"OFF" {
        return Err(bad());
    }
    Ok(layout)
}

/// Reads an OFF file.
///
/// # Errors
/// [`crate::Error::Parse`] for a malformed file, with the 1-based line of the problem.
pub fn read(bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    let mut lines = Lines::new(bytes);
    let mut warnings = Vec::new();

    let Some((header_line, header)) = lines.next_content() else {
        return Err(perr(FORMAT, Location::Whole, "empty file: no `OFF` header"));
    };
    let mut header_words = lex::words(header);
    let keyword = header_words.next().unwrap_or_default();
    let layout = parse_keyword(keyword, header_line)?;
    let mut count_words: Vec<&[u8]> = header_words.collect();
    let mut count_line = header_line;
    if count_words.first() == Some(&&b"BINARY"[..]) {
        return Err(perr(
            FORMAT,
            Location::Line(header_line),
            "binary OFF is not supported",
        ));
    }
    if count_words.is_empty() {
        let Some((n, line)) = lines.next_content() else {
            return Err(perr(
                FORMAT,
                Location::Line(lines.next_number()),
                "the file ends before the vertex and face counts",
            ));
        };
        count_words = lex::words(line).collect();
        count_line = n;
    }
    let count_err = |m: String| perr(FORMAT, Location::Line(count_line), m);
    if !(2..=3).contains(&count_words.len()) {
        return Err(count_err(format!(
            "expected the counts `vertices faces [edges]`, found {} values",
            count_words.len()
        )));
    }
    let mut counts = [0u64; 2];
    for (c, tok) in counts.iter_mut().zip(&count_words) {
        *c = lex::parse_count(tok, "count").map_err(count_err)?;
    }
    if let Some(tok) = count_words.get(2) {
        lex::parse_count(tok, "edge count").map_err(count_err)?;
    }
    let [nv, nf] = counts;
    if nv > MAX_VERTICES {
        return Err(count_err(format!(
            "vertex count {nv} exceeds the limit of {MAX_VERTICES}"
        )));
    }
    if nf > MAX_TRIANGLES {
        return Err(count_err(format!(
            "face count {nf} exceeds the limit of {MAX_TRIANGLES}"
        )));
    }
    let remaining = (bytes.len() - lines.offset()) as u64;
    let needed = nv.checked_mul(MIN_VERTEX_BYTES).and_then(|a| {
        nf.checked_mul(MIN_FACE_BYTES)
            .and_then(|b| a.checked_add(b))
    });
    if needed.is_none_or(|n| n > remaining + 1) {
        return Err(count_err(format!(
            "the header declares {nv} vertices and {nf} faces, which need at least {} bytes, \
             but only {remaining} bytes follow",
            needed.map_or_else(|| "more than 2^64".to_string(), |n| n.to_string())
        )));
    }

    // The check above bounds both counts by the input length.
    let mut positions = Vec::with_capacity(nv as usize);
    let mut normals = Vec::with_capacity(if layout.normals { nv as usize } else { 0 });
    let mut texcoords = Vec::with_capacity(if layout.texcoords { nv as usize } else { 0 });
    let mut colors = RawColors::new(FORMAT);
    let base = 3 + if layout.normals { 3 } else { 0 } + if layout.texcoords { 2 } else { 0 };
    let mut toks: Vec<&[u8]> = Vec::new();

    for i in 0..nv {
        let Some((n, line)) = lines.next_content() else {
            return Err(perr(
                FORMAT,
                Location::Line(lines.next_number()),
                format!("the file ends after {i} of {nv} vertices"),
            ));
        };
        let err = |m: String| perr(FORMAT, Location::Line(n), m);
        toks.clear();
        toks.extend(lex::words(line));
        let extra = toks.len().checked_sub(base);
        let color_count = match extra {
            Some(k @ (3 | 4)) => k,
            Some(0) if !layout.colors => 0,
            _ => {
                let expected = if layout.colors {
                    format!("{} or {}", base + 3, base + 4)
                } else {
                    format!("{base}, or {} or {} with a color", base + 3, base + 4)
                };
                return Err(err(format!(
                    "vertex {i}: expected {expected} values, found {}",
                    toks.len()
                )));
            }
        };
        let mut next = 0;
        let take3 = |what: &str, next: &mut usize| -> Result<[f32; 3]> {
            let mut v = [0.0f32; 3];
            for (k, x) in v.iter_mut().enumerate() {
                *x = lex::parse_f32(toks[*next + k], what)
                    .map_err(|m| err(format!("vertex {i}: {m}")))?;
            }
            *next += 3;
            Ok(v)
        };
        positions.push(take3("coordinate", &mut next)?);
        if layout.normals {
            normals.push(take3("normal component", &mut next)?);
        }
        if color_count > 0 {
            colors.push(&toks[next..next + color_count], n, i)?;
            next += color_count;
        }
        if layout.texcoords {
            let mut st = [0.0f32; 2];
            for (k, x) in st.iter_mut().enumerate() {
                *x = lex::parse_f32(toks[next + k], "texture coordinate")
                    .map_err(|m| err(format!("vertex {i}: {m}")))?;
            }
            texcoords.push(st);
        }
    }

    let mut triangles = Vec::with_capacity(nf as usize);
    let mut poly: Vec<u32> = Vec::new();
    for f in 0..nf {
        let Some((n, line)) = lines.next_content() else {
            return Err(perr(
                FORMAT,
                Location::Line(lines.next_number()),
                format!("the file ends after {f} of {nf} faces"),
            ));
        };
        let err = |m: String| perr(FORMAT, Location::Line(n), format!("face {f}: {m}"));
        let mut words = lex::words(line);
        let first = words.next().unwrap_or_default();
        let k = lex::parse_int(first, "vertex count").map_err(err)?;
        if k < 3 {
            return Err(err(format!("{k} vertices; a face needs at least 3")));
        }
        poly.clear();
        for j in 0..k {
            let Some(tok) = words.next() else {
                return Err(err(format!("declares {k} vertices but lists {j}")));
            };
            let v = lex::parse_int(tok, "vertex index").map_err(err)?;
            if v < 0 || v as u64 >= nv {
                return Err(err(format!(
                    "vertex index {v} out of range: the file has {nv} vertices"
                )));
            }
            poly.push(v as u32);
        }
        push_fan(&mut triangles, &poly).map_err(err)?;
    }

    if let Some((n, _)) = lines.next_content() {
        warnings.push(format!(
            "content after the last face (from line {n}) was ignored"
        ));
    }

    let colors = if layout.colors || (colors.count == nv && nv > 0) {
        Some(colors.finish(&mut warnings)?)
    } else {
        if colors.count > 0 {
            warnings.push(format!(
                "only {} of {nv} vertex lines carry a color; colors were ignored",
                colors.count
            ));
        }
        None
    };
    let mesh = super::vertex_mesh(
        positions,
        triangles,
        layout.normals.then_some(normals),
        layout.texcoords.then_some(texcoords),
        colors,
    );
    Ok(Loaded { mesh, warnings })
}

/// Writes an OFF file: the keyword `[ST][C][N]OFF` for the attributes present, vertex lines
/// `x y z [nx ny nz] [r g b a] [s t]` and triangle lines `3 a b c`.
///
/// Colors are written as integers `0..=255`, except when every component is 0 or 1, which the
/// reader would take for fractions: then they are written as fractions of 255.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    let mesh = &mesh.split_seams();
    let normals = mesh.vertex_values::<3>(&Semantic::Normal);
    let texcoords = mesh.vertex_values::<2>(&Semantic::TexCoord(0));
    let colors = mesh.vertex_colors_rgba8();
    let st = if texcoords.is_some() { "ST" } else { "" };
    let c = if colors.is_some() { "C" } else { "" };
    let n = if normals.is_some() { "N" } else { "" };
    writeln!(w, "{st}{c}{n}OFF")?;
    writeln!(w, "{} {} 0", mesh.positions.len(), mesh.triangles.len())?;
    let colors_as_fractions = colors
        .as_ref()
        .is_some_and(|cs| cs.iter().flatten().all(|&x| x <= 1));
    for (i, p) in mesh.positions.iter().enumerate() {
        write!(w, "{} {} {}", Float(p[0]), Float(p[1]), Float(p[2]))?;
        if let Some(nm) = &normals {
            let v = nm[i];
            write!(w, " {} {} {}", Float(v[0]), Float(v[1]), Float(v[2]))?;
        }
        if let Some(cs) = &colors {
            for x in cs[i] {
                if colors_as_fractions {
                    write!(w, " {}", Float(super::u8_to_unit(x)))?;
                } else {
                    write!(w, " {x}")?;
                }
            }
        }
        if let Some(tc) = &texcoords {
            write!(w, " {} {}", Float(tc[i][0]), Float(tc[i][1]))?;
        }
        writeln!(w)?;
    }
    for t in &mesh.triangles {
        writeln!(w, "3 {} {} {}", t[0], t[1], t[2])?;
    }
    w.flush()
}
