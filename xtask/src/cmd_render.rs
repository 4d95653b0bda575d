//! `cargo xtask render` (not implemented yet).

/// Arguments of `cargo xtask render`.
#[derive(clap::Args)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`render` is not implemented yet")
}
