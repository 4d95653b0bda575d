//! A scripted OpenAI-compatible chat endpoint on loopback: try `--agent mllm` without a model.
//!
//! ```text
//! cargo run -p vlnverse-mllm --example scripted_server -- [--port 8011] [--script FILE]
//! cargo xtask evaluate --agent mllm --mllm-endpoint http://127.0.0.1:8011/v1 --mllm-model scripted ...
//! ```
//!
//! Without `--script` it serves `examples/walk.toml` (a random-looking but repeatable walk:
//! moves, turns, an unreadable reply now and then, questions in dialogue episodes, stops).
//! It runs until killed and prints a line per 50 requests.

use std::time::Duration;

use vlnverse_mllm::scripted::{Script, ScriptedServer};

const DEFAULT_SCRIPT: &str = include_str!("walk.toml");

fn main() {
    let mut port = 8011u16;
    let mut script_text = DEFAULT_SCRIPT.to_string();
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match (a.as_str(), args.next()) {
            ("--port", Some(p)) => match p.parse() {
                Ok(p) => port = p,
                Err(e) => fail(&format!("--port {p}: {e}")),
            },
            ("--script", Some(f)) => match std::fs::read_to_string(&f) {
                Ok(t) => script_text = t,
                Err(e) => fail(&format!("--script {f}: {e}")),
            },
            _ => fail("usage: scripted_server [--port N] [--script FILE]"),
        }
    }
    let script = Script::parse(&script_text).unwrap_or_else(|e| fail(&format!("script: {e}")));
    let server = ScriptedServer::start(script, port)
        .unwrap_or_else(|e| fail(&format!("127.0.0.1:{port}: {e}")));
    println!("scripted chat endpoint at {}", server.url);
    let mut last = 0;
    loop {
        std::thread::sleep(Duration::from_millis(500));
        let n = server
            .seen
            .requests
            .load(std::sync::atomic::Ordering::Relaxed);
        if n / 50 > last / 50 {
            println!("{n} requests");
        }
        last = n;
    }
}

fn fail(msg: &str) -> ! {
    eprintln!("scripted_server: {msg}");
    std::process::exit(2)
}
