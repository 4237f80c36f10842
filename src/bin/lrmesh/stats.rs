//! `lrmesh stats`: the storage figures of every connectivity representation (LR paper,
//! Table 1), each structure built once.

use lrmesh::edgebreaker::EdgebreakerStats;
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrOptions, LrStats, Zipper};
use lrmesh::strips::{StripOptions, StripStats};
use lrmesh::{CornerTable, TopologyReport};

use crate::common::{show, show_json, MeshInput};
use crate::progress;

/// Storage statistics of the mesh's connectivity representations (LR paper, Table 1).
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// Print one JSON object instead of text (keys `lr`, `lr_compact`, `zipper`,
    /// `edgebreaker`, `strips`, and `hints`).
    #[arg(long)]
    json: bool,
    /// Make the triangles' orientation consistent first, as `encode --orient` does.
    #[arg(long)]
    orient: bool,
    /// RING-EXPANDER runs per component (different seed corners); the best ring is kept.
    #[arg(long, default_value_t = LrOptions::default().tries)]
    tries: u32,
    /// Seed for the choice of seed corners (same seed, same result).
    #[arg(long, default_value_t = LrOptions::default().seed)]
    seed: u64,
    #[command(flatten)]
    threads: crate::common::Threads,
    /// Bit-efficient LR: the HYBRID-RING-EXPANDER period k to use (0: depth first)
    /// instead of trying several and keeping the smallest.
    #[arg(long)]
    period: Option<u32>,
}

/// The HYBRID-RING-EXPANDER periods to try: the one `--period` forces, or the defaults.
pub fn compact_periods(period: Option<u32>) -> Vec<u32> {
    period.map_or(CompactOptions::default().periods, |k| vec![k])
}

/// One-line hints at what makes the representations larger than the mesh needs, each
/// naming the option that helps (not given when that option is on): edges two triangles use
/// in the same direction (`--orient`), vertices that repeat another's position (`--weld`).
pub fn hints(report: &TopologyReport, orient: bool, weld: bool) -> Vec<String> {
    let mut out = Vec::new();
    if !orient && report.inconsistent_edges > 0 {
        out.push(format!(
            "{} edges run twice in the same direction (inconsistent orientation), which cuts \
             the surface there: --orient repairs it (encode does when the file is smaller \
             so, unless --no-orient)",
            report.inconsistent_edges
        ));
    }
    if !weld && report.duplicate_positions > 0 {
        out.push(format!(
            "{} vertices repeat another vertex's position (an unwelded mesh?), which cuts \
             the surface there: --weld merges them",
            report.duplicate_positions
        ));
    }
    out
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let mesh = args.input.load()?;
    // Of the mesh as read: valences count undirected edges, so orienting changes none.
    let report = TopologyReport::of(&mesh);
    let hints = hints(&report, args.orient, args.input.weld);
    let mesh = if args.orient {
        lrmesh::mesh::orient(&mesh).mesh
    } else {
        mesh
    };
    // The order `encode` builds from, so that the figures are those of the file it writes.
    let mesh = lrmesh::write::in_encoding_order(mesh, &Default::default())?;
    let lr_options = LrOptions {
        tries: args.tries,
        seed: args.seed,
        threads: args.threads.get(),
    };
    let table = progress::step("building the corner table", || {
        CornerTable::from_mesh(&mesh)
    })?;
    let lr = progress::step("building the LR", || Lr::build(&table, &lr_options))?;
    let stats = LrStats::new(&lr, report.valence6_pct);
    let compact = progress::step("building the bit-efficient LR", || {
        CompactLr::build(
            &table,
            &CompactOptions {
                lr: lr_options,
                periods: compact_periods(args.period),
                ..CompactOptions::default()
            },
        )
    })?
    .stats();
    let edgebreaker = progress::step("encoding Edgebreaker", || EdgebreakerStats::of(&table))?;
    let strips = progress::step("building strips", || {
        StripStats::from_built(&mesh, &table, &lr, &StripOptions::default())
    })?;
    // As `encode` builds it at the default level: on a small mesh, the smallest of several
    // seeds' rings.
    let triangles = table.v_table().len() / 3;
    let seeds = lrmesh::write::zipper_seeds(lrmesh::write::DEFAULT_LEVEL, triangles);
    let zipper = progress::step("encoding the Zipper", || match seeds {
        1 => Zipper::encode(lr),
        _ => Zipper::build_smallest(&table, &lr_options, seeds),
    })?
    .stats();
    if args.json {
        show_json(&serde_json::json!({
            "lr": stats,
            "lr_compact": compact,
            "zipper": zipper,
            "edgebreaker": edgebreaker,
            "strips": strips,
            "hints": hints,
        }));
    } else {
        show(&stats);
        show(&compact);
        show(&zipper);
        show(&edgebreaker);
        show(&strips);
        for hint in &hints {
            eprintln!("hint: {hint}");
        }
    }
    Ok(())
}
