//! DNS rebinding: only requests naming this server in `Host` (a loopback name on the served
//! port, or a name given with `--allow-host`) are answered, for every route; a page whose name
//! was rebound to 127.0.0.1 can neither read the dataset nor write the review file.

use std::net::SocketAddr;
use std::sync::Arc;

use serde_json::{json, Value};
use tokio::io::{AsyncReadExt, AsyncWriteExt};
use vlnverse_web::server::{serve_on_with, AllowedHosts};
use vlnverse_web::App;

use crate::support::{config, fine_query, make_dataset, Server};

/// One raw HTTP/1.1 request with the headers exactly as given: (status, JSON body or null).
async fn raw(
    addr: SocketAddr,
    method: &str,
    path: &str,
    headers: &[(&str, String)],
    body: Option<&Value>,
) -> (u16, Value) {
    let mut s = tokio::net::TcpStream::connect(addr).await.unwrap();
    let body = body.map(|b| b.to_string()).unwrap_or_default();
    let mut req = format!("{method} {path} HTTP/1.1\r\nConnection: close\r\n");
    for (k, v) in headers {
        req.push_str(&format!("{k}: {v}\r\n"));
    }
    req.push_str(&format!(
        "Content-Type: application/json\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    ));
    s.write_all(req.as_bytes()).await.unwrap();
    let mut buf = Vec::new();
    tokio::time::timeout(std::time::Duration::from_secs(30), s.read_to_end(&mut buf))
        .await
        .expect("the server answers within 30 s")
        .unwrap();
    let end = buf
        .windows(4)
        .position(|w| w == b"\r\n\r\n")
        .expect("an HTTP response");
    let head = String::from_utf8_lossy(&buf[..end]).to_string();
    let status = head.split_whitespace().nth(1).unwrap().parse().unwrap();
    let text = String::from_utf8_lossy(&buf[end + 4..]).to_string();
    // Small JSON bodies come whole or as one chunk: take the JSON object inside.
    let json = match (text.find('{'), text.rfind('}')) {
        (Some(a), Some(b)) if a < b => serde_json::from_str(&text[a..=b]).unwrap_or(Value::Null),
        _ => Value::Null,
    };
    (status, json)
}

fn host(h: &str) -> (&'static str, String) {
    ("Host", h.to_string())
}

fn origin(o: &str) -> (&'static str, String) {
    ("Origin", o.to_string())
}

fn decision(id: u64) -> Value {
    json!({"task": "fine", "split": "val_unseen", "episode_id": id, "decision": "rejected"})
}

/// A 403 with the app's JSON error naming the refused host.
fn assert_refused((status, body): (u16, Value), what: &str, name: &str) {
    assert_eq!(status, 403, "{what}: {body}");
    let msg = body["error"]
        .as_str()
        .unwrap_or_else(|| panic!("{what}: {body}"));
    assert!(msg.contains(name), "{what}: {msg}");
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn rebinding_requests_are_refused_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let port = srv.addr.port();
    let evil = format!("evil.example:{port}");
    let review = dir.path().join("out/review.json");

    // The rebinding page's POST: its Origin matches its Host, so only the Host tells it apart.
    let r = raw(
        srv.addr,
        "POST",
        "/api/review/decision",
        &[host(&evil), origin(&format!("http://{evil}"))],
        Some(&decision(1)),
    )
    .await;
    assert_refused(r, "rebinding POST", "evil.example");
    assert!(
        !review.exists(),
        "a refused decision wrote {}",
        review.display()
    );

    // Reading is refused too: the page, the catalogue, the data files, the drive socket.
    for path in [
        "/".to_string(),
        "/api/info".to_string(),
        "/api/episodes?task=fine&split=val_unseen".to_string(),
        "/api/review/decisions".to_string(),
        "/files/dataset/fine/val_unseen/val_unseen.json.gz".to_string(),
        format!("/api/drive?{}", fine_query(1)),
    ] {
        let r = raw(srv.addr, "GET", &path, &[host(&evil)], None).await;
        assert_refused(r, &path, "evil.example");
    }
    let mut ws = tokio_tungstenite::tungstenite::client::IntoClientRequest::into_client_request(
        format!("ws://{}/api/drive?{}", srv.addr, fine_query(1)),
    )
    .unwrap();
    ws.headers_mut().insert("Host", evil.parse().unwrap());
    ws.headers_mut()
        .insert("Origin", format!("http://{evil}").parse().unwrap());
    match tokio_tungstenite::connect_async(ws).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => {
            assert_eq!(r.status().as_u16(), 403)
        }
        other => panic!(
            "rebinding WebSocket: expected 403, got {:?}",
            other.map(|_| ())
        ),
    }
    assert_eq!(srv.app.drivers.load(std::sync::atomic::Ordering::SeqCst), 0);

    // Loopback names on another port, look-alikes, no Host at all, and an absolute target
    // naming another host are refused as well.
    let other = if port == 65535 { 1 } else { port + 1 };
    for h in [
        format!("127.0.0.1:{other}"),
        format!("localhost:{other}"),
        "localhost".to_string(),
        format!("localhost.evil.example:{port}"),
        format!("127.0.0.1.evil.example:{port}"),
        format!("localhost:{port}x"),
    ] {
        let r = raw(srv.addr, "GET", "/api/info", &[host(&h)], None).await;
        assert_eq!(r.0, 403, "Host {h}: {}", r.1);
    }
    let r = raw(srv.addr, "GET", "/api/info", &[], None).await;
    assert_eq!(r.0, 403, "no Host: {}", r.1);
    let r = raw(
        srv.addr,
        "POST",
        &format!("http://{evil}/api/review/decision"),
        &[host(&format!("127.0.0.1:{port}"))],
        Some(&decision(1)),
    )
    .await;
    assert_eq!(r.0, 403, "absolute target: {}", r.1);
    assert!(
        !review.exists(),
        "a refused decision wrote {}",
        review.display()
    );
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn loopback_hosts_on_the_served_port_are_answered() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 2);
    let srv = Server::start(config(dir.path())).await;
    let port = srv.addr.port();
    for h in [
        format!("127.0.0.1:{port}"),
        format!("localhost:{port}"),
        format!("LocalHost:{port}"),
        format!("[::1]:{port}"),
    ] {
        let (s, v) = raw(srv.addr, "GET", "/api/info", &[host(&h)], None).await;
        assert_eq!(s, 200, "Host {h}: {v}");
        assert_eq!(v["splits"][0]["task"], "fine", "Host {h}");
    }
    // A page of this server posts with its own origin, under either name.
    for (id, name) in [(1, "127.0.0.1"), (2, "localhost")] {
        let me = format!("{name}:{port}");
        let (s, v) = raw(
            srv.addr,
            "POST",
            "/api/review/decision",
            &[host(&me), origin(&format!("http://{me}"))],
            Some(&decision(id)),
        )
        .await;
        assert_eq!(s, 200, "{me}: {v}");
    }
    // The Origin check stays: our Host with another site's Origin is refused.
    let me = format!("localhost:{port}");
    let r = raw(
        srv.addr,
        "POST",
        "/api/review/decision",
        &[host(&me), origin("http://evil.example")],
        Some(&decision(1)),
    )
    .await;
    assert_refused(r, "foreign Origin", "evil.example");
    let (s, v) = raw(srv.addr, "GET", "/api/review/decisions", &[host(&me)], None).await;
    assert_eq!(s, 200, "{v}");
    srv.stop().await;
    let doc = vlnverse_web::read_review(&dir.path().join("out/review.json")).unwrap();
    assert_eq!(doc.decisions.len(), 2);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn allow_host_admits_a_named_host() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let app = Arc::new(App::new(config(dir.path())).unwrap());
    let listener = tokio::net::TcpListener::bind("127.0.0.1:0").await.unwrap();
    let addr = listener.local_addr().unwrap();
    let port = addr.port();
    let (tx, rx) = tokio::sync::oneshot::channel::<()>();
    let allow = vec!["VLNVerse.Lan".to_string(), "proxy.example:8443".to_string()];
    let task = tokio::spawn(async move {
        serve_on_with(app, listener, &allow, async move {
            let _ = rx.await;
        })
        .await
    });
    let named = format!("vlnverse.lan:{port}");
    for h in [
        named.clone(),
        "vlnverse.lan".to_string(),
        "proxy.example:8443".to_string(),
        format!("127.0.0.1:{port}"),
    ] {
        let (s, v) = raw(addr, "GET", "/api/info", &[host(&h)], None).await;
        assert_eq!(s, 200, "Host {h}: {v}");
    }
    let (s, v) = raw(
        addr,
        "POST",
        "/api/review/decision",
        &[host(&named), origin(&format!("http://{named}"))],
        Some(&decision(1)),
    )
    .await;
    assert_eq!(s, 200, "{v}");
    for h in [
        format!("evil.example:{port}"),
        format!("proxy.example:{port}"),
        "vlnverse.lan:1".to_string(),
    ] {
        let r = raw(addr, "GET", "/api/info", &[host(&h)], None).await;
        assert_eq!(r.0, 403, "Host {h}: {}", r.1);
    }
    let _ = tx.send(());
    let _ = tokio::time::timeout(std::time::Duration::from_secs(10), task).await;
    assert!(dir.path().join("out/review.json").is_file());
}

#[test]
fn allowed_hosts_match_names_and_ports() {
    let h = AllowedHosts::loopback(8787).allow("lab.example");
    for ok in [
        "127.0.0.1:8787",
        "localhost:8787",
        "[::1]:8787",
        " LOCALHOST:8787 ",
        "lab.example:8787",
        "lab.example",
    ] {
        assert!(h.admits(ok), "{ok}");
    }
    for bad in [
        "",
        "127.0.0.1",
        "127.0.0.1:80",
        "127.0.0.2:8787",
        "localhost:08787x",
        "[::1]",
        "::1:8787",
        "lab.example:1",
        "sub.lab.example:8787",
        "evil.example:8787",
    ] {
        assert!(!h.admits(bad), "{bad}");
    }
    assert!(AllowedHosts::loopback(80).admits("localhost"));
    let bound = AllowedHosts::for_addr("192.168.1.5:9000".parse().unwrap());
    assert!(bound.admits("192.168.1.5:9000") && !bound.admits("192.168.1.5:9001"));
    let any = AllowedHosts::for_addr("0.0.0.0:9000".parse().unwrap());
    assert!(!any.admits("0.0.0.0:9000") && any.admits("localhost:9000"));
}
