//! The statement pass of the OBJ reader: every line read into records, face corners and part
//! labels, with relative indices resolved; `assemble` then checks the indices and builds the
//! mesh.

use std::collections::HashMap;

use super::{assemble, FORMAT, NONE};
use crate::error::{Location, Result};
use crate::io::lex::{self, Lines};
use crate::io::{perr, Loaded, RawColors, ReadOptions, MAX_VERTICES};
use crate::mesh::Part;

/// Statements that are skipped without a warning: smoothing and the free-form geometry that
/// this reader does not evaluate.
const IGNORED: &[&[u8]] = &[
    b"s",
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

/// One face as read: its line, where its corners start in [`Statements::corners`], and its
/// part.
pub(super) struct Face {
    pub(super) line: u64,
    pub(super) start: usize,
    pub(super) part: u32,
}

/// Everything the statements of a file say, before the indices are checked.
pub(super) struct Statements {
    pub(super) positions: Vec<[f32; 3]>,
    pub(super) colors: RawColors,
    pub(super) texcoords: Vec<[f32; 2]>,
    pub(super) normals: Vec<[f32; 3]>,
    /// `[v, vt, vn]` of every face corner, 0-based; [`NONE`] for a missing `vt` or `vn`.
    pub(super) corners: Vec<[u32; 3]>,
    pub(super) faces: Vec<Face>,
    /// The parts in order of first use by a face.
    pub(super) parts: Vec<Part>,
    pub(super) libraries: Vec<String>,
    pub(super) warnings: Vec<String>,
}

/// The labels in force and the parts met so far (a hash map, so that a file of many groups
/// stays linear).
#[derive(Default)]
struct Labels {
    current: Part,
    /// Index of `current` once a face has used it since the last label statement.
    current_index: Option<u32>,
    index: HashMap<Part, u32>,
}

impl Labels {
    /// The part of the next face.
    fn part(&mut self, parts: &mut Vec<Part>) -> u32 {
        if let Some(i) = self.current_index {
            return i;
        }
        let i = *self.index.entry(self.current.clone()).or_insert_with(|| {
            parts.push(self.current.clone());
            (parts.len() - 1) as u32
        });
        self.current_index = Some(i);
        i
    }

    /// Sets one label: `None` when the statement has no name.
    fn set(&mut self, label: fn(&mut Part) -> &mut Option<String>, args: &[&[u8]]) {
        let name = (!args.is_empty()).then(|| {
            args.iter()
                .map(|w| String::from_utf8_lossy(w))
                .collect::<Vec<_>>()
                .join(" ")
        });
        if *label(&mut self.current) != name {
            *label(&mut self.current) = name;
            self.current_index = None;
        }
    }
}

/// Counts of things read but not kept, reported as warnings at the end.
#[derive(Default)]
struct Skipped {
    elements: u64,
    unknown: Vec<String>,
    unknown_count: u64,
    first_unknown_line: u64,
    texture_w: u64,
    vertex_w: u64,
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
/// [`crate::Error::Parse`] for a malformed file, with the 1-based line of the problem, or
/// for a file with no `v` and no `f` statement.
pub fn read(bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    let statements = statements(bytes)?;
    assemble::assemble(statements)
}

/// Reads every statement of the file.
fn statements(bytes: &[u8]) -> Result<Statements> {
    let mut s = Statements {
        positions: Vec::new(),
        colors: RawColors::new(FORMAT),
        texcoords: Vec::new(),
        normals: Vec::new(),
        corners: Vec::new(),
        faces: Vec::new(),
        parts: Vec::new(),
        libraries: Vec::new(),
        warnings: Vec::new(),
    };
    let mut labels = Labels::default();
    let mut skipped = Skipped::default();

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
            b"v" => vertex(&mut s, args, n, &mut skipped)?,
            b"vt" => texcoord(&mut s, args, &mut skipped).map_err(err)?,
            b"vn" => normal(&mut s, args).map_err(err)?,
            b"f" => {
                let part = labels.part(&mut s.parts);
                face(&mut s, args, n, part).map_err(err)?;
            }
            b"o" => labels.set(|p| &mut p.object, args),
            b"g" => labels.set(|p| &mut p.group, args),
            b"usemtl" => labels.set(|p| &mut p.material, args),
            b"mtllib" => {
                for name in args {
                    let name = String::from_utf8_lossy(name).into_owned();
                    if !s.libraries.contains(&name) {
                        s.libraries.push(name);
                    }
                }
            }
            b"l" | b"p" => skipped.elements += 1,
            k if IGNORED.contains(&k) => {}
            k => {
                if skipped.unknown_count == 0 {
                    skipped.first_unknown_line = n;
                }
                skipped.unknown_count += 1;
                let name = lex::show(k);
                if skipped.unknown.len() < 8 && !skipped.unknown.contains(&name) {
                    skipped.unknown.push(name);
                }
            }
        }
    }
    if s.positions.is_empty() && s.faces.is_empty() {
        let mut message = "no vertex or face statement (`v`, `f`): not an OBJ file".to_string();
        if skipped.unknown_count > 0 {
            message.push_str(&format!(
                "; {} statements with unknown keywords, the first on line {}: `{}`",
                skipped.unknown_count, skipped.first_unknown_line, skipped.unknown[0]
            ));
        }
        return Err(perr(FORMAT, Location::Whole, message));
    }
    report(&skipped, &mut s.warnings);
    Ok(s)
}

/// `v x y z [w]`, `v x y z r g b [a]`.
fn vertex(s: &mut Statements, args: &[&[u8]], n: u64, skipped: &mut Skipped) -> Result<()> {
    let err = |m: String| perr(FORMAT, Location::Line(n), m);
    if s.positions.len() as u64 >= MAX_VERTICES {
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
    if args.len() == 4 && lex::parse_f32(args[3], "weight `w`").map_err(err)? != 1.0 {
        skipped.vertex_w += 1;
    }
    if let Some(c) = color {
        s.colors.push(c, n, s.positions.len() as u64)?;
    }
    s.positions.push(p);
    Ok(())
}

/// `vt u [v [w]]`.
fn texcoord(s: &mut Statements, args: &[&[u8]], skipped: &mut Skipped) -> Result<(), String> {
    if !(1..=3).contains(&args.len()) {
        return Err(format!(
            "`vt` needs 1 to 3 values (u [v [w]]), found {}",
            args.len()
        ));
    }
    if s.texcoords.len() as u64 >= MAX_VERTICES {
        return Err(format!("more than {MAX_VERTICES} `vt` records"));
    }
    let mut t = [0.0f32; 2];
    for (x, tok) in t.iter_mut().zip(args) {
        *x = lex::parse_f32(tok, "texture coordinate")?;
    }
    if let Some(w) = args.get(2) {
        if lex::parse_f32(w, "texture coordinate")? != 0.0 {
            skipped.texture_w += 1;
        }
    }
    s.texcoords.push(t);
    Ok(())
}

/// `vn x y z`.
fn normal(s: &mut Statements, args: &[&[u8]]) -> Result<(), String> {
    if args.len() != 3 {
        return Err(format!("`vn` needs 3 values (x y z), found {}", args.len()));
    }
    if s.normals.len() as u64 >= MAX_VERTICES {
        return Err(format!("more than {MAX_VERTICES} `vn` records"));
    }
    let mut v = [0.0f32; 3];
    for (x, tok) in v.iter_mut().zip(args) {
        *x = lex::parse_f32(tok, "normal component")?;
    }
    s.normals.push(v);
    Ok(())
}

/// `f` and its corners `i`, `i/t`, `i//n`, `i/t/n`.
fn face(s: &mut Statements, args: &[&[u8]], line: u64, part: u32) -> Result<(), String> {
    if args.len() < 3 {
        return Err(format!(
            "face with {} vertices; a face needs at least 3",
            args.len()
        ));
    }
    s.faces.push(Face {
        line,
        start: s.corners.len(),
        part,
    });
    for tok in args {
        let mut fields = tok.split(|&b| b == b'/');
        let bad = || {
            format!(
                "corner `{}` is not of the form i, i/t, i//n or i/t/n",
                lex::show(tok)
            )
        };
        let v = fields.next().unwrap_or_default();
        let t = fields.next();
        let nm = fields.next();
        if fields.next().is_some() || v.is_empty() {
            return Err(bad());
        }
        let v = resolve(v, s.positions.len(), "vertex")?;
        let t = match t {
            None => NONE,
            Some(b"") if nm.is_some() => NONE,
            Some(b"") => return Err(bad()),
            Some(t) => resolve(t, s.texcoords.len(), "texture coordinate")?,
        };
        let nm = match nm {
            None => NONE,
            Some(b"") => return Err(bad()),
            Some(nm) => resolve(nm, s.normals.len(), "normal")?,
        };
        s.corners.push([v, t, nm]);
    }
    Ok(())
}

/// The warnings for what was skipped.
fn report(skipped: &Skipped, warnings: &mut Vec<String>) {
    if skipped.vertex_w > 0 {
        warnings.push(format!(
            "{} `v` records have a weight `w` other than 1; it was ignored",
            skipped.vertex_w
        ));
    }
    if skipped.texture_w > 0 {
        warnings.push(format!(
            "{} `vt` records have a third component `w` other than 0; only `u` and `v` were kept",
            skipped.texture_w
        ));
    }
    if skipped.elements > 0 {
        warnings.push(format!(
            "skipped {} line (`l`) and point (`p`) elements",
            skipped.elements
        ));
    }
    if skipped.unknown_count > 0 {
        warnings.push(format!(
            "skipped {} statements with unknown keywords: {}",
            skipped.unknown_count,
            skipped
                .unknown
                .iter()
                .map(|k| format!("`{k}`"))
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
}
