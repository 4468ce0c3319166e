//! Segment cams: the polynomials against independently computed values,
//! the checks that name the point, make continuous, continuity, sampling.

use ecam_core::segments::{
    InterpolationPoint, Quantity, SegmentCam, SegmentError, SegmentLaw, SegmentSpec,
    make_continuous,
};
use ecam_core::table::Continuity;
use ecam_core::{CamCurve, Cursor, MotionLaw};
use proptest::prelude::*;
use serde_json::Value;

const FIXTURE: &str = include_str!("../fixtures/segment_polynomials.json");

fn close(a: f64, b: f64, scale: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(scale)
}

fn numbers(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

/// A one-segment cam with the fixture case's boundary values.
fn cam_of(case: &Value) -> SegmentCam {
    let degree = case["degree"].as_u64().unwrap();
    let (span, rise) = (
        case["span"].as_f64().unwrap(),
        case["rise"].as_f64().unwrap(),
    );
    let (s, e) = (numbers(&case["start"]), numbers(&case["end"]));
    let jerk = |x: f64| (degree == 7).then_some(x);
    let start = InterpolationPoint {
        velocity: Some(s[0]),
        acceleration: Some(s[1]),
        jerk: jerk(s[2]),
        ..InterpolationPoint::new(0, 0)
    };
    let law = if degree == 7 {
        SegmentLaw::Poly7
    } else {
        SegmentLaw::Poly5
    };
    let end = InterpolationPoint {
        velocity: Some(e[0]),
        acceleration: Some(e[1]),
        jerk: jerk(e[2]),
        ..InterpolationPoint::new(span as i64, rise as i64)
    };
    SegmentCam::new(start, vec![SegmentSpec::new(law, 0, 0).with_end(end)]).unwrap()
}

#[test]
fn polynomial_coefficients_and_peaks_match_the_numpy_fixture() {
    let fixture: Value = serde_json::from_str(FIXTURE).unwrap();
    let cases = fixture["cases"].as_array().unwrap();
    assert!(cases.len() >= 8);
    for case in cases {
        let name = case["name"].as_str().unwrap();
        let cam = cam_of(case);
        let want = numbers(&case["coefficients_u"]);
        let got = cam.polynomial(0).unwrap().coefficients;
        let scale = want.iter().fold(0.0_f64, |m, c| m.max(c.abs()));
        for (k, (g, w)) in got.iter().zip(&want).enumerate() {
            assert!(close(*g, *w, scale), "{name}: c{k} {g} vs {w}");
        }
        let p = cam.peaks()[0];
        for (what, got, want) in [
            ("peak velocity", p.peak_velocity, &case["peak_velocity"]),
            (
                "peak acceleration",
                p.peak_acceleration,
                &case["peak_acceleration"],
            ),
            ("peak jerk", p.peak_jerk, &case["peak_jerk"]),
        ] {
            let want = want.as_f64().unwrap();
            assert!(close(got, want, 0.0), "{name}: {what} {got} vs {want}");
        }
        for (what, got, want) in [
            ("Cv", p.cv, &case["cv"]),
            ("Ca", p.ca, &case["ca"]),
            ("Cj", p.cj, &case["cj"]),
        ] {
            match (got, want.as_f64()) {
                (Some(g), Some(w)) => assert!(close(g, w, 0.0), "{name}: {what} {g} vs {w}"),
                (None, None) => {}
                other => panic!("{name}: {what} {other:?}"),
            }
        }
    }
}

#[test]
fn the_flying_saw_made_continuous_solves_to_the_fixture() {
    // The example's segments, free values filled in by make continuous.
    let cv = SegmentLaw::Rise(MotionLaw::ConstantVelocity);
    let cam = SegmentCam::continuous(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Poly5, 1000, 500),
            SegmentSpec::new(cv, 2000, 1500),
            SegmentSpec::new(SegmentLaw::Poly5, 3000, 2000),
            SegmentSpec::new(SegmentLaw::Poly7, 5000, 0),
            SegmentSpec::new(cv, 6000, 0),
        ],
    )
    .unwrap();
    let fixture: Value = serde_json::from_str(FIXTURE).unwrap();
    let by_name = |n: &str| {
        fixture["cases"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"].as_str().unwrap().starts_with(n))
            .unwrap()
            .clone()
    };
    for (segment, name) in [
        (0, "flying saw, segment 1"),
        (2, "flying saw, segment 3"),
        (3, "flying saw, segment 4"),
    ] {
        let want = numbers(&by_name(name)["coefficients_u"]);
        let got = cam.polynomial(segment).unwrap().coefficients;
        for (g, w) in got.iter().zip(&want) {
            assert!(close(*g, *w, 2000.0), "{name}: {got:?} vs {want:?}");
        }
    }
    // Hand-computed boundary values: 1 pulse/count into and out of the cut,
    // rest where the saw turns (3000), at the dwell (5000) and the seam.
    let points = cam.points();
    let v: Vec<f64> = points.iter().map(|p| p.velocity.unwrap()).collect();
    assert_eq!(v, [0.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
    assert!(points.iter().all(|p| p.acceleration == Some(0.0)));
    let report = cam.continuity();
    assert_eq!(report.cam, Continuity::C2);
    let classes: Vec<Continuity> = report.joints.iter().map(|j| j.class).collect();
    // The poly-7 takes the jerk of both neighbours: C3 either side of it.
    assert_eq!(
        classes,
        [
            Continuity::C2,
            Continuity::C2,
            Continuity::C3,
            Continuity::C3,
            Continuity::C2
        ]
    );
}

#[test]
fn a_rest_to_rest_law_is_refused_where_the_point_asks_for_velocity() {
    let err = SegmentCam::new(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::Cycloid), 1000, 500).with_velocity(0.5),
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 2000, 1000),
        ],
    )
    .unwrap_err();
    match &err {
        SegmentError::CannotMeet {
            point,
            segment,
            quantity,
            ..
        } => {
            assert_eq!((*point, *segment, *quantity), (1, 1, Quantity::Velocity));
        }
        other => panic!("{other:?}"),
    }
    let text = err.to_string();
    assert!(text.contains("point 1 (master 1000)"), "{text}");
    assert!(
        text.contains("cycloid") && text.contains("poly-5"),
        "{text}"
    );
    assert_eq!(err.code(), 6781);
}

#[test]
fn make_continuous_refuses_two_laws_that_fix_different_velocities() {
    let err = SegmentCam::continuous(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::Cycloid), 1000, 500),
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 2000, 1500),
        ],
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("point 1 (master 1000)")
            && text.contains("arrives with velocity 0")
            && text.contains("leaves with 1"),
        "{text}"
    );
    // Without make continuous the same cam is built, and its report says C0.
    let cam = SegmentCam::new(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::Cycloid), 1000, 500),
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 2000, 1500),
        ],
    )
    .unwrap();
    let report = cam.continuity();
    assert_eq!(report.cam, Continuity::C0);
    assert_eq!(report.joints[0].master, 1000);
    assert!((report.joints[0].velocity_jump - 1.0).abs() < 1e-12);
}

#[test]
fn bad_points_are_named() {
    let e = SegmentCam::new(InterpolationPoint::new(0, 0), vec![]).unwrap_err();
    assert_eq!(e, SegmentError::NoSegments);
    let e = SegmentCam::new(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Poly5, 100, 1),
            SegmentSpec::new(SegmentLaw::Poly5, 100, 2),
        ],
    )
    .unwrap_err();
    assert_eq!(e, SegmentError::MasterNotIncreasing { point: 2 });
    assert_eq!(e.code(), 6782);
    let e = SegmentCam::new(
        InterpolationPoint {
            velocity: Some(f64::NAN),
            ..InterpolationPoint::new(0, 0)
        },
        vec![SegmentSpec::new(SegmentLaw::Poly5, 100, 1)],
    )
    .unwrap_err();
    assert_eq!(
        e,
        SegmentError::OutOfRange {
            point: 0,
            what: "velocity"
        }
    );
    let e = SegmentCam::new(
        InterpolationPoint::new(0, 0),
        vec![SegmentSpec::new(SegmentLaw::Poly5, 1 << 60, 1)],
    )
    .unwrap_err();
    assert_eq!(
        e,
        SegmentError::OutOfRange {
            point: 1,
            what: "master"
        }
    );
}

#[test]
fn a_poly_5_cannot_meet_a_jerk_a_poly_7_can() {
    let ask = |law| {
        SegmentCam::new(
            InterpolationPoint {
                jerk: Some(1e-6),
                ..InterpolationPoint::new(0, 0)
            },
            vec![SegmentSpec::new(law, 1000, 100)],
        )
    };
    match ask(SegmentLaw::Poly5).unwrap_err() {
        SegmentError::CannotMeet {
            quantity, point, ..
        } => {
            assert_eq!((quantity, point), (Quantity::Jerk, 0));
        }
        other => panic!("{other:?}"),
    }
    let cam = ask(SegmentLaw::Poly7).unwrap();
    assert!((cam.eval(0.0, &mut Cursor::new()).j - 1e-6).abs() < 1e-15);
}

#[test]
fn sampling_keeps_the_points_and_fills_buffers() {
    let cam = SegmentCam::continuous(
        InterpolationPoint {
            velocity: Some(0.4),
            ..InterpolationPoint::new(0, 0)
        },
        vec![
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 500, 200),
            SegmentSpec::new(SegmentLaw::VelocityCycloid, 2250, 600),
            SegmentSpec::new(SegmentLaw::VelocityCycloid, 4000, 1000),
        ],
    )
    .unwrap();
    let table = cam.sample(100).unwrap();
    assert_eq!(table.points().len(), 100);
    for p in cam.points() {
        assert!(
            table
                .points()
                .iter()
                .any(|q| q.master == p.master && q.slave == p.slave)
        );
    }
    // Every table point within half a pulse of the exact cam.
    let mut c = Cursor::new();
    for q in table.points() {
        assert!((cam.position(q.master as f64, &mut c) - q.slave as f64).abs() <= 0.5 + 1e-9);
    }
    let buffer = cam.sample_uniform(401).unwrap();
    assert_eq!(buffer.cam_counts(), 4000);
    assert_eq!(buffer.values()[50], 200); // master 500: the end of the sync zone
    let image = ecam_core::register_image::to_words(&table).unwrap();
    assert_eq!(image.len(), ecam_core::register_image::block_len(100));
    // JSON round trip.
    let json = serde_json::to_string(&cam).unwrap();
    let back: SegmentCam = serde_json::from_str(&json).unwrap();
    assert_eq!(back, cam);
}

fn law_strategy() -> impl Strategy<Value = SegmentLaw> {
    prop::sample::select(SegmentLaw::ALL.to_vec())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(200)))]

    /// Whatever the laws and points, building and making continuous never
    /// panic; a cam that builds meets every value its points fix, and one
    /// made continuous is at least C1 wherever it is not refused... and C2
    /// wherever both neighbours adapt.
    #[test]
    fn solved_segments_meet_their_points(
        laws in prop::collection::vec(law_strategy(), 1..6),
        steps in prop::collection::vec((1i64..5000, -3000i64..3000), 6),
        v0 in prop::option::of(-3.0f64..3.0),
    ) {
        let mut master = 0;
        let mut slave = 0;
        let segments: Vec<SegmentSpec> = laws.iter().zip(&steps).map(|(law, (dm, ds))| {
            master += dm;
            slave += ds;
            SegmentSpec::new(*law, master, slave)
        }).collect();
        let start = InterpolationPoint { velocity: v0, ..InterpolationPoint::new(0, 0) };
        if let Ok(cam) = SegmentCam::new(start, segments.clone()) {
            let mut c = Cursor::new();
            for p in cam.points() {
                let k = cam.eval(p.master as f64, &mut c);
                prop_assert!((k.s - p.slave as f64).abs() < 1e-6);
            }
            let _ = cam.continuity();
            let _ = cam.sample(100);
        }
        if let Ok((s, segs)) = make_continuous(start, segments) {
            if let Ok(cam) = SegmentCam::new(s, segs) {
                prop_assert!(cam.continuity().cam >= Continuity::C2, "{:?}", cam.continuity());
                prop_assert!(cam.continuity().seam >= Continuity::C2);
            }
        }
    }
}

#[test]
fn a_dwell_that_adapts_takes_the_filled_velocities() {
    // The poly-5 segments 1 and 3 do not rise; make continuous gives them
    // the constant velocity's 5000/1200 at one end and 0 at the other.
    // (Rounding in the solved end values once refused them as unmet.)
    let cam = SegmentCam::continuous(
        InterpolationPoint::new(0, 0),
        vec![
            SegmentSpec::new(SegmentLaw::Poly5, 600, 0),
            SegmentSpec::new(SegmentLaw::Rise(MotionLaw::ConstantVelocity), 1800, 5000),
            SegmentSpec::new(SegmentLaw::Poly5, 2400, 5000),
            SegmentSpec::new(SegmentLaw::Poly5, 3600, 0),
        ],
    )
    .unwrap();
    assert_eq!(cam.continuity().cam, Continuity::C2);
    let v = cam.points()[1].velocity.unwrap();
    assert!((v - 5000.0 / 1200.0).abs() < 1e-12);
    assert!(cam.peaks()[0].cv.is_none());
}
