//! `ecam law`: the contract output (names, CSV header, row count, ends) and errors.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::ecam;

use std::process::Output;

const LAWS: [&str; 11] = [
    "constant-velocity",
    "constant-acceleration",
    "simple-harmonic",
    "cycloid",
    "modified-trapezoid",
    "modified-sine",
    "modified-constant-velocity",
    "poly-345",
    "poly-4567",
    "cubic",
    "s-type",
];

fn stdout(out: &Output) -> String {
    assert!(
        out.status.success(),
        "ecam failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

/// Rows of `u,s,v,a,j` as numbers, header checked.
fn rows(text: &str) -> Vec<[f64; 5]> {
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("u,s,v,a,j"));
    lines
        .map(|l| {
            let v: Vec<f64> = l.split(',').map(|f| f.parse().unwrap()).collect();
            [v[0], v[1], v[2], v[3], v[4]]
        })
        .collect()
}

#[test]
fn list_prints_every_law_once_per_line() {
    let text = stdout(&ecam(&["law", "--list"]));
    let names: Vec<&str> = text.lines().collect();
    assert_eq!(names, LAWS);
}

#[test]
fn every_law_is_a_normalised_rise_with_1001_points_by_default() {
    for law in LAWS {
        let r = rows(&stdout(&ecam(&["law", law])));
        assert_eq!(r.len(), 1001, "{law}");
        assert_eq!(r[0][0], 0.0, "{law}");
        assert_eq!(r[1000][0], 1.0, "{law}");
        assert!(r[0][1].abs() < 1e-12, "{law}: s(0) = {}", r[0][1]);
        assert!(
            (r[1000][1] - 1.0).abs() < 1e-12,
            "{law}: s(1) = {}",
            r[1000][1]
        );
        for w in r.windows(2) {
            assert!(w[1][0] > w[0][0], "{law}: u increases");
            assert!(w[1][1] >= w[0][1] - 1e-12, "{law}: a rise never falls back");
        }
    }
}

#[test]
fn velocity_is_the_derivative_of_displacement() {
    for law in LAWS {
        let r = rows(&stdout(&ecam(&["law", law, "--points", "2001"])));
        let du = r[1][0] - r[0][0];
        for i in 1..r.len() - 1 {
            let numeric = (r[i + 1][1] - r[i - 1][1]) / (2.0 * du);
            assert!(
                (numeric - r[i][2]).abs() < 1e-3 * r[i][2].abs().max(1.0),
                "{law} at u = {}: ds/du {numeric} vs v {}",
                r[i][0],
                r[i][2]
            );
        }
    }
}

#[test]
fn points_sets_the_row_count_including_both_ends() {
    let r = rows(&stdout(&ecam(&["law", "cycloid", "--points", "2"])));
    assert_eq!(r.len(), 2);
    assert_eq!((r[0][0], r[1][0]), (0.0, 1.0));
    let r = rows(&stdout(&ecam(&["law", "poly-345", "--points", "5"])));
    let u: Vec<f64> = r.iter().map(|row| row[0]).collect();
    assert_eq!(u, [0.0, 0.25, 0.5, 0.75, 1.0]);
    // poly-345 at u = 0.5 is exactly half-way.
    assert!((r[2][1] - 0.5).abs() < 1e-12);
}

#[test]
fn unknown_law_is_an_error_on_stderr() {
    let out = ecam(&["law", "wobble"]);
    // A usage mistake: clap names the value and the laws there are.
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("'wobble'") && err.contains("cycloid"), "{err}");
}

#[test]
fn fewer_than_two_points_is_an_error() {
    for n in ["1", "0"] {
        let out = ecam(&["law", "cycloid", "--points", n]);
        assert_eq!(out.status.code(), Some(2), "--points {n}");
        assert!(out.stdout.is_empty());
        assert!(String::from_utf8_lossy(&out.stderr).contains("from 2"));
    }
    let out = ecam(&["law", "cycloid", "--points", "many"]);
    assert!(!out.status.success());
}

#[test]
fn a_name_or_list_is_required() {
    let out = ecam(&["law"]);
    assert!(!out.status.success());
    assert!(!out.stderr.is_empty());
}
