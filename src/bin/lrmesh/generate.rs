//! `lrmesh generate`: a test mesh of a chosen size and topology, so that nobody has to write
//! a script to try lrmesh on a large mesh.

use std::path::PathBuf;

use lrmesh::generate::{surface, SurfaceOptions};

use crate::common::{is_stdio, output_format, save, Format, Report};
use crate::progress;

/// Write a generated mesh of about N triangles: a torus (or a sphere, or a torus with
/// handles) per component, holes punched, valences made irregular if asked.
#[derive(clap::Args)]
pub struct Args {
    /// The mesh to write (.ply is binary; .obj, .off, .stl, .gltf, .glb, .lrm), or `-` for
    /// standard output with --output-format.
    output: PathBuf,
    /// About this many triangles in all (16 to 2^31).
    #[arg(long, value_parser = clap::value_parser!(u64).range(16..=1 << 31))]
    triangles: u64,
    /// Genus of each component: 0 a sphere, 1 a torus, more a torus with handles.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(0..=10_000))]
    genus: u32,
    /// Triangles removed at random, each opening a hole.
    #[arg(long, default_value_t = 0)]
    holes: u32,
    /// Components, side by side.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    components: u32,
    /// Irregular valences: edges flipped at random and vertices jittered (the default grid
    /// has every valence 6, which flatters every connectivity).
    #[arg(long)]
    irregular: bool,
    /// The same seed gives the same mesh.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The output's format, for standard output or a name without its extension.
    #[arg(long, value_enum, value_name = "FORMAT")]
    output_format: Option<Format>,
    /// Print one JSON object instead of text: `output`, `format`, `vertices`, `triangles`.
    #[arg(long)]
    json: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let format = output_format(&args.output, args.output_format)?;
    let options = SurfaceOptions {
        triangles: args.triangles,
        genus: args.genus,
        holes: args.holes,
        components: args.components,
        irregular: args.irregular,
        seed: args.seed,
    };
    let mesh = progress::step("generating", || surface(&options));
    save(&args.output, format, &mesh, false)?;
    let report = Report::new(is_stdio(&args.output));
    if args.json {
        report.json(&serde_json::json!({
            "output": args.output.display().to_string(),
            "format": format.to_string(),
            "vertices": mesh.vertex_count(),
            "triangles": mesh.triangle_count(),
        }));
    } else {
        eprintln!(
            "wrote {}: {} vertices, {} triangles",
            args.output.display(),
            mesh.vertex_count(),
            mesh.triangle_count()
        );
    }
    Ok(())
}
