//! `cargo xtask scene-info` (not implemented yet).

/// Arguments of `cargo xtask scene-info`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`scene-info` is not implemented yet")
}
