//! The `STRP` section (connectivity kind 3): constrained triangle strips with the
//! adjacent-strips table, validated once by rules V28–V32 of `spec/FORMAT.md` and then read
//! in place as [`CtsTables`] over the buffer's little-endian words.

use super::fields::Fields;
use super::lr_rules::check_vertex_corners;
use super::Sections;
use crate::corner_table::NONE;
use crate::error::{Error, Result, Rule};
use crate::format::layout::StrpHeader;
use crate::format::Tag;
use crate::ids::Corner;
use crate::ops::CornerOps;
use crate::strips::{CtsTables, DELIMITER};
use crate::words::{LeWords, Words};

/// The arrays of the section, for error offsets.
#[derive(Clone, Copy)]
enum Array {
    T,
    A,
    C,
}

/// The `STRP` section as tables, after checking the rules that keep every operator's answer
/// in range; with `verify`, every rule (FORMAT.md §3.5c, §5.1).
pub(super) fn strips_tables<'a>(
    sections: &Sections<'a>,
    m: u32,
    verify: bool,
) -> Result<CtsTables<LeWords<'a>>> {
    let f = Fields::new(sections.required(Tag::STRP)?);
    let b = f.bytes();
    // [V28] counts and length.
    f.expect_at_least(StrpHeader::LEN, Rule(28))?;
    let h = StrpHeader::read(b);
    let (v, len) = (h.m, h.len);
    f.expect_vertices(0, v, m, Rule(28))?;
    if m == DELIMITER {
        return Err(f.err(
            0,
            Rule(28),
            "vertex ids must stay below the delimiter 0xFFFFFFFF",
        ));
    }
    if let Some(i) = h.reserved.iter().position(|&r| r != 0) {
        return Err(f.err(8 + 4 * i, Rule(28), "reserved field is not zero"));
    }
    if len % 2 != 0 || 3 * len as u64 >= NONE as u64 {
        return Err(f.err(
            4,
            Rule(28),
            format!("{len} strip entries: the count must be even and 3 times it below 2^32 - 1"),
        ));
    }
    let layout = h.layout();
    f.expect_len(layout.as_ref().map(|l| l.len), Rule(28))?;
    let layout = layout.expect("checked by expect_len");
    let len = len as usize;
    let (t_at, a_at, c_at) = (
        layout.array("T").start,
        layout.array("A").start,
        layout.array("C").start,
    );
    let t = LeWords(&b[t_at..a_at]);
    let a = LeWords(&b[a_at..c_at]);
    let c = LeWords(&b[c_at..]);
    let err = |array: Array, i: usize, rule: Rule, message: String| -> Error {
        let (base, name) = match array {
            Array::T => (t_at, "T"),
            Array::A => (a_at, "A"),
            Array::C => (c_at, "C"),
        };
        f.err(base + 4 * i, rule, format!("{name}[{i}]: {message}"))
    };

    // [V29] Layout: strips of at least three vertex ids, each from an even position and padded
    // with one delimiter (odd length) or two (even length).
    let mut j = 0;
    let mut runs = Vec::new();
    while j < len {
        if t.at(j) == DELIMITER {
            return Err(err(
                Array::T,
                j,
                Rule(29),
                "a strip must start here, found a delimiter".into(),
            ));
        }
        let start = j;
        while j < len && t.at(j) != DELIMITER {
            if t.at(j) >= m {
                return Err(err(
                    Array::T,
                    j,
                    Rule(29),
                    format!("vertex {} out of range ({m} vertices)", t.at(j)),
                ));
            }
            j += 1;
        }
        let run = j - start;
        if run < 3 {
            return Err(err(
                Array::T,
                start,
                Rule(29),
                format!("a strip of {run} entries, fewer than 3"),
            ));
        }
        let pad = if run % 2 == 1 { 1 } else { 2 };
        for _ in 0..pad {
            if j >= len {
                return Err(f.err(
                    a_at,
                    Rule(29),
                    format!("T ends inside the padding of the strip at {start}"),
                ));
            }
            if t.at(j) != DELIMITER {
                return Err(err(
                    Array::T,
                    j,
                    Rule(29),
                    format!("a strip of {run} entries must be followed by {pad} delimiters"),
                ));
            }
            j += 1;
        }
        runs.push((start, run));
    }

    let mut tables = CtsTables {
        t,
        a,
        c,
        triangles: 0,
    };
    // Strips start and end with a triangle and never hold two swaps in a row.
    let mut triangles = 0u32;
    for &(start, run) in &runs {
        let windows = start..start + run - 2;
        if let Some(w) = [start, start + run - 3]
            .into_iter()
            .find(|&w| !tables.is_triangle(w))
        {
            return Err(err(
                Array::T,
                w,
                Rule(29),
                "a strip must start and end with a triangle, not a swap".into(),
            ));
        }
        for w in windows {
            if tables.is_triangle(w) {
                triangles += 1;
            } else if tables.is_swap(w + 1) {
                return Err(err(Array::T, w, Rule(29), "two swaps in a row".into()));
            }
        }
    }
    tables.triangles = triangles;

    // [V30] A: entries the operators read are the delimiter or a triangle's position; the
    // others are the delimiter.
    for j in 0..len {
        let x = a.at(j);
        let read = (j >= 1 && tables.is_triangle(j - 1))
            || (tables.is_triangle(j) && tables.back(j) == NONE)
            || (j >= 2 && tables.is_triangle(j - 2) && tables.forward(j - 2) == NONE);
        if x == DELIMITER {
            continue;
        }
        if !read {
            return Err(err(
                Array::A,
                j,
                Rule(30),
                format!("{x} where no operator reads: must be the delimiter"),
            ));
        }
        if x as usize >= len || !tables.is_triangle(x as usize) {
            return Err(err(
                Array::A,
                j,
                Rule(30),
                format!("{x} is not the position of a triangle"),
            ));
        }
    }

    // [V32] C holds corners of the mesh; then C[v] is a corner of v ([V32]), NONE exactly
    // for an unused vertex and the start of an open fan ([V38]).
    for i in 0..c.count() {
        let x = c.at(i);
        if x != NONE && !tables.is_corner(Corner(x)) {
            return Err(err(
                Array::C,
                i,
                Rule(32),
                format!("{x:#x} is not a corner of the mesh"),
            ));
        }
    }
    if verify {
        check_opposites(&tables, &err)?;
        check_vertex_corners(&tables, Rule(32), |v, rule, message| {
            err(Array::C, v as usize, rule, message)
        })?;
    }
    Ok(tables)
}

/// [V31] (a verifying reader's rule).
fn check_opposites(
    tables: &CtsTables<LeWords<'_>>,
    err: &impl Fn(Array, usize, Rule, String) -> Error,
) -> Result<()> {
    // [V31] c.o is an involution across one edge, reversed: checked at every corner that has
    // one, so that an error names the corner whose opposite does not point back.
    for tri in tables.triangles() {
        for corner in tables.triangle_corners(tri) {
            let Some(o) = tables.opposite(corner) else {
                continue;
            };
            // Each corner checks that its opposite points back; the shared edge is checked
            // once, from the smaller corner of the pair (or a corner that is its own opposite).
            let points_back = tables.is_corner(o) && tables.opposite(o) == Some(corner);
            if !points_back
                || o.0 >= corner.0
                    && (tables.vertex(tables.next(o)) != tables.vertex(tables.prev(corner))
                        || tables.vertex(tables.prev(o)) != tables.vertex(tables.next(corner)))
            {
                return Err(err(
                    Array::T,
                    tri.idx(),
                    Rule(31),
                    format!(
                        "corner {} and its opposite {} do not face each other across one edge",
                        corner.0, o.0
                    ),
                ));
            }
        }
    }

    Ok(())
}
