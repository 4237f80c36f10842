//! The `lrmesh` command: a thin layer over the library, one file per command.

use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod bench;
mod common;
mod convert;
mod decode;
mod encode;
mod generate;
#[cfg(target_os = "linux")]
mod huge;
mod info;
mod progress;
mod render;
mod shell;
mod stats;

#[derive(Parser)]
#[command(
    name = "lrmesh",
    version,
    about = "Compact random-access triangle mesh connectivity"
)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Show no progress on stderr (it shows only when stderr is a terminal anyway).
    #[arg(long, short, global = true)]
    quiet: bool,
}

#[derive(Subcommand)]
enum Command {
    /// Report a mesh's topology as read (counts, boundaries, genus, defects), or what an .lrm
    /// container holds.
    Info(info::Args),
    /// Storage statistics of the mesh's connectivity representations (LR paper, Table 1).
    Stats(stats::Args),
    /// Encode a mesh into an .lrm container and print the sizes.
    Encode(encode::Args),
    /// Decode an .lrm container into a mesh file.
    Decode(decode::DecodeArgs),
    /// Validate an .lrm container fully: exit 0 only when it is valid.
    Verify(decode::VerifyArgs),
    /// Convert a mesh between formats, chosen by the file extensions.
    Convert(convert::Args),
    /// Draw the mesh as a PNG: coloured by ring order (blue to red, LR paper Table 1) or by
    /// triangle class (T0, T2 and warts highlighted, LR paper Fig. 1).
    Render(render::Args),
    /// Compare the connectivity representations on one mesh in one run: sizes, build and
    /// open times, and the LR paper's Fig. 10 loops as ratios to the corner table.
    Bench(bench::Args),
    /// Write a generated mesh of about N triangles, of a chosen genus, holes and components,
    /// with regular or irregular valences.
    Generate(generate::Args),
    /// Print a shell's completion script (bash, zsh, fish, elvish, powershell).
    Completions(shell::CompletionsArgs),
    /// Print the man page (roff), with a section for every command.
    Man(shell::ManArgs),
}

fn run(cli: Cli) -> lrmesh::Result<()> {
    progress::set_quiet(cli.quiet);
    match cli.command {
        Command::Info(args) => info::run(args),
        Command::Stats(args) => stats::run(args),
        Command::Encode(args) => encode::run(args),
        Command::Decode(args) => decode::decode(args),
        Command::Verify(args) => decode::verify(args),
        Command::Convert(args) => convert::run(args),
        Command::Render(args) => render::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Generate(args) => generate::run(args),
        Command::Completions(args) => shell::completions(args),
        Command::Man(args) => shell::man(args),
    }
}

/// glibc raises its mmap threshold to the size of each large block freed (up to 32 MB), after
/// which such blocks come from the heap and stay resident once freed. The encoder frees its
/// large arrays phase by phase (corner table, rings, working arrays): with the threshold fixed
/// at glibc's default of 128 KiB they go back to the system at once, which takes 5-7% off an
/// encode's peak resident memory at 3.3M triangles. Not for `bench`: there every timed run
/// would get fresh pages for its large blocks, faulted and zeroed again (an `open`'s
/// validation buffers, 2 bytes per ring vertex: 1.3-1.5 ms of a 5 ms open at 3.3M
/// triangles), which a program that opens or builds more than once does not pay, nor the
/// memcpy the opens are compared with, whose buffer is allocated once.
#[cfg(target_os = "linux")]
#[global_allocator]
static ALLOCATOR: huge::HugePages = huge::HugePages;

#[cfg(all(target_os = "linux", target_env = "gnu"))]
fn return_large_blocks_at_once() {
    // SAFETY: mallopt only sets an allocator parameter; it is called before any thread exists.
    unsafe {
        libc::mallopt(libc::M_MMAP_THRESHOLD, 128 * 1024);
    }
}

#[cfg(not(all(target_os = "linux", target_env = "gnu")))]
fn return_large_blocks_at_once() {}

fn main() -> ExitCode {
    let cli = Cli::parse();
    if !matches!(cli.command, Command::Bench(_)) {
        return_large_blocks_at_once();
    }
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
