//! CSV, JSON and register-image round trips and their errors.
#![allow(clippy::unwrap_used)]

use ecam_core::io::{FormatError, curve_to_csv, from_csv, from_json, to_csv, to_json};
use ecam_core::{
    CamCurve, CamPoint, CamTable, MotionLaw, PointTable, Segment, SegmentProfile, TableError,
    UniformTable, register_image,
};

fn doc001() -> PointTable {
    PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)]).unwrap()
}

#[test]
fn csv_round_trip_and_header() {
    let t = doc001();
    let text = to_csv(&t);
    assert!(text.starts_with("master,slave\n0,500\n10000,1500\n"));
    assert_eq!(from_csv(&text).unwrap(), t);
    // Extra columns, spaces, comments and spreadsheet-style whole floats are fine.
    let text = "# exported\nmaster, slave, velocity, acceleration, jerk\n0, 0, 0, 0, 0\n100.0, 50, 1, 0, 0\n";
    assert_eq!(
        from_csv(text).unwrap(),
        PointTable::from_pairs(&[(0, 0), (100, 50)]).unwrap()
    );
}

#[test]
fn csv_errors_name_the_row() {
    assert_eq!(
        from_csv("m,s\n0,0\n"),
        Err(FormatError::MissingColumn { column: "master" })
    );
    assert_eq!(
        from_csv(""),
        Err(FormatError::MissingColumn { column: "master" })
    );
    assert_eq!(
        from_csv("master,s\n0,0\n"),
        Err(FormatError::MissingColumn { column: "slave" })
    );
    let e = from_csv("master,slave\n0,0\n10,1.5\n").unwrap_err();
    assert!(
        matches!(
            e,
            FormatError::NotAnInteger {
                line: 3,
                column: "slave",
                ..
            }
        ),
        "{e}"
    );
    assert!(e.to_string().starts_with("line 3: slave `1.5`"), "{e}");
    // Every row has the header's number of fields; the message names the
    // file's line (comments counted) and quotes it.
    let e = from_csv("master,slave\n# a comment\n0,0\n10\n").unwrap_err();
    assert!(matches!(e, FormatError::CsvRow { line: 4, .. }), "{e}");
    assert!(e.to_string().starts_with("line 4: `10`: 1 fields"), "{e}");
    // A point the table checks refuse is named by its line too.
    let e = from_csv("master,slave\n0,0\n# a comment\n10,5\n5,6\n").unwrap_err();
    assert!(
        e.to_string()
            .starts_with("line 5: `5,6`: table error (6782)"),
        "{e}"
    );
    assert!(from_csv("master,slave\n0,0\n10,5,7\n").is_err());
    assert!(matches!(
        from_csv("master,slave\n0,0\n0,1\n").unwrap_err(),
        FormatError::TableLine {
            line: 3,
            error: TableError::MasterNotIncreasing { section: 1 },
            ..
        }
    ));
    assert_eq!(
        from_csv("master,slave\n0,0\n1e300,1\n")
            .unwrap_err()
            .to_string(),
        "line 3: master `1e300` is not an integer"
    );
    // Derivative columns, when all three are there, must hold numbers.
    let e =
        from_csv("master,slave,velocity,acceleration,jerk\n0,0,1,0,0\n10,5,nan,0,0\n").unwrap_err();
    assert_eq!(e.to_string(), "line 3: velocity `nan` is not a number");
}

#[test]
fn curve_csv_has_all_derivatives() {
    let p = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![Segment::new(100, 1000, MotionLaw::Cycloid)],
    )
    .unwrap();
    let text = curve_to_csv(&p, [0, 50, 100]);
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "master,slave,velocity,acceleration,jerk");
    assert_eq!(lines.len(), 4);
    assert!(lines[2].starts_with("50,500,20,"), "{}", lines[2]);
    // The table reader accepts it (slave values here are whole).
    assert_eq!(from_csv(&text).unwrap().slave_last(), 1000);
}

#[test]
fn json_round_trip_every_kind() {
    let tables: Vec<CamTable> = vec![
        doc001().into(),
        UniformTable::new(vec![0, 100, 200], 100).unwrap().into(),
        SegmentProfile::new(
            CamPoint::new(0, 0),
            vec![
                Segment::new(100, 1000, MotionLaw::ModifiedSine).with_resolution(30),
                Segment::new(200, 0, MotionLaw::SType),
            ],
        )
        .unwrap()
        .into(),
    ];
    for t in tables {
        let text = to_json(&t);
        assert_eq!(from_json(&text).unwrap(), t, "{text}");
    }
    let hand = r#"{"kind":"profile","start":{"master":0,"slave":0},
                   "segments":[{"master_end":360,"slave_end":90,"law":"cycloid"}]}"#;
    assert_eq!(from_json(hand).unwrap().master_last(), 360);
}

#[test]
fn json_is_validated() {
    let bad_order = r#"{"kind":"points","points":[{"master":5,"slave":0},{"master":5,"slave":1}]}"#;
    let e = from_json(bad_order).unwrap_err();
    assert!(e.to_string().contains("6782"), "{e}");
    let bad_law = r#"{"kind":"profile","start":{"master":0,"slave":0},
                      "segments":[{"master_end":360,"slave_end":90,"law":"wobble"}]}"#;
    assert!(
        from_json(bad_law)
            .unwrap_err()
            .to_string()
            .contains("unknown motion law")
    );
    assert!(from_json(r#"{"kind":"uniform","values":[1,2],"cam_counts":1}"#).is_err());
    assert!(from_json("[").is_err());
}

#[test]
fn register_image_round_trip() {
    let t = doc001();
    let words = register_image::to_words(&t).unwrap();
    assert_eq!(words.len(), register_image::block_len(4));
    assert_eq!(&words[38..42], &[4, 40, 0, 0]);
    assert_eq!(&words[42..44], &[500, 0]);
    assert_eq!(register_image::from_words(&words).unwrap(), t);
    assert_eq!(
        register_image::table_words(&t).unwrap(),
        words[38..].to_vec()
    );
}

#[test]
fn json_refuses_unknown_keys() {
    // A misspelt key must not silently fall back to a default (here: the
    // segment's own resolution would be shared instead).
    let bad = [
        r#"{"kind":"points","points":[{"master":0,"slave":0},{"master":1,"slave":1}],"bogus":3}"#,
        r#"{"kind":"points","points":[{"master":0,"slave":0,"slav":1},{"master":1,"slave":1}]}"#,
        r#"{"kind":"uniform","values":[0,1],"cam_counts":10,"counts":3}"#,
        r#"{"kind":"profile","start":{"master":0,"slave":0},"segments":[{"master_end":10,"slave_end":5,"law":"cycloid","resoluton":4}]}"#,
        r#"{"kind":"profile","start":{"master":0,"slave":0},"segments":[],"extra":1}"#,
    ];
    for text in bad {
        let err = from_json(text).unwrap_err().to_string();
        assert!(err.contains("unknown field"), "{text}: {err}");
    }
    let good = r#"{"kind":"profile","start":{"master":0,"slave":0},"segments":[{"master_end":10,"slave_end":5,"law":"cycloid","resolution":4}]}"#;
    assert!(from_json(good).is_ok());
}
