//! `cargo xtask merge` (not implemented yet).

/// Arguments of `cargo xtask merge`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`merge` is not implemented yet")
}
