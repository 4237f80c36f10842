//! `lrmesh decode` and `lrmesh verify`: a container back to a mesh file, or only checked.

use std::path::{Path, PathBuf};
use std::time::Instant;

use lrmesh::read::{self, Limits, Sections};
use lrmesh::Error;

use crate::common::{is_stdio, ms, output_format, read_container, save, say, Format, Report};
use crate::convert::Written;
use crate::progress;

/// Decode an .lrm container into a mesh file.
#[derive(clap::Args)]
pub struct DecodeArgs {
    /// The container, or `-` for standard input.
    input: PathBuf,
    /// The mesh to write (.obj, .off, .ply, .stl, .gltf, .glb), or `-` for standard output
    /// (the report then goes to stderr).
    #[arg(short, long)]
    output: PathBuf,
    /// The output's format, for standard output or a name without its extension.
    #[arg(long, visible_alias = "format", value_enum, value_name = "FORMAT")]
    output_format: Option<Format>,
    /// STL output: ASCII instead of binary.
    #[arg(long)]
    ascii: bool,
    /// Print one JSON object instead of text: `input`, `output`, `format`, `vertices`,
    /// `triangles`, `attributes`, `parts`, `quantized`, `open_ms`, `decode_ms`, `write_ms`.
    #[arg(long)]
    json: bool,
}

/// Validate an .lrm container fully: exit 0 only when it is valid.
#[derive(clap::Args)]
pub struct VerifyArgs {
    /// The container, or `-` for standard input.
    file: PathBuf,
    /// Print one JSON object instead of text: `file`, `valid`, `checks` (each `check`, `ok`,
    /// `ms`, in order, up to the first that fails), `error` (`rule`, `section`, `offset`,
    /// `message`; null when valid), `version`, `vertices` and `triangles` (null unless
    /// valid). The exit status is 1 when the file is not valid, JSON or not.
    #[arg(long)]
    json: bool,
}

/// The JSON report of `lrmesh decode --json`.
#[derive(serde::Serialize)]
struct DecodeReport {
    #[serde(flatten)]
    written: Written,
    quantized: bool,
    open_ms: f64,
    decode_ms: f64,
    write_ms: f64,
}

pub fn decode(args: DecodeArgs) -> lrmesh::Result<()> {
    let format = output_format(&args.output, args.output_format)?;
    let bytes = read_container(&args.input)?;
    let started = Instant::now();
    let view =
        read::open_verified(&bytes, &Limits::default()).map_err(|e| e.with_file(&args.input))?;
    let open_ms = ms(started.elapsed());
    let started = Instant::now();
    let mesh = progress::step("decoding", || view.to_mesh());
    let decode_ms = ms(started.elapsed());
    let started = Instant::now();
    save(&args.output, format, &mesh, args.ascii)?;
    let write_ms = ms(started.elapsed());
    let written = Written::new(&args.input, &args.output, format, &mesh);
    let report = Report::new(is_stdio(&args.output));
    if args.json {
        report.json(&DecodeReport {
            written,
            quantized: view.is_quantized(),
            open_ms,
            decode_ms,
            write_ms,
        });
        return Ok(());
    }
    eprintln!(
        "wrote {}: {} vertices, {} triangles{}",
        written.output,
        written.vertices,
        written.triangles,
        if view.is_quantized() {
            " (positions were quantized: lossy)"
        } else {
            ""
        }
    );
    Ok(())
}

/// One check of `lrmesh verify`.
#[derive(serde::Serialize)]
struct Check {
    check: &'static str,
    ok: bool,
    ms: f64,
}

/// The JSON report of `lrmesh verify --json`.
#[derive(serde::Serialize)]
struct VerifyReport {
    file: String,
    valid: bool,
    checks: Vec<Check>,
    error: Option<serde_json::Value>,
    version: Option<String>,
    vertices: Option<u32>,
    triangles: Option<u64>,
}

/// The checks of `lrmesh verify`, in order: each level of `FORMAT.md` §5.1, then the decoded
/// mesh. Stops at the first that fails, with its error.
fn checks(
    bytes: &[u8],
    file: &Path,
) -> (Vec<Check>, Option<Error>, Option<read::ContainerSummary>) {
    let limits = Limits::default();
    let mut checks = Vec::new();
    let mut run = |check: &'static str, f: &mut dyn FnMut() -> lrmesh::Result<()>| {
        let started = Instant::now();
        let result = f().map_err(|e| e.with_file(file));
        checks.push(Check {
            check,
            ok: result.is_ok(),
            ms: ms(started.elapsed()),
        });
        result
    };
    let mut container = None;
    let result = run("header, section table and checksums", &mut || {
        Sections::parse(bytes, &limits).map(|_| ())
    })
    .and_then(|()| {
        run(
            "well formed (every rule but the semantic ones)",
            &mut || {
                container = Some(read::open(bytes, &limits)?);
                Ok(())
            },
        )
    })
    .and_then(|()| {
        run("semantic rules", &mut || {
            container.as_mut().map_or(Ok(()), |c| c.verify())
        })
    })
    .and_then(|()| {
        run("decoded mesh", &mut || {
            container
                .as_ref()
                .map_or(Ok(()), |c| c.to_mesh().validate())
        })
    });
    let summary = container.as_ref().map(|c| c.summary());
    (checks, result.err(), summary)
}

pub fn verify(args: VerifyArgs) -> lrmesh::Result<()> {
    let bytes = read_container(&args.file)?;
    let (checks, error, summary) = checks(&bytes, &args.file);
    if args.json {
        let valid = error.is_none();
        say!(
            "{}",
            serde_json::to_string_pretty(&VerifyReport {
                file: args.file.display().to_string(),
                valid,
                checks,
                error: error.as_ref().map(|e| match e {
                    Error::Format(f) => serde_json::json!({
                        "rule": f.rule.0,
                        "section": f.section,
                        "offset": f.offset,
                        "message": f.message,
                    }),
                    other => serde_json::json!({
                        "rule": null, "section": null, "offset": null,
                        "message": other.to_string(),
                    }),
                }),
                version: summary
                    .as_ref()
                    .filter(|_| valid)
                    .map(|s| s.version.clone()),
                vertices: summary.as_ref().filter(|_| valid).map(|s| s.vertices),
                triangles: summary.as_ref().filter(|_| valid).map(|s| s.triangles),
            })
            .unwrap_or_default()
        );
    }
    if let Some(e) = error {
        return Err(e);
    }
    if !args.json {
        let summary = summary.expect("a valid container has a summary");
        say!(
            "{}: valid lrmesh container {}, {} vertices, {} triangles",
            args.file.display(),
            summary.version,
            summary.vertices,
            summary.triangles
        );
    }
    Ok(())
}
