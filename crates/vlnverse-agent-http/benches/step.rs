//! What the HTTP agent adds to a step on the paper's rig (RGB 224x224, depth 256x256): the
//! observation as a pickle, base64 and JSON (`encode`), and a whole step against a loopback
//! server that answers at once (`round_trip`: encode, send, read the reply, map the action).
//! The agent's own thinking and the server's decoding are not in it; the Python reference
//! server's decoding is timed by `python3 crates/vlnverse-agent-http/benches/server_decode.py`.
//!
//! `cargo bench -p vlnverse-agent-http --bench step`

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpListener;

use criterion::{criterion_group, criterion_main, Criterion};
use vlnverse_agent_http::{EpisodeStart, HttpAgent, HttpAgentConfig};
use vlnverse_env::Pose;
use vlnverse_eval::{ActionSpace, StepInput, SubGoalProgress};
use vlnverse_sensors::{Frame, Observation, Observations};

/// A keep-alive server answering every request with a fixed reply.
fn server() -> String {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    std::thread::spawn(move || {
        for stream in listener.incoming().flatten() {
            std::thread::spawn(move || {
                // One write per reply and no Nagle: the client's delayed ACK must not be timed.
                let _ = stream.set_nodelay(true);
                let mut out = stream.try_clone().unwrap();
                let mut r = BufReader::new(stream);
                loop {
                    let mut line = String::new();
                    if r.read_line(&mut line).unwrap_or(0) == 0 {
                        return;
                    }
                    let mut len = 0;
                    loop {
                        let mut h = String::new();
                        if r.read_line(&mut h).unwrap_or(0) == 0 {
                            return;
                        }
                        if h.trim().is_empty() {
                            break;
                        }
                        if let Some(v) = h.to_ascii_lowercase().strip_prefix("content-length:") {
                            len = v.trim().parse().unwrap();
                        }
                    }
                    let mut body = vec![0; len];
                    r.read_exact(&mut body).unwrap();
                    let reply = if line.contains("/init") {
                        r#"{"agent_name": "bench"}"#
                    } else {
                        r#"{"action": [[1]]}"#
                    };
                    let head = format!(
                        "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
                        reply.len()
                    );
                    if out.write_all(format!("{head}{reply}").as_bytes()).is_err() {
                        return;
                    }
                }
            });
        }
    });
    url
}

fn observations() -> Observations {
    let rgb = Frame {
        width: 224,
        height: 224,
        rgb: (0..224 * 224 * 3).map(|i| (i * 7 % 251) as u8).collect(),
        ..Default::default()
    };
    let depth = Frame {
        width: 256,
        height: 256,
        depth: (0..256 * 256).map(|i| (i % 1000) as f32 / 1000.0).collect(),
        ..Default::default()
    };
    let mut obs = Observations::new();
    obs.insert("rgb".into(), Observation::Rgb(rgb));
    obs.insert("depth".into(), Observation::Depth(depth));
    obs
}

fn bench(c: &mut Criterion) {
    let url = server();
    let mut agent = HttpAgent::connect(HttpAgentConfig::new(url, "bench")).unwrap();
    agent
        .begin(EpisodeStart {
            id: 1,
            instruction: "Walk past the sofa and stop at the lamp.".into(),
            start: Pose::IDENTITY,
            step_size: 0.25,
            turn: 15f32.to_radians(),
            action_space: ActionSpace::Discrete,
        })
        .unwrap();
    let obs = observations();
    let step = StepInput {
        step: 3,
        observations: &obs,
        pose: Pose::IDENTITY,
        last: None,
        sub_goal: SubGoalProgress {
            current: 0,
            total: 1,
        },
        oracle: None,
    };
    let mut g = c.benchmark_group("http_agent");
    g.bench_function("encode", |b| b.iter(|| agent.step_body(&step).len()));
    g.bench_function("round_trip", |b| b.iter(|| agent.step(&step).unwrap()));
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
