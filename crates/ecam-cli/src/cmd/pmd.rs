//! `ecam pmd`: the motion-processor face (document 002).
//!
//! `ecam pmd run SCRIPT` runs a command script in simulated time and prints
//! one JSON object per line for every `Get…` command and for every line
//! that was refused (`{"cmd":…,"axis":…,"line":…,"error":"…"}`); the script
//! goes on after a refused line. See `docs/pmd.md`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::Context;

/// Subcommands of `ecam pmd`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Run a motion-processor command script in simulated time.
    Run(RunArgs),
}

/// Arguments of `ecam pmd run`.
#[derive(clap::Args)]
pub struct RunArgs {
    /// The script: one command per line; `'` starts a comment.
    #[arg(value_hint = clap::ValueHint::FilePath)]
    pub script: PathBuf,
    /// Give a symbolic value in the script a number, e.g. `cam_table_0=120`
    /// (same as a `Define cam_table_0 120` line at the top).
    #[arg(long = "define", value_name = "NAME=VALUE", value_parser = crate::values::define)]
    pub defines: Vec<(String, i64)>,
    /// Stop at the first refused line with a non-zero exit.
    #[arg(long)]
    pub strict: bool,
}

/// Runs `ecam pmd`.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Run(args) => run_script(&args),
    }
}

fn run_script(args: &RunArgs) -> anyhow::Result<()> {
    let text = std::fs::read_to_string(&args.script)
        .with_context(|| format!("cannot read script {}", args.script.display()))?;
    tracing::debug!("{}: {} lines", args.script.display(), text.lines().count());
    let mut runner = ecam_pmd::ScriptRunner::new();
    for (name, value) in &args.defines {
        runner.define(name, *value);
    }
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    for (i, line) in text.lines().enumerate() {
        let line_no = i.saturating_add(1);
        if let Some(report) = runner.run_line(line_no, line) {
            writeln!(out, "{}", report.to_json())?;
            if args.strict
                && let ecam_pmd::Report::Error { message, .. } = &report
            {
                out.flush()?;
                anyhow::bail!("{}:{line_no}: {message}", args.script.display());
            }
        }
    }
    out.flush()?;
    Ok(())
}
