//! `ecam serve` (being written).

/// Arguments of `ecam serve`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `ecam serve`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("ecam serve is not built yet")
}
