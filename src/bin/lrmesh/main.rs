//! The `lrmesh` command: a thin layer over the library.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};
use lrmesh::edgebreaker::EdgebreakerStats;
use lrmesh::io::{self, ReadOptions};
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrOptions, LrStats};
use lrmesh::read::{self, Limits};
use lrmesh::strips::StripStats;
use lrmesh::write::{self, EncodeOptions};
use lrmesh::{CornerTable, Error, TopologyReport};

mod progress;

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
        /// Bit-efficient LR: the HYBRID-RING-EXPANDER period k to use (0: depth first)
        /// instead of trying several and keeping the smallest.
        #[arg(long)]
        period: Option<u32>,
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
        /// Bit-efficient LR: the HYBRID-RING-EXPANDER period k to use (0: depth first)
        /// instead of trying several and keeping the smallest.
        #[arg(long)]
        period: Option<u32>,
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
    /// Draw the mesh as a PNG: coloured by ring order (blue to red, LR paper Table 1) or by
    /// triangle class (T0, T2 and warts highlighted, LR paper Fig. 1).
    Render {
        /// The mesh file (.obj, .off, .ply, .stl) or an LR container (.lrm).
        mesh: PathBuf,
        /// The PNG to write.
        #[arg(short, long)]
        output: PathBuf,
        /// `ring`: ring order, blue to red; `classes`: T0 green, T0^w red, T2 blue, T2^w
        /// violet, T1 cream.
        #[arg(long, value_enum, default_value_t = RenderMode::Ring)]
        mode: RenderMode,
        /// Image size in pixels, WIDTHxHEIGHT.
        #[arg(long, default_value = "800x600", value_parser = parse_size)]
        size: (u32, u32),
        /// Viewpoint, AZIMUTH,ELEVATION in degrees around the up axis.
        #[arg(long, default_value = "30,20", value_parser = parse_view, allow_hyphen_values = true)]
        view: (f32, f32),
        /// The axis that points up in the picture.
        #[arg(long, value_enum, default_value_t = UpAxis::Y)]
        up: UpAxis,
        /// Perspective projection instead of orthographic.
        #[arg(long)]
        perspective: bool,
        /// Draw the ring edges as black lines.
        #[arg(long)]
        ring_lines: bool,
        /// Supersamples per pixel along each axis (anti-aliasing).
        #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u32).range(1..=4))]
        samples: u32,
        /// RING-EXPANDER runs per component (mesh input only).
        #[arg(long, default_value_t = LrOptions::default().tries)]
        tries: u32,
        /// Seed for the choice of seed corners (mesh input only).
        #[arg(long, default_value_t = LrOptions::default().seed)]
        seed: u64,
        /// STL input only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
    },
    /// Compare the connectivity representations on one mesh in one run: sizes, build and
    /// open times, and the LR paper's Fig. 10 loops as ratios to the corner table.
    Bench {
        /// The mesh file (.obj, .off, .ply, .stl).
        mesh: PathBuf,
        /// Print one JSON object instead of the table.
        #[arg(long)]
        json: bool,
        /// Timed runs of each step; the median is reported.
        #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
        runs: u32,
        /// STL only: merge corners with identical positions into shared vertices.
        #[arg(long)]
        weld: bool,
    },
}

/// Colourings of `lrmesh render`.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum RenderMode {
    /// Ring order, blue to red.
    Ring,
    /// Triangle classes.
    Classes,
}

/// Up axes of `lrmesh render`.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum UpAxis {
    /// x up.
    X,
    /// y up.
    Y,
    /// z up.
    Z,
}

/// `WIDTHxHEIGHT`, each from 1 to 16384.
fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let (w, h) = s
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("`{s}` is not WIDTHxHEIGHT"))?;
    let side = |t: &str| match t.trim().parse::<u32>() {
        Ok(n) if (1..=16384).contains(&n) => Ok(n),
        _ => Err(format!("`{t}` is not a size from 1 to 16384")),
    };
    Ok((side(w)?, side(h)?))
}

/// `AZIMUTH,ELEVATION` in degrees.
fn parse_view(s: &str) -> Result<(f32, f32), String> {
    let (a, e) = s
        .split_once(',')
        .ok_or_else(|| format!("`{s}` is not AZIMUTH,ELEVATION"))?;
    let angle = |t: &str| match t.trim().parse::<f32>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("`{t}` is not an angle in degrees")),
    };
    Ok((angle(a)?, angle(e)?))
}

/// Connectivity representations of a container.
#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum Connectivity {
    /// Standard Laced Ring: random access on the loaded file.
    Lr,
    /// Edgebreaker: the smallest, decoded sequentially.
    Edgebreaker,
    /// Constrained triangle strips with the adjacent-strips table: a rendering index list
    /// that also answers corner queries on the loaded file.
    Strips,
    /// Bit-efficient Laced Ring: 16-bit offsets, random access on the loaded file.
    LrCompact,
}

/// The HYBRID-RING-EXPANDER periods to try: the one `--period` forces, or the defaults.
fn compact_periods(period: Option<u32>) -> Vec<u32> {
    period.map_or(CompactOptions::default().periods, |k| vec![k])
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
    let loaded = progress::step(&format!("reading {}", path.display()), || {
        io::read_mesh(path, &ReadOptions { weld })
    })?;
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
            period,
        } => {
            let mesh = load(&mesh, weld)?;
            let report = TopologyReport::of(&mesh);
            let table = progress::step("building the corner table", || {
                CornerTable::from_mesh(&mesh)
            })?;
            let lr = progress::step("building the LR", || {
                Lr::build(&table, &LrOptions { tries, seed })
            })?;
            let stats = LrStats::new(&lr, report.valence6_pct);
            let compact = progress::step("building the bit-efficient LR", || {
                CompactLr::build(
                    &table,
                    &CompactOptions {
                        lr: LrOptions { tries, seed },
                        periods: compact_periods(period),
                    },
                )
            })?
            .stats();
            let edgebreaker =
                progress::step("encoding Edgebreaker", || EdgebreakerStats::of(&table))?;
            let strips = progress::step("building strips", || StripStats::of(&mesh))?;
            if json {
                let out = serde_json::json!({
                    "lr": stats,
                    "lr_compact": compact,
                    "edgebreaker": edgebreaker,
                    "strips": strips,
                });
                say!(
                    "{}",
                    serde_json::to_string_pretty(&out).expect("stats serialise")
                );
            } else {
                show(&stats);
                show(&compact);
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
            period,
            weld,
        } => {
            let mesh = load(&input, weld)?;
            let mut options = EncodeOptions {
                connectivity: match connectivity {
                    Connectivity::Lr => write::Connectivity::Lr,
                    Connectivity::Edgebreaker => write::Connectivity::Edgebreaker,
                    Connectivity::Strips => write::Connectivity::Strips,
                    Connectivity::LrCompact => write::Connectivity::LrCompact,
                },
                lr: LrOptions { tries, seed },
                periods: compact_periods(period),
                keep_order,
                quantize16: quantize.is_some(),
                ..EncodeOptions::default()
            };
            options.metadata.source = input.file_name().map(|n| n.to_string_lossy().into_owned());
            let bytes = progress::step("encoding", || write::encode(&mesh, &options))?;
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
            let mesh = progress::step("decoding", || view.to_mesh());
            progress::step("writing", || io::write_mesh(&output, &mesh))?;
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
        Command::Render {
            mesh,
            output,
            mode,
            size,
            view,
            up,
            perspective,
            ring_lines,
            samples,
            tries,
            seed,
            weld,
        } => {
            use lrmesh::render::{self, Axis, ColorMode, RenderOptions};
            use lrmesh::CornerOps;
            let options = RenderOptions {
                width: size.0,
                height: size.1,
                mode: match mode {
                    RenderMode::Ring => ColorMode::Ring,
                    RenderMode::Classes => ColorMode::Classes,
                },
                azimuth: view.0,
                elevation: view.1,
                up: match up {
                    UpAxis::X => Axis::X,
                    UpAxis::Y => Axis::Y,
                    UpAxis::Z => Axis::Z,
                },
                perspective,
                samples,
                ring_lines,
                ..RenderOptions::default()
            };
            let image = if is_container(&mesh) {
                let bytes = map(&mesh)?;
                let view =
                    read::open(&bytes, &Limits::default()).map_err(|e| e.with_file(&mesh))?;
                let positions = |bound: u32| -> Vec<[f32; 3]> {
                    (0..bound)
                        .map(|v| view.position(lrmesh::Vertex(v)))
                        .collect()
                };
                if let Some(lr) = view.lr() {
                    let positions = positions(lr.vertex_id_bound());
                    progress::step("rendering", || render::render(lr, &positions, &options))?
                } else if let Some(lr) = view.lr_compact() {
                    let positions = positions(lr.vertex_id_bound());
                    progress::step("rendering", || render::render(lr, &positions, &options))?
                } else {
                    return Err(Error::Unsupported(format!(
                        "{}: render needs LR connectivity (lr or lr-compact), the file holds {}",
                        mesh.display(),
                        view.summary().connectivity
                    )));
                }
            } else {
                let input = load(&mesh, weld)?;
                let table = progress::step("building the corner table", || {
                    CornerTable::from_mesh(&input)
                })?;
                let lr = progress::step("building the LR", || {
                    Lr::build(&table, &LrOptions { tries, seed })
                })?;
                let positions: Vec<[f32; 3]> = (0..lr.vertex_id_bound())
                    .map(|v| input.positions[lr.input_vertex(lrmesh::Vertex(v)) as usize])
                    .collect();
                progress::step("rendering", || {
                    render::render(lr.tables(), &positions, &options)
                })?
            };
            let io_error = |source| Error::Io {
                path: output.clone(),
                source,
            };
            let file = std::fs::File::create(&output).map_err(io_error)?;
            image
                .write_png(std::io::BufWriter::new(file))
                .map_err(io_error)?;
            eprintln!(
                "wrote {}: {}x{} pixels",
                output.display(),
                image.width(),
                image.height()
            );
        }
        Command::Bench {
            mesh,
            json,
            runs,
            weld,
        } => {
            let input = load(&mesh, weld)?;
            let bar = progress::spinner("benchmarking");
            let report = lrmesh::bench::run(
                &input,
                &lrmesh::bench::BenchOptions {
                    runs: runs as usize,
                    ..Default::default()
                },
                &mut |step| bar.set_message(format!("benchmarking: {step}")),
            )?;
            bar.finish_and_clear();
            if json {
                say!(
                    "{}",
                    serde_json::to_string_pretty(&report).expect("a bench report serialises")
                );
            } else {
                show(&report);
            }
        }
        Command::Convert {
            input,
            output,
            weld,
        } => {
            let mesh = load(&input, weld)?;
            progress::step("writing", || io::write_mesh(&output, &mesh))?;
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
