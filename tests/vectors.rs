//! The test vectors of `spec/vectors/`: for each source mesh, the exact container bytes and
//! the vertex and opposite of every corner. The crate must reproduce the bytes when encoding
//! the source, and read the listed answers from the bytes.
//!
//! `LRMESH_REGENERATE_VECTORS=1 cargo test --test vectors` rewrites the files after a
//! deliberate format change.

use std::fmt::Write as _;
use std::path::PathBuf;

mod common;
use common::{assert_same_up_to_rotation, assert_within_half_a_step};

use lrmesh::format::Metadata;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::LrLayout;
use lrmesh::read::{open, open_verified, Connectivity as View, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::CornerOps;

/// Sources, read as OFF unless named in [`OBJ_VECTORS`].
const VECTORS: [&str; 11] = [
    "closed_tetrahedron",
    "boundary_hedra_open",
    "two_components",
    "nonmanifold_vertex",
    // A torus whose LR has T0 triangles and irregular slots (records, T0 rows).
    "torus_with_t0",
    // A torus with flipped edges, a non-manifold edge and vertex, a degenerate triangle and
    // an unused vertex (spec/vectors/README.md): in lr-compact, stored opposites that are
    // ring corners and NONE.
    "defective_torus",
    // Per-corner texture coordinates and normals with seams, and parts (FORMAT.md §3.9,
    // §3.10): each container also has an attribute listing.
    "seamed_cube",
    // A flat grid with bent normals: on the 12-bit grid they are predicted from their
    // neighbours (ATTR normal predictor 1, GEOMETRY.md §7.3).
    "bent_normals",
    // A cube with reversed triangles and per-corner texture coordinates, encoded with its
    // orientation repaired (section FLIP, FORMAT.md §3.11).
    "misoriented_cube",
    // CGAL's genus-3 torus (corpus/meshes/3torus.off): Zipper records that store both
    // opposites (the pair list).
    "genus3_torus",
    // Four spheres apart (`lrmesh generate --triangles 400 --components 4 --genus 0
    // --irregular`): four rings over four blocks, each block's ring in RING_BLOCKS (ZIPR).
    "four_spheres",
];

/// The sources written as OBJ (per-corner attributes, parts).
const OBJ_VECTORS: [&str; 3] = ["seamed_cube", "bent_normals", "misoriented_cube"];

/// The sources encoded with [`Orient::Repair`].
const ORIENTED_VECTORS: [&str; 1] = ["misoriented_cube"];

/// Sources also written with quantized positions (`NAME.q12*.lrm`: a 12-bit grid, GEOM
/// encodings 2 and 4) and attributes (normals on 10 bits, texture coordinates on 12: ATTR
/// value encoding 1), each container with a listing of its decoded positions and values.
const QUANTIZED_VECTORS: [&str; 3] = ["torus_with_t0", "seamed_cube", "bent_normals"];

/// Sources also written at compression level 1 with quantized positions, Edgebreaker only
/// (`NAME.q12.l1.edgebreaker.lrm`: `GEOM` encoding 6, GEOMETRY.md §9), each with a listing
/// of its decoded positions.
const ANCHORED_VECTORS: [&str; 2] = ["torus_with_t0", "defective_torus"];

/// The level of [`ANCHORED_VECTORS`]; the others are written at the default level.
const ANCHORED_LEVEL: u8 = 1;

/// The grid of the quantized vectors' positions and texture coordinates.
const QUANTIZED_BITS: u8 = 12;
/// The bits of the quantized vectors' octahedral normals.
const QUANTIZED_NORMAL_BITS: u8 = 10;

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("spec/vectors")
}

/// The options the vectors are encoded with: input order kept, fixed metadata, the
/// orientation repaired for [`ORIENTED_VECTORS`].
fn options(
    name: &str,
    connectivity: Connectivity,
    position_bits: Option<u8>,
    level: u8,
) -> EncodeOptions {
    EncodeOptions {
        connectivity,
        level,
        keep_order: true,
        orient: if ORIENTED_VECTORS.contains(&name) {
            Orient::Repair
        } else {
            Orient::AsGiven
        },
        position_bits,
        normal_bits: position_bits.map(|_| QUANTIZED_NORMAL_BITS),
        texcoord_bits: position_bits,
        metadata: Metadata {
            generator: "lrmesh test vectors".into(),
            ..Metadata::default()
        },
        ..EncodeOptions::default()
    }
}

/// For LR and strips, one line per corner of every (canonical) triangle:
/// `corner vertex opposite` (`-` for none), then one per vertex: `vertex v.c`. For Edgebreaker, one line per decoded triangle: its
/// three vertices, in decode order.
fn listing(name: &str, bytes: &[u8]) -> String {
    let view = open(bytes, &Limits::default()).unwrap();
    let mut out = String::new();
    let n = view.triangle_count();
    match view.connectivity() {
        View::Lr(lr) => corner_listing(
            &mut out,
            name,
            lr,
            format!(
                "{n} triangles, {} ring vertices, boundaries on the ring: {}, open fans listed: {}",
                lr.ring_vertices(),
                lr.boundaries_on_ring(),
                lr.listed_fans().map_or("no list".to_string(), |f| f.len().to_string())
            ),
        ),
        View::LrCompact(lr) => corner_listing(
            &mut out,
            name,
            lr,
            format!(
                "{n} triangles, {} ring vertices, {} T0 rows, boundaries on the ring: {}",
                lr.ring_vertices(),
                lr.t0_count(),
                lr.boundaries_on_ring()
            ),
        ),
        View::Zipper(z) => corner_listing(
            &mut out,
            name,
            z,
            format!(
                "{n} triangles, {} ring vertices, {} T0 rows, {} exceptions, {} records, {} pairs, {} explicit T0 opposites, boundaries on the ring: {}, wart deltas: {}, short heads: {}, packed lists: {}, inner ring starts: {}, ring blocks: {}, compact: {}, fours: {}, row records: {}, implied warts: {}, joined lists: {}",
                z.ring_vertices(),
                z.t0_count(),
                z.exception_count(),
                z.record_count(),
                z.pair_count(),
                z.explicit_count(),
                z.boundaries_on_ring(),
                z.wart_deltas(),
                z.short_heads(),
                z.packed_lists(),
                z.inner_ring_starts(),
                z.ring_blocks(),
                match z.head_widths() {
                    Some([a, x, i]) => format!("heads of {a}-bit anchors, {x}- and {i}-bit counts"),
                    None => "false".into(),
                },
                match z.fours() {
                    [false, false] => "none",
                    [true, false] => "left",
                    [false, true] => "right",
                    [true, true] => "left and right",
                },
                z.row_records_and_implied_warts()[0],
                z.row_records_and_implied_warts()[1],
                z.joined_lists(),
            ),
        ),
        View::Strips(strips) => corner_listing(
            &mut out,
            name,
            strips,
            format!("{n} triangles, {} strip entries", strips.len()),
        ),
        View::Edgebreaker(table) => {
            writeln!(
                out,
                "# lrmesh test vector {name}: the decoded triangles, in decode order"
            )
            .unwrap();
            writeln!(out, "# {} triangles", table.triangle_id_bound()).unwrap();
            writeln!(out, "# triangle a b c").unwrap();
            for t in table.triangles() {
                let [a, b, c] = table.triangle_vertices(t);
                writeln!(out, "{t} {a} {b} {c}").unwrap();
            }
        }
    }
    // Section FLIP (FORMAT.md §3.11): u32 T, then a bit per output triangle.
    if let Some(flip) = view.sections.section(lrmesh::format::Tag::FLIP) {
        let bits = &flip.bytes[4..];
        let words: Vec<String> = (0..8 * bits.len())
            .filter(|&j| bits[j / 8] >> (j % 8) & 1 == 1)
            .map(|j| j.to_string())
            .collect();
        writeln!(
            out,
            "# FLIP: output triangles reversed on decoding: {}",
            words.join(" ")
        )
        .unwrap();
    }
    out
}

/// For a container with attributes or parts, one line per corner of every triangle slot
/// (FORMAT.md §3.9): `slot corner vertex`, the value index of each attribute in file order,
/// and the slot's part (`-` without `PART`).
fn attribute_listing(name: &str, bytes: &[u8]) -> Option<String> {
    let file = open(bytes, &Limits::default()).unwrap();
    if file.attributes().is_empty() && file.parts().is_none() {
        return None;
    }
    let conn = file.connectivity();
    let mut out = String::new();
    writeln!(
        out,
        "# lrmesh test vector {name}: the value of every attribute and the part at every corner"
    )
    .unwrap();
    let parts = file.parts().map_or(0, |p| p.labels.parts.len());
    writeln!(
        out,
        "# {} attributes, {parts} parts, {} kept triangles",
        file.attributes().len(),
        file.kept_triangle_count()
    )
    .unwrap();
    if let Some(p) = file.parts() {
        for (i, part) in p.labels.parts.iter().enumerate() {
            writeln!(out, "# part {i} {}", serde_json::to_string(part).unwrap()).unwrap();
        }
        for lib in &p.labels.material_libraries {
            writeln!(out, "# library {}", serde_json::to_string(lib).unwrap()).unwrap();
        }
    }
    let names: Vec<String> = (0..file.attributes().len())
        .map(|a| format!("a{a}"))
        .collect();
    writeln!(out, "# slot corner vertex {} part", names.join(" ")).unwrap();
    let part = |p: Option<u32>| p.map_or("-".to_string(), |p| p.to_string());
    for t in conn.triangles() {
        for (k, c) in conn.triangle_corners(t).into_iter().enumerate() {
            let values: Vec<String> = file
                .attributes()
                .iter()
                .map(|a| file.value_index(a, c).to_string())
                .collect();
            let v = conn.vertex(c);
            writeln!(
                out,
                "{t} {k} {v} {} {}",
                values.join(" "),
                part(file.part_index(t))
            )
            .unwrap();
        }
    }
    let bound = conn.triangle_id_bound();
    for j in 0..file.kept_triangle_count() {
        for k in 0..3 {
            let values: Vec<String> = file
                .attributes()
                .iter()
                .map(|a| file.kept_value_index(a, j, k).to_string())
                .collect();
            let v = file.kept_vertex(j, k);
            let slot = bound + j;
            writeln!(
                out,
                "{slot} {k} {v} {} {}",
                values.join(" "),
                part(file.kept_part_index(j))
            )
            .unwrap();
        }
    }
    Some(out)
}

/// The listing of a representation with corner operators: a header with its vertex count
/// and `counts`, then `corner vertex opposite` for every corner of every canonical triangle.
fn corner_listing<M: CornerOps>(out: &mut String, name: &str, m: &M, counts: String) {
    writeln!(
        out,
        "# lrmesh test vector {name}: the vertex and opposite of every corner"
    )
    .unwrap();
    writeln!(out, "# {} vertices, {counts}", m.vertex_id_bound()).unwrap();
    writeln!(out, "# corner vertex opposite").unwrap();
    for c in m.corners() {
        let o = m.opposite(c).map_or("-".to_string(), |o| o.0.to_string());
        writeln!(out, "{} {} {o}", c.0, m.vertex(c).0).unwrap();
    }
    writeln!(
        out,
        "# vertex v.c (the first corner of its fan when the fan is open)"
    )
    .unwrap();
    for v in m.vertices() {
        let c = m
            .vertex_corner(v)
            .map_or("-".to_string(), |c| c.0.to_string());
        writeln!(out, "{} {c}", v.0).unwrap();
    }
}

/// One line per container vertex: its id and decoded position, each coordinate as the hex
/// bits of its f32 then its decimal value.
fn positions_listing(name: &str, bytes: &[u8]) -> String {
    let file = open(bytes, &Limits::default()).unwrap();
    let mut out = String::new();
    writeln!(
        out,
        "# lrmesh test vector {name}: the decoded position of every container vertex"
    )
    .unwrap();
    let summary = file.summary();
    writeln!(
        out,
        "# {} vertices, GEOM encoding {}, {} bits",
        file.connectivity_vertex_count(),
        summary.positions.encoding,
        summary.positions.bits.unwrap_or(32)
    )
    .unwrap();
    writeln!(out, "# vertex x y z (f32 bits, then value)").unwrap();
    for v in 0..file.connectivity_vertex_count() {
        let p = file.position(lrmesh::Vertex(v));
        let bits: Vec<String> = p.iter().map(|x| format!("{:08x}", x.to_bits())).collect();
        writeln!(
            out,
            "{v} {} {} {} {:?} {:?} {:?}",
            bits[0], bits[1], bits[2], p[0], p[1], p[2]
        )
        .unwrap();
    }
    out
}

/// For a container with quantized attribute values (ATTR value encoding 1), one line per
/// value of each such attribute: the attribute's index, the value's index, its stored
/// integers, then its decoded components as the hex bits of their f32s. `None` without one.
fn values_listing(name: &str, bytes: &[u8]) -> Option<String> {
    let file = open(bytes, &Limits::default()).unwrap();
    let quantized: Vec<(usize, &lrmesh::read::attributes::AttributeView)> = file
        .attributes()
        .iter()
        .enumerate()
        .filter(|(_, a)| a.quantizer().is_some())
        .collect();
    if quantized.is_empty() {
        return None;
    }
    let mut out = String::new();
    writeln!(
        out,
        "# lrmesh test vector {name}: the decoded values of every quantized attribute"
    )
    .unwrap();
    writeln!(out, "# {} quantized attributes", quantized.len()).unwrap();
    writeln!(
        out,
        "# attribute value integers... components... (f32 bits)"
    )
    .unwrap();
    for (index, a) in quantized {
        let integers = if a.semantic == lrmesh::mesh::Semantic::Normal {
            2
        } else {
            a.components as usize
        };
        for i in 0..a.value_count() {
            let q = a.value_levels(i).unwrap();
            let x = a.value_f32(i);
            let q: Vec<String> = q[..integers].iter().map(|q| q.to_string()).collect();
            let x: Vec<String> = x[..a.components as usize]
                .iter()
                .map(|x| format!("{:08x}", x.to_bits()))
                .collect();
            writeln!(out, "{index} {i} {} {}", q.join(" "), x.join(" ")).unwrap();
        }
    }
    Some(out)
}

/// The source mesh of vector `name` (OFF, or OBJ for those of [`OBJ_VECTORS`]).
fn source_mesh(name: &str) -> lrmesh::Mesh {
    let extension = if OBJ_VECTORS.contains(&name) {
        "obj"
    } else {
        "off"
    };
    let source = dir().join(format!("{name}.{extension}"));
    read_mesh(&source, &ReadOptions::default()).unwrap().mesh
}

#[test]
fn vectors_match() {
    let regenerate = std::env::var_os("LRMESH_REGENERATE_VECTORS").is_some();
    let exact = VECTORS.iter().map(|&name| (name, None));
    let quantized = QUANTIZED_VECTORS
        .iter()
        .map(|&name| (name, Some(QUANTIZED_BITS)));
    let default = EncodeOptions::default().level;
    let at_default = exact
        .chain(quantized)
        .map(|(name, bits)| (name, bits, default));
    let anchored = ANCHORED_VECTORS
        .iter()
        .map(|&name| (name, Some(QUANTIZED_BITS), ANCHORED_LEVEL));
    for (name, bits, level) in at_default.chain(anchored) {
        let mut grid = bits.map_or(String::new(), |b| format!(".q{b}"));
        if level != default {
            grid += &format!(".l{level}");
        }
        for (connectivity, suffix) in [
            (Connectivity::Lr, ""),
            (Connectivity::Edgebreaker, ".edgebreaker"),
            (Connectivity::Strips, ".strips"),
            (Connectivity::LrCompact, ".lr-compact"),
            (Connectivity::Zipper, ".zipper"),
        ] {
            if level != default && connectivity != Connectivity::Edgebreaker {
                continue;
            }
            let mesh = source_mesh(name);
            let bytes = encode(&mesh, &options(name, connectivity, bits, level)).unwrap();
            let stem = format!("{name}{grid}{suffix}");
            let lrm = dir().join(format!("{stem}.lrm"));
            let txt = dir().join(format!("{stem}.txt"));
            let attributes_txt = dir().join(format!("{stem}.attributes.txt"));
            let positions_txt = dir().join(format!("{stem}.positions.txt"));
            let values_txt = dir().join(format!("{stem}.values.txt"));
            if regenerate {
                std::fs::write(&lrm, &bytes).unwrap();
                std::fs::write(&txt, listing(name, &bytes)).unwrap();
                if let Some(a) = attribute_listing(name, &bytes) {
                    std::fs::write(&attributes_txt, a).unwrap();
                }
                if bits.is_some() {
                    std::fs::write(&positions_txt, positions_listing(name, &bytes)).unwrap();
                }
                if let Some(v) = values_listing(name, &bytes) {
                    std::fs::write(&values_txt, v).unwrap();
                }
            }
            let stored = std::fs::read(&lrm).unwrap();
            assert_eq!(
                bytes, stored,
                "{name}: encoding the source no longer gives the vector's bytes"
            );
            let expected = std::fs::read_to_string(&txt).unwrap();
            assert_eq!(
                listing(name, &stored),
                expected,
                "{name}: corner answers differ"
            );
            assert_eq!(
                attribute_listing(name, &stored),
                std::fs::read_to_string(&attributes_txt).ok(),
                "{name}: attribute answers differ"
            );
            // Decoding gives back the source exactly (the vectors keep the input order),
            // every corner's attribute values and every triangle's part included; quantized
            // positions as listed, within half a step of the source's.
            let back = open_verified(&stored, &Limits::default())
                .unwrap()
                .to_mesh();
            let mut mesh = mesh;
            if let Some(bits) = bits {
                assert_eq!(
                    positions_listing(name, &stored),
                    std::fs::read_to_string(&positions_txt).unwrap(),
                    "{stem}: decoded positions differ"
                );
                assert_within_half_a_step(&back.positions, &mesh.positions, bits, &stem);
                mesh.positions = back.positions.clone();
                // Quantized attribute values come back as `dequantized` says, and as listed.
                mesh = lrmesh::write::dequantized(
                    &mesh,
                    &options(name, connectivity, Some(bits), level),
                )
                .unwrap();
            }
            assert_eq!(
                values_listing(name, &stored),
                std::fs::read_to_string(&values_txt).ok(),
                "{stem}: decoded attribute values differ"
            );
            assert_eq!(back.positions, mesh.positions, "{name}");
            assert_same_up_to_rotation(&back.triangles, &mesh.triangles, name);
            lrmesh::fuzz_checks::assert_same_in_order(&back, &mesh);
        }
    }
}

/// Zipper files of versions 1.7 (no `WART_DELTAS`: every wart an exception word), 1.8
/// (four-word heads, before `SHORT_HEADS`), 1.9 (32-bit lists, before `PACKED_LISTS`), 1.10
/// (every ring start stored, ring-end bits, before `INNER_RING_STARTS` and `RING_BLOCKS`)
/// 1.12 (the 40-byte header and two-word heads, before the compact form), 1.13 (before
/// `LEFT_FOURS` and `RIGHT_FOURS`: a chain's step of 4 an exception word) and 1.14 (before
/// `ROW_RECORDS` and `IMPLIED_WARTS`: records of T0 corners, stored WART flags) and 1.15
/// (before `JOINED_LISTS`: each list padded to a word), kept from before each change, for `torus_with_t0` and `genus3_torus`, `two_components` of versions
/// 1.10 and 1.12 to 1.15 (two rings) and `four_spheres` of versions 1.12 to 1.15 (four
/// rings over four blocks): they still open, verify, and give every corner's vertex and opposite as a file
/// of the current version of the same ring does (the listing after its header lines). They
/// were written from the ring of seed 1 alone: the current vectors come from the smallest
/// of 32 seeds (level 6, `write::zipper_seeds`), so that file is written at level 5, which
/// builds one.
#[test]
fn zipper_files_of_versions_1_7_to_1_15_read_the_same() {
    let versions = [
        (
            7,
            "wart deltas: false, short heads: false, packed lists: false, inner ring starts: false, ring blocks: false, compact: false, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (
            8,
            "wart deltas: true, short heads: false, packed lists: false, inner ring starts: false, ring blocks: false, compact: false, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (
            9,
            "wart deltas: true, short heads: true, packed lists: false, inner ring starts: false, ring blocks: false, compact: false, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (
            10,
            "wart deltas: true, short heads: true, packed lists: true, inner ring starts: false, ring blocks: false, compact: false, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (
            12,
            "wart deltas: true, short heads: true, packed lists: true, inner ring starts: true, ring blocks: true, compact: false, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (
            13,
            "-bit counts, fours: none, row records: false, implied warts: false, joined lists: false",
        ),
        (14, "row records: false, implied warts: false, joined lists: false"),
        (15, "row records: true, implied warts: true, joined lists: false"),
    ];
    for name in [
        "torus_with_t0",
        "genus3_torus",
        "two_components",
        "four_spheres",
    ] {
        let versions = match name {
            "two_components" => &versions[3..],
            "four_spheres" => &versions[4..],
            _ => &versions[..],
        };
        let mesh = source_mesh(name);
        let one_seed = options(name, Connectivity::Zipper, None, 5);
        assert_eq!(lrmesh::write::zipper_seeds(5, mesh.triangles.len()), 1);
        let current = encode(&mesh, &one_seed).unwrap();
        let new_listing = listing(name, &current);
        let header = new_listing.lines().nth(1).unwrap();
        assert!(
            header.contains(
                "short heads: false, packed lists: true, inner ring starts: true, \
                 ring blocks: true, compact: heads of"
            ),
            "{header}"
        );
        assert!(header.contains("fours: left"), "{header}");
        assert!(header.contains("row records: true"), "{header}");
        assert!(header.ends_with("joined lists: true"), "{header}");
        for &(minor, flags) in versions {
            let file = format!("{name}.zipper-1.{minor}.lrm");
            let old = std::fs::read(dir().join(&file)).unwrap();
            assert_eq!(u16::from_le_bytes([old[10], old[11]]), minor, "{file}");
            open_verified(&old, &Limits::default()).unwrap();
            let old_listing = listing(name, &old);
            assert!(
                old_listing.lines().nth(1).unwrap().ends_with(flags),
                "{file}"
            );
            let corners = |s: &str| s.lines().skip(2).map(str::to_owned).collect::<Vec<_>>();
            assert_eq!(corners(&old_listing), corners(&new_listing), "{file}");
        }
    }
}

/// `NAME.lr-compact-bases.lrm`, for `torus_with_t0` and `genus3_torus`: `NAME.lr-compact.lrm`
/// with its plain pairs rewritten under the `LRBE` flag `TIP_BASES` (FORMAT.md §3.5d, version
/// 1.11), as spec/vectors/README.md says: each block's base of a side is the lower median of
/// its plain pairs' offsets `tip − v` on that side (`NULL` tips left out; 0 when there are
/// none), and each tip is written from the base when that offset is smaller in magnitude,
/// from `v` otherwise. The writer sets the flag only when it saves bytes, which it never
/// does on a small mesh: this keeps files with both kinds of field.
fn with_tip_bases(bytes: &[u8]) -> Vec<u8> {
    use common::forge::{forge, Tables, BASES, PAIRS};
    use lrmesh::format::layout::LRBE_TIP_BASES;
    use lrmesh::lr::compact::plain::{short15, FAR, NEAR_MAX, NEAR_MIN};
    forge(bytes, lrmesh::format::Tag::LRBE, |p| {
        let mut t = Tables::lrbe(p);
        t.head[7] |= LRBE_TIP_BASES;
        let pairs = t.array(PAIRS).clone();
        let plain = |word: u32| word >> 30 != 3;
        let mut bases = Vec::new();
        for block in pairs.chunks(256) {
            for side in 0..2 {
                let mut offsets: Vec<i32> = block
                    .iter()
                    .filter(|&&word| plain(word))
                    .map(|word| short15(word >> (15 * side)))
                    .filter(|&d| d != 0)
                    .collect();
                offsets.sort_unstable();
                bases.push(
                    offsets
                        .get(offsets.len().saturating_sub(1) / 2)
                        .map_or(0, |&d| d),
                );
            }
        }
        for (v, word) in t.array(PAIRS).iter_mut().enumerate() {
            if !plain(*word) {
                continue;
            }
            let mut fields = [0u32; 2];
            for (side, field) in fields.iter_mut().enumerate() {
                let d = short15(*word >> (15 * side)) as i64;
                let e = d - bases[2 * (v / 256) + side] as i64;
                *field = if d == 0 {
                    0
                } else if e.abs() < d.abs() && (NEAR_MIN..=NEAR_MAX).contains(&e) {
                    FAR | e as u32 & 0x3FFF
                } else {
                    assert!((NEAR_MIN..=NEAR_MAX).contains(&d), "a small mesh's offset");
                    d as u32 & 0x3FFF
                };
            }
            *word = *word & 0xC000_0000 | fields[1] << 15 | fields[0];
        }
        *t.array(BASES) = bases.iter().map(|&b| b as u32).collect();
        *p = t.join();
    })
}

/// The files of [`with_tip_bases`]: the rewrite gives exactly the stored bytes (or rewrites
/// them with `LRMESH_REGENERATE_VECTORS`), they have minor version 11, both kinds of field,
/// open, verify, and give every corner's vertex and opposite as `NAME.lr-compact.txt` lists.
#[test]
fn lr_compact_files_with_tip_bases_read_the_same() {
    let regenerate = std::env::var_os("LRMESH_REGENERATE_VECTORS").is_some();
    for name in ["torus_with_t0", "genus3_torus"] {
        let plain_file = std::fs::read(dir().join(format!("{name}.lr-compact.lrm"))).unwrap();
        let ours = with_tip_bases(&plain_file);
        let path = dir().join(format!("{name}.lr-compact-bases.lrm"));
        if regenerate {
            std::fs::write(&path, &ours).unwrap();
        }
        let stored = std::fs::read(&path).unwrap();
        assert_eq!(ours, stored, "{name}: the rewrite gives the stored bytes");
        assert_eq!(u16::from_le_bytes([stored[10], stored[11]]), 11, "{name}");
        let view = open_verified(&stored, &Limits::default()).unwrap();
        let View::LrCompact(t) = view.connectivity() else {
            panic!("{name}: not lr-compact");
        };
        assert!(t.has_tip_bases(), "{name}");
        let words = common::forge::Tables::lrbe(&common::forge::payload(
            &stored,
            lrmesh::format::Tag::LRBE,
        ))
        .array(common::forge::PAIRS)
        .clone();
        let fields: Vec<u32> = words
            .iter()
            .filter(|&&w| w >> 30 != 3)
            .flat_map(|&w| [w & 0x7FFF, w >> 15 & 0x7FFF])
            .filter(|&f| f != 0)
            .collect();
        let far = fields.iter().filter(|&&f| f & (1 << 14) != 0).count();
        assert!(
            far > 0 && far < fields.len(),
            "{name}: {far} far fields of {}",
            fields.len()
        );
        let corners = |s: &str| s.lines().skip(2).map(str::to_owned).collect::<Vec<_>>();
        let expected =
            std::fs::read_to_string(dir().join(format!("{name}.lr-compact.txt"))).unwrap();
        assert_eq!(
            corners(&listing(name, &stored)),
            corners(&expected),
            "{name}"
        );
    }
}
