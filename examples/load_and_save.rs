//! Loads a mesh, prints its topology, and saves it as an `.lrm` container.
//!
//! ```sh
//! cargo run --example load_and_save [MESH] [OUT.lrm]
//! ```
//!
//! Without arguments it reads the bunny shipped in `corpus/meshes/` and writes
//! `bunny_small.lrm` in the system's temporary folder.

use std::path::PathBuf;

use lrmesh::io::{read_mesh, ReadOptions};
use lrmesh::read::{self, Limits};
use lrmesh::write::{self, EncodeOptions};
use lrmesh::TopologyReport;

fn main() -> Result<(), lrmesh::Error> {
    let mut args = std::env::args_os().skip(1).map(PathBuf::from);
    let input = args.next().unwrap_or_else(|| {
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("corpus/meshes/bunny_small.obj")
    });
    let output = args
        .next()
        .unwrap_or_else(|| std::env::temp_dir().join("bunny_small.lrm"));

    let loaded = read_mesh(&input, &ReadOptions::default())?;
    for warning in &loaded.warnings {
        eprintln!("warning: {warning}");
    }
    let mesh = loaded.mesh;
    let report = TopologyReport::of(&mesh);
    println!(
        "{}: {} vertices, {} triangles, {} boundary loops, genus {:?}",
        input.display(),
        report.vertices,
        report.triangles,
        report.boundary_loops,
        report.genus
    );

    // Standard LR connectivity, positions as f32, the input's order kept.
    let options = EncodeOptions {
        keep_order: true,
        ..EncodeOptions::default()
    };
    let bytes = write::encode(&mesh, &options)?;
    std::fs::write(&output, &bytes).map_err(|source| lrmesh::Error::Io {
        path: output.clone(),
        source,
    })?;

    // Read it back to report what the file holds.
    let summary = read::open(&bytes, &Limits::default())?.summary();
    println!(
        "wrote {}: {} bytes, connectivity {:.2} bits per triangle ({:.3} references)",
        output.display(),
        bytes.len(),
        summary.connectivity_bpt,
        summary.rpt.unwrap_or(0.0)
    );
    Ok(())
}
