//! `ecam simulate` (being written).

/// Arguments of `ecam simulate`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `ecam simulate`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("ecam simulate is not built yet")
}
