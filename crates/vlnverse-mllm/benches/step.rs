//! Simulator-side cost of one MLLM step, the model left out: render the agent's cameras (CPU
//! rasteriser), update and draw the map, encode the pictures, build the request. A backend that
//! answers at once with one primitive makes every step a decision (the most work per step).
//! One worker thread; throughput is in steps, so criterion's time per element is ms per step.
//!
//! `cargo bench -p vlnverse-mllm --bench step -- --warm-up-time 1 --measurement-time 5`

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use vlnverse_eval::{evaluate, EvalConfig, EvalRequest, Result};
use vlnverse_instructions::llm::{ChatMessage, ChatReply, Usage};
use vlnverse_mllm::{ChatBackend, History, MllmConfig, MllmFactory, View};
use vlnverse_score::{Split, Task};

/// Answers at once: a forward step, then a turn, in turn (never stop).
struct Instant(AtomicU64);

impl ChatBackend for Instant {
    fn chat(&self, messages: &[ChatMessage], _seed: u64) -> Result<ChatReply> {
        std::hint::black_box(messages);
        let k = self.0.fetch_add(1, Ordering::Relaxed);
        Ok(ChatReply {
            text: if k % 3 == 2 {
                "turn left 15 degrees"
            } else {
                "move forward 25 cm"
            }
            .into(),
            usage: Some(Usage::default()),
            cached: false,
            attempts: 1,
            latency: Duration::ZERO,
        })
    }
}

const STEPS: u32 = 100;
const EPISODES: usize = 2;

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    vlnverse_testkit::datasets::make_dataset(dir.path(), Task::Fine, 1, EPISODES, 3);
    std::fs::write(
        dir.path().join("rig.toml"),
        "backend = \"raster\"\n[[sensors]]\ntype = \"compass\"\n",
    )
    .unwrap();
    let run = AtomicU64::new(0);
    let mut g = c.benchmark_group("mllm_step");
    g.sample_size(10);
    g.throughput(Throughput::Elements(u64::from(STEPS) * EPISODES as u64));
    let cases = [
        ("text_current_png", History::Text, View::Current),
        ("map_current_png", History::Map, View::Current),
        ("map_panorama4_png", History::Map, View::Panorama4),
        // The map alone, no camera picture: the cost of the map and its encoding.
        ("map_none_png", History::Map, View::None),
    ];
    for (name, history, view) in cases {
        let cfg = MllmConfig {
            history,
            view,
            endpoint: "http://127.0.0.1:9/v1".into(),
            model: "bench".into(),
            cache: false,
            ..Default::default()
        };
        g.bench_function(BenchmarkId::from_parameter(name), |b| {
            b.iter(|| {
                let out = dir
                    .path()
                    .join(format!("run{}", run.fetch_add(1, Ordering::Relaxed)));
                let req = EvalRequest::new(dir.path().to_path_buf(), Task::Fine, Split::Test, out)
                    .threads(1)
                    .config(EvalConfig {
                        max_steps: STEPS,
                        setting: vlnverse_eval::Setting::Lenient,
                        plots: 0,
                        rig: dir.path().join("rig.toml").display().to_string(),
                        ..Default::default()
                    });
                let f =
                    MllmFactory::with_backend(cfg.clone(), Arc::new(Instant(AtomicU64::new(0))));
                let o = evaluate(&req, &f).unwrap();
                assert_eq!(o.steps_run, u64::from(STEPS) * EPISODES as u64);
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
