//! `lrmesh info`: the topology of a mesh as read, or what a container holds.

use lrmesh::read::{self, Limits};
use lrmesh::TopologyReport;

use crate::common::{show, show_json, MeshInput};

/// Report a mesh's topology as read (counts, boundaries, genus, defects), or what an .lrm
/// container holds.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let path = &args.input.path;
    if let Some(bytes) = args.input.container()? {
        // The headers alone (`lrmesh verify` reads every byte).
        let summary = read::summarize(&bytes, &Limits::default()).map_err(|e| e.with_file(path))?;
        if args.json {
            show_json(&summary);
        } else {
            show(&summary);
        }
        return Ok(());
    }
    let report = TopologyReport::of(&args.input.load()?);
    if args.json {
        show_json(&report);
    } else {
        show(&report);
    }
    Ok(())
}
