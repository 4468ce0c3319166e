//! The HTTP face: device memory and status as JSON, the designer's JSON
//! endpoints, and the designer page itself (`web/`, compiled into the
//! binary so `ecam serve` works from any directory).
//!
//! | route | what |
//! |---|---|
//! | `GET /` , `/app.js`, `/style.css` | the designer page |
//! | `GET /api/status` | scan count, PLC time, lag, Modbus counters, state dir |
//! | `GET /api/devices?names=D2000,M0,DD2019,D100:4` | values, as `ecam plc run --dump` prints them |
//! | `POST /api/devices` `{"D100": 3183, "M0": 1}` | set (durably, like a Modbus write); answers the new values |
//! | `GET /api/laws` | motion laws and their characteristic values |
//! | `GET /api/law/NAME?points=N` | `u, s, v, a, j` arrays of the normalised rise |
//! | `GET /api/generators` | generator names, parameters, defaults |
//! | `POST /api/table/gen` `{"generator": "rotary-cut", "params": {...}}` | a generated table with its curves |
//! | `POST /api/keypoints` `{"lines": "600 0 cycloid\n..."}` | key points typed one per line, as `{"key": [...]}` |
//!
//! Errors answer `{"error": "message"}` with status 400 (bad request), 404
//! (unknown route) or 500 (the write could not be made durable).

use std::collections::HashMap;
use std::sync::Arc;

use axum::Router;
use axum::body::Bytes;
use axum::extract::{Path, Query, State};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use ecam_serve::{Shared, devices_to_json, parse_device_names, parse_device_sets};
use serde_json::{Value, json};

const INDEX_HTML: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../web/index.html"));
const APP_JS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../web/app.js"));
const STYLE_CSS: &str = include_str!(concat!(env!("CARGO_MANIFEST_DIR"), "/../../web/style.css"));

/// The router of `ecam serve`'s HTTP face.
pub fn router(shared: Arc<Shared>) -> Router {
    Router::new()
        .route(
            "/",
            get(|| async { asset("text/html; charset=utf-8", INDEX_HTML) }),
        )
        .route(
            "/index.html",
            get(|| async { asset("text/html; charset=utf-8", INDEX_HTML) }),
        )
        .route(
            "/app.js",
            get(|| async { asset("text/javascript; charset=utf-8", APP_JS) }),
        )
        .route(
            "/style.css",
            get(|| async { asset("text/css; charset=utf-8", STYLE_CSS) }),
        )
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
        .fallback(|| async { error(StatusCode::NOT_FOUND, "no such route; see GET /api/status") })
        .with_state(shared)
}

fn asset(content_type: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, content_type)], body).into_response()
}

fn json_text(status: StatusCode, body: String) -> Response {
    (status, [(header::CONTENT_TYPE, "application/json")], body).into_response()
}

fn json_value(status: StatusCode, value: &Value) -> Response {
    json_text(status, value.to_string())
}

fn error(status: StatusCode, message: &str) -> Response {
    json_value(status, &json!({ "error": message }))
}

async fn status(State(shared): State<Arc<Shared>>) -> Response {
    json_value(StatusCode::OK, &shared.status())
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
    let written = tokio::task::spawn_blocking(move || writer.write(&batch))
        .await
        .map_err(|e| e.to_string())
        .and_then(|r| r.map_err(|e| e.to_string()));
    match written {
        Ok(()) => json_text(
            StatusCode::OK,
            shared.read(|devices| devices_to_json(&views, devices)),
        ),
        Err(message) => error(
            StatusCode::INTERNAL_SERVER_ERROR,
            &format!("not written: {message}"),
        ),
    }
}

async fn law(Path(name): Path<String>, Query(query): Query<HashMap<String, String>>) -> Response {
    let points = match query.get("points") {
        None => Ok(ecam_design::DEFAULT_LAW_POINTS),
        Some(text) => text
            .trim()
            .parse::<usize>()
            .map_err(|_| format!("points must be a whole number, not `{text}`")),
    };
    match points.and_then(|points| ecam_design::law_curves_json(&name, points)) {
        Ok(value) => json_value(StatusCode::OK, &value),
        Err(message) => error(StatusCode::BAD_REQUEST, &message),
    }
}

async fn table_gen(body: Bytes) -> Response {
    json_call(&body, ecam_design::generate_json)
}

async fn key_points(body: Bytes) -> Response {
    json_call(&body, ecam_design::key_points_json)
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
