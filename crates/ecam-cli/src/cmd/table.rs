//! `ecam table` (being written).

/// Subcommands of `ecam table`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Placeholder while being written.
    Pending,
}

/// Runs `ecam table`.
pub fn run(_command: Command) -> anyhow::Result<()> {
    anyhow::bail!("ecam table is not built yet")
}
