//! ECAMTBX K100 rotary-cut generator: the manual's demo, the four cut-length
//! regimes, every placement and curve, and the parameter checks.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::rotary_cut::{CutRegime, Generated, Params, generate};
use ecam_core::{CamCurve, CamPoint, PointTable, TableError};

/// The manual's demo: 3183 / 1000 / 333 / 5:3 / max 50:3, leftCAM.
fn demo() -> Params {
    Params {
        master_length: 3183,
        slave_length: 1000,
        sync_length: 333,
        sync_ratio: 5.0 / 3.0,
        max_ratio: 50.0 / 3.0,
        accel_curve: AccelCurve::UniformAcceleration,
        placement: CamPlacement::LeftCam,
        resolution: 100,
    }
}

/// (Δmaster, slope) of every section.
fn sections(t: &PointTable) -> Vec<(i64, f64)> {
    t.points()
        .windows(2)
        .map(|w| {
            let dm = w[1].master - w[0].master;
            (dm, (w[1].slave - w[0].slave) as f64 / dm as f64)
        })
        .collect()
}

/// Velocity continuity on a point table: neighbouring sections may differ by
/// what whole-pulse rounding (≤ 1 pulse per section) and a smooth ramp over
/// the two sections explain, never by a jump of the order of the peak.
fn assert_velocity_continuous(t: &PointTable, seam: bool, scale: f64) {
    let s = sections(t);
    let mut pairs: Vec<((i64, f64), (i64, f64))> = s.windows(2).map(|w| (w[0], w[1])).collect();
    if seam {
        pairs.push((*s.last().unwrap(), s[0]));
    }
    for ((dm0, v0), (dm1, v1)) in pairs {
        let tol = 1.0 / dm0 as f64 + 1.0 / dm1 as f64 + 0.2 * scale;
        assert!(
            (v1 - v0).abs() <= tol,
            "slope {v0} then {v1} (Δm {dm0}, {dm1}), tolerance {tol}"
        );
    }
}

/// Checks shared by every rotary table.
fn assert_rotary_table(p: &Params, g: &Generated) {
    let t = &g.table;
    assert_eq!(t.points()[0], CamPoint::new(0, 0));
    assert_eq!(
        (t.master_last(), t.slave_last()),
        (p.master_length, p.slave_length)
    );
    assert!(t.points().len() <= usize::from(p.resolution));
    // The knife never turns backwards and never exceeds the max ratio.
    for (_, v) in sections(t) {
        assert!(v >= 0.0 && v <= p.max_ratio, "{v}");
    }
    assert!(g.peak_ratio <= p.max_ratio);
    // The sync zone is exactly one section, at the requested ratio.
    let (m0, m1) = g.sync.unwrap();
    let i = t.points().iter().position(|q| q.master == m0).unwrap();
    let (a, b) = (t.points()[i], t.points()[i + 1]);
    assert_eq!(
        (b.master, a.slave, b.slave),
        (m1, g.sync_slave.0, g.sync_slave.1)
    );
    let ratio = (b.slave - a.slave) as f64 / (b.master - a.master) as f64;
    assert_eq!(ratio, g.sync_ratio);
    assert!((ratio - p.sync_ratio).abs() <= 0.5 / (m1 - m0) as f64 + 1e-12);
    assert!(b.slave - a.slave >= p.sync_length);
}

#[test]
#[should_panic(expected = "slope")]
fn continuity_check_catches_a_velocity_jump() {
    // Sync at 5/3, then an abrupt stop: what a generator must never produce.
    let jump = PointTable::from_pairs(&[(0, 0), (201, 335), (400, 335), (3183, 1000)]).unwrap();
    assert_velocity_continuous(&jump, false, 5.0 / 3.0);
}

#[test]
fn manual_demo_both_curve_codes() {
    // The demo writes "low word = 0: uniform acceleration" while the register
    // table calls code 0 "uniform curve" and code 1 "uniform acceleration";
    // every code must give the same synchronisation and stroke.
    for curve in AccelCurve::ALL {
        let p = Params {
            accel_curve: curve,
            ..demo()
        };
        let g = generate(&p).unwrap();
        assert_rotary_table(&p, &g);
        assert_eq!(g.regime, CutRegime::StopAndDwell);
        assert_eq!(g.sync, Some((0, 201)));
        assert_eq!(g.sync_slave, (0, 335));
        // 335/201 is 5/3 exactly.
        assert_eq!(335 * 3, 201 * 5);
        assert!(!g.capped_at_max);
        // The knife stops between cuts: at least one flat section.
        assert!(sections(&g.table).iter().any(|&(_, v)| v == 0.0));
        assert_velocity_continuous(&g.table, true, 5.0 / 3.0);
    }
}

#[test]
fn four_cut_length_regimes() {
    // Knife 1000 pulses, sync 333 → 335 pulses over 201 counts; the free
    // motion covers 665 pulses over P1 − 201 counts.
    let cases = [
        (400, CutRegime::SpeedUp),       // cut shorter than the circumference
        (600, CutRegime::Constant),      // 600·5/3 = 1000: equal
        (900, CutRegime::SlowDown),      // between one and two circumferences
        (1300, CutRegime::StopAndDwell), // over 2·1000 − 333 slave pulses of cut
        (3183, CutRegime::StopAndDwell),
    ];
    for (master_length, regime) in cases {
        for curve in AccelCurve::ALL {
            let p = Params {
                master_length,
                accel_curve: curve,
                resolution: 60,
                ..demo()
            };
            let g = generate(&p).unwrap();
            assert_eq!(g.regime, regime, "P1 = {master_length}");
            assert_rotary_table(&p, &g);
            assert_velocity_continuous(&g.table, true, g.peak_ratio);
            let flat = sections(&g.table).iter().any(|&(_, v)| v == 0.0);
            assert_eq!(flat, regime == CutRegime::StopAndDwell);
            match regime {
                CutRegime::SpeedUp => assert!(g.peak_ratio > 3.0),
                CutRegime::Constant => assert_eq!(g.table.points().len(), 3),
                _ => assert!(g.peak_ratio < 5.0 / 3.0 + 0.2),
            }
        }
    }
}

#[test]
fn regime_boundary_between_slow_down_and_dwell() {
    // Slow-down reaches exactly zero when the free mean ratio is half the sync
    // ratio: 665/(P1 − 201) = 5/6 → P1 = 999.
    let at = |master_length| {
        generate(&Params {
            master_length,
            ..demo()
        })
        .unwrap()
        .regime
    };
    assert_eq!(at(999), CutRegime::SlowDown);
    assert_eq!(at(1000), CutRegime::StopAndDwell);
}

#[test]
fn every_placement_keeps_stroke_sync_and_continuity() {
    for placement in CamPlacement::ALL {
        for master_length in [400, 900, 3183] {
            let p = Params {
                master_length,
                placement,
                resolution: 80,
                ..demo()
            };
            let g = generate(&p).unwrap();
            assert_rotary_table(&p, &g);
            let repeating = matches!(
                placement,
                CamPlacement::LeftCam | CamPlacement::RightCam | CamPlacement::MidCamAll
            );
            assert_velocity_continuous(&g.table, repeating, g.peak_ratio);
            let (m0, m1) = g.sync.unwrap();
            let s = sections(&g.table);
            match placement {
                CamPlacement::LeftCam => assert_eq!(m0, 0),
                CamPlacement::RightCam => assert_eq!(m1, master_length),
                CamPlacement::MidCamAll => assert_eq!(m0, (master_length - 201) / 2),
                // Starting from rest: the first section is (nearly) still.
                CamPlacement::MidCamBegin => {
                    assert_eq!(m0, (master_length - 201) / 2);
                    assert!(
                        s[0].1 <= 1.0 / s[0].0 as f64 + 0.2 * g.peak_ratio,
                        "{:?}",
                        s[0]
                    );
                }
                CamPlacement::MidCamEnd => {
                    assert_eq!(m0, (master_length - 201) / 2);
                    let last = s.last().unwrap();
                    assert!(
                        last.1 <= 1.0 / last.0 as f64 + 0.2 * g.peak_ratio,
                        "{last:?}"
                    );
                }
            }
        }
    }
}

#[test]
fn mid_tables_chain_into_each_other() {
    // begin → all → end: the slave is continuous in position (each table
    // covers P2) and the velocity at each joint matches.
    let tables: Vec<Generated> = [
        CamPlacement::MidCamBegin,
        CamPlacement::MidCamAll,
        CamPlacement::MidCamEnd,
    ]
    .into_iter()
    .map(|placement| {
        generate(&Params {
            master_length: 900,
            placement,
            ..demo()
        })
        .unwrap()
    })
    .collect();
    for w in tables.windows(2) {
        let out = sections(&w[0].table).last().copied().unwrap();
        let inn = sections(&w[1].table)[0];
        assert!(
            (out.1 - inn.1).abs() <= 1.0 / out.0 as f64 + 1.0 / inn.0 as f64 + 0.1,
            "{out:?} {inn:?}"
        );
    }
}

#[test]
fn right_cam_is_left_cam_rotated() {
    let left = generate(&Params {
        master_length: 900,
        resolution: 512,
        ..demo()
    })
    .unwrap();
    let right = generate(&Params {
        master_length: 900,
        resolution: 512,
        placement: CamPlacement::RightCam,
        ..demo()
    })
    .unwrap();
    let mut c = ecam_core::Cursor::new();
    let mut d = ecam_core::Cursor::new();
    for m in 0..=699 {
        let l = left.table.position(f64::from(m + 201), &mut c) - 335.0;
        let r = right.table.position(f64::from(m), &mut d);
        assert!((l - r).abs() <= 1.0, "at {m}: {l} vs {r}");
    }
}

#[test]
fn max_ratio_caps_the_speed_up_or_refuses() {
    // P1 = 300: the free 99 counts must carry 665 pulses (mean 6.7);
    // a triangle would peak at 11.8.
    let p = Params {
        master_length: 300,
        max_ratio: 9.0,
        ..demo()
    };
    let g = generate(&p).unwrap();
    assert!(g.capped_at_max && g.peak_ratio <= 9.0);
    assert_rotary_table(&p, &g);
    let free = generate(&Params {
        max_ratio: 20.0,
        ..p
    })
    .unwrap();
    assert!(!free.capped_at_max && free.peak_ratio > 11.0);
    let e = generate(&Params {
        max_ratio: 6.0,
        ..p
    })
    .unwrap_err();
    assert!(matches!(e, TableError::Infeasible { .. }));
    assert_eq!(e.code(), 6781);
    // A sync ratio above the cap is refused outright.
    assert_eq!(
        generate(&Params {
            max_ratio: 1.5,
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
            master_length: -5,
            ..d
        },
        Params {
            master_length: i64::from(i32::MAX) + 1,
            ..d
        },
        Params {
            slave_length: 0,
            ..d
        },
        Params {
            slave_length: -1000,
            ..d
        },
        Params {
            sync_length: 0,
            ..d
        },
        Params {
            sync_length: 1000,
            ..d
        },
        Params {
            sync_ratio: f64::NAN,
            ..d
        },
        Params {
            sync_ratio: f64::INFINITY,
            ..d
        },
        Params {
            sync_ratio: 0.0,
            ..d
        },
        Params {
            sync_ratio: -1.0,
            ..d
        },
        Params {
            max_ratio: f64::NAN,
            ..d
        },
        Params {
            max_ratio: f64::NEG_INFINITY,
            ..d
        },
        Params { resolution: 1, ..d },
        Params {
            resolution: 513,
            ..d
        },
        // Sync zone longer than the cut.
        Params {
            master_length: 150,
            ..d
        },
    ];
    for p in bad {
        let e = generate(&p).unwrap_err();
        assert_eq!(e.code(), 6781, "{p:?}: {e}");
    }
    // One range, the manual's 10–512 points: 5 points would make the four
    // pieces, but 9 is below the range (6781) and 10 is the fewest.
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
