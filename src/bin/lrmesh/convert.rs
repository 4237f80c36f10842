//! `lrmesh convert`: between mesh formats, chosen by the file extensions.

use std::path::PathBuf;

use lrmesh::io;

use crate::common::load;
use crate::progress;

/// Convert a mesh between formats, chosen by the file extensions.
#[derive(clap::Args)]
pub struct Args {
    /// The input mesh (.obj, .off, .ply, .stl).
    input: PathBuf,
    /// The output mesh (.obj, .off, .ply).
    output: PathBuf,
    /// STL input only: merge corners with identical positions into shared vertices.
    #[arg(long)]
    weld: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let mesh = load(&args.input, args.weld)?;
    progress::step("writing", || io::write_mesh(&args.output, &mesh))?;
    eprintln!(
        "wrote {}: {} vertices, {} triangles",
        args.output.display(),
        mesh.vertex_count(),
        mesh.triangle_count()
    );
    Ok(())
}
