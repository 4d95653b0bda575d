//! The tiny preset's fine-grained episodes, generated once per test binary.

use std::path::Path;
use std::sync::OnceLock;

use vlnverse_task::generate::{GenerateRequest, StageTimes};
use vlnverse_task::Task;

/// The tiny dataset (fine-grained task only).
pub fn tiny() -> &'static Path {
    static DIR: OnceLock<tempfile::TempDir> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = tempfile::tempdir().unwrap();
        let mut req = GenerateRequest::preset("tiny", d.path());
        req.tasks = vec![Task::Fine];
        let run = req.prepare().unwrap();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| run.run(&StageTimes::default(), &|_| {}))
            .unwrap();
        d
    })
    .path()
}
