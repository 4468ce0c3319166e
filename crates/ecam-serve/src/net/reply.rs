//! JSON answers of the HTTP face: `{"error": message}` for every refusal,
//! in the project's words.

use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use serde_json::{Value, json};

/// `body` (JSON text) with `status`.
pub fn json_text(status: StatusCode, body: String) -> Response {
    (status, [(header::CONTENT_TYPE, "application/json")], body).into_response()
}

/// `value` with `status`.
pub fn json_value(status: StatusCode, value: &Value) -> Response {
    json_text(status, value.to_string())
}

/// `{"error": message}` with `status`.
pub fn error(status: StatusCode, message: &str) -> Response {
    json_value(status, &json!({ "error": message }))
}
