//! ECAMTBX K0/K1 S-curve generator: the manual's calculation case and the
//! parameter checks.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::AccelCurve;
use ecam_core::generator::s_curve::{Params, generate};
use ecam_core::{CamCurve, CamPoint, Cursor, PointTable};

fn slopes(t: &PointTable) -> Vec<f64> {
    t.points()
        .windows(2)
        .map(|w| (w[1].slave - w[0].slave) as f64 / (w[1].master - w[0].master) as f64)
        .collect()
}

#[test]
fn manual_calculation_case() {
    // 10000 pulses, 50 kHz, 100 ms / 100 ms, resolution 200.
    let g = generate(&Params::default()).unwrap();
    let t = &g.table;
    assert_eq!(t.points()[0], CamPoint::new(0, 0));
    assert_eq!((t.master_last(), t.slave_last()), (300, 10000));
    assert!(t.points().len() <= 200);
    assert_eq!(g.sync, None);
    assert_eq!(g.duration, 300);
    assert_eq!(g.last_section_master, 100); // P8
    assert_eq!(g.last_section_slave, 2500); // P9
    assert_eq!(g.uniform_time, 100); // P10
    assert_eq!(g.max_speed_hz, 50000); // P11
    let mut c = Cursor::new();
    // Phase boundaries: 2500 pulses up, 5000 cruising, 2500 down; symmetric.
    assert_eq!(t.position(100.0, &mut c), 2500.0);
    assert_eq!(t.position(200.0, &mut c), 7500.0);
    assert_eq!(t.position(150.0, &mut c), 5000.0);
    // Cruise at exactly 50 pulses per ms.
    let cruise = t.eval(150.0, &mut c).v;
    assert_eq!(cruise, 50.0);
    // Starts and ends at rest, never faster than 50 kHz.
    let s = slopes(t);
    assert!(
        s[0] <= 1.0 && *s.last().unwrap() <= 1.0,
        "{} {}",
        s[0],
        s.last().unwrap()
    );
    assert!(s.iter().all(|&v| (0.0..=50.0).contains(&v)));
}

#[test]
fn s_type_ramp_has_continuous_acceleration() {
    // The S ramp's velocity grows slowly at first (acceleration starts at 0);
    // the uniform (trapezoid) ramp's grows at once.
    let s = generate(&Params::default()).unwrap();
    let lin = generate(&Params {
        curve: AccelCurve::Uniform,
        ..Params::default()
    })
    .unwrap();
    let mut c = Cursor::new();
    let early_s = s.table.position(10.0, &mut c);
    let early_lin = lin.table.position(10.0, &mut c);
    // Trapezoid: 0.5·0.5·10² = 25; S-type: (2/3)·(0.1)³·100·50 ≈ 3.3.
    assert!((early_lin - 25.0).abs() <= 1.0, "{early_lin}");
    assert!(early_s <= 4.0, "{early_s}");
    // Both reach the same phases.
    assert_eq!(lin.uniform_time, 100);
    assert_eq!(lin.table.slave_last(), 10000);
}

#[test]
fn short_move_becomes_triangular() {
    let g = generate(&Params {
        total_pulses: 1000,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(g.uniform_time, 0);
    // Same rates: peak √(2·1000·50/200) ≈ 22.4 pulses/ms, ramps 44.7 ms each.
    assert!(
        g.max_speed_hz < 50_000 && g.max_speed_hz > 21_000,
        "{}",
        g.max_speed_hz
    );
    assert_eq!(g.table.slave_last(), 1000);
    assert_eq!(g.table.master_last(), 90); // ⌈89.4⌉
    assert_eq!(g.last_section_master, 45);
    assert_eq!(g.last_section_slave, 500);
}

#[test]
fn zero_ramp_times_give_a_straight_move() {
    let g = generate(&Params {
        accel_ms: 0,
        decel_ms: 0,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(
        g.table.points(),
        &[CamPoint::new(0, 0), CamPoint::new(200, 10000)]
    );
    assert_eq!(
        (g.uniform_time, g.max_speed_hz, g.last_section_master),
        (200, 50000, 0)
    );
}

#[test]
fn duration_rounds_up_and_speed_stays_under_the_limit() {
    // 10001 pulses: 300.02 ms, stretched to 301 whole counts.
    let g = generate(&Params {
        total_pulses: 10_001,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(g.table.master_last(), 301);
    assert_eq!(g.table.slave_last(), 10_001);
    assert!(g.max_speed_hz <= 50_000);
}

#[test]
fn very_short_move_has_fewer_points_than_the_resolution() {
    let g = generate(&Params {
        total_pulses: 10,
        max_speed_hz: 150_000,
        accel_ms: 0,
        decel_ms: 0,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(
        g.table.points(),
        &[CamPoint::new(0, 0), CamPoint::new(1, 10)]
    );
    assert_eq!(g.max_speed_hz, 10_000); // whole master counts cannot go faster
}

#[test]
fn negative_total_moves_backwards() {
    let fwd = generate(&Params::default()).unwrap();
    let back = generate(&Params {
        total_pulses: -10_000,
        ..Params::default()
    })
    .unwrap();
    assert_eq!(back.table.slave_last(), -10_000);
    for (a, b) in fwd.table.points().iter().zip(back.table.points()) {
        assert_eq!((a.master, a.slave), (b.master, -b.slave));
    }
}

#[test]
fn every_parameter_is_checked() {
    let d = Params::default();
    let bad = [
        Params {
            total_pulses: 0,
            ..d
        },
        Params {
            total_pulses: i64::from(i32::MAX) + 1,
            ..d
        },
        Params {
            total_pulses: i64::MIN,
            ..d
        },
        Params {
            max_speed_hz: 0,
            ..d
        },
        Params {
            max_speed_hz: 150_001,
            ..d
        },
        Params {
            accel_ms: 32_768,
            ..d
        },
        Params {
            decel_ms: u16::MAX,
            ..d
        },
        Params {
            resolution: 50,
            ..d
        },
        Params {
            resolution: 513,
            ..d
        },
    ];
    for p in bad {
        let e = generate(&p).unwrap_err();
        assert_eq!(e.code(), 6781, "{p:?}: {e}");
    }
    let edges = [
        Params {
            max_speed_hz: 150_000,
            ..d
        },
        Params {
            accel_ms: 32_767,
            decel_ms: 32_767,
            ..d
        },
        Params {
            resolution: 51,
            ..d
        },
        Params {
            resolution: 512,
            ..d
        },
        Params {
            total_pulses: i64::from(i32::MAX),
            ..d
        },
    ];
    for p in edges {
        let g = generate(&p).unwrap();
        assert_eq!(g.table.slave_last(), p.total_pulses);
        assert!(g.table.points().len() <= usize::from(p.resolution));
    }
}
