//! `ecam pmd` (being written).

/// Subcommands of `ecam pmd`.
#[derive(clap::Subcommand)]
pub enum Command {
    /// Placeholder while being written.
    Pending,
}

/// Runs `ecam pmd`.
pub fn run(_command: Command) -> anyhow::Result<()> {
    anyhow::bail!("ecam pmd is not built yet")
}
