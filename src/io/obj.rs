//! Wavefront OBJ reading and writing.
//!
//! The reader takes `v x y z [w]` (`w` is ignored), `v x y z r g b` and, as an extension
//! that the writer uses for translucent colors, `v x y z r g b a`; `vt u [v [w]]`; `vn x y z`;
//! and `f` with corners `i`, `i/t`, `i//n` or `i/t/n`, 1-based or negative (relative to the
//! records read so far). Faces may refer to vertices defined later in the file; indices are
//! checked once the whole file is read, and an error still names the face's line. `#` starts a
//! comment, and a line ending in `\` continues on the next one. `o`, `g`, `s`, `usemtl`,
//! `mtllib` and the free-form geometry statements are skipped silently; `l` and `p` elements
//! and unknown statements are skipped with a warning.
//!
//! **Attributes.** OBJ gives texture coordinates and normals per face corner; the mesh has
//! them per vertex. When the file has as many `vt` (or `vn`) records as `v` records and every
//! corner uses the record with its vertex's number, vertex `i` takes record `i`, unreferenced
//! vertices included. Otherwise each vertex takes the record of the first corner that uses
//! it; vertices whose later corners use a different value keep the first (one warning counts
//! such seam vertices), and vertices that no corner gives a value get zeros (with a warning).
//!
//! **Colors** are kept when every `v` record has one (otherwise they are ignored with a
//! warning). They follow the file-wide rule of OFF: fractions in `0..=1` unless every
//! component is written as an integer and some exceeds 1, in which case they are `0..=255`.

use std::io::{BufWriter, Write};

use super::lex::{self, Lines};
use super::{
    check_writable, perr, push_fan, u8_to_unit, Float, Loaded, RawColors, ReadOptions, MAX_VERTICES,
};
use crate::error::{Location, Result};
use crate::mesh::Mesh;

const FORMAT: &str = "OBJ";

/// No texture coordinate or normal at a corner.
const NONE: u32 = u32::MAX;

/// Statements that are skipped without a warning: grouping, materials, smoothing and the
/// free-form geometry that this reader does not evaluate.
const IGNORED: &[&[u8]] = &[
    b"o",
    b"g",
    b"s",
    b"usemtl",
    b"mtllib",
    b"vp",
    b"cstype",
    b"deg",
    b"bmat",
    b"step",
    b"curv",
    b"curv2",
    b"surf",
    b"parm",
    b"trim",
    b"hole",
    b"scrv",
    b"sp",
    b"end",
    b"con",
    b"mg",
    b"bevel",
    b"c_interp",
    b"d_interp",
    b"lod",
    b"maplib",
    b"usemap",
    b"shadow_obj",
    b"trace_obj",
    b"ctech",
    b"stech",
    b"call",
    b"csh",
];

/// One face as read: its line and where its corners start.
struct Face {
    line: u64,
    start: usize,
}

/// Resolves a 1-based or negative index against the `count` records read so far.
fn resolve(tok: &[u8], count: usize, what: &str) -> Result<u32, String> {
    let i = lex::parse_int(tok, &format!("{what} index"))?;
    if i > 0 {
        u32::try_from(i - 1)
            .ok()
            .filter(|&v| v != NONE)
            .ok_or_else(|| format!("{what} index {i} is out of range"))
    } else if i < 0 {
        let r = count as i64 + i;
        u32::try_from(r).map_err(|_| {
            format!(
                "relative {what} index {i} reaches before the first record ({count} read so far)"
            )
        })
    } else {
        Err(format!(
            "{what} index 0 is invalid (OBJ indices start at 1)"
        ))
    }
}

/// Reads an OBJ file.
///
/// # Errors
/// [`crate::Error::Parse`] for a malformed file, with the 1-based line of the problem.
pub fn read(bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    let mut positions: Vec<[f32; 3]> = Vec::new();
    let mut colors = RawColors::new(FORMAT);
    let mut vts: Vec<[f32; 2]> = Vec::new();
    let mut vns: Vec<[f32; 3]> = Vec::new();
    let mut corners: Vec<[u32; 3]> = Vec::new();
    let mut faces: Vec<Face> = Vec::new();
    let mut skipped_elements = 0u64;
    let mut unknown: Vec<String> = Vec::new();
    let mut unknown_count = 0u64;
    let mut warnings = Vec::new();

    let mut lines = Lines::new(bytes);
    let mut joined: Vec<u8> = Vec::new();
    while let Some((n, first)) = lines.next_line() {
        let mut line = first;
        if first.trim_ascii_end().ends_with(b"\\") {
            joined.clear();
            let mut part = first;
            loop {
                let t = part.trim_ascii_end();
                match t.strip_suffix(b"\\") {
                    Some(head) => {
                        joined.extend_from_slice(head);
                        joined.push(b' ');
                    }
                    None => {
                        joined.extend_from_slice(part);
                        break;
                    }
                }
                match lines.next_line() {
                    Some((_, next)) => part = next,
                    None => break,
                }
            }
            line = &joined;
        }
        let line = lex::strip_comment(line);
        let toks: Vec<&[u8]> = lex::words(line).collect();
        let Some((&keyword, args)) = toks.split_first() else {
            continue;
        };
        let err = |m: String| perr(FORMAT, Location::Line(n), m);
        match keyword {
            b"v" => {
                if positions.len() as u64 >= MAX_VERTICES {
                    return Err(err(format!("more than {MAX_VERTICES} vertices")));
                }
                let color = match args.len() {
                    3 | 4 => None,
                    6 => Some(&args[3..6]),
                    7 => Some(&args[3..7]),
                    k => {
                        return Err(err(format!(
                            "`v` needs 3 values (x y z), 4 (x y z w), 6 (x y z r g b) or 7 \
                             (x y z r g b a), found {k}"
                        )))
                    }
                };
                let mut p = [0.0f32; 3];
                for (x, tok) in p.iter_mut().zip(args) {
                    *x = lex::parse_f32(tok, "coordinate").map_err(err)?;
                }
                if args.len() == 4 {
                    lex::parse_f32(args[3], "weight `w`").map_err(err)?;
                }
                if let Some(c) = color {
                    colors.push(c, n, positions.len() as u64)?;
                }
                positions.push(p);
            }
            b"vt" => {
                if !(1..=3).contains(&args.len()) {
                    return Err(err(format!(
                        "`vt` needs 1 to 3 values (u [v [w]]), found {}",
                        args.len()
                    )));
                }
                if vts.len() as u64 >= MAX_VERTICES {
                    return Err(err(format!("more than {MAX_VERTICES} `vt` records")));
                }
                let mut t = [0.0f32; 2];
                for (x, tok) in t.iter_mut().zip(args) {
                    *x = lex::parse_f32(tok, "texture coordinate").map_err(err)?;
                }
                if let Some(w) = args.get(2) {
                    lex::parse_f32(w, "texture coordinate").map_err(err)?;
                }
                vts.push(t);
            }
            b"vn" => {
                if args.len() != 3 {
                    return Err(err(format!(
                        "`vn` needs 3 values (x y z), found {}",
                        args.len()
                    )));
                }
                if vns.len() as u64 >= MAX_VERTICES {
                    return Err(err(format!("more than {MAX_VERTICES} `vn` records")));
                }
                let mut v = [0.0f32; 3];
                for (x, tok) in v.iter_mut().zip(args) {
                    *x = lex::parse_f32(tok, "normal component").map_err(err)?;
                }
                vns.push(v);
            }
            b"f" => {
                if args.len() < 3 {
                    return Err(err(format!(
                        "face with {} vertices; a face needs at least 3",
                        args.len()
                    )));
                }
                faces.push(Face {
                    line: n,
                    start: corners.len(),
                });
                for tok in args {
                    let mut parts = tok.split(|&b| b == b'/');
                    let bad = || {
                        err(format!(
                            "corner `{}` is not of the form i, i/t, i//n or i/t/n",
                            lex::show(tok)
                        ))
                    };
                    let v = parts.next().unwrap_or_default();
                    let t = parts.next();
                    let nm = parts.next();
                    if parts.next().is_some() || v.is_empty() {
                        return Err(bad());
                    }
                    let v = resolve(v, positions.len(), "vertex").map_err(err)?;
                    let t = match t {
                        None => NONE,
                        Some(b"") if nm.is_some() => NONE,
                        Some(b"") => return Err(bad()),
                        Some(t) => resolve(t, vts.len(), "texture coordinate").map_err(err)?,
                    };
                    let nm = match nm {
                        None => NONE,
                        Some(b"") => return Err(bad()),
                        Some(nm) => resolve(nm, vns.len(), "normal").map_err(err)?,
                    };
                    corners.push([v, t, nm]);
                }
            }
            b"l" | b"p" => skipped_elements += 1,
            k if IGNORED.contains(&k) => {}
            k => {
                unknown_count += 1;
                let name = lex::show(k);
                if unknown.len() < 8 && !unknown.contains(&name) {
                    unknown.push(name);
                }
            }
        }
    }

    let nv = positions.len();
    let mut triangles = Vec::new();
    let mut poly: Vec<u32> = Vec::new();
    for (f, face) in faces.iter().enumerate() {
        let end = faces.get(f + 1).map_or(corners.len(), |next| next.start);
        let err = |m: String| perr(FORMAT, Location::Line(face.line), m);
        poly.clear();
        for &[v, t, nm] in &corners[face.start..end] {
            if v as usize >= nv {
                return Err(err(format!(
                    "vertex index {} out of range: the file has {nv} vertices",
                    u64::from(v) + 1
                )));
            }
            if t != NONE && t as usize >= vts.len() {
                return Err(err(format!(
                    "texture coordinate index {} out of range: the file has {} `vt` records",
                    u64::from(t) + 1,
                    vts.len()
                )));
            }
            if nm != NONE && nm as usize >= vns.len() {
                return Err(err(format!(
                    "normal index {} out of range: the file has {} `vn` records",
                    u64::from(nm) + 1,
                    vns.len()
                )));
            }
            poly.push(v);
        }
        push_fan(&mut triangles, &poly).map_err(err)?;
    }

    let texcoords = per_vertex(
        &corners,
        1,
        &vts,
        nv,
        "texture coordinates",
        |a, b| a.map(f32::to_bits) == b.map(f32::to_bits),
        &mut warnings,
    );
    let normals = per_vertex(
        &corners,
        2,
        &vns,
        nv,
        "normals",
        |a, b| a.map(f32::to_bits) == b.map(f32::to_bits),
        &mut warnings,
    );
    let colors = if colors.count > 0 && colors.count == nv as u64 {
        Some(colors.finish(&mut warnings)?)
    } else {
        if colors.count > 0 {
            warnings.push(format!(
                "only {} of {nv} `v` records carry a color; colors were ignored",
                colors.count
            ));
        }
        None
    };
    if skipped_elements > 0 {
        warnings.push(format!(
            "skipped {skipped_elements} line (`l`) and point (`p`) elements"
        ));
    }
    if unknown_count > 0 {
        warnings.push(format!(
            "skipped {unknown_count} statements with unknown keywords: {}",
            unknown
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let mesh = Mesh {
        positions,
        triangles,
        normals,
        texcoords,
        colors,
    };
    Ok(Loaded { mesh, warnings })
}

/// Turns the per-corner references `corners[..][k]` into one value per vertex, by the rules
/// of the module documentation. `None` when no corner has a reference.
fn per_vertex<T: Copy + Default>(
    corners: &[[u32; 3]],
    k: usize,
    values: &[T],
    nv: usize,
    name: &str,
    same: impl Fn(&T, &T) -> bool,
    warnings: &mut Vec<String>,
) -> Option<Vec<T>> {
    if corners.iter().all(|c| c[k] == NONE) {
        return None;
    }
    if values.len() == nv && corners.iter().all(|c| c[k] == NONE || c[k] == c[0]) {
        return Some(values.to_vec());
    }
    let mut first = vec![NONE; nv];
    let mut seam = vec![false; nv];
    for c in corners {
        let (v, r) = (c[0] as usize, c[k]);
        if r == NONE {
            continue;
        }
        if first[v] == NONE {
            first[v] = r;
        } else if first[v] != r && !same(&values[first[v] as usize], &values[r as usize]) {
            seam[v] = true;
        }
    }
    let seams = seam.iter().filter(|&&s| s).count();
    let missing = first.iter().filter(|&&r| r == NONE).count();
    if seams > 0 {
        warnings.push(format!(
            "{seams} vertices are used with differing {name} (a seam); each keeps the first one \
             used"
        ));
    }
    if missing > 0 {
        warnings.push(format!(
            "{missing} of {nv} vertices have no {name}; they were set to zero"
        ));
    }
    Some(
        first
            .iter()
            .map(|&r| {
                if r == NONE {
                    T::default()
                } else {
                    values[r as usize]
                }
            })
            .collect(),
    )
}

/// Writes an OBJ file: `v x y z [r g b [a]]` (colors as fractions of 255; `a` only when some
/// alpha is not 255), `vt u v`, `vn x y z` and triangles `f` with the corner form for the
/// attributes present, all 1-based and with the vertex's own number for every attribute.
///
/// OBJ ties texture coordinates and normals to face corners, so those of unreferenced vertices
/// read back only because the reader maps record `i` to vertex `i` when the counts agree.
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    writeln!(w, "# written by lrmesh")?;
    let alpha = mesh
        .colors
        .as_ref()
        .is_some_and(|cs| cs.iter().any(|c| c[3] != 255));
    for (i, p) in mesh.positions.iter().enumerate() {
        write!(w, "v {} {} {}", Float(p[0]), Float(p[1]), Float(p[2]))?;
        if let Some(cs) = &mesh.colors {
            let n = if alpha { 4 } else { 3 };
            for &c in &cs[i][..n] {
                write!(w, " {}", Float(u8_to_unit(c)))?;
            }
        }
        writeln!(w)?;
    }
    if let Some(ts) = &mesh.texcoords {
        for t in ts {
            writeln!(w, "vt {} {}", Float(t[0]), Float(t[1]))?;
        }
    }
    if let Some(ns) = &mesh.normals {
        for n in ns {
            writeln!(w, "vn {} {} {}", Float(n[0]), Float(n[1]), Float(n[2]))?;
        }
    }
    let (t, n) = (mesh.texcoords.is_some(), mesh.normals.is_some());
    for tri in &mesh.triangles {
        w.write_all(b"f")?;
        for &v in tri {
            let v = u64::from(v) + 1;
            match (t, n) {
                (false, false) => write!(w, " {v}")?,
                (true, false) => write!(w, " {v}/{v}")?,
                (false, true) => write!(w, " {v}//{v}")?,
                (true, true) => write!(w, " {v}/{v}/{v}")?,
            }
        }
        writeln!(w)?;
    }
    w.flush()
}
