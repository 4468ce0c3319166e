//! Errors a user can cause name the input and the place, never Rust types
//! or addresses.

use crate::common::{ecam, fails, scratch_dir};

#[test]
fn expression_errors_show_no_internals() {
    for expr in ["1 + * 2", "x ^ ^ 2", "(((x", "foo(x)"] {
        let err = fails(ecam(&["table", "gen", "function", "--expr", expr]));
        assert!(err.contains(expr), "{err}");
        for internal in ["0x", "Operator {", "BinOp", "apply:"] {
            assert!(!err.contains(internal), "{expr}: {err}");
        }
    }
}

#[test]
fn json_errors_say_what_is_wrong_in_the_authors_words() {
    let dir = scratch_dir("messages");
    // A syntax error inside a uniform table is a syntax error, not an
    // "unknown variant".
    let broken = dir.join("broken.json");
    std::fs::write(&broken, r#"{"kind":"uniform","values":[1,2,}"#).unwrap();
    let err = fails(ecam(&["table", "show", broken.to_str().unwrap()]));
    assert!(err.contains("line 1 column"), "{err}");
    assert!(!err.contains("variant"), "{err}");
    // A wrong value type names what was expected, not a Rust type.
    let typed = dir.join("typed.json");
    std::fs::write(
        &typed,
        r#"{"kind":"points","points":[{"master":"a","slave":0}]}"#,
    )
    .unwrap();
    let err = fails(ecam(&["table", "show", typed.to_str().unwrap()]));
    assert!(err.contains("whole number"), "{err}");
    assert!(!err.contains("i64"), "{err}");
}

#[test]
fn parameter_errors_name_no_rust_types() {
    let dir = scratch_dir("messages-params");
    let params = dir.join("s.toml");
    std::fs::write(&params, "pulses = \"a\"\n").unwrap();
    let err = fails(ecam(&[
        "table",
        "gen",
        "s-curve",
        "--params",
        params.to_str().unwrap(),
    ]));
    assert!(
        err.contains("pulses") && err.contains("whole number"),
        "{err}"
    );
    assert!(!err.contains("i64"), "{err}");
}

#[test]
fn generator_reports_use_words_not_rust_names() {
    let out = ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--params",
        "../../examples/tables/rotary-cut-demo.toml",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(err.contains("regime: stop and dwell between cuts"), "{err}");
    let out = ecam(&[
        "table",
        "gen",
        "fly-saw",
        "--master",
        "1750",
        "--slave",
        "2000",
        "--sync",
        "667",
        "--ratio",
        "3*pi",
        "--max-ratio",
        "10",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("stroke: forward (following the material)"),
        "{err}"
    );
    for debug in ["StopAndDwell", "SpeedUp", "SlowDown", "Forward", "Return"] {
        assert!(!err.contains(debug), "{err}");
    }
}

#[test]
fn csv_errors_name_the_file_line_and_value() {
    let dir = scratch_dir("messages-csv");
    let csv = dir.join("t.csv");
    // The bad value is on line 4 of the file (a comment before it counts).
    std::fs::write(&csv, "master,slave\n0,0\n# a comment\n10,x\n").unwrap();
    let err = fails(ecam(&["table", "show", csv.to_str().unwrap()]));
    assert!(
        err.contains("t.csv") && err.contains("line 4: slave `x`"),
        "{err}"
    );
    std::fs::write(&csv, "master,slave\n0,0\n10,5\n5,6\n").unwrap();
    let err = fails(ecam(&["table", "show", csv.to_str().unwrap()]));
    assert!(err.contains("line 4: `5,6`: table error (6782)"), "{err}");
}

#[test]
fn a_bad_value_in_a_parameter_file_names_the_file_and_line() {
    let dir = scratch_dir("messages-params-file");
    let params = dir.join("cut.toml");
    std::fs::write(&params, "master = 3183\naccel = \"linear\"\n").unwrap();
    let out = ecam(&[
        "table",
        "gen",
        "rotary-cut",
        "--params",
        params.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("cut.toml") && err.contains("line 2: `accel = \"linear\"`"),
        "{err}"
    );
    assert!(
        err.contains("uniform, uniform-acceleration, b-type"),
        "{err}"
    );
}

#[test]
fn an_unknown_function_is_named_not_a_parser_internal() {
    let err = fails(ecam(&[
        "table",
        "gen",
        "function",
        "--expr",
        "1000*sinn(x)",
    ]));
    assert!(err.contains("`sinn` is not a function"), "{err}");
    assert!(!err.contains("wlog") && !err.contains("right:"), "{err}");
}

#[test]
fn errors_quote_a_short_excerpt_of_a_huge_input() {
    let dir = scratch_dir("messages-excerpt");
    // A 10 MB field in a CSV table, a 3 MB value in a parameter file.
    let csv = dir.join("huge.csv");
    std::fs::write(
        &csv,
        format!("master,slave\n0,0\n10,{}.5\n", "9".repeat(10_000_000)),
    )
    .unwrap();
    let err = fails(ecam(&["table", "show", csv.to_str().unwrap()]));
    assert!(err.len() < 300, "{} bytes", err.len());
    assert!(err.contains("(10000002 bytes)"), "{err}");
    assert!(err.contains("line 3"), "the position: {err}");
    let params = dir.join("huge.toml");
    std::fs::write(&params, format!("pulses = \"{}\"\n", "x".repeat(3_000_000))).unwrap();
    let err = fails(ecam(&[
        "table",
        "gen",
        "s-curve",
        "--params",
        params.to_str().unwrap(),
    ]));
    assert!(err.len() < 1000, "{} bytes", err.len());
    assert!(err.contains("line 1, column 10"), "the position: {err}");
    // An IL token.
    let il = dir.join("huge.il");
    std::fs::write(
        &il,
        format!("LD M8000\nMOV K{} D0\n", "1".repeat(1_000_000)),
    )
    .unwrap();
    let err = fails(ecam(&["plc", "run", il.to_str().unwrap(), "--scans", "1"]));
    assert!(err.len() < 300, "{} bytes: {err}", err.len());
    assert!(err.contains("huge.il:2"), "the position: {err}");
}
