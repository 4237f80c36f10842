use super::*;
use crate::format::{Flags, Tag};
use crate::read::Section;
use crate::rng::Rng;

/// Vertex counts around block boundaries of every size the writer tries.
const COUNTS: [usize; 16] = [
    0, 1, 2, 3, 15, 16, 17, 31, 32, 33, 63, 64, 65, 127, 129, 1000,
];

fn parse(bytes: &[u8], m: usize) -> Result<BlockedView<'_>> {
    let section = Section {
        tag: Tag::GEOM,
        flags: Flags::REQUIRED,
        offset: 0,
        bytes,
    };
    BlockedView::parse(&Fields::new(section), m as u64, true)
}

/// Random points, one in eight far from the others (so that some residuals are wide).
fn random_points(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    (0..n)
        .map(|i| {
            let scale = if i % 8 == 3 { 1000.0 } else { 1.0 };
            [0, 1, 2].map(|_| (rng.unit() - 0.5) * scale)
        })
        .collect()
}

/// A walk of small steps, as vertices along a ring.
fn walk(rng: &mut Rng, n: usize) -> Vec<[f32; 3]> {
    let mut p = [0.0f32; 3];
    (0..n)
        .map(|_| {
            for x in &mut p {
                *x += (rng.unit() - 0.5) * 0.01;
            }
            p
        })
        .collect()
}

#[track_caller]
fn assert_round_trip(points: &[[f32; 3]], grid: Option<Grid>) -> usize {
    let bytes = encode(points, grid);
    let view = parse(&bytes, points.len()).unwrap_or_else(|e| panic!("{grid:?}: {e}"));
    assert_eq!(view.grid(), grid);
    for (i, p) in points.iter().enumerate() {
        let want = match grid {
            Some(g) => g.dequantize(g.quantize(*p)),
            None => *p,
        };
        assert_eq!(
            view.position(i).map(f32::to_bits),
            want.map(f32::to_bits),
            "vertex {i} of {}, {grid:?}",
            points.len()
        );
    }
    bytes.len()
}

#[test]
fn round_trip_on_grids_of_every_width() {
    let mut rng = Rng::new(7);
    for n in COUNTS {
        for points in [random_points(&mut rng, n), walk(&mut rng, n)] {
            for bits in [1, 2, 11, 16, 29, 30] {
                assert_round_trip(&points, Some(Grid::of(points.iter().copied(), bits)));
            }
        }
    }
}

#[test]
fn round_trip_of_exact_floats() {
    let mut rng = Rng::new(8);
    let special = [
        0.0,
        -0.0,
        1e-45,
        -1e-45,
        f32::MIN_POSITIVE,
        f32::MAX,
        f32::MIN,
        1.0,
        -1.0,
    ];
    for n in COUNTS {
        for mut points in [random_points(&mut rng, n), walk(&mut rng, n)] {
            for (i, p) in points.iter_mut().enumerate().step_by(5) {
                p[i % 3] = special[i % special.len()];
            }
            assert_round_trip(&points, None);
        }
    }
}

/// Every block size a reader accepts, not only those the writer tries.
#[test]
fn round_trip_with_every_block_size() {
    let mut rng = Rng::new(9);
    let points = walk(&mut rng, 300);
    let grid = Grid::of(points.iter().copied(), 14);
    let values: Vec<[i64; 3]> = points
        .iter()
        .map(|&p| grid.quantize(p).map(i64::from))
        .collect();
    for levels in 1..=MAX_LEVELS {
        let bytes = writer::encode_with(&values, Some(grid), levels);
        let view = parse(&bytes, points.len()).unwrap();
        for (i, p) in points.iter().enumerate() {
            assert_eq!(
                view.position(i),
                grid.dequantize(grid.quantize(*p)),
                "{levels}: {i}"
            );
        }
    }
}

#[test]
fn empty_and_single_vertex_sections() {
    let grid = Grid::of([], 12);
    let empty = encode(&[], Some(grid));
    assert_eq!(empty.len(), 8 + 20 + 8);
    parse(&empty, 0).unwrap();
    assert_eq!(encode(&[], None).len(), 16);
    // One vertex: its anchor and the end record, no residual.
    let one = [[1.0, 2.0, 3.0]];
    assert_round_trip(&one, None);
    assert_round_trip(&one, Some(Grid::of(one, 16)));
    // The count must match the section.
    assert!(parse(&empty, 1).is_err());
    let bytes = encode(&one, None);
    assert!(parse(&bytes, 0).is_err());
    assert!(parse(&bytes, 17).is_err());
}

/// Neighbouring vertices cost their differences, not the grid's bits: a random walk whose
/// steps are 1/70 of its extent (about 10 bits of 16) takes under 0.85 of raw.
#[test]
fn a_walk_is_smaller_than_raw() {
    let mut rng = Rng::new(10);
    let points = walk(&mut rng, 5000);
    let bytes = assert_round_trip(&points, Some(Grid::of(points.iter().copied(), 16)));
    assert!(bytes * 100 < 6 * points.len() * 85, "{bytes} bytes");
    let exact = assert_round_trip(&points, None);
    assert!(exact * 100 < 12 * points.len() * 85, "{exact} bytes");
}

#[test]
fn fields_read_past_the_end_as_zero() {
    let bytes = [0xAB, 0xCD, 0xEF];
    assert_eq!(field(&bytes, 0, 24), 0xEFCDAB);
    assert_eq!(field(&bytes, 4, 8), 0xDA);
    assert_eq!(field(&bytes, 20, 12), 0xE);
    assert_eq!(field(&bytes, 1 << 40, 8), 0);
    assert_eq!(field(&[0xFF; 16], 7, 56), (1 << 56) - 1);
    for z in 0..1000u64 {
        assert_eq!(writer::zigzag(unzigzag(z)), z);
    }
}

/// No i below the vertex count panics or leaves the range, whatever the residuals (the
/// parse has checked them): the fuzz targets reach the rest.
#[test]
fn damaged_sections_are_refused_or_decode_in_range() {
    let mut rng = Rng::new(11);
    let points = walk(&mut rng, 100);
    for grid in [Some(Grid::of(points.iter().copied(), 10)), None] {
        let bytes = encode(&points, grid);
        let mut accepted = 0;
        for at in 0..bytes.len() {
            for x in [0x01u8, 0x10, 0x80] {
                let mut bad = bytes.clone();
                bad[at] ^= x;
                if let Ok(view) = parse(&bad, points.len()) {
                    accepted += 1;
                    for i in 0..points.len() {
                        assert!(view.position(i).iter().all(|x| x.is_finite()));
                    }
                }
            }
        }
        assert!(accepted > 0, "no change of a residual is ever valid?");
    }
}
