//! PLY (Polygon File Format) reading and writing.
//!
//! The reader takes `format ascii 1.0`, `binary_little_endian 1.0` and `binary_big_endian 1.0`,
//! `comment` and `obj_info` lines, and any elements with any scalar or list properties of the
//! types `char`/`int8`, `uchar`/`uint8`, `short`/`int16`, `ushort`/`uint16`, `int`/`int32`,
//! `uint`/`uint32`, `float`/`float32`, `double`/`float64`, in any order.
//!
//! What becomes part of the mesh:
//! - element `vertex`: `x y z` (required, any scalar type), `nx ny nz`, texture coordinates
//!   from the first complete pair of `s t`, `u v`, `texture_u texture_v`,
//!   `texture_s texture_t`, and colors from `red green blue [alpha]` (or the same with a
//!   `diffuse_` prefix). Integer colors are clamped to `0..=255`; float colors are fractions
//!   in `0..=1`, clamped and scaled by 255 with rounding. A missing alpha is 255.
//! - element `face`: the list property `vertex_indices` (or `vertex_index`) with integer
//!   items. Negative or out-of-range indices are errors.
//!
//! Every other element and property is parsed, so that binary offsets stay right, and
//! skipped with one warning that names them. Binary errors give the byte offset from the start
//! of the file, ASCII errors the line. Data after the last element is ignored with a warning.
//!
//! The writer produces binary little-endian PLY with `float` positions, normals (`nx ny nz`)
//! and texture coordinates (`s t`), `uchar` colors (`red green blue alpha`) and faces as
//! `list uchar uint vertex_indices`.

use std::collections::HashSet;
use std::io::{BufWriter, Write};

use super::lex::{self, Lines, Tokens};
use super::{
    check_writable, perr, push_fan, unit_to_u8, Loaded, ReadOptions, MAX_TRIANGLES, MAX_VERTICES,
};
use crate::error::{Error, Location, Result};
use crate::mesh::Mesh;

const FORMAT: &str = "PLY";

/// A scalar type of the PLY header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(name: &[u8]) -> Option<Scalar> {
        Some(match name {
            b"char" | b"int8" => Scalar::I8,
            b"uchar" | b"uint8" => Scalar::U8,
            b"short" | b"int16" => Scalar::I16,
            b"ushort" | b"uint16" => Scalar::U16,
            b"int" | b"int32" => Scalar::I32,
            b"uint" | b"uint32" => Scalar::U32,
            b"float" | b"float32" => Scalar::F32,
            b"double" | b"float64" => Scalar::F64,
            _ => return None,
        })
    }

    fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    fn is_int(self) -> bool {
        !matches!(self, Scalar::F32 | Scalar::F64)
    }

    fn name(self) -> &'static str {
        match self {
            Scalar::I8 => "char",
            Scalar::U8 => "uchar",
            Scalar::I16 => "short",
            Scalar::U16 => "ushort",
            Scalar::I32 => "int",
            Scalar::U32 => "uint",
            Scalar::F32 => "float",
            Scalar::F64 => "double",
        }
    }

    /// The value range of an integer type.
    fn int_range(self) -> (i64, i64) {
        match self {
            Scalar::I8 => (i8::MIN.into(), i8::MAX.into()),
            Scalar::U8 => (0, u8::MAX.into()),
            Scalar::I16 => (i16::MIN.into(), i16::MAX.into()),
            Scalar::U16 => (0, u16::MAX.into()),
            Scalar::I32 => (i32::MIN.into(), i32::MAX.into()),
            Scalar::U32 => (0, u32::MAX.into()),
            Scalar::F32 | Scalar::F64 => (i64::MIN, i64::MAX),
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Kind {
    Scalar(Scalar),
    List { count: Scalar, item: Scalar },
}

/// What a property contributes to the mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Role {
    Skip,
    Position(usize),
    Normal(usize),
    Texcoord(usize),
    Color(usize),
    Indices,
}

#[derive(Debug)]
struct Property {
    name: String,
    kind: Kind,
    role: Role,
}

#[derive(Debug)]
struct Element {
    name: String,
    count: u64,
    props: Vec<Property>,
    /// Header line of the `element` statement.
    line: u64,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Encoding {
    Ascii,
    Binary { big_endian: bool },
}

struct Header {
    encoding: Encoding,
    elements: Vec<Element>,
    /// Byte offset of the body.
    body: usize,
    /// Line on which the body starts (for ASCII).
    body_line: u64,
}

fn header_err(line: u64, message: impl Into<String>) -> Error {
    perr(FORMAT, Location::Line(line), message)
}

fn parse_header(bytes: &[u8]) -> Result<Header> {
    let mut lines = Lines::new(bytes);
    match lines.next_line() {
        Some((_, l)) if l.trim_ascii_end() == b"ply" => {}
        _ => {
            return Err(header_err(
                1,
                "not a PLY file: the first line must be `ply`",
            ))
        }
    }
    let mut encoding = None;
    let mut elements: Vec<Element> = Vec::new();
    // Names seen so far, so that a header of many statements stays linear.
    let mut element_names: HashSet<String> = HashSet::new();
    let mut property_names: HashSet<(usize, String)> = HashSet::new();
    loop {
        let Some((n, line)) = lines.next_line() else {
            return Err(header_err(
                lines.next_number(),
                "the file ends before the `end_header` line",
            ));
        };
        let words: Vec<&[u8]> = lex::words(line).collect();
        let Some((&keyword, args)) = words.split_first() else {
            continue;
        };
        match keyword {
            b"comment" | b"obj_info" => {}
            b"format" => {
                if encoding.is_some() {
                    return Err(header_err(n, "a second `format` line"));
                }
                let [enc, version] = args else {
                    return Err(header_err(
                        n,
                        "expected `format <ascii|binary_little_endian|binary_big_endian> 1.0`",
                    ));
                };
                encoding = Some(match *enc {
                    b"ascii" => Encoding::Ascii,
                    b"binary_little_endian" => Encoding::Binary { big_endian: false },
                    b"binary_big_endian" => Encoding::Binary { big_endian: true },
                    other => {
                        return Err(header_err(
                            n,
                            format!("unknown format `{}`", lex::show(other)),
                        ))
                    }
                });
                if !matches!(*version, b"1.0" | b"1") {
                    return Err(header_err(
                        n,
                        format!("unsupported PLY version `{}`", lex::show(version)),
                    ));
                }
            }
            b"element" => {
                if encoding.is_none() {
                    return Err(header_err(n, "`element` before the `format` line"));
                }
                let [name, count] = args else {
                    return Err(header_err(n, "expected `element <name> <count>`"));
                };
                let count =
                    lex::parse_count(count, "element count").map_err(|m| header_err(n, m))?;
                let name = String::from_utf8_lossy(name).into_owned();
                if !element_names.insert(name.clone()) {
                    return Err(header_err(n, format!("a second element `{name}`")));
                }
                elements.push(Element {
                    name,
                    count,
                    props: Vec::new(),
                    line: n,
                });
            }
            b"property" => {
                let element_index = elements.len();
                let Some(element) = elements.last_mut() else {
                    return Err(header_err(n, "`property` before any `element`"));
                };
                let scalar = |t: &[u8]| {
                    Scalar::parse(t).ok_or_else(|| {
                        header_err(n, format!("unknown property type `{}`", lex::show(t)))
                    })
                };
                let (kind, name) = match args {
                    [b"list", count, item, name] => {
                        let count = scalar(count)?;
                        if !count.is_int() {
                            return Err(header_err(
                                n,
                                format!("list length type `{}` is not an integer", count.name()),
                            ));
                        }
                        (
                            Kind::List {
                                count,
                                item: scalar(item)?,
                            },
                            name,
                        )
                    }
                    [b"list", ..] => {
                        return Err(header_err(
                            n,
                            "expected `property list <length type> <item type> <name>`",
                        ))
                    }
                    [t, name] => (Kind::Scalar(scalar(t)?), name),
                    _ => return Err(header_err(n, "expected `property <type> <name>`")),
                };
                let name = String::from_utf8_lossy(name).into_owned();
                if !property_names.insert((element_index, name.clone())) {
                    return Err(header_err(
                        n,
                        format!("a second property `{name}` in element `{}`", element.name),
                    ));
                }
                element.props.push(Property {
                    name,
                    kind,
                    role: Role::Skip,
                });
            }
            b"end_header" => break,
            other => {
                return Err(header_err(
                    n,
                    format!("unknown header statement `{}`", lex::show(other)),
                ))
            }
        }
    }
    let Some(encoding) = encoding else {
        return Err(header_err(1, "the header has no `format` line"));
    };
    Ok(Header {
        encoding,
        elements,
        body: lines.offset(),
        body_line: lines.next_number(),
    })
}

/// Which mesh data the file provides.
#[derive(Debug, Default)]
struct Layout {
    vertex: Option<usize>,
    face: Option<usize>,
    normals: bool,
    texcoords: bool,
    colors: bool,
}

/// Assigns roles to the properties of `vertex` and `face`, and lists what is skipped.
fn assign_roles(elements: &mut [Element]) -> Result<(Layout, Option<String>)> {
    let mut layout = Layout::default();
    for (i, e) in elements.iter_mut().enumerate() {
        let scalar_index = |e: &Element, name: &str| {
            e.props
                .iter()
                .position(|p| p.name == name && matches!(p.kind, Kind::Scalar(_)))
        };
        match e.name.as_str() {
            "vertex" => {
                layout.vertex = Some(i);
                for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
                    let Some(p) = e.props.iter_mut().find(|p| p.name == axis) else {
                        return Err(header_err(
                            e.line,
                            format!("element `vertex` has no property `{axis}`"),
                        ));
                    };
                    if matches!(p.kind, Kind::List { .. }) {
                        return Err(header_err(
                            e.line,
                            format!("vertex property `{axis}` is a list, not a scalar"),
                        ));
                    }
                    p.role = Role::Position(k);
                }
                let normal: Vec<_> = ["nx", "ny", "nz"]
                    .iter()
                    .filter_map(|n| scalar_index(e, n))
                    .collect();
                if normal.len() == 3 {
                    layout.normals = true;
                    for (k, &p) in normal.iter().enumerate() {
                        e.props[p].role = Role::Normal(k);
                    }
                }
                for [s, t] in [
                    ["s", "t"],
                    ["u", "v"],
                    ["texture_u", "texture_v"],
                    ["texture_s", "texture_t"],
                ] {
                    if let (Some(s), Some(t)) = (scalar_index(e, s), scalar_index(e, t)) {
                        layout.texcoords = true;
                        e.props[s].role = Role::Texcoord(0);
                        e.props[t].role = Role::Texcoord(1);
                        break;
                    }
                }
                for prefix in ["", "diffuse_"] {
                    let idx: Vec<_> = ["red", "green", "blue"]
                        .iter()
                        .filter_map(|c| scalar_index(e, &format!("{prefix}{c}")))
                        .collect();
                    if idx.len() == 3 {
                        layout.colors = true;
                        for (k, &p) in idx.iter().enumerate() {
                            e.props[p].role = Role::Color(k);
                        }
                        if let Some(a) = scalar_index(e, &format!("{prefix}alpha")) {
                            e.props[a].role = Role::Color(3);
                        }
                        break;
                    }
                }
            }
            "face" => {
                layout.face = Some(i);
                let found = ["vertex_indices", "vertex_index"]
                    .iter()
                    .find_map(|n| e.props.iter().position(|p| p.name == *n));
                let Some(p) = found.map(|k| &mut e.props[k]) else {
                    return Err(header_err(
                        e.line,
                        "element `face` has no list property `vertex_indices`",
                    ));
                };
                match p.kind {
                    Kind::List { item, .. } if item.is_int() => p.role = Role::Indices,
                    Kind::List { item, .. } => {
                        return Err(header_err(
                            e.line,
                            format!(
                                "face property `{}` has non-integer items of type `{}`",
                                p.name,
                                item.name()
                            ),
                        ))
                    }
                    Kind::Scalar(_) => {
                        return Err(header_err(
                            e.line,
                            format!("face property `{}` is a scalar, not a list", p.name),
                        ))
                    }
                }
            }
            _ => {}
        }
    }
    let Some(v) = layout.vertex else {
        return Err(perr(
            FORMAT,
            Location::Whole,
            "the header declares no `vertex` element",
        ));
    };
    if elements[v].count > MAX_VERTICES {
        return Err(header_err(
            elements[v].line,
            format!(
                "vertex count {} exceeds the limit of {MAX_VERTICES}",
                elements[v].count
            ),
        ));
    }
    if let Some(f) = layout.face {
        if elements[f].count > MAX_TRIANGLES {
            return Err(header_err(
                elements[f].line,
                format!(
                    "face count {} exceeds the limit of {MAX_TRIANGLES}",
                    elements[f].count
                ),
            ));
        }
    }
    let mut skipped = Vec::new();
    for e in elements.iter() {
        if e.name == "vertex" || e.name == "face" {
            for p in e.props.iter().filter(|p| p.role == Role::Skip) {
                skipped.push(format!("property `{}.{}`", e.name, p.name));
            }
        } else {
            skipped.push(format!("element `{}` ({} records)", e.name, e.count));
        }
    }
    let warning = (!skipped.is_empty()).then(|| {
        format!(
            "skipped PLY data the mesh does not use: {}",
            list_some(&skipped)
        )
    });
    Ok((layout, warning))
}

/// The first few items of a list, joined, with how many more there are.
fn list_some(items: &[String]) -> String {
    const SHOWN: usize = 20;
    let mut s = items[..items.len().min(SHOWN)].join(", ");
    if items.len() > SHOWN {
        s.push_str(&format!(" and {} more", items.len() - SHOWN));
    }
    s
}

/// Where the values of the body come from.
trait Source {
    /// Where the next value starts.
    fn location(&mut self) -> Location;
    /// Reads one value.
    fn scalar(&mut self, t: Scalar) -> Result<f64, String>;
    /// Skips `n` values.
    fn skip(&mut self, n: u64, t: Scalar) -> Result<(), String>;
    /// Checks that `n` values of type `t` can still follow.
    fn check_room(&self, n: u64, t: Scalar) -> Result<(), String>;
    /// The smallest number of bytes a value takes.
    fn min_value_bytes(t: Scalar) -> u64;
    /// Bytes the minimum sizes may exceed the body by (a final value without a separator).
    const SLACK: u64;
    /// Input left after the body, as a warning.
    fn trailing(&mut self) -> Option<String>;
}

struct Binary<'a> {
    bytes: &'a [u8],
    pos: usize,
    big_endian: bool,
}

impl Binary<'_> {
    fn truncated(&self, need: u64) -> String {
        format!(
            "truncated: {need} more bytes needed, but the file ends at byte {}",
            self.bytes.len()
        )
    }
}

impl Source for Binary<'_> {
    const SLACK: u64 = 0;

    fn location(&mut self) -> Location {
        Location::Byte(self.pos as u64)
    }

    fn scalar(&mut self, t: Scalar) -> Result<f64, String> {
        let n = t.size();
        let Some(b) = self.bytes.get(self.pos..self.pos + n) else {
            return Err(self.truncated(n as u64));
        };
        self.pos += n;
        let mut a = [0u8; 8];
        a[..n].copy_from_slice(b);
        if self.big_endian {
            a[..n].reverse();
        }
        let [b0, b1, b2, b3, ..] = a;
        Ok(match t {
            Scalar::I8 => f64::from(b0 as i8),
            Scalar::U8 => f64::from(b0),
            Scalar::I16 => f64::from(i16::from_le_bytes([b0, b1])),
            Scalar::U16 => f64::from(u16::from_le_bytes([b0, b1])),
            Scalar::I32 => f64::from(i32::from_le_bytes([b0, b1, b2, b3])),
            Scalar::U32 => f64::from(u32::from_le_bytes([b0, b1, b2, b3])),
            Scalar::F32 => f64::from(f32::from_le_bytes([b0, b1, b2, b3])),
            Scalar::F64 => f64::from_le_bytes(a),
        })
    }

    fn skip(&mut self, n: u64, t: Scalar) -> Result<(), String> {
        self.check_room(n, t)?;
        // check_room bounds n * size by the bytes left.
        self.pos += n as usize * t.size();
        Ok(())
    }

    fn check_room(&self, n: u64, t: Scalar) -> Result<(), String> {
        let left = (self.bytes.len() - self.pos) as u64;
        match n.checked_mul(t.size() as u64) {
            Some(need) if need <= left => Ok(()),
            need => Err(format!(
                "truncated: a list of {n} `{}` values needs {} bytes, but only {left} are left",
                t.name(),
                need.map_or_else(|| "more than 2^64".to_string(), |x| x.to_string())
            )),
        }
    }

    fn min_value_bytes(t: Scalar) -> u64 {
        t.size() as u64
    }

    fn trailing(&mut self) -> Option<String> {
        let left = self.bytes.len() - self.pos;
        (left > 0).then(|| {
            format!(
                "{left} bytes after the last element (from byte {}) were ignored",
                self.pos
            )
        })
    }
}

struct Ascii<'a> {
    tokens: Tokens<'a>,
    /// Bytes of the body, for a rough room check.
    len: u64,
}

impl Source for Ascii<'_> {
    const SLACK: u64 = 1;

    fn location(&mut self) -> Location {
        self.tokens.skip_space();
        Location::Line(self.tokens.line())
    }

    fn scalar(&mut self, t: Scalar) -> Result<f64, String> {
        let Some((tok, _)) = self.tokens.next_token() else {
            return Err("the file ends before this value".to_string());
        };
        match t {
            Scalar::F32 => lex::parse_any::<f32>(tok, "value").map(f64::from),
            Scalar::F64 => lex::parse_any::<f64>(tok, "value"),
            _ => {
                let v = lex::parse_int(tok, "value")?;
                let (lo, hi) = t.int_range();
                if (lo..=hi).contains(&v) {
                    Ok(v as f64)
                } else {
                    Err(format!("{v} is out of range for type `{}`", t.name()))
                }
            }
        }
    }

    fn skip(&mut self, n: u64, t: Scalar) -> Result<(), String> {
        self.check_room(n, t)?;
        for _ in 0..n {
            self.scalar(t)?;
        }
        Ok(())
    }

    fn check_room(&self, n: u64, _t: Scalar) -> Result<(), String> {
        if n <= self.len {
            Ok(())
        } else {
            Err(format!(
                "a list of {n} values cannot fit in the {} bytes of the body",
                self.len
            ))
        }
    }

    fn min_value_bytes(_t: Scalar) -> u64 {
        2
    }

    fn trailing(&mut self) -> Option<String> {
        (!self.tokens.at_end()).then(|| {
            format!(
                "content after the last element (from line {}) was ignored",
                self.tokens.line()
            )
        })
    }
}

/// Reads a PLY file.
///
/// # Errors
/// [`crate::Error::Parse`] for a malformed file: header problems with their line, body
/// problems with their line (ASCII) or byte offset from the start of the file (binary).
pub fn read(bytes: &[u8], _opts: &ReadOptions) -> Result<Loaded> {
    let mut header = parse_header(bytes)?;
    let (layout, skipped) = assign_roles(&mut header.elements)?;
    let mut warnings: Vec<String> = skipped.into_iter().collect();
    let body = &bytes[header.body..];
    match header.encoding {
        Encoding::Ascii => {
            let src = Ascii {
                tokens: Tokens::new(body, header.body_line),
                len: body.len() as u64,
            };
            read_body(src, &header, &layout, body.len() as u64, &mut warnings)
        }
        Encoding::Binary { big_endian } => {
            let src = Binary {
                bytes,
                pos: header.body,
                big_endian,
            };
            read_body(src, &header, &layout, body.len() as u64, &mut warnings)
        }
    }
    .map(|mesh| Loaded { mesh, warnings })
}

fn read_body<S: Source>(
    mut src: S,
    header: &Header,
    layout: &Layout,
    body_len: u64,
    warnings: &mut Vec<String>,
) -> Result<Mesh> {
    let start = src.location();
    check_counts::<S>(header, body_len, start)?;

    let nv = layout.vertex.map_or(0, |v| header.elements[v].count);
    // check_counts bounds the vertex and face counts by the body length.
    let cap = |on: bool| if on { nv as usize } else { 0 };
    let mut positions: Vec<[f32; 3]> = Vec::with_capacity(nv as usize);
    let mut normals: Vec<[f32; 3]> = Vec::with_capacity(cap(layout.normals));
    let mut texcoords: Vec<[f32; 2]> = Vec::with_capacity(cap(layout.texcoords));
    let mut colors: Vec<[u8; 4]> = Vec::with_capacity(cap(layout.colors));
    let nf = layout.face.map_or(0, |f| header.elements[f].count);
    let mut triangles: Vec<[u32; 3]> = Vec::with_capacity(nf as usize);
    let mut poly: Vec<u32> = Vec::new();
    let mut clamped = 0u64;

    for e in &header.elements {
        if e.props.is_empty() {
            continue;
        }
        for r in 0..e.count {
            let mut pos = [0.0f32; 3];
            let mut nrm = [0.0f32; 3];
            let mut tex = [0.0f32; 2];
            let mut col = [255u8; 4];
            for p in &e.props {
                let loc = src.location();
                let err = |m: String| {
                    perr(
                        FORMAT,
                        loc,
                        format!(
                            "element `{}` record {r}, property `{}`: {m}",
                            e.name, p.name
                        ),
                    )
                };
                match p.kind {
                    Kind::Scalar(t) => {
                        let v = src.scalar(t).map_err(err)?;
                        let finite = |what: &str| {
                            let x = v as f32;
                            if x.is_finite() {
                                Ok(x)
                            } else if v.is_nan() {
                                Err(err(format!("{what} is NaN")))
                            } else {
                                Err(err(format!(
                                    "{what} {v} is infinite or beyond the f32 range"
                                )))
                            }
                        };
                        match p.role {
                            Role::Position(k) => pos[k] = finite("coordinate")?,
                            Role::Normal(k) => nrm[k] = finite("normal component")?,
                            Role::Texcoord(k) => tex[k] = finite("texture coordinate")?,
                            Role::Color(k) => {
                                col[k] = if v.is_nan() {
                                    return Err(err("color component is NaN".to_string()));
                                } else if t.is_int() {
                                    if !(0.0..=255.0).contains(&v) {
                                        clamped += 1;
                                    }
                                    v.clamp(0.0, 255.0) as u8
                                } else {
                                    if !(0.0..=1.0).contains(&v) {
                                        clamped += 1;
                                    }
                                    unit_to_u8(v)
                                }
                            }
                            Role::Skip | Role::Indices => {}
                        }
                    }
                    Kind::List { count, item } => {
                        let n = src.scalar(count).map_err(err)?;
                        if n < 0.0 {
                            return Err(err(format!("negative list length {n}")));
                        }
                        let n = n as u64;
                        if p.role != Role::Indices {
                            src.skip(n, item).map_err(err)?;
                            continue;
                        }
                        if n < 3 {
                            return Err(err(format!(
                                "face with {n} vertices; a face needs at least 3"
                            )));
                        }
                        src.check_room(n, item).map_err(err)?;
                        poly.clear();
                        for _ in 0..n {
                            let loc = src.location();
                            let ierr = |m: String| {
                                perr(FORMAT, loc, format!("element `{}` record {r}: {m}", e.name))
                            };
                            let v = src.scalar(item).map_err(ierr)?;
                            if v < 0.0 {
                                return Err(ierr(format!("negative vertex index {v}")));
                            }
                            if v >= nv as f64 {
                                return Err(ierr(format!(
                                    "vertex index {v} out of range: the file has {nv} vertices"
                                )));
                            }
                            poly.push(v as u32);
                        }
                        push_fan(&mut triangles, &poly).map_err(err)?;
                    }
                }
            }
            if e.name == "vertex" {
                positions.push(pos);
                if layout.normals {
                    normals.push(nrm);
                }
                if layout.texcoords {
                    texcoords.push(tex);
                }
                if layout.colors {
                    colors.push(col);
                }
            }
        }
    }
    if let Some(w) = src.trailing() {
        warnings.push(w);
    }
    if clamped > 0 {
        warnings.push(format!(
            "{clamped} color components outside their range were clamped"
        ));
    }
    Ok(Mesh {
        positions,
        triangles,
        normals: layout.normals.then_some(normals),
        texcoords: layout.texcoords.then_some(texcoords),
        colors: layout.colors.then_some(colors),
    })
}

/// Checks that the body can hold every declared record before anything is reserved: each
/// value takes at least [`Source::min_value_bytes`], and each face at least 3 indices.
fn check_counts<S: Source>(header: &Header, body_len: u64, at: Location) -> Result<()> {
    let mut total: u64 = 0;
    let mut overflow = false;
    for e in &header.elements {
        let record: u64 = e
            .props
            .iter()
            .map(|p| match p.kind {
                Kind::Scalar(t) => S::min_value_bytes(t),
                Kind::List { count, item } if p.role == Role::Indices => {
                    S::min_value_bytes(count) + 3 * S::min_value_bytes(item)
                }
                Kind::List { count, .. } => S::min_value_bytes(count),
            })
            .sum();
        match e
            .count
            .checked_mul(record)
            .and_then(|b| total.checked_add(b))
        {
            Some(t) => total = t,
            None => overflow = true,
        }
    }
    if overflow || total > body_len + S::SLACK {
        let declared: Vec<String> = header
            .elements
            .iter()
            .map(|e| format!("{} `{}`", e.count, e.name))
            .collect();
        return Err(perr(
            FORMAT,
            at,
            format!(
                "the header declares {}, which need at least {} bytes, but the body has {body_len}",
                declared.join(", "),
                if overflow {
                    "more than 2^64".to_string()
                } else {
                    total.to_string()
                }
            ),
        ));
    }
    Ok(())
}

/// Writes a binary little-endian PLY file (see the module documentation for the layout).
///
/// # Errors
/// Errors of the writer, and [`std::io::ErrorKind::InvalidInput`] for a mesh that does not
/// validate.
pub fn write<W: Write>(w: W, mesh: &Mesh) -> std::io::Result<()> {
    check_writable(mesh)?;
    let mut w = BufWriter::new(w);
    writeln!(w, "ply")?;
    writeln!(w, "format binary_little_endian 1.0")?;
    writeln!(w, "comment written by lrmesh")?;
    writeln!(w, "element vertex {}", mesh.positions.len())?;
    for p in ["x", "y", "z"] {
        writeln!(w, "property float {p}")?;
    }
    if mesh.normals.is_some() {
        for p in ["nx", "ny", "nz"] {
            writeln!(w, "property float {p}")?;
        }
    }
    if mesh.texcoords.is_some() {
        for p in ["s", "t"] {
            writeln!(w, "property float {p}")?;
        }
    }
    if mesh.colors.is_some() {
        for p in ["red", "green", "blue", "alpha"] {
            writeln!(w, "property uchar {p}")?;
        }
    }
    writeln!(w, "element face {}", mesh.triangles.len())?;
    writeln!(w, "property list uchar uint vertex_indices")?;
    writeln!(w, "end_header")?;
    for (i, p) in mesh.positions.iter().enumerate() {
        for x in p {
            w.write_all(&x.to_le_bytes())?;
        }
        if let Some(n) = &mesh.normals {
            for x in n[i] {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        if let Some(t) = &mesh.texcoords {
            for x in t[i] {
                w.write_all(&x.to_le_bytes())?;
            }
        }
        if let Some(c) = &mesh.colors {
            w.write_all(&c[i])?;
        }
    }
    for t in &mesh.triangles {
        w.write_all(&[3])?;
        for v in t {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    w.flush()
}
