//! `cargo xtask import` (not implemented yet).

/// Arguments of `cargo xtask import`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`import` is not implemented yet")
}
