//! The `round_trip` fuzz target: a triangle soup with attributes, made from the fuzzer's bytes, encoded with arbitrary
//! options (connectivity, tries, seed, input order kept or not, positions quantized or not)
//! and decoded: the same triangles (oriented, up to rotation) on the same positions with the
//! same attributes; in the input order when it was kept, as the same multiset otherwise;
//! quantized positions within one step of the grid. Encoding never fails on a valid mesh.

use arbitrary::{Result, Unstructured};

use crate::lr::LrOptions;
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
    if u.arbitrary()? {
        mesh.normals = Some((0..vertices).map(|v| [v as f32, 0.5, -1.0]).collect());
    }
    if u.arbitrary()? {
        mesh.texcoords = Some((0..vertices).map(|v| [v as f32 / 3.0, 0.25]).collect());
    }
    if u.arbitrary()? {
        mesh.colors = Some((0..vertices).map(|v| [v as u8, 7, 9, 255]).collect());
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
        },
        keep_order: u.arbitrary()?,
        quantize16: u.arbitrary()?,
        ..EncodeOptions::default()
    };
    Ok((mesh, options))
}

/// A triangle as its lexicographically smallest rotation, so that two rotations of one
/// triangle compare equal even when it repeats an entry.
pub fn rotated<T: Ord + Copy>(t: [T; 3]) -> [T; 3] {
    [t, [t[1], t[2], t[0]], [t[2], t[0], t[1]]]
        .into_iter()
        .min()
        .unwrap_or(t)
}

/// Same triangles, in order, up to rotation; same vertices and attributes.
pub fn assert_same_in_order(got: &Mesh, want: &Mesh) {
    assert_eq!(got.positions, want.positions);
    assert_eq!(got.normals, want.normals);
    assert_eq!(got.texcoords, want.texcoords);
    assert_eq!(got.colors, want.colors);
    assert_eq!(got.triangles.len(), want.triangles.len());
    for (k, (g, w)) in got.triangles.iter().zip(&want.triangles).enumerate() {
        assert_eq!(rotated(*g), rotated(*w), "triangle {k}");
    }
}

/// Same triangles on the same positions, in any order: compares the sorted lists of triangles
/// written as (position, attributes) triples.
pub fn assert_same_up_to_order(got: &Mesh, want: &Mesh) {
    assert_eq!(got.positions.len(), want.positions.len(), "vertex count");
    let key = |m: &Mesh, v: u32| {
        let v = v as usize;
        (
            m.positions[v].map(f32::to_bits),
            m.normals.as_ref().map(|n| n[v].map(f32::to_bits)),
            m.texcoords.as_ref().map(|t| t[v].map(f32::to_bits)),
            m.colors.as_ref().map(|c| c[v]),
        )
    };
    let triangles = |m: &Mesh| {
        let mut t: Vec<_> = m
            .triangles
            .iter()
            .map(|t| rotated(t.map(|v| key(m, v))))
            .collect();
        t.sort();
        t
    };
    assert_eq!(triangles(got), triangles(want));
    let vertices = |m: &Mesh| {
        let mut v: Vec<_> = (0..m.positions.len() as u32).map(|v| key(m, v)).collect();
        v.sort();
        v
    };
    assert_eq!(
        vertices(got),
        vertices(want),
        "vertex multiset (unreferenced ones too)"
    );
}

/// The round-trip target: a soup and options from `data`, encoded and decoded; panics on
/// any difference.
pub fn round_trip(data: &[u8]) {
    let Ok((mut mesh, options)) = soup(&mut Unstructured::new(data)) else {
        return;
    };
    let bytes = encode(&mesh, &options).expect("a valid mesh encodes");
    let view = open(&bytes, &Limits::default()).expect("what we write opens");
    let back = view.to_mesh();
    assert_eq!(back.positions.len(), mesh.positions.len());
    if options.quantize16 {
        // Compare positions on the grid, then use the decoded ones below.
        let extent = |i: usize| {
            let (lo, hi) = mesh
                .positions
                .iter()
                .fold((f32::MAX, f32::MIN), |(lo, hi), p| {
                    (lo.min(p[i]), hi.max(p[i]))
                });
            hi - lo
        };
        let step = [0, 1, 2].map(|i| extent(i) / 65535.0 * 1.01 + 1e-4);
        if options.keep_order {
            for (p, q) in back.positions.iter().zip(&mesh.positions) {
                assert!(
                    (0..3).all(|i| (p[i] - q[i]).abs() <= step[i]),
                    "{p:?} {q:?}"
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
