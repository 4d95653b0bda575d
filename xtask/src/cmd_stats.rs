//! `cargo xtask stats` (not implemented yet).

/// Arguments of `cargo xtask stats`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stats` is not implemented yet")
}
