//! Export throughput: frames/s of `export` (plan, render, PNG + Parquet, metadata) on the tiny
//! preset's fine-grained `val_unseen` episodes, on all threads and on one.
//!
//! `cargo bench -p vlnverse-export --bench export -- --warm-up-time 1 --measurement-time 10`
//!
//! The dataset is generated once into a temporary folder; each iteration exports into a fresh
//! folder (a resumed export would skip the work).

use std::sync::atomic::{AtomicUsize, Ordering};

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use vlnverse_export::{export, ExportRequest};
use vlnverse_task::generate::{GenerateRequest, StageTimes};
use vlnverse_task::{Split, Task};

const EPISODES: usize = 4;

fn bench(c: &mut Criterion) {
    let data = tempfile::tempdir().expect("temporary folder");
    let mut gen = GenerateRequest::preset("tiny", data.path());
    gen.tasks = vec![Task::Fine];
    gen.prepare()
        .and_then(|r| r.run(&StageTimes::default(), &|_| {}))
        .expect("tiny preset");
    let outs = tempfile::tempdir().expect("temporary folder");
    let n = AtomicUsize::new(0);
    let request = |threads: usize| {
        let k = n.fetch_add(1, Ordering::Relaxed);
        let mut req = ExportRequest::new(
            data.path(),
            Task::Fine,
            Split::ValUnseen,
            outs.path().join(format!("run-{k}")),
        );
        req.episodes = Some(EPISODES);
        req.threads = Some(threads);
        req
    };
    // Frames per iteration, from one export.
    let frames = export(&request(1), &|_| {}).expect("export").frames as u64;
    let mut g = c.benchmark_group("export");
    g.sample_size(10);
    g.throughput(Throughput::Elements(frames));
    let all = rayon::current_num_threads();
    for threads in [1, all] {
        g.bench_function(
            format!("lerobot_tiny_{EPISODES}_episodes_{threads}_threads"),
            |b| {
                b.iter(|| {
                    let out = request(threads);
                    let s = export(&out, &|_| {}).expect("export");
                    std::fs::remove_dir_all(&out.out).ok();
                    s.frames
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
