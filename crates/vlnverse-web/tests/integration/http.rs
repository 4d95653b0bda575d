//! Paths, bad requests and the page.

use crate::support::{config, make_dataset, Server};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn path_traversal_is_refused_and_inner_files_are_served() {
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    make_dataset(&data, 2);
    std::fs::write(
        dir.path().join("vlnverse-web-secret.txt"),
        "TOP-SECRET-CONTENT",
    )
    .unwrap();
    let srv = Server::start(config(&data)).await;
    let (s, body) = srv.get("/files/dataset/scenes/tiny_000/scene.json").await;
    assert_eq!(s, 200);
    assert!(String::from_utf8_lossy(&body).contains("tiny_000"));
    for bad in [
        "/files/dataset/..%2f..%2f..%2fetc%2fpasswd",
        "/files/dataset/scenes/..%2f..%2fvlnverse-web-secret.txt",
        "/files/dataset/..%2fvlnverse-web-secret.txt",
        "/files/dataset/%2e%2e/vlnverse-web-secret.txt",
        "/files/dataset/scenes%2f..%2f..%2f..%2fetc%2fpasswd",
        "/files/dataset/%2fetc%2fpasswd",
        "/files/dataset/scenes/..%5c..%5cetc",
    ] {
        let (s, body) = srv.get(bad).await;
        let text = String::from_utf8_lossy(&body);
        assert!(s == 403 || s == 404, "{bad}: status {s}, body {text}");
        assert!(
            !text.contains("root:") && !text.contains("TOP-SECRET"),
            "{bad}: leaked {text}"
        );
        if s == 403 {
            assert!(text.contains("outside the served folder"), "{bad}: {text}");
        }
    }
    // Literal `..` segments (a client that does not normalise them).
    let (s, _) = srv.get("/files/dataset/../../etc/passwd").await;
    assert!(s == 403 || s == 404, "literal ..: {s}");
    // Runs: a run index that does not exist.
    let (s, v) = srv.get_json("/files/runs/3/summary.json").await;
    assert_eq!(s, 404);
    assert!(v["error"].as_str().unwrap().contains("no run 3"), "{v}");
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn bad_episode_ids_get_clear_json_errors() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 2);
    let srv = Server::start(config(dir.path())).await;
    let cases: &[(&str, u16, &str)] = &[
        (
            "/api/episode?task=fine&split=val_unseen&id=abc",
            400,
            "invalid episode id `abc`",
        ),
        (
            "/api/episode?task=fine&split=val_unseen&id=-1",
            400,
            "invalid episode id `-1`",
        ),
        (
            "/api/episode?task=fine&split=val_unseen&id=999",
            404,
            "no episode with episode_id 999",
        ),
        (
            "/api/episode?task=fine&split=val_unseen",
            400,
            "missing query parameter `id`",
        ),
        ("/api/episode?task=nope&split=val_unseen&id=1", 400, "nope"),
        (
            "/api/episode?task=fine&split=test&id=1",
            404,
            "has no fine/test split",
        ),
        (
            "/api/drive?task=fine&split=val_unseen&episode=999",
            404,
            "no episode with episode_id 999",
        ),
        (
            "/api/drive?task=fine&split=val_unseen&episode=x1",
            400,
            "invalid episode id `x1`",
        ),
        (
            "/api/drive?task=fine&split=val_unseen&episode=1&setting=fast",
            400,
            "fast",
        ),
        (
            "/api/drive?task=fine&split=val_unseen&episode=1&profile=tank",
            400,
            "invalid profile `tank`",
        ),
        (
            "/api/drive?task=fine&split=val_unseen&episode=1",
            400,
            "WebSocket endpoint",
        ),
        ("/api/runs/0/episodes/1", 404, "no run 0"),
        ("/api/runs/x/episodes", 400, "invalid run index `x`"),
        ("/api/nothing", 404, "no such page"),
    ];
    for (path, status, needle) in cases {
        let (s, v) = srv.get_json(path).await;
        assert_eq!(s, *status, "{path}: {v}");
        let e = v["error"]
            .as_str()
            .unwrap_or_else(|| panic!("{path}: no error field: {v}"));
        assert!(e.contains(needle), "{path}: `{e}` does not name `{needle}`");
    }
    let (s, v) = srv
        .get_json("/api/episode?task=fine&split=val_unseen&id=2")
        .await;
    assert_eq!(s, 200);
    assert_eq!(v["episode_id"], 2);
    assert_eq!(v["instruction"], "Walk to goal number 2.");
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_and_its_assets_are_served_from_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let (s, page) = srv.get("/").await;
    assert_eq!(s, 200);
    let page = String::from_utf8(page).unwrap();
    assert!(page.contains("/assets/app.js") && page.contains("mode-review"));
    assert!(
        !page.contains("http://") && !page.contains("https://"),
        "no network assets"
    );
    for a in ["app.js", "app.css"] {
        let (s, body) = srv.get(&format!("/assets/{a}")).await;
        assert_eq!(s, 200, "{a}");
        assert!(body.len() > 500, "{a}");
    }
    let (s, v) = srv.get_json("/api/info").await;
    assert_eq!(s, 200);
    assert_eq!(v["splits"][0]["task"], "fine");
    assert_eq!(v["splits"][0]["split"], "val_unseen");
    assert!(v["profiles"]
        .as_array()
        .unwrap()
        .iter()
        .any(|p| p == "vlnverse"));
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn requests_from_pages_of_other_sites_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let mut req =
        tokio_tungstenite::tungstenite::client::IntoClientRequest::into_client_request(format!(
            "ws://{}/api/drive?{}",
            srv.addr,
            crate::support::fine_query(1)
        ))
        .unwrap();
    req.headers_mut()
        .insert("Origin", "http://evil.example".parse().unwrap());
    match tokio_tungstenite::connect_async(req).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => {
            assert_eq!(r.status().as_u16(), 403)
        }
        other => panic!("expected 403, got {:?}", other.map(|_| ())),
    }
    // The page's own origin is welcome.
    let mut req =
        tokio_tungstenite::tungstenite::client::IntoClientRequest::into_client_request(format!(
            "ws://{}/api/drive?{}",
            srv.addr,
            crate::support::fine_query(1)
        ))
        .unwrap();
    req.headers_mut()
        .insert("Origin", format!("http://{}", srv.addr).parse().unwrap());
    assert!(tokio_tungstenite::connect_async(req).await.is_ok());
    srv.stop().await;
}
