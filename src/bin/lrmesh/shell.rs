//! `lrmesh completions` and `lrmesh man`: generated from the command definition itself, so
//! that they never disagree with `--help`.

use clap::CommandFactory;

use crate::common::show;

/// Print a shell's completion script for lrmesh.
#[derive(clap::Args)]
pub struct CompletionsArgs {
    /// The shell (bash: `lrmesh completions bash > /etc/bash_completion.d/lrmesh`).
    #[arg(value_enum)]
    shell: clap_complete::Shell,
}

/// Print the man page (roff): `lrmesh man > lrmesh.1; man ./lrmesh.1`.
#[derive(clap::Args)]
pub struct ManArgs {}

pub fn completions(args: CompletionsArgs) -> lrmesh::Result<()> {
    let mut out = Vec::new();
    clap_complete::generate(args.shell, &mut crate::Cli::command(), "lrmesh", &mut out);
    show(String::from_utf8_lossy(&out));
    Ok(())
}

pub fn man(_: ManArgs) -> lrmesh::Result<()> {
    let mut out = Vec::new();
    let command = crate::Cli::command();
    clap_mangen::Man::new(command.clone())
        .render(&mut out)
        .map_err(io_error)?;
    // A section per subcommand, after the main page.
    for sub in command.get_subcommands() {
        let name = format!("lrmesh-{}", sub.get_name());
        clap_mangen::Man::new(sub.clone())
            .title(name)
            .render(&mut out)
            .map_err(io_error)?;
    }
    show(String::from_utf8_lossy(&out));
    Ok(())
}

fn io_error(source: std::io::Error) -> lrmesh::Error {
    lrmesh::Error::Io {
        path: "-".into(),
        source,
    }
}
