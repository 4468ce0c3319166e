//! Table kinds through the `CamCurve` interface: segment profiles and their
//! sampling, evenly spaced tables, function tables, summaries.
#![allow(clippy::unwrap_used)]

use ecam_core::table::{Continuity, Summary, sample_function};
use ecam_core::{
    CamCurve, CamPoint, CamTable, Cursor, MotionLaw, PointTable, Segment, SegmentProfile,
    TableError, UniformTable,
};

fn dwell_rise_dwell_return(law: MotionLaw) -> SegmentProfile {
    SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![
            Segment::new(90, 0, law),
            Segment::new(180, 3600, law),
            Segment::new(270, 3600, law),
            Segment::new(360, 0, law),
        ],
    )
    .unwrap()
}

#[test]
fn profile_scales_each_law_onto_its_segment() {
    for law in MotionLaw::ALL {
        let p = dwell_rise_dwell_return(law);
        let mut c = Cursor::new();
        let mid = p.eval(135.0, &mut c);
        let c_law = law.characteristics();
        assert!((mid.s - 1800.0).abs() < 1e-9, "{law}");
        let k = law.eval(0.5);
        assert!((mid.v - k.v * 3600.0 / 90.0).abs() < 1e-9, "{law}");
        assert!(c_law.cv * 40.0 >= mid.v.abs() - 1e-9);
        // Return segment runs backwards.
        assert!(p.eval(315.0, &mut c).v < 0.0, "{law}");
        assert_eq!(p.position(360.0, &mut c), 0.0);
        assert_eq!(p.position(180.0, &mut c), 3600.0);
    }
}

#[test]
fn continuity_follows_the_laws_promises() {
    let class = |law| Summary::of(&dwell_rise_dwell_return(law)).continuity;
    assert_eq!(class(MotionLaw::ConstantVelocity), Continuity::C0);
    assert_eq!(class(MotionLaw::ConstantAcceleration), Continuity::C1);
    assert_eq!(class(MotionLaw::SimpleHarmonic), Continuity::C1);
    assert_eq!(class(MotionLaw::Cubic), Continuity::C1);
    for law in [
        MotionLaw::Cycloid,
        MotionLaw::ModifiedTrapezoid,
        MotionLaw::ModifiedSine,
        MotionLaw::ModifiedConstantVelocity,
        MotionLaw::Poly345,
        MotionLaw::Poly4567,
        MotionLaw::SType,
    ] {
        assert_eq!(class(law), Continuity::C2, "{law}");
    }
    // A point table of a smooth curve is only C0: its slope changes at every point.
    let sampled = dwell_rise_dwell_return(MotionLaw::Cycloid)
        .sample(100)
        .unwrap();
    assert_eq!(Summary::of(&sampled).continuity, Continuity::C0);
    let line = PointTable::from_pairs(&[(0, 0), (10, 10), (20, 20)]).unwrap();
    assert_eq!(Summary::of(&line).continuity, Continuity::C2);
}

#[test]
fn summary_reports_peaks_and_stroke() {
    let p = dwell_rise_dwell_return(MotionLaw::ModifiedSine);
    let s = Summary::of(&p);
    assert_eq!(s.sections, 4);
    assert_eq!(s.master_span, 360);
    assert_eq!(s.stroke, 0);
    assert_eq!((s.slave_min, s.slave_max), (0.0, 3600.0));
    let c = MotionLaw::ModifiedSine.characteristics();
    assert!((s.peak_velocity - c.cv * 40.0).abs() < 1e-3 * s.peak_velocity);
    assert!((s.peak_acceleration - c.ca * 3600.0 / 8100.0).abs() < 1e-3 * s.peak_acceleration);
    assert_eq!(s.seam, Continuity::C2);
    // A straight-line point table repeats smoothly; a bend at the seam does not.
    let line = PointTable::from_pairs(&[(0, 0), (10, 10), (20, 20)]).unwrap();
    assert_eq!(Summary::of(&line).seam, Continuity::C2);
    let bent = PointTable::from_pairs(&[(0, 0), (10, 10), (20, 30)]).unwrap();
    assert_eq!(Summary::of(&bent).seam, Continuity::C0);
    // A rise that ends at full speed (constant velocity) meets the next cycle's
    // start at full speed too.
    let ramp = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![Segment::new(100, 100, MotionLaw::ConstantVelocity)],
    )
    .unwrap();
    assert_eq!(Summary::of(&ramp).seam, Continuity::C2);
}

#[test]
fn sampling_hits_key_points_and_counts_points() {
    let p = SegmentProfile::new(
        CamPoint::new(-500, 7),
        vec![
            Segment::new(400, 7, MotionLaw::Poly345),
            Segment::new(1000, 3607, MotionLaw::Poly345),
            Segment::new(1200, -3, MotionLaw::SType),
        ],
    )
    .unwrap();
    for total in [10u16, 11, 100, 357, 512] {
        let t = p.sample(total).unwrap();
        assert_eq!(t.points().len(), usize::from(total));
        for key in p.key_points() {
            assert!(t.points().contains(&key), "{total}: {key:?}");
        }
    }
    let fixed = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![
            Segment::new(90, 0, MotionLaw::Cycloid).with_resolution(5),
            Segment::new(180, 100, MotionLaw::Cycloid),
        ],
    )
    .unwrap();
    assert_eq!(fixed.resolutions(20).unwrap(), vec![5, 14]);
    assert_eq!(fixed.sample(20).unwrap().points()[5], CamPoint::new(90, 0));
    // More points than master counts in a segment.
    let short = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![Segment::new(5, 10, MotionLaw::Cycloid)],
    )
    .unwrap();
    assert_eq!(short.sample(10).unwrap_err().code(), 6781);
}

#[test]
fn profile_constructor_refuses_bad_segments() {
    let seg = |m| Segment::new(m, 0, MotionLaw::Cycloid);
    let start = CamPoint::new(0, 0);
    assert_eq!(SegmentProfile::new(start, vec![]).unwrap_err().code(), 6783);
    assert_eq!(
        SegmentProfile::new(start, vec![seg(10), seg(10)]).unwrap_err(),
        TableError::MasterNotIncreasing { section: 2 }
    );
    assert_eq!(
        SegmentProfile::new(start, vec![seg(10), seg(i64::MAX)]).unwrap_err(),
        TableError::ValueOutOfRange { section: 2 }
    );
    assert_eq!(
        SegmentProfile::new(start, vec![seg(10).with_resolution(0)])
            .unwrap_err()
            .code(),
        6781
    );
}

#[test]
fn cam_table_delegates_and_cursor_agrees_with_fresh_search() {
    let tables: Vec<CamTable> = vec![
        PointTable::from_pairs(&[(0, 500), (10000, 1500), (20000, 1000), (30000, 2000)])
            .unwrap()
            .into(),
        UniformTable::new(vec![0, 100, 50, 400, 400], 30000)
            .unwrap()
            .into(),
        dwell_rise_dwell_return(MotionLaw::ModifiedTrapezoid).into(),
    ];
    for t in &tables {
        let mut seq = Cursor::new();
        let span = t.master_span() as f64;
        for i in 0..=3000 {
            let m = t.master_first() as f64 + span * i as f64 / 3000.0;
            let a = t.eval(m, &mut seq);
            let b = t.eval(m, &mut Cursor::new());
            assert_eq!(a, b, "{t:?} at {m}");
        }
        // Backwards and with jumps.
        for m in [span, 0.0, span / 2.0, span / 3.0, span, -5.0] {
            assert_eq!(t.eval(m, &mut seq), t.eval(m, &mut Cursor::new()));
        }
    }
    assert_eq!(tables[0].segment_count(), 3);
    assert_eq!(tables[1].stroke(), 400);
    assert_eq!(tables[2].master_last(), 360);
}

#[test]
fn function_table_is_the_sine_example() {
    let t = sample_function(
        |m| 5000.0 * (m / 36000.0 * std::f64::consts::TAU).sin(),
        0,
        36000,
        361,
    )
    .unwrap();
    assert_eq!(t.points().len(), 361);
    assert_eq!(t.points()[90], CamPoint::new(9000, 5000));
    assert_eq!(t.points()[270], CamPoint::new(27000, -5000));
    assert_eq!(t.slave_last(), 0);
    // Uneven division: masters are whole counts, ends exact.
    let t = sample_function(|m| m, 7, 17, 4).unwrap();
    let masters: Vec<i64> = t.points().iter().map(|p| p.master).collect();
    assert_eq!(masters, vec![7, 10, 13, 17]);
    assert_eq!(
        sample_function(|_| f64::NAN, 0, 10, 3).unwrap_err(),
        TableError::ValueOutOfRange { section: 0 }
    );
    assert_eq!(sample_function(|m| m, 0, 10, 1).unwrap_err().code(), 6783);
    assert_eq!(sample_function(|m| m, 10, 10, 2).unwrap_err().code(), 6782);
    assert_eq!(sample_function(|m| m, 0, 10, 12).unwrap_err().code(), 6781);
}

#[test]
fn profile_fills_an_evenly_spaced_buffer() {
    let p = SegmentProfile::new(
        CamPoint::new(1000, 50),
        vec![
            Segment::new(1500, 50, MotionLaw::Cycloid),
            Segment::new(2000, 1050, MotionLaw::Cycloid),
        ],
    )
    .unwrap();
    let u = p.sample_uniform(7).unwrap(); // 1000 counts in 6 pieces of 166⅔
    assert_eq!(u.cam_counts(), 1000);
    assert_eq!(u.values().len(), 7);
    assert_eq!(u.values()[0], 50);
    assert_eq!(u.values()[3], 50); // 500 counts in: end of the dwell
    assert_eq!(u.values()[6], 1050);
    let mut c = Cursor::new();
    let expected = p.position(1000.0 + 1000.0 * 4.0 / 6.0, &mut c).round() as i64;
    assert_eq!(u.values()[4], expected);
    assert_eq!(p.sample_uniform(1).unwrap_err().code(), 6783);
    let short = SegmentProfile::new(
        CamPoint::new(0, 0),
        vec![Segment::new(1, 1, MotionLaw::Cycloid)],
    )
    .unwrap();
    assert_eq!(short.sample_uniform(2).unwrap_err().code(), 6781);
}
