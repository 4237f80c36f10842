//! The sections around the connectivity: `META` (V11), `MESH` (V12), `GEOM` (V13), the
//! per-vertex attributes (V14), `COPY` (V24) or `COPC` (V52), `KEPT` (V25) or `KEPC` (V50)
//! and `PERM` (V26).

use super::fields::{format_error, Fields};
use super::{Limits, Sections};
use crate::error::{Error, Result, Rule};
use crate::format::layout::{self, MeshRecord};
use crate::format::{copied, kept, Kind, Metadata, Tag};
use crate::words::{LeWords, Stored, Words};

/// The `META` section, if present.
pub(super) fn metadata(sections: &Sections, limits: &Limits) -> Result<Option<Metadata>> {
    let Some(s) = sections.section(Tag::META) else {
        return Ok(None);
    };
    if s.bytes.len() as u64 > limits.max_metadata_bytes {
        return Err(Error::LimitExceeded {
            what: "metadata size",
            value: s.bytes.len() as u64,
            limit: limits.max_metadata_bytes,
        });
    }
    serde_json::from_slice::<Metadata>(s.bytes)
        .map(Some)
        .map_err(|e| {
            format_error(
                "META",
                s.offset,
                Rule(11),
                format!("not a metadata JSON object: {e}"),
            )
        })
}

/// The `MESH` record, with the rules that need no other section.
pub(super) fn mesh_record<'a>(sections: &Sections<'a>) -> Result<(MeshRecord, Fields<'a>)> {
    let f = Fields::new(sections.required(Tag::MESH)?);
    f.expect_len(Some(MeshRecord::LEN as u64), Rule(12))?;
    let record = MeshRecord::read(f.bytes());
    if !Kind::ALL.contains(&record.kind) {
        return Err(f.err(
            MeshRecord::KIND_AT,
            Rule(12),
            format!("unknown connectivity kind {}", record.kind.0),
        ));
    }
    if record.reserved != 0 {
        return Err(f.err(
            MeshRecord::RESERVED_AT,
            Rule(12),
            "reserved field is not zero",
        ));
    }
    if record.output_vertices > record.vertices {
        return Err(f.err(
            MeshRecord::OUTPUT_VERTICES_AT,
            Rule(12),
            format!(
                "{} output vertices of {}",
                record.output_vertices, record.vertices
            ),
        ));
    }
    Ok((record, f))
}

/// A per-vertex attribute section of `size` bytes a vertex, if present.
pub(super) fn attribute<'a>(
    sections: &Sections<'a>,
    tag: Tag,
    m: u32,
    size: u64,
    floats: bool,
) -> Result<Option<&'a [u8]>> {
    let Some(section) = sections.section(tag) else {
        return Ok(None);
    };
    let f = Fields::new(*section);
    f.expect_len((m as u64).checked_mul(size), Rule(14))?;
    if floats {
        f.expect_finite(0..f.len(), Rule(14))?;
    }
    Ok(Some(section.bytes))
}

/// Every per-vertex attribute section: normals, texture coordinates, colors.
pub(super) fn attributes<'a>(sections: &Sections<'a>, m: u32) -> Result<[Option<&'a [u8]>; 3]> {
    Ok([
        attribute(sections, Tag::NORM, m, layout::attribute::NORMAL_LEN, true)?,
        attribute(
            sections,
            Tag::TEXC,
            m,
            layout::attribute::TEXCOORD_LEN,
            true,
        )?,
        attribute(sections, Tag::COLR, m, layout::attribute::COLOR_LEN, false)?,
    ])
}

/// The `(copy, original)` pairs of `COPY`, or decoded from `COPC` (an Edgebreaker
/// container's); empty without either.
pub(super) fn copies<'a>(sections: &Sections<'a>, m: u32, edgebreaker: bool) -> Result<Stored<'a>> {
    if let Some(coded) = sections.section(Tag::COPC) {
        let (plain, rule) = (Tag::COPY, Rule(52));
        return coded_ids(
            sections,
            coded,
            (plain, rule),
            (m, edgebreaker),
            copied::decode,
        )
        .map(Stored::Decoded);
    }
    let Some(section) = sections.section(Tag::COPY) else {
        return Ok(Stored::default());
    };
    let f = Fields::new(*section);
    let rule = Rule(24);
    let k = f.u32(0, rule)? as u64;
    let at = layout::copy::HEADER_LEN;
    f.expect_len(
        k.checked_mul(4 * layout::copy::PAIR_WORDS)
            .and_then(|x| x.checked_add(at as u64)),
        rule,
    )?;
    let words = LeWords(&section.bytes[at..]);
    let mut is_copy = vec![false; m as usize];
    let mut previous = None;
    for i in 0..k as usize {
        let (copy, original) = (words.at(2 * i), words.at(2 * i + 1));
        if copy >= m || original >= m || previous.is_some_and(|p| copy <= p) {
            let field = if copy >= m || previous.is_some_and(|p| copy <= p) {
                0
            } else {
                4
            };
            return Err(f.err(
                at + 8 * i + field,
                rule,
                format!(
                    "bad copy pair ({copy}, {original}): ids must be below {m}, copies increasing"
                ),
            ));
        }
        is_copy[copy as usize] = true;
        previous = Some(copy);
    }
    for i in 0..k as usize {
        if is_copy[words.at(2 * i + 1) as usize] {
            return Err(f.err(
                at + 8 * i + 4,
                rule,
                "the original of a copy is itself a copy",
            ));
        }
    }
    Ok(Stored::File(words))
}

/// The kept triangles, three vertices each: those of `KEPT`, or decoded from `KEPC` (an
/// Edgebreaker container, `edgebreaker`); empty without either.
pub(super) fn kept<'a>(sections: &Sections<'a>, m: u32, edgebreaker: bool) -> Result<Stored<'a>> {
    if let Some(coded) = sections.section(Tag::KEPC) {
        let (plain, rule) = (Tag::KEPT, Rule(50));
        return coded_ids(
            sections,
            coded,
            (plain, rule),
            (m, edgebreaker),
            kept::decode,
        )
        .map(Stored::Decoded);
    }
    let Some(section) = sections.section(Tag::KEPT) else {
        return Ok(Stored::default());
    };
    let f = Fields::new(*section);
    let rule = Rule(25);
    let k = f.u32(0, rule)? as u64;
    let at = layout::kept::HEADER_LEN;
    f.expect_len(
        k.checked_mul(4 * layout::kept::TRIANGLE_WORDS)
            .and_then(|x| x.checked_add(at as u64)),
        rule,
    )?;
    let words = LeWords(&section.bytes[at..]);
    if let Some(i) = (0..words.count()).find(|&i| words.at(i) >= m) {
        return Err(f.err(
            at + 4 * i,
            rule,
            format!("vertex {} out of range ({m} vertices)", words.at(i)),
        ));
    }
    Ok(Stored::File(words))
}

/// The stream decoder of a range-coded section: (stream, its offset in the file, `k`, `m`)
/// to the ids, or where and why the stream breaks its rule.
type CodedIds = fn(&[u8], usize, u32, u32) -> std::result::Result<Vec<u32>, (u64, String)>;

/// A range-coded section standing for a plain one, `COPC` for `COPY` (V52) or `KEPC` for
/// `KEPT` (V50): only in an Edgebreaker container and not with the plain section; u32 `k`,
/// u32 `n` and the `n` bytes of the stream exactly; the stream decodes (`decode`) to `k`
/// entries of vertices below `m`.
fn coded_ids(
    sections: &Sections,
    section: &crate::read::sections::Section<'_>,
    (plain, rule): (Tag, Rule),
    (m, edgebreaker): (u32, bool),
    decode: CodedIds,
) -> Result<Vec<u32>> {
    let f = Fields::new(*section);
    let coded = section.tag;
    if sections.section(plain).is_some() {
        return Err(f.err(0, rule, format!("both {plain} and {coded}")));
    }
    if !edgebreaker {
        return Err(f.err(
            0,
            rule,
            format!("{coded} needs the Edgebreaker connectivity"),
        ));
    }
    let (k, n) = (f.u32(0, rule)?, f.u32(4, rule)?);
    // Both coded sections start with `k` and `n`.
    const _: () = assert!(copied::HEADER_LEN == 8 && kept::HEADER_LEN == 8);
    let at = kept::HEADER_LEN;
    f.expect_len(Some(at as u64 + u64::from(n)), rule)?;
    let base = section.offset as usize;
    decode(&section.bytes[at..], base + at, k, m).map_err(|(offset, message)| {
        f.err(
            (offset as usize).saturating_sub(base).min(f.len()),
            rule,
            message,
        )
    })
}

/// The vertex and triangle permutations of `PERM`, if present, for `w` output vertices and
/// `t` triangles.
pub(super) fn perm<'a>(
    sections: &Sections<'a>,
    w: u32,
    t: u64,
) -> Result<Option<(LeWords<'a>, LeWords<'a>)>> {
    let Some(section) = sections.section(Tag::PERM) else {
        return Ok(None);
    };
    let f = Fields::new(*section);
    let rule = Rule(26);
    let (nv, nt) = (f.u32(0, rule)?, f.u32(4, rule)?);
    if nv != w || nt as u64 != t {
        return Err(f.err(
            if nv != w { 0 } else { 4 },
            rule,
            format!("permutations of {nv} vertices and {nt} triangles, the mesh has {w} and {t}"),
        ));
    }
    let at = layout::perm::HEADER_LEN;
    f.expect_len(Some(at as u64 + 4 * (nv as u64 + nt as u64)), rule)?;
    let split = at + 4 * nv as usize;
    let vertices = LeWords(&section.bytes[at..split]);
    let triangles = LeWords(&section.bytes[split..]);
    check_permutation(&f, at, vertices)?;
    check_permutation(&f, split, triangles)?;
    Ok(Some((vertices, triangles)))
}

/// The reversed output triangles of `FLIP`, if present, among `t` output triangles
/// ([V54]): u32 `T = t`, then a bit per triangle, increasing.
pub(super) fn flips(sections: &Sections, t: u64) -> Result<Option<Vec<u32>>> {
    let Some(section) = sections.section(Tag::FLIP) else {
        return Ok(None);
    };
    let f = Fields::new(*section);
    let rule = Rule(54);
    let count = f.u32(0, rule)?;
    if count as u64 != t {
        return Err(f.err(0, rule, format!("{count} triangles, the mesh has {t}")));
    }
    let at = layout::flip::HEADER_LEN;
    f.expect_len(Some(at as u64 + t.div_ceil(8)), rule)?;
    let bits = &section.bytes[at..];
    if t % 8 != 0 && bits[bits.len() - 1] >> (t % 8) != 0 {
        return Err(f.err(f.len() - 1, rule, "padding bits are not 0"));
    }
    let reversed = (0..t as u32)
        .filter(|&j| bits[(j / 8) as usize] >> (j % 8) & 1 == 1)
        .collect();
    Ok(Some(reversed))
}

fn check_permutation(f: &Fields, at: usize, words: LeWords) -> Result<()> {
    let n = words.count();
    let mut seen = vec![false; n];
    for i in 0..n {
        let x = words.at(i) as usize;
        if x >= n || seen[x] {
            return Err(f.err(
                at + 4 * i,
                Rule(26),
                format!("{x} breaks a permutation of 0..{n}"),
            ));
        }
        seen[x] = true;
    }
    Ok(())
}
