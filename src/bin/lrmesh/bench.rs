//! `lrmesh bench`: every representation compared on one mesh in one run.

use crate::common::{show, show_json, MeshInput};
use crate::progress;

/// Compare the connectivity representations on one mesh in one run: sizes, build and
/// open times, and the LR paper's Fig. 10 loops as ratios to the corner table.
#[derive(clap::Args)]
pub struct Args {
    #[command(flatten)]
    input: MeshInput,
    /// Print one JSON object instead of the table.
    #[arg(long)]
    json: bool,
    /// Timed runs of each step; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    runs: u32,
}

pub fn run(args: Args) -> lrmesh::Result<()> {
    let input = args.input.load()?;
    let bar = progress::spinner("benchmarking");
    let report = lrmesh::bench::run(
        &input,
        &lrmesh::bench::BenchOptions {
            runs: args.runs as usize,
            ..Default::default()
        },
        &mut |step| bar.set_message(format!("benchmarking: {step}")),
    )?;
    bar.finish_and_clear();
    if args.json {
        show_json(&report);
    } else {
        show(&report);
    }
    Ok(())
}
