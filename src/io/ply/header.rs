//! The PLY header: its statements parsed into elements and properties, and the roles
//! (position, normal, texture coordinate, colour, face indices) given to those properties.

use std::collections::HashSet;

use super::{Element, Encoding, Header, Kind, Layout, Property, Role, Scalar, FORMAT};
use crate::error::{Error, Location, Result};
use crate::io::lex::{self, Lines};
use crate::io::{perr, MAX_TRIANGLES, MAX_VERTICES};

fn header_err(line: u64, message: impl Into<String>) -> Error {
    perr(FORMAT, Location::Line(line), message)
}

pub(super) fn parse_header(bytes: &[u8]) -> Result<Header> {
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
    // Lines with no known keyword: how many, and the first with its number.
    let mut unknown: Option<(u64, String)> = None;
    let mut unknown_count = 0u64;
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
                    return Err(header_err(
                        n,
                        format!("a second element `{}`", lex::show(name.as_bytes())),
                    ));
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
                        format!(
                            "a second property `{}` in element `{}`",
                            lex::show(name.as_bytes()),
                            lex::show(element.name.as_bytes())
                        ),
                    ));
                }
                element.props.push(Property {
                    name,
                    kind,
                    role: Role::Skip,
                });
            }
            b"end_header" => break,
            _ => {
                // Free text without the `comment` keyword, as Blender 2.4 wrote
                // (`Created by Blender3D 247 - www.blender.org, source file: ...`).
                if unknown.is_none() {
                    unknown = Some((n, lex::show_at_most(line.trim_ascii(), 100)));
                }
                unknown_count += 1;
            }
        }
    }
    let Some(encoding) = encoding else {
        return Err(header_err(1, "the header has no `format` line"));
    };
    let warnings = unknown
        .map(|(line, text)| {
            format!(
                "skipped {unknown_count} header line(s) with no known keyword, the first on \
                 line {line}: `{text}`"
            )
        })
        .into_iter()
        .collect();
    Ok(Header {
        encoding,
        elements,
        body: lines.offset(),
        body_line: lines.next_number(),
        warnings,
    })
}

/// Assigns roles to the properties of `vertex` and `face`, and lists what is skipped.
pub(super) fn assign_roles(elements: &mut [Element]) -> Result<(Layout, Option<String>)> {
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
                skipped.push(format!(
                    "property `{}.{}`",
                    e.name,
                    lex::show(p.name.as_bytes())
                ));
            }
        } else {
            skipped.push(format!(
                "element `{}` ({} records)",
                lex::show(e.name.as_bytes()),
                e.count
            ));
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
