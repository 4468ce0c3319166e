//! The HTTP face: device memory and status as JSON, the designer's JSON
//! endpoints, the live view's WebSocket, and the designer page itself
//! (`crates/ecam-cli/web/`, compiled into the binary by [`super::assets`]).
//!
//! | route | what |
//! |---|---|
//! | `GET /`, `/app.js`, … | the designer page ([`super::assets::ASSETS`]) |
//! | `GET /api/status` | scan count, PLC time, lag, Modbus counters, state dir |
//! | `GET /api/devices?names=D2000,M0,DD2019,D100:4` | values, as `ecam plc run --dump` prints them |
//! | `POST /api/devices` `{"D100": 3183, "M0": 1}` | set (durably, like a Modbus write); answers the new values |
//! | `GET /api/laws` | motion laws and their characteristic values |
//! | `GET /api/law/NAME?points=N` | `u, s, v, a, j` arrays of the normalised rise |
//! | `GET /api/generators` | generator names, parameters, defaults |
//! | `POST /api/table/gen` `{"generator": "rotary-cut", "params": {...}}` | a generated table with its curves |
//! | `POST /api/keypoints` `{"lines": "600 0 cycloid\n..."}` | key points typed one per line, as `{"key": [...]}` |
//! | `POST /api/segments/continuous` `{"start": {...}, "segment": [...]}` | a segment cam's free boundary values filled in from the neighbours |
//! | `POST /api/drive/check` `{"generator", "params", "drive", "master_speed"}` | the design checked against a drive (docs/design.md) |
//! | `POST /api/table/load` `{"block": 2000, "points": [[0, 0], ...], "while_running": "at-seam"}` | a point table into a DECAM block the program names (or one clear of them, below D8000), one durable write (409 while its cam runs, unless `at-seam`) |
//! | `POST /api/table/check` `{"points": [[0, 0], ...]}` | a point table checked, with its section velocities, impulses and summary |
//! | `POST /api/table/read` `{"name": "t.csv", "text": "..."}` | an uploaded table file read as `ecam table show` reads it |
//! | `POST /api/table/convert` `{"format": "csv", "points": [...], ...}` | a table as `ecam table gen -o` writes it, `{"text": ...}` |
//! | `GET /api/limits` | table and key-point limits, key-point curve names |
//! | `GET /api/block?name=D2000` | where a DECAM block starts, or why it cannot |
//! | `GET /api/live?block=2000&rate=20` (WebSocket) | the cam's master, slave, speeds and sync output, [`super::live`] |
//! | `GET /api/ethercat` | `--ethercat`: the line and every drive (state, positions, faults, lateness) |
//! | `POST /api/ethercat/enable`, `/disable`, `/reset` `{}` | `--ethercat`: enable or disable the drives, clear the faults (202: done at the next cycle) |
//! | `POST /api/ethercat/fault` `{"drive": 1, "code": 29456}` | `--emulated`: make an emulated drive fault |
//!
//! Errors answer `{"error": "message"}` with status 400 (bad request), 404
//! (unknown route), 409 (a write the program's cams refuse, with the PLC
//! error `"code"` when there is one) or 500 (the write could not be made
//! durable).

use std::collections::HashMap;
use std::sync::Arc;

use axum::Router;
use axum::body::Bytes;
use axum::extract::Request;
use axum::extract::{Path, Query, State};
use axum::http::{StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use ecam_serve::{BusCommand, Shared, devices_to_json, parse_device_names, parse_device_sets};
use hyper_util::rt::{TokioIo, TokioTimer};
use serde_json::{Value, json};
use tokio::net::TcpListener;
use tower::Service as _;

use super::assets::{ASSETS, Asset, INDEX};
use super::limits::ConnectionLimits;

/// Serves `router` on `listener` for ever, within `limits`: at most so many
/// connections (the newest refused at the cap), request headers complete
/// within `limits.partial`, an idle connection closed after `limits.idle`.
/// (`axum::serve` offers neither a cap nor a header deadline.)
pub async fn serve(listener: TcpListener, router: Router, limits: ConnectionLimits) {
    loop {
        let stream = match listener.accept().await {
            Ok((stream, _)) => stream,
            Err(err) => {
                // Out of file descriptors and the like: wait, do not spin.
                tracing::error!(target: "ecam::http", "accept: {err}");
                tokio::time::sleep(std::time::Duration::from_millis(100)).await;
                continue;
            }
        };
        let Some(slot) = limits.admit() else {
            drop(stream);
            continue;
        };
        let router = router.clone();
        let limits = limits.clone();
        tokio::spawn(async move {
            let service = hyper::service::service_fn(
                move |request: hyper::Request<hyper::body::Incoming>| {
                    router.clone().call(request.map(axum::body::Body::new))
                },
            );
            let connection = hyper::server::conn::http1::Builder::new()
                .timer(TokioTimer::new())
                .header_read_timeout(limits.partial)
                .serve_connection(TokioIo::new(stream), service)
                // The live view's WebSocket (`/api/live`).
                .with_upgrades();
            // Errors only mean the client went away (or was sent away).
            let _ = connection.await;
            drop(slot);
        });
    }
}

/// Who may talk to the HTTP face: the threat model is a page in the
/// operator's browser (or a rebinding DNS name) sending requests to a
/// server on the operator's machine (docs/modbus.md, "Web safety").
#[derive(Clone, Debug)]
pub struct Access {
    /// `Host` header values accepted (`name` or `name:port`).
    hosts: Vec<String>,
    /// A token writes must present as `Authorization: Bearer TOKEN`.
    token: Option<String>,
}

impl Access {
    /// Accepts the bound address, `localhost` and `127.0.0.1` at its port,
    /// and `names` (as given, or with the port); writes need `token` when
    /// one is given.
    pub fn new(bound: std::net::SocketAddr, names: &[String], token: Option<String>) -> Self {
        let port = bound.port();
        let mut hosts = vec![
            bound.to_string(),
            format!("localhost:{port}"),
            format!("127.0.0.1:{port}"),
            format!("[::1]:{port}"),
        ];
        for name in names {
            hosts.push(name.clone());
            hosts.push(format!("{name}:{port}"));
        }
        Self { hosts, token }
    }

    fn host_allowed(&self, host: &str) -> bool {
        self.hosts.iter().any(|h| h.eq_ignore_ascii_case(host))
    }
}

/// Refuses requests for another host (DNS rebinding), from a foreign page
/// (`Origin`), writes that are not JSON (a cross-site form or `text/plain`
/// post), and writes without the token when one is set.
async fn guard(State(access): State<Arc<Access>>, request: Request, next: Next) -> Response {
    let headers = request.headers();
    let host = headers
        .get(header::HOST)
        .and_then(|h| h.to_str().ok())
        .unwrap_or("");
    if !access.host_allowed(host) {
        return error(
            StatusCode::MISDIRECTED_REQUEST,
            &format!("Host `{host}` is not this server; name it with --http-name"),
        );
    }
    if let Some(origin) = headers.get(header::ORIGIN) {
        let origin = origin.to_str().unwrap_or("");
        let own = origin
            .strip_prefix("http://")
            .or_else(|| origin.strip_prefix("https://"))
            .is_some_and(|o| access.host_allowed(o));
        if !own {
            return error(
                StatusCode::FORBIDDEN,
                &format!("requests from pages of `{origin}` are refused"),
            );
        }
    }
    let reads = matches!(
        *request.method(),
        axum::http::Method::GET | axum::http::Method::HEAD
    );
    if !reads {
        let json = headers
            .get(header::CONTENT_TYPE)
            .and_then(|c| c.to_str().ok())
            .is_some_and(|c| {
                c.trim()
                    .to_ascii_lowercase()
                    .starts_with("application/json")
            });
        if !json {
            return error(
                StatusCode::UNSUPPORTED_MEDIA_TYPE,
                "writes need Content-Type: application/json",
            );
        }
        if let Some(token) = &access.token {
            let given = headers
                .get(header::AUTHORIZATION)
                .and_then(|a| a.to_str().ok())
                .and_then(|a| a.strip_prefix("Bearer "));
            if given != Some(token.as_str()) {
                return error(
                    StatusCode::UNAUTHORIZED,
                    "writes need the token: Authorization: Bearer TOKEN (see --token-file)",
                );
            }
        }
    }
    next.run(request).await
}

/// The router of `ecam serve`'s HTTP face, behind [`Access`].
pub fn router(shared: Arc<Shared>, access: Access) -> Router {
    let mut router = Router::new().route("/", get(|| async { asset(INDEX) }));
    for &file in ASSETS {
        router = router.route(file.path, get(move || async move { asset(file) }));
    }
    router
        .route("/api/status", get(status))
        .route("/api/devices", get(get_devices).post(post_devices))
        .route(
            "/api/laws",
            get(|| async { json_value(StatusCode::OK, &ecam_design::laws_json()) }),
        )
        .route("/api/law/{name}", get(law))
        .route(
            "/api/generators",
            get(|| async { json_value(StatusCode::OK, &ecam_design::generators_json()) }),
        )
        .route("/api/table/gen", post(table_gen))
        .route("/api/keypoints", post(key_points))
        .route(
            "/api/segments/continuous",
            post(|b: Bytes| design(b, ecam_design::segments_continuous_json)),
        )
        .route(
            "/api/drive/check",
            post(|b: Bytes| design(b, ecam_design::drive_check_json)),
        )
        .route(
            "/api/table/check",
            post(|b: Bytes| design(b, ecam_design::table_check_json)),
        )
        .route(
            "/api/table/read",
            post(|b: Bytes| design(b, ecam_design::table_read_json)),
        )
        .route(
            "/api/table/convert",
            post(|b: Bytes| design(b, ecam_design::table_convert_json)),
        )
        .route(
            "/api/limits",
            get(|| async { json_value(StatusCode::OK, &ecam_design::limits_json()) }),
        )
        .route("/api/block", get(block))
        .route("/api/table/load", post(table_load))
        .route("/api/live", get(super::live::live))
        .route("/api/ethercat", get(ethercat_status))
        .route("/api/ethercat/{command}", post(ethercat_command))
        .fallback(|| async { error(StatusCode::NOT_FOUND, "no such route; see GET /api/status") })
        .with_state(shared)
        .layer(middleware::from_fn_with_state(Arc::new(access), guard))
}

fn asset(file: Asset) -> Response {
    ([(header::CONTENT_TYPE, file.content_type)], file.body).into_response()
}

fn json_text(status: StatusCode, body: String) -> Response {
    (status, [(header::CONTENT_TYPE, "application/json")], body).into_response()
}

fn json_value(status: StatusCode, value: &Value) -> Response {
    json_text(status, value.to_string())
}

/// `{"error": message}` with `status`.
pub(super) fn error(status: StatusCode, message: &str) -> Response {
    json_value(status, &json!({ "error": message }))
}

async fn status(State(shared): State<Arc<Shared>>) -> Response {
    json_value(StatusCode::OK, &shared.status())
}

fn no_bus() -> Response {
    error(
        StatusCode::NOT_FOUND,
        "no drives: start the server with --ethercat CONFIG",
    )
}

async fn ethercat_status(State(shared): State<Arc<Shared>>) -> Response {
    match shared.bus.get() {
        Some(bus) => match serde_json::to_value(bus.snapshot()) {
            Ok(value) => json_value(StatusCode::OK, &value),
            Err(e) => error(StatusCode::INTERNAL_SERVER_ERROR, &e.to_string()),
        },
        None => no_bus(),
    }
}

async fn ethercat_command(
    State(shared): State<Arc<Shared>>,
    Path(command): Path<String>,
    body: Bytes,
) -> Response {
    let Some(bus) = shared.bus.get() else {
        return no_bus();
    };
    let body: Value = match serde_json::from_slice(&body) {
        Ok(value) => value,
        Err(e) => {
            return error(
                StatusCode::BAD_REQUEST,
                &format!("the body is not JSON: {e}"),
            );
        }
    };
    let command = match command.as_str() {
        "enable" => BusCommand::Enable,
        "disable" => BusCommand::Disable,
        "reset" => BusCommand::Reset,
        "fault" => {
            if !bus.snapshot().transport.starts_with("emulated") {
                return error(
                    StatusCode::CONFLICT,
                    "faults can only be injected into emulated drives (--emulated N)",
                );
            }
            let drive = body.get("drive").and_then(Value::as_u64);
            let code = body.get("code").and_then(Value::as_u64).unwrap_or(0x7500);
            match (
                drive.and_then(|d| usize::try_from(d).ok()),
                u16::try_from(code),
            ) {
                (Some(drive), Ok(code)) => BusCommand::EmulateFault { drive, code },
                _ => {
                    return error(
                        StatusCode::BAD_REQUEST,
                        "give {\"drive\": N} and optionally {\"code\": 0..65535}",
                    );
                }
            }
        }
        other => {
            return error(
                StatusCode::NOT_FOUND,
                &format!("no command `{other}`: enable, disable, reset or fault"),
            );
        }
    };
    match bus.command(command) {
        Ok(()) => json_value(StatusCode::ACCEPTED, &json!({ "queued": command })),
        Err(e) => error(
            StatusCode::SERVICE_UNAVAILABLE,
            &format!("the bus cycle is not taking commands: {e}"),
        ),
    }
}

async fn get_devices(
    State(shared): State<Arc<Shared>>,
    Query(query): Query<HashMap<String, String>>,
) -> Response {
    let names = query.get("names").map_or("", String::as_str);
    match parse_device_names(names) {
        Ok(views) => json_text(
            StatusCode::OK,
            shared.read(|devices| devices_to_json(&views, devices)),
        ),
        Err(message) => error(StatusCode::BAD_REQUEST, &message),
    }
}

async fn post_devices(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let (batch, views) = match parse_device_sets(&body) {
        Ok(parsed) => parsed,
        Err(message) => return error(StatusCode::BAD_REQUEST, &message),
    };
    // The journal syncs to disk: keep that off the async workers.
    let writer = Arc::clone(&shared);
    match tokio::task::spawn_blocking(move || writer.write(&batch)).await {
        Ok(Ok(())) => json_text(
            StatusCode::OK,
            shared.read(|devices| devices_to_json(&views, devices)),
        ),
        Ok(Err(e)) => refused(e.http_status(), &e.to_string(), e.code()),
        Err(e) => error(StatusCode::INTERNAL_SERVER_ERROR, &e.to_string()),
    }
}

/// `{"error": message, "code": 6782}` (the code when there is one).
fn refused(status: u16, message: &str, code: Option<u16>) -> Response {
    let status = StatusCode::from_u16(status).unwrap_or(StatusCode::INTERNAL_SERVER_ERROR);
    let mut body = json!({ "error": message });
    if let Some(code) = code {
        body["code"] = json!(code);
    }
    json_value(status, &body)
}

async fn law(Path(name): Path<String>, Query(query): Query<HashMap<String, String>>) -> Response {
    let points = match query.get("points") {
        None => Ok(ecam_design::DEFAULT_LAW_POINTS),
        Some(text) => text
            .trim()
            .parse::<usize>()
            .map_err(|_| format!("points must be a whole number, not `{text}`")),
    };
    off_the_network_threads(move || {
        match points.and_then(|points| ecam_design::law_curves_json(&name, points)) {
            Ok(value) => json_value(StatusCode::OK, &value),
            Err(message) => error(StatusCode::BAD_REQUEST, &message),
        }
    })
    .await
}

async fn table_load(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let load = match ecam_serve::parse_table_load(&body) {
        Ok(load) => load,
        Err(message) => return error(StatusCode::BAD_REQUEST, &message),
    };
    let (block, points) = (load.block, load.points);
    // One journal record for the whole image (a sync to disk: off the
    // async workers); the scan sees the table complete or not at all.
    match tokio::task::spawn_blocking(move || shared.load_table(&load)).await {
        Ok(Ok(switch)) => json_value(
            StatusCode::OK,
            &json!({ "block": block, "points": points, "switch": switch.name() }),
        ),
        Ok(Err(e)) => refused(e.http_status(), &e.to_string(), e.code()),
        Err(e) => error(StatusCode::INTERNAL_SERVER_ERROR, &e.to_string()),
    }
}

async fn table_gen(body: Bytes) -> Response {
    off_the_network_threads(move || json_call(&body, ecam_design::generate_json)).await
}

async fn key_points(body: Bytes) -> Response {
    design(body, ecam_design::key_points_json).await
}

/// A design endpoint: `answer(body)` off the network threads.
async fn design(body: Bytes, answer: fn(&Value) -> Result<Value, String>) -> Response {
    off_the_network_threads(move || json_call(&body, answer)).await
}

async fn block(Query(query): Query<HashMap<String, String>>) -> Response {
    let name = query.get("name").map_or("", String::as_str);
    match ecam_plc::decam::block_at(name) {
        Ok(block) => json_value(StatusCode::OK, &json!({ "block": block })),
        Err(e) => error(StatusCode::BAD_REQUEST, &e.to_string()),
    }
}

/// Longest a design request may compute before it is answered with 503.
const DESIGN_DEADLINE: std::time::Duration = std::time::Duration::from_secs(30);

/// Runs CPU-bound work on the blocking pool, so that the async workers
/// (Modbus clients, other HTTP requests) are never held up by it; gives up
/// waiting after [`DESIGN_DEADLINE`] (the work itself is bounded by
/// `ecam_core::limits`).
async fn off_the_network_threads(work: impl FnOnce() -> Response + Send + 'static) -> Response {
    match tokio::time::timeout(DESIGN_DEADLINE, tokio::task::spawn_blocking(work)).await {
        Ok(Ok(response)) => response,
        Ok(Err(_)) => error(StatusCode::INTERNAL_SERVER_ERROR, "the request failed"),
        Err(_) => error(
            StatusCode::SERVICE_UNAVAILABLE,
            "the request took too long; ask for fewer points",
        ),
    }
}

/// Answers `answer(body)`, or 400 with its error.
fn json_call(body: &[u8], answer: fn(&Value) -> Result<Value, String>) -> Response {
    let result = serde_json::from_slice::<Value>(body)
        .map_err(|e| format!("the body is not JSON: {e}"))
        .and_then(|value| answer(&value));
    match result {
        Ok(value) => json_value(StatusCode::OK, &value),
        Err(message) => error(StatusCode::BAD_REQUEST, &message),
    }
}
