//! ECAMTBX K101 flying-saw generator: the manual's demo (forward and return
//! tables), the equal-area rule, placements and the parameter checks.
#![allow(clippy::unwrap_used)]

use std::f64::consts::PI;

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::flying_saw::{
    Generated, Params, Stroke, decode_cam_word, generate, generate_pair,
};
use ecam_core::{CamCurve, CamPoint, PointTable, TableError};

/// The manual's demo: 1750 master, 2000 slave, 667 sync at 3π, max 10.
fn demo() -> Params {
    Params {
        master_length: 1750,
        slave_length: 2000,
        sync_length: 667,
        sync_ratio: 3.0 * PI,
        max_ratio: 10.0,
        accel_curve: AccelCurve::Uniform,
        placement: CamPlacement::LeftCam,
        resolution: 100,
    }
}

fn sections(t: &PointTable) -> Vec<(i64, f64)> {
    t.points()
        .windows(2)
        .map(|w| {
            let dm = w[1].master - w[0].master;
            (dm, (w[1].slave - w[0].slave) as f64 / dm as f64)
        })
        .collect()
}

fn assert_velocity_continuous(t: &PointTable, scale: f64) {
    for w in sections(t).windows(2) {
        let ((dm0, v0), (dm1, v1)) = (w[0], w[1]);
        let tol = 1.0 / dm0 as f64 + 1.0 / dm1 as f64 + 0.2 * scale;
        assert!(
            (v1 - v0).abs() <= tol,
            "slope {v0} then {v1} (Δm {dm0}, {dm1})"
        );
    }
}

fn assert_saw_table(p: &Params, g: &Generated) {
    let t = &g.table;
    assert_eq!(t.points()[0], CamPoint::new(0, 0));
    assert_eq!(
        (t.master_last(), t.slave_last()),
        (p.master_length, p.slave_length)
    );
    assert!(t.points().len() <= usize::from(p.resolution));
    let s = sections(t);
    // Never beyond the cap, never backwards within a stroke.
    for &(_, v) in &s {
        assert!(v.abs() <= p.max_ratio);
        assert!(v * p.slave_length.signum() as f64 >= 0.0);
    }
    // Starts and ends at rest (first section within rounding of zero speed).
    let (dm0, v0) = s[0];
    let (dm1, v1) = *s.last().unwrap();
    assert!(v0.abs() <= 1.0 / dm0 as f64 + 0.2 * p.sync_ratio, "{v0}");
    assert!(v1.abs() <= 1.0 / dm1 as f64 + 0.2 * p.sync_ratio, "{v1}");
    assert_velocity_continuous(t, p.sync_ratio);
    // The constant zone is one section at the sync ratio.
    let (m0, m1) = g.constant_zone;
    let i = t.points().iter().position(|q| q.master == m0).unwrap();
    let (a, b) = (t.points()[i], t.points()[i + 1]);
    assert_eq!(
        (b.master, a.slave, b.slave),
        (m1, g.constant_slave.0, g.constant_slave.1)
    );
    let ratio = (b.slave - a.slave) as f64 / (m1 - m0) as f64;
    assert_eq!(ratio, g.sync_ratio);
    assert!((ratio.abs() - p.sync_ratio).abs() <= 0.5 / (m1 - m0) as f64 + 1e-12);
    assert!((b.slave - a.slave).abs() >= p.sync_length);
}

#[test]
fn manual_demo_forward_and_return() {
    let (fwd, back) = generate_pair(&demo()).unwrap();
    assert_saw_table(&demo(), &fwd);
    assert_saw_table(
        &Params {
            slave_length: -2000,
            ..demo()
        },
        &back,
    );
    assert_eq!((fwd.stroke, back.stroke), (Stroke::Forward, Stroke::Return));
    // Sync: 669 pulses over 71 counts = 9.4225 for 3π = 9.4248.
    let (m0, m1) = fwd.sync.unwrap();
    assert_eq!(m1 - m0, 71);
    assert_eq!(fwd.constant_slave.1 - fwd.constant_slave.0, 669);
    assert!((fwd.sync_ratio - 3.0 * PI).abs() < 0.003);
    assert_eq!(back.sync, None);
    assert!(fwd.peak_ratio <= 10.0);
    // Equal-area rule: forward travel equals return travel, the saw ends where it started.
    assert_eq!(fwd.table.stroke() + back.table.stroke(), 0);
    let ahead: i64 = fwd
        .table
        .points()
        .windows(2)
        .map(|w| (w[1].slave - w[0].slave).max(0))
        .sum();
    let behind: i64 = back
        .table
        .points()
        .windows(2)
        .map(|w| (w[0].slave - w[1].slave).max(0))
        .sum();
    assert_eq!((ahead, behind), (2000, 2000));
    // The return table is the forward one mirrored.
    for (f, b) in fwd.table.points().iter().zip(back.table.points()) {
        assert_eq!((f.master, f.slave), (b.master, -b.slave));
    }
    // Motion then rest: accelerating ramp ends at the sync start, about
    // 2·665/3π ≈ 141 counts; after the stop the saw waits at 2000.
    assert_eq!(m0, 142);
    let mut cursor = ecam_core::Cursor::new();
    assert_eq!(fwd.table.position(1000.0, &mut cursor), 2000.0);
}

#[test]
fn every_curve_and_placement() {
    for curve in AccelCurve::ALL {
        for placement in [
            CamPlacement::LeftCam,
            CamPlacement::MidCamAll,
            CamPlacement::RightCam,
        ] {
            for slave_length in [2000, -2000] {
                let p = Params {
                    accel_curve: curve,
                    placement,
                    slave_length,
                    ..demo()
                };
                let g = generate(&p).unwrap();
                assert_saw_table(&p, &g);
                let (m0, m1) = g.constant_zone;
                match placement {
                    CamPlacement::LeftCam => assert_eq!(m0, 142),
                    // Ends at rest exactly at the table end: ramp of ≈141.4 counts.
                    CamPlacement::RightCam => assert_eq!(m1, 1750 - 142),
                    _ => assert!((m0 + m1 - 1750).abs() <= 2, "{m0} {m1}"),
                }
            }
        }
    }
    let e = generate(&Params {
        placement: CamPlacement::MidCamBegin,
        ..demo()
    })
    .unwrap_err();
    assert_eq!(e.code(), 6781);
}

#[test]
fn return_flag_decodes() {
    assert_eq!(
        decode_cam_word(0x1000).unwrap(),
        (CamPlacement::LeftCam, Stroke::Return)
    );
    assert_eq!(
        decode_cam_word(0x0000).unwrap(),
        (CamPlacement::LeftCam, Stroke::Forward)
    );
    assert_eq!(
        decode_cam_word(0x1004).unwrap(),
        (CamPlacement::RightCam, Stroke::Return)
    );
}

#[test]
fn feasibility() {
    // Ramps ≈ 2·141 counts plus 71 in sync: 354 counts are needed.
    assert!(
        generate(&Params {
            master_length: 355,
            ..demo()
        })
        .is_ok()
    );
    let e = generate(&Params {
        master_length: 300,
        ..demo()
    })
    .unwrap_err();
    assert!(matches!(e, TableError::Infeasible { .. }));
    // Sync ratio above the cap.
    assert_eq!(
        generate(&Params {
            max_ratio: 9.0,
            ..demo()
        })
        .unwrap_err()
        .code(),
        6781
    );
}

#[test]
fn every_parameter_is_checked() {
    let d = demo();
    let bad = [
        Params {
            master_length: 0,
            ..d
        },
        Params {
            master_length: -1750,
            ..d
        },
        Params {
            slave_length: 0,
            ..d
        },
        Params {
            slave_length: i64::MIN,
            ..d
        },
        Params {
            sync_length: 0,
            ..d
        },
        Params {
            sync_length: 1999,
            ..d
        },
        Params {
            sync_ratio: f64::NAN,
            ..d
        },
        Params {
            sync_ratio: 0.0,
            ..d
        },
        Params {
            max_ratio: f64::INFINITY,
            ..d
        },
        Params {
            max_ratio: -10.0,
            ..d
        },
        Params { resolution: 0, ..d },
        Params {
            resolution: 600,
            ..d
        },
    ];
    for p in bad {
        let e = generate(&p).unwrap_err();
        assert_eq!(e.code(), 6781, "{p:?}: {e}");
    }
    // One range, the manual's 10–512 points: 9 is refused (6781), 10 makes
    // the five pieces (dwell, ramp, sync, ramp, dwell).
    let e = generate(&Params { resolution: 9, ..d }).unwrap_err();
    assert_eq!(e.code(), 6781, "{e}");
    assert!(e.to_string().contains("between 10 and 512"), "{e}");
    assert!(
        generate(&Params {
            resolution: 10,
            ..d
        })
        .is_ok()
    );
}
