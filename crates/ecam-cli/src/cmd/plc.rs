//! `ecam plc` (being written).

/// Subcommands of `ecam plc`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Placeholder while being written.
    Pending,
}

/// Runs `ecam plc`.
pub fn run(_command: Command) -> anyhow::Result<()> {
    anyhow::bail!("ecam plc is not built yet")
}
