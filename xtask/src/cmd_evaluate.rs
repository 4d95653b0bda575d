//! `cargo xtask evaluate` (not implemented yet).

/// Arguments of `cargo xtask evaluate`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`evaluate` is not implemented yet")
}
