//! `lrmesh stats`: the storage figures of every connectivity representation (LR paper,
//! Table 1), each structure built once.

use std::path::PathBuf;

use lrmesh::edgebreaker::EdgebreakerStats;
use lrmesh::lr::{CompactLr, CompactOptions, Lr, LrOptions, LrStats};
use lrmesh::strips::{StripOptions, StripStats};
use lrmesh::{CornerTable, TopologyReport};

use crate::common::{load, show, show_json};
use crate::progress;

/// Storage statistics of the mesh's connectivity representations (LR paper, Table 1).
#[derive(clap::Args)]
pub struct Args {
    /// The mesh file (.obj, .off, .ply, .stl).
    mesh: PathBuf,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Merge vertices with identical positions into shared vertices (any input format:
    /// attributes that differ between them become per corner)
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
}

/// The HYBRID-RING-EXPANDER periods to try: the one `--period` forces, or the defaults.
pub fn compact_periods(period: Option<u32>) -> Vec<u32> {
    period.map_or(CompactOptions::default().periods, |k| vec![k])
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let mesh = load(&args.mesh, args.weld)?;
    let lr_options = LrOptions {
        tries: args.tries,
        seed: args.seed,
    };
    let report = TopologyReport::of(&mesh);
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
            },
        )
    })?
    .stats();
    let edgebreaker = progress::step("encoding Edgebreaker", || EdgebreakerStats::of(&table))?;
    let strips = progress::step("building strips", || {
        StripStats::from_built(&mesh, &table, &lr, &StripOptions::default())
    })?;
    if args.json {
        show_json(&serde_json::json!({
            "lr": stats,
            "lr_compact": compact,
            "edgebreaker": edgebreaker,
            "strips": strips,
        }));
    } else {
        show(&stats);
        show(&compact);
        show(&edgebreaker);
        show(&strips);
    }
    Ok(())
}
