//! Property tests over random generator parameters: no panics, and every
//! table that is produced hits its end points exactly, has a strictly
//! increasing master and respects its speed limit.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::{flying_saw, rotary_cut, s_curve};
use ecam_core::{CamCurve, CamPoint, PointTable};
use proptest::prelude::*;

fn peak(t: &PointTable) -> f64 {
    t.points()
        .windows(2)
        .map(|w| ((w[1].slave - w[0].slave) as f64 / (w[1].master - w[0].master) as f64).abs())
        .fold(0.0, f64::max)
}

fn assert_well_formed(t: &PointTable, master_end: i64, slave_end: i64, resolution: u16) {
    assert_eq!(t.points()[0], CamPoint::new(0, 0));
    assert_eq!((t.master_last(), t.slave_last()), (master_end, slave_end));
    assert!(t.points().windows(2).all(|w| w[1].master > w[0].master));
    assert!(t.points().len() <= usize::from(resolution));
}

/// Ratios from tame to extreme, plus the floats that must be refused.
fn ratio() -> impl Strategy<Value = f64> {
    prop_oneof![
        8 => 0.01f64..50.0,
        1 => prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(0.0), Just(-1.0), Just(1e-300), Just(1e300)],
    ]
}

fn curve() -> impl Strategy<Value = AccelCurve> {
    prop::sample::select(AccelCurve::ALL.to_vec())
}

fn placement() -> impl Strategy<Value = CamPlacement> {
    prop::sample::select(CamPlacement::ALL.to_vec())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(300)))]

    #[test]
    fn s_curve_tables_are_well_formed(
        total in prop_oneof![-3_000_000_000i64..3_000_000_000, -2000i64..2000],
        speed in 0u32..160_000,
        accel in 0u16..=33_000,
        decel in 0u16..=33_000,
        resolution in 40u16..=530,
        curve in curve(),
    ) {
        let p = s_curve::Params { total_pulses: total, max_speed_hz: speed, accel_ms: accel, decel_ms: decel, resolution, curve };
        if let Ok(g) = s_curve::generate(&p) {
            assert_well_formed(&g.table, g.duration, total, resolution);
            // P11 is the table's steepest section.
            prop_assert_eq!(g.max_speed_hz, (peak(&g.table) * 1000.0).round() as i64);
            // Whole-pulse steps cannot beat the limit when it is a whole
            // number of pulses per master count.
            if speed % 1000 == 0 {
                prop_assert!(g.max_speed_hz <= i64::from(speed), "{} > {}", g.max_speed_hz, speed);
            }
            prop_assert!(g.uniform_time >= 0 && g.uniform_time <= g.duration);
        }
    }

    #[test]
    fn rotary_cut_tables_are_well_formed(
        raw_master in prop_oneof![4 => Just(None), 1 => (-10i64..3_000_000_000).prop_map(Some)],
        cut_factor in 0.2f64..6.0,
        slave_length in prop_oneof![4 => 2i64..100_000, 1 => -10i64..3_000_000_000],
        sync_fraction in 0.0f64..1.1,
        sync_ratio in ratio(),
        headroom in prop_oneof![6 => 1.0f64..20.0, 1 => 0.5f64..1.0, 1 => Just(1.0)],
        curve in curve(),
        placement in placement(),
        resolution in prop_oneof![4 => 20u16..=512, 1 => 0u16..=520],
    ) {
        // Mostly a cut length around the circumference (regimes from speed-up
        // to dwell), sometimes anything.
        let derived = (slave_length as f64 / sync_ratio * cut_factor).clamp(-1e12, 1e12) as i64;
        let master_length = raw_master.unwrap_or(derived);
        let sync_length = (slave_length as f64 * sync_fraction) as i64;
        let p = rotary_cut::Params {
            master_length, slave_length, sync_length, sync_ratio,
            max_ratio: sync_ratio * headroom, accel_curve: curve, placement, resolution,
        };
        if let Ok(g) = rotary_cut::generate(&p) {
            assert_well_formed(&g.table, master_length, slave_length, resolution);
            prop_assert!(peak(&g.table) <= p.max_ratio);
            prop_assert!(g.table.points().windows(2).all(|w| w[1].slave >= w[0].slave));
            let (m0, m1) = g.sync.unwrap();
            prop_assert!((g.sync_ratio - sync_ratio).abs() <= 0.5 / (m1 - m0) as f64 + 1e-9 * sync_ratio);
            let pts = g.table.points();
            let i = pts.iter().position(|q| q.master == m0).unwrap();
            prop_assert_eq!(pts[i + 1].master, m1);
        }
    }

    #[test]
    fn flying_saw_tables_are_well_formed(
        raw_master in prop_oneof![4 => Just(None), 1 => (-10i64..3_000_000_000).prop_map(Some)],
        stroke_factor in 0.5f64..10.0,
        slave_length in prop_oneof![4 => -100_000i64..100_000, 1 => -3_000_000_000i64..3_000_000_000],
        sync_fraction in 0.0f64..1.1,
        sync_ratio in ratio(),
        headroom in prop_oneof![6 => 1.0f64..20.0, 1 => 0.5f64..1.0, 1 => Just(1.0)],
        curve in curve(),
        placement in prop_oneof![
            4 => prop::sample::select(vec![CamPlacement::LeftCam, CamPlacement::MidCamAll, CamPlacement::RightCam]),
            1 => placement(),
        ],
        resolution in prop_oneof![4 => 20u16..=512, 1 => 0u16..=520],
    ) {
        // Mostly a master long enough for the two ramps (about 2·stroke/ratio), sometimes anything.
        let derived = (slave_length.unsigned_abs() as f64 / sync_ratio * stroke_factor).clamp(-1e12, 1e12) as i64;
        let master_length = raw_master.unwrap_or(derived);
        let sync_length = (slave_length.unsigned_abs() as f64 * sync_fraction) as i64;
        let p = flying_saw::Params {
            master_length, slave_length, sync_length, sync_ratio,
            max_ratio: sync_ratio * headroom, accel_curve: curve, placement, resolution,
        };
        if let Ok(g) = flying_saw::generate(&p) {
            assert_well_formed(&g.table, master_length, slave_length, resolution);
            prop_assert!(peak(&g.table) <= p.max_ratio);
            let sign = slave_length.signum();
            prop_assert!(g.table.points().windows(2).all(|w| (w[1].slave - w[0].slave) * sign >= 0));
            let back = flying_saw::generate(&flying_saw::Params { slave_length: -slave_length, ..p }).unwrap();
            prop_assert_eq!(g.table.stroke() + back.table.stroke(), 0);
        }
    }

    #[test]
    fn non_finite_ratios_are_parameter_errors(bad in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), Just(f64::NEG_INFINITY), -1e9f64..=0.0]) {
        let r = rotary_cut::generate(&rotary_cut::Params { sync_ratio: bad, ..Default::default() });
        prop_assert_eq!(r.unwrap_err().code(), 6781);
        let r = rotary_cut::generate(&rotary_cut::Params { max_ratio: bad, ..Default::default() });
        prop_assert_eq!(r.unwrap_err().code(), 6781);
        let f = flying_saw::generate(&flying_saw::Params { sync_ratio: bad, ..Default::default() });
        prop_assert_eq!(f.unwrap_err().code(), 6781);
        let f = flying_saw::generate(&flying_saw::Params { max_ratio: bad, ..Default::default() });
        prop_assert_eq!(f.unwrap_err().code(), 6781);
    }
}

/// Random geometry succeeds often enough for the properties above to mean something.
#[test]
fn random_geometry_mostly_generates() {
    let mut ok = 0;
    for lm in (200..3000).step_by(97) {
        for s in [100, 300, 600] {
            let p = rotary_cut::Params {
                master_length: lm,
                sync_length: s,
                ..Default::default()
            };
            ok += usize::from(rotary_cut::generate(&p).is_ok());
        }
    }
    assert!(ok > 60, "{ok}");
}
