//! The client against scripted agent servers on loopback: the protocol's requests, action
//! replies, retries of requests that did not reach the agent, and servers that never answer
//! (each test bounded by the client's own timeouts).

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use serde_json::{json, Value};
use vlnverse_agent_http::{action_code, EpisodeStart, HttpAgent, HttpAgentConfig, HttpFactory};
use vlnverse_env::Pose;
use vlnverse_eval::{ActionSpace, AgentFactory, StepInput, SubGoalProgress};
use vlnverse_sensors::{Frame, Observation, Observations};
use vlnverse_sim::Action;

/// One request as the server saw it.
#[derive(Debug, Clone)]
struct Seen {
    path: String,
    body: Value,
}

/// What the scripted server does with a request.
#[derive(Clone)]
enum Reply {
    /// Answer with this status and body.
    Status(u16, String),
    /// Read the request, then never answer (the connection stays open).
    Hang,
}

/// A server answering from `script(path, n)` (n = requests on that path so far); returns the
/// base URL and the requests seen.
fn serve(
    script: impl Fn(&str, usize) -> Reply + Send + Sync + 'static,
) -> (String, Arc<Mutex<Vec<Seen>>>) {
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    let seen = Arc::new(Mutex::new(Vec::new()));
    let log = seen.clone();
    let script = Arc::new(script);
    std::thread::spawn(move || {
        let counts = Arc::new(Mutex::new(BTreeMap::<String, usize>::new()));
        for stream in listener.incoming() {
            let Ok(stream) = stream else { break };
            let (log, script, counts) = (log.clone(), script.clone(), counts.clone());
            std::thread::spawn(move || connection(stream, &log, &*script, &counts));
        }
    });
    (url, seen)
}

fn connection(
    stream: TcpStream,
    log: &Mutex<Vec<Seen>>,
    script: &dyn Fn(&str, usize) -> Reply,
    counts: &Mutex<BTreeMap<String, usize>>,
) {
    let mut out = stream.try_clone().unwrap();
    let mut r = BufReader::new(stream);
    loop {
        let mut line = String::new();
        if r.read_line(&mut line).unwrap_or(0) == 0 {
            return;
        }
        let path = line.split_whitespace().nth(1).unwrap_or("").to_string();
        let mut len = 0;
        loop {
            let mut h = String::new();
            if r.read_line(&mut h).unwrap_or(0) == 0 {
                return;
            }
            if h.trim().is_empty() {
                break;
            }
            if let Some(v) = h.to_ascii_lowercase().strip_prefix("content-length:") {
                len = v.trim().parse().unwrap();
            }
        }
        let mut body = vec![0; len];
        r.read_exact(&mut body).unwrap();
        let n = {
            let mut c = counts.lock().unwrap();
            let n = c.entry(path.clone()).or_default();
            *n += 1;
            *n - 1
        };
        log.lock().unwrap().push(Seen {
            path: path.clone(),
            body: serde_json::from_slice(&body).unwrap_or(Value::Null),
        });
        match script(&path, n) {
            Reply::Status(status, text) => {
                let head = format!(
                    "HTTP/1.1 {status} X\r\nContent-Type: application/json\r\nContent-Length: {}\r\n\r\n",
                    text.len()
                );
                if out.write_all(head.as_bytes()).is_err()
                    || out.write_all(text.as_bytes()).is_err()
                {
                    return;
                }
            }
            Reply::Hang => {
                std::thread::sleep(Duration::from_secs(30));
                return;
            }
        }
    }
}

/// A server speaking the protocol: init names the agent, steps answer `action`.
fn agent_server(action: &'static str) -> (String, Arc<Mutex<Vec<Seen>>>) {
    serve(move |path, _| match path {
        "/agent/init" => Reply::Status(
            201,
            r#"{"status": "success", "agent_name": "walker"}"#.into(),
        ),
        "/agent/walker/reset" => Reply::Status(200, r#"{"status": "success"}"#.into()),
        "/agent/walker/step" => Reply::Status(200, format!(r#"{{"action": {action}}}"#)),
        _ => Reply::Status(404, r#"{"detail": "Agent not found"}"#.into()),
    })
}

fn config(url: &str) -> HttpAgentConfig {
    let mut cfg = HttpAgentConfig::new(url, "walker");
    cfg.step_timeout = Duration::from_secs(2);
    cfg.init_timeout = Duration::from_secs(2);
    cfg.retry_backoff = Duration::from_millis(10);
    cfg
}

fn inputs(space: ActionSpace) -> EpisodeStart {
    EpisodeStart {
        id: 7,
        instruction: "Go to the sofa.".into(),
        start: Pose::from_yaw(glam::Vec3::new(1.0, 0.0, 2.0), 0.5),
        step_size: 0.25,
        turn: 15f32.to_radians(),
        action_space: space,
    }
}

fn observations() -> Observations {
    let frame = Frame {
        width: 3,
        height: 2,
        rgb: (0..18).collect(),
        depth: vec![0.25; 6],
        ..Default::default()
    };
    let mut obs = Observations::new();
    obs.insert("rgb".into(), Observation::Rgb(frame.clone()));
    obs.insert("depth".into(), Observation::Depth(frame));
    obs
}

fn step<'a>(obs: &'a Observations, n: u32) -> StepInput<'a> {
    StepInput {
        step: n,
        observations: obs,
        pose: Pose::from_yaw(glam::Vec3::new(1.5, 0.0, 2.0), 0.5),
        last: None,
        sub_goal: SubGoalProgress {
            current: 0,
            total: 1,
        },
        oracle: None,
    }
}

#[test]
fn an_episode_sends_init_reset_and_pickled_steps() {
    let (url, seen) = agent_server("[[3]]");
    let mut agent = HttpAgent::connect(config(&url)).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let obs = observations();
    let a = agent.step(&step(&obs, 0)).unwrap();
    assert_eq!(a, Action::TurnRight(15f32.to_radians()));
    let seen = seen.lock().unwrap().clone();
    let paths: Vec<&str> = seen.iter().map(|s| s.path.as_str()).collect();
    assert_eq!(
        paths,
        ["/agent/init", "/agent/walker/reset", "/agent/walker/step"]
    );
    let cfg = &seen[0].body["agent_config"];
    assert_eq!(cfg["model_name"], "walker");
    assert_eq!(cfg["server_host"], "127.0.0.1");
    assert!(cfg["server_port"].as_u64().unwrap() > 0);
    assert_eq!(seen[1].body, json!({"reset_index": [0]}));
    // The observation is base64 of a protocol-3 pickle holding the step's arrays.
    use base64::Engine as _;
    let b64 = seen[2].body["observation"].as_str().unwrap();
    let raw = base64::engine::general_purpose::STANDARD
        .decode(b64)
        .unwrap();
    assert_eq!(&raw[..2], &[0x80, 3]);
    assert_eq!(raw.last(), Some(&b'.'));
    let text = String::from_utf8_lossy(&raw);
    for key in [
        "rgb",
        "depth",
        "instruction",
        "globalgps",
        "globalrotation",
        "compass",
        "gps",
    ] {
        assert!(text.contains(key), "no `{key}` in the pickle");
    }
    assert!(text.contains("Go to the sofa."));
    let rgb: Vec<u8> = (0..18).collect();
    assert!(raw.windows(18).any(|w| w == rgb.as_slice()));
}

#[test]
fn every_reply_shape_of_the_original_agents_is_read() {
    for (reply, code) in [
        (json!({"action": [[0]]}), 0),
        (json!({"action": [2]}), 2),
        (json!({"action": [{"action": [5], "ideal_flag": true}]}), 5),
        (json!({"action": -1}), -1),
        (json!({"action": [[1.0]]}), 1),
    ] {
        assert_eq!(action_code(&reply), Ok(code), "{reply}");
    }
    for bad in [
        json!({}),
        json!({"action": []}),
        json!({"action": "left"}),
        json!({"action": [[1.5]]}),
        json!({"action": [{"action": [1.0, 0.0, 0.0], "ideal_flag": false}]}),
    ] {
        assert!(action_code(&bad).is_err(), "{bad}");
    }
}

#[test]
fn unknown_codes_and_other_action_spaces_are_refused_by_name() {
    let (url, _) = agent_server("[[9]]");
    let mut agent = HttpAgent::connect(config(&url)).unwrap();
    let err = agent
        .begin(inputs(ActionSpace::Continuous))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("continuous") && err.contains("discrete"),
        "{err}"
    );
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let obs = observations();
    let err = agent.step(&step(&obs, 4)).unwrap_err().to_string();
    assert!(
        err.contains("action 9")
            && err.contains("/agent/walker/step")
            && err.contains("step 4")
            && err.contains(&url),
        "{err}"
    );
}

#[test]
fn requests_that_did_not_reach_the_agent_are_retried_a_bounded_number_of_times() {
    // Two 503s, then the step goes through.
    let (url, seen) = serve(|path, n| match path {
        "/agent/init" => Reply::Status(201, r#"{"agent_name": "walker"}"#.into()),
        "/agent/walker/step" if n < 2 => Reply::Status(503, "busy".into()),
        _ => Reply::Status(200, r#"{"action": [[1]], "status": "success"}"#.into()),
    });
    let mut agent = HttpAgent::connect(config(&url)).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let obs = observations();
    assert_eq!(
        agent.step(&step(&obs, 0)).unwrap(),
        Action::MoveForward(0.25)
    );
    let steps = seen
        .lock()
        .unwrap()
        .iter()
        .filter(|s| s.path.ends_with("/step"))
        .count();
    assert_eq!(steps, 3);

    // Always 503: gives up after 1 + retries attempts, naming them.
    let (url, seen) = serve(|path, _| match path {
        "/agent/init" => Reply::Status(201, r#"{"agent_name": "walker"}"#.into()),
        "/agent/walker/reset" => Reply::Status(200, "{}".into()),
        _ => Reply::Status(503, "overloaded".into()),
    });
    let mut cfg = config(&url);
    cfg.retries = 3;
    let mut agent = HttpAgent::connect(cfg).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let err = agent.step(&step(&obs, 0)).unwrap_err().to_string();
    assert!(
        err.contains("HTTP 503") && err.contains("4 attempts"),
        "{err}"
    );
    let steps = seen
        .lock()
        .unwrap()
        .iter()
        .filter(|s| s.path.ends_with("/step"))
        .count();
    assert_eq!(steps, 4);

    // A 500 (the agent failed) is not retried.
    let (url, seen) = serve(|path, _| match path {
        "/agent/init" => Reply::Status(201, r#"{"agent_name": "walker"}"#.into()),
        "/agent/walker/reset" => Reply::Status(200, "{}".into()),
        _ => Reply::Status(500, r#"{"detail": "CUDA out of memory"}"#.into()),
    });
    let mut agent = HttpAgent::connect(config(&url)).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let err = agent.step(&step(&obs, 0)).unwrap_err().to_string();
    assert!(
        err.contains("HTTP 500") && err.contains("CUDA out of memory"),
        "{err}"
    );
    let steps = seen
        .lock()
        .unwrap()
        .iter()
        .filter(|s| s.path.ends_with("/step"))
        .count();
    assert_eq!(steps, 1);
}

#[test]
fn a_server_that_never_replies_ends_the_step_with_an_error() {
    let (url, seen) = serve(|path, _| match path {
        "/agent/init" => Reply::Status(201, r#"{"agent_name": "walker"}"#.into()),
        "/agent/walker/reset" => Reply::Status(200, "{}".into()),
        _ => Reply::Hang,
    });
    let mut cfg = config(&url);
    cfg.step_timeout = Duration::from_millis(500);
    let mut agent = HttpAgent::connect(cfg).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let obs = observations();
    let err = agent.step(&step(&obs, 0)).unwrap_err().to_string();
    assert!(
        err.contains("no reply within 0.5 s")
            && err.contains("/agent/walker/step")
            && err.contains("episode 7"),
        "{err}"
    );
    // A timeout is not retried: the agent may be in the middle of the step.
    let steps = seen
        .lock()
        .unwrap()
        .iter()
        .filter(|s| s.path.ends_with("/step"))
        .count();
    assert_eq!(steps, 1);
}

#[test]
fn no_server_and_bad_settings_are_clear_errors() {
    // A port nobody listens on: refused, retried, then named.
    let port = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let url = format!("http://127.0.0.1:{port}");
    let err = HttpAgent::connect(config(&url)).err().unwrap().to_string();
    assert!(
        err.contains(&url) && err.contains("/agent/init") && err.contains("cannot connect"),
        "{err}"
    );
    for (url, name, what) in [
        ("ftp://x:1", "walker", "http://"),
        ("http://", "walker", "HOST:PORT"),
        ("http://127.0.0.1:1", "a/b", "agent_name"),
    ] {
        let err = HttpFactory::new(HttpAgentConfig::new(url, name))
            .err()
            .unwrap()
            .to_string();
        assert!(err.contains(what), "{url} {name}: {err}");
    }
    let mut cfg = HttpAgentConfig::new("http://127.0.0.1:1", "walker");
    cfg.step_timeout = Duration::ZERO;
    assert!(HttpFactory::new(cfg)
        .err()
        .unwrap()
        .to_string()
        .contains("step_timeout"));
}

#[test]
fn the_factory_keeps_one_agent_alive() {
    let (url, _) = agent_server("[[0]]");
    let f = HttpFactory::new(config(&url)).unwrap();
    let a = f.make().unwrap();
    let err = f.make().err().unwrap().to_string();
    assert!(err.contains("--threads 1"), "{err}");
    drop(a);
    assert!(f.make().is_ok());
}

#[test]
fn every_request_goes_over_one_kept_alive_connection() {
    // A server that serves one connection at a time (Python's plain HTTPServer, for one):
    // a client that opened a second connection would wait on it for ever.
    let listener = TcpListener::bind("127.0.0.1:0").unwrap();
    let url = format!("http://{}", listener.local_addr().unwrap());
    let log = Arc::new(Mutex::new(Vec::new()));
    let seen = log.clone();
    std::thread::spawn(move || {
        let counts = Mutex::new(BTreeMap::new());
        for stream in listener.incoming().flatten() {
            let script = |path: &str, _: usize| match path {
                "/agent/init" => Reply::Status(201, r#"{"agent_name": "walker"}"#.into()),
                "/agent/walker/reset" => Reply::Status(200, "{}".into()),
                _ => Reply::Status(200, r#"{"action": [[2]]}"#.into()),
            };
            connection(stream, &log, &script, &counts);
        }
    });
    let mut agent = HttpAgent::connect(config(&url)).unwrap();
    agent.begin(inputs(ActionSpace::Discrete)).unwrap();
    let obs = observations();
    for n in 0..3 {
        assert_eq!(
            agent.step(&step(&obs, n)).unwrap(),
            Action::TurnLeft(15f32.to_radians())
        );
    }
    assert_eq!(seen.lock().unwrap().len(), 5);
}
