//! What a careless or hostile client cannot do: hold connections with half-sent headers, wait
//! unanswered beyond the connection limit, get a plain-text error, go unanswered with a binary
//! WebSocket message, or run a second server on the same output folder (whose review decisions
//! would overwrite the first's).

use std::time::Duration;

use serde_json::{json, Value};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use tokio::net::TcpStream;
use vlnverse_web::App;

use crate::support::{config, fine_query, make_dataset, Driver, Server};

/// Read until the server closes the connection (bounded: the test fails instead of hanging).
async fn closed_by_server(mut s: TcpStream) -> bool {
    let mut buf = [0u8; 1024];
    let waited = tokio::time::timeout(Duration::from_secs(60), async {
        loop {
            match s.read(&mut buf).await {
                Ok(0) | Err(_) => return,
                Ok(_) => {}
            }
        }
    })
    .await;
    waited.is_ok()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn half_sent_headers_are_dropped_and_others_are_still_served() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let mut cfg = config(dir.path());
    cfg.header_timeout = Duration::from_millis(500);
    cfg.max_connections = 8;
    let srv = Server::start(cfg).await;
    // More slow clients than the server takes at once, each holding an unfinished header.
    let mut slow = Vec::new();
    for i in 0..20 {
        let mut s = TcpStream::connect(srv.addr).await.unwrap();
        let part = format!(
            "GET /api/info HTTP/1.1\r\nHost: {}\r\nX-Slow-{i}: ",
            srv.addr
        );
        s.write_all(part.as_bytes()).await.unwrap();
        slow.push(s);
    }
    // A normal request is answered once the unfinished ones are closed and free their slots
    // (until then it is told the server is busy).
    let (status, body) = tokio::time::timeout(Duration::from_secs(60), async {
        loop {
            let (status, body) = srv.get_json("/api/info").await;
            if status != 503 {
                break (status, body);
            }
            tokio::time::sleep(Duration::from_millis(100)).await;
        }
    })
    .await
    .expect("an answer while slow clients hold connections");
    assert_eq!(status, 200, "{body}");
    for (i, s) in slow.into_iter().enumerate() {
        assert!(closed_by_server(s).await, "slow client {i} still connected");
    }
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_connection_over_the_limit_gets_a_503_json_error_at_once() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let mut cfg = config(dir.path());
    // Long enough that the held connections stay held for the whole test.
    cfg.header_timeout = Duration::from_secs(120);
    cfg.max_connections = 4;
    let srv = Server::start(cfg).await;
    let mut held = Vec::new();
    for _ in 0..4 {
        let mut s = TcpStream::connect(srv.addr).await.unwrap();
        s.write_all(format!("GET /api/info HTTP/1.1\r\nHost: {}\r\n", srv.addr).as_bytes())
            .await
            .unwrap();
        held.push(s);
    }
    // Connections are accepted in the order they arrived: the four take every slot first.
    let mut extra = TcpStream::connect(srv.addr).await.unwrap();
    extra
        .write_all(
            format!(
                "GET /api/info HTTP/1.1\r\nHost: {}\r\nConnection: close\r\n\r\n",
                srv.addr
            )
            .as_bytes(),
        )
        .await
        .unwrap();
    let mut answer = Vec::new();
    tokio::time::timeout(Duration::from_secs(60), extra.read_to_end(&mut answer))
        .await
        .expect("an answer, not a wait in the listen queue")
        .unwrap();
    let text = String::from_utf8_lossy(&answer).to_string();
    assert!(text.starts_with("HTTP/1.1 503 "), "{text}");
    let body = &text[text.find("\r\n\r\n").expect("a header end") + 4..];
    let v: Value = serde_json::from_str(body).unwrap_or_else(|e| panic!("{e}: {text}"));
    assert!(
        v["error"]
            .as_str()
            .is_some_and(|m| m.contains("busy") && m.contains('4')),
        "{v}"
    );
    // Once the held connections go, requests are served again.
    drop(held);
    let (status, body) = tokio::time::timeout(Duration::from_secs(60), async {
        loop {
            let (status, body) = srv.get_json("/api/info").await;
            if status != 503 {
                break (status, body);
            }
            tokio::time::sleep(Duration::from_millis(50)).await;
        }
    })
    .await
    .expect("served after the held connections closed");
    assert_eq!(status, 200, "{body}");
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn every_error_is_json() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let cases: [(&str, &str, u16); 5] = [
        // No upgrade headers: axum's own rejection.
        ("GET", "/api/drive?task=fine&split=val_unseen&id=1", 400),
        // A wrong method: axum's empty 405.
        ("POST", "/api/info", 405),
        ("DELETE", "/api/review/decision", 405),
        // A query that does not deserialise (a repeated field).
        (
            "GET",
            "/api/episodes?task=fine&task=coarse&split=val_unseen",
            400,
        ),
        // A body that is not JSON.
        ("POST", "/api/review/decision", 400),
    ];
    for (method, path, want) in cases {
        let body = (method == "POST").then(|| "not json".to_string());
        let (status, bytes) = srv.raw(method, path, body).await;
        let text = String::from_utf8_lossy(&bytes).to_string();
        assert_eq!(status, want, "{method} {path}: {text}");
        let v: Value = serde_json::from_slice(&bytes)
            .unwrap_or_else(|e| panic!("{method} {path}: not JSON ({e}): {text}"));
        let msg = v["error"].as_str().unwrap_or_default();
        assert!(!msg.is_empty(), "{method} {path}: {v}");
    }
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_binary_websocket_message_gets_a_json_error() {
    use futures_util::{SinkExt, StreamExt};
    use tokio_tungstenite::tungstenite::Message;
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let mut d = Driver::connect(srv.addr, &fine_query(1)).await;
    d.ws.send(Message::Binary(vec![1u8, 2, 3].into()))
        .await
        .unwrap();
    let reply = loop {
        let msg = tokio::time::timeout(Duration::from_secs(60), d.ws.next())
            .await
            .expect("a reply")
            .expect("open")
            .unwrap();
        if let Message::Text(t) = msg {
            break serde_json::from_str::<Value>(&t).unwrap();
        }
    };
    assert_eq!(reply["type"], "error", "{reply}");
    assert!(
        reply["error"].as_str().unwrap().contains("binary"),
        "{reply}"
    );
    // The session goes on: a key still moves the agent.
    let s = d.key("d").await;
    assert_eq!(s["type"], "state", "{s}");
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_second_server_on_one_output_folder_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let first = App::new(config(dir.path())).unwrap();
    let err = App::new(config(dir.path())).err().unwrap();
    let out = dir.path().join("out").canonicalize().unwrap();
    assert!(
        err.contains(&out.display().to_string())
            && err.contains(&format!("pid {}", std::process::id())),
        "{err}"
    );
    drop(first);
    // Once the first is gone the folder is free again.
    App::new(config(dir.path())).unwrap();

    // A review file kept elsewhere locks its own folder too.
    let elsewhere = dir.path().join("reviews");
    std::fs::create_dir_all(&elsewhere).unwrap();
    let mut a = config(dir.path());
    a.out = dir.path().join("out_a");
    a.review_file = Some(elsewhere.join("review.json"));
    let mut b = a.clone();
    b.out = dir.path().join("out_b");
    let _held = App::new(a).unwrap();
    let err = App::new(b).err().unwrap();
    assert!(
        err.contains("--review-file") && err.contains("reviews"),
        "{err}"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn temporary_review_files_of_a_killed_server_are_removed_and_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let out = dir.path().join("out");
    std::fs::create_dir_all(&out).unwrap();
    let stale = [".review.json.tmp4242", ".review.json.tmp1"];
    let kept = [
        ".review.json.tmpx",
        ".other.json.tmp4242",
        "review.json.tmp4242",
        "notes.txt",
    ];
    for f in stale.iter().chain(&kept) {
        std::fs::write(out.join(f), vec![b'x'; 1000]).unwrap();
    }
    let srv = Server::start(config(dir.path())).await;
    for f in stale {
        assert!(!out.join(f).exists(), "{f} left behind");
    }
    for f in kept {
        assert!(out.join(f).exists(), "{f} removed");
    }
    // Decisions still land in the review file.
    let (status, v) = srv
        .post_json(
            "/api/review/decision",
            &json!({"task": "fine", "split": "val_unseen", "episode_id": 1, "decision": "accepted"}),
        )
        .await;
    assert_eq!(status, 200, "{v}");
    assert!(out.join("review.json").is_file());
    srv.stop().await;
}
