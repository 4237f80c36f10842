//! The `lrmesh` command: a thin layer over the library.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use lrmesh::edgebreaker::EdgebreakerStats;
use lrmesh::io::{self, ReadOptions};
use lrmesh::lr::{Lr, LrOptions, LrStats};
use lrmesh::read::{self, Limits};
use lrmesh::strips::StripStats;
use lrmesh::write::{self, EncodeOptions};
use lrmesh::{CornerTable, Error, TopologyReport};

/// Prints a line to stdout; a closed pipe (`lrmesh info x | head`) is not an error.
macro_rules! say {
    ($($arg:tt)*) => {{
        use std::io::Write;
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

/// Prints text to stdout as it is, ignoring a closed pipe.
fn show(text: impl std::fmt::Display) {
    use std::io::Write;
    let _ = write!(std::io::stdout(), "{text}");
}

#[derive(Parser)]
#[command(
    name = "lrmesh",
    version,
    about = "Compact random-access triangle mesh connectivity"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Report a mesh's topology as read (counts, boundaries, genus, defects), or what an .lrm
    /// container holds.
    Info {
        /// The mesh file (.obj, .off, .ply, .stl) or container (.lrm).
        mesh: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// STL only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
    },
    /// Storage statistics of the mesh's connectivity representations (LR paper, Table 1).
    Stats {
        /// The mesh file (.obj, .off, .ply, .stl).
        mesh: PathBuf,
        /// Print one JSON object instead of text.
        #[arg(long)]
        json: bool,
        /// STL only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
        /// RING-EXPANDER runs per component (different seed corners); the best ring is kept.
        #[arg(long, default_value_t = LrOptions::default().tries)]
        tries: u32,
        /// Seed for the choice of seed corners (same seed, same result).
        #[arg(long, default_value_t = LrOptions::default().seed)]
        seed: u64,
    },
    /// Encode a mesh into an .lrm container and print the sizes.
    Encode {
        /// The input mesh (.obj, .off, .ply, .stl).
        input: PathBuf,
        /// The container to write.
        #[arg(short, long)]
        output: PathBuf,
        /// Connectivity representation.
        #[arg(long, value_enum, default_value_t = Connectivity::Lr)]
        connectivity: Connectivity,
        /// Store the input's vertex and triangle order, so that decoding restores it.
        #[arg(long)]
        keep_order: bool,
        /// Store positions quantized to this many bits in their bounding box (lossy; 16 only).
        #[arg(long, value_parser = clap::value_parser!(u8).range(16..=16))]
        quantize: Option<u8>,
        /// RING-EXPANDER runs per component; the best ring is kept.
        #[arg(long, default_value_t = LrOptions::default().tries)]
        tries: u32,
        /// Seed for the choice of seed corners (same seed, same bytes).
        #[arg(long, default_value_t = LrOptions::default().seed)]
        seed: u64,
        /// STL input only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
    },
    /// Decode an .lrm container into a mesh file.
    Decode {
        /// The container.
        input: PathBuf,
        /// The mesh to write (.obj, .off, .ply).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Validate an .lrm container fully: exit 0 only when it is valid.
    Verify {
        /// The container.
        file: PathBuf,
    },
    /// Convert a mesh between formats, chosen by the file extensions.
    Convert {
        /// The input mesh (.obj, .off, .ply, .stl).
        input: PathBuf,
        /// The output mesh (.obj, .off, .ply).
        output: PathBuf,
        /// STL input only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
    },
}

/// Connectivity representations of a container.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Connectivity {
    /// Standard Laced Ring: random access on the loaded file.
    Lr,
    /// Edgebreaker: the smallest, decoded sequentially.
    Edgebreaker,
}

/// Maps a container file read-only.
fn map(path: &Path) -> lrmesh::Result<memmap2::Mmap> {
    let io_error = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let file = std::fs::File::open(path).map_err(io_error)?;
    // SAFETY: the mapping is read-only and the library only reads it as a `&[u8]`, checking
    // every offset against its length. The remaining hazard is another process changing or
    // truncating the file while we run (changed bytes, or SIGBUS on truncation): the exposure
    // of any program that reads a file being rewritten under it, which a command-line tool
    // accepts. The library itself never maps files (a "safe" mapping API would be unsound).
    unsafe { memmap2::Mmap::map(&file) }.map_err(io_error)
}

fn is_container(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("lrm"))
}

fn load(path: &std::path::Path, weld: bool) -> lrmesh::Result<lrmesh::Mesh> {
    let loaded = io::read_mesh(path, &ReadOptions { weld })?;
    for warning in &loaded.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    Ok(loaded.mesh)
}

fn run(cli: Cli) -> lrmesh::Result<()> {
    match cli.command {
        Command::Info { mesh, json, .. } if is_container(&mesh) => {
            let bytes = map(&mesh)?;
            let view = read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&mesh))?;
            let summary = view.summary();
            if json {
                say!(
                    "{}",
                    serde_json::to_string_pretty(&summary).expect("a summary serialises")
                );
            } else {
                show(&summary);
            }
        }
        Command::Info { mesh, json, weld } => {
            let report = TopologyReport::of(&load(&mesh, weld)?);
            if json {
                say!(
                    "{}",
                    serde_json::to_string_pretty(&report).expect("a report always serialises")
                );
            } else {
                show(&report);
            }
        }
        Command::Stats {
            mesh,
            json,
            weld,
            tries,
            seed,
        } => {
            let mesh = load(&mesh, weld)?;
            let report = TopologyReport::of(&mesh);
            let table = CornerTable::from_mesh(&mesh)?;
            let lr = Lr::build(&table, &LrOptions { tries, seed })?;
            let stats = LrStats::new(&lr, report.valence6_pct);
            let edgebreaker = EdgebreakerStats::of(&table)?;
            let strips = StripStats::of(&mesh)?;
            if json {
                let out = serde_json::json!({
                    "lr": stats,
                    "edgebreaker": edgebreaker,
                    "strips": strips,
                });
                say!(
                    "{}",
                    serde_json::to_string_pretty(&out).expect("stats serialise")
                );
            } else {
                show(&stats);
                show(&edgebreaker);
                show(&strips);
            }
        }
        Command::Encode {
            input,
            output,
            connectivity,
            keep_order,
            quantize,
            tries,
            seed,
            weld,
        } => {
            let mesh = load(&input, weld)?;
            let mut options = EncodeOptions {
                connectivity: match connectivity {
                    Connectivity::Lr => write::Connectivity::Lr,
                    Connectivity::Edgebreaker => write::Connectivity::Edgebreaker,
                },
                lr: LrOptions { tries, seed },
                keep_order,
                quantize16: quantize.is_some(),
                ..EncodeOptions::default()
            };
            options.metadata.source = input.file_name().map(|n| n.to_string_lossy().into_owned());
            let bytes = write::encode(&mesh, &options)?;
            std::fs::write(&output, &bytes).map_err(|source| Error::Io {
                path: output.clone(),
                source,
            })?;
            let summary = read::open(&bytes, &Limits::default())?.summary();
            let n = summary.triangles.max(1) as f64;
            let table_refs = 6 * summary.triangles + summary.connectivity_vertices as u64;
            say!("wrote {}: {} bytes", output.display(), bytes.len());
            say!(
                "{:<28} {:>12} {:>10} {:>10}",
                "connectivity",
                "bytes",
                "bits/tri",
                "refs/tri"
            );
            say!(
                "{:<28} {:>12} {:>10.2} {:>10}",
                format!("{} (this file)", summary.connectivity),
                summary.connectivity_bytes,
                summary.connectivity_bpt,
                summary.rpt.map_or("-".to_string(), |r| format!("{r:.3}"))
            );
            say!(
                "{:<28} {:>12} {:>10.2} {:>10.3}",
                "indexed triangle list",
                12 * summary.triangles,
                96.0,
                3.0
            );
            say!(
                "{:<28} {:>12} {:>10.2} {:>10.3}",
                "corner table (V, O, C)",
                4 * table_refs,
                32.0 * table_refs as f64 / n,
                table_refs as f64 / n
            );
            if summary.quantized {
                say!("positions quantized to 16 bits: lossy");
            }
        }
        Command::Decode { input, output } => {
            let bytes = map(&input)?;
            let view = read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&input))?;
            let mesh = view.to_mesh();
            io::write_mesh(&output, &mesh)?;
            eprintln!(
                "wrote {}: {} vertices, {} triangles{}",
                output.display(),
                mesh.vertex_count(),
                mesh.triangle_count(),
                if view.is_quantized() {
                    " (positions were quantized: lossy)"
                } else {
                    ""
                }
            );
        }
        Command::Verify { file } => {
            let bytes = map(&file)?;
            let view = read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&file))?;
            let summary = view.summary();
            say!(
                "{}: valid lrmesh container {}, {} vertices, {} triangles",
                file.display(),
                summary.version,
                summary.vertices,
                summary.triangles
            );
        }
        Command::Convert {
            input,
            output,
            weld,
        } => {
            let mesh = load(&input, weld)?;
            io::write_mesh(&output, &mesh)?;
            eprintln!(
                "wrote {}: {} vertices, {} triangles",
                output.display(),
                mesh.vertex_count(),
                mesh.triangle_count()
            );
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run(Cli::parse()) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
