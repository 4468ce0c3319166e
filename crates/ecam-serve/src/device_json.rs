//! Device names and values as JSON, for `GET`/`POST /api/devices`: the
//! same names and value forms as `ecam plc run --dump/--set` (`D2000`,
//! `DD2019` signed 32-bit, `DE106` float, `M0`, `X17`, `Y7`, `C231`,
//! `V0`/`Z0` index registers (read only here: the program sets them);
//! `NAME:COUNT` for consecutive devices).

use std::collections::HashSet;
use std::fmt::Write as _;

use ecam_plc::View;
use ecam_plc::{Device, Devices};
use serde_json::Value;

use crate::write::WriteBatch;

/// Most values one `GET /api/devices` returns.
pub const MAX_DEVICE_NAMES: usize = 10_000;

/// Expands a comma-separated list of `NAME[:COUNT]`, in order, each device once.
///
/// # Errors
/// An unknown or out-of-range name, a bad count, or more than [`MAX_DEVICE_NAMES`] values.
pub fn parse_device_names(names: &str) -> Result<Vec<View>, String> {
    let mut views = Vec::new();
    let mut seen = HashSet::new();
    for item in names.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let (name, count) = match item.split_once(':') {
            Some((name, count)) => {
                let count: u16 =
                    count
                        .trim()
                        .parse()
                        .ok()
                        .filter(|&c| c >= 1)
                        .ok_or_else(|| {
                            format!(
                                "`{item}`: COUNT must be a whole number 1..65535",
                                item = ecam_core::excerpt::excerpt(item)
                            )
                        })?;
                (name, count)
            }
            None => (item, 1),
        };
        let first = View::parse(name).map_err(|e| e.to_string())?;
        for k in 0..count {
            let view = first.nth(k).map_err(|e| e.to_string())?;
            if seen.insert(view) {
                views.push(view);
            }
            if views.len() > MAX_DEVICE_NAMES {
                return Err(format!("at most {MAX_DEVICE_NAMES} values per request"));
            }
        }
    }
    if views.is_empty() {
        return Err("give device names, e.g. ?names=D2000,M0,DD2019".to_string());
    }
    Ok(views)
}

/// `{"D2000": 5200, "M0": 1}` with keys in the order of `views` (like
/// `ecam plc run`'s dump).
pub fn devices_to_json(views: &[View], devices: &Devices) -> String {
    let mut json = String::from("{");
    for (i, view) in views.iter().enumerate() {
        if i > 0 {
            json.push_str(", ");
        }
        let _ = write!(json, "\"{view}\": {}", view.read(devices));
    }
    json.push('}');
    json
}

/// Reads a `POST /api/devices` body, `{"D100": 3183, "DE106": 1.6667,
/// "M0": 1, "X17": true}`, into the words and bits to write, and the views
/// to answer with. Keys are taken in name order.
///
/// # Errors
/// Not JSON, not an object, an unknown name, a Y output or counter (read
/// only from outside), or a value that does not fit the device.
pub fn parse_device_sets(body: &[u8]) -> Result<(WriteBatch, Vec<View>), String> {
    parse_json_body(body).and_then(|value| sets_from_json(&value))
}

/// Reads an HTTP request body as JSON.
///
/// # Errors
/// `the body is not JSON (…)`, saying where, in the server's words.
pub fn parse_json_body(body: &[u8]) -> Result<Value, String> {
    serde_json::from_slice::<Value>(body).map_err(|e| {
        format!(
            "the body is not JSON: {}",
            ecam_core::io::json_syntax_message(&e)
        )
    })
}

/// [`parse_device_sets`] once the body is JSON.
fn sets_from_json(body: &Value) -> Result<(WriteBatch, Vec<View>), String> {
    let object = body
        .as_object()
        .ok_or("the body must be a JSON object such as {\"D100\": 3183, \"M0\": 1}")?;
    if object.is_empty() {
        return Err("nothing to set".to_string());
    }
    let mut batch = WriteBatch::new();
    let mut views = Vec::new();
    // Values are parsed exactly as `--set` parses them, into scratch memory,
    // then copied from there word by word.
    let mut scratch = Devices::new();
    for (name, value) in object {
        let view = View::parse(name).map_err(|e| e.to_string())?;
        let text = match value {
            Value::Number(n) => n.to_string(),
            Value::Bool(b) => u8::from(*b).to_string(),
            Value::String(s) => s.clone(),
            _ => {
                return Err(format!(
                    "{view}: the value must be a number, a boolean or a string"
                ));
            }
        };
        match view {
            View::Bit(Device::Y(_)) => {
                return Err(format!("{view} is an output: the program drives it"));
            }
            View::Counter(_) => {
                return Err(format!(
                    "{view} is a counter: the program and inputs drive it"
                ));
            }
            View::Timer(_) => {
                return Err(format!("{view} is a timer: the program drives it"));
            }
            View::Index(_) => {
                // Index registers are not part of the journalled register
                // image; the program sets them (MOV K5 Z0).
                return Err(format!(
                    "{view} is an index register: the program drives it"
                ));
            }
            View::WordBit(n, _) => {
                // One bit of a word is a read-modify-write of the word, which a
                // batch of plain word writes cannot express atomically.
                return Err(format!("{view}: write the whole word D{n}"));
            }
            _ => {}
        }
        view.write(&mut scratch, &text).map_err(|e| e.to_string())?;
        let word = |n: u16| scratch.word(n).unwrap_or(0) as u16;
        match view {
            View::Word(n) => {
                batch.word(n, word(n));
            }
            View::Double(n) | View::Float(n) => {
                // View::parse checked that n + 1 exists.
                let high = n.saturating_add(1);
                batch.word(n, word(n)).word(high, word(high));
            }
            View::Bit(device) => {
                batch.bit(device, scratch.bit(device).unwrap_or(false));
            }
            View::Counter(_) | View::Timer(_) | View::WordBit(..) | View::Index(_) => {}
        }
        views.push(view);
    }
    // Two keys that reach the same word or bit (`D300` and `d300`, or `DD100`
    // and `D101`) would leave which value wins to key order: refuse them.
    let mut written = HashSet::new();
    for &(slot, _) in batch.writes() {
        if !written.insert(slot) {
            return Err(format!(
                "{} is set more than once in this request (two names reach it); set each device once",
                slot.device()
            ));
        }
    }
    Ok((batch, views))
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn names_expand_in_order_without_repeats() {
        let views = parse_device_names("D2019:2, DD2019, M0,D2019,X17").unwrap();
        let names: Vec<String> = views.iter().map(ToString::to_string).collect();
        assert_eq!(names, ["D2019", "D2020", "DD2019", "M0", "X17"]);
        assert!(parse_device_names("").is_err());
        assert!(parse_device_names("D8512").is_err());
        assert!(parse_device_names("D8511:2").is_err());
        assert!(parse_device_names("Q1").is_err());
    }

    #[test]
    fn dump_matches_plc_run() {
        let mut devices = Devices::new();
        devices.set_dword(2019, -70000).unwrap();
        devices.set_m(0, true).unwrap();
        let views = parse_device_names("DD2019,D2019,M0").unwrap();
        assert_eq!(
            devices_to_json(&views, &devices),
            r#"{"DD2019": -70000, "D2019": -4464, "M0": 1}"#
        );
    }

    #[test]
    fn index_registers_read_like_words() {
        let mut devices = Devices::new();
        devices
            .set_index_register(ecam_plc::IndexReg::Z(1), -4)
            .unwrap();
        devices.set_index_pair(2, 70000).unwrap();
        let views = parse_device_names("Z1,V2,Z2,V7:1").unwrap();
        assert_eq!(
            devices_to_json(&views, &devices),
            r#"{"Z1": -4, "V2": 1, "Z2": 4464, "V7": 0}"#
        );
        assert!(parse_device_names("V8").is_err());
        assert!(parse_device_names("Z7:2").is_err());
    }

    #[test]
    fn sets_become_word_and_bit_writes() {
        let (batch, views) = sets_from_json(
            &json!({"DD100": -2, "DE106": 1.5, "M0": true, "X17": "1", "D7": 65535}),
        )
        .unwrap();
        let mut devices = Devices::new();
        batch.apply(&mut devices);
        assert_eq!(devices.dword(100), Ok(-2));
        assert_eq!(devices.float(106), Ok(1.5));
        assert_eq!(devices.m(0), Ok(true));
        assert_eq!(devices.bit(Device::X(15)), Ok(true));
        assert_eq!(devices.word(7), Ok(-1));
        assert_eq!(views.len(), 5);
    }

    #[test]
    fn bodies_are_json_objects() {
        let (batch, _) = parse_device_sets(br#"{"D100": 3183}"#).unwrap();
        assert_eq!(batch.to_line(), "D100 3183");
        let message = parse_device_sets(b"D100=3183").unwrap_err();
        assert!(message.starts_with("the body is not JSON: "), "{message}");
    }

    #[test]
    fn read_only_and_bad_values_are_refused() {
        for body in [
            json!({"Y7": 1}),
            json!({"C231": 5}),
            json!({"M0": 2}),
            json!({"D0": 70000}),
            json!({"D0": 1.5}),
            json!({"D0": null}),
            json!({"Q0": 1}),
            json!({}),
            json!([1]),
            json!({"D300": 5, "d300": 6}),
            json!({"DD100": 1, "D101": 5}),
            json!({"X17": 1, "x017": 0}),
            json!({"Z0": 5}),
            json!({"V7": 5}),
        ] {
            assert!(sets_from_json(&body).is_err(), "{body}");
        }
    }
}
