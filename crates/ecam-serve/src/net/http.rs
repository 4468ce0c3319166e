//! The HTTP face: device memory and status as JSON, the designer's JSON
//! endpoints, the live view's WebSocket, and the designer page itself
//! (`crates/ecam-cli/web/`, compiled into the binary, handed over as a [`Page`]).
//!
//! | route | what |
//! |---|---|
//! | `GET /`, `/app.js`, … | the designer page ([`Page::files`]) |
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

use crate::{
    Access, Kind, MAX_BODY_BYTES, Outcome, RequestFacts, Shared, devices_to_json,
    parse_bus_command, parse_device_names, parse_device_sets, parse_json_body,
};
use axum::Router;
use axum::body::{Body, Bytes};
use axum::extract::Request;
use axum::extract::{Path, Query, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use ecam_core::budget::Budget;
use hyper_util::rt::{TokioIo, TokioTimer};
use serde_json::{Value, json};
use tokio::net::TcpListener;
use tower::Service as _;

use super::conn::Conn;
use super::page::{Asset, Page};
use super::reply::{error, json_text, json_value};

/// Serves `router` on `listener` for ever, within the server's limits: at
/// the HTTP cap the idlest connection makes room, request headers must be
/// complete within `partial` (so an idle keep-alive connection closes
/// then), bodies within `body` (`body_within`). (`axum::serve` offers
/// neither a cap nor these deadlines.)
pub async fn serve(listener: TcpListener, router: Router, shared: Arc<Shared>) {
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
        let conn = Conn::admit(&shared, Kind::Http);
        let router = router.clone();
        let partial = shared.info.limits.partial;
        tokio::spawn(async move {
            let requests = conn.clone();
            let service = hyper::service::service_fn(
                move |mut request: hyper::Request<hyper::body::Incoming>| {
                    requests.touch();
                    // For the body deadline and the live view's upgrade.
                    request.extensions_mut().insert(requests.clone());
                    router.clone().call(request.map(Body::new))
                },
            );
            let connection = hyper::server::conn::http1::Builder::new()
                .timer(TokioTimer::new())
                .header_read_timeout(partial)
                .serve_connection(TokioIo::new(stream), service)
                // The live view's WebSocket (`/api/live`).
                .with_upgrades();
            // Errors only mean the client went away (or was sent away).
            tokio::select! {
                _ = connection => {}
                () = conn.closed() => {}
            }
        });
    }
}

/// Reads a request's body within the body deadline and size limit (408 or
/// 413, and the connection closed, otherwise), then lets the route work on
/// it with the connection marked busy (it goes last when room is made).
async fn body_within(State(shared): State<Arc<Shared>>, request: Request, next: Next) -> Response {
    let deadline = shared.info.limits.body;
    let (parts, body) = request.into_parts();
    let declared = parts
        .headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok()?.parse::<u64>().ok());
    let too_large = || {
        let message = format!("the request body is over {MAX_BODY_BYTES} bytes (or was cut short)");
        closing(error(StatusCode::PAYLOAD_TOO_LARGE, &message))
    };
    if declared.is_some_and(|n| n > MAX_BODY_BYTES as u64) {
        return too_large();
    }
    let bytes =
        match tokio::time::timeout(deadline, axum::body::to_bytes(body, MAX_BODY_BYTES)).await {
            Ok(Ok(bytes)) => bytes,
            Ok(Err(_)) => return too_large(),
            Err(_) => {
                let message = format!(
                    "the request body did not arrive within {} s of its headers",
                    deadline.as_secs_f64()
                );
                return closing(error(StatusCode::REQUEST_TIMEOUT, &message));
            }
        };
    let _busy = parts
        .extensions
        .get::<Conn>()
        .map(|conn| conn.registration.activity().busy());
    next.run(Request::from_parts(parts, Body::from(bytes)))
        .await
}

/// `response`, after which the connection is closed (its request body was
/// not read to the end).
fn closing(mut response: Response) -> Response {
    let headers = response.headers_mut();
    headers.insert(header::CONNECTION, HeaderValue::from_static("close"));
    response
}

/// Refuses what [`Access::check`] refuses (foreign hosts and pages,
/// writes that are not JSON or lack the token; docs/modbus.md, "Web
/// safety").
async fn guard(State(access): State<Arc<Access>>, request: Request, next: Next) -> Response {
    let headers = request.headers();
    let text = |name| headers.get(name).map(|v| v.to_str().unwrap_or(""));
    let facts = RequestFacts {
        read: matches!(
            *request.method(),
            axum::http::Method::GET | axum::http::Method::HEAD
        ),
        host: text(header::HOST).unwrap_or(""),
        origin: text(header::ORIGIN),
        content_type: text(header::CONTENT_TYPE),
        authorization: text(header::AUTHORIZATION),
    };
    if let Err(refusal) = access.check(&facts) {
        let status = StatusCode::from_u16(refusal.status).unwrap_or(StatusCode::FORBIDDEN);
        return error(status, &refusal.message);
    }
    next.run(request).await
}

/// The router of `ecam serve`'s HTTP face, behind [`Access`].
pub fn router(shared: Arc<Shared>, access: Access, page: Page) -> Router {
    let index = page.index;
    let mut router = Router::new().route("/", get(move || async move { asset(index) }));
    for &file in page.files {
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
        .route("/api/segments/continuous", post(segments_continuous))
        .route("/api/drive/check", post(drive_check))
        .route(
            "/api/table/check",
            post(|state: State<Arc<Shared>>, b: Bytes| {
                table_fact(state, b, ecam_design::table_check_json)
            }),
        )
        .route(
            "/api/table/read",
            post(|state: State<Arc<Shared>>, b: Bytes| {
                table_fact(state, b, ecam_design::table_read_json)
            }),
        )
        .route(
            "/api/table/convert",
            post(|state: State<Arc<Shared>>, b: Bytes| {
                table_fact(state, b, ecam_design::table_convert_json)
            }),
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
        .layer(middleware::from_fn_with_state(
            Arc::clone(&shared),
            body_within,
        ))
        .with_state(shared)
        .layer(middleware::from_fn_with_state(Arc::new(access), guard))
}

fn asset(file: Asset) -> Response {
    ([(header::CONTENT_TYPE, file.content_type)], file.body).into_response()
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
    let body = match parse_json_body(&body) {
        Ok(value) => value,
        Err(message) => return error(StatusCode::BAD_REQUEST, &message),
    };
    let transport = bus.snapshot().transport;
    let command = match parse_bus_command(&command, &body, &transport) {
        Ok(command) => command,
        Err(e) => return refused(e.http_status(), &e.to_string(), None),
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

async fn law(
    State(shared): State<Arc<Shared>>,
    Path(name): Path<String>,
    Query(query): Query<HashMap<String, String>>,
) -> Response {
    let points = match query.get("points") {
        None => Ok(ecam_design::DEFAULT_LAW_POINTS),
        Some(text) => text.trim().parse::<usize>().map_err(|_| {
            let text = ecam_core::excerpt::excerpt(text);
            format!("points must be a whole number, not `{text}`")
        }),
    };
    design(&shared, move |_| {
        match points.and_then(|points| ecam_design::law_curves_json(&name, points)) {
            Ok(value) => json_value(StatusCode::OK, &value),
            Err(message) => error(StatusCode::BAD_REQUEST, &message),
        }
    })
    .await
}

async fn table_load(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    let load = match crate::parse_table_load(&body) {
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

async fn table_gen(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    design(&shared, move |budget| {
        json_call(&body, |value| {
            ecam_design::generate_json_within(value, budget)
        })
    })
    .await
}

async fn key_points(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    design(&shared, move |_| {
        json_call(&body, ecam_design::key_points_json)
    })
    .await
}

async fn segments_continuous(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    design(&shared, move |_| {
        json_call(&body, ecam_design::segments_continuous_json)
    })
    .await
}

async fn drive_check(State(shared): State<Arc<Shared>>, body: Bytes) -> Response {
    design(&shared, move |_| {
        json_call(&body, ecam_design::drive_check_json)
    })
    .await
}

/// The designer's table facts (check, read, convert): in the design pool
/// like every design request.
async fn table_fact(
    State(shared): State<Arc<Shared>>,
    body: Bytes,
    answer: fn(&Value) -> Result<Value, String>,
) -> Response {
    design(&shared, move |_| json_call(&body, answer)).await
}

async fn block(Query(query): Query<HashMap<String, String>>) -> Response {
    let name = query.get("name").map_or("", String::as_str);
    match ecam_plc::decam::block_at(name) {
        Ok(block) => json_value(StatusCode::OK, &json!({ "block": block })),
        Err(e) => error(StatusCode::BAD_REQUEST, &e.to_string()),
    }
}

/// Every design request goes through here: computed in the server's design
/// pool ([`crate::DesignPool`]: bounded, at the lowest CPU priority,
/// never on the threads that answer Modbus), answered 503 at once when the
/// pool is full or when the design deadline passes, and its work stopped
/// then, or as soon as the client leaves (this future is dropped, and the
/// ticket with it).
async fn design(
    shared: &Shared,
    work: impl FnOnce(&mut Budget) -> Response + Send + 'static,
) -> Response {
    let Some(pool) = shared.design() else {
        return error(
            StatusCode::SERVICE_UNAVAILABLE,
            "the designer's workers could not start",
        );
    };
    let (tx, rx) = tokio::sync::oneshot::channel();
    let ticket = match pool.submit(work, move |outcome| {
        let _ = tx.send(outcome);
    }) {
        Ok(ticket) => ticket,
        Err(busy) => return error(StatusCode::SERVICE_UNAVAILABLE, &busy.to_string()),
    };
    let deadline = shared.info.limits.design_deadline;
    let response = match tokio::time::timeout(deadline, rx).await {
        Ok(Ok(Outcome::Done(response))) => response,
        Ok(_) => error(
            StatusCode::INTERNAL_SERVER_ERROR,
            "the request was given up",
        ),
        Err(_) => error(
            StatusCode::SERVICE_UNAVAILABLE,
            &format!(
                "not computed within the design deadline of {} s: ask for fewer points or a simpler expression",
                deadline.as_secs_f64()
            ),
        ),
    };
    drop(ticket);
    response
}

/// Answers `answer(body)`, or 400 with its error.
fn json_call(body: &[u8], answer: impl FnOnce(&Value) -> Result<Value, String>) -> Response {
    match parse_json_body(body).and_then(|value| answer(&value)) {
        Ok(value) => json_value(StatusCode::OK, &value),
        Err(message) => error(StatusCode::BAD_REQUEST, &message),
    }
}
