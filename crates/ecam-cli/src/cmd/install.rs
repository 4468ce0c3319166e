//! `ecam completions SHELL` and `ecam man`: what a package or a user's
//! dotfiles install next to the binary, generated from the one clap
//! definition so they never fall behind it.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;
use clap::CommandFactory;
use clap_complete::Shell;

use crate::Cli;

/// Arguments of `ecam completions`.
#[derive(clap::Args, Debug)]
pub struct CompletionsArgs {
    /// The shell to complete in.
    #[arg(value_enum)]
    pub shell: Shell,
}

/// Arguments of `ecam man`.
#[derive(clap::Args, Debug)]
pub struct ManArgs {
    /// Write one page per subcommand (`ecam.1`, `ecam-table-gen.1`, …) into
    /// this directory instead of printing `ecam.1`.
    #[arg(long, value_name = "DIR")]
    pub dir: Option<PathBuf>,
}

/// Prints the completion script for `args.shell`, e.g.
/// `ecam completions bash > ~/.local/share/bash-completion/completions/ecam`.
///
/// # Errors
/// When stdout cannot be written.
pub fn completions(args: &CompletionsArgs) -> anyhow::Result<()> {
    let mut command = Cli::command();
    tracing::debug!("completions for {}", args.shell);
    let mut out = Vec::new();
    clap_complete::generate(args.shell, &mut command, "ecam", &mut out);
    let mut stdout = std::io::stdout().lock();
    stdout.write_all(&out)?;
    stdout.flush()?;
    Ok(())
}

/// Prints `ecam.1`, or writes every subcommand's page into `--dir`.
///
/// # Errors
/// When the output cannot be written.
pub fn man(args: &ManArgs) -> anyhow::Result<()> {
    let command = Cli::command();
    tracing::debug!(
        "man pages for {} commands",
        command.get_subcommands().count() + 1
    );
    match &args.dir {
        Some(dir) => {
            std::fs::create_dir_all(dir)
                .with_context(|| format!("cannot create {}", dir.display()))?;
            clap_mangen::generate_to(command, dir)
                .with_context(|| format!("cannot write man pages into {}", dir.display()))?;
        }
        None => {
            let mut out = Vec::new();
            clap_mangen::Man::new(command).render(&mut out)?;
            let mut stdout = std::io::stdout().lock();
            stdout.write_all(&out)?;
            stdout.flush()?;
        }
    }
    Ok(())
}
