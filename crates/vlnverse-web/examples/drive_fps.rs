//! Drive episodes over the WebSocket as the page does and measure what the page gets: frames
//! per second per driver (one driver alone, then several at once) and the server's resident
//! memory per connected driver.
//!
//! ```sh
//! cargo run --release -p vlnverse-web --example drive_fps -- datasets/tiny fine val_unseen 4
//! ```
//!
//! The server runs in this process (so its memory is this process's), on a free port of
//! 127.0.0.1; every driver follows the teacher's hints (`teacher_hints`) to the end of its
//! episode.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use futures_util::{SinkExt, StreamExt};
use serde_json::{json, Value};
use tokio_tungstenite::tungstenite::Message;
use vlnverse_web::{rss_bytes, App, ServerConfig};

/// What was measured.
#[derive(Debug, Clone)]
pub struct Figures {
    /// Frames per second one driver alone receives.
    pub fps_alone: f64,
    /// Frames per second each of `drivers` concurrent drivers receives (mean).
    pub fps_each_concurrent: f64,
    /// Drivers driven at once.
    pub drivers: usize,
    /// Server memory growth per connected driver (bytes; None off Linux).
    pub rss_per_driver: Option<f64>,
    /// Frames received in all.
    pub frames: usize,
}

type Ws =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

async fn next_state(ws: &mut Ws) -> Result<Value, String> {
    loop {
        let m = ws
            .next()
            .await
            .ok_or("connection closed")?
            .map_err(|e| e.to_string())?;
        if let Message::Text(t) = m {
            let v: Value = serde_json::from_str(&t).map_err(|e| e.to_string())?;
            if v["type"] == "error" {
                return Err(v["error"].to_string());
            }
            // The frame follows its state.
            ws.next()
                .await
                .ok_or("connection closed")?
                .map_err(|e| e.to_string())?;
            return Ok(v);
        }
    }
}

async fn connect(
    addr: SocketAddr,
    task: &str,
    split: &str,
    id: u64,
) -> Result<(Ws, Value), String> {
    let url =
        format!("ws://{addr}/api/drive?task={task}&split={split}&episode={id}&setting=telhop");
    let (mut ws, _) = tokio_tungstenite::connect_async(url)
        .await
        .map_err(|e| e.to_string())?;
    let first = next_state(&mut ws).await?;
    Ok((ws, first))
}

/// Follow the teacher to the end of the episode; returns (frames, seconds).
async fn follow(ws: &mut Ws, mut s: Value) -> Result<(usize, f64), String> {
    let t0 = Instant::now();
    let mut frames = 0;
    while !s["done"].as_bool().unwrap_or(true) {
        let k = s["expert_key"]
            .as_str()
            .ok_or("no teacher hint")?
            .to_string();
        ws.send(Message::Text(json!({ "key": k }).to_string().into()))
            .await
            .map_err(|e| e.to_string())?;
        s = next_state(ws).await?;
        frames += 1;
    }
    Ok((frames, t0.elapsed().as_secs_f64()))
}

/// Measure on `dataset` (`protocol_dir`: protocol files, e.g. `configs/eval`).
pub fn run(
    dataset: &Path,
    task: &str,
    split: &str,
    drivers: usize,
    protocol_dir: Option<PathBuf>,
) -> Result<Figures, String> {
    let out = tempfile::tempdir().map_err(|e| e.to_string())?;
    let cfg = ServerConfig {
        out: out.path().to_path_buf(),
        protocol_dir,
        teacher_hints: true,
        max_drivers: drivers + 1,
        ..ServerConfig::new(dataset)
    };
    let app = Arc::new(App::new(cfg)?);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| e.to_string())?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0")
            .await
            .map_err(|e| e.to_string())?;
        let addr = listener.local_addr().map_err(|e| e.to_string())?;
        let ids: Vec<u64> = app
            .episodes(
                task.parse().map_err(|e| format!("{e}"))?,
                split.parse().map_err(|e| format!("{e}"))?,
            )
            .map_err(|e| e.message)?
            .iter()
            .map(|e| e.episode_id)
            .collect();
        tokio::spawn(vlnverse_web::serve_on(
            app.clone(),
            listener,
            std::future::pending(),
        ));
        // One driver alone (a warm-up episode first: scene caches, renderer start-up).
        let (mut ws, s) = connect(addr, task, split, ids[0]).await?;
        follow(&mut ws, s).await?;
        let (mut ws, s) = connect(addr, task, split, ids[0]).await?;
        let (frames_alone, secs) = follow(&mut ws, s).await?;
        drop(ws);
        // Memory: connected drivers holding their simulators.
        tokio::time::sleep(std::time::Duration::from_millis(300)).await;
        let before = rss_bytes();
        let mut held = Vec::new();
        for i in 0..drivers {
            held.push(connect(addr, task, split, ids[i % ids.len()]).await?);
        }
        let after = rss_bytes();
        // Then all of them driving at once.
        let tasks: Vec<_> = held
            .into_iter()
            .map(|(mut ws, s)| tokio::spawn(async move { follow(&mut ws, s).await }))
            .collect();
        let mut fps = Vec::new();
        let mut frames = frames_alone;
        for t in tasks {
            let (f, s) = t.await.map_err(|e| e.to_string())??;
            frames += f;
            fps.push(f as f64 / s.max(1e-9));
        }
        Ok(Figures {
            fps_alone: frames_alone as f64 / secs.max(1e-9),
            fps_each_concurrent: fps.iter().sum::<f64>() / fps.len().max(1) as f64,
            drivers,
            rss_per_driver: match (before, after) {
                (Some(b), Some(a)) => Some((a as f64 - b as f64) / drivers.max(1) as f64),
                _ => None,
            },
            frames,
        })
    })
}

#[allow(dead_code)]
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let dataset = PathBuf::from(args.first().map_or("datasets/tiny", String::as_str));
    let task = args.get(1).map_or("fine", String::as_str);
    let split = args.get(2).map_or("val_unseen", String::as_str);
    let drivers: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(4);
    let protocols = Path::new("configs/eval");
    let protocols = protocols.is_dir().then(|| protocols.to_path_buf());
    match run(&dataset, task, split, drivers, protocols) {
        Ok(f) => {
            println!("frames/s received by one driver alone: {:.1}", f.fps_alone);
            println!(
                "frames/s received by each of {} drivers at once: {:.1}",
                f.drivers, f.fps_each_concurrent
            );
            match f.rss_per_driver {
                Some(b) => println!(
                    "server memory per connected driver: {:.1} MiB",
                    b / 1048576.0
                ),
                None => println!("server memory per connected driver: unknown (no /proc)"),
            }
        }
        Err(e) => {
            eprintln!("drive_fps: {e}");
            std::process::exit(1);
        }
    }
}
