//! Test scenes for the instruction and oracle tests: the tiny preset's homes with maps, graph
//! and random shortest paths between navigable points.

#![allow(dead_code)]

use glam::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpListener;
use std::sync::{Arc, Mutex};
use vlnverse_env::geodesic::shortest_path;
use vlnverse_env::occupancy::{build_maps, GridMap, OccupancyConfig, OccupancyMaps};
use vlnverse_env::scene_graph::{yaw_from_direction, SceneGraph};
use vlnverse_env::{Scene, SceneSource};
use vlnverse_procgen::{HomeGenerator, Preset};
use vlnverse_task::instructions::PathContext;

/// A scene with its maps and graph.
pub struct World {
    pub scene: Scene,
    pub maps: OccupancyMaps,
    pub graph: SceneGraph,
}

/// A sampled path.
pub struct Sample {
    pub path: Vec<[f32; 3]>,
    pub start_yaw: f32,
}

impl World {
    pub fn ctx<'a>(&'a self, s: &'a Sample) -> PathContext<'a> {
        PathContext {
            scene: &self.scene,
            graph: &self.graph,
            navigable: &self.maps.navigable,
            path: &s.path,
            start_yaw: s.start_yaw,
        }
    }
}

/// The first `n` homes of the tiny preset.
pub fn worlds(n: usize) -> Vec<World> {
    let homes = HomeGenerator::from_preset(Preset::Tiny).expect("tiny preset");
    (0..n.min(homes.len()))
        .map(|i| {
            let scene = homes.scene(i).expect("tiny scene");
            let maps = build_maps(&scene, &OccupancyConfig::default()).expect("maps");
            let graph = SceneGraph::build(&scene);
            World { scene, maps, graph }
        })
        .collect()
}

/// A random free point of the map.
pub fn random_free(map: &GridMap, rng: &mut ChaCha8Rng) -> Vec2 {
    let free: Vec<(u32, u32)> = map.free_cells().collect();
    let (c, r) = free[rng.random_range(0..free.len())];
    map.cell_center(c, r)
}

/// `count` shortest paths between random navigable points at least 3 m apart; the start yaw is
/// random.
pub fn paths(w: &World, count: usize, seed: u64) -> Vec<Sample> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let map = &w.maps.navigable;
    let free: Vec<(u32, u32)> = map.free_cells().collect();
    let mut out = Vec::new();
    let mut tries = 0;
    while out.len() < count && tries < count * 50 {
        tries += 1;
        let (c, r) = free[rng.random_range(0..free.len())];
        let a = map.cell_center(c, r);
        let (c, r) = free[rng.random_range(0..free.len())];
        let b = map.cell_center(c, r);
        if a.distance(b) < 3.0 {
            continue;
        }
        let Some(p) = shortest_path(map, a, b).expect("finite points") else {
            continue;
        };
        let start_yaw = rng.random_range(-std::f32::consts::PI..std::f32::consts::PI);
        out.push(Sample {
            path: p.points.iter().map(|q| [q.x, 0.0, q.y]).collect(),
            start_yaw,
        });
    }
    out
}

/// Goal target: the non-structure object whose footprint is closest to the path's end (for
/// coarse tests), if it has a unique description.
pub fn yaw_along(a: Vec2, b: Vec2) -> f32 {
    yaw_from_direction(b - a)
}

/// A local stub of an OpenAI-compatible chat endpoint: one connection per reply, in order,
/// `(status, assistant content)`; returns the base URL and the requests received.
/// A request the stub received.
#[derive(Clone, Debug)]
pub struct Seen {
    pub request_line: String,
    pub authorization: Option<String>,
    pub body: serde_json::Value,
}

pub fn stub(replies: Vec<(u16, String)>) -> (String, Arc<Mutex<Vec<Seen>>>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}/v1", listener.local_addr().unwrap());
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    std::thread::spawn(move || {
        for (status, content) in replies {
            let Ok((stream, _)) = listener.accept() else {
                return;
            };
            let mut reader = BufReader::new(stream.try_clone().unwrap());
            let mut request_line = String::new();
            reader.read_line(&mut request_line).unwrap();
            let (mut len, mut auth) = (0usize, None);
            loop {
                let mut line = String::new();
                reader.read_line(&mut line).unwrap();
                let line = line.trim_end();
                if line.is_empty() {
                    break;
                }
                let lower = line.to_ascii_lowercase();
                if let Some(v) = lower.strip_prefix("content-length:") {
                    len = v.trim().parse().unwrap();
                }
                if lower.starts_with("authorization:") {
                    auth = Some(line["authorization:".len()..].trim().to_string());
                }
            }
            let mut body = vec![0u8; len];
            reader.read_exact(&mut body).unwrap();
            log.lock().unwrap().push(Seen {
                request_line: request_line.trim_end().to_string(),
                authorization: auth,
                body: serde_json::from_slice(&body).unwrap(),
            });
            let payload = if status == 200 {
                serde_json::json!({
                    "id": "stub", "object": "chat.completion",
                    "choices": [{"index": 0, "finish_reason": "stop",
                                 "message": {"role": "assistant", "content": content}}]
                })
                .to_string()
            } else {
                format!("{{\"error\": \"{content}\"}}")
            };
            let mut out = stream;
            write!(
                out,
                "HTTP/1.1 {status} X\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{payload}",
                payload.len()
            )
            .unwrap();
            out.flush().unwrap();
        }
    });
    (url, seen)
}
