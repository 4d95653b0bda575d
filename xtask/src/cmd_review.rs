//! `cargo xtask review`: apply review decisions to make a reviewed copy of a dataset.
//! (Being written for issue 15; the arguments land with it.)

/// Arguments of `cargo xtask review`.
#[derive(clap::Args, Debug)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`review` is not available yet")
}
