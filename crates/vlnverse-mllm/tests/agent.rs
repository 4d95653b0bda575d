//! The MLLM agent against the scripted chat endpoint on loopback: what it sends (text, pictures
//! that decode, the map of explored space only), how it reads replies (corrective retry, counted
//! fallbacks, questions within the budget), the transport (retries, a dead endpoint, the
//! concurrency limit) and the books (tokens summed, a cached rerun that sends nothing and
//! writes the same bytes).

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

use base64::engine::general_purpose::STANDARD;
use base64::Engine as _;
use vlnverse_eval::{evaluate, EvalConfig, EvalRequest};
use vlnverse_mllm::scripted::{Script, ScriptedServer};
use vlnverse_mllm::{
    read_records, write_accounting, EpisodeStats, Fallback, History, MllmConfig, MllmFactory, View,
};
use vlnverse_score::{dataset, Split, Task};

const RIG: &str = "backend = \"raster\"\n[[sensors]]\ntype = \"compass\"\n";

/// A split of `task` with `n` episodes (dialogue: a question budget of `budget`).
fn data(dir: &Path, task: Task, n: usize, budget: u32) {
    let mut eps = vlnverse_testkit::datasets::make_object_dataset(dir, 1, n, 5);
    eps.truncate(n);
    for e in &mut eps {
        e.task = task;
        if task == Task::Dialogue {
            e.oracle_budget = Some(budget);
        }
    }
    dataset::write_split(dir, task, Split::Test, &eps).unwrap();
    std::fs::write(dir.join("rig.toml"), RIG).unwrap();
}

fn request(dir: &Path, task: Task, out: &str, threads: usize, max_steps: u32) -> EvalRequest {
    EvalRequest::new(dir.to_path_buf(), task, Split::Test, dir.join(out))
        .threads(threads)
        .fresh(true)
        .config(EvalConfig {
            max_steps,
            plots: 0,
            rig: dir.join("rig.toml").display().to_string(),
            ..Default::default()
        })
}

fn config(url: &str, cache: Option<PathBuf>) -> MllmConfig {
    MllmConfig {
        endpoint: url.into(),
        model: "scripted".into(),
        image_size: 48,
        map_size: 96,
        retries: 0,
        retry_backoff_ms: 1,
        timeout_s: 20.0,
        cache: cache.is_some(),
        cache_dir: cache,
        ..Default::default()
    }
}

/// Requests the server answered, in order: (body, prompt tokens, completion tokens).
fn log(server: &ScriptedServer) -> Vec<(serde_json::Value, u64, u64)> {
    server
        .seen
        .log
        .lock()
        .unwrap()
        .iter()
        .map(|(b, u)| (b.clone(), u.prompt_tokens, u.completion_tokens))
        .collect()
}

fn user_text(body: &serde_json::Value) -> String {
    let m = body["messages"].as_array().unwrap().last().unwrap();
    match &m["content"] {
        serde_json::Value::String(s) => s.clone(),
        serde_json::Value::Array(parts) => parts
            .iter()
            .filter_map(|p| p["text"].as_str())
            .collect::<Vec<_>>()
            .join("\n"),
        _ => String::new(),
    }
}

/// The pictures of a request's last message, decoded.
fn pictures(body: &serde_json::Value) -> Vec<image::RgbImage> {
    let m = body["messages"].as_array().unwrap().last().unwrap();
    let Some(parts) = m["content"].as_array() else {
        return Vec::new();
    };
    parts
        .iter()
        .filter_map(|p| p["image_url"]["url"].as_str())
        .map(|url| {
            let (head, b64) = url.split_once(";base64,").unwrap();
            assert!(
                head == "data:image/png" || head == "data:image/jpeg",
                "{head}"
            );
            let bytes = STANDARD.decode(b64).unwrap();
            image::load_from_memory(&bytes).unwrap().to_rgb8()
        })
        .collect()
}

fn run(req: &EvalRequest, f: &MllmFactory) -> Vec<EpisodeStats> {
    evaluate(req, f).unwrap();
    f.stats()
}

#[test]
fn an_unreadable_reply_gets_one_corrective_retry_then_a_counted_fallback() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Coarse, 1, 0);
    let server = ScriptedServer::start(
        Script::sequence(&["I see a sofa.", "Hmm.", "move forward 50 cm", "stop"]),
        0,
    )
    .unwrap();
    let f = MllmFactory::new(MllmConfig {
        fallback: Fallback::TurnRight,
        ..config(&server.url, None)
    })
    .unwrap();
    let stats = run(&request(dir.path(), Task::Coarse, "run", 1, 20), &f);
    let s = &stats[0];
    assert_eq!(
        (s.decisions, s.calls, s.parse_retries, s.fallbacks),
        (3, 4, 1, 1)
    );
    let seen = log(&server);
    assert_eq!(seen.len(), 4);
    // The retry carries the unreadable reply and the correction.
    let retry = seen[1].0["messages"].as_array().unwrap();
    assert_eq!(retry[retry.len() - 2]["content"], "I see a sofa.");
    assert!(user_text(&seen[1].0).contains("could not read a move"));
    // The first request: the camera view, decodable, at the configured size.
    let first = pictures(&seen[0].0);
    assert_eq!(first.len(), 1);
    assert_eq!(first[0].dimensions(), (48, 48));
    assert!(user_text(&seen[0].0).contains("Instruction: "));
    // The fallback was a right turn, then two forward steps, then stop: the history says so.
    let third = user_text(&seen[2].0);
    assert!(third.contains("turn right 15 degrees"), "{third}");
}

#[test]
fn transport_errors_are_retried_and_a_dead_endpoint_falls_back_without_hanging() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Coarse, 1, 0);
    let mut script = Script::sequence(&["stop"]);
    script.fail_first = 2;
    let server = ScriptedServer::start(script, 0).unwrap();
    let f = MllmFactory::new(MllmConfig {
        retries: 2,
        ..config(&server.url, None)
    })
    .unwrap();
    let s = run(&request(dir.path(), Task::Coarse, "run", 1, 20), &f);
    assert_eq!(
        (s[0].calls, s[0].requests, s[0].transport_retries),
        (1, 1, 2)
    );
    assert_eq!(server.seen.requests.load(Ordering::SeqCst), 3);

    // Nothing listens: every call fails, the fallback (stop) ends the episode.
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let f = MllmFactory::new(MllmConfig {
        fallback: Fallback::Stop,
        timeout_s: 2.0,
        ..config(&format!("http://127.0.0.1:{port}/v1"), None)
    })
    .unwrap();
    let s = run(&request(dir.path(), Task::Coarse, "dead", 1, 20), &f);
    assert_eq!((s[0].failed_calls, s[0].fallbacks, s[0].calls), (1, 1, 0));
}

#[test]
fn a_missing_api_key_variable_is_refused_before_the_run() {
    let err = MllmFactory::new(MllmConfig {
        api_key_env: Some("VLNVERSE_MLLM_TEST_KEY_THAT_IS_NOT_SET".into()),
        ..config("http://127.0.0.1:9/v1", None)
    })
    .err()
    .expect("refused");
    let e = err.to_string();
    assert!(
        e.contains("mllm.api_key_env") && e.contains("NOT_SET"),
        "{e}"
    );
}

#[test]
fn a_cached_rerun_sends_nothing_and_writes_the_same_bytes_and_tokens_add_up() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Coarse, 3, 0);
    let text =
        std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/walk.toml"))
            .unwrap();
    let server = ScriptedServer::start(Script::parse(&text).unwrap(), 0).unwrap();
    let cache = dir.path().join("cache");
    let cfg = MllmConfig {
        image_format: vlnverse_mllm::ImageFormat::Jpeg,
        ..config(&server.url, Some(cache))
    };
    let req = request(dir.path(), Task::Coarse, "run", 2, 25);
    let out = dir.path().join("run");
    let first = MllmFactory::new(cfg.clone()).unwrap();
    let stats = run(&req, &first);
    let (totals, traffic) = write_accounting(&out, "scripted", &stats, None).unwrap();
    let sent = server.seen.requests.load(Ordering::SeqCst);
    assert!(sent > 0);
    assert_eq!(traffic.requests, sent);
    // Tokens: the sum of what the server reported, over every request it answered.
    let seen = log(&server);
    let p: u64 = seen.iter().map(|s| s.1).sum();
    let c: u64 = seen.iter().map(|s| s.2).sum();
    assert_eq!((totals.prompt_tokens, totals.completion_tokens), (p, c));
    assert_eq!(totals.calls, sent);
    let files = ["summary.json", "episodes.csv", "trajectories.jsonl"];
    let before: Vec<Vec<u8>> = files
        .iter()
        .map(|f| std::fs::read(out.join(f)).unwrap())
        .collect();
    let summary: serde_json::Value = serde_json::from_slice(&before[0]).unwrap();
    assert_eq!(summary["mllm"]["prompt_tokens"], p);
    assert_eq!(summary["mllm"]["episodes"], 3);

    // Again from scratch, one thread this time: all from the cache.
    let again = MllmFactory::new(cfg).unwrap();
    let stats = run(&request(dir.path(), Task::Coarse, "run", 1, 25), &again);
    write_accounting(&out, "scripted", &stats, None).unwrap();
    assert_eq!(
        server.seen.requests.load(Ordering::SeqCst),
        sent,
        "the rerun sent requests"
    );
    for (f, b) in files.iter().zip(&before) {
        assert_eq!(&std::fs::read(out.join(f)).unwrap(), b, "{f} differs");
    }
    let lines = read_records(&out).unwrap();
    assert_eq!(lines.len(), 3);
    assert!(lines
        .iter()
        .all(|r| r.requests == 0 && r.cache_hits == r.calls));
}

#[test]
fn requests_in_flight_stay_within_the_limit() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Coarse, 4, 0);
    let mut script = Script::sequence(&["turn left 15 degrees"]);
    script.delay_ms = 40;
    let server = ScriptedServer::start(script, 0).unwrap();
    let f = MllmFactory::new(MllmConfig {
        max_concurrent_requests: 2,
        ..config(&server.url, None)
    })
    .unwrap();
    run(&request(dir.path(), Task::Coarse, "run", 4, 4), &f);
    assert_eq!(server.seen.requests.load(Ordering::SeqCst), 16);
    let peak = server.seen.peak_in_flight.load(Ordering::SeqCst);
    assert!((1..=2).contains(&peak), "peak {peak}");
}

fn grey(img: &image::RgbImage) -> usize {
    img.pixels()
        .filter(|p| p.0 == vlnverse_mllm::map::UNKNOWN_RGB)
        .count()
}

#[test]
fn the_map_grows_with_what_the_agent_has_seen_and_never_shows_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Coarse, 1, 0);
    let server = ScriptedServer::start(
        Script::sequence(&[
            "turn left 90 degrees",
            "turn left 90 degrees",
            "turn left 90 degrees",
            "stop",
        ]),
        0,
    )
    .unwrap();
    let f = MllmFactory::new(MllmConfig {
        history: History::Map,
        view: View::Panorama4,
        max_actions_per_reply: 6,
        ..config(&server.url, None)
    })
    .unwrap();
    run(&request(dir.path(), Task::Coarse, "run", 1, 40), &f);
    let seen = log(&server);
    assert_eq!(seen.len(), 4);
    let first = pictures(&seen[0].0);
    let last = pictures(&seen[3].0);
    // A 4-view strip (48 px views, 2 px gaps) and the map.
    assert_eq!(first.len(), 2);
    assert_eq!(first[0].dimensions(), (4 * 48 + 6, 48));
    assert_eq!(first[1].dimensions(), (96, 96));
    assert!(user_text(&seen[0].0).contains("m per pixel"));
    // Unknown grey remains in both maps, and after a full look around the map knows more
    // floor (in square metres: the map is rescaled as it grows) than before turning.
    let area = |body: &serde_json::Value, img: &image::RgbImage| {
        let text = user_text(body);
        let mpp: f64 = text
            .split(" m per pixel")
            .next()
            .and_then(|t| t.rsplit('(').next())
            .and_then(|t| t.parse().ok())
            .unwrap_or_else(|| panic!("no scale in {text}"));
        let free = img
            .pixels()
            .filter(|p| p.0 == vlnverse_mllm::map::FREE_RGB)
            .count();
        free as f64 * mpp * mpp
    };
    assert!(grey(&first[1]) > 0 && grey(&last[1]) > 0);
    let (before, after) = (area(&seen[0].0, &first[1]), area(&seen[3].0, &last[1]));
    assert!(after > 1.5 * before, "{after} m2 vs {before} m2");
}

#[test]
fn questions_go_to_the_oracle_within_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::Dialogue, 1, 1);
    let server = ScriptedServer::start(
        Script::sequence(&[
            "ask: Which way should I go?",
            "ask: And after that?",
            "stop",
        ]),
        0,
    )
    .unwrap();
    let f = MllmFactory::new(config(&server.url, None)).unwrap();
    let s = run(&request(dir.path(), Task::Dialogue, "run", 1, 20), &f);
    assert_eq!((s[0].asks, s[0].parse_retries, s[0].calls), (1, 1, 3));
    let seen = log(&server);
    assert!(user_text(&seen[0].0).contains("Questions left: 1."));
    let second = user_text(&seen[1].0);
    assert!(
        second.contains("You asked: Which way should I go?"),
        "{second}"
    );
    assert!(second.contains("The guide said: ") && second.contains("Questions left: 0."));
    // The second question is refused (one per step, and none left): a correction follows.
    assert!(user_text(&seen[2].0).contains("No question can be asked now"));
    // The system prompt of dialogue episodes offers the question.
    let sys = seen[0].0["messages"][0]["content"].as_str().unwrap();
    assert!(sys.contains("ask:"));
}

#[test]
fn visual_reference_episodes_send_the_reference_picture_first() {
    let dir = tempfile::tempdir().unwrap();
    data(dir.path(), Task::VisualReference, 1, 0);
    let reference =
        image::RgbImage::from_fn(40, 30, |x, y| image::Rgb([x as u8 * 5, y as u8 * 7, 200]));
    reference
        .save(dir.path().join("visual_reference/test/goal.png"))
        .unwrap();
    let mut eps = dataset::read_split(dir.path(), Task::VisualReference, Split::Test).unwrap();
    for e in &mut eps {
        e.reference_image = Some("goal.png".into());
    }
    dataset::write_split(dir.path(), Task::VisualReference, Split::Test, &eps).unwrap();
    let server = ScriptedServer::start(Script::sequence(&["stop"]), 0).unwrap();
    let f = MllmFactory::new(config(&server.url, None)).unwrap();
    run(
        &request(dir.path(), Task::VisualReference, "run", 1, 10),
        &f,
    );
    let seen = log(&server);
    let pics = pictures(&seen[0].0);
    assert_eq!(pics.len(), 2);
    assert_eq!(pics[0], reference, "the reference picture, unchanged (PNG)");
    assert_eq!(pics[1].dimensions(), (48, 48));
    assert!(user_text(&seen[0].0).contains("reference picture taken at the goal"));
}
