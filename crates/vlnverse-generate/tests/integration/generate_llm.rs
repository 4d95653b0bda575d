//! The LLM stage of `generate` (`[instructions.llm]`) against a local server that speaks the
//! OpenAI chat-completions API: rewrites kept or falling back by reason, pictures for the
//! describer, the reply cache (same bytes, nothing sent twice), the concurrency limit.

use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpListener;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};

use serde_json::Value;
use vlnverse_generate::{GenerateRequest, StageTimes};
use vlnverse_instructions::llm::{DESCRIBER_PROMPT, VERIFIER_PROMPT};
use vlnverse_score::dataset::read_split;
use vlnverse_score::{Split, Task};

/// What the server saw.
#[derive(Default)]
struct Log {
    requests: AtomicUsize,
    in_flight: AtomicUsize,
    most_in_flight: AtomicUsize,
    pictures: Mutex<Vec<String>>,
}

fn text_of(m: &Value) -> String {
    match &m["content"] {
        Value::String(s) => s.clone(),
        Value::Array(parts) => parts
            .iter()
            .filter_map(|p| p["text"].as_str())
            .collect::<Vec<_>>()
            .join("\n"),
        _ => String::new(),
    }
}

/// The reply of the fake model: the describer says "Please, <reference instruction>" (adding
/// a piano, which no tiny home has, when the reference mentions a sofa); the verifier says NO
/// when the candidate mentions a bed, else YES.
fn answer(body: &Value, log: &Log) -> String {
    let msgs = body["messages"].as_array().unwrap();
    let system = text_of(&msgs[0]);
    let user = text_of(&msgs[1]);
    if let Value::Array(parts) = &msgs[1]["content"] {
        for p in parts {
            if let Some(url) = p["image_url"]["url"].as_str() {
                log.pictures.lock().unwrap().push(url.to_string());
            }
        }
    }
    let reference = user
        .lines()
        .find_map(|l| l.strip_prefix("Reference instruction: "))
        .unwrap_or("")
        .to_string();
    if system == DESCRIBER_PROMPT {
        let mut s = format!("Please, {reference}");
        if reference.contains("sofa") {
            // An object no home holds: the grounding check must refuse it.
            s.push_str(" Then look at the spaceship.");
        }
        s
    } else if system == VERIFIER_PROMPT {
        let candidate = user
            .lines()
            .find_map(|l| l.strip_prefix("Candidate instruction: "))
            .unwrap_or("");
        if candidate.contains(" bed") {
            "NO. The bed is described differently.".into()
        } else {
            "YES. Same objects and sides.".into()
        }
    } else {
        "Then do all of it.".into()
    }
}

fn serve(log: Arc<Log>) -> String {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}/v1", listener.local_addr().unwrap());
    std::thread::spawn(move || {
        for stream in listener.incoming() {
            let Ok(stream) = stream else { return };
            let log = log.clone();
            std::thread::spawn(move || {
                let now = log.in_flight.fetch_add(1, Ordering::SeqCst) + 1;
                log.most_in_flight.fetch_max(now, Ordering::SeqCst);
                log.requests.fetch_add(1, Ordering::SeqCst);
                let mut reader = BufReader::new(stream.try_clone().unwrap());
                let mut line = String::new();
                reader.read_line(&mut line).unwrap();
                let mut len = 0usize;
                loop {
                    let mut h = String::new();
                    reader.read_line(&mut h).unwrap();
                    let h = h.trim_end().to_ascii_lowercase();
                    if h.is_empty() {
                        break;
                    }
                    if let Some(v) = h.strip_prefix("content-length:") {
                        len = v.trim().parse().unwrap();
                    }
                }
                let mut body = vec![0u8; len];
                reader.read_exact(&mut body).unwrap();
                let body: Value = serde_json::from_slice(&body).unwrap();
                // Long enough for requests from several workers to overlap.
                std::thread::sleep(std::time::Duration::from_millis(3));
                let content = answer(&body, &log);
                let payload = serde_json::json!({
                    "id": "local", "object": "chat.completion",
                    "choices": [{"index": 0, "finish_reason": "stop",
                                 "message": {"role": "assistant", "content": content}}]
                })
                .to_string();
                log.in_flight.fetch_sub(1, Ordering::SeqCst);
                let mut out = stream;
                let _ = write!(
                    out,
                    "HTTP/1.1 200 OK\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{payload}",
                    payload.len()
                );
                let _ = out.flush();
            });
        }
    });
    url
}

/// The tiny preset with an `[instructions.llm]` section.
fn config(dir: &Path, url: &str, cache: &Path) -> std::path::PathBuf {
    let base = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("configs/generate/tiny.toml"),
    )
    .unwrap();
    let path = dir.join("tiny_llm.toml");
    std::fs::write(
        &path,
        format!(
            "{base}\n[instructions.llm]\nbase_url = \"{url}\"\nmodel = \"local\"\n\
             api_key_env = \"VLNVERSE_TEST_GENERATE_LLM_KEY\"\nmax_concurrent = 1\nframes = 2\n\
             retries = 0\ncache_dir = \"{}\"\n",
            cache.display()
        ),
    )
    .unwrap();
    path
}

fn generate(config: Option<&Path>, out: &Path) {
    let req = GenerateRequest {
        config: config.map(Path::to_path_buf),
        tasks: vec![Task::Fine, Task::Coarse],
        ..GenerateRequest::preset("tiny", out)
    };
    let run = req.prepare().unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(4)
        .build()
        .unwrap();
    pool.install(|| run.run(&StageTimes::default(), &|_| {}))
        .unwrap();
}

fn texts(dir: &Path, task: Task) -> Vec<String> {
    Split::ALL
        .into_iter()
        .flat_map(|s| read_split(dir, task, s).unwrap())
        .map(|e| e.instruction.instruction_text)
        .collect()
}

#[test]
fn the_llm_stage_rewrites_checks_caches_and_reports() {
    std::env::set_var("VLNVERSE_TEST_GENERATE_LLM_KEY", "sk-local");
    let dir = tempfile::tempdir().unwrap();
    let log = Arc::new(Log::default());
    let url = serve(log.clone());
    let cache = dir.path().join("cache");
    let cfg = config(dir.path(), &url, &cache);
    let llm_out = dir.path().join("llm");
    generate(Some(&cfg), &llm_out);
    let plain_out = dir.path().join("plain");
    generate(None, &plain_out);

    let report: Value =
        serde_json::from_slice(&std::fs::read(llm_out.join("llm_report.json")).unwrap()).unwrap();
    let asked = report["instructions"].as_u64().unwrap();
    let accepted = report["accepted"].as_u64().unwrap();
    let fallbacks = &report["fallbacks"];
    let rejected = fallbacks["verifier_rejected"].as_u64().unwrap_or(0);
    let ungrounded = fallbacks["grounding_check_failed"].as_u64().unwrap_or(0);
    let mut total = 0;
    for task in [Task::Fine, Task::Coarse] {
        let (llm, plain) = (texts(&llm_out, task), texts(&plain_out, task));
        assert_eq!(llm.len(), plain.len());
        total += llm.len() as u64;
        for (a, b) in llm.iter().zip(&plain) {
            // Kept rewrites are the fake model's; every other instruction is the template's.
            if a != b {
                assert_eq!(a, &format!("Please, {b}"), "{task}");
                assert!(!a.contains("spaceship") && !a.contains(" bed"), "{a}");
            }
        }
    }
    assert_eq!(asked, total, "{report}");
    assert_eq!(accepted + rejected + ungrounded, asked, "{report}");
    assert!(accepted > 0 && rejected > 0 && ungrounded > 0, "{report}");
    // Describer and verifier per instruction; the limit of one request at a time held with
    // four workers.
    assert_eq!(log.requests.load(Ordering::SeqCst) as u64, 2 * asked);
    assert_eq!(log.most_in_flight.load(Ordering::SeqCst), 1);
    // The describer saw PNG pictures: two along each fine path, the goal view for coarse.
    let pics = log.pictures.lock().unwrap();
    assert!(pics.len() as u64 >= asked);
    assert!(pics
        .iter()
        .all(|p| p.starts_with("data:image/png;base64,iVBORw0KGgo")));

    // Another folder with the same cache: the same bytes, and nothing sent again.
    let sent = log.requests.load(Ordering::SeqCst);
    let again = dir.path().join("again");
    generate(Some(&cfg), &again);
    assert_eq!(log.requests.load(Ordering::SeqCst), sent);
    for task in [Task::Fine, Task::Coarse] {
        for split in Split::ALL {
            let f = vlnverse_score::dataset::split_path(&llm_out, task, split);
            let g = vlnverse_score::dataset::split_path(&again, task, split);
            assert_eq!(std::fs::read(f).unwrap(), std::fs::read(g).unwrap());
        }
    }
    let report: Value =
        serde_json::from_slice(&std::fs::read(again.join("llm_report.json")).unwrap()).unwrap();
    assert_eq!(report["requests"], 0);
    assert_eq!(report["cache_hits"].as_u64().unwrap(), 2 * asked);
}

#[test]
fn a_bad_llm_section_names_the_file_and_field() {
    let dir = tempfile::tempdir().unwrap();
    let cfg = config(dir.path(), "ftp://nowhere", &dir.path().join("c"));
    let err = GenerateRequest {
        config: Some(cfg.clone()),
        ..GenerateRequest::preset("tiny", dir.path().join("out"))
    }
    .prepare()
    .err()
    .expect("an ftp endpoint is refused")
    .to_string();
    assert!(
        err.contains("tiny_llm.toml") && err.contains("base_url"),
        "{err}"
    );
    let text = std::fs::read_to_string(&cfg)
        .unwrap()
        .replace("ftp://nowhere", "http://127.0.0.1:9/v1")
        .replace("frames = 2", "frames = 2\nshout = true");
    std::fs::write(&cfg, text).unwrap();
    let err = GenerateRequest {
        config: Some(cfg),
        ..GenerateRequest::preset("tiny", dir.path().join("out"))
    }
    .prepare()
    .err()
    .expect("an unknown field is refused")
    .to_string();
    assert!(err.contains("shout"), "{err}");
}
