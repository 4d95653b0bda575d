//! `cargo xtask scenes` (not implemented yet).

/// Arguments of `cargo xtask scenes`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`scenes` is not implemented yet")
}
