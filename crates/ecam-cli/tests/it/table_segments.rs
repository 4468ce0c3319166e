//! `ecam table gen segments`: every example generates, `table show --json`
//! reports the segment cam's continuity and per-segment peaks, `--drive`
//! checks it against a drive; flags build the same cam as a file.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::common::{ecam, fails, ok};

fn example(name: &str) -> String {
    format!(
        "{}/../../examples/tables/{name}",
        env!("CARGO_MANIFEST_DIR")
    )
}

#[test]
fn every_example_generates_and_shows_its_continuity_and_peaks() {
    let dir = crate::common::scratch_dir("table-segments");
    for (name, segments, sync) in [
        ("rotary-knife", 3, Some([0, 500])),
        ("flying-saw", 5, Some([1000, 2000])),
        ("pick-and-place", 4, None),
    ] {
        let out = dir.join(format!("{name}.json"));
        let params = example(&format!("segments-{name}.toml"));
        ok(ecam(&[
            "table",
            "gen",
            "segments",
            "--params",
            &params,
            "-o",
            out.to_str().unwrap(),
        ]));
        let shown = ok(ecam(&["table", "show", out.to_str().unwrap(), "--json"]));
        let v: serde_json::Value = serde_json::from_str(&shown).unwrap();
        let s = &v["segments"];
        assert_eq!(s["continuity"]["cam"], "C2", "{name}: {s}");
        assert_eq!(s["peaks"].as_array().unwrap().len(), segments, "{name}");
        assert_eq!(
            s["continuity"]["joints"].as_array().unwrap().len(),
            segments,
            "{name}"
        );
        assert_eq!(v["sync"], serde_json::json!(sync), "{name}");
        let text = ok(ecam(&["table", "show", out.to_str().unwrap()]));
        assert!(text.contains("segment cam:       continuity C2"), "{text}");
    }
}

#[test]
fn the_drive_check_reports_speeds_torques_and_the_binding_limit() {
    let dir = crate::common::scratch_dir("table-segments-drive");
    let out = dir.join("pick.json");
    let params = example("segments-pick-and-place.toml");
    ok(ecam(&[
        "table",
        "gen",
        "segments",
        "--params",
        &params,
        "-o",
        out.to_str().unwrap(),
    ]));
    let drive = example("drive-pick-and-place.toml");
    let args = [
        "table",
        "show",
        out.to_str().unwrap(),
        "--drive",
        &drive,
        "--master-speed",
        "3600",
    ];
    let text = ok(ecam(&args));
    assert!(
        text.contains("motor speed:     843.") && text.contains("rpm peak"),
        "{text}"
    );
    assert!(text.contains("0.2995 N·m RMS"), "{text}");
    assert!(text.contains("RMS torque binds first"), "{text}");
    let mut json_args = args.to_vec();
    json_args.push("--json");
    let v: serde_json::Value = serde_json::from_str(&ok(ecam(&json_args))).unwrap();
    let d = &v["drive"];
    assert_eq!(d["binding"], "rms-torque");
    assert!((d["at_speed"]["motor_speed_rpm"].as_f64().unwrap() - 843.75).abs() < 1e-6);
    assert!((d["max_cycles_per_min"].as_f64().unwrap() - 74.36).abs() < 0.01);
    // A drive file with a typo is refused, naming the key.
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[mechanics]\nunits_per_rev = 1\n").unwrap();
    let err = fails(ecam(&[
        "table",
        "show",
        out.to_str().unwrap(),
        "--drive",
        bad.to_str().unwrap(),
    ]));
    assert!(err.contains("units_per_rev"), "{err}");
}

#[test]
fn flags_build_the_cam_a_file_does() {
    let out = ok(ecam(&[
        "table",
        "gen",
        "segments",
        "--start",
        "0:0:0.4",
        "--segment",
        "constant-velocity:500:200",
        "--segment",
        "vv-cycloid:2250:600",
        "--segment",
        "vv-cycloid:4000:1000",
        "--continuous",
        "--resolution",
        "100",
        "--minimal",
    ]));
    let file = ok(ecam(&[
        "table",
        "gen",
        "segments",
        "--params",
        &example("segments-rotary-knife.toml"),
        "--minimal",
    ]));
    assert_eq!(out, file);
    let err = fails(ecam(&[
        "table",
        "gen",
        "segments",
        "--segment",
        "cycloid:1000:500:0.5",
    ]));
    assert!(
        err.contains("point 1 (master 1000)") && err.contains("velocity 0.5"),
        "{err}"
    );
    let err = fails(ecam(&[
        "table",
        "gen",
        "segments",
        "--segment",
        "wobble:1000:500",
    ]));
    assert!(err.contains("unknown segment law"), "{err}");
}
