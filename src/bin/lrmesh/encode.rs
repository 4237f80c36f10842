//! `lrmesh encode`: a mesh into a container, with the connectivity's size next to an
//! indexed triangle list and a corner table.

use std::path::PathBuf;
use std::time::Instant;

use clap::ValueEnum;
use lrmesh::lr::LrOptions;
use lrmesh::read::{self, Limits};
use lrmesh::write::{self, EncodeOptions, Orient};

use crate::common::{is_stdio, ms, write_out, MeshInput, Report};
use crate::progress;
use crate::stats::{compact_periods, hints};

/// Encode a mesh into an .lrm container and print the sizes.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// The container to write, or `-` for standard output (the report then goes to stderr).
    #[arg(short, long)]
    output: PathBuf,
    /// Connectivity representation.
    #[arg(long, value_enum, default_value_t = Connectivity::Lr)]
    connectivity: Connectivity,
    /// Store the input's vertex and triangle order, so that decoding restores it.
    #[arg(long)]
    keep_order: bool,
    /// Store positions on a grid of this many bits per coordinate (1 to 30) in their
    /// bounding box: lossy, each coordinate within half a grid step. Without it, the f32
    /// positions are kept exactly. `--quantize` is the same option.
    #[arg(long, visible_alias = "quantize", value_name = "BITS",
          value_parser = clap::value_parser!(u8).range(1..=30))]
    quantize_position: Option<u8>,
    /// Store f32 normals octahedral, two integers of this many bits (1 to 24) per normal:
    /// lossy. Without it, normals are kept exactly.
    #[arg(long, value_name = "BITS", value_parser = clap::value_parser!(u8).range(1..=24))]
    quantize_normal: Option<u8>,
    /// Store f32 texture coordinates and custom attributes on a grid of this many bits per
    /// component (1 to 30) over their range: lossy, each within half a grid step.
    #[arg(long, value_name = "BITS", value_parser = clap::value_parser!(u8).range(1..=30))]
    quantize_texcoord: Option<u8>,
    /// Store f32 colors on a grid of this many bits per component (1 to 30): lossy. Integer
    /// colors are always kept exactly.
    #[arg(long, value_name = "BITS", value_parser = clap::value_parser!(u8).range(1..=30))]
    quantize_color: Option<u8>,
    /// Compression level, 0 to 9: 0 stores positions raw (f32, or 16-bit words: the fastest
    /// to write and to open); from 1, Edgebreaker predicts them and range codes the residuals,
    /// and the random-access kinds store positions in blocks (exact ones when that is smaller
    /// than raw f32). From 6, `zipper` on a small mesh builds its ring from several seeds (from
    /// --seed on: up to 32 at 6, twice as many at each level above, within a fixed budget of
    /// work) and keeps the smallest tables.
    #[arg(short, long, default_value_t = write::DEFAULT_LEVEL,
          value_parser = clap::value_parser!(u8).range(0..=9))]
    level: u8,
    /// RING-EXPANDER runs per component; the best ring is kept.
    #[arg(long, default_value_t = LrOptions::default().tries)]
    tries: u32,
    /// Seed for the choice of seed corners (same seed, same bytes).
    #[arg(long, default_value_t = LrOptions::default().seed)]
    seed: u64,
    #[command(flatten)]
    threads: crate::common::Threads,
    /// Bit-efficient LR: the HYBRID-RING-EXPANDER period k to use (0: depth first)
    /// instead of trying several and keeping the smallest.
    #[arg(long)]
    period: Option<u32>,
    /// Make the triangles' orientation consistent first (reversing those that disagree with
    /// their neighbours, per component): an edge two triangles use in the same direction
    /// cuts the surface, which costs every representation. Decoding still gives back the
    /// input's triangles (the reversed ones are listed in the file)
    #[arg(long)]
    orient: bool,
    /// With --orient: decoding gives the repaired triangles instead of the input's
    #[arg(long, requires = "orient")]
    keep_repaired: bool,
    /// Store the triangles as given. Without --orient or this option, a mesh with edges two
    /// triangles use in the same direction is also encoded as --orient does, and the
    /// smaller file kept
    #[arg(long, conflicts_with = "orient")]
    no_orient: bool,
    /// Print one JSON object instead of text: the container's figures as `lrmesh info
    /// --json` gives them (`container`), with `output`, `bytes`, `read_ms`, `encode_ms`,
    /// `write_ms`, `orientation` and `hints`
    #[arg(long)]
    json: bool,
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
    /// Zipper: the Laced Ring's slots in 3-bit symbols, random access on the loaded file.
    Zipper,
}

/// The JSON report of `lrmesh encode --json`.
#[derive(serde::Serialize)]
struct EncodeReport {
    output: String,
    bytes: usize,
    read_ms: f64,
    encode_ms: f64,
    write_ms: f64,
    /// With --orient, or when the file was smaller so: triangles reversed, and edges that
    /// still disagree (a Möbius band).
    orientation: Option<Orientation>,
    hints: Vec<String>,
    container: lrmesh::read::ContainerSummary,
}

#[derive(serde::Serialize)]
struct Orientation {
    reversed_triangles: usize,
    conflicts: usize,
    recorded: bool,
    /// Chosen by the encoder (no --orient) because the file was smaller so.
    automatic: bool,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let started = Instant::now();
    let mesh = args.input.load()?;
    let read_ms = ms(started.elapsed());
    let report = Report::new(is_stdio(&args.output));
    let mut options = EncodeOptions {
        connectivity: match args.connectivity {
            Connectivity::Lr => write::Connectivity::Lr,
            Connectivity::Edgebreaker => write::Connectivity::Edgebreaker,
            Connectivity::Strips => write::Connectivity::Strips,
            Connectivity::LrCompact => write::Connectivity::LrCompact,
            Connectivity::Zipper => write::Connectivity::Zipper,
        },
        lr: LrOptions {
            tries: args.tries,
            seed: args.seed,
            threads: args.threads.get(),
        },
        periods: compact_periods(args.period),
        keep_order: args.keep_order,
        position_bits: args.quantize_position,
        normal_bits: args.quantize_normal,
        texcoord_bits: args.quantize_texcoord,
        color_bits: args.quantize_color,
        level: args.level,
        orient: match (args.orient, args.keep_repaired, args.no_orient) {
            (false, _, false) => Orient::Auto,
            (false, _, true) => Orient::AsGiven,
            (true, false, _) => Orient::Repair,
            (true, true, _) => Orient::RepairAndKeep,
        },
        ..EncodeOptions::default()
    };
    options.metadata.source = (!is_stdio(&args.input.path))
        .then(|| args.input.path.file_name())
        .flatten()
        .map(|n| n.to_string_lossy().into_owned());
    // In the order the writer takes (it keeps the order it is given then), so that the
    // topology report below walks memory in order too: on a large mesh in scattered order it
    // took a third of the command's time.
    let mesh = write::in_encoding_order(mesh, &options)?;
    // Oriented here once, for the report and for the writer.
    let oriented = args.orient.then(|| lrmesh::mesh::orient(&mesh));
    let mut orientation = oriented.as_ref().map(|o| Orientation {
        reversed_triangles: o.flipped_count(),
        conflicts: o.conflicts,
        recorded: !args.keep_repaired && o.flipped_count() > 0,
        automatic: false,
    });
    let topology = lrmesh::TopologyReport::of(&mesh);
    // What the encoder's own choice would repair, for the report (only a mesh with such
    // edges is oriented again).
    let auto = options.orient == Orient::Auto && topology.inconsistent_edges > 0;
    let conflicts = auto.then(|| lrmesh::mesh::orient(&mesh).conflicts);
    let hints = hints(&topology, args.orient || auto, args.input.weld);
    let started = Instant::now();
    let bytes = progress::step("encoding", || match &oriented {
        Some(o) => write::encode_oriented(o, &options),
        // Taken, so that its triangles go once the corner table holds them.
        None => write::encode_owned(mesh, &options),
    })?;
    let encode_ms = ms(started.elapsed());
    let output = &args.output;
    let started = Instant::now();
    write_out(output, &bytes)?;
    let write_ms = ms(started.elapsed());
    let summary = read::open(&bytes, &Limits::default())?.summary();
    if let (Some(conflicts), true) = (conflicts, summary.reversed_triangles > 0) {
        orientation = Some(Orientation {
            reversed_triangles: summary.reversed_triangles as usize,
            conflicts,
            recorded: true,
            automatic: true,
        });
    }
    if args.json {
        report.json(&EncodeReport {
            output: output.display().to_string(),
            bytes: bytes.len(),
            read_ms,
            encode_ms,
            write_ms,
            orientation,
            hints,
            container: summary,
        });
        return Ok(());
    }
    let say = |line: String| report.line(&line);
    let n = summary.triangles.max(1) as f64;
    let table_refs = 6 * summary.triangles + summary.connectivity_vertices as u64;
    say(format!("wrote {}: {} bytes", output.display(), bytes.len()));
    say(format!(
        "{:<28} {:>12} {:>10} {:>10}",
        "connectivity", "bytes", "bits/tri", "refs/tri"
    ));
    say(format!(
        "{:<28} {:>12} {:>10.2} {:>10}",
        format!("{} (this file)", summary.connectivity),
        summary.connectivity_bytes,
        summary.connectivity_bpt,
        summary.rpt.map_or("-".to_string(), |r| format!("{r:.3}"))
    ));
    say(format!(
        "{:<28} {:>12} {:>10.2} {:>10.3}",
        "indexed triangle list",
        12 * summary.triangles,
        96.0,
        3.0
    ));
    say(format!(
        "{:<28} {:>12} {:>10.2} {:>10.3}",
        "corner table (V, O, C)",
        4 * table_refs,
        32.0 * table_refs as f64 / n,
        table_refs as f64 / n
    ));
    if let Some(o) = &orientation {
        say(format!(
            "orientation repaired{}: {} triangles reversed{}{}",
            if o.automatic {
                " (the smaller file)"
            } else {
                ""
            },
            o.reversed_triangles,
            if o.recorded {
                " (decoding reverses them back)"
            } else {
                ""
            },
            match o.conflicts {
                0 => String::new(),
                n => format!(", {n} edges still disagree (a non-orientable surface)"),
            }
        ));
    }
    for hint in &hints {
        eprintln!("hint: {hint}");
    }
    if let Some(bits) = args.quantize_position {
        say(format!("positions quantized to {bits} bits: lossy"));
    }
    for (what, bits) in [
        ("normals", args.quantize_normal),
        ("texture coordinates", args.quantize_texcoord),
        ("colors", args.quantize_color),
    ] {
        if let Some(bits) = bits {
            say(format!("f32 {what} quantized to {bits} bits: lossy"));
        }
    }
    Ok(())
}
