//! `lrmesh info`: the topology of a mesh as read, or what a container holds.

use std::path::PathBuf;

use lrmesh::read::{self, Limits};
use lrmesh::TopologyReport;

use crate::common::{is_container, load, map, show, show_json};

/// Report a mesh's topology as read (counts, boundaries, genus, defects), or what an .lrm
/// container holds.
#[derive(clap::Args)]
pub struct Args {
    /// The mesh file (.obj, .off, .ply, .stl) or container (.lrm).
    mesh: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Merge vertices with identical positions into shared vertices (any input format:
    /// attributes that differ between them become per corner)
    #[arg(long)]
    weld: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    if is_container(&args.mesh) {
        let bytes = map(&args.mesh)?;
        let view = read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&args.mesh))?;
        let summary = view.summary();
        if args.json {
            show_json(&summary);
        } else {
            show(&summary);
        }
        return Ok(());
    }
    let report = TopologyReport::of(&load(&args.mesh, args.weld)?);
    if args.json {
        show_json(&report);
    } else {
        show(&report);
    }
    Ok(())
}
