//! `ecam law` (being written).

/// Arguments of `ecam law`.
#[derive(clap::Args)]
pub struct Args {}

/// Runs `ecam law`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("ecam law is not built yet")
}
