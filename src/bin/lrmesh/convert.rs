//! `lrmesh convert`: between mesh formats, chosen by the file extensions or `--format`.

use std::path::PathBuf;

use crate::common::{is_stdio, output_format, save, Format, MeshInput, Report};

/// Convert a mesh between formats, chosen by the file extensions.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// The output mesh (.obj, .off, .ply, .stl, .gltf, .glb, .lrm), or `-` for standard
    /// output (the report then goes to stderr).
    output: PathBuf,
    /// The output's format, for standard output or a name without its extension.
    #[arg(long, value_enum, value_name = "FORMAT")]
    output_format: Option<Format>,
    /// STL output: ASCII instead of binary.
    #[arg(long)]
    ascii: bool,
    /// Print one JSON object instead of text: `input`, `output`, `format` (of the output),
    /// `vertices`, `triangles`, `attributes` (names), `parts` (null without).
    #[arg(long)]
    json: bool,
}

/// The JSON report of `lrmesh convert --json` and `lrmesh decode --json`.
#[derive(serde::Serialize)]
pub struct Written {
    pub input: String,
    pub output: String,
    pub format: String,
    pub vertices: usize,
    pub triangles: usize,
    pub attributes: Vec<String>,
    pub parts: Option<usize>,
}

impl Written {
    pub fn new(
        input: &std::path::Path,
        output: &std::path::Path,
        format: lrmesh::io::MeshFormat,
        mesh: &lrmesh::Mesh,
    ) -> Written {
        Written {
            input: input.display().to_string(),
            output: output.display().to_string(),
            format: format.to_string(),
            vertices: mesh.vertex_count(),
            triangles: mesh.triangle_count(),
            attributes: mesh
                .attributes
                .iter()
                .map(|a| a.semantic.to_string())
                .collect(),
            parts: mesh.parts.as_ref().map(|p| p.parts.len()),
        }
    }
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let mesh = args.input.load()?;
    let format = output_format(&args.output, args.output_format)?;
    save(&args.output, format, &mesh, args.ascii)?;
    let report = Report::new(is_stdio(&args.output));
    let written = Written::new(&args.input.path, &args.output, format, &mesh);
    if args.json {
        report.json(&written);
    } else {
        eprintln!(
            "wrote {}: {} vertices, {} triangles",
            written.output, written.vertices, written.triangles
        );
    }
    Ok(())
}
