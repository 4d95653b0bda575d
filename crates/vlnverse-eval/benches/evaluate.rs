//! Evaluation throughput: agent steps per second of the oracle with the paper's RGB-D rig
//! (224x224 RGB + 256x256 depth rendered every step), all threads, on procgen `tiny` homes;
//! per renderer backend (`raycast`, and `auto` = wgpu on a GPU or lavapipe when present) and
//! setting, plus the protocol without rendering.
//!
//! `cargo bench -p vlnverse-eval --bench evaluate -- --warm-up-time 1 --measurement-time 3`

use std::sync::atomic::{AtomicU64, Ordering};

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use vlnverse_eval::agents::builtin;
use vlnverse_eval::{evaluate, ActionSpace, EvalConfig, EvalRequest, Setting};
use vlnverse_score::{Split, Task};
use vlnverse_sensors::Backend;

fn bench(c: &mut Criterion) {
    let dir = tempfile::tempdir().unwrap();
    vlnverse_testkit::datasets::make_dataset(dir.path(), Task::Fine, 2, 4, 3);
    let run = AtomicU64::new(0);
    let mut g = c.benchmark_group("evaluate_oracle");
    g.sample_size(10);
    let cases = [
        (
            "telhop_waypoint_rgbd_auto",
            Setting::Telhop,
            ActionSpace::Waypoint,
            Some(Backend::Auto),
            true,
        ),
        (
            "lenient_discrete_rgbd_auto",
            Setting::Lenient,
            ActionSpace::Discrete,
            Some(Backend::Auto),
            true,
        ),
        (
            "lenient_discrete_rgbd_raycast",
            Setting::Lenient,
            ActionSpace::Discrete,
            Some(Backend::Raycast),
            true,
        ),
        (
            "lenient_discrete_no_render",
            Setting::Lenient,
            ActionSpace::Discrete,
            None,
            false,
        ),
    ];
    for (name, setting, space, backend, render) in cases {
        let cfg = EvalConfig {
            setting,
            action_space: space,
            backend,
            render,
            plots: 0,
            ..Default::default()
        };
        let factory = builtin("oracle", None, &cfg).unwrap();
        let req = |cfg: &EvalConfig| {
            EvalRequest::new(
                dir.path().to_path_buf(),
                Task::Fine,
                Split::Test,
                dir.path()
                    .join(format!("run{}", run.fetch_add(1, Ordering::Relaxed))),
            )
            .config(cfg.clone())
        };
        let steps = evaluate(&req(&cfg), &*factory).unwrap().steps_run;
        g.throughput(Throughput::Elements(steps));
        g.bench_function(name, |b| {
            b.iter(|| evaluate(&req(&cfg), &*factory).unwrap().steps_run)
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
