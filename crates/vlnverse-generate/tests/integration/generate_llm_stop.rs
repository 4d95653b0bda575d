//! `on_reject = "error"`: the first rewrite not used ends the generation, with the reason, no
//! flood of further requests and no LLM report.

use std::path::Path;

use vlnverse_generate::{GenerateRequest, StageTimes};
use vlnverse_score::Task;

#[test]
fn on_reject_error_stops_generation_at_the_first_rejection() {
    let dir = tempfile::tempdir().unwrap();
    // Every reply (describer and verifier alike) is a refusal.
    let (url, seen) =
        vlnverse_testkit::llm_stub::stub(vec![(200, "NO. It names other things.".into()); 64]);
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/generate/tiny.toml"),
    )
    .unwrap();
    let cfg = dir.path().join("tiny_llm.toml");
    std::fs::write(
        &cfg,
        format!(
            "{base}\n[instructions.llm]\nbase_url = \"{url}\"\nmodel = \"local\"\n\
             on_reject = \"error\"\nretries = 0\nframes = 0\ncache_dir = \"{}\"\n",
            dir.path().join("cache").display()
        ),
    )
    .unwrap();
    let out = dir.path().join("out");
    let run = GenerateRequest {
        config: Some(cfg),
        tasks: vec![Task::Fine],
        ..GenerateRequest::preset("tiny", &out)
    }
    .prepare()
    .unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let err = pool
        .install(|| run.run(&StageTimes::default(), &|_| {}))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("on_reject")
            && err.contains("verifier_rejected")
            && !err.contains("min_length"),
        "{err}"
    );
    // One describer and one verifier call per worker at most, not one per sampling attempt.
    let sent = seen.lock().unwrap().len();
    assert!(sent <= 4, "{sent} requests after the first rejection");
    assert!(!out.join(vlnverse_generate::LLM_REPORT_FILE).exists());
}
