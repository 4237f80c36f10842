//! The PLY body: values read from ASCII tokens or binary bytes through one [`Source`], and
//! the records turned into a [`Mesh`].

use super::{Encoding, Header, Kind, Layout, Role, Scalar, FORMAT};
use crate::error::{Location, Result};
use crate::io::lex::{self, Tokens};
use crate::io::{perr, push_fan, unit_to_u8};
use crate::mesh::Mesh;

/// Reads the body of `bytes` described by `header`, in its encoding.
pub(super) fn body(
    bytes: &[u8],
    header: &Header,
    layout: &Layout,
    warnings: &mut Vec<String>,
) -> Result<Mesh> {
    let body = &bytes[header.body..];
    match header.encoding {
        Encoding::Ascii => {
            let src = Ascii {
                tokens: Tokens::new(body, header.body_line),
                len: body.len() as u64,
            };
            read_body(src, header, layout, body.len() as u64, warnings)
        }
        Encoding::Binary { big_endian } => {
            let src = Binary {
                bytes,
                pos: header.body,
                big_endian,
            };
            read_body(src, header, layout, body.len() as u64, warnings)
        }
    }
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

    let records: u64 = header.elements.iter().map(|e| e.count).sum();
    crate::progress::phase("reading", records);
    let mut record = 0usize;
    for e in &header.elements {
        if e.props.is_empty() {
            continue;
        }
        for r in 0..e.count {
            crate::progress::tick(record);
            record += 1;
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
                            lex::show(e.name.as_bytes()),
                            lex::show(p.name.as_bytes())
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
                                perr(
                                    FORMAT,
                                    loc,
                                    format!(
                                        "element `{}` record {r}: {m}",
                                        lex::show(e.name.as_bytes())
                                    ),
                                )
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
    Ok(crate::io::vertex_mesh(
        positions,
        triangles,
        layout.normals.then_some(normals),
        layout.texcoords.then_some(texcoords),
        layout.colors.then_some(colors),
    ))
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
            .map(|e| format!("{} `{}`", e.count, lex::show(e.name.as_bytes())))
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
