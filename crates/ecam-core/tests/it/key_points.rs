//! ECAMTBX K2 (document 000's appendix): the application case and the
//! parameter checks.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::key_points::{self, CurveType, KeyPoint, Params};
use ecam_core::table::{Continuity, Summary};
use ecam_core::{CamCurve, CamPoint, Cursor, TableError};

#[test]
fn application_case_total_resolution_100() {
    let params = Params::default();
    assert_eq!(params.total_resolution, 100);
    let g = key_points::generate(&params).unwrap();
    assert_eq!(g.sync, None);
    assert_eq!(g.resolutions, vec![20, 20, 20, 20, 19]);
    let points = g.table.points();
    assert_eq!(points.len(), 100, "total resolution = points in the table");
    assert_eq!(points[0], CamPoint::new(0, 0));
    // Every key point is in the table exactly.
    for (index, key) in [
        (20, (600, 0)),
        (40, (1500, 2000)),
        (60, (1700, 2000)),
        (80, (1900, 600)),
        (99, (2000, 0)),
    ] {
        assert_eq!(
            points[index],
            CamPoint::new(key.0, key.1),
            "key point at {index}"
        );
    }
    // 0–600: the slave stays at 0; 1500–1700: it stays at 2000.
    assert!(points[..=20].iter().all(|p| p.slave == 0));
    assert!(points[40..=60].iter().all(|p| p.slave == 2000));
    // Even spacing inside a segment: 600/20 = 30, 900/20 = 45 counts.
    assert_eq!(points[1].master, 30);
    assert_eq!(points[21].master, 645);
    // Constant acceleration rise 600→1500 by 2000: half-way (1050) is 1000,
    // a quarter of the way (825) is 2·(1/4)²·2000 = 250.
    assert_eq!(points[30], CamPoint::new(1050, 1000));
    assert_eq!(points[25], CamPoint::new(825, 250));
    // Rises rise and returns return.
    assert!(points[20..=40].windows(2).all(|w| w[1].slave >= w[0].slave));
    assert!(points[60..].windows(2).all(|w| w[1].slave <= w[0].slave));
}

#[test]
fn profile_is_the_exact_curve_behind_the_table() {
    let g = key_points::generate(&Params::default()).unwrap();
    let mut c = Cursor::new();
    for p in g.table.points() {
        let exact = g.profile.position(p.master as f64, &mut c);
        assert!((exact - p.slave as f64).abs() <= 0.5, "{p:?} vs {exact}");
    }
    // Constant acceleration joins the dwells with continuous velocity only.
    assert_eq!(Summary::of(&g.profile).continuity, Continuity::C1);
}

#[test]
fn curve_types_and_initial_offset() {
    let params = Params {
        total_resolution: 50,
        key_points: vec![
            KeyPoint::new(1000, 500, CurveType::Cycloid),
            KeyPoint::new(2000, 500, CurveType::ConstantSpeed),
            KeyPoint {
                resolution: 10,
                ..KeyPoint::new(3000, 0, CurveType::SType)
            },
        ],
        initial_slave: -100,
    };
    let g = key_points::generate(&params).unwrap();
    assert_eq!(g.resolutions, vec![20, 19, 10]);
    assert_eq!(g.table.slave_first(), -100);
    assert_eq!(g.table.slave_last(), -100);
    assert_eq!(g.table.points()[20], CamPoint::new(1000, 400));
    assert_eq!(g.table.points().len(), 50);
    for code in 0..4 {
        assert_eq!(CurveType::from_code(code).unwrap().code(), code as u16);
    }
    assert_eq!(CurveType::from_code(4), None);
}

#[test]
fn parameter_checks_use_the_plc_codes() {
    let with = |edit: &dyn Fn(&mut Params)| {
        let mut p = Params::default();
        edit(&mut p);
        key_points::generate(&p).unwrap_err()
    };
    // Master not increasing: key point 3 (1-based) goes back.
    let e = with(&|p| p.key_points[2].master = 1500);
    assert_eq!(e, TableError::MasterNotIncreasing { section: 3 });
    assert_eq!(e.code(), 6782);
    // The first key point must lie after master 0.
    assert_eq!(
        with(&|p| p.key_points[0].master = 0),
        TableError::MasterNotIncreasing { section: 1 }
    );
    // Key point count 1..=10.
    assert_eq!(with(&|p| p.key_points.clear()).code(), 6781);
    assert_eq!(
        with(&|p| p.key_points = (1..=11)
            .map(|i| KeyPoint::new(i * 100, 0, CurveType::Cycloid))
            .collect())
        .code(),
        6781
    );
    // Resolutions.
    assert_eq!(with(&|p| p.total_resolution = 9).code(), 6781);
    assert_eq!(with(&|p| p.total_resolution = 513).code(), 6783);
    assert_eq!(with(&|p| p.key_points[0].resolution = 513).code(), 6781);
    assert_eq!(with(&|p| p.key_points[0].resolution = 99).code(), 6781);
    // Values beyond the 32-bit registers.
    assert_eq!(
        with(&|p| p.initial_slave = i64::from(i32::MAX)),
        TableError::ValueOutOfRange { section: 2 }
    );
    assert_eq!(
        with(&|p| p.key_points[4].master = 1 << 40),
        TableError::ValueOutOfRange { section: 5 }
    );
    assert_eq!(
        with(&|p| p.key_points[4].slave = i64::MIN),
        TableError::ValueOutOfRange { section: 5 }
    );
}

#[test]
fn ten_key_points_at_full_resolution() {
    let params = Params {
        total_resolution: 512,
        key_points: (1..=10)
            .map(|i| {
                KeyPoint::new(
                    i * 1000,
                    if i % 2 == 0 { 0 } else { 5000 },
                    CurveType::SType,
                )
            })
            .collect(),
        initial_slave: 0,
    };
    let g = key_points::generate(&params).unwrap();
    assert_eq!(g.table.points().len(), 512);
    assert_eq!(
        ecam_core::register_image::to_words(&g.table).unwrap().len(),
        40 + 4 * 512
    );
}
