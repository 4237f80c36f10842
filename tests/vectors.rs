//! The test vectors of `spec/vectors/`: for each source mesh, the exact container bytes and
//! the vertex and opposite of every corner. The crate must reproduce the bytes when encoding
//! the source, and read the listed answers from the bytes.
//!
//! `LRMESH_REGENERATE_VECTORS=1 cargo test --test vectors` rewrites the files after a
//! deliberate format change.

use std::fmt::Write as _;
use std::path::PathBuf;

mod common;
use common::assert_same_up_to_rotation;

use lrmesh::format::Metadata;
use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::lr::LrLayout;
use lrmesh::read::{open, Connectivity as View, Limits};
use lrmesh::write::{encode, Connectivity, EncodeOptions};
use lrmesh::CornerOps;

const VECTORS: [&str; 6] = [
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
];

fn dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("spec/vectors")
}

/// The options the vectors are encoded with: input order kept, fixed metadata.
fn options(connectivity: Connectivity) -> EncodeOptions {
    EncodeOptions {
        connectivity,
        keep_order: true,
        metadata: Metadata {
            generator: "lrmesh test vectors".into(),
            ..Metadata::default()
        },
        ..EncodeOptions::default()
    }
}

/// For LR and strips, one line per corner of every (canonical) triangle:
/// `corner vertex opposite` (`-` for none). For Edgebreaker, one line per decoded triangle: its
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
            format!("{n} triangles, {} ring vertices", lr.ring_vertices()),
        ),
        View::LrCompact(lr) => corner_listing(
            &mut out,
            name,
            lr,
            format!(
                "{n} triangles, {} ring vertices, {} T0 rows",
                lr.ring_vertices(),
                lr.t0_count()
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
    out
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
}

#[test]
fn vectors_match() {
    let regenerate = std::env::var_os("LRMESH_REGENERATE_VECTORS").is_some();
    for name in VECTORS {
        for (connectivity, suffix) in [
            (Connectivity::Lr, ""),
            (Connectivity::Edgebreaker, ".edgebreaker"),
            (Connectivity::Strips, ".strips"),
            (Connectivity::LrCompact, ".lr-compact"),
        ] {
            let source = dir().join(format!("{name}.off"));
            let mesh = read_mesh(&source, &ReadOptions::default()).unwrap().mesh;
            let bytes = encode(&mesh, &options(connectivity)).unwrap();
            let lrm = dir().join(format!("{name}{suffix}.lrm"));
            let txt = dir().join(format!("{name}{suffix}.txt"));
            if regenerate {
                std::fs::write(&lrm, &bytes).unwrap();
                std::fs::write(&txt, listing(name, &bytes)).unwrap();
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
            // Decoding gives back the source exactly (the vectors keep the input order).
            let back = open(&stored, &Limits::default()).unwrap().to_mesh();
            assert_eq!(back.positions, mesh.positions, "{name}");
            assert_same_up_to_rotation(&back.triangles, &mesh.triangles, name);
        }
    }
}
