//! Fuzzing harnesses: one function per reader a user can feed, shared by
//! the cargo-fuzz targets in `fuzz/` and by the stable property tests in
//! `tests/it/fuzz.rs`, so both exercise the same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use ecam_core::generator::schema::{GENERATORS, Generator};

use crate::{
    Generated, MasterFunction, find, from_json, generate, generate_json, key_points_json, number,
    read_toml,
};

/// The generator the first byte of `data` picks (wrapping round the list),
/// found by name as a user's `--generator NAME` is, and the rest of `data`
/// as text.
fn pick(data: &[u8]) -> Option<(&'static Generator, &str)> {
    let (&first, rest) = data.split_first()?;
    let count = GENERATORS.len().max(1);
    let listed = GENERATORS.get(usize::from(first) % count)?;
    let generator = find(listed.name).ok()?;
    Some((generator, core::str::from_utf8(rest).ok()?))
}

/// Feeds `data` to a generator's TOML parameter reader ([`read_toml`] for
/// the generator [`find`] gives, picked by the first byte) and generates
/// from what it accepts ([`generate`]).
pub fn generator_toml(data: &[u8]) {
    let Some((generator, text)) = pick(data) else {
        return;
    };
    if let Ok(values) = read_toml(generator, text)
        && let Ok(generated) = generate(generator, values)
    {
        exercise(&generated);
    }
}

/// Feeds `data` as JSON to a generator ([`from_json`], picked by the first
/// byte), and the same JSON to the designer's requests
/// ([`generate_json`], [`key_points_json`]).
pub fn generator_json(data: &[u8]) {
    let Some((generator, text)) = pick(data) else {
        return;
    };
    let Ok(value) = serde_json::from_str::<serde_json::Value>(text) else {
        return;
    };
    let _ = generate_json(&value);
    let _ = key_points_json(&value);
    if let Ok(generated) = from_json(generator.name, value) {
        exercise(&generated);
    }
}

/// Feeds `data` to the expression readers: a cam function of the master
/// ([`MasterFunction::parse`], then evaluated) and a number ([`number`]).
pub fn expression(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    let _ = number(text);
    let Ok(function) = MasterFunction::parse(text) else {
        return;
    };
    for x in [0.0, 1.0, -1.0, 0.5, 360.0, 36_000.0, -1e9, 1e12] {
        let _ = function.at(x);
        let _ = function.kinematics(x, 1.0);
    }
}

/// Reads what a generated table holds, as `ecam table gen` prints it.
fn exercise(generated: &Generated) {
    let points = generated.table.points().len();
    if let Some(kinematics) = &generated.kinematics {
        assert_eq!(
            kinematics.len(),
            points,
            "{}: one set of derivatives per point",
            generated.name
        );
    }
    let _ = (&generated.sync, &generated.outputs);
}
