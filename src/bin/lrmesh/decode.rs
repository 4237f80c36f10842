//! `lrmesh decode` and `lrmesh verify`: a container back to a mesh file, or only checked.

use std::path::PathBuf;

use lrmesh::read::{self, Limits};

use crate::common::{map, save, say};
use crate::progress;

/// Decode an .lrm container into a mesh file.
#[derive(clap::Args)]
pub struct DecodeArgs {
    /// The container.
    input: PathBuf,
    /// The mesh to write (.obj, .off, .ply, .stl, .gltf, .glb).
    #[arg(short, long)]
    output: PathBuf,
    /// STL output: ASCII instead of binary.
    #[arg(long)]
    ascii: bool,
}

/// Validate an .lrm container fully: exit 0 only when it is valid.
#[derive(clap::Args)]
pub struct VerifyArgs {
    /// The container.
    file: PathBuf,
}

pub fn decode(args: DecodeArgs) -> lrmesh::Result<()> {
    let bytes = map(&args.input)?;
    let view =
        read::open_verified(&bytes, &Limits::default()).map_err(|e| e.with_file(&args.input))?;
    let mesh = progress::step("decoding", || view.to_mesh());
    save(&args.output, &mesh, args.ascii)?;
    eprintln!(
        "wrote {}: {} vertices, {} triangles{}",
        args.output.display(),
        mesh.vertex_count(),
        mesh.triangle_count(),
        if view.is_quantized() {
            " (positions were quantized: lossy)"
        } else {
            ""
        }
    );
    Ok(())
}

pub fn verify(args: VerifyArgs) -> lrmesh::Result<()> {
    let bytes = map(&args.file)?;
    let view =
        read::open_verified(&bytes, &Limits::default()).map_err(|e| e.with_file(&args.file))?;
    let summary = view.summary();
    say!(
        "{}: valid lrmesh container {}, {} vertices, {} triangles",
        args.file.display(),
        summary.version,
        summary.vertices,
        summary.triangles
    );
    Ok(())
}
