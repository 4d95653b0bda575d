//! `cargo xtask serve`: the local web app (drive episodes with the keyboard, replay evaluation
//! runs, review generated episodes); see docs/web.md.

use std::net::{IpAddr, SocketAddr};
use std::path::PathBuf;

use vlnverse_web::ServerConfig;

/// Arguments of `cargo xtask serve`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Dataset folder (holds `<task>/<split>/<split>.json.gz` and `scenes/`).
    #[arg(long)]
    pub dataset: PathBuf,
    /// Evaluation run folders to replay (written by `cargo xtask evaluate` or `score`).
    #[arg(long, num_args = 1..)]
    pub runs: Vec<PathBuf>,
    /// Port (0 picks a free one; the URL printed names it).
    #[arg(long, default_value_t = 8787)]
    pub port: u16,
    /// Address to bind; the default keeps the app on this machine.
    #[arg(long, default_value = "127.0.0.1")]
    pub host: IpAddr,
    /// Folder of the drive logs (`drives/<task>/<split>/`) and of the default review file.
    #[arg(long, default_value = "runs/web")]
    pub out: PathBuf,
    /// Review file (default `OUT/review.json`); `cargo xtask review --decisions` applies it.
    #[arg(long)]
    pub review_file: Option<PathBuf>,
    /// Folder of the protocol files `<setting>.toml`.
    #[arg(long, default_value = "configs/eval")]
    pub protocols: PathBuf,
    /// Renderer backend override: auto, wgpu, raster or raycast.
    #[arg(long)]
    pub backend: Option<vlnverse_sensors::Backend>,
    /// Most drivers (one simulator each) at once.
    #[arg(long, default_value_t = 16)]
    pub max_drivers: usize,
    /// Show the teacher's next key while driving (tests, demonstrations; not for a human study).
    #[arg(long)]
    pub teacher_hints: bool,
    /// Also answer requests for this host name (repeatable; `NAME` or `NAME:PORT`). Only
    /// 127.0.0.1, localhost, `[::1]` and the bound address are answered otherwise (DNS rebinding).
    #[arg(long = "allow-host", value_name = "NAME")]
    pub allow_host: Vec<String>,
}

/// Run the command.
pub fn run(args: Args) -> anyhow::Result<()> {
    if !args.host.is_loopback() {
        tracing::warn!(
            "binding {}: the app is reachable from other machines and has no authentication",
            args.host
        );
    }
    let cfg = ServerConfig {
        runs: args.runs,
        out: args.out,
        review_file: args.review_file,
        protocol_dir: Some(args.protocols),
        backend: args.backend,
        teacher_hints: args.teacher_hints,
        max_drivers: args.max_drivers.max(1),
        ..ServerConfig::new(args.dataset)
    };
    let addr = SocketAddr::new(args.host, args.port);
    vlnverse_web::server::run_server_with(cfg, addr, &args.allow_host, |bound| {
        // The tests read this line to find the port.
        println!("vlnverse web app: open http://{bound}/  (Ctrl-C stops it)");
        use std::io::Write as _;
        let _ = std::io::stdout().flush();
    })
    .map_err(anyhow::Error::msg)
}
