//! Forged containers for the rules of `ATTR` and `PART` (FORMAT.md §3.9, §3.10: [V40]–[V43],
//! [V46])
//! and of the version-1.0 attribute sections ([V14]). How a rule is broken and what the
//! reader must report: `tests/common/forge.rs`.

mod common;

use common::forge::*;
use lrmesh::format::attributes::AttributeHeader;
use lrmesh::format::Tag;
use lrmesh::mesh::{Attribute, Part, Parts, Semantic, Values};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::{CornerOps, Mesh};

/// The cube of `spec/vectors/seamed_cube.obj`: texture coordinates per corner with seams,
/// a custom per-vertex byte, and two parts.
fn cube() -> Mesh {
    let positions = (0..8)
        .map(|i| [(i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32])
        .collect();
    let triangles = vec![
        [0, 2, 3],
        [0, 3, 1],
        [4, 5, 7],
        [4, 7, 6],
        [0, 1, 5],
        [0, 5, 4],
        [1, 3, 7],
        [1, 7, 5],
        [3, 2, 6],
        [3, 6, 7],
        [2, 0, 4],
        [2, 4, 6],
    ];
    // Each face its own four texture coordinates: every vertex has three values, its own
    // and two extra ones.
    let uv: Vec<[f32; 2]> = (0..24).map(|i| [i as f32 / 24.0, (i % 4) as f32]).collect();
    let corners = (0..12u32)
        .flat_map(|t| {
            let face = t / 2;
            let quad = if t % 2 == 0 { [0, 1, 2] } else { [0, 2, 3] };
            quad.map(|k| 4 * face + k)
        })
        .collect();
    let mut mesh = Mesh::new(positions, triangles);
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, corners));
    mesh.attributes.push(Attribute {
        semantic: Semantic::Custom("q".into()),
        components: 1,
        normalized: false,
        values: Values::U8((0..8).collect()),
        corners: None,
    });
    let mut parts = Parts::default();
    for t in 0..12 {
        let material = if t < 4 { "cap" } else { "side" };
        let i = parts.intern(Part {
            material: Some(material.into()),
            ..Part::default()
        });
        parts.of_triangle.push(i);
    }
    mesh.parts = Some(parts);
    mesh
}

/// Record offsets in the `ATTR` payload: record 0 (texture coordinates) at 4, record 1
/// (custom) after it.
fn records(p: &[u8]) -> (usize, usize, AttributeHeader) {
    let h = AttributeHeader::parse(&p[4..]);
    let len = h.layout(8).unwrap().len();
    (4, 4 + len, h)
}

fn byte(bytes: &[u8], at: usize, x: u8) -> Vec<u8> {
    forge(bytes, Tag::ATTR, |p| p[at] = x)
}

/// [V40] Each record's header, name and values; records tile the payload; one attribute
/// per semantic.
#[test]
fn v40_attribute_records() {
    let bytes = encoded(&cube(), Connectivity::Lr);
    let at = section_at(&bytes, Tag::ATTR);
    let p = payload(&bytes, Tag::ATTR);
    let (r0, r1, h0) = records(&p);
    assert_eq!((h0.extra, h0.flagged > 0, p[r1]), (16, true, 0));
    let o = |x: usize| at + x as u64;
    breaks(&byte(&bytes, r0, 4), 40, "ATTR", o(r0), "unknown semantic");
    breaks(&byte(&bytes, r1 + 1, 2), 40, "ATTR", o(r1 + 1), "set 2");
    breaks(
        &byte(&bytes, r0 + 2, 9),
        40,
        "ATTR",
        o(r0 + 2),
        "component type 9",
    );
    breaks(
        &byte(&bytes, r0 + 3, 3),
        40,
        "ATTR",
        o(r0 + 3),
        "3 components",
    );
    breaks(
        &byte(&bytes, r0 + 4, 6),
        40,
        "ATTR",
        o(r0 + 4),
        "unknown flag",
    );
    breaks(
        &byte(&bytes, r0 + 4, 3),
        40,
        "ATTR",
        o(r0 + 4),
        "normalized floats",
    );
    // Per corner without seams is valid (every corner takes its vertex's value); seams on
    // a per-vertex attribute are not.
    open(&byte(&bytes, r1 + 4, 2), &Limits::default()).unwrap();
    breaks(
        &byte(&bytes, r0 + 4, 0),
        40,
        "ATTR",
        o(r0 + 5),
        "per-corner",
    );
    // The first reserved word's low bytes are the value and seam encodings ([V46], [V49])
    // and the normal predictor, 0 without predicted values ([V47]).
    for k in 0..3 {
        let at = r0 + 20 + 4 * k + 3 * usize::from(k == 0);
        let bad = byte(&bytes, at, 1);
        breaks(&bad, 40, "ATTR", o(at), "reserved");
    }
    breaks(
        &byte(&bytes, r0 + 22, 1),
        40,
        "ATTR",
        o(r0 + 22),
        "normal predictor without predicted values",
    );
    // A name on a standard semantic, none on a custom one, a name that is not UTF-8.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[r0 + 6] = 1;
        p.insert(r0 + 32, b'n');
    });
    breaks(&bad, 40, "ATTR", o(r0 + 6), "name");
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[r1 + 6] = 0;
        p.remove(r1 + 32);
    });
    breaks(&bad, 40, "ATTR", o(r1 + 6), "name");
    breaks(
        &byte(&bytes, r1 + 32, 0xFF),
        40,
        "ATTR",
        o(r1 + 32),
        "UTF-8",
    );
    // The entry width must be the fewest bits that hold E (here 5 for 16); E ≥ 1 with F.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[r0 + 5] = 6;
        let extra = 4 * (3 * h0.flagged as usize * 6).div_ceil(32)
            - 4 * (3 * h0.flagged as usize * 5).div_ceil(32);
        for _ in 0..extra {
            p.insert(r1, 0);
        }
    });
    breaks(&bad, 40, "ATTR", o(r0 + 5), "5 entry bits");
    // Extra values without a flagged triangle: on the per-vertex record (one more value).
    let bad = forge(&bytes, Tag::ATTR, |p| {
        put(p, r1 + 8, 1);
        p.push(0);
    });
    breaks(&bad, 40, "ATTR", o(r1 + 5), "no flagged triangle");
    // The slot count.
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, r0 + 16, h0.slots + 1));
    breaks(&bad, 40, "ATTR", o(r0 + 16), "triangle slots");
    // A non-finite value: component 1 of value 3.
    let value = r0 + 32 + 8 * 3 + 4;
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, value, f32::NAN.to_bits()));
    breaks(&bad, 40, "ATTR", o(value), "non-finite");
    // Records must tile the payload: a byte too many, a record cut short, a count too high.
    breaks(
        &forge(&bytes, Tag::ATTR, |p| p.push(0)),
        40,
        "ATTR",
        o(p.len()),
        "after the last",
    );
    let bad = forge(&bytes, Tag::ATTR, |p| p.truncate(p.len() - 1));
    breaks(&bad, 40, "ATTR", o(r1), "left");
    breaks(
        &forge(&bytes, Tag::ATTR, |p| put(p, 0, 3)),
        40,
        "ATTR",
        o(p.len()),
        "left",
    );
    // The same semantic twice: record 0 again, or texture coordinates in TEXC too.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        put(p, 0, 3);
        let copy = p[r0..r1].to_vec();
        p.extend(copy);
    });
    breaks(&bad, 40, "ATTR", o(p.len()), "a second texcoord0");
    let with_texc = forge_sections(&bytes, |s| {
        let at = s.iter().position(|x| x.0 == Tag::ATTR).unwrap();
        s.insert(at, (Tag::TEXC, lrmesh::format::Flags::NONE, vec![0; 8 * 8]));
    });
    let at_texc = section_at(&with_texc, Tag::ATTR);
    breaks(&with_texc, 40, "ATTR", at_texc + 4, "a second texcoord0");
}

/// [V41] `FLAGS`, `RANK` and `ENTRIES` of a per-corner record.
#[test]
fn v41_seam_tables() {
    let bytes = encoded(&cube(), Connectivity::Lr);
    let at = section_at(&bytes, Tag::ATTR);
    let p = payload(&bytes, Tag::ATTR);
    let (r0, _, h) = records(&p);
    let l = h.layout(8).unwrap();
    let (flags, rank, entries) = (r0 + l.flags.start, r0 + l.rank.start, r0 + l.entries.start);
    let o = |x: usize| at + x as u64;
    assert_eq!((get(&p, rank), h.slots < 32), (0, true));
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, rank, 1));
    breaks(&bad, 41, "ATTR", o(rank), "RANK[0]");
    // A bit at or past S; a flag cleared, so that F disagrees.
    let word = get(&p, flags);
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, flags, word | 1 << h.slots));
    breaks(&bad, 41, "ATTR", o(flags), "holds no triangle");
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, flags, word & (word - 1)));
    breaks(&bad, 41, "ATTR", o(r0 + 12), "FLAGS marks");
    // An entry above E (entry 0 is bits 0..5 of the first word: 31 > 16).
    let first = get(&p, entries);
    let bad = forge(&bytes, Tag::ATTR, |p| put(p, entries, first | 31));
    breaks(&bad, 41, "ATTR", o(entries), "entry 0 is 31");
    // Bits past the last entry.
    let used = 3 * h.flagged as usize * h.entry_bits as usize;
    assert_ne!(used % 32, 0, "the forgery needs a partly used last word");
    let last = r0 + l.entries.end - 4;
    let bad = forge(&bytes, Tag::ATTR, |p| {
        let x = get(p, last);
        put(p, last, x | 1 << 31)
    });
    breaks(&bad, 41, "ATTR", o(last), "past the last entry");
}

/// A triangle id of the container's connectivity that holds no triangle (strips leave
/// positions between strips).
fn empty_slot(bytes: &[u8]) -> u32 {
    let file = open(bytes, &Limits::default()).unwrap();
    let conn = file.connectivity();
    let holds: Vec<u32> = conn.triangles().map(|t| t.0).collect();
    (0..conn.triangle_id_bound())
        .find(|t| !holds.contains(t))
        .expect("strips have a position that is no triangle")
}

/// [V41] A flagged slot that holds no triangle: strips leave positions between strips.
#[test]
fn v41_flag_on_an_empty_slot() {
    let mut mesh = common::torus_with_everything(6, 5, 0, 0, 0, 3);
    let n = mesh.triangles.len() as u32;
    let uv: Vec<[f32; 2]> = (0..3 * n).map(|i| [i as f32, 0.0]).collect();
    mesh.attributes.push(Attribute::per_corner(
        Semantic::TexCoord(0),
        &uv,
        (0..3 * n).collect(),
    ));
    let bytes = encoded(&mesh, Connectivity::Strips);
    let empty = empty_slot(&bytes);
    let at = section_at(&bytes, Tag::ATTR);
    let p = payload(&bytes, Tag::ATTR);
    let (r0, _, h) = records(&p);
    let l = h.layout(mesh.positions.len() as u32).unwrap();
    let word = r0 + l.flags.start + 4 * (empty as usize / 32);
    let bad = forge(&bytes, Tag::ATTR, |p| {
        let x = get(p, word);
        put(p, word, x | 1 << (empty % 32))
    });
    breaks(
        &bad,
        41,
        "ATTR",
        at + word as u64,
        &format!("slot {empty} is flagged"),
    );
}

/// [V42] A per-vertex attribute gives copies their original's value.
#[test]
fn v42_copies_share_per_vertex_values() {
    // Two tetrahedra sharing vertex 0: one copy (spec/vectors/nonmanifold_vertex.off).
    let source = manifest().join("spec/vectors/nonmanifold_vertex.off");
    let mut mesh = lrmesh::load(&source).unwrap();
    let colors: Vec<[u8; 4]> = (0..mesh.positions.len() as u8)
        .map(|i| [i, 0, 0, 255])
        .collect();
    mesh.attributes.push(Attribute::rgba8(&colors));
    let bytes = encoded(&mesh, Connectivity::Lr);
    let copy = get(&payload(&bytes, Tag::COPY), 4) as usize;
    let at = section_at(&bytes, Tag::ATTR);
    let value = 4 + 32 + 4 * copy;
    let bad = forge(&bytes, Tag::ATTR, |p| p[value + 1] ^= 1);
    breaks(
        &bad,
        42,
        "ATTR",
        at + value as u64,
        &format!("vertex copy {copy}"),
    );
}

/// [V43] `PART`: header, labels, indices.
#[test]
fn v43_parts() {
    // Level 0: the labels as JSON (from level 1 they are coded, [V51]).
    let options = EncodeOptions {
        connectivity: Connectivity::Lr,
        keep_order: true,
        level: 0,
        ..EncodeOptions::default()
    };
    let bytes = encode(&cube(), &options).unwrap();
    let at = section_at(&bytes, Tag::PART);
    let p = payload(&bytes, Tag::PART);
    let (parts, slots, bits, json) = (get(&p, 0), get(&p, 4), get(&p, 8), get(&p, 12) as usize);
    assert_eq!((parts, bits), (2, 1));
    let word = |f: usize, x: u32| forge(&bytes, Tag::PART, |p| put(p, f, x));
    breaks(
        &forge(&bytes, Tag::PART, |p| p.truncate(15)),
        43,
        "PART",
        at,
        "header",
    );
    breaks(
        &forge(&bytes, Tag::PART, |p| p.push(0)),
        43,
        "PART",
        at,
        "counts call for",
    );
    breaks(&word(4, slots + 1), 43, "PART", at + 4, "triangle slots");
    breaks(&word(8, 2), 43, "PART", at + 8, "bits per index");
    breaks(&word(0, 3), 43, "PART", at + 8, "bits per index");
    // P = 3 needs 2 bits: the index words grow with them, the JSON still lists 2.
    let bad = forge(&bytes, Tag::PART, |p| {
        put(p, 0, 3);
        put(p, 8, 2);
        let words = (slots as usize * 2).div_ceil(32) - (slots as usize).div_ceil(32);
        p.extend(vec![0; 4 * words]);
    });
    breaks(&bad, 43, "PART", at, "the JSON lists 2");
    let bad = forge(&bytes, Tag::PART, |p| p[16] = b'[');
    breaks(&bad, 43, "PART", at + 16, "not a JSON object");
    let bad = forge(&bytes, Tag::PART, |p| {
        let text = String::from_utf8(p[16..16 + json].to_vec()).unwrap();
        let changed = text.replacen("\"cap\"", "17000", 1);
        assert_ne!(text, changed);
        p.splice(16..16 + json, changed.bytes());
        put(p, 12, changed.len() as u32);
    });
    breaks(&bad, 43, "PART", at + 16, "not a JSON object");
    // An index at or past P: with P = 1 and b = 0 every index is 0, so shrink to one
    // part and keep b = 1: the check on b comes first. Instead, three parts in the JSON
    // with P = 3, b = 2, and slot 0 given index 3.
    let bad = forge(&bytes, Tag::PART, |p| {
        let text = String::from_utf8(p[16..16 + json].to_vec()).unwrap();
        let three = text.replacen("]", ",{\"group\":\"x\"}]", 1);
        let indices: Vec<u32> = (0..slots).map(|t| if t == 0 { 3 } else { 0 }).collect();
        let packed = lrmesh::format::attributes::pack(&indices, 2);
        p.clear();
        for x in [3, slots, 2, three.len() as u32] {
            p.extend(x.to_le_bytes());
        }
        p.extend(three.bytes());
        for w in packed {
            p.extend(w.to_le_bytes());
        }
    });
    let json3 = json + "{\"group\":\"x\"}".len() + 1;
    breaks(
        &bad,
        43,
        "PART",
        at + 16 + json3 as u64,
        "slot 0 has part 3",
    );
    // Bits past the last index.
    let last = p.len() - 4;
    assert_ne!(slots % 32, 0);
    breaks(
        &word(last, get(&p, last) | 1 << 31),
        43,
        "PART",
        at + last as u64,
        "past the last",
    );
}

/// [V43] A slot that holds no triangle has part 0.
#[test]
fn v43_empty_slot_has_part_zero() {
    let mut mesh = common::torus_with_everything(6, 5, 0, 0, 0, 3);
    let mut parts = Parts::default();
    for t in 0..mesh.triangles.len() {
        let i = parts.intern(Part {
            group: Some(format!("g{}", t % 2)),
            ..Part::default()
        });
        parts.of_triangle.push(i);
    }
    mesh.parts = Some(parts);
    let bytes = encoded(&mesh, Connectivity::Strips);
    let empty = empty_slot(&bytes);
    let at = section_at(&bytes, Tag::PART);
    let p = payload(&bytes, Tag::PART);
    let word = 16 + get(&p, 12) as usize + 4 * (empty as usize / 32);
    let bad = forge(&bytes, Tag::PART, |p| {
        let x = get(p, word);
        put(p, word, x | 1 << (empty % 32))
    });
    breaks(&bad, 43, "PART", at + word as u64, "holds no triangle");
}

/// [V14] `NORM`, `TEXC`, `COLR` (written by version-1.0 writers): lengths `12V`, `8V`,
/// `4V`; finite values. Forged from a container without attributes.
#[test]
fn v14_attributes() {
    let bytes = encoded(
        &common::torus_with_everything(6, 5, 0, 0, 0, 3),
        Connectivity::Lr,
    );
    let file = open(&bytes, &Limits::default()).unwrap();
    let n = file.connectivity_vertex_count() as usize;
    let legacy = forge_sections(&bytes, |s| {
        s.insert(3, (Tag::NORM, lrmesh::format::Flags::NONE, vec![0; 12 * n]));
        s.insert(4, (Tag::TEXC, lrmesh::format::Flags::NONE, vec![0; 8 * n]));
        s.insert(5, (Tag::COLR, lrmesh::format::Flags::NONE, vec![7; 4 * n]));
    });
    let read = open(&legacy, &Limits::default()).unwrap();
    assert_eq!(read.attributes().len(), 3);
    assert_eq!(read.color(lrmesh::Vertex(2)), Some([7; 4]));
    for (tag, size) in [(Tag::NORM, 12), (Tag::TEXC, 8), (Tag::COLR, 4)] {
        let at = section_at(&legacy, tag);
        let bad = forge(&legacy, tag, |p| p.extend([0; 4]));
        breaks(&bad, 14, &tag.name(), at, "");
        let bad = forge(&legacy, tag, |p| p.truncate(size * (n - 1)));
        breaks(&bad, 14, &tag.name(), at, "");
        if tag != Tag::COLR {
            let field = size * 3 + 4;
            let bad = forge(&legacy, tag, |p| put(p, field, f32::INFINITY.to_bits()));
            breaks(&bad, 14, &tag.name(), at + field as u64, "non-finite");
        }
    }
}

/// The cube with per-vertex normals after its custom byte and texture coordinates last,
/// encoded with normals on 9 bits and texture coordinates on 11 (so that both records end
/// inside a word): the payload's three records as (offset, header).
fn quantized_cube() -> (Vec<u8>, [(usize, AttributeHeader); 3]) {
    use lrmesh::write::{encode, EncodeOptions};
    let mut mesh = cube();
    let uv = mesh.attributes.remove(0);
    let normals: Vec<[f32; 3]> = mesh.positions.iter().map(|p| p.map(|x| x - 0.5)).collect();
    mesh.attributes
        .push(Attribute::per_vertex(Semantic::Normal, &normals));
    mesh.attributes.push(uv);
    let options = EncodeOptions {
        keep_order: true,
        normal_bits: Some(9),
        texcoord_bits: Some(11),
        ..EncodeOptions::default()
    };
    let bytes = encode(&mesh, &options).unwrap();
    open(&bytes, &Limits::default()).expect("a valid container to forge");
    let p = payload(&bytes, Tag::ATTR);
    let mut at = 4;
    let records = [0; 3].map(|_| {
        let h = AttributeHeader::parse(&p[at..]);
        let len = record_len(&p[at..], &h);
        let r = (at, h);
        at += len;
        r
    });
    assert_eq!(at, p.len());
    (bytes, records)
}

/// The length of the record `r` whose header is `h`, quantized or not (8 vertices).
fn record_len(r: &[u8], h: &AttributeHeader) -> usize {
    use lrmesh::format::quantized::Quantizer;
    if h.value_encoding() == 0 {
        return h.layout(8).unwrap().len();
    }
    let bits = r[32 + h.name_len as usize];
    let q = if h.semantic == 1 {
        Quantizer::Octahedral { bits }
    } else {
        Quantizer::Grid {
            bits,
            components: h.components,
            lo: [0.0; 4],
            size: 0.0,
        }
    };
    let values = q.values_len(8 + u64::from(h.extra)).unwrap();
    h.layout_with_values(values).unwrap().len()
}

/// [V46] The value encoding: known, quantized only for f32 components, `b` in range, the
/// values part within the section, a finite range and size at least 0, and the last word's
/// unused bits 0.
#[test]
fn v46_quantized_values() {
    let (bytes, [(custom, hc), (normal, hn), (uv, hu)]) = quantized_cube();
    assert_eq!(
        (
            hc.value_encoding(),
            hn.value_encoding(),
            hu.value_encoding()
        ),
        (0, 1, 1)
    );
    assert!(hu.flagged > 0);
    let at = section_at(&bytes, Tag::ATTR);
    let o = |x: usize| at + x as u64;
    // An unknown encoding; encoding 1 on integers.
    breaks(
        &byte(&bytes, normal + 20, 3),
        46,
        "ATTR",
        o(normal + 20),
        "unknown value encoding",
    );
    breaks(
        &byte(&bytes, custom + 20, 1),
        46,
        "ATTR",
        o(custom + 20),
        "component type",
    );
    // `b` out of range: 0, 25 for a normal, 31 otherwise.
    let (nb, ub) = (normal + 32, uv + 32);
    assert_eq!((bytes_at(&bytes, nb), bytes_at(&bytes, ub)), (9, 11));
    breaks(
        &byte(&bytes, nb, 0),
        46,
        "ATTR",
        o(nb),
        "bits per quantized",
    );
    breaks(&byte(&bytes, nb, 25), 46, "ATTR", o(nb), "1 to 24");
    breaks(&byte(&bytes, ub, 31), 46, "ATTR", o(ub), "1 to 30");
    // One bit more: the last record no longer fits.
    breaks(&byte(&bytes, ub, 12), 46, "ATTR", o(uv), "section has");
    // A range that is not finite, a negative size.
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[ub + 1..ub + 5].copy_from_slice(&f32::NAN.to_le_bytes())
    });
    breaks(&bad, 46, "ATTR", o(ub + 1), "lo[0]");
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[ub + 5..ub + 9].copy_from_slice(&f32::INFINITY.to_le_bytes())
    });
    breaks(&bad, 46, "ATTR", o(ub + 5), "lo[1]");
    let bad = forge(&bytes, Tag::ATTR, |p| {
        p[ub + 9..ub + 13].copy_from_slice(&(-1.0f32).to_le_bytes())
    });
    breaks(&bad, 46, "ATTR", o(ub + 9), "size -1");
    // A bit set past the last value: 8 normals of 2 · 9 bits end inside the fifth word.
    let end = normal + record_len(&payload(&bytes, Tag::ATTR)[normal..], &hn);
    let bad = forge(&bytes, Tag::ATTR, |p| p[end - 1] |= 0x80);
    breaks(
        &bad,
        46,
        "ATTR",
        o(end - 4),
        "bits past the last quantized value",
    );
    // A zero size is valid: every value is `lo`.
    let ok = forge(&bytes, Tag::ATTR, |p| {
        p[ub + 9..ub + 13].copy_from_slice(&0.0f32.to_le_bytes())
    });
    let file = open(&ok, &Limits::default()).unwrap();
    let a = file.attribute(&Semantic::TexCoord(0)).unwrap();
    assert_eq!(a.value_f32(3), a.value_f32(0));
}

/// The byte of the `ATTR` payload at `at`.
fn bytes_at(bytes: &[u8], at: usize) -> u8 {
    payload(bytes, Tag::ATTR)[at]
}
