//! Invariants of laws, profiles and tables under random input.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::key_points::{self, CurveType, KeyPoint, Params};
use ecam_core::io::{from_csv, from_json};
use ecam_core::table::{Continuity, Summary, sample_function};
use ecam_core::{
    CamCurve, CamPoint, Cursor, MotionLaw, PointTable, Segment, SegmentProfile, UniformTable,
    register_image,
};
use proptest::prelude::*;

/// Any i64, but often a small one, so that valid inputs come up too.
fn position() -> impl Strategy<Value = i64> {
    prop_oneof![any::<i64>(), -100_000i64..100_000]
}

fn any_law() -> impl Strategy<Value = MotionLaw> {
    prop::sample::select(MotionLaw::ALL.to_vec())
}

/// A valid profile: 1..8 segments, each 600..20000 counts long, rising or
/// falling by up to ±50000 pulses, along `law`.
fn profile_with(law: impl Strategy<Value = MotionLaw>) -> impl Strategy<Value = SegmentProfile> {
    (
        -100_000i64..100_000,
        -100_000i64..100_000,
        prop::collection::vec((600i64..20_000, -50_000i64..50_000, law), 1..8),
    )
        .prop_map(|(m0, s0, segs)| {
            let mut m = m0;
            let segments = segs
                .into_iter()
                .map(|(span, slave, law)| {
                    m += span;
                    Segment::new(m, slave, law)
                })
                .collect();
            SegmentProfile::new(CamPoint::new(m0, s0), segments).unwrap()
        })
}

/// Largest |acceleration| inside a segment of `law` (the published Ca counts
/// end impulses as infinite; inside the segment the constant-velocity law has none).
fn interior_ca(law: MotionLaw) -> f64 {
    let ca = law.characteristics().ca;
    if ca.is_finite() { ca } else { 0.0 }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn sampled_table_reproduces_its_profile(
        profile in profile_with(any_law()),
        total in 10u16..=512,
        probes in prop::collection::vec(0.0f64..=1.0, 50),
    ) {
        let Ok(table) = profile.sample(total) else {
            // Only refused when a segment is too short for its share.
            let res = profile.resolutions(total).unwrap();
            let first = profile.master_first();
            let too_short = profile.segments().iter().zip(&res).enumerate().any(|(i, (s, &r))| {
                let from = if i == 0 { first } else { profile.segments()[i - 1].master_end };
                s.master_end - from < i64::from(r)
            });
            prop_assert!(too_short);
            return Ok(());
        };
        prop_assert_eq!(table.points().len(), usize::from(total));
        prop_assert_eq!(table.master_first(), profile.master_first());
        prop_assert_eq!(table.master_last(), profile.master_last());
        prop_assert_eq!(table.slave_first(), profile.slave_first());
        prop_assert_eq!(table.slave_last(), profile.slave_last());
        for key in profile.key_points() {
            prop_assert!(table.points().contains(&key));
        }
        // Linear interpolation of a curve with |a| ≤ A over a step h errs by
        // at most A·h²/8; rounding the points adds at most half a pulse.
        let res = profile.resolutions(total).unwrap();
        let mut from = profile.start();
        let mut bound_of_segment = Vec::new();
        for (seg, &r) in profile.segments().iter().zip(&res) {
            let span = (seg.master_end - from.master) as f64;
            let rise = (seg.slave_end - from.slave) as f64;
            let h = (span / f64::from(r)).ceil();
            let a = interior_ca(seg.law) * rise.abs() / (span * span);
            bound_of_segment.push((seg.master_end, a * h * h / 8.0 + 0.5 + 1e-6));
            from = CamPoint::new(seg.master_end, seg.slave_end);
        }
        let (mut ct, mut cp) = (Cursor::new(), Cursor::new());
        let first = profile.master_first() as f64;
        let span = profile.master_span() as f64;
        for u in probes {
            let m = first + u * span;
            let bound = bound_of_segment.iter().find(|(end, _)| m <= *end as f64).map_or(0.5, |b| b.1);
            let err = (table.position(m, &mut ct) - profile.position(m, &mut cp)).abs();
            prop_assert!(err <= bound, "at {} error {} > {}", m, err, bound);
        }
    }

    #[test]
    fn laws_with_zero_end_velocity_join_smoothly(
        profile in profile_with(prop::sample::select(
            MotionLaw::ALL.into_iter().filter(|l| l.characteristics().zero_end_velocity).collect::<Vec<_>>(),
        )),
    ) {
        let all_c2 = profile.segments().iter().all(|s| s.law.characteristics().zero_end_acceleration);
        let class = Summary::of(&profile).continuity;
        prop_assert!(class >= Continuity::C1, "{:?}", class);
        if all_c2 {
            prop_assert_eq!(class, Continuity::C2);
        }
    }

    #[test]
    fn law_eval_never_misbehaves(law in any_law(), u in any::<f64>()) {
        let k = law.eval(u);
        prop_assert!(k.s.is_finite() && k.v.is_finite() && k.a.is_finite() && k.j.is_finite());
        prop_assert!((-1e-12..=1.0 + 1e-12).contains(&k.s));
    }

    #[test]
    fn constructors_refuse_instead_of_panicking(
        values in prop::collection::vec(position(), 0..6),
        cam_counts in position(),
        start in (position(), position()),
        segs in prop::collection::vec((position(), position(), any_law(), any::<Option<u16>>()), 0..5),
        total in any::<u16>(),
        master in any::<f64>(),
    ) {
        let mut c = Cursor::new();
        if let Ok(t) = UniformTable::new(values.clone(), cam_counts) {
            let _ = t.eval(master, &mut c);
        }
        let pairs: Vec<(i64, i64)> = values.chunks(2).filter(|p| p.len() == 2).map(|p| (p[0], p[1])).collect();
        if let Ok(t) = PointTable::from_pairs(&pairs) {
            let _ = t.eval(master, &mut c);
            let _ = register_image::to_words(&t);
            let _ = Summary::of(&t);
        }
        let segments = segs
            .into_iter()
            .map(|(m, s, law, resolution)| Segment { master_end: m, slave_end: s, law, resolution })
            .collect();
        if let Ok(p) = SegmentProfile::new(CamPoint::new(start.0, start.1), segments) {
            let _ = p.eval(master, &mut c);
            let _ = Summary::of(&p);
            let _ = p.sample_uniform(usize::from(total % 600));
            // Sampling huge spans could allocate; the resolution bounds it to 512 points.
            let _ = p.sample(total);
        }
    }

    #[test]
    fn function_sampling_refuses_bad_values(
        first in any::<i64>(),
        last in any::<i64>(),
        points in 0usize..600,
        value in any::<f64>(),
    ) {
        if let Ok(t) = sample_function(|_| value, first, last, points) {
            prop_assert_eq!(t.points().len(), points);
            prop_assert_eq!(t.master_first(), first);
            prop_assert_eq!(t.master_last(), last);
        }
    }

    #[test]
    fn readers_refuse_garbage(words in prop::collection::vec(any::<i16>(), 0..120), text in ".{0,200}") {
        let mut words = words;
        if words.len() > 39 {
            words[39] = 40;
            words[38] = words[38].rem_euclid(20);
        }
        let _ = register_image::from_words(&words);
        let _ = from_csv(&text);
        let _ = from_csv(&format!("master,slave\n{text}"));
        let _ = from_json(&text);
    }

    #[test]
    fn register_image_round_trips(points in prop::collection::btree_map(any::<i32>(), any::<i32>(), 2..60)) {
        let pairs: Vec<(i64, i64)> = points.into_iter().map(|(m, s)| (i64::from(m), i64::from(s))).collect();
        let t = PointTable::from_pairs(&pairs).unwrap();
        let words = register_image::to_words(&t).unwrap();
        prop_assert_eq!(register_image::from_words(&words).unwrap(), t);
    }

    #[test]
    fn key_points_generator_never_panics(
        total in any::<u16>(),
        initial in any::<i64>(),
        kps in prop::collection::vec((any::<i64>(), any::<i64>(), 0i32..4, any::<u16>()), 0..12),
    ) {
        let key_points = kps
            .into_iter()
            .map(|(m, s, code, resolution)| KeyPoint {
                master: m,
                slave: s,
                curve: CurveType::from_code(code).unwrap(),
                resolution,
            })
            .collect();
        let params = Params { total_resolution: total, key_points, initial_slave: initial };
        if let Ok(g) = key_points::generate(&params) {
            prop_assert!(g.table.points().len() <= 512);
            prop_assert!(register_image::to_words(&g.table).is_ok());
        }
    }
}
