//! `threadcheck serve`: the shop's page and the JSON API, one binary, no outside resource.
//!
//! `GET /` is the page (plain HTML, a small script of ours, a style sheet: all embedded);
//! `POST /api/{command}` answers with exactly what `threadcheck {command} --json -` prints for
//! the same input, `POST /api/{command}/{document}` with the command's `text`, `svg`, `html` or
//! `fix` document; the body is a JSON object of the Python function's keyword arguments
//! ([`run_request`](crate::run_request) with files refused: the server reads no file of its own
//! for a request). Nothing is written to disk.
//!
//! Every error of every layer is JSON, `{"error": "<one line>", "status": N}`: 400 bad input,
//! 403 a Host that is not this server's name, 404 no such command or page, 405 a method the
//! path does not take, 408 a body not sent within [`ServeOptions::body_timeout`] or arriving
//! slower than [`ServeOptions::min_body_rate`] (the connection is closed), 413 a body
//! over [`ServeOptions::body_limit`] (answered from `Content-Length` before any of the body is
//! read), 414 a path over 2 KiB, 415 a body that is not `application/json`, 431 headers over
//! 16 KiB, 503 when the requests in flight are at their bound for longer than the queue wait or
//! one ran past the time budget. (A request hyper cannot parse as HTTP at all, or with a head
//! over 64 KiB, gets hyper's own bare 400 or 431 and the connection is closed.)
//!
//! What the server holds, and for how long:
//! - a request's body is read only once its computation has a slot, so at most
//!   `max_in_flight` bodies are in memory, each at most `body_limit`; a waiting request holds
//!   its connection's read buffer only;
//! - at most `max_connections` connections are open; past that the server stops accepting until
//!   one closes (the operating system queues the rest); an accept error (too many open files)
//!   waits 50 ms and serving goes on;
//! - a connection that has not sent a whole request head within `header_timeout` (idle
//!   keep-alive connections included) is closed; when more than half the connections are open,
//!   new ones get a tenth of it;
//! - a computation past `time_budget`, or whose client went away, is stopped at its next check
//!   ([`Cancel`](crate::Cancel)) and frees its slot;
//! - Ctrl-C stops every computation and the server within a second.

use crate::ground::cancel::Cancel;
mod args;
pub use args::ServeArgs;

use crate::commands::{run_request, Command, Document, Files};
use crate::Error;
use axum::body::Body;
use axum::extract::{Path, Request, State};
use axum::http::{header, HeaderValue, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::Router;
use std::net::{IpAddr, SocketAddr};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::Semaphore;

/// The page, its script and its style sheet, embedded in the binary.
const PAGE: &str = include_str!("page.html");
const SCRIPT: &str = include_str!("app.js");
const STYLE: &str = include_str!("style.css");

/// The largest request body the server takes by default, bytes (8 MiB).
pub const MAX_BODY_BYTES: usize = 8 << 20;

/// The slowest a request body may arrive by default, bytes a second (after a second of grace):
/// 16 KiB/s, which the largest body meets in 10 minutes and a program of a few kilobytes at once.
pub const MIN_BODY_RATE: u64 = 16 << 10;

/// The longest request target (path and query) answered, bytes.
pub const MAX_URI_BYTES: usize = 2 << 10;

/// The most header bytes (names and values) a request may carry.
pub const MAX_HEADER_BYTES: usize = 16 << 10;

/// hyper's read buffer per connection, bytes: a request head longer than this is refused by
/// hyper itself.
const READ_BUFFER_BYTES: usize = 64 << 10;

/// How the server listens and what it bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct ServeOptions {
    /// The address to listen on (loopback by default).
    pub bind: IpAddr,
    /// The port (0: any free one; the start-up line names it).
    pub port: u16,
    /// The largest request body, bytes (8 MiB: room for a program at its own bound, 2 MiB,
    /// written as JSON text, whose escapes can grow it).
    pub body_limit: usize,
    /// Requests computed at once; others wait up to `queue_wait`, then get 503.
    pub max_in_flight: usize,
    /// How long a request waits for its turn.
    pub queue_wait: Duration,
    /// How long one request may compute before it is stopped and answered 503.
    pub time_budget: Duration,
    /// How long a connection may take to send a request head, or stay idle between requests.
    pub header_timeout: Duration,
    /// How long a request's body may take to arrive once its turn has come.
    pub body_timeout: Duration,
    /// The slowest a body may arrive once its turn has come, bytes a second, after a first
    /// second of grace: a body that falls behind is answered 408 and its connection closed, so
    /// that a client trickling its body cannot hold a slot for the whole `body_timeout`.
    pub min_body_rate: u64,
    /// Connections open at once.
    pub max_connections: usize,
    /// Host names the server answers besides its own address and `localhost` (`--allow-host`):
    /// a page on another site that a shop's browser opens cannot reach the server through a
    /// name of its own (DNS rebinding).
    pub allow_hosts: Vec<String>,
}

impl Default for ServeOptions {
    fn default() -> Self {
        let cores = std::thread::available_parallelism().map_or(2, usize::from);
        ServeOptions {
            bind: IpAddr::from([127, 0, 0, 1]),
            port: 8080,
            body_limit: MAX_BODY_BYTES,
            max_in_flight: 2 * cores,
            queue_wait: Duration::from_secs(5),
            time_budget: Duration::from_secs(10),
            header_timeout: Duration::from_secs(5),
            body_timeout: Duration::from_secs(10),
            min_body_rate: MIN_BODY_RATE,
            max_connections: 256,
            allow_hosts: Vec::new(),
        }
    }
}

/// What the handlers share.
struct Shared {
    options: ServeOptions,
    permits: Arc<Semaphore>,
    /// Raised when the server stops: every computation in flight stops with it.
    stopping: Cancel,
}

/// The application: the page and the API, ready to be served (by [`serve`], or by a test on
/// its own listener).
pub fn router(options: ServeOptions) -> Router {
    router_with(options, Cancel::new())
}

fn router_with(options: ServeOptions, stopping: Cancel) -> Router {
    let shared = Arc::new(Shared {
        permits: Arc::new(Semaphore::new(options.max_in_flight.max(1))),
        options,
        stopping,
    });
    Router::new()
        .route("/", get(|| async { with_type("text/html; charset=utf-8", PAGE) }))
        .route("/app.js", get(|| async { with_type("text/javascript; charset=utf-8", SCRIPT) }))
        .route("/style.css", get(|| async { with_type("text/css; charset=utf-8", STYLE) }))
        .route("/api", get(api_index))
        .route("/api/{command}", post(api_json))
        .route("/api/{command}/{document}", post(api_document))
        .fallback(|| async { error(StatusCode::NOT_FOUND, "no such page: the API is under /api/".into()) })
        .layer(axum::middleware::from_fn_with_state(Arc::clone(&shared), guard))
        .with_state(shared)
}

/// Binds and serves until interrupted (Ctrl-C). `started` is called with the start-up line
/// once the socket is bound (the address, and a warning when it is not loopback).
pub fn serve(options: ServeOptions, started: impl FnOnce(&str)) -> Result<(), Error> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| Error::io("the server's runtime", e))?;
    let result = runtime.block_on(run(options, started));
    // A computation that has not seen the stop yet is not waited for.
    runtime.shutdown_timeout(Duration::from_millis(200));
    result
}

async fn run(options: ServeOptions, started: impl FnOnce(&str)) -> Result<(), Error> {
    let addr = SocketAddr::new(options.bind, options.port);
    let listener = tokio::net::TcpListener::bind(addr).await.map_err(|e| Error::io(addr, e))?;
    let local = listener.local_addr().map_err(|e| Error::io(addr, e))?;
    let reach = if options.bind.is_loopback() {
        "this computer only (loopback)".to_string()
    } else {
        format!("every machine that can reach {} (--bind {}: your choice)", options.bind, options.bind)
    };
    started(&format!(
        "threadcheck serve: http://{local}/ for {reach}; {} requests at once, bodies up to {} bytes; Ctrl-C stops",
        options.max_in_flight, options.body_limit
    ));
    let stopping = Cancel::new();
    let mut options = options;
    // The port the server really has (0 asks for any): the Host check compares with it.
    options.port = local.port();
    let (header_timeout, max_connections) = (options.header_timeout, options.max_connections.max(1));
    let app = router_with(options, stopping.clone());
    let connections = Arc::new(Semaphore::new(max_connections));
    let stop = tokio::signal::ctrl_c();
    tokio::pin!(stop);
    loop {
        let permit = tokio::select! {
            _ = &mut stop => break,
            p = Arc::clone(&connections).acquire_owned() => match p {
                Ok(p) => p,
                Err(_) => break,
            },
        };
        let stream = tokio::select! {
            _ = &mut stop => break,
            a = listener.accept() => match a {
                Ok((stream, _)) => stream,
                // Out of file descriptors, a connection reset before it was taken: wait a moment
                // and go on serving.
                Err(_) => {
                    tokio::time::sleep(Duration::from_millis(50)).await;
                    continue;
                }
            },
        };
        // Crowded: a newcomer gets a tenth of the head timeout, so idle connections cannot hold
        // the server.
        let crowded = connections.available_permits() < max_connections / 2;
        let timeout = if crowded { header_timeout / 10 } else { header_timeout };
        let app = app.clone();
        tokio::spawn(async move {
            let service =
                hyper::service::service_fn(move |req: axum::http::Request<hyper::body::Incoming>| {
                    let mut app = app.clone();
                    async move { tower_service::Service::call(&mut app, req.map(Body::new)).await }
                });
            let mut http = hyper::server::conn::http1::Builder::new();
            http.timer(hyper_util::rt::TokioTimer::new())
                .header_read_timeout(timeout)
                .max_buf_size(READ_BUFFER_BYTES);
            let _ = http.serve_connection(hyper_util::rt::TokioIo::new(stream), service).await;
            drop(permit);
        });
    }
    stopping.raise();
    Ok(())
}

fn with_type(media: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, media), (header::CACHE_CONTROL, "no-cache")], body).into_response()
}

/// A JSON error: the command line's one line and the status.
fn error(status: StatusCode, message: String) -> Response {
    let body = serde_json::json!({ "error": crate::one_line(&message), "status": status.as_u16() });
    (status, [(header::CONTENT_TYPE, "application/json")], body.to_string()).into_response()
}

/// Every request passes here first: its Host, its size, and (for the API) its media type; every
/// error answer that comes back without a JSON body (axum's 405, an extractor's rejection) gets
/// the documented one.
async fn guard(State(shared): State<Arc<Shared>>, req: Request, next: Next) -> Response {
    if req.uri().to_string().len() > MAX_URI_BYTES {
        return error(
            StatusCode::URI_TOO_LONG,
            format!("the request's path is longer than {MAX_URI_BYTES} bytes"),
        );
    }
    let header_bytes: usize = req.headers().iter().map(|(k, v)| k.as_str().len() + v.len() + 4).sum();
    if header_bytes > MAX_HEADER_BYTES {
        return error(
            StatusCode::REQUEST_HEADER_FIELDS_TOO_LARGE,
            format!("the request's headers are larger than {MAX_HEADER_BYTES} bytes"),
        );
    }
    // Two Host headers: which one a proxy or a browser meant is not known (RFC 9112 §3.2: a
    // request with more than one Host field is answered 400).
    if req.headers().get_all(header::HOST).iter().count() > 1 {
        return error(StatusCode::BAD_REQUEST, "the request has more than one Host header".to_string());
    }
    if let Err(host) = host_allowed(&shared.options, req.headers().get(header::HOST)) {
        return error(StatusCode::FORBIDDEN, host);
    }
    let (method, path) = (req.method().clone(), req.uri().path().to_string());
    if method == Method::POST && path.starts_with("/api/") {
        let media = req
            .headers()
            .get(header::CONTENT_TYPE)
            .and_then(|v| v.to_str().ok())
            .map(|v| v.split(';').next().unwrap_or("").trim().to_ascii_lowercase());
        if media.as_deref() != Some("application/json") {
            return error(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                format!(
                    "the request body must be JSON, sent as Content-Type: application/json (it came as {})",
                    media.map_or("nothing".to_string(), |m| format!("'{m}'"))
                ),
            );
        }
    }
    let response = next.run(req).await;
    let is_json = response
        .headers()
        .get(header::CONTENT_TYPE)
        .is_some_and(|v| v.as_bytes().starts_with(b"application/json"));
    let status = response.status();
    if (status.is_client_error() || status.is_server_error()) && !is_json {
        let message = match status {
            StatusCode::METHOD_NOT_ALLOWED => format!(
                "{method} {path}: not taken here (the page and GET /api are read with GET, the API's commands are POST /api/COMMAND)"
            ),
            s => format!("{method} {path}: {}", s.canonical_reason().unwrap_or("error")),
        };
        return error(status, message);
    }
    response
}

/// Whether the Host header names this server: its own address, a loopback name when it listens
/// on loopback (or every address), `localhost`, or a name `--allow-host` gave.
fn host_allowed(options: &ServeOptions, host: Option<&HeaderValue>) -> Result<(), String> {
    let Some(host) = host.and_then(|h| h.to_str().ok()) else {
        return Err("the request names no Host: HTTP/1.1 requests must".into());
    };
    let name = match host.strip_prefix('[') {
        // [::1]:8080
        Some(v6) => v6.split(']').next().unwrap_or("").to_string(),
        None => host.rsplit_once(':').map_or(host, |(n, _)| n).to_string(),
    };
    let name = name.to_ascii_lowercase();
    let mut allowed = vec!["localhost".to_string()];
    if !options.bind.is_unspecified() {
        allowed.push(options.bind.to_string());
    }
    if options.bind.is_loopback() || options.bind.is_unspecified() {
        allowed.extend(["127.0.0.1".to_string(), "::1".to_string()]);
    }
    allowed.extend(options.allow_hosts.iter().map(|h| h.to_ascii_lowercase()));
    let mut seen = std::collections::HashSet::new();
    allowed.retain(|h| seen.insert(h.clone()));
    if allowed.contains(&name) {
        Ok(())
    } else {
        Err(format!(
            "Host '{host}' is not a name of this server ({}): a web page of another site may be trying to reach it; start the server with --allow-host {name} to answer that name",
            allowed.join(", ")
        ))
    }
}

/// `GET /api`: the commands, their keys and documents.
async fn api_index() -> Response {
    let commands: Vec<serde_json::Value> = Command::API
        .iter()
        .map(|name| {
            serde_json::json!({
                "command": name,
                "keys": Command::keys(name).unwrap_or_default(),
                // What the API serves: a run of many's documents are the command line's.
                "documents": Command::api_documents(name).iter().map(|d| d.name()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let body = serde_json::json!({ "version": env!("CARGO_PKG_VERSION"), "commands": commands });
    ([(header::CONTENT_TYPE, "application/json")], body.to_string()).into_response()
}

async fn api_json(State(shared): State<Arc<Shared>>, Path(command): Path<String>, req: Request) -> Response {
    answer(shared, &command, "json", req).await
}

async fn api_document(
    State(shared): State<Arc<Shared>>,
    Path((command, document)): Path<(String, String)>,
    req: Request,
) -> Response {
    answer(shared, &command, &document, req).await
}

/// Raises its flag when dropped: a request whose client went away (its future dropped) stops
/// its computation.
struct RaiseOnDrop(Cancel);

impl Drop for RaiseOnDrop {
    fn drop(&mut self) {
        self.0.raise();
    }
}

/// Why a request body was not read whole.
enum BodyFault {
    TooLarge,
    /// Past the body timeout, or behind the minimum rate: the message says which.
    Slow(String),
    Unreadable(String),
}

/// Reads a request body within the options' bounds: at most `body_limit` bytes, all of it
/// within `body_timeout`, and at every moment after the first second at least `min_body_rate`
/// bytes a second on average since the slot was taken.
async fn read_body(mut body: Body, options: &ServeOptions) -> Result<Vec<u8>, BodyFault> {
    use axum::body::HttpBody;
    let start = tokio::time::Instant::now();
    let end = start + options.body_timeout;
    let rate = options.min_body_rate.max(1) as f64;
    let mut got: Vec<u8> = Vec::new();
    loop {
        // When the bytes so far stop being enough: a second of grace, then `rate` a second.
        let behind = start + Duration::from_secs(1) + Duration::from_secs_f64(got.len() as f64 / rate);
        let deadline = behind.min(end);
        let frame = std::future::poll_fn(|cx| std::pin::Pin::new(&mut body).poll_frame(cx));
        match tokio::time::timeout_at(deadline, frame).await {
            Err(_) if deadline == end => {
                return Err(BodyFault::Slow(format!(
                    "the request body did not arrive within {} s",
                    options.body_timeout.as_secs_f64()
                )))
            }
            Err(_) => {
                return Err(BodyFault::Slow(format!(
                    "the request body arrived slower than {} bytes a second ({} bytes in {:.1} s): the connection is closed",
                    options.min_body_rate,
                    got.len(),
                    start.elapsed().as_secs_f64()
                )))
            }
            Ok(None) => return Ok(got),
            Ok(Some(Err(e))) => return Err(BodyFault::Unreadable(crate::one_line(&e.to_string()))),
            Ok(Some(Ok(frame))) => {
                if let Ok(data) = frame.into_data() {
                    if got.len() + data.len() > options.body_limit {
                        return Err(BodyFault::TooLarge);
                    }
                    got.extend_from_slice(&data);
                }
            }
        }
    }
}

/// One API request: checked, queued for a permit, its body read, computed on the blocking pool
/// within the time budget, answered.
async fn answer(shared: Arc<Shared>, command: &str, document: &str, req: Request) -> Response {
    // The page says it asks (`X-Threadcheck-Reader: page`): its messages name its fields; any
    // other client reads the API's keys.
    let reader = match req.headers().get("x-threadcheck-reader").map(HeaderValue::as_bytes) {
        Some(b"page") => crate::Audience::Page,
        _ => crate::Audience::Api,
    };
    if let Err(e) = Command::keys(command) {
        return error(StatusCode::NOT_FOUND, e.to_string());
    }
    let command = command.to_string();
    let document: Document = match document.parse() {
        Ok(d) => d,
        Err(e) => return error(StatusCode::NOT_FOUND, e.to_string()),
    };
    // Only what `GET /api` lists for the command (it listed SARIF, JUnit and JSON Lines for
    // verify, and each was answered 400).
    if let Err(e) = Command::served(&command, document) {
        return error(StatusCode::NOT_FOUND, e.to_string());
    }
    let limit = shared.options.body_limit;
    let too_large =
        || error(StatusCode::PAYLOAD_TOO_LARGE, format!("the request body is larger than {limit} bytes"));
    // Announced over the limit: answered before a byte of it is read.
    let declared = req
        .headers()
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<u64>().ok());
    if declared.is_some_and(|n| n > limit as u64) {
        return too_large();
    }
    let permit =
        match tokio::time::timeout(shared.options.queue_wait, Arc::clone(&shared.permits).acquire_owned())
            .await
        {
            Ok(Ok(p)) => p,
            _ => {
                return error(
                    StatusCode::SERVICE_UNAVAILABLE,
                    format!(
                        "busy: {} requests are being computed and this one waited {} s; try again",
                        shared.options.max_in_flight,
                        shared.options.queue_wait.as_secs_f64()
                    ),
                )
            }
        };
    // The body is read only now, with a slot: the bodies in memory are bounded by the slots.
    let body = match read_body(req.into_body(), &shared.options).await {
        Ok(b) => b,
        Err(BodyFault::TooLarge) => return too_large(),
        Err(BodyFault::Slow(why)) => {
            let mut r = error(StatusCode::REQUEST_TIMEOUT, why);
            // The slot is freed now and the connection is not read on.
            r.headers_mut().insert(header::CONNECTION, HeaderValue::from_static("close"));
            return r;
        }
        Err(BodyFault::Unreadable(e)) => {
            return error(StatusCode::BAD_REQUEST, format!("the request body could not be read: {e}"))
        }
    };
    let Ok(args) = String::from_utf8(body) else {
        return error(StatusCode::BAD_REQUEST, "the request body is not UTF-8 text".into());
    };
    let stop = Cancel::new();
    // Dropped with this future: a client gone stops the computation.
    let _stop_on_drop = RaiseOnDrop(stop.clone());
    let (work_stop, stopping) = (stop.clone(), shared.stopping.clone());
    // The permit goes with the computation: a request answered 503 for its time budget keeps
    // its permit until its computation really ends (at its next check of the flag), so the
    // bound holds.
    let work = tokio::task::spawn_blocking(move || {
        let r = if stopping.is_raised() {
            Err(Error::Cancelled)
        } else {
            work_stop.run(|| run_request(&command, document, &args, Files::Refused, reader))
        };
        drop(permit);
        r
    });
    match tokio::time::timeout(shared.options.time_budget, work).await {
        Err(_) => {
            stop.raise();
            error(
                StatusCode::SERVICE_UNAVAILABLE,
                format!(
                    "the request took longer than the time budget of {} s; it was stopped",
                    shared.options.time_budget.as_secs_f64()
                ),
            )
        }
        Ok(Err(_)) => error(StatusCode::INTERNAL_SERVER_ERROR, "the computation stopped unexpectedly".into()),
        Ok(Ok(Err(e))) => {
            let status = match e {
                Error::Data(_) | Error::Io { .. } => StatusCode::INTERNAL_SERVER_ERROR,
                Error::Cancelled => StatusCode::SERVICE_UNAVAILABLE,
                _ => StatusCode::BAD_REQUEST,
            };
            error(status, e.one_line_for(reader))
        }
        Ok(Ok(Ok((body, outcome)))) => {
            let outcome = match outcome {
                crate::Outcome::Pass => "pass",
                crate::Outcome::OutOfTolerance => "out-of-tolerance",
                crate::Outcome::Unreadable => "unreadable",
            };
            (
                [
                    (header::CONTENT_TYPE, HeaderValue::from_static(document.media_type())),
                    (
                        header::HeaderName::from_static("x-threadcheck-outcome"),
                        HeaderValue::from_static(outcome),
                    ),
                ],
                body,
            )
                .into_response()
        }
    }
}
