//! The `round_trip` fuzz target: a triangle soup with attributes, made from the fuzzer's bytes, encoded with arbitrary
//! options (connectivity, tries, seed, input order kept or not, positions quantized or not)
//! and decoded: the same triangles (oriented, up to rotation) on the same positions with the
//! same attributes; in the input order when it was kept, as the same multiset otherwise;
//! quantized positions within one step of the grid, quantized attribute values as
//! [`crate::write::dequantized`] gives them. Encoding never fails on a valid mesh.

use arbitrary::{Result, Unstructured};

use crate::lr::LrOptions;
use crate::mesh::{Attribute, Order, Part, Parts, Semantic};
use crate::read::{open, Limits};
use crate::write::{encode, Connectivity, EncodeOptions};
use crate::Mesh;

fn soup(u: &mut Unstructured) -> Result<(Mesh, EncodeOptions)> {
    let vertices = u.int_in_range(1..=40u32)?;
    let triangles = u.int_in_range(0..=80u32)?;
    let coordinate =
        |u: &mut Unstructured| -> Result<f32> { Ok(u.int_in_range(-1000..=1000i16)? as f32 / 7.0) };
    let mut mesh = Mesh::default();
    for _ in 0..vertices {
        mesh.positions
            .push([coordinate(u)?, coordinate(u)?, coordinate(u)?]);
    }
    for _ in 0..triangles {
        let mut t = [0u32; 3];
        for x in &mut t {
            *x = u.int_in_range(0..=vertices - 1)?;
        }
        mesh.triangles.push(t);
    }
    let corners = 3 * mesh.triangles.len();
    if u.arbitrary()? {
        let normals: Vec<[f32; 3]> = (0..vertices).map(|v| [v as f32, 0.5, -1.0]).collect();
        mesh.attributes
            .push(Attribute::per_vertex(Semantic::Normal, &normals));
    }
    if u.arbitrary()? {
        // Per corner with seams: a few values, each corner picking one.
        let count = u.int_in_range(1..=8u32)?;
        let values: Vec<[f32; 2]> = (0..count).map(|i| [i as f32 / 3.0, 0.25]).collect();
        let mut index = Vec::with_capacity(corners);
        for _ in 0..corners {
            index.push(u.int_in_range(0..=count - 1)?);
        }
        mesh.attributes
            .push(Attribute::per_corner(Semantic::TexCoord(0), &values, index));
    }
    if u.arbitrary()? {
        let colors: Vec<[u8; 4]> = (0..vertices).map(|v| [v as u8, 7, 9, 255]).collect();
        mesh.attributes.push(Attribute::rgba8(&colors));
    }
    if u.arbitrary()? {
        // Parts: a label per triangle.
        let mut parts = Parts::default();
        for _ in 0..mesh.triangles.len() {
            let p = u.int_in_range(0..=2u32)?;
            let part = Part {
                material: Some(format!("m{p}")),
                group: (p == 1).then(|| "g".to_string()),
                object: None,
            };
            let i = parts.intern(part);
            parts.of_triangle.push(i);
        }
        mesh.parts = Some(parts);
    }
    let options = EncodeOptions {
        connectivity: match u.int_in_range(0..=3u8)? {
            0 => Connectivity::Lr,
            1 => Connectivity::Edgebreaker,
            2 => Connectivity::Strips,
            _ => Connectivity::LrCompact,
        },
        periods: vec![u.int_in_range(0..=8u32)?],
        lr: LrOptions {
            tries: u.int_in_range(1..=4)?,
            seed: u.arbitrary()?,
            threads: u.int_in_range(1..=2)?,
        },
        keep_order: u.arbitrary()?,
        position_bits: match u.int_in_range(0..=31u8)? {
            0 => None,
            b => Some(b.min(crate::geometry::MAX_GRID_BITS)),
        },
        level: u.int_in_range(0..=9)?,
        normal_bits: match u.int_in_range(0..=24u8)? {
            0 => None,
            b => Some(b),
        },
        texcoord_bits: match u.int_in_range(0..=30u8)? {
            0 => None,
            b => Some(b),
        },
        ..EncodeOptions::default()
    };
    Ok((mesh, options))
}

/// A triangle as its lexicographically smallest rotation, so that two rotations of one
/// triangle compare equal even when it repeats an entry.
pub fn rotated<T: Ord + Clone>(t: [T; 3]) -> [T; 3] {
    let [a, b, c] = t;
    let first = [a.clone(), b.clone(), c.clone()];
    let second = [b.clone(), c.clone(), a.clone()];
    let third = [c, a, b];
    first.min(second).min(third)
}

/// What a corner carries: its position's bits and, for each attribute (by semantic), the
/// bytes of its value; with the triangle's part labels.
type CornerKey = ([u32; 3], Vec<Vec<u8>>);

fn corner_keys(m: &Mesh, t: usize) -> [CornerKey; 3] {
    let tri = m.triangles[t];
    let mut attributes: Vec<&Attribute> = m.attributes.iter().collect();
    attributes.sort_by(|a, b| a.semantic.cmp(&b.semantic));
    [0, 1, 2].map(|k| {
        let values = attributes
            .iter()
            .map(|a| a.corner_bytes(t, k, tri))
            .collect();
        (m.positions[tri[k] as usize].map(f32::to_bits), values)
    })
}

/// The semantics, bindings and types of the attributes, and the part of each triangle.
fn shape(m: &Mesh) -> Vec<(crate::mesh::Semantic, bool, u8, bool)> {
    let mut s: Vec<_> = m
        .attributes
        .iter()
        .map(|a| {
            (
                a.semantic.clone(),
                a.is_per_corner(),
                a.components,
                a.normalized,
            )
        })
        .collect();
    s.sort_by(|a, b| a.0.cmp(&b.0));
    s
}

/// The part of triangle `t`; a part without labels is no part (a file format with nothing
/// to write for it, OBJ, gives it back as none).
fn part_of(m: &Mesh, t: usize) -> Option<Part> {
    m.parts
        .as_ref()
        .map(|p| p.of(t).clone())
        .filter(|p| *p != Part::default())
}

/// Per-vertex values of the per-vertex attributes of vertex `v` (the only place where an
/// unreferenced vertex keeps anything beyond its position).
fn vertex_key(m: &Mesh, v: usize) -> ([u32; 3], Vec<Vec<u8>>) {
    let mut attributes: Vec<&Attribute> =
        m.attributes.iter().filter(|a| !a.is_per_corner()).collect();
    attributes.sort_by(|a, b| a.semantic.cmp(&b.semantic));
    let values = attributes
        .iter()
        .map(|a| {
            let mut out = Vec::new();
            a.value_bytes(v, &mut out);
            out
        })
        .collect();
    (m.positions[v].map(f32::to_bits), values)
}

/// Same triangles, in order, up to rotation; same vertices, attributes at every corner and
/// parts.
pub fn assert_same_in_order(got: &Mesh, want: &Mesh) {
    assert_eq!(got.positions, want.positions);
    assert_eq!(shape(got), shape(want), "attributes");
    assert_eq!(got.triangles.len(), want.triangles.len());
    for (v, _) in want.positions.iter().enumerate() {
        assert_eq!(vertex_key(got, v), vertex_key(want, v), "vertex {v}");
    }
    for (k, (g, w)) in got.triangles.iter().zip(&want.triangles).enumerate() {
        assert_eq!(rotated(*g), rotated(*w), "triangle {k}");
        assert_eq!(
            rotated(corner_keys(got, k)),
            rotated(corner_keys(want, k)),
            "corners of triangle {k}"
        );
        assert_eq!(part_of(got, k), part_of(want, k), "part of triangle {k}");
    }
    let libraries = |m: &Mesh| {
        m.parts
            .as_ref()
            .map(|p| p.material_libraries.clone())
            .filter(|l| !l.is_empty())
    };
    assert_eq!(libraries(got), libraries(want));
}

/// Same triangles on the same positions, in any order: compares the sorted lists of triangles
/// written as (position, attribute values) per corner, with their parts; and the multiset
/// of vertices with their per-vertex values.
pub fn assert_same_up_to_order(got: &Mesh, want: &Mesh) {
    assert_eq!(got.positions.len(), want.positions.len(), "vertex count");
    assert_eq!(shape(got), shape(want), "attributes");
    let triangles = |m: &Mesh| {
        let mut t: Vec<_> = (0..m.triangles.len())
            .map(|t| (rotated(corner_keys(m, t)), part_of(m, t)))
            .collect();
        t.sort();
        t
    };
    assert_eq!(triangles(got), triangles(want));
    let vertices = |m: &Mesh| {
        let mut v: Vec<_> = (0..m.positions.len()).map(|v| vertex_key(m, v)).collect();
        v.sort();
        v
    };
    assert_eq!(
        vertices(got),
        vertices(want),
        "vertex multiset (unreferenced ones too)"
    );
}

/// `mesh` through the container in every connectivity kind, with and without the input
/// order: decoded, it has the same triangles with the same values at every corner (in order
/// when the order was kept). `more` then sees each kind's options, bytes and decoded mesh.
/// `what` names the mesh in failures.
pub fn round_trip_every_kind(
    mesh: &Mesh,
    what: &str,
    more: impl FnMut(&EncodeOptions, &[u8], &Mesh),
) {
    round_trip_every_kind_with(mesh, &EncodeOptions::default(), what, more);
}

/// [`round_trip_every_kind`] with `base`'s options but the kind and the order: the decoded
/// mesh is `mesh` as [`crate::write::dequantized`] says (quantized attribute values as they
/// decode).
pub fn round_trip_every_kind_with(
    mesh: &Mesh,
    base: &EncodeOptions,
    what: &str,
    mut more: impl FnMut(&EncodeOptions, &[u8], &Mesh),
) {
    for connectivity in [
        Connectivity::Lr,
        Connectivity::LrCompact,
        Connectivity::Edgebreaker,
        Connectivity::Strips,
    ] {
        for keep_order in [false, true] {
            let options = EncodeOptions {
                connectivity,
                keep_order,
                ..base.clone()
            };
            let want = crate::write::dequantized(mesh, &options)
                .unwrap_or_else(|e| panic!("{what} {connectivity:?}: {e}"));
            let bytes =
                encode(mesh, &options).unwrap_or_else(|e| panic!("{what} {connectivity:?}: {e}"));
            let back = open(&bytes, &Limits::default())
                .unwrap_or_else(|e| panic!("{what} {connectivity:?}: {e}"))
                .to_mesh();
            if keep_order {
                assert_same_in_order(&back, &want);
            } else {
                assert_same_up_to_order(&back, &want);
            }
            more(&options, &bytes, &back);
        }
    }
}

/// The round-trip target: a soup and options from `data`, encoded and decoded; panics on
/// any difference.
pub fn round_trip(data: &[u8]) {
    let Ok((mut mesh, options)) = soup(&mut Unstructured::new(data)) else {
        return;
    };
    let bytes = encode(&mesh, &options).expect("a valid mesh encodes");
    // The order large meshes are encoded in (below its size here) loses nothing, and a mesh
    // in that order keeps it.
    let ordered = Order::of(&mesh).expect("a valid mesh has an order");
    let moved = ordered.apply(&mesh).expect("of the same counts");
    assert_same_up_to_order(&moved, &mesh);
    assert!(crate::mesh::is_in_order(&moved), "an ordered mesh says so");
    if crate::mesh::is_in_order(&mesh) {
        assert!(
            moved == mesh,
            "a mesh that says it is in order is left as it is"
        );
    }
    let again = Order::of(&moved).and_then(|o| o.apply(&moved));
    assert!(
        again.expect("valid") == moved,
        "the order of an ordered mesh is itself"
    );
    // Quantized attribute values come back as `dequantized` says (their error bounds:
    // `tests/attributes.rs`).
    mesh = crate::write::dequantized(&mesh, &options).expect("bits in range");
    let view = open(&bytes, &Limits::default()).expect("what we write opens");
    let back = view.to_mesh();
    assert_eq!(back.positions.len(), mesh.positions.len());
    if let Some(bits) = options.position_bits {
        // Compare positions on the grid (within half a step, plus the f32 rounding of the
        // decoded value), then use the decoded ones below.
        let step = crate::geometry::Grid::of(mesh.positions.iter().copied(), bits).step();
        if options.keep_order {
            for (p, q) in back.positions.iter().zip(&mesh.positions) {
                assert!(
                    (0..3).all(|i| {
                        let error = (p[i] as f64 - q[i] as f64).abs();
                        error <= step * 0.5 * (1.0 + 1e-9) + p[i].abs() as f64 * 1.2e-7
                    }),
                    "{bits} bits: {p:?} {q:?}, step {step:?}"
                );
            }
            mesh.positions = back.positions.clone();
        } else {
            // Without the order, positions only identify vertices when not quantized.
            assert_eq!(back.triangles.len(), mesh.triangles.len());
            return;
        }
    }
    if options.keep_order {
        assert_same_in_order(&back, &mesh);
    } else {
        assert_same_up_to_order(&back, &mesh);
    }
}
