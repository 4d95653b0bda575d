//! `cargo xtask score` (not implemented yet).

/// Arguments of `cargo xtask score`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`score` is not implemented yet")
}
