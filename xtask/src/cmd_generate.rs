//! `cargo xtask generate` (not implemented yet).

/// Arguments of `cargo xtask generate`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`generate` is not implemented yet")
}
