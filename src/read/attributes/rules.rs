//! The rules of the `ATTR` records (V40–V42, V46) and of the version-1.0 per-vertex
//! sections (V14): each attribute validated once, when the container is opened, into an
//! [`AttributeView`].

use super::AttributeView;
use super::{coded, predicted, Packed};
use crate::error::{Result, Rule};
use crate::format::attributes::{
    bits_for, AttributeHeader, Seams, CODED_SEAMS, NORMALIZED, PER_CORNER, RANK_SPAN,
    RECORD_HEADER_LEN, TABLE_SEAMS,
};
use crate::format::quantized::{
    Quantizer, MAX_NORMAL_BITS, MAX_VALUE_BITS, PREDICTED, QUANTIZED, RAW,
};
use crate::format::{le_f32, Tag};
use crate::mesh::{ComponentType, Semantic};
use crate::ops::CornerOps;
use crate::read::fields::Fields;
use crate::read::view::Connectivity;
use crate::read::Sections;
use crate::words::{LeWords, Words};

/// What the attribute rules need to know of the rest of the container.
pub(in crate::read) struct Context<'c, 'a> {
    pub vertices: u32,
    pub connectivity: &'c Connectivity<'a>,
    /// The positions, for predicted values (encoding 2).
    pub positions: &'c crate::read::Positions<'a>,
    pub kept: u32,
    /// The kept triangles, three vertices each.
    pub kept_triangles: &'c crate::words::Stored<'a>,
    /// The `(copy, original)` pairs.
    pub copies: &'c crate::words::Stored<'a>,
    /// Which of the connectivity's triangle ids hold a triangle: made once, when `ATTR` or
    /// `PART` first needs it.
    pub holds: std::cell::OnceCell<Vec<bool>>,
    /// The vertices and opposite corners of every slot of an Edgebreaker container, for
    /// coded seams and predicted values: made once, when a record first needs them.
    pub slots: std::cell::OnceCell<crate::geometry::values::SlotCorners>,
}

impl Context<'_, '_> {
    /// Whether triangle slot `t` (FORMAT.md §3.9; below `S`) holds a triangle: a kept one
    /// always does, a connectivity id when it is one of its triangles.
    pub fn holds_triangle(&self, t: u64) -> bool {
        let bound = self.connectivity.triangle_id_bound();
        t >= u64::from(bound)
            || self.holds.get_or_init(|| {
                let mut holds = vec![false; bound as usize];
                for t in self.connectivity.triangles() {
                    holds[t.0 as usize] = true;
                }
                holds
            })[t as usize]
    }
}

/// Every attribute: the version-1.0 sections first (`NORM`, `TEXC`, `COLR`, already
/// checked by V14), then the records of `ATTR`.
pub(in crate::read) fn attributes<'a>(
    sections: &Sections<'a>,
    legacy: [Option<&'a [u8]>; 3],
    cx: &Context<'_, 'a>,
) -> Result<Vec<AttributeView<'a>>> {
    let [normals, texcoords, colors] = legacy;
    let plain =
        |semantic, components, component_type, normalized, values: &'a [u8]| AttributeView {
            semantic,
            components,
            component_type,
            normalized,
            per_corner: false,
            values,
            quantized: None,
            value_count: cx.vertices,
            extra: 0,
            flagged: 0,
            seams: None,
            seam_encoding: TABLE_SEAMS,
            normal_predictor: 0,
            stored_bytes: values.len() as u64,
        };
    let mut out = Vec::new();
    if let Some(b) = normals {
        out.push(plain(Semantic::Normal, 3, ComponentType::F32, false, b));
    }
    if let Some(b) = texcoords {
        out.push(plain(
            Semantic::TexCoord(0),
            2,
            ComponentType::F32,
            false,
            b,
        ));
    }
    if let Some(b) = colors {
        out.push(plain(Semantic::Color(0), 4, ComponentType::U8, true, b));
    }
    let Some(section) = sections.section(Tag::ATTR) else {
        return Ok(out);
    };
    let f = Fields::new(*section);
    let count = f.u32(0, Rule(40))?;
    let slots = u64::from(cx.connectivity.triangle_id_bound()) + u64::from(cx.kept);
    let mut at = 4usize;
    for i in 0..count {
        let view = record(&f, at, i, cx, slots)?;
        if out.iter().any(|a| a.semantic == view.0.semantic) {
            return Err(f.err(
                at,
                Rule(40),
                format!("attribute {i}: a second {} attribute", view.0.semantic),
            ));
        }
        copies_agree(&f, &view.0, view.1, cx)?;
        out.push(view.0);
        at = view.2;
    }
    if at != f.len() {
        return Err(f.err(
            at,
            Rule(40),
            format!("{} bytes after the last of {count} records", f.len() - at),
        ));
    }
    Ok(out)
}

/// The record at `at`: its view, where its values start, where it ends (V40, V41).
fn record<'a>(
    f: &Fields<'a>,
    at: usize,
    i: u32,
    cx: &Context<'_, 'a>,
    slots: u64,
) -> Result<(AttributeView<'a>, usize, usize)> {
    let rule = Rule(40);
    let bytes = f.bytes();
    let err = |field: usize, message: String| {
        f.err(at + field, rule, format!("attribute {i}: {message}"))
    };
    if bytes.len() - at < RECORD_HEADER_LEN {
        return Err(err(
            0,
            format!(
                "{} bytes left, a record header takes {RECORD_HEADER_LEN}",
                bytes.len() - at
            ),
        ));
    }
    let h = AttributeHeader::parse(&bytes[at..]);
    let Some(component_type) = ComponentType::from_code(h.component_type) else {
        return Err(err(
            2,
            format!("unknown component type {}", h.component_type),
        ));
    };
    if h.semantic > 3 {
        return Err(err(0, format!("unknown semantic {}", h.semantic)));
    }
    if h.set != 0 && !matches!(h.semantic, 2 | 3) {
        return Err(err(1, format!("set {} for a semantic without sets", h.set)));
    }
    let kind = h.semantic("").expect("semantic code checked");
    if !kind.allowed_components().contains(&h.components) {
        return Err(err(
            3,
            format!("{} components for a {kind} attribute", h.components),
        ));
    }
    if h.flags & !(NORMALIZED | PER_CORNER) != 0 {
        return Err(err(4, format!("unknown flag bits {:#04x}", h.flags)));
    }
    let normalized = h.flags & NORMALIZED != 0;
    if normalized && !component_type.is_integer() {
        return Err(err(4, "normalized floats".into()));
    }
    let reserved = [h.reserved[0] & !0xff_ffff, h.reserved[1], h.reserved[2]];
    if let Some(k) = reserved.iter().position(|&r| r != 0) {
        return Err(err(
            20 + 4 * k + 3 * usize::from(k == 0),
            "reserved field is not zero".into(),
        ));
    }
    // Byte 22 says how predicted values are predicted ([V47] checks it); it is 0 otherwise.
    if h.normal_predictor() != 0 && h.value_encoding() != PREDICTED {
        return Err(err(22, "normal predictor without predicted values".into()));
    }
    let coded_seams = match h.seam_encoding() {
        TABLE_SEAMS => false,
        CODED_SEAMS => true,
        other => {
            return Err(f.err(
                at + 21,
                Rule(49),
                format!("attribute {i}: unknown seam encoding {other}"),
            ))
        }
    };
    let encoding = h.value_encoding();
    let quantizer = match encoding {
        RAW => None,
        QUANTIZED | PREDICTED => Some(quantizer(f, at, i, &h, component_type, cx.vertices)?),
        _ => {
            return Err(f.err(
                at + 20,
                Rule(46),
                format!("attribute {i}: unknown value encoding {encoding}"),
            ))
        }
    };
    let start = RECORD_HEADER_LEN + usize::from(h.name_len);
    let values_len = match &quantizer {
        None => h.raw_values_len(cx.vertices),
        Some(q) if encoding == PREDICTED => Some(predicted::values_len(f, at, i, start, q)?),
        Some(q) => q.values_len(u64::from(cx.vertices) + u64::from(h.extra)),
    };
    let Some(values_len) = values_len else {
        return Err(err(8, "counts overflow".into()));
    };
    let coded_len = if coded_seams {
        let part = (at as u64 + start as u64 + values_len).min(bytes.len() as u64);
        Some(coded::seams_len(f, part as usize, i)?)
    } else {
        None
    };
    let Some(layout) = h.layout_with_parts(values_len, coded_len) else {
        return Err(err(8, "counts overflow".into()));
    };
    if layout.len() > bytes.len() - at {
        // A quantized record's length depends on its `b` (V46), a predicted one's on `n`.
        let rule = match encoding {
            _ if coded_seams => Rule(49),
            PREDICTED => Rule(47),
            QUANTIZED => Rule(46),
            _ => rule,
        };
        return Err(f.err(
            at,
            rule,
            format!(
                "attribute {i}: {} bytes, the section has {} left",
                layout.len(),
                bytes.len() - at
            ),
        ));
    }
    let name =
        std::str::from_utf8(&bytes[at + layout.name.start..at + layout.name.end]).map_err(|e| {
            err(
                RECORD_HEADER_LEN + e.valid_up_to(),
                "the name is not UTF-8".into(),
            )
        })?;
    if (h.semantic == 0) == name.is_empty() {
        return Err(err(
            6,
            "a name is given for custom attributes, and only for them".into(),
        ));
    }
    let semantic = h.semantic(name).expect("semantic code checked");
    let per_corner = h.flags & PER_CORNER != 0;
    if h.flagged == 0 && (h.extra != 0 || h.entry_bits != 0) {
        return Err(err(
            5,
            "extra values or entry bits with no flagged triangle".into(),
        ));
    }
    if h.flagged != 0
        && (!per_corner || h.extra == 0 || u32::from(h.entry_bits) != bits_for(h.extra))
    {
        return Err(err(
            5,
            format!(
                "{} flagged triangles need a per-corner attribute, extra values and {} entry bits; found {} extra, {} bits",
                h.flagged,
                bits_for(h.extra),
                h.extra,
                h.entry_bits
            ),
        ));
    }
    if u64::from(h.slots) != slots {
        return Err(err(
            16,
            format!("{} triangle slots, the container has {slots}", h.slots),
        ));
    }
    let mut values = &bytes[at + layout.values.start..at + layout.values.end];
    let quantized = match quantizer {
        None => {
            if component_type == ComponentType::F32 {
                f.expect_finite(at + layout.values.start..at + layout.values.end, rule)?;
            }
            None
        }
        Some(q) if encoding == PREDICTED => {
            values = &[];
            Some((q, Packed::Decoded(Vec::new())))
        }
        Some(q) => {
            let words = LeWords(&values[q.header_len()..]);
            let used = (u64::from(cx.vertices) + u64::from(h.extra))
                * u64::from(q.fields())
                * u64::from(q.bits());
            if used % 32 != 0 && words.at(words.count() - 1) >> (used % 32) != 0 {
                return Err(f.err(
                    at + layout.values.end - 4,
                    Rule(46),
                    format!("attribute {i}: bits past the last quantized value are not 0"),
                ));
            }
            values = &[];
            Some((q, Packed::File(words)))
        }
    };
    let seams = if coded_seams {
        let part = at + layout.entries.start..at + layout.entries.end;
        Some(coded::decode(f, (i, &h, part), cx)?)
    } else if h.flagged == 0 {
        None
    } else {
        let words =
            |r: &std::ops::Range<usize>| Packed::File(LeWords(&bytes[at + r.start..at + r.end]));
        let seams = Seams {
            flags: words(&layout.flags),
            rank: words(&layout.rank),
            entries: words(&layout.entries),
            bits: u32::from(h.entry_bits),
        };
        check_seams(f, at, i, &h, &layout, &seams, cx)?;
        Some(seams)
    };
    let mut quantized = quantized;
    if let Some((q, packed @ Packed::Decoded(_))) = &mut quantized {
        let range = at + layout.values.start..at + layout.values.end;
        *packed = Packed::Decoded(predicted::decode(f, (i, &h, range), q, seams.as_ref(), cx)?);
    }
    let view = AttributeView {
        semantic,
        components: h.components,
        component_type,
        normalized,
        per_corner,
        values,
        quantized,
        value_count: cx.vertices + h.extra,
        extra: h.extra,
        flagged: h.flagged,
        seams,
        seam_encoding: h.seam_encoding(),
        normal_predictor: h.normal_predictor(),
        stored_bytes: layout.len() as u64,
    };
    Ok((view, at + layout.values.start, at + layout.len()))
}

/// V46: the header of the values part of a quantized record at `at`: f32 components only,
/// `b` in range (1 to 24 for normals, 1 to 30 otherwise), the values part within the
/// section, a finite `lo` and a finite `size` at least 0.
fn quantizer(
    f: &Fields,
    at: usize,
    i: u32,
    h: &AttributeHeader,
    component_type: ComponentType,
    vertices: u32,
) -> Result<Quantizer> {
    let bytes = f.bytes();
    let err = |offset: usize, message: String| {
        f.err(at + offset, Rule(46), format!("attribute {i}: {message}"))
    };
    if component_type != ComponentType::F32 {
        return Err(err(
            20,
            format!("quantized values of component type {}", h.component_type),
        ));
    }
    let start = RECORD_HEADER_LEN + usize::from(h.name_len);
    let left = bytes.len() - at;
    if start >= left {
        return Err(err(
            start.min(left),
            "no room for the quantized values' bits".into(),
        ));
    }
    let bits = bytes[at + start];
    let most = if h.semantic == 1 {
        MAX_NORMAL_BITS
    } else {
        MAX_VALUE_BITS
    };
    if !(1..=most).contains(&bits) {
        return Err(err(
            start,
            format!("{bits} bits per quantized component, 1 to {most} allowed"),
        ));
    }
    let q = if h.semantic == 1 {
        Quantizer::Octahedral { bits }
    } else {
        let c = usize::from(h.components);
        let grid_end = start + 1 + 4 * c + 4;
        if grid_end > left {
            return Err(err(start, "no room for the quantized values' range".into()));
        }
        let mut lo = [0.0f32; 4];
        for (k, x) in lo.iter_mut().take(c).enumerate() {
            *x = le_f32(bytes, at + start + 1 + 4 * k);
        }
        let size = le_f32(bytes, at + start + 1 + 4 * c);
        if let Some(k) = lo.iter().position(|x| !x.is_finite()) {
            return Err(err(start + 1 + 4 * k, format!("lo[{k}] is {}", lo[k])));
        }
        if !(size.is_finite() && size >= 0.0) {
            return Err(err(
                start + 1 + 4 * c,
                format!("size {size}: finite and at least 0 needed"),
            ));
        }
        Quantizer::Grid {
            bits,
            components: h.components,
            lo,
            size,
        }
    };
    let need = q.values_len(u64::from(vertices) + u64::from(h.extra));
    if h.value_encoding() == QUANTIZED && need.is_none_or(|n| n > (left - start) as u64) {
        return Err(err(
            start,
            format!(
                "the quantized values take {} bytes, the section has {} left",
                need.map_or("too many".into(), |n| n.to_string()),
                left - start
            ),
        ));
    }
    Ok(q)
}

/// V41: `FLAGS` marks `F` triangles of the container and nothing past `S`, `RANK` counts
/// them, every entry is at most `E` and the bits past the last entry are 0.
fn check_seams(
    f: &Fields,
    at: usize,
    i: u32,
    h: &AttributeHeader,
    layout: &crate::format::attributes::RecordLayout,
    seams: &Seams<Packed>,
    cx: &Context,
) -> Result<()> {
    let rule = Rule(41);
    let err = |offset: usize, message: String| {
        f.err(at + offset, rule, format!("attribute {i}: {message}"))
    };
    let mut flagged = 0u32;
    for w in 0..seams.flags.count() {
        if w % (RANK_SPAN as usize / 32) == 0 && seams.rank.at(w / 8) != flagged {
            return Err(err(
                layout.rank.start + 4 * (w / 8),
                format!(
                    "RANK[{}] is {}, {flagged} slots are flagged before",
                    w / 8,
                    seams.rank.at(w / 8)
                ),
            ));
        }
        let word = seams.flags.at(w);
        for b in 0..32 {
            if word >> b & 1 == 0 {
                continue;
            }
            let t = 32 * w as u64 + b;
            let real = t < u64::from(h.slots) && cx.holds_triangle(t);
            if !real {
                return Err(err(
                    layout.flags.start + 4 * w,
                    format!("slot {t} is flagged but holds no triangle"),
                ));
            }
        }
        flagged += word.count_ones();
    }
    if flagged != h.flagged {
        return Err(err(
            12,
            format!("{} flagged triangles, FLAGS marks {flagged}", h.flagged),
        ));
    }
    for j in 0..3 * h.flagged {
        let e = seams.entry(j);
        if e > h.extra {
            return Err(err(
                layout.entries.start + (u64::from(j) * u64::from(h.entry_bits) / 32) as usize * 4,
                format!("entry {j} is {e}, there are {} extra values", h.extra),
            ));
        }
    }
    let used = 3 * u64::from(h.flagged) * u64::from(h.entry_bits);
    let tail = used % 32;
    if tail != 0 {
        let last = seams.entries.at(seams.entries.count() - 1);
        if last >> tail != 0 {
            return Err(err(
                layout.entries.end - 4,
                "bits past the last entry are not 0".into(),
            ));
        }
    }
    Ok(())
}

/// V42: a per-vertex attribute gives a copy the value of its original.
fn copies_agree(f: &Fields, a: &AttributeView, values_at: usize, cx: &Context) -> Result<()> {
    if a.per_corner {
        return Ok(());
    }
    for p in 0..cx.copies.count() / 2 {
        let (copy, original) = (cx.copies.at(2 * p), cx.copies.at(2 * p + 1));
        if a.value_bytes(copy) != a.value_bytes(original)
            || a.value_levels(copy) != a.value_levels(original)
        {
            let offset = match a.quantizer() {
                // The word that holds the copy's first integer.
                Some(q) => {
                    q.header_len()
                        + 4 * (u64::from(copy) * u64::from(q.fields()) * u64::from(q.bits()) / 32)
                            as usize
                }
                None => a.value_len() * copy as usize,
            };
            return Err(f.err(
                values_at + offset,
                Rule(42),
                format!(
                    "{} of vertex copy {copy} differs from its original {original}'s",
                    a.semantic
                ),
            ));
        }
    }
    Ok(())
}
