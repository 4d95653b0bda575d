//! `cargo xtask serve`: the local web app (drive, replay, review).
//! (Being written for issue 15; the arguments and the server land with it.)

/// Arguments of `cargo xtask serve`.
#[derive(clap::Args, Debug)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`serve` is not available yet")
}
