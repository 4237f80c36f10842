//! Per-corner attributes with seams and per-triangle parts through the container: every
//! connectivity kind, with and without the input order, keeps every corner's values; the
//! zero-copy view answers the value at a corner as the decoded mesh has it; seams cost only
//! where values differ.

use lrmesh::fuzz_checks::{round_trip_every_kind, round_trip_every_kind_with};
use lrmesh::lr::LrLayout;
use lrmesh::mesh::{Attribute, Part, Parts, Semantic, Values};
use lrmesh::ops::CornerOps;
use lrmesh::write::{encode, Connectivity, EncodeOptions, Orient};
use lrmesh::{Corner, Mesh};
use proptest::prelude::*;

/// A grid of `n × n` quads on a torus or a sheet, with per-corner texture coordinates that
/// break along one column (a seam) and per-face normals on some rows (creases).
fn seamed_grid(n: u32, closed: bool) -> Mesh {
    let size = if closed { n } else { n + 1 };
    let id = |i: u32, j: u32| (i % size) * size + (j % size);
    let mut positions = Vec::new();
    for i in 0..size {
        for j in 0..size {
            let (a, b) = (i as f32 / n as f32, j as f32 / n as f32);
            positions.push([a, b, (a * 7.0).sin() * (b * 5.0).cos()]);
        }
    }
    let mut triangles = Vec::new();
    let mut uv = Vec::new();
    let mut uv_index = Vec::new();
    let mut normals: Vec<[f32; 3]> = Vec::new();
    let mut normal_index = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let quad = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            for tri in [[quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]] {
                triangles.push(tri);
                for &v in &tri {
                    // The texture wraps: the last column's right corners get u = 1, not 0.
                    let (vi, vj) = (v / size, v % size);
                    let wraps = closed && vj == 0 && j == n - 1;
                    uv.push([
                        if wraps { 1.0 } else { vj as f32 / n as f32 },
                        vi as f32 / n as f32,
                    ]);
                    uv_index.push(uv.len() as u32 - 1);
                    // Rows i % 3 == 0 are flat shaded: one normal per triangle.
                    if i % 3 == 0 {
                        if normal_index.len() % 3 == 0 {
                            normals.push([0.0, (triangles.len() % 5) as f32, 1.0]);
                        }
                        normal_index.push(normals.len() as u32 - 1);
                    } else {
                        normals.push([vi as f32, vj as f32, 1.0]);
                        normal_index.push(normals.len() as u32 - 1);
                    }
                }
            }
        }
    }
    let mut mesh = Mesh::new(positions, triangles);
    mesh.attributes
        .push(Attribute::per_corner(Semantic::TexCoord(0), &uv, uv_index));
    mesh.attributes.push(Attribute::per_corner(
        Semantic::Normal,
        &normals,
        normal_index,
    ));
    mesh
}

/// Every kind, with and without the input order, keeps every corner's values (with the
/// default options, which may reverse triangles); as given and without the order, the view
/// answers each corner's value index as the decoded mesh has it (a reversed triangle's
/// corners 1 and 2 trade places on decoding).
fn round_trip(mesh: &Mesh) {
    round_trip_every_kind(mesh, "mesh", |_, _, _| {});
    let as_given = EncodeOptions {
        orient: Orient::AsGiven,
        ..EncodeOptions::default()
    };
    round_trip_every_kind_with(mesh, &as_given, "mesh", |options, bytes, back| {
        if options.keep_order {
            return;
        }
        let file = lrmesh::open(bytes).unwrap();
        let conn = file.connectivity();
        for (slot, t) in conn.triangles().enumerate() {
            for (k, c) in conn.triangle_corners(t).into_iter().enumerate() {
                for (view, decoded) in file.attributes().iter().zip(&back.attributes) {
                    if let Some(index) = &decoded.corners {
                        assert_eq!(
                            file.value_index(view, c),
                            index[3 * slot + k],
                            "{:?} corner {c}",
                            options.connectivity
                        );
                    }
                }
            }
        }
    });
}

#[test]
fn seams_of_a_torus_and_a_sheet_survive_every_kind() {
    round_trip(&seamed_grid(6, true));
    round_trip(&seamed_grid(5, false));
}

#[test]
fn seams_cost_extra_values_only_where_values_differ() {
    let mesh = seamed_grid(6, true);
    let file_bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let file = lrmesh::open(&file_bytes).unwrap();
    let uv = file.attribute(&Semantic::TexCoord(0)).unwrap();
    // The seam column: 6 vertices each get one extra value (u = 1 beside u = 0).
    assert_eq!(uv.extra_values(), 6);
    assert_eq!(uv.value_count(), 36 + 6);
    // Each vertex of the seam column has three triangles on each side: the side with fewer
    // corners on the minority value is flagged, at most 6 · 3 triangles, at least 6.
    let flagged = uv.flagged_triangles();
    assert!((6..=18).contains(&flagged), "{flagged}");
    // A seamless per-corner attribute costs its values and nothing else.
    let mut smooth = mesh.clone();
    smooth
        .attributes
        .retain(|a| a.semantic == Semantic::TexCoord(0));
    let uv_values: Vec<[f32; 2]> = smooth.positions.iter().map(|p| [p[0], p[1]]).collect();
    let index = smooth.triangles.iter().flatten().copied().collect();
    smooth.attributes = vec![Attribute::per_corner(
        Semantic::TexCoord(0),
        &uv_values,
        index,
    )];
    let bytes = encode(&smooth, &EncodeOptions::default()).unwrap();
    let file = lrmesh::open(&bytes).unwrap();
    let a = file.attribute(&Semantic::TexCoord(0)).unwrap();
    assert_eq!((a.extra_values(), a.flagged_triangles()), (0, 0));
    let attr = file.sections.section(lrmesh::format::Tag::ATTR).unwrap();
    assert_eq!(attr.bytes.len(), 4 + 32 + 8 * 36);
}

#[test]
fn a_corner_value_reads_in_place() {
    let mesh = seamed_grid(4, true);
    let bytes = encode(&mesh, &EncodeOptions::default()).unwrap();
    let file = lrmesh::open(&bytes).unwrap();
    let normal = file.attribute(&Semantic::Normal).unwrap();
    let conn = file.connectivity();
    // Every corner of a flat-shaded triangle has the same normal.
    let mut flat = 0;
    for t in conn.triangles() {
        let [a, b, c] = conn
            .triangle_corners(t)
            .map(|c: Corner| normal.value_f32(file.value_index(normal, c)));
        if a == b && b == c && a[0] == 0.0 {
            flat += 1;
        }
    }
    assert!(flat >= 2 * 4 * 2 - 2, "{flat}");
}

/// A soup on few vertices with random per-corner values, several attribute types, parts and
/// degenerate triangles.
fn soup() -> impl Strategy<Value = Mesh> {
    (3u32..12, 0usize..30).prop_flat_map(|(v, t)| {
        (
            proptest::collection::vec(proptest::array::uniform3(0..v), t),
            proptest::collection::vec(0u32..4, 3 * t),
            proptest::collection::vec(0u32..3, t),
            proptest::collection::vec(any::<u16>(), v as usize),
            Just(v),
        )
            .prop_map(|(triangles, wedge, part, custom, v)| {
                let positions = (0..v).map(|i| [i as f32, (i * i) as f32, 1.0]).collect();
                let mut mesh = Mesh::new(positions, triangles);
                let uv: Vec<[f32; 2]> = (0..4).map(|i| [i as f32 * 0.25, -0.0]).collect();
                mesh.attributes
                    .push(Attribute::per_corner(Semantic::TexCoord(1), &uv, wedge));
                mesh.attributes.push(Attribute {
                    semantic: Semantic::Custom("quality".into()),
                    components: 1,
                    normalized: true,
                    values: Values::U16(custom),
                    corners: None,
                });
                let mut parts = Parts::default();
                for p in part {
                    let i = parts.intern(Part {
                        material: Some(format!("m{p}")),
                        ..Part::default()
                    });
                    parts.of_triangle.push(i);
                }
                parts.material_libraries = vec!["a.mtl".into()];
                mesh.parts = Some(parts);
                mesh
            })
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]
    #[test]
    fn generated_seams_and_parts_round_trip(mesh in soup()) {
        round_trip(&mesh);
    }
}

/// The angle between `a` and the direction of `b`, in radians.
fn angle(a: &[f32], b: &[f32]) -> f64 {
    let (a, b) = (
        [a[0], a[1], a[2]].map(f64::from),
        [b[0], b[1], b[2]].map(f64::from),
    );
    let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    cross.iter().map(|x| x * x).sum::<f64>().sqrt().atan2(dot)
}

/// Quantized values (FORMAT.md §3.9.1) in every kind, with and without the input order:
/// decoding gives what [`dequantized`] says, the view gives the same at every corner, and
/// every value is within the stated error: half a step per grid component, `3·√2 / max`
/// radians for an octahedral normal.
fn quantized_round_trip(mesh: &Mesh, normal_bits: u8, texcoord_bits: u8) {
    use lrmesh::fuzz_checks::round_trip_every_kind_with;
    use lrmesh::write::dequantized;
    let base = EncodeOptions {
        normal_bits: Some(normal_bits),
        texcoord_bits: Some(texcoord_bits),
        ..EncodeOptions::default()
    };
    // The error bounds, value by value (the kind and the order change nothing here).
    let want = dequantized(mesh, &base).unwrap();
    for (a, q) in mesh.attributes.iter().zip(&want.attributes) {
        for i in 0..a.value_count() {
            let (x, y) = (a.value_f32(i), q.value_f32(i));
            if a.semantic == Semantic::Normal {
                let max = ((1u64 << normal_bits) - 1) as f64;
                let e = angle(&y, &x);
                assert!(e <= 3.0 * 2f64.sqrt() / max + 1e-6, "{x:?} {y:?}: {e}");
                let len: f64 = y.iter().map(|&c| (c as f64).powi(2)).sum();
                assert!((len - 1.0).abs() < 1e-6);
            } else {
                let lo = (0..a.value_count())
                    .map(|j| a.value_f32(j))
                    .fold([f32::MAX; 2], |m, v| [m[0].min(v[0]), m[1].min(v[1])]);
                let hi = (0..a.value_count())
                    .map(|j| a.value_f32(j))
                    .fold([f32::MIN; 2], |m, v| [m[0].max(v[0]), m[1].max(v[1])]);
                let size = (0..2)
                    .map(|k| hi[k] as f64 - lo[k] as f64)
                    .fold(0.0, f64::max);
                let step = size / ((1u64 << texcoord_bits) - 1) as f64;
                for k in 0..2 {
                    let e = (x[k] as f64 - y[k] as f64).abs();
                    assert!(e <= step / 2.0 * (1.0 + 1e-6) + 1.2e-7 * y[k].abs() as f64);
                }
            }
        }
    }
    // Decoding gives `want` in every kind (checked by the round trip); the view gives the
    // same values at every corner.
    round_trip_every_kind_with(mesh, &base, "quantized", |options, bytes, back| {
        let file = lrmesh::open(bytes).unwrap();
        // 1.17 for LR tables listing open fans, 1.4 with the boundary flag, 1.3 for normals
        // predicted from their neighbours alone, else 1.2.
        let flagged = file.lr().is_some_and(|t| t.boundaries_on_ring())
            || file.lr_compact().is_some_and(|t| t.boundaries_on_ring());
        let listed = file.lr().is_some_and(|t| t.open_fans_listed());
        let minor = if listed {
            17
        } else if flagged {
            4
        } else if file.attributes().iter().any(|a| a.normal_predictor() == 1) {
            3
        } else {
            2
        };
        assert_eq!(u16::from_le_bytes([bytes[10], bytes[11]]), minor, "version");
        if options.keep_order {
            return;
        }
        let conn = file.connectivity();
        for (slot, t) in conn.triangles().enumerate() {
            for (k, c) in conn.triangle_corners(t).into_iter().enumerate() {
                for (view, decoded) in file.attributes().iter().zip(&back.attributes) {
                    // Predicted (2) only in Edgebreaker from level 1, where it is shorter.
                    let predictable =
                        options.connectivity == Connectivity::Edgebreaker && options.level > 0;
                    assert!(
                        view.value_encoding() == 1 || (predictable && view.value_encoding() == 2),
                        "{:?} level {}: encoding {}",
                        options.connectivity,
                        options.level,
                        view.value_encoding()
                    );
                    let i = file.value_index(view, c);
                    assert!(view.value_bytes(i).is_none());
                    let index = decoded.corners.as_ref().unwrap();
                    let got = view.value_f32(i);
                    let from_mesh = decoded.value_f32(index[3 * slot + k] as usize);
                    assert_eq!(&got[..from_mesh.len()], &from_mesh[..]);
                }
            }
        }
    });
}

#[test]
fn quantized_values_survive_every_kind_within_their_bounds() {
    for bits in [(10, 12), (4, 3), (24, 30), (1, 1)] {
        quantized_round_trip(&seamed_grid(6, true), bits.0, bits.1);
        quantized_round_trip(&seamed_grid(5, false), bits.0, bits.1);
    }
}

#[test]
fn quantized_values_are_smaller_and_raw_files_do_not_change() {
    let mesh = seamed_grid(8, true);
    let raw = encode(&mesh, &EncodeOptions::default()).unwrap();
    let options = EncodeOptions {
        normal_bits: Some(10),
        texcoord_bits: Some(12),
        ..EncodeOptions::default()
    };
    let quantized = encode(&mesh, &options).unwrap();
    let attr = |b: &[u8]| {
        let file = lrmesh::open(b).unwrap();
        let n = file
            .sections
            .section(lrmesh::format::Tag::ATTR)
            .unwrap()
            .bytes
            .len();
        n
    };
    assert!(
        3 * attr(&quantized) < attr(&raw),
        "{} {}",
        attr(&quantized),
        attr(&raw)
    );
    // Integer attributes stay raw; bits out of range are refused.
    let mut colored = mesh.clone();
    colored
        .attributes
        .push(lrmesh::mesh::Attribute::rgba8(&vec![
            [1, 2, 3, 4];
            colored.positions.len()
        ]));
    let file_bytes = encode(
        &colored,
        &EncodeOptions {
            color_bits: Some(8),
            ..options.clone()
        },
    )
    .unwrap();
    let file = lrmesh::open(&file_bytes).unwrap();
    let color = file.attribute(&Semantic::Color(0)).unwrap();
    assert_eq!(color.value_encoding(), 0);
    assert_eq!(file.color(lrmesh::Vertex(0)), Some([1, 2, 3, 4]));
    for bad in [
        EncodeOptions {
            normal_bits: Some(25),
            ..EncodeOptions::default()
        },
        EncodeOptions {
            texcoord_bits: Some(0),
            ..EncodeOptions::default()
        },
    ] {
        assert!(encode(&mesh, &bad).is_err());
    }
}

/// Real meshes with seams: in Edgebreaker from level 1, quantized normals and texture
/// coordinates are predicted (value encoding 2) with coded seams (seam encoding 1), shorter
/// than packed with the seam tables, and every corner reads the same value as in the packed
/// file of level 0.
#[test]
fn predicted_values_equal_the_packed_ones_on_real_meshes() {
    for path in [
        "corpus/assets/obj/spider/spider.obj",
        "corpus/assets/obj/regr01/regr01.obj",
        "corpus/assets/obj/tinyobjloader/map-bump.obj",
    ] {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(path);
        let mesh = lrmesh::io::read_mesh(&path, &Default::default())
            .unwrap()
            .mesh;
        // As given: whether reversing triangles makes the smaller file depends on the level.
        let options = |level| EncodeOptions {
            connectivity: Connectivity::Edgebreaker,
            position_bits: Some(14),
            normal_bits: Some(10),
            texcoord_bits: Some(12),
            level,
            orient: Orient::AsGiven,
            ..EncodeOptions::default()
        };
        let packed = encode(&mesh, &options(0)).unwrap();
        let predicted = encode(&mesh, &options(6)).unwrap();
        let (a, b) = (
            lrmesh::open(&packed).unwrap(),
            lrmesh::open(&predicted).unwrap(),
        );
        assert_eq!(a.attributes().len(), b.attributes().len());
        for (x, y) in a.attributes().iter().zip(b.attributes()) {
            assert_eq!((x.value_encoding(), y.value_encoding()), (1, 2), "{path:?}");
            if x.flagged_triangles() > 0 {
                assert_eq!((x.seam_encoding(), y.seam_encoding()), (0, 1), "{path:?}");
            }
            assert!(
                y.stored_bytes() < x.stored_bytes(),
                "{path:?} {}: predicted {} bytes, packed {}",
                y.semantic,
                y.stored_bytes(),
                x.stored_bytes()
            );
            let (ca, cb) = (a.connectivity(), b.connectivity());
            assert_eq!(ca.triangle_count(), cb.triangle_count());
            for (ta, tb) in ca.triangles().zip(cb.triangles()) {
                for (c, d) in ca
                    .triangle_corners(ta)
                    .into_iter()
                    .zip(cb.triangle_corners(tb))
                {
                    let (i, j) = (a.value_index(x, c), b.value_index(y, d));
                    assert_eq!(x.value_levels(i), y.value_levels(j), "{path:?}");
                }
            }
        }
    }
}
