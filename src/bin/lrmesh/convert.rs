//! `lrmesh convert`: between mesh formats, chosen by the file extensions.

use std::path::PathBuf;

use crate::common::{load, save};

/// Convert a mesh between formats, chosen by the file extensions.
#[derive(clap::Args)]
pub struct Args {
    /// The input mesh (.obj, .off, .ply, .stl, .gltf, .glb).
    input: PathBuf,
    /// The output mesh (.obj, .off, .ply, .stl, .gltf, .glb).
    output: PathBuf,
    /// Merge vertices with identical positions into shared vertices (any input format:
    /// attributes that differ between them become per corner)
    #[arg(long)]
    weld: bool,
    /// STL output: ASCII instead of binary.
    #[arg(long)]
    ascii: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let mesh = load(&args.input, args.weld)?;
    save(&args.output, &mesh, args.ascii)?;
    eprintln!(
        "wrote {}: {} vertices, {} triangles",
        args.output.display(),
        mesh.vertex_count(),
        mesh.triangle_count()
    );
    Ok(())
}
