//! `ecam mc run`: the motion-controller face (document 001) from a script.
//! See docs/mc.md, "Scripts".

use std::io::Write;
use std::path::PathBuf;

/// Subcommands of `ecam mc`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Run a motion-controller script (document 001's E-CAM) in simulated
    /// time; prints one JSON object per line for every Get command.
    Run(RunArgs),
}

/// Arguments of `ecam mc run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// The script: one command per line; `'` starts a comment.
    #[arg(value_hint = clap::ValueHint::FilePath)]
    pub script: PathBuf,
}

/// Runs `ecam mc`.
pub fn run(command: Command) -> anyhow::Result<()> {
    let Command::Run(args) = command;
    tracing::debug!("script {}", args.script.display());
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut written = Ok(());
    // What ran before an error stands: its lines are printed, then the
    // error (SCRIPT:LINE: message) goes to stderr.
    let result = ecam_mc::script::run_file_with(&args.script, |report| {
        if written.is_ok() {
            written = writeln!(out, "{report}");
        }
    });
    out.flush()?;
    result?;
    written?;
    Ok(())
}
