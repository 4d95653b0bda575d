//! Driving: logs, concurrency, dropped clients.

use std::sync::atomic::Ordering;
use std::time::Duration;

use serde_json::json;
use vlnverse_task::trajectory::read_trajectories;

use crate::support::{config, drive_dir, fine_query, make_dataset, Driver, Server};

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_drive_to_success_is_logged_as_csv_and_trajectories() {
    let dir = tempfile::tempdir().unwrap();
    let eps = make_dataset(dir.path(), 2);
    let srv = Server::start(config(dir.path())).await;
    let mut d = Driver::connect(srv.addr, &fine_query(1)).await;
    let start = d.states[0].clone();
    assert_eq!(start["step"], 0);
    assert_eq!(start["setting"], "strict");
    // An unknown key and a malformed message are errors that change nothing.
    d.send(json!({"key": "x"})).await;
    let e = d.next_state().await;
    assert_eq!(e["type"], "error");
    assert!(e["error"].as_str().unwrap().contains("unknown key `x`"));
    d.send(json!({"jump": 1})).await;
    let e = d.next_state().await;
    assert!(e["error"].as_str().unwrap().contains("cannot read message"));
    // Depth view: a state and a frame, no step.
    d.send(json!({"view": "depth"})).await;
    let s = d.next_state().await;
    assert_eq!(
        (s["view"].as_str(), s["step"].as_u64()),
        (Some("depth"), Some(0))
    );
    tokio::time::sleep(Duration::from_millis(160)).await;
    let end = d.follow_teacher().await;
    assert_eq!(end["terminated"], true);
    assert_eq!(end["metrics"]["success"], true, "{end}");
    let steps = end["step"].as_u64().unwrap();
    // Keys after the end are refused.
    d.send(json!({"key": "w"})).await;
    let e = d.next_state().await;
    assert!(e["error"].as_str().unwrap().contains("is over"));
    drop(d);

    let out = drive_dir(dir.path());
    let trajs = read_trajectories(&out.join("trajectories.jsonl")).unwrap();
    assert_eq!(trajs.len(), 1);
    assert_eq!(trajs[0].episode_id, 1);
    assert!(trajs[0].stopped);
    assert_eq!(trajs[0].steps as u64, steps);
    let first = trajs[0].positions[0];
    let (dx, dz) = (
        first[0] - eps[0].start_position[0],
        first[2] - eps[0].start_position[2],
    );
    assert!(dx.hypot(dz) < 0.3, "starts at the episode's start");
    // The CSV: a header, rows 50 ms apart, the keys pressed, the last row at the final step.
    let csv = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|e| e == "csv"))
        .unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("time_s,step,x,y,z,heading_rad,key"));
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert!(rows.len() >= 3, "{text}");
    let times: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    for w in times.windows(2).take(rows.len() - 2) {
        let dt = w[1] - w[0];
        assert!((dt - 0.05).abs() < 1e-3, "rows {dt} s apart: {text}");
    }
    let last = rows.last().unwrap();
    assert_eq!(last[1].parse::<u64>().unwrap(), steps);
    let keys: String = rows
        .iter()
        .map(|r| r[6].clone())
        .collect::<Vec<_>>()
        .join("+");
    assert!(keys.contains("space"), "the final stop is logged: {keys}");
    let pressed = keys.split('+').filter(|k| !k.is_empty()).count() as u64;
    assert_eq!(pressed, steps, "every key of a step appears once: {keys}");
    let record = std::fs::read_to_string(csv.with_extension("json")).unwrap();
    let record: serde_json::Value = serde_json::from_str(&record).unwrap();
    assert_eq!(record["metrics"]["success"], true);
    srv.stop().await;
}

/// Drive episode `id` with the teacher and return its positions.
async fn drive_once(addr: std::net::SocketAddr, id: u64) -> (Vec<serde_json::Value>, usize) {
    let mut d = Driver::connect(addr, &fine_query(id)).await;
    let end = d.follow_teacher().await;
    assert_eq!(end["metrics"]["success"], true, "episode {id}: {end}");
    let positions = d.states.iter().map(|s| s["position"].clone()).collect();
    (positions, d.frames)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn concurrent_drivers_do_not_interfere() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 3);
    let srv = Server::start(config(dir.path())).await;
    // Alone first: the reference drives.
    let alone1 = drive_once(srv.addr, 1).await.0;
    let alone2 = drive_once(srv.addr, 2).await.0;
    // Then six at once: two per episode, interleaved.
    let mut tasks = Vec::new();
    for id in [1u64, 2, 3, 1, 2, 3] {
        let addr = srv.addr;
        tasks.push(tokio::spawn(
            async move { (id, drive_once(addr, id).await) },
        ));
    }
    let mut seen3 = Vec::new();
    for t in tasks {
        let (id, (positions, frames)) = t.await.unwrap();
        assert_eq!(frames, positions.len(), "one frame per state");
        match id {
            1 => assert_eq!(positions, alone1, "episode 1 driven alongside others"),
            2 => assert_eq!(positions, alone2, "episode 2 driven alongside others"),
            _ => seen3.push(positions),
        }
    }
    assert_eq!(seen3[0], seen3[1]);
    // Every driver's place is given back.
    for _ in 0..100 {
        if srv.app.drivers.load(Ordering::SeqCst) == 0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    assert_eq!(srv.app.drivers.load(Ordering::SeqCst), 0);
    let trajs = read_trajectories(&drive_dir(dir.path()).join("trajectories.jsonl")).unwrap();
    let ids: Vec<u64> = trajs.iter().map(|t| t.episode_id).collect();
    assert_eq!(ids, vec![1, 2, 3], "one line per episode, the latest drive");
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_server_keeps_serving_after_a_client_drops_mid_episode() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 2);
    let mut cfg = config(dir.path());
    cfg.max_drivers = 1;
    let srv = Server::start(cfg).await;
    {
        let mut d = Driver::connect(srv.addr, &fine_query(1)).await;
        let k = d.states[0]["expert_key"].as_str().unwrap().to_string();
        d.key(&k).await;
        let (s, _) = srv.get("/api/info").await;
        assert_eq!(s, 200);
        // Queue keys and vanish without a close handshake. (Turns only: in this home a step
        // forward from there collides, which ends the episode in Strict and writes it.)
        d.send(json!({"key": "d"})).await;
        d.send(json!({"key": "a"})).await;
        let stream = d.ws.into_inner();
        drop(stream);
    }
    // The place comes back, the partial drive left a CSV and no trajectory.
    for _ in 0..200 {
        if srv.app.drivers.load(Ordering::SeqCst) == 0 {
            break;
        }
        tokio::time::sleep(Duration::from_millis(25)).await;
    }
    assert_eq!(
        srv.app.drivers.load(Ordering::SeqCst),
        0,
        "the dropped driver's place is free"
    );
    let out = drive_dir(dir.path());
    assert!(!out.join("trajectories.jsonl").exists());
    let csvs = std::fs::read_dir(&out).unwrap().count();
    assert_eq!(csvs, 1);
    let (s, v) = srv.get_json("/api/stats").await;
    assert_eq!((s, v["drivers"].as_u64()), (200, Some(0)));
    // A new driver completes its episode.
    let mut d = Driver::connect(srv.addr, &fine_query(2)).await;
    let end = d.follow_teacher().await;
    assert_eq!(end["metrics"]["success"], true);
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn drivers_beyond_the_limit_are_told_the_server_is_busy() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let mut cfg = config(dir.path());
    cfg.max_drivers = 1;
    let srv = Server::start(cfg).await;
    let _d = Driver::connect(srv.addr, &fine_query(1)).await;
    let url = format!("ws://{}/api/drive?{}", srv.addr, fine_query(1));
    match tokio_tungstenite::connect_async(url).await {
        Err(tokio_tungstenite::tungstenite::Error::Http(r)) => {
            assert_eq!(r.status().as_u16(), 503);
            let body = String::from_utf8_lossy(r.body().as_deref().unwrap_or_default()).to_string();
            assert!(body.contains("--max-drivers"), "{body}");
        }
        other => panic!("expected 503, got {:?}", other.map(|_| ())),
    }
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn dialogue_questions_are_answered_within_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let mut d = Driver::connect(
        srv.addr,
        "task=dialogue&split=val_unseen&episode=1&setting=strict",
    )
    .await;
    assert_eq!(d.states[0]["questions_left"], 2);
    for left in [1, 0] {
        d.send(json!({"ask": "which way?"})).await;
        let s = d.next_state().await;
        assert_eq!(s["step"], 0, "a question within the budget costs no step");
        assert_eq!(s["questions_left"], left);
        assert!(s["answer"].as_str().unwrap().len() > 3, "{s}");
    }
    d.send(json!({"ask": "and now?"})).await;
    let s = d.next_state().await;
    assert_eq!(
        s["step"], 1,
        "a question beyond the budget is a refused action"
    );
    assert_eq!(s["refused"], "no questions left");
    let end = d.follow_teacher().await;
    assert_eq!(end["metrics"]["success"], true);
    srv.stop().await;
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn walking_into_a_wall_fails_a_strict_episode_as_in_evaluation() {
    let dir = tempfile::tempdir().unwrap();
    make_dataset(dir.path(), 1);
    let srv = Server::start(config(dir.path())).await;
    let mut d = Driver::connect(srv.addr, &fine_query(1)).await;
    let mut s = d.states[0].clone();
    for _ in 0..80 {
        if s["done"].as_bool().unwrap() {
            break;
        }
        s = d.key("w").await;
    }
    assert_eq!(s["done"], true, "15+ m straight ahead meets a wall: {s}");
    assert_eq!(s["terminated"], true);
    assert_eq!(s["noticeable"], true);
    assert!(
        s["failure"].is_string(),
        "a Strict failure is reported: {s}"
    );
    assert_eq!(s["metrics"]["success"], false);
    assert_eq!(s["metrics"]["collisions"], 1);
    srv.stop().await;
}
