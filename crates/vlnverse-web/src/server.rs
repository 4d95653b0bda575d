//! The router: the page and its assets, the catalogue of the dataset, the three modes' APIs,
//! and raw files of the dataset and runs (refused outside them).
//!
//! Every request must name this server in `Host` ([`AllowedHosts`]: a loopback name on the
//! served port, or a name given with `--allow-host`), so a web page whose own name was rebound
//! to 127.0.0.1 (DNS rebinding) can neither read nor write; requests that carry `Origin` (POSTs,
//! WebSocket handshakes) must also come from a page of this server.

use std::net::{IpAddr, SocketAddr};
use std::sync::atomic::Ordering;
use std::sync::Arc;

use axum::extract::{Path as UrlPath, Query, State};
use axum::http::header;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use serde_json::{json, Value};
use vlnverse_task::{dataset, Split, Task};

use crate::app::{profiles, App};
use crate::error::{ApiError, ApiResult};
use crate::files::{content_type, resolve_inside};
use crate::{assets, drive, replay, review};

/// The `Host` names the server answers: `127.0.0.1`, `localhost` and `[::1]` on the served
/// port, the address it is bound to (when not a wildcard), and the names added with
/// [`AllowedHosts::allow`] (`cargo xtask serve --allow-host NAME`). A request naming any other
/// host is refused with 403: its page reached this server through a name rebound to it.
#[derive(Debug, Clone)]
pub struct AllowedHosts {
    port: u16,
    /// This machine's names (lower case): answered on the served port only.
    local: Vec<String>,
    /// Names added by the user (lower case, no port): answered on the served port or with no
    /// port (a proxy in front of the app serving it on the default port).
    names: Vec<String>,
    /// `name:port` entries added by the user (lower case): answered exactly.
    with_port: Vec<String>,
}

impl AllowedHosts {
    /// The loopback names on `port`.
    pub fn loopback(port: u16) -> Self {
        AllowedHosts {
            port,
            local: vec!["127.0.0.1".into(), "localhost".into(), "[::1]".into()],
            names: Vec::new(),
            with_port: Vec::new(),
        }
    }

    /// The loopback names and `addr`'s IP (unless it is `0.0.0.0` or `[::]`) on `addr`'s port.
    pub fn for_addr(addr: SocketAddr) -> Self {
        let mut hosts = Self::loopback(addr.port());
        let ip = addr.ip();
        if !ip.is_unspecified() && !ip.is_loopback() {
            hosts.local.push(match ip {
                IpAddr::V4(ip) => ip.to_string(),
                IpAddr::V6(ip) => format!("[{ip}]"),
            });
        }
        hosts
    }

    /// Also answer `name`: a host name or IP (`[...]` for IPv6) on the served port or with no
    /// port, or `name:port` for exactly that.
    pub fn allow(mut self, name: impl AsRef<str>) -> Self {
        let name = name.as_ref().trim().to_ascii_lowercase();
        if name.is_empty() {
            return self;
        }
        match split_port(&name) {
            (_, Some(_)) => self.with_port.push(name),
            (_, None) => self.names.push(name),
        }
        self
    }

    /// The served port.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// Whether a request with this `Host` header is answered.
    pub fn admits(&self, host: &str) -> bool {
        let host = host.trim().to_ascii_lowercase();
        if self.with_port.contains(&host) {
            return true;
        }
        let (name, port) = split_port(&host);
        let port = match port {
            Some(p) => match p.parse::<u16>() {
                Ok(p) => Some(p),
                Err(_) => return false,
            },
            None => None,
        };
        let served = port.unwrap_or(80) == self.port;
        (served && self.local.iter().any(|n| n == name))
            || ((served || port.is_none()) && self.names.iter().any(|n| n == name))
    }
}

/// `host[:port]` or `[v6][:port]` split at the port (the port not parsed).
fn split_port(host: &str) -> (&str, Option<&str>) {
    if host.starts_with('[') {
        return match host.find(']') {
            Some(end) => {
                let (name, rest) = host.split_at(end + 1);
                (name, rest.strip_prefix(':'))
            }
            None => (host, None),
        };
    }
    match host.rsplit_once(':') {
        Some((name, port)) if !name.contains(':') => (name, Some(port)),
        _ => (host, None),
    }
}

/// The app's routes over a shared state, answering only requests whose `Host` is in `hosts`.
pub fn router(app: Arc<App>, hosts: AllowedHosts) -> Router {
    Router::new()
        .route("/", get(|| async { asset("index.html") }))
        .route(
            "/assets/{name}",
            get(|UrlPath(n): UrlPath<String>| async move { asset(&n) }),
        )
        .route("/api/info", get(info))
        .route("/api/stats", get(stats))
        .route("/api/episodes", get(episodes))
        .route("/api/episode", get(episode))
        .route("/api/reference-image", get(reference_image))
        .route("/api/drive", get(drive::drive_ws))
        .route("/api/runs", get(replay::runs))
        .route("/api/runs/{run}/episodes", get(replay::run_episodes))
        .route("/api/runs/{run}/episodes/{id}", get(replay::run_episode))
        .route(
            "/api/runs/{run}/episodes/{id}/topdown.png",
            get(replay::run_topdown),
        )
        .route(
            "/api/runs/{run}/episodes/{id}/view/{step}",
            get(replay::run_view),
        )
        .route("/api/review/episodes", get(review::review_list))
        .route("/api/review/view", get(review::review_view))
        .route("/api/review/topdown.png", get(review::review_topdown))
        .route("/api/review/decision", post(review::review_decide))
        .route("/api/review/decisions", get(review::review_decisions))
        .route("/files/dataset/{*path}", get(dataset_file))
        .route("/files/runs/{run}/{*path}", get(run_file))
        .fallback(|| async { ApiError::not_found("no such page or endpoint") })
        .layer(axum::middleware::from_fn(same_origin))
        .layer(axum::middleware::from_fn(move |req, next| {
            known_host(hosts.clone(), req, next)
        }))
        .layer(axum::middleware::from_fn(json_errors))
        .with_state(app)
}

/// Every error is the documented JSON `{"error": "..."}`: the answers that axum's extractors
/// and router give on their own (a path or query that does not parse, a WebSocket request
/// without its upgrade headers, a wrong method) are plain text or empty, and are rewritten
/// here with their status and headers kept.
async fn json_errors(req: axum::extract::Request, next: axum::middleware::Next) -> Response {
    let resp = next.run(req).await;
    let status = resp.status();
    if !(status.is_client_error() || status.is_server_error()) {
        return resp;
    }
    let is_json = resp
        .headers()
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|t| t.starts_with("application/json"));
    if is_json {
        return resp;
    }
    let (mut parts, body) = resp.into_parts();
    let bytes = axum::body::to_bytes(body, 64 * 1024)
        .await
        .unwrap_or_default();
    let text = String::from_utf8_lossy(&bytes).trim().to_string();
    let message = if text.is_empty() {
        format!(
            "{} {}",
            status.as_u16(),
            status.canonical_reason().unwrap_or("error")
        )
    } else {
        text
    };
    let body = serde_json::to_vec(&json!({ "error": message })).unwrap_or_default();
    parts.headers.remove(header::CONTENT_LENGTH);
    parts.headers.insert(
        header::CONTENT_TYPE,
        header::HeaderValue::from_static("application/json"),
    );
    Response::from_parts(parts, axum::body::Body::from(body))
}

/// Refuse requests whose `Host` is not one of this server's names (DNS rebinding: a page of
/// `evil.example` whose name now resolves to 127.0.0.1 sends `Host: evil.example:PORT`, and its
/// `Origin` matches that host, so only the host itself tells it apart).
async fn known_host(
    hosts: AllowedHosts,
    req: axum::extract::Request,
    next: axum::middleware::Next,
) -> Response {
    let host = req
        .headers()
        .get(header::HOST)
        .map(|h| h.to_str().unwrap_or("(not text)"));
    // An absolute request target (`GET http://name/ HTTP/1.1`) names the host too.
    let target = req.uri().authority().map(|a| a.as_str());
    let refused = match (host, target) {
        (None, None) => Some("(none)".to_string()),
        (h, t) => h
            .into_iter()
            .chain(t)
            .find(|h| !hosts.admits(h))
            .map(str::to_string),
    };
    if let Some(host) = refused {
        return ApiError::forbidden(format!(
            "requests for host `{host}` are refused: this server answers 127.0.0.1, localhost \
             and [::1] on port {} (start it with `--allow-host NAME` to add a name)",
            hosts.port()
        ))
        .into_response();
    }
    next.run(req).await
}

/// Refuse requests sent by pages of other sites: a browser names the page's origin in
/// `Origin` (WebSocket handshakes and POSTs always); it must be this server's own address, so
/// a web page elsewhere cannot drive, review or read through the user's browser.
async fn same_origin(req: axum::extract::Request, next: axum::middleware::Next) -> Response {
    let headers = req.headers();
    if let Some(origin) = headers.get(header::ORIGIN) {
        let host = headers
            .get(header::HOST)
            .and_then(|h| h.to_str().ok())
            .unwrap_or("");
        let origin = origin.to_str().unwrap_or("");
        let own = origin
            .strip_prefix("http://")
            .or_else(|| origin.strip_prefix("https://"))
            .is_some_and(|o| o == host);
        if !own {
            return ApiError::forbidden(format!(
                "requests from pages of other sites are refused (Origin `{origin}`, this server `{host}`)"
            ))
            .into_response();
        }
    }
    next.run(req).await
}

fn asset(name: &str) -> Response {
    match assets::get(name) {
        Some((bytes, ty)) => (
            [
                (header::CONTENT_TYPE, ty),
                (header::CACHE_CONTROL, "no-cache"),
            ],
            bytes,
        )
            .into_response(),
        None => ApiError::not_found(format!("no asset `{name}`")).into_response(),
    }
}

/// `GET /api/info`: the dataset's tasks and splits (with episode counts), settings, profiles,
/// runs and whether teacher hints are on.
async fn info(State(app): State<Arc<App>>) -> Json<Value> {
    let mut splits = Vec::new();
    for task in Task::ALL {
        for split in Split::ALL {
            if dataset::split_path(&app.dataset, task, split).is_file() {
                splits.push(json!({"task": task.name(), "split": split.name()}));
            }
        }
    }
    Json(json!({
        "dataset": app.dataset.display().to_string(),
        "splits": splits,
        "settings": ["strict", "telhop", "lenient"],
        "profiles": profiles(),
        "runs": app.runs.iter().map(|r| r.name.clone()).collect::<Vec<_>>(),
        "teacher_hints": app.cfg.teacher_hints,
        "drive_log": crate::drive::drive_dir(&app.out, Task::Fine, Split::Train)
            .parent().and_then(|p| p.parent()).map(|p| p.display().to_string()),
        "keys": {"w": "forward", "a": "turn left", "d": "turn right", "q": "look up", "e": "look down", "space": "stop"},
    }))
}

/// Resident memory of this process (bytes), from `/proc/self/status` (Linux).
pub fn rss_bytes() -> Option<u64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmRSS:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

/// `GET /api/stats`: drivers connected and the server's resident memory.
async fn stats(State(app): State<Arc<App>>) -> Json<Value> {
    Json(json!({
        "drivers": app.drivers.load(Ordering::SeqCst),
        "rss_bytes": rss_bytes(),
    }))
}

/// Query naming a split (and an episode).
#[derive(Debug, Default, serde::Deserialize)]
struct EpQuery {
    task: Option<String>,
    split: Option<String>,
    id: Option<String>,
}

fn need<'a>(v: &'a Option<String>, name: &str) -> ApiResult<&'a str> {
    v.as_deref()
        .filter(|s| !s.is_empty())
        .ok_or_else(|| ApiError::bad_request(format!("missing query parameter `{name}`")))
}

/// `GET /api/episodes?task&split`: the split's episodes (id, scene, instruction).
async fn episodes(State(app): State<Arc<App>>, Query(q): Query<EpQuery>) -> ApiResult<Json<Value>> {
    let (task, split) = App::task_split(need(&q.task, "task")?, need(&q.split, "split")?)?;
    let eps = app.episodes(task, split)?;
    let list: Vec<Value> = eps
        .iter()
        .map(|e| {
            json!({
                "episode_id": e.episode_id,
                "scene_id": e.scene_id,
                "instruction": e.instruction.instruction_text,
                "geodesic_distance": e.info.geodesic_distance,
            })
        })
        .collect();
    Ok(Json(
        json!({"task": task.name(), "split": split.name(), "episodes": list}),
    ))
}

/// `GET /api/episode?task&split&id`: what the driver is shown of an episode.
async fn episode(State(app): State<Arc<App>>, Query(q): Query<EpQuery>) -> ApiResult<Json<Value>> {
    let (task, split) = App::task_split(need(&q.task, "task")?, need(&q.split, "split")?)?;
    let id = App::parse_id(need(&q.id, "id")?)?;
    let (eps, k) = app.episode(task, split, id)?;
    let e = &eps[k];
    Ok(Json(json!({
        "task": task.name(),
        "split": split.name(),
        "episode_id": e.episode_id,
        "scene_id": e.scene_id,
        "instruction": e.instruction.instruction_text,
        "sub_instructions": e.instruction.sub_instructions,
        "style": e.style(),
        "has_reference_image": e.reference_image.is_some(),
        "oracle_budget": e.oracle_budget,
    })))
}

/// `GET /api/reference-image?task&split&id`: a visual-reference episode's goal image.
async fn reference_image(
    State(app): State<Arc<App>>,
    Query(q): Query<EpQuery>,
) -> ApiResult<Response> {
    let (task, split) = App::task_split(need(&q.task, "task")?, need(&q.split, "split")?)?;
    let id = App::parse_id(need(&q.id, "id")?)?;
    let (eps, k) = app.episode(task, split, id)?;
    let rel = eps[k].reference_image.clone().ok_or_else(|| {
        ApiError::not_found(format!(
            "{task}/{split} episode {id} has no reference image"
        ))
    })?;
    let split_dir = dataset::split_path(&app.dataset, task, split)
        .parent()
        .map(|p| p.to_path_buf())
        .unwrap_or_else(|| app.dataset.clone());
    // The image path is relative to the split's folder and must stay inside the dataset.
    let rel_to_dataset = split_dir
        .strip_prefix(&app.dataset)
        .map(|p| p.join(&rel))
        .map_err(|_| ApiError::internal("split folder outside the dataset"))?;
    let rel_str = rel_to_dataset.to_string_lossy().replace('\\', "/");
    serve_file(&app.dataset, &rel_str).await
}

async fn serve_file(root: &std::path::Path, rel: &str) -> ApiResult<Response> {
    let path = resolve_inside(root, rel)?;
    let bytes = tokio::fs::read(&path)
        .await
        .map_err(|e| ApiError::not_found(format!("{rel}: {e}")))?;
    Ok(([(header::CONTENT_TYPE, content_type(&path))], bytes).into_response())
}

/// `GET /files/dataset/{path}`: a file of the dataset.
async fn dataset_file(
    State(app): State<Arc<App>>,
    UrlPath(path): UrlPath<String>,
) -> ApiResult<Response> {
    serve_file(&app.dataset, &path).await
}

/// `GET /files/runs/{run}/{path}`: a file of a run folder (plots, report.md, ...).
async fn run_file(
    State(app): State<Arc<App>>,
    UrlPath((run, path)): UrlPath<(String, String)>,
) -> ApiResult<Response> {
    let i: usize = run
        .parse()
        .map_err(|_| ApiError::bad_request(format!("invalid run index `{run}`")))?;
    let dir = app.run(i)?.dir.clone();
    serve_file(&dir, &path).await
}

/// Serve on `listener` until `shutdown` resolves, answering the loopback names (and the bound
/// address) on the listener's port.
pub async fn serve_on(
    app: Arc<App>,
    listener: tokio::net::TcpListener,
    shutdown: impl std::future::Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    serve_on_with(app, listener, &[], shutdown).await
}

/// [`serve_on`], also answering the host names `allow_hosts` (see [`AllowedHosts::allow`]).
///
/// Each connection must send a request's headers within `header_timeout` of the
/// configuration or is closed, and at most `max_connections` are served at once: a further
/// one is answered at once with a 503 JSON error and closed (`refuse_busy`), so clients
/// that open connections and send headers slowly cannot hold the server, and a client over
/// the limit learns why instead of waiting in the listen queue.
pub async fn serve_on_with(
    app: Arc<App>,
    listener: tokio::net::TcpListener,
    allow_hosts: &[String],
    shutdown: impl std::future::Future<Output = ()> + Send + 'static,
) -> std::io::Result<()> {
    use hyper_util::rt::{TokioIo, TokioTimer};
    use hyper_util::service::TowerToHyperService;

    let hosts = allow_hosts
        .iter()
        .fold(AllowedHosts::for_addr(listener.local_addr()?), |h, n| {
            h.allow(n)
        });
    let header_timeout = app.cfg.header_timeout;
    let max_connections = app.cfg.max_connections.max(1);
    let slots = Arc::new(tokio::sync::Semaphore::new(max_connections));
    // Refusals in flight; past this many a connection over the limit is closed unanswered.
    let refusals = Arc::new(tokio::sync::Semaphore::new(MAX_REFUSALS));
    let router = router(app, hosts);
    // `stop` tells connections to finish (graceful shutdown); `done` closes when the last
    // connection task has ended.
    let (stop_tx, stop_rx) = tokio::sync::watch::channel(());
    let (done_tx, done_rx) = tokio::sync::watch::channel(());
    let mut shutdown = std::pin::pin!(shutdown);
    loop {
        let tcp = tokio::select! {
            r = listener.accept() => match r {
                Ok((tcp, _)) => tcp,
                Err(e) => {
                    // Out of file descriptors and the like: wait instead of spinning.
                    tracing::warn!(error = %e, "accept failed");
                    tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                    continue;
                }
            },
            _ = &mut shutdown => break,
        };
        let Ok(slot) = slots.clone().try_acquire_owned() else {
            if let Ok(permit) = refusals.clone().try_acquire_owned() {
                let done_rx = done_rx.clone();
                tokio::spawn(async move {
                    refuse_busy(tcp, max_connections).await;
                    drop(permit);
                    drop(done_rx);
                });
            }
            continue;
        };
        // A frame is a text message and a binary one: without TCP_NODELAY the second waits
        // for the client's delayed ACK (~40 ms), which capped a driver at ~20 frames/s.
        let _ = tcp.set_nodelay(true);
        let service = TowerToHyperService::new(router.clone());
        let mut stop_rx = stop_rx.clone();
        let done_rx = done_rx.clone();
        tokio::spawn(async move {
            let mut builder = hyper::server::conn::http1::Builder::new();
            builder
                .timer(TokioTimer::new())
                .header_read_timeout(header_timeout);
            let conn = builder
                .serve_connection(TokioIo::new(tcp), service)
                .with_upgrades();
            let mut conn = std::pin::pin!(conn);
            let mut stopping = false;
            loop {
                tokio::select! {
                    r = conn.as_mut() => {
                        if let Err(e) = r {
                            tracing::debug!(error = %e, "connection ended with an error");
                        }
                        break;
                    }
                    _ = stop_rx.changed(), if !stopping => {
                        stopping = true;
                        conn.as_mut().graceful_shutdown();
                    }
                }
            }
            drop(slot);
            drop(done_rx);
        });
    }
    drop(listener);
    drop(stop_tx);
    drop(done_rx);
    done_tx.closed().await;
    Ok(())
}

/// Connections over the limit being answered 503 at once (each for at most
/// [`REFUSAL_DRAIN`]); a flood beyond this is closed unanswered.
const MAX_REFUSALS: usize = 256;
/// How long a refused connection's request is read (and thrown away) after the answer.
const REFUSAL_DRAIN: std::time::Duration = std::time::Duration::from_millis(500);

/// Answer a connection over the `max` limit with a 503 JSON error and close it, without
/// reading its request. The request is then drained for a moment so closing does not reset
/// the connection before the client has read the answer.
async fn refuse_busy(mut tcp: tokio::net::TcpStream, max: usize) {
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let body = json!({
        "error": format!(
            "server busy: {max} connections are open (the server's limit); try again shortly"
        )
    })
    .to_string();
    let head = format!(
        "HTTP/1.1 503 Service Unavailable\r\ncontent-type: application/json\r\n\
         content-length: {}\r\nretry-after: 1\r\nconnection: close\r\n\r\n",
        body.len()
    );
    let drain = async {
        tcp.write_all(format!("{head}{body}").as_bytes()).await?;
        tcp.shutdown().await?;
        let mut buf = [0u8; 4096];
        while tcp.read(&mut buf).await? > 0 {}
        std::io::Result::Ok(())
    };
    let _ = tokio::time::timeout(REFUSAL_DRAIN, drain).await;
}

/// Bind `addr` and serve until Ctrl-C; `on_ready` gets the bound address (port 0 picks a free
/// one) before the first request is taken. Only the loopback names and the bound address are
/// answered ([`AllowedHosts::for_addr`]; [`run_server_with`] adds names).
pub fn run_server(
    cfg: crate::ServerConfig,
    addr: SocketAddr,
    on_ready: impl FnOnce(SocketAddr),
) -> Result<(), String> {
    run_server_with(cfg, addr, &[], on_ready)
}

/// [`run_server`], also answering the host names `allow_hosts` (`cargo xtask serve
/// --allow-host`, see [`AllowedHosts::allow`]).
pub fn run_server_with(
    cfg: crate::ServerConfig,
    addr: SocketAddr,
    allow_hosts: &[String],
    on_ready: impl FnOnce(SocketAddr),
) -> Result<(), String> {
    let app = Arc::new(App::new(cfg)?);
    let rt = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| format!("cannot start the async runtime: {e}"))?;
    rt.block_on(async move {
        let listener = tokio::net::TcpListener::bind(addr)
            .await
            .map_err(|e| format!("cannot listen on {addr}: {e}"))?;
        let bound = listener
            .local_addr()
            .map_err(|e| format!("listening socket: {e}"))?;
        on_ready(bound);
        serve_on_with(app, listener, allow_hosts, async {
            let _ = tokio::signal::ctrl_c().await;
        })
        .await
        .map_err(|e| format!("server on {bound}: {e}"))
    })
}
