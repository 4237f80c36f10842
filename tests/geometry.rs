//! Position coding (FORMAT.md §3.3, GEOMETRY.md): lossless files give every f32 back bit for
//! bit, quantized ones every coordinate within half a grid step, in every kind and at every
//! level, on generated meshes with every defect and on real ones.

mod common;

use common::{assert_within_half_a_step, corpus_dir, torus_with_everything};
use lrmesh::generate::{self, Rng};
use lrmesh::read::{open, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::Mesh;
use proptest::prelude::*;

/// Encodes with the input order kept and returns the decoded positions.
fn round_trip(
    mesh: &Mesh,
    connectivity: Connectivity,
    bits: Option<u8>,
    level: u8,
) -> Vec<[f32; 3]> {
    let options = EncodeOptions {
        connectivity,
        keep_order: true,
        position_bits: bits,
        level,
        ..EncodeOptions::default()
    };
    let bytes = encode(mesh, &options).unwrap();
    let file = open(&bytes, &Limits::default()).unwrap();
    assert_eq!(file.is_quantized(), bits.is_some());
    file.to_mesh().positions
}

fn assert_exact(got: &[[f32; 3]], want: &[[f32; 3]], what: &str) {
    let bits =
        |p: &[[f32; 3]]| -> Vec<[u32; 3]> { p.iter().map(|p| p.map(f32::to_bits)).collect() };
    assert_eq!(bits(got), bits(want), "{what}");
}

/// Positions that stress the float coder: signed zeros, subnormals, huge and tiny values,
/// values on both sides of exponent boundaries.
fn hostile_positions(n: usize, rng: &mut Rng) -> Vec<[f32; 3]> {
    let specials = [
        0.0f32,
        -0.0,
        f32::MIN_POSITIVE,
        -f32::MIN_POSITIVE,
        1e-45,
        -1e-45,
        f32::MAX,
        -f32::MAX,
        1.0,
        1.0 - f32::EPSILON / 2.0,
        -2.0,
        3.4e38,
        1e-30,
    ];
    (0..n)
        .map(|_| {
            [0, 1, 2].map(|_| match rng.below(4) {
                0 => specials[rng.below(specials.len() as u32) as usize],
                1 => f32::from_bits(rng.next_u64() as u32 & 0x7F7F_FFFF),
                _ => (rng.below(2000) as f32 - 1000.0) / 7.0,
            })
        })
        .collect()
}

#[test]
fn lossless_positions_come_back_bit_for_bit_even_hostile_ones() {
    let mut rng = Rng::new(11);
    for seed in 0..6 {
        let mut mesh = torus_with_everything(7, 5, 2, 4, 1, seed);
        mesh.positions = hostile_positions(mesh.positions.len(), &mut rng);
        for kind in Connectivity::ALL {
            for level in [0, 6, 9] {
                let got = round_trip(&mesh, kind, None, level);
                assert_exact(&got, &mesh.positions, &format!("{kind:?} level {level}"));
            }
        }
    }
}

#[test]
fn real_meshes_round_trip_in_every_kind() {
    for name in [
        "fandisk.off",
        "knot1.off",
        "elephant-with-holes.off",
        "b9_mesh.off",
        "polygon_mesh.off",
    ] {
        let mesh = lrmesh::load(corpus_dir().join(name)).unwrap();
        for kind in Connectivity::ALL {
            let got = round_trip(&mesh, kind, None, 6);
            assert_exact(&got, &mesh.positions, name);
            for (bits, level) in [(11, 6), (14, 6), (16, 6), (11, 1), (16, 2)] {
                let got = round_trip(&mesh, kind, Some(bits), level);
                assert_within_half_a_step(
                    &got,
                    &mesh.positions,
                    bits,
                    &format!("{name} {kind:?} {bits} bits, level {level}"),
                );
            }
        }
    }
}

/// The coded Edgebreaker positions are smaller than the raw ones: exact ones than 12 bytes
/// a vertex, quantized ones than the bits they hold.
#[test]
fn predicted_positions_are_smaller_than_raw() {
    let mesh = lrmesh::load(corpus_dir().join("fandisk.off")).unwrap();
    let size = |bits: Option<u8>, level: u8| {
        let bytes = encode(
            &mesh,
            &EncodeOptions {
                connectivity: Connectivity::Edgebreaker,
                position_bits: bits,
                level,
                ..EncodeOptions::default()
            },
        )
        .unwrap();
        open(&bytes, &Limits::default())
            .unwrap()
            .summary()
            .positions
    };
    let v = mesh.positions.len() as f64;
    let exact = size(None, 6);
    assert_eq!(exact.encoding, "predicted-f32");
    assert!((exact.bytes as f64) < 0.7 * 12.0 * v, "{exact:?}");
    assert_eq!(size(None, 0).encoding, "f32");
    for bits in [8u8, 12, 16] {
        let coded = size(Some(bits), 6);
        assert_eq!(coded.encoding, "predicted-grid");
        assert!(coded.bits_per_vertex < 3.0 * bits as f64 * 0.8, "{coded:?}");
        // Encoding 6, fast to decode: on this CAD mesh about 30% above encoding 2, whose
        // traversal and choices suit flat regions (a few percent on scans).
        let fast = size(Some(bits), 1);
        assert_eq!(fast.encoding, "anchored-grid");
        assert!(fast.bits_per_vertex < 3.0 * bits as f64 * 0.8, "{fast:?}");
        assert!(
            fast.bytes as f64 <= 1.4 * coded.bytes as f64,
            "{fast:?} {coded:?}"
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn generated_meshes_round_trip(around in 3u32..9, along in 3u32..9, holes in 0usize..6,
                                   defects in 0usize..8, handles in 0usize..3, seed in any::<u64>(),
                                   bits in prop::option::of(1u8..=30), level in 0u8..=9,
                                   kind in 0usize..4, jitter in 0u32..3) {
        let mut mesh = torus_with_everything(around, along, holes, defects, handles, seed);
        generate::jitter(&mut mesh, jitter as f32 * 0.05, &mut Rng::new(seed));
        let got = round_trip(&mesh, Connectivity::ALL[kind], bits, level);
        match bits {
            None => assert_exact(&got, &mesh.positions, "exact"),
            Some(b) => {
                assert_within_half_a_step(&got, &mesh.positions, b, "grid");
            }
        }
    }

    #[test]
    fn soups_round_trip(vertices in 1u32..30, triangles in 0u32..60, seed in any::<u64>(),
                        bits in prop::option::of(1u8..=30), kind in 0usize..4,
                        level in prop::sample::select(vec![1u8, 6])) {
        let mesh = generate::soup(vertices, triangles, &mut Rng::new(seed));
        let got = round_trip(&mesh, Connectivity::ALL[kind], bits, level);
        match bits {
            None => assert_exact(&got, &mesh.positions, "exact"),
            Some(b) => {
                assert_within_half_a_step(&got, &mesh.positions, b, "grid");
            }
        }
    }
}
