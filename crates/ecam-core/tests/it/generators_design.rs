//! The design curve behind the S-curve, rotary-cut and flying-saw tables:
//! analytic derivatives that agree with finite differences, every table
//! point within half a pulse of it, and the sync ratio held exactly in the
//! sync zone.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::DesignCurve;
use ecam_core::generator::{flying_saw, rotary_cut, s_curve};
use ecam_core::{CamCurve, PointTable};
use proptest::prelude::*;

/// Every table point within ½ pulse of the design (the sampler rounds half
/// up; 1e-9 covers the float noise of the design's own sums).
fn assert_passes_through(table: &PointTable, design: &DesignCurve) {
    let (first, last) = design.master_range();
    assert_eq!(first, table.master_first() as f64);
    assert_eq!(last, table.master_last() as f64);
    for p in table.points() {
        let s = design.eval(p.master as f64).s;
        assert!(
            (s - p.slave as f64).abs() <= 0.5 + 1e-9,
            "point ({}, {}) vs design {s}",
            p.master,
            p.slave
        );
    }
}

/// Central differences of each derivative, at masters at least `2h` from
/// any joint (where a derivative may step) and from the ends.
fn assert_derivatives_match(design: &DesignCurve, curve: AccelCurve) {
    let (first, last) = design.master_range();
    let joints: Vec<f64> = design.joints().collect();
    // S-type ramps have a corner of acceleration in their middle: skip
    // the midpoints of all pieces too.
    let mut corners = joints.clone();
    let mut lo = first;
    for &j in joints.iter().chain(std::iter::once(&last)) {
        corners.push(0.5 * (lo + j));
        lo = j;
    }
    let span = last - first;
    let h = 1e-4 * span.max(1.0) / 1000.0;
    let near = |m: f64| m - first < 2.0 * h || last - m < 2.0 * h;
    let scale_v = (design.slave_last() - design.slave_first()).abs().max(1.0) / span;
    let (mut checked, n) = (0, 997);
    for i in 1..n {
        let m = first + span * f64::from(i) / f64::from(n);
        if near(m) || corners.iter().any(|c| (m - c).abs() < 2.0 * h) {
            continue;
        }
        let (lo, k, hi) = (design.eval(m - h), design.eval(m), design.eval(m + h));
        let d = |a: f64, b: f64| (b - a) / (2.0 * h);
        let tol = |scale: f64| 1e-5 * scale;
        assert!(
            (k.v - d(lo.s, hi.s)).abs() < tol(scale_v.max(k.v.abs())),
            "{curve:?} v at {m}: {} vs {}",
            k.v,
            d(lo.s, hi.s)
        );
        let scale_a = scale_v / span * 100.0;
        assert!(
            (k.a - d(lo.v, hi.v)).abs() < tol(scale_a.max(k.a.abs())),
            "{curve:?} a at {m}: {} vs {}",
            k.a,
            d(lo.v, hi.v)
        );
        let scale_j = scale_a / span * 100.0;
        assert!(
            (k.j - d(lo.a, hi.a)).abs() < tol(scale_j.max(k.j.abs())) * 10.0,
            "{curve:?} j at {m}: {} vs {}",
            k.j,
            d(lo.a, hi.a)
        );
        checked += 1;
    }
    assert!(checked > n / 2, "only {checked} masters checked");
}

/// In the sync zone the designed velocity is the sync ratio exactly, with
/// no acceleration or jerk, at every whole master count of it.
fn assert_sync_exact(design: &DesignCurve, sync: (i64, i64), ratio: f64) {
    for m in sync.0..sync.1 {
        let k = design.eval(m as f64);
        assert_eq!(k.v, ratio, "v at {m}");
        assert_eq!((k.a, k.j), (0.0, 0.0), "a, j at {m}");
    }
    let mid = design.eval(0.5 * (sync.0 + sync.1) as f64);
    assert_eq!(mid.v, ratio);
}

#[test]
fn rotary_cut_designs() {
    let base = rotary_cut::Params {
        master_length: 3183,
        sync_length: 333,
        ..rotary_cut::Params::default()
    };
    // Speed-up, constant, slow-down, stop-and-dwell; and one capped at P5.
    let cuts = [
        (400, 50.0 / 3.0),
        (600, 50.0 / 3.0),
        (900, 50.0 / 3.0),
        (3183, 50.0 / 3.0),
        (300, 9.0),
    ];
    for (master_length, max_ratio) in cuts {
        for accel_curve in AccelCurve::ALL {
            for placement in CamPlacement::ALL {
                let p = rotary_cut::Params {
                    master_length,
                    max_ratio,
                    accel_curve,
                    placement,
                    ..base
                };
                let g = rotary_cut::generate(&p).unwrap();
                let what = format!("{master_length} {accel_curve:?} {placement:?}");
                assert_passes_through(&g.table, &g.design);
                assert_derivatives_match(&g.design, accel_curve);
                assert_sync_exact(&g.design, g.sync.unwrap(), g.sync_ratio);
                // The designed velocity never exceeds the cap the table keeps.
                for (_, k) in g.design.sample_pieces(64) {
                    assert!(
                        k.v <= max_ratio + 1e-9 && k.v >= -1e-12,
                        "{what}: v {}",
                        k.v
                    );
                }
            }
        }
    }
}

#[test]
fn flying_saw_designs() {
    let demo = flying_saw::Params {
        master_length: 1750,
        slave_length: 2000,
        sync_length: 667,
        sync_ratio: 3.0 * std::f64::consts::PI,
        max_ratio: 10.0,
        ..flying_saw::Params::default()
    };
    for accel_curve in AccelCurve::ALL {
        for placement in [
            CamPlacement::LeftCam,
            CamPlacement::MidCamAll,
            CamPlacement::RightCam,
        ] {
            let p = flying_saw::Params {
                accel_curve,
                placement,
                ..demo
            };
            let (forward, back) = flying_saw::generate_pair(&p).unwrap();
            for g in [&forward, &back] {
                assert_passes_through(&g.table, &g.design);
                assert_derivatives_match(&g.design, accel_curve);
                assert_sync_exact(&g.design, g.constant_zone, g.sync_ratio);
                // From rest to rest.
                assert_eq!(g.design.eval(0.0).v, 0.0);
                assert!(g.design.eval(1750.0).v.abs() < 1e-12);
            }
            // The return design is the forward one mirrored.
            for m in (0..=1750).step_by(25) {
                let (f, b) = (
                    forward.design.eval(f64::from(m)),
                    back.design.eval(f64::from(m)),
                );
                assert_eq!((b.s, b.v, b.a, b.j), (-f.s, -f.v, -f.a, -f.j));
            }
            // Forward then return: back to the start.
            let cycle = forward.design.followed_by(&back.design);
            assert_eq!(cycle.master_range(), (0.0, 3500.0));
            assert!(cycle.slave_last().abs() < 1e-9);
        }
    }
}

#[test]
fn s_curve_designs() {
    let cases = [
        s_curve::Params::default(),
        s_curve::Params {
            total_pulses: -10_000,
            ..s_curve::Params::default()
        },
        s_curve::Params {
            total_pulses: 1000, // triangular: the peak is lowered
            ..s_curve::Params::default()
        },
        s_curve::Params {
            accel_ms: 37,
            decel_ms: 250,
            max_speed_hz: 12_345,
            ..s_curve::Params::default()
        },
    ];
    for base in cases {
        for curve in AccelCurve::ALL {
            let p = s_curve::Params { curve, ..base };
            let g = s_curve::generate(&p).unwrap();
            assert_passes_through(&g.table, &g.design);
            assert_derivatives_match(&g.design, curve);
            assert_eq!(g.design.eval(0.0).v, 0.0);
            assert!(g.design.eval(g.duration as f64).v.abs() < 1e-9);
            // The designed top speed is at most P2 (in pulses per ms).
            let top = g
                .design
                .sample_pieces(32)
                .iter()
                .map(|(_, k)| k.v.abs())
                .fold(0.0, f64::max);
            assert!(top <= f64::from(p.max_speed_hz) / 1000.0 + 1e-9, "{top}");
        }
    }
    // The manual's case: the S-type ramp's acceleration peaks at twice the
    // mean, 2·50/100 pulses/ms², in the middle of the 100 ms ramp.
    let g = s_curve::generate(&s_curve::Params::default()).unwrap();
    assert!((g.design.eval(50.0).a - 1.0).abs() < 1e-9);
    assert!((g.design.eval(150.0).v - 50.0).abs() < 1e-9);
    assert!((g.design.eval(250.0).a + 1.0).abs() < 1e-9);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(200)))]

    #[test]
    fn every_rotary_cut_point_is_on_its_design(
        master_length in 200i64..20_000,
        slave_length in 100i64..5000,
        sync_fraction in 0.05f64..0.6,
        sync_ratio in 0.2f64..5.0,
        curve in prop::sample::select(AccelCurve::ALL.to_vec()),
        placement in prop::sample::select(CamPlacement::ALL.to_vec()),
        resolution in 20u16..=512,
    ) {
        let p = rotary_cut::Params {
            master_length,
            slave_length,
            sync_length: ((slave_length as f64 * sync_fraction) as i64).max(1),
            sync_ratio,
            max_ratio: 20.0 * sync_ratio,
            accel_curve: curve,
            placement,
            resolution,
        };
        if let Ok(g) = rotary_cut::generate(&p) {
            assert_passes_through(&g.table, &g.design);
            assert_sync_exact(&g.design, g.sync.unwrap(), g.sync_ratio);
        }
    }

    #[test]
    fn every_flying_saw_and_s_curve_point_is_on_its_design(
        master_length in 200i64..20_000,
        stroke in prop_oneof![100i64..5000, -5000i64..-100],
        sync_fraction in 0.05f64..0.6,
        sync_ratio in 0.2f64..5.0,
        curve in prop::sample::select(AccelCurve::ALL.to_vec()),
        placement in prop::sample::select(vec![CamPlacement::LeftCam, CamPlacement::MidCamAll, CamPlacement::RightCam]),
        resolution in 51u16..=512,
        speed in 1u32..150_000,
        accel_ms in 0u16..2000,
        decel_ms in 0u16..2000,
    ) {
        let p = flying_saw::Params {
            master_length,
            slave_length: stroke,
            sync_length: ((stroke.abs() as f64 * sync_fraction) as i64).max(1),
            sync_ratio,
            max_ratio: 20.0 * sync_ratio,
            accel_curve: curve,
            placement,
            resolution,
        };
        if let Ok(g) = flying_saw::generate(&p) {
            assert_passes_through(&g.table, &g.design);
            assert_sync_exact(&g.design, g.constant_zone, g.sync_ratio);
        }
        let p = s_curve::Params {
            total_pulses: stroke * 7,
            max_speed_hz: speed,
            accel_ms,
            decel_ms,
            resolution,
            curve,
        };
        if let Ok(g) = s_curve::generate(&p) {
            assert_passes_through(&g.table, &g.design);
        }
    }
}
