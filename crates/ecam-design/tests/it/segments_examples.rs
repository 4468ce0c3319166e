//! The segment-cam examples of `examples/tables/` generate, with the
//! boundary values worked out by hand in their comments; the drive check of
//! the pick-and-place cam gives the figures `docs/design.md` derives by hand.

use ecam_core::CamCurve;
use ecam_core::drive_check::Limit;
use ecam_core::io::{AnyTable, TableFile};
use ecam_core::table::Continuity;
use ecam_design::Generated;

fn example(name: &str) -> String {
    let path = format!(
        "{}/../../examples/tables/{name}",
        env!("CARGO_MANIFEST_DIR")
    );
    std::fs::read_to_string(&path).unwrap()
}

fn generate(name: &str) -> Generated {
    let values =
        ecam_design::read_toml(ecam_design::find("segments").unwrap(), &example(name)).unwrap();
    ecam_design::generate(ecam_design::find("segments").unwrap(), values).unwrap()
}

fn near(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol
}

#[test]
fn the_rotary_knife_synchronises_and_is_continuous() {
    let g = generate("segments-rotary-knife.toml");
    let cam = g.segments.as_ref().unwrap();
    assert_eq!(g.table.points().len(), 100);
    assert_eq!((g.table.master_last(), g.table.slave_last()), (4000, 1000));
    assert_eq!(g.sync, Some((0, 500)));
    let p = cam.points();
    // Filled in: the sync speed at 0, 500 and the seam; the chords' mean at 2250.
    assert_eq!(p[0].velocity, Some(0.4));
    assert_eq!(p[1].velocity, Some(0.4));
    assert!(near(p[2].velocity.unwrap(), 0.228_571_428_571, 1e-9));
    assert_eq!(p[3].velocity, Some(0.4));
    assert!(p.iter().all(|q| q.acceleration == Some(0.0)));
    let report = cam.continuity();
    assert_eq!(report.cam, Continuity::C2);
    assert_eq!(report.seam, Continuity::C2);
    // The knife never turns back: its slowest point, mid-way through the
    // slow-down, is still forward.
    let lowest = cam
        .sample_segments(500)
        .iter()
        .map(|(_, k)| k.v)
        .fold(f64::INFINITY, f64::min);
    assert!(lowest > 0.1, "{lowest}");
}

#[test]
fn the_flying_saw_returns_and_waits() {
    let g = generate("segments-flying-saw.toml");
    let cam = g.segments.as_ref().unwrap();
    assert_eq!(g.table.points().len(), 200);
    assert_eq!(g.sync, Some((1000, 2000)));
    let v: Vec<f64> = cam.points().iter().map(|p| p.velocity.unwrap()).collect();
    assert_eq!(v, [0.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
    let peaks = cam.peaks();
    // Rest to velocity 1 over 1000 counts covering 500: the poly-5 is
    // 0.5·u⁴(2 − u)... its velocity peaks at the end (1), its acceleration
    // at u = 1/2: 1.5/1000 pulses/count².
    assert!(near(peaks[0].peak_velocity, 1.0, 1e-12));
    assert!(near(peaks[0].peak_acceleration, 0.0015, 1e-12));
    assert_eq!(cam.continuity().cam, Continuity::C2);
}

#[test]
fn the_pick_and_place_is_c2_as_written() {
    let g = generate("segments-pick-and-place.toml");
    let cam = g.segments.as_ref().unwrap();
    assert_eq!(g.table.points().len(), 120);
    assert_eq!(g.sync, None);
    let peaks = cam.peaks();
    // Cv·h/β of the modified sine and of the poly-5 (3-4-5) return.
    assert!(near(
        peaks[1].peak_velocity,
        1.759_603_385_953_770_5 * 5000.0 / 1200.0,
        1e-9
    ));
    assert!(near(peaks[3].peak_velocity, 1.875 * 5000.0 / 1200.0, 1e-9));
    assert!(near(peaks[3].ca.unwrap(), 10.0 / 3f64.sqrt(), 1e-9));
    assert!(
        cam.continuity()
            .joints
            .iter()
            .all(|j| j.class == Continuity::C2)
    );
}

#[test]
fn the_pick_and_place_drive_check_is_the_hand_calculation() {
    let g = generate("segments-pick-and-place.toml");
    let table = AnyTable::Points(TableFile {
        table: g.table.clone(),
        sync: None,
        generator: None,
        kinematics: None,
        segments: g.segments.clone().map(Box::new),
    });
    let r = ecam_design::check_table(&table, &example("drive-pick-and-place.toml"), Some(3600.0))
        .unwrap();
    // docs/design.md, "The drive check by hand".
    let j = 0.00012 + 0.0045 / 9.0;
    let k = j * 2.0 * std::f64::consts::PI / 2000.0; // N·m per pulse/s²
    let a_peak = 10.0 / 3f64.sqrt() * 5000.0 / 1200.0_f64.powi(2);
    let at = r.at_speed.unwrap();
    assert!(near(r.inertia_at_motor, j, 1e-15));
    assert!(near(at.motor_speed_rpm, 843.75, 1e-6));
    assert!(near(
        at.peak_torque,
        k * a_peak * 3600.0 * 3600.0 + 0.1,
        1e-6
    ));
    // ∫a² over the rise: h²/β³·Ca²/2 (modified sine); over the return:
    // h²/β³·120/7 (poly-5); friction 0.1 N·m while moving (2400 counts).
    let ca_sine = 5.527_957_070_544_09_f64;
    let a2 = 5000.0_f64.powi(2) / 1200.0_f64.powi(3) * (ca_sine * ca_sine / 2.0 + 120.0 / 7.0);
    let rms = ((k * 3600.0 * 3600.0).powi(2) * a2 + 0.01 * 2400.0) / 3600.0;
    assert!(
        near(at.rms_torque, rms.sqrt(), 1e-5),
        "{} vs {}",
        at.rms_torque,
        rms.sqrt()
    );
    assert!(at.within_limits);
    // The highest speed each limit allows.
    let by = |l: Limit| {
        r.limits
            .iter()
            .find(|s| s.limit == l)
            .unwrap()
            .max_master_hz
    };
    assert!(near(by(Limit::Speed), 12800.0, 1e-6));
    // Sampled 2000 times per segment: within a few parts per million.
    let peak_hz = (1.2 / (k * a_peak)).sqrt();
    assert!(
        near(by(Limit::PeakTorque), peak_hz, 1e-5 * peak_hz),
        "{} vs {peak_hz}",
        by(Limit::PeakTorque)
    );
    let rms_hz = ((0.45f64.powi(2) * 3600.0 - 24.0) / (k * k * a2)).powf(0.25);
    assert!(
        near(by(Limit::RmsTorque), rms_hz, 1e-5 * rms_hz),
        "{} vs {rms_hz}",
        by(Limit::RmsTorque)
    );
    assert_eq!(r.binding, Limit::RmsTorque);
    assert!(
        near(r.max_cycles_per_min, rms_hz * 60.0 / 3600.0, 1e-5 * rms_hz),
        "{} vs {}",
        r.max_cycles_per_min,
        rms_hz * 60.0 / 3600.0
    );
}

#[test]
fn a_velocity_step_leaves_no_safe_speed() {
    let values = ecam_design::read_toml(
        ecam_design::find("segments").unwrap(),
        "[[segment]]\nlaw = \"cycloid\"\nmaster = 1000\nslave = 500\n\
         [[segment]]\nlaw = \"constant-velocity\"\nmaster = 2000\nslave = 1500\n",
    )
    .unwrap();
    let g = ecam_design::generate(ecam_design::find("segments").unwrap(), values).unwrap();
    let motion = ecam_design::motion_of_cam(g.segments.as_ref().unwrap());
    assert_eq!(motion.velocity_steps(), [1000.0, 1000.0].get(..1).unwrap());
    let drive = ecam_design::read_drive(&example("drive-pick-and-place.toml")).unwrap();
    let r = ecam_core::drive_check::check(&motion, &drive, Some(100.0)).unwrap();
    assert_eq!(r.max_master_hz, 0.0);
    assert!(!r.at_speed.unwrap().within_limits);
}

#[test]
fn bad_drive_files_name_the_key() {
    let e = ecam_design::read_drive("[mechanics]\nunits_per_motor_rev = 0\nload_inertia = 1\nmotor_inertia = 1\n[limits]\nmax_speed = 1\npeak_torque = 1\nrms_torque = 1\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("units_per_motor_rev"), "{e}");
    let e = ecam_design::read_drive("[mechanics]\nunits_per_motor_rv = 1\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("units_per_motor_rv"), "{e}");
}

#[test]
fn the_published_double_dwell_case() {
    // docs/design.md, "A published case": h = 25 mm over β = 90° at
    // ω = 2π rad/s with the 3-4-5 law peaks at 1.875·h·ω/β = 187.5 mm/s,
    // 5.7735·h·ω²/β² = 2309.4 mm/s² and 60·h·ω³/β³ = 96 000 mm/s³.
    let g = generate("segments-double-dwell.toml");
    let cam = g.segments.as_ref().unwrap();
    let rise = cam.peaks()[1];
    let f = 3600.0; // counts/s: one turn a second
    let mm = 0.001; // per pulse
    assert!(near(rise.peak_velocity * f * mm, 187.5, 1e-9));
    assert!(near(
        rise.peak_acceleration * f * f * mm,
        2_309.401_076_758_503,
        1e-6
    ));
    assert!(near(rise.peak_jerk * f * f * f * mm, 96_000.0, 1e-6));
    let c = cam.polynomial(1).unwrap().coefficients;
    for (got, want) in c
        .iter()
        .zip([0.0, 0.0, 0.0, 250_000.0, -375_000.0, 150_000.0])
    {
        assert!(near(*got, want, 1e-6), "{c:?}");
    }
    assert_eq!(cam.continuity().cam, Continuity::C2);
}
