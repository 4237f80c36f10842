//! Checks shared by the integration tests.
#![allow(dead_code)]

pub mod forge;
pub mod io_helpers;

use lrmesh::ops::{self, CornerOps};
use lrmesh::{Corner, CornerTable, Mesh, TopologyReport};
use std::collections::BTreeSet;
use std::path::PathBuf;

/// The repository's corpus of meshes.
pub fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/meshes")
}

/// The team's shared meshes, when this checkout sits beside them. Their absence is said
/// loudly on stderr, and fails the test under CI (`CI` set), where `shared/` is always
/// beside the clone: a test over them must never pass by checking nothing there.
pub fn shared_dir() -> Option<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../shared/meshes");
    if dir.join("MANIFEST.tsv").exists() {
        return Some(dir);
    }
    assert!(
        std::env::var_os("CI").is_none(),
        "{}: the shared meshes are missing under CI",
        dir.display()
    );
    eprintln!(
        "WARNING: {} not found: the shared-mesh part of this test is SKIPPED",
        dir.display()
    );
    None
}

/// Builds the corner table of `mesh` and checks every invariant the crate promises:
/// `c.o.o == c`; `c.o` faces the reversed edge of `c` from another triangle; swinging from
/// `v.c` visits exactly the corners of `v` (one fan per vertex); copies map to input vertices;
/// the map back gives the input triangles exactly; cut edges are counted as the report counts
/// them.
pub fn check_corner_table(mesh: &Mesh) -> CornerTable {
    let table = CornerTable::from_mesh(mesh).expect("corner table");
    assert_eq!(
        table.input_triangles(),
        mesh.triangles,
        "map back to the input"
    );

    let mut corners_of = vec![BTreeSet::new(); table.vertex_id_bound() as usize];
    for c in table.corners() {
        corners_of[table.vertex(c).idx()].insert(c);
        assert_eq!(table.next(table.prev(c)), c);
        assert_eq!(table.triangle(table.next(c)), table.triangle(c));
        if let Some(o) = table.opposite(c) {
            assert_eq!(table.opposite(o), Some(c), "c.o.o == c at {c:?}");
            assert_ne!(table.triangle(o), table.triangle(c));
            assert_eq!(table.vertex(table.next(o)), table.vertex(table.prev(c)));
            assert_eq!(table.vertex(table.prev(o)), table.vertex(table.next(c)));
        }
        if let Some(s) = table.swing(c) {
            assert_eq!(table.vertex(s), table.vertex(c));
            assert_eq!(table.unswing(s), Some(c));
        }
    }
    for v in table.vertices() {
        let star: Vec<Corner> = ops::star(&table, v).collect();
        let unique: BTreeSet<Corner> = star.iter().copied().collect();
        assert_eq!(unique.len(), star.len(), "star of {v:?} repeats a corner");
        assert_eq!(unique, corners_of[v.idx()], "star of {v:?} is not its fan");
        if let Some(c) = table.vertex_corner(v) {
            assert_eq!(table.vertex(c), v);
        }
        let original = table.original_vertex(v);
        assert!(original.0 < table.input_vertex_count());
        if v.0 < table.input_vertex_count() {
            assert_eq!(original, v);
        } else {
            assert!(!corners_of[v.idx()].is_empty(), "a copy without corners");
        }
    }
    let report = TopologyReport::of(mesh);
    let conversion = table.conversion();
    assert_eq!(conversion.kept_aside as u64, report.degenerate_triangles);
    if report.degenerate_triangles == 0 {
        assert_eq!(
            conversion.cut_nonmanifold_edges as u64,
            report.nonmanifold_edges
        );
        assert_eq!(
            conversion.cut_inconsistent_edges as u64,
            report.inconsistent_edges
        );
    }
    if report.vertex_manifold && report.oriented && report.degenerate_triangles == 0 {
        assert_eq!(conversion.vertex_copies, 0);
    }
    table
}

/// Checks a representation against the corner table of the same mesh, corner by corner.
///
/// Corners are matched by `(input triangle, input vertex)`, which `key` gives for the
/// representation's corners (a non-degenerate triangle has three distinct input vertices).
/// Checks: the canonical triangles are exactly the table's, with the same orientation; `c.o`
/// matches the table's (and so `c.o.o == c` and the shared edge is reversed); swinging around
/// each vertex visits exactly the table's fan; valence and vertex normals agree.
pub fn check_against_table<M: CornerOps>(
    rep: &M,
    key: impl Fn(Corner) -> (u32, u32),
    vertex_position: impl Fn(lrmesh::Vertex) -> [f32; 3],
    table: &CornerTable,
    mesh: &Mesh,
) {
    use std::collections::HashMap;
    let table_key = |c: Corner| {
        (
            table.input_triangle(table.triangle(c)),
            table.original_vertex(table.vertex(c)).0,
        )
    };
    let table_corner: HashMap<(u32, u32), Corner> =
        table.corners().map(|c| (table_key(c), c)).collect();
    let mut seen = std::collections::HashSet::new();
    for t in rep.triangles() {
        let corners = rep.triangle_corners(t);
        let keys = corners.map(&key);
        assert!(
            seen.insert(keys[0].0),
            "triangle {t:?} enumerated twice (input {})",
            keys[0].0
        );
        // Same input triangle, same orientation: the table's next of our corner is our next.
        for (i, &c) in corners.iter().enumerate() {
            let tc = *table_corner
                .get(&keys[i])
                .unwrap_or_else(|| panic!("corner {c:?} {:?} is not a table corner", keys[i]));
            assert_eq!(
                table_key(table.next(tc)),
                keys[(i + 1) % 3],
                "orientation of {t:?}"
            );
            let ours = rep.opposite(c).map(&key);
            let theirs = table.opposite(tc).map(table_key);
            assert_eq!(ours, theirs, "c.o of corner {c:?} in triangle {t:?}");
            if let Some(o) = rep.opposite(c) {
                assert_eq!(rep.opposite(o), Some(c), "c.o.o at {c:?}");
            }
        }
    }
    assert_eq!(
        seen.len(),
        table.triangle_id_bound() as usize,
        "triangle count"
    );
    let rep_positions: Vec<[f32; 3]> = (0..rep.vertex_id_bound())
        .map(|v| vertex_position(lrmesh::Vertex(v)))
        .collect();
    let table_positions = table.extend_to_copies(&mesh.positions);
    let mut vertices = 0;
    for v in rep.vertices() {
        vertices += 1;
        let Some(c) = rep.vertex_corner(v) else {
            assert_eq!(rep.any_corner(v), None, "a corner of {v:?} without v.c");
            continue;
        };
        let tc = table_corner[&key(c)];
        let ours: BTreeSet<(u32, u32)> = ops::star(rep, v).map(&key).collect();
        let theirs: BTreeSet<(u32, u32)> =
            ops::star(table, table.vertex(tc)).map(table_key).collect();
        assert_eq!(ours, theirs, "star of {v:?}");
        // Valence and normals walk from any corner of `v`: it must be one of its star.
        let any = rep.any_corner(v).map(&key);
        assert!(
            any.is_some_and(|k| ours.contains(&k)),
            "any_corner of {v:?} is not in its star"
        );
        assert_eq!(
            ops::valence(rep, v),
            ops::valence(table, table.vertex(tc)),
            "valence of {v:?}"
        );
        // Normals agree wherever they are well defined: where the triangles' cross products
        // do not nearly cancel (as they do in a two-triangle pocket).
        let ours = ops::vertex_normal(rep, &rep_positions, v);
        let theirs = ops::vertex_normal(table, &table_positions, table.vertex(tc));
        let (sum, total) = cross_sums(table, &table_positions, table.vertex(tc));
        if sum > 1e-3 * total {
            let gap = (0..3)
                .map(|i| (ours[i] - theirs[i]).abs())
                .fold(0.0, f32::max);
            assert!(gap < 1e-4, "normal of {v:?}: {ours:?} != {theirs:?}");
        }
    }
    assert_eq!(vertices, table.vertex_id_bound(), "vertex count");
}

/// The length of the sum of the cross products around `v`, and the sum of their lengths.
fn cross_sums(table: &CornerTable, positions: &[[f32; 3]], v: lrmesh::Vertex) -> (f64, f64) {
    let p = |c: Corner| positions[table.vertex(c).idx()].map(f64::from);
    let (mut sum, mut total) = ([0.0f64; 3], 0.0);
    for c in ops::star(table, v) {
        let (o, a, b) = (p(c), p(table.next(c)), p(table.prev(c)));
        let (a, b) = (
            [0, 1, 2].map(|i| a[i] - o[i]),
            [0, 1, 2].map(|i| b[i] - o[i]),
        );
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        total += (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        sum = [0, 1, 2].map(|i| sum[i] + n[i]);
    }
    (
        (sum[0] * sum[0] + sum[1] * sum[1] + sum[2] * sum[2]).sqrt(),
        total,
    )
}

/// A torus with flipped edges, `handles` handles, a second torus, `holes` holes and `defects`
/// defects: the generated meshes the LR proptests check.
pub fn torus_with_everything(
    around: u32,
    along: u32,
    holes: usize,
    defects: usize,
    handles: usize,
    seed: u64,
) -> Mesh {
    use lrmesh::generate::{self, Rng};
    let mut rng = Rng::new(seed);
    let mut mesh = generate::torus(around, along);
    generate::flip_edges(&mut mesh, 20, &mut rng);
    generate::add_random_handles(&mut mesh, handles, &mut rng);
    generate::append(&mut mesh, &generate::torus(3, 5));
    generate::punch_holes(&mut mesh, holes, &mut rng);
    generate::add_defects(&mut mesh, defects, &mut rng);
    mesh
}

/// Asserts that `got` has the triangles of `want`, in the same order, each the same oriented
/// triple, possibly rotated.
pub fn assert_same_up_to_rotation(got: &[[u32; 3]], want: &[[u32; 3]], what: &str) {
    assert_eq!(got.len(), want.len(), "{what}: triangle count");
    for (k, (got, want)) in got.iter().zip(want).enumerate() {
        let rotations = [
            *want,
            [want[1], want[2], want[0]],
            [want[2], want[0], want[1]],
        ];
        assert!(
            rotations.contains(got),
            "{what}: triangle {k}: {got:?} != {want:?}"
        );
    }
}

/// The sections of a valid container as `(tag, flags, payload)`, in file order, ready to
/// alter and [`assemble`](lrmesh::write::assemble) again.
pub fn sections_of(bytes: &[u8]) -> Vec<lrmesh::write::SectionBytes> {
    lrmesh::read::Sections::parse(bytes, &lrmesh::read::Limits::default())
        .unwrap()
        .to_section_bytes()
}

/// Forges section `tag` of the container `bytes`: every little-endian field of `width` bytes
/// (2 or 4) in turn takes each of `values(original)` that differs from it, and the container
/// is reassembled with its checksums recomputed, so that the section's rules themselves must
/// catch the change. A forged container must fail to open with an error naming `tag` or
/// `MESH`, or open and pass `consistent`. Returns how many were rejected and accepted.
pub fn forge_fields(
    bytes: &[u8],
    tag: lrmesh::format::Tag,
    width: usize,
    values: impl Fn(u32) -> Vec<u32>,
    mut consistent: impl FnMut(&lrmesh::read::Container),
) -> (usize, usize) {
    use lrmesh::read::{open, open_verified, Limits};
    let sections = sections_of(bytes);
    let index = sections.iter().position(|s| s.0 == tag).unwrap();
    let (mut rejected, mut accepted) = (0, 0);
    for at in (0..sections[index].2.len() / width).map(|i| width * i) {
        let field = &sections[index].2[at..at + width];
        let original = field.iter().rev().fold(0u32, |x, &b| x << 8 | b as u32);
        for value in values(original) {
            if value == original {
                continue;
            }
            let mut forged = sections.clone();
            forged[index].2[at..at + width].copy_from_slice(&value.to_le_bytes()[..width]);
            let forged = lrmesh::write::assemble(&forged);
            // The well-formed check: every answer in range, or the verifier's error.
            let quick = open(&forged, &Limits::default());
            if let Ok(view) = &quick {
                lrmesh::fuzz_checks::walk_in_range(view);
            }
            match open_verified(&forged, &Limits::default()) {
                Err(e) => {
                    if let Err(q) = &quick {
                        assert_eq!(q.to_string(), e.to_string());
                    }
                    let message = e.to_string();
                    assert!(
                        message.contains(&tag.name()) || message.contains("MESH"),
                        "byte {at} = {value:#x}: {message}"
                    );
                    rejected += 1;
                }
                Ok(view) => {
                    accepted += 1;
                    consistent(&view);
                }
            }
        }
    }
    (rejected, accepted)
}

/// Asserts that every coordinate of `got` is within half a step of the `bits`-bit grid over
/// `want`'s positions (FORMAT.md §3.3.1), plus the f32 rounding of the decoded value; returns
/// the largest error, in steps.
pub fn assert_within_half_a_step(got: &[[f32; 3]], want: &[[f32; 3]], bits: u8, what: &str) -> f64 {
    let step = lrmesh::geometry::Grid::of(want.iter().copied(), bits).step();
    let mut worst = 0.0f64;
    for (p, q) in got.iter().zip(want) {
        for k in 0..3 {
            let error = (p[k] as f64 - q[k] as f64).abs();
            let rounding = p[k].abs() as f64 * f32::EPSILON as f64;
            assert!(
                error <= step / 2.0 + rounding,
                "{what}: {p:?} for {q:?}, step {step}"
            );
            worst = worst.max(error / step);
        }
    }
    worst
}
