//! Shared fixtures: a one-home dataset with fine-grained episodes, a small fast rig, a server
//! on a free port, a raw HTTP client (it sends paths exactly as written, `..` included) and a
//! WebSocket driver.
#![allow(dead_code)]

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec2, Vec3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde_json::Value;
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio_tungstenite::tungstenite::Message;
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::io::write_scene_bundle;
use vlnverse_env::occupancy::OccupancyConfig;
use vlnverse_env::Pose;
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_task::{dataset, Episode, EpisodeInfo, Goal, Instruction, Split, Task};
use vlnverse_web::{App, ServerConfig};

/// Write one tiny home and `n` fine-grained `val_unseen` episodes (4 to 10 m) under `dir`, plus
/// protocol files (`dir/protocols/{strict,telhop}.toml`) on a small ray-cast rig.
pub fn make_dataset(dir: &Path, n: usize) -> Vec<Episode> {
    let gen = HomeGenerator::from_preset(Preset::Tiny).unwrap();
    let scene = gen.generate(7, "tiny_000").unwrap();
    let (bundle, _) =
        write_scene_bundle(dir.join("scenes"), scene, &OccupancyConfig::default()).unwrap();
    let nav = &bundle.maps.navigable;
    let free: Vec<Vec2> = nav
        .free_cells()
        .map(|(c, r)| nav.cell_center(c, r))
        .collect();
    let y = bundle.scene.floor_height;
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let mut eps = Vec::new();
    let mut tries = 0;
    while eps.len() < n && tries < 20_000 {
        tries += 1;
        let a = free[rng.random_range(0..free.len())];
        let b = free[rng.random_range(0..free.len())];
        let Ok(Some(path)) = shortest_path(nav, a, b) else {
            continue;
        };
        if !(4.0..=10.0).contains(&path.length) {
            continue;
        }
        let id = eps.len() as u64 + 1;
        let start = Pose::from_yaw(Vec3::new(a.x, y, a.y), rng.random_range(-3.0..3.0));
        let end = *path.points.last().unwrap();
        eps.push(Episode {
            episode_id: id,
            trajectory_id: id,
            scene_id: bundle.scene.id.clone(),
            start_position: start.position,
            start_rotation: start.rotation,
            goals: vec![Goal {
                position: [end.x, y, end.y],
                radius: 3.0,
                object_id: None,
            }],
            instruction: Instruction {
                instruction_text: format!("Walk to goal number {id}."),
                ..Default::default()
            },
            reference_path: path.points.iter().map(|p| [p.x, y, p.y]).collect(),
            info: EpisodeInfo {
                geodesic_distance: path.length,
                ..Default::default()
            },
            task: Task::Fine,
            ..Default::default()
        });
    }
    assert_eq!(eps.len(), n, "fixture: not enough episodes");
    dataset::write_split(dir, Task::Fine, Split::ValUnseen, &eps).unwrap();
    // The same paths as dialogue episodes with an oracle budget of 2 questions.
    let dialogue: Vec<Episode> = eps
        .iter()
        .map(|e| Episode {
            task: Task::Dialogue,
            oracle_budget: Some(2),
            ..e.clone()
        })
        .collect();
    dataset::write_split(dir, Task::Dialogue, Split::ValUnseen, &dialogue).unwrap();
    let protocols = dir.join("protocols");
    std::fs::create_dir_all(&protocols).unwrap();
    std::fs::write(
        protocols.join("small_rig.toml"),
        "backend = \"raycast\"\nseed = 0\n\n[[sensors]]\ntype = \"rgb\"\nwidth = 48\nheight = 36\nhfov_deg = 90.0\n\n[[sensors]]\ntype = \"depth\"\nwidth = 48\nheight = 36\nhfov_deg = 90.0\n",
    )
    .unwrap();
    for setting in ["strict", "telhop"] {
        std::fs::write(
            protocols.join(format!("{setting}.toml")),
            format!("setting = \"{setting}\"\nrig = \"small_rig.toml\"\nmax_steps = 200\n"),
        )
        .unwrap();
    }
    eps
}

/// A running server.
pub struct Server {
    pub addr: SocketAddr,
    pub app: Arc<App>,
    stop: Option<tokio::sync::oneshot::Sender<()>>,
    task: Option<tokio::task::JoinHandle<std::io::Result<()>>>,
}

impl Server {
    pub async fn start(cfg: ServerConfig) -> Server {
        let app = Arc::new(App::new(cfg).unwrap());
        let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
        let addr = listener.local_addr().unwrap();
        let (tx, rx) = tokio::sync::oneshot::channel();
        let task = tokio::spawn(vlnverse_web::serve_on(app.clone(), listener, async move {
            let _ = rx.await;
        }));
        Server {
            addr,
            app,
            stop: Some(tx),
            task: Some(task),
        }
    }

    pub async fn stop(mut self) {
        if let Some(s) = self.stop.take() {
            let _ = s.send(());
        }
        if let Some(t) = self.task.take() {
            let _ = tokio::time::timeout(std::time::Duration::from_secs(10), t).await;
        }
    }

    /// `GET path` exactly as written: (status, body).
    pub async fn get(&self, path: &str) -> (u16, Vec<u8>) {
        self.request("GET", path, None).await
    }

    /// `GET path` expecting JSON.
    pub async fn get_json(&self, path: &str) -> (u16, Value) {
        let (s, b) = self.get(path).await;
        let v = serde_json::from_slice(&b)
            .unwrap_or_else(|e| panic!("{path}: not JSON ({e}): {}", String::from_utf8_lossy(&b)));
        (s, v)
    }

    /// `POST path` with a JSON body.
    pub async fn post_json(&self, path: &str, body: &Value) -> (u16, Value) {
        let (s, b) = self.request("POST", path, Some(body.to_string())).await;
        (s, serde_json::from_slice(&b).unwrap_or(Value::Null))
    }

    /// Any method and body, exactly as written: (status, body).
    pub async fn raw(&self, method: &str, path: &str, body: Option<String>) -> (u16, Vec<u8>) {
        self.request(method, path, body).await
    }

    async fn request(&self, method: &str, path: &str, body: Option<String>) -> (u16, Vec<u8>) {
        let mut s = tokio::net::TcpStream::connect(self.addr).await.unwrap();
        let body = body.unwrap_or_default();
        let req = format!(
            "{method} {path} HTTP/1.1\r\nHost: {}\r\nConnection: close\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
            self.addr,
            body.len()
        );
        s.write_all(req.as_bytes()).await.unwrap();
        let mut buf = Vec::new();
        s.read_to_end(&mut buf).await.unwrap();
        let head_end = buf
            .windows(4)
            .position(|w| w == b"\r\n\r\n")
            .expect("an HTTP response");
        let head = String::from_utf8_lossy(&buf[..head_end]).to_string();
        let status: u16 = head.split_whitespace().nth(1).unwrap().parse().unwrap();
        let mut body = buf[head_end + 4..].to_vec();
        if head
            .to_ascii_lowercase()
            .contains("transfer-encoding: chunked")
        {
            body = dechunk(&body);
        }
        (status, body)
    }
}

fn dechunk(mut b: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    loop {
        let Some(eol) = b.windows(2).position(|w| w == b"\r\n") else {
            return out;
        };
        let n = usize::from_str_radix(std::str::from_utf8(&b[..eol]).unwrap().trim(), 16).unwrap();
        if n == 0 {
            return out;
        }
        out.extend_from_slice(&b[eol + 2..eol + 2 + n]);
        b = &b[eol + 2 + n + 2..];
    }
}

/// Server config for a fixture dataset in `dir` (logs in `dir/out`, teacher hints on).
pub fn config(dir: &Path) -> ServerConfig {
    ServerConfig {
        out: dir.join("out"),
        protocol_dir: Some(dir.join("protocols")),
        teacher_hints: true,
        ..ServerConfig::new(dir)
    }
}

type Ws =
    tokio_tungstenite::WebSocketStream<tokio_tungstenite::MaybeTlsStream<tokio::net::TcpStream>>;

/// A drive connection.
pub struct Driver {
    pub ws: Ws,
    /// States received (the first is the start).
    pub states: Vec<Value>,
    /// Frames received (JPEG bytes).
    pub frames: usize,
}

impl Driver {
    pub async fn connect(addr: SocketAddr, query: &str) -> Driver {
        let url = format!("ws://{addr}/api/drive?{query}");
        let (ws, _) = tokio_tungstenite::connect_async(url).await.unwrap();
        let mut d = Driver {
            ws,
            states: Vec::new(),
            frames: 0,
        };
        d.next_state().await;
        d
    }

    /// Read until the next state and its frame.
    pub async fn next_state(&mut self) -> Value {
        use futures_util::StreamExt;
        loop {
            let msg = tokio::time::timeout(std::time::Duration::from_secs(60), self.ws.next())
                .await
                .expect("a reply within 60 s")
                .expect("the connection is open")
                .unwrap();
            match msg {
                Message::Text(t) => {
                    let v: Value = serde_json::from_str(&t).unwrap();
                    match v["type"].as_str() {
                        Some("state") => {
                            // Its frame follows.
                            let f = tokio::time::timeout(
                                std::time::Duration::from_secs(60),
                                self.ws.next(),
                            )
                            .await
                            .unwrap()
                            .unwrap()
                            .unwrap();
                            match f {
                                Message::Binary(b) => {
                                    assert_eq!(&b[..2], &[0xFF, 0xD8], "a JPEG frame");
                                    self.frames += 1;
                                }
                                other => panic!("expected a frame, got {other:?}"),
                            }
                            self.states.push(v.clone());
                            return v;
                        }
                        _ => return v,
                    }
                }
                Message::Close(_) => panic!("closed"),
                _ => {}
            }
        }
    }

    pub async fn send(&mut self, v: Value) {
        use futures_util::SinkExt;
        self.ws
            .send(Message::Text(v.to_string().into()))
            .await
            .unwrap();
    }

    /// Press a key and wait for the state it produced.
    pub async fn key(&mut self, k: &str) -> Value {
        self.send(serde_json::json!({ "key": k })).await;
        self.next_state().await
    }

    /// Follow the teacher's hints to the end; returns the final state.
    pub async fn follow_teacher(&mut self) -> Value {
        let mut s = self.states.last().cloned().unwrap();
        for _ in 0..400 {
            if s["done"].as_bool().unwrap() {
                return s;
            }
            let k = s["expert_key"].as_str().unwrap().to_string();
            s = self.key(&k).await;
        }
        panic!("the teacher did not finish in 400 steps");
    }
}

pub fn fine_query(id: u64) -> String {
    format!("task=fine&split=val_unseen&episode={id}&setting=strict")
}

pub fn drive_dir(dir: &Path) -> PathBuf {
    dir.join("out/drives/fine/val_unseen")
}
