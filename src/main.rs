//! The `lrmesh` command: a thin layer over the library.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};
use lrmesh::io::{self, ReadOptions};
use lrmesh::lr::{Lr, LrOptions, LrStats};
use lrmesh::{CornerTable, TopologyReport};

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
    /// Report a mesh's topology as read: counts, boundaries, genus, defects.
    Info {
        /// The mesh file (.obj, .off, .ply, .stl).
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

fn load(path: &std::path::Path, weld: bool) -> lrmesh::Result<lrmesh::Mesh> {
    let loaded = io::read_mesh(path, &ReadOptions { weld })?;
    for warning in &loaded.warnings {
        eprintln!("warning: {}: {warning}", path.display());
    }
    Ok(loaded.mesh)
}

fn run(cli: Cli) -> lrmesh::Result<()> {
    match cli.command {
        Command::Info { mesh, json, weld } => {
            let report = TopologyReport::of(&load(&mesh, weld)?);
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&report).expect("a report always serialises")
                );
            } else {
                print!("{report}");
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
            if json {
                let out = serde_json::json!({ "lr": stats });
                println!(
                    "{}",
                    serde_json::to_string_pretty(&out).expect("stats serialise")
                );
            } else {
                print!("{stats}");
            }
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
