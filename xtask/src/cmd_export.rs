//! `cargo xtask export`: observations along teacher trajectories as an offline dataset.
//! (Being written for issue 14; the arguments and the writer land with it.)

/// Arguments of `cargo xtask export`.
#[derive(clap::Args, Debug)]
pub struct Args {}

/// Run the command.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`export` is not available yet")
}
