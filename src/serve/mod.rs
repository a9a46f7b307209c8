//! `threadcheck serve`: the shop's page and the JSON API, one binary, no outside resource.
//!
//! `GET /` is the page (plain HTML, a small script of ours, a style sheet: all embedded);
//! `POST /api/{command}` answers with exactly what `threadcheck {command} --json -` prints for
//! the same input, `POST /api/{command}/{document}` with the command's `text`, `svg`, `html` or
//! `fix` document; the body is a JSON object of the Python function's keyword arguments
//! ([`run_request`](crate::run_request) with files refused: the server reads no file of its own
//! for a request). Errors are JSON, `{"error": "<the command line's one line>", "status": N}`:
//! 400 bad input, 404 no such command, 413 a body over [`ServeOptions::body_limit`], 503 when
//! the requests in flight are at their bound for longer than the queue wait, or one ran past the
//! time budget. Nothing is written to disk.

use crate::request::{run_request, Command, Document, Files};
use crate::Error;
use axum::body::Bytes;
use axum::extract::rejection::BytesRejection;
use axum::extract::{DefaultBodyLimit, Path, State};
use axum::http::{header, HeaderValue, StatusCode};
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
    /// How long one request may compute before it is answered 503.
    pub time_budget: Duration,
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
            time_budget: Duration::from_secs(30),
        }
    }
}

/// What the handlers share.
struct Shared {
    options: ServeOptions,
    permits: Arc<Semaphore>,
}

/// The application: the page and the API, ready to be served (by [`serve`], or by a test on
/// its own listener).
pub fn router(options: ServeOptions) -> Router {
    let shared =
        Arc::new(Shared { permits: Arc::new(Semaphore::new(options.max_in_flight.max(1))), options });
    Router::new()
        .route("/", get(|| async { with_type("text/html; charset=utf-8", PAGE) }))
        .route("/app.js", get(|| async { with_type("text/javascript; charset=utf-8", SCRIPT) }))
        .route("/style.css", get(|| async { with_type("text/css; charset=utf-8", STYLE) }))
        .route("/api", get(api_index))
        .route("/api/{command}", post(api_json))
        .route("/api/{command}/{document}", post(api_document))
        .fallback(|| async { error(StatusCode::NOT_FOUND, "no such page: the API is under /api/".into()) })
        .layer(DefaultBodyLimit::max(shared.options.body_limit))
        .with_state(shared)
}

/// Binds and serves until interrupted (Ctrl-C). `started` is called with the start-up line
/// once the socket is bound (the address, and a warning when it is not loopback).
pub fn serve(options: ServeOptions, started: impl FnOnce(&str)) -> Result<(), Error> {
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .map_err(|e| Error::io("the server's runtime", e))?;
    runtime.block_on(async move {
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
        axum::serve(listener, router(options))
            .with_graceful_shutdown(async {
                let _ = tokio::signal::ctrl_c().await;
            })
            .await
            .map_err(|e| Error::io(local, e))
    })
}

fn with_type(media: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, media), (header::CACHE_CONTROL, "no-cache")], body).into_response()
}

/// A JSON error: the command line's one line and the status.
fn error(status: StatusCode, message: String) -> Response {
    let body = serde_json::json!({ "error": crate::one_line(&message), "status": status.as_u16() });
    (status, [(header::CONTENT_TYPE, "application/json")], body.to_string()).into_response()
}

/// `GET /api`: the commands, their keys and documents.
async fn api_index() -> Response {
    let commands: Vec<serde_json::Value> = Command::ALL
        .iter()
        .map(|c| {
            serde_json::json!({
                "command": c.name(),
                "keys": c.keys(),
                "documents": c.documents().iter().map(|d| d.name()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let body = serde_json::json!({ "version": env!("CARGO_PKG_VERSION"), "commands": commands });
    ([(header::CONTENT_TYPE, "application/json")], body.to_string()).into_response()
}

async fn api_json(
    State(shared): State<Arc<Shared>>,
    Path(command): Path<String>,
    body: Result<Bytes, BytesRejection>,
) -> Response {
    answer(shared, &command, "json", body).await
}

async fn api_document(
    State(shared): State<Arc<Shared>>,
    Path((command, document)): Path<(String, String)>,
    body: Result<Bytes, BytesRejection>,
) -> Response {
    answer(shared, &command, &document, body).await
}

/// One API request: parsed, queued for a permit, computed on the blocking pool within the
/// time budget, answered.
async fn answer(
    shared: Arc<Shared>,
    command: &str,
    document: &str,
    body: Result<Bytes, BytesRejection>,
) -> Response {
    let command: Command = match command.parse() {
        Ok(c) => c,
        Err(e) => return error(StatusCode::NOT_FOUND, e.to_string()),
    };
    let document: Document = match document.parse() {
        Ok(d) => d,
        Err(e) => return error(StatusCode::NOT_FOUND, e.to_string()),
    };
    let body = match body {
        Ok(b) => b,
        Err(rejection) => {
            let status = rejection.status();
            let message = if status == StatusCode::PAYLOAD_TOO_LARGE {
                format!("the request body is larger than {} bytes", shared.options.body_limit)
            } else {
                rejection.body_text()
            };
            return error(status, message);
        }
    };
    let Ok(args) = String::from_utf8(body.to_vec()) else {
        return error(StatusCode::BAD_REQUEST, "the request body is not UTF-8 text".into());
    };
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
    // The permit goes with the computation: a request answered 503 for its time budget keeps
    // its permit until its computation really ends, so the bound holds.
    let work = tokio::task::spawn_blocking(move || {
        let r = run_request(command, document, &args, Files::Refused);
        drop(permit);
        r
    });
    match tokio::time::timeout(shared.options.time_budget, work).await {
        Err(_) => error(
            StatusCode::SERVICE_UNAVAILABLE,
            format!(
                "the request took longer than the time budget of {} s",
                shared.options.time_budget.as_secs_f64()
            ),
        ),
        Ok(Err(_)) => error(StatusCode::INTERNAL_SERVER_ERROR, "the computation stopped unexpectedly".into()),
        Ok(Ok(Err(e))) => {
            let status = match e {
                Error::Data(_) | Error::Io { .. } => StatusCode::INTERNAL_SERVER_ERROR,
                _ => StatusCode::BAD_REQUEST,
            };
            error(status, e.one_line())
        }
        Ok(Ok(Ok(a))) => {
            let outcome = match a.outcome {
                crate::Outcome::Pass => "pass",
                crate::Outcome::OutOfTolerance => "out-of-tolerance",
            };
            (
                [
                    (header::CONTENT_TYPE, HeaderValue::from_static(document.media_type())),
                    (
                        header::HeaderName::from_static("x-threadcheck-outcome"),
                        HeaderValue::from_static(outcome),
                    ),
                ],
                a.body,
            )
                .into_response()
        }
    }
}
