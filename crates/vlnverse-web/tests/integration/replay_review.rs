//! Replay of an evaluation run, and review decisions applied to a dataset copy.

use serde_json::json;
use vlnverse_task::eval::agents::builtin;
use vlnverse_task::eval::{EvalConfig, EvalRequest};
use vlnverse_task::{dataset, Split, Task};
use vlnverse_web::{apply_review, read_review};

use crate::support::{config, make_dataset, Server};

fn evaluate_oracle(dir: &std::path::Path) -> std::path::PathBuf {
    let cfg = EvalConfig::load(dir.join("protocols/telhop.toml")).unwrap();
    let out = dir.join("run-oracle");
    let req = EvalRequest::new(dir.to_path_buf(), Task::Fine, Split::ValUnseen, out.clone())
        .threads(1)
        .fresh(true)
        .config(cfg.clone());
    let agent = builtin("oracle", None, &cfg).unwrap();
    vlnverse_task::evaluate(&req, &*agent).unwrap();
    out
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_run_is_listed_and_stepped_through() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 2);
    let run = tokio::task::spawn_blocking({
        let d = dir.path().to_path_buf();
        move || evaluate_oracle(&d)
    })
    .await
    .unwrap();
    let mut cfg = config(dir.path());
    cfg.runs = vec![run];
    let srv = Server::start(cfg).await;
    let (s, v) = srv.get_json("/api/runs").await;
    assert_eq!(s, 200);
    assert_eq!(v["runs"][0]["name"], "run-oracle");
    assert_eq!(v["runs"][0]["agent"], "oracle");
    assert_eq!(v["runs"][0]["summary"]["sr"], 1.0);
    let (s, v) = srv.get_json("/api/runs/0/episodes").await;
    assert_eq!(s, 200);
    let rows = v["episodes"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    assert_eq!(rows[0]["episode_id"], 1);
    assert_eq!(rows[0]["success"], 1);
    let (s, ep) = srv.get_json("/api/runs/0/episodes/1").await;
    assert_eq!(s, 200, "{ep}");
    let n = ep["trajectory"]["positions"].as_array().unwrap().len();
    assert!(n >= 2);
    assert_eq!(
        ep["trajectory"]["actions"]
            .as_array()
            .unwrap()
            .last()
            .unwrap(),
        "stop"
    );
    assert!(ep["topdown"]["px_per_m"].as_f64().unwrap() > 0.0);
    let (s, png) = srv.get("/api/runs/0/episodes/1/topdown.png").await;
    assert_eq!(s, 200);
    assert_eq!(&png[1..4], b"PNG");
    let mut views = Vec::new();
    for k in 0..n {
        let (s, jpg) = srv.get(&format!("/api/runs/0/episodes/1/view/{k}")).await;
        assert_eq!(s, 200, "step {k}");
        assert_eq!(&jpg[..2], &[0xFF, 0xD8]);
        views.push(jpg);
    }
    assert_ne!(views[0], views[n - 1], "the view changes along the path");
    let (s, v) = srv
        .get_json(&format!("/api/runs/0/episodes/1/view/{n}"))
        .await;
    assert_eq!(s, 404);
    assert!(v["error"]
        .as_str()
        .unwrap()
        .contains(&format!("no step {n}")));
    let (s, _) = srv.get_json("/api/runs/0/episodes/77").await;
    assert_eq!(s, 404);
    // Files of the run, and nothing beside it.
    let (s, _) = srv.get("/files/runs/0/summary.json").await;
    assert_eq!(s, 200);
    let (s, _) = srv.get("/files/runs/0/..%2fprotocols%2fstrict.toml").await;
    assert_eq!(s, 403);
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn review_decisions_make_a_reviewed_copy() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 3);
    let srv = Server::start(config(dir.path())).await;
    let (s, v) = srv
        .get_json("/api/review/episodes?task=fine&split=val_unseen")
        .await;
    assert_eq!(s, 200);
    assert_eq!(v["episodes"].as_array().unwrap().len(), 3);
    assert!(v["episodes"][0]["decision"].is_null());
    for at in ["start", "goal"] {
        let (s, jpg) = srv
            .get(&format!(
                "/api/review/view?task=fine&split=val_unseen&id=2&at={at}"
            ))
            .await;
        assert_eq!(s, 200, "{at}");
        assert_eq!(&jpg[..2], &[0xFF, 0xD8]);
    }
    let (s, v) = srv
        .get_json("/api/review/view?task=fine&split=val_unseen&id=2&at=middle")
        .await;
    assert_eq!(s, 400);
    assert!(v["error"].as_str().unwrap().contains("middle"));
    let (s, png) = srv
        .get("/api/review/topdown.png?task=fine&split=val_unseen&id=2")
        .await;
    assert_eq!((s, &png[1..4]), (200, &b"PNG"[..]));
    let decide = |id: u64, d: &str, text: Option<&str>| {
        let mut b = json!({"task": "fine", "split": "val_unseen", "episode_id": id, "decision": d});
        if let Some(t) = text {
            b["instruction_text"] = json!(t);
        }
        b
    };
    let (s, _) = srv
        .post_json("/api/review/decision", &decide(1, "accepted", None))
        .await;
    assert_eq!(s, 200);
    let (s, _) = srv
        .post_json("/api/review/decision", &decide(2, "rejected", None))
        .await;
    assert_eq!(s, 200);
    let (s, _) = srv
        .post_json(
            "/api/review/decision",
            &decide(3, "edited", Some("Go to the third goal.")),
        )
        .await;
    assert_eq!(s, 200);
    // Bad decisions are refused with the reason.
    let (s, v) = srv
        .post_json("/api/review/decision", &decide(3, "edited", None))
        .await;
    assert_eq!(s, 400);
    assert!(v["error"].as_str().unwrap().contains("instruction_text"));
    let (s, v) = srv
        .post_json("/api/review/decision", &decide(42, "rejected", None))
        .await;
    assert_eq!(s, 404);
    assert!(v["error"].as_str().unwrap().contains("42"));
    let (s, v) = srv
        .post_json("/api/review/decision", &decide(1, "maybe", None))
        .await;
    assert_eq!(s, 400, "{v}");
    let (_, v) = srv
        .get_json("/api/review/episodes?task=fine&split=val_unseen")
        .await;
    assert_eq!(v["episodes"][1]["decision"], "rejected");
    srv.stop().await;

    let review = dir.path().join("out/review.json");
    let doc = read_review(&review).unwrap();
    assert_eq!(doc.decisions.len(), 3);
    let copy = dir.path().join("reviewed");
    let report = apply_review(dir.path(), &review, &copy, false).unwrap();
    let c = report.splits["fine/val_unseen"];
    assert_eq!(
        (c.before, c.accepted, c.rejected, c.edited, c.after),
        (3, 1, 1, 1, 2)
    );
    let eps = dataset::read_split(&copy, Task::Fine, Split::ValUnseen).unwrap();
    let ids: Vec<u64> = eps.iter().map(|e| e.episode_id).collect();
    assert_eq!(ids, vec![1, 3]);
    assert_eq!(eps[1].instruction.instruction_text, "Go to the third goal.");
    assert!(copy.join("scenes/tiny_000/scene.json").is_file());
    assert!(copy.join("review_report.json").is_file());
    // An existing output folder is refused; so is a decision about a missing episode.
    let e = apply_review(dir.path(), &review, &copy, false).unwrap_err();
    assert!(e.to_string().contains("already exists"), "{e}");
    let bad = dir.path().join("bad_review.json");
    std::fs::write(
        &bad,
        json!({"format": "vlnverse-review/1", "dataset": "x", "decisions": [
            {"task": "fine", "split": "val_unseen", "episode_id": 9, "decision": "rejected"}]})
        .to_string(),
    )
    .unwrap();
    let e = apply_review(dir.path(), &bad, &dir.path().join("r2"), false).unwrap_err();
    assert!(e.to_string().contains("episode_id` = 9"), "{e}");
    assert!(!dir.path().join("r2").exists());
}
