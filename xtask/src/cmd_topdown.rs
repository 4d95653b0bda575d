//! `cargo xtask topdown` (not implemented yet).

/// Arguments of `cargo xtask topdown`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`topdown` is not implemented yet")
}
