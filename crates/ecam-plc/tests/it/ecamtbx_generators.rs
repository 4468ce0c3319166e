//! ECAMTBX parameter blocks of the manual's demos, read back against the
//! generators in ecam-core, and the error results.
#![allow(clippy::unwrap_used)]

use ecam_core::generator::AccelCurve;
use ecam_core::generator::CamPlacement;
use ecam_core::generator::{flying_saw, key_points, rotary_cut, s_curve};
use ecam_core::{CamCurve, CamPoint};
use ecam_plc::Devices;
use ecam_plc::ecamtbx;

const P: u16 = 100; // parameter block S0
const T: u16 = 2000; // table block D1
const R: u16 = 500; // result D2

fn table(dev: &Devices) -> Vec<CamPoint> {
    let n = dev.word(T + 38).unwrap();
    assert_eq!(dev.word(T + 39).unwrap(), 40);
    (0..n as u16)
        .map(|i| {
            let at = T + 40 + 4 * i;
            CamPoint::new(
                i64::from(dev.dword(at).unwrap()),
                i64::from(dev.dword(at + 2).unwrap()),
            )
        })
        .collect()
}

fn cut_block(dev: &mut Devices, p: [i32; 3], ratio: f32, max: f32, curve: i16, cam: i16, res: i16) {
    dev.set_dword(P, p[0]).unwrap();
    dev.set_dword(P + 2, p[1]).unwrap();
    dev.set_dword(P + 4, p[2]).unwrap();
    dev.set_float(P + 6, ratio).unwrap();
    dev.set_float(P + 8, max).unwrap();
    dev.set_word(P + 10, curve).unwrap();
    dev.set_word(P + 11, cam).unwrap();
    dev.set_word(P + 12, res).unwrap();
}

#[test]
fn rotary_cut_demo_k100() {
    let mut dev = Devices::new();
    cut_block(&mut dev, [3183, 1000, 333], 5.0 / 3.0, 50.0 / 3.0, 0, 0, 0);
    ecamtbx::execute(&mut dev, P, 100, T, R).unwrap();
    let expected = rotary_cut::generate(&rotary_cut::Params {
        master_length: 3183,
        slave_length: 1000,
        sync_length: 333,
        sync_ratio: f64::from(5.0f32 / 3.0),
        max_ratio: f64::from(50.0f32 / 3.0),
        accel_curve: AccelCurve::Uniform,
        placement: CamPlacement::LeftCam,
        resolution: ecam_core::generator::CutParams::default().resolution,
    })
    .unwrap();
    let got = table(&dev);
    assert_eq!(got, expected.table.points());
    assert_eq!(dev.word(R).unwrap() as usize, got.len());
    assert_eq!(got.last().unwrap().master, 3183);
}

#[test]
fn flying_saw_demo_k101_forward_and_return() {
    let pi3 = (3.0 * std::f64::consts::PI) as f32;
    for (stroke, cam) in [(2000, 0), (-2000, 0x1000)] {
        let mut dev = Devices::new();
        cut_block(&mut dev, [1750, stroke, 667], pi3, 10.0, 0, cam, 0);
        ecamtbx::execute(&mut dev, P, 101, T, R).unwrap();
        let got = table(&dev);
        let expected = flying_saw::generate(&flying_saw::Params {
            master_length: 1750,
            slave_length: i64::from(stroke),
            sync_length: 667,
            sync_ratio: f64::from(pi3),
            max_ratio: 10.0,
            accel_curve: AccelCurve::Uniform,
            placement: CamPlacement::LeftCam,
            resolution: ecam_core::generator::CutParams::default().resolution,
        })
        .unwrap();
        assert_eq!(got, expected.table.points());
        assert_eq!(got.last().unwrap().slave, i64::from(stroke));
        assert_eq!(got.last().unwrap().master, 1750);
    }
}

#[test]
fn s_curve_demo_writes_the_table_and_p8_to_p11() {
    let mut dev = Devices::new();
    dev.set_dword(P, 10_000).unwrap();
    dev.set_dword(P + 2, 50_000).unwrap();
    dev.set_word(P + 6, 100).unwrap();
    dev.set_word(P + 7, 100).unwrap();
    dev.set_word(P + 8, 200).unwrap();
    for kind in [0, 1] {
        ecamtbx::execute(&mut dev, P, kind, T, R).unwrap();
        let expected = s_curve::generate(&s_curve::Params::default()).unwrap();
        let got = table(&dev);
        assert_eq!(got, expected.table.points());
        assert_eq!(got.last().unwrap(), &CamPoint::new(300, 10_000));
        assert_eq!(
            i64::from(dev.dword(P + 10).unwrap()),
            expected.last_section_master
        );
        assert_eq!(
            i64::from(dev.dword(P + 12).unwrap()),
            expected.last_section_slave
        );
        assert_eq!(dev.dword(P + 14).unwrap(), 100, "P10 uniform time");
        assert_eq!(dev.dword(P + 16).unwrap(), 50_000, "P11 top speed reached");
        assert_eq!(
            dev.word(P + 19).unwrap(),
            dev.word(R).unwrap(),
            "P13 result"
        );
    }
}

fn key_point_block(dev: &mut Devices, total: i16, points: &[(i32, i32, i16, i16)]) {
    dev.set_word(P + 2, total).unwrap();
    dev.set_word(P + 3, points.len() as i16).unwrap();
    for (i, &(m, s, curve, res)) in points.iter().enumerate() {
        let at = P + 8 + 6 * i as u16;
        dev.set_dword(at, m).unwrap();
        dev.set_dword(at + 2, s).unwrap();
        dev.set_word(at + 4, curve).unwrap();
        dev.set_word(at + 5, res).unwrap();
    }
}

const K2_CASE: &[(i32, i32, i16, i16)] = &[
    (600, 0, 0, 0),
    (1500, 2000, 0, 0),
    (1700, 2000, 0, 0),
    (1900, 600, 0, 0),
    (2000, 0, 0, 0),
];

#[test]
fn key_point_case_k2() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let expected = key_points::generate(&key_points::Params::default()).unwrap();
    let got = table(&dev);
    assert_eq!(got, expected.table.points());
    assert_eq!(dev.word(R).unwrap(), 100);
    assert_eq!(dev.word(P).unwrap(), 100, "S0: curve generation result");
    assert_eq!(dev.word(P + 1).unwrap(), 0, "S0+1: no error position");
    assert_eq!(expected.table.master_last(), 2000);
}

#[test]
fn k2_initial_slave_offsets_the_table() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    dev.set_dword(P + 4, 500).unwrap();
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    assert_eq!(table(&dev)[0], CamPoint::new(0, 500));
}

#[test]
fn k2_master_not_increasing_reports_the_key_point_and_keeps_the_old_table() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    dev.set_dword(P + 8 + 6 * 2, 1400).unwrap(); // key point 3 below key point 2
    let err = ecamtbx::execute(&mut dev, P, 2, T, R).unwrap_err();
    assert_eq!(err.code, 6782);
    assert_eq!(dev.word(R).unwrap(), -6782);
    assert_eq!(dev.word(P).unwrap(), -6782);
    assert_eq!(dev.word(P + 1).unwrap(), 3, "S0+1: the key point at fault");
    assert_eq!(table(&dev), before);
}

#[test]
fn k2_parameter_errors() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    dev.set_word(P + 3, 11).unwrap();
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 2, T, R).unwrap_err().code,
        6781
    );
    assert_eq!(dev.word(P + 1).unwrap(), 3);
    key_point_block(&mut dev, 100, K2_CASE);
    dev.set_word(P + 8 + 4, 7).unwrap(); // curve type of key point 1
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 2, T, R).unwrap_err().code,
        6781
    );
    assert_eq!(dev.word(P + 1).unwrap(), 1);
    key_point_block(&mut dev, 600, K2_CASE);
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 2, T, R).unwrap_err().code,
        6783
    );
    assert_eq!(dev.word(R).unwrap(), -6783);
}

#[test]
fn k2_key_point_resolution_error_names_the_key_point() {
    // A key point's resolution above 512 used to leave S0+1 at 0.
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    dev.set_word(P + 8 + 6 * 3 + 5, 513).unwrap(); // resolution of key point 4
    let err = ecamtbx::execute(&mut dev, P, 2, T, R).unwrap_err();
    assert_eq!(err.code, 6781);
    assert!(err.message.contains("key point 4"), "{}", err.message);
    assert_eq!(dev.word(P + 1).unwrap(), 4, "S0+1: the key point at fault");
    assert_eq!(dev.word(R).unwrap(), -6781);
    assert_eq!(table(&dev), before, "the previous table is kept");
}

#[test]
fn a_result_register_inside_the_table_is_refused_and_the_old_table_kept() {
    // D2 = D1 + 50 (point 2's slave): the result used to overwrite the table
    // it had just written.
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    let inside = T + 50;
    let err = ecamtbx::execute(&mut dev, P, 2, T, inside).unwrap_err();
    assert_eq!(err.code, 6781);
    assert!(err.message.contains("inside the table"), "{}", err.message);
    assert_eq!(
        table(&dev),
        before,
        "old table intact, D2 not written into it"
    );
    // Just past the new table's last word is fine.
    let after = T + 40 + 4 * 100;
    ecamtbx::execute(&mut dev, P, 2, T, after).unwrap();
    assert_eq!(dev.word(after).unwrap(), 100);
}

#[test]
fn bad_parameters_give_negative_results() {
    let mut dev = Devices::new();
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 7, T, R).unwrap_err().code,
        6781
    );
    assert_eq!(dev.word(R).unwrap(), -6781);
    // S-curve with resolution 600.
    dev.set_dword(P, 10_000).unwrap();
    dev.set_dword(P + 2, 50_000).unwrap();
    dev.set_word(P + 8, 600).unwrap();
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 0, T, R).unwrap_err().code,
        6781
    );
    // Rotary cut with a NaN ratio.
    let mut dev = Devices::new();
    cut_block(&mut dev, [3183, 1000, 333], f32::NAN, 10.0, 0, 0, 0);
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 100, T, R).unwrap_err().code,
        6781
    );
    assert_eq!(dev.word(T + 38).unwrap(), 0, "nothing written");
    // Unknown cam curve code.
    cut_block(&mut dev, [3183, 1000, 333], 5.0 / 3.0, 10.0, 0, 9, 0);
    assert_eq!(
        ecamtbx::execute(&mut dev, P, 100, T, R).unwrap_err().code,
        6781
    );
}

#[test]
fn a_generated_table_drives_decam() {
    use ecam_plc::Device;
    use ecam_plc::Hardware;
    use ecam_plc::decam::{Decam, DecamOperands, MasterOperand};
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let ops = DecamOperands::new(
        MasterOperand::Register(10),
        T,
        Device::X(0),
        0,
        Device::Y(4),
    )
    .unwrap();
    let mut cam = Decam::new(ops);
    let mut hw = Hardware::new();
    dev.set_word(T + 5, 1).unwrap();
    cam.execute(true, &mut dev, 0).unwrap();
    // Up to master 1500 at 50 kHz, then hold (the slave's peak speed needs
    // more than the 200 kHz limit for a moment; the backlog drains).
    for t in 1..=300u64 {
        dev.set_dword(10, (t.min(300) * 5) as i32).unwrap();
        cam.hardware_tick(&mut dev, &mut hw, t * 100, 100);
    }
    // Master 1500: key point 2, slave 2000.
    assert_eq!(dev.dword(T + 27).unwrap(), 1500);
    assert_eq!(dev.dword(8140).unwrap(), 2000);
}

fn s_curve_block(dev: &mut Devices, base: u16) {
    // The manual's case: 10000 pulses, 50 kHz, 100/100 ms, resolution 200.
    dev.set_dword(base, 10_000).unwrap();
    dev.set_dword(base + 2, 50_000).unwrap();
    dev.set_word(base + 6, 100).unwrap();
    dev.set_word(base + 7, 100).unwrap();
    dev.set_word(base + 8, 200).unwrap();
}

#[test]
fn s_curve_results_inside_the_new_table_are_refused_and_the_old_table_kept() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    // The 200-point S-curve takes T+38..T+839; P8 (S0+10) at T+510 is inside.
    let s0 = T + 500;
    s_curve_block(&mut dev, s0);
    let err = ecamtbx::execute(&mut dev, s0, 0, T, R).unwrap_err();
    assert_eq!(err.code, 6781);
    assert!(err.message.contains("S0+10"), "{}", err.message);
    assert_eq!(table(&dev), before, "the old table is untouched");
    assert_eq!(dev.word(R).unwrap(), -6781);
    assert_eq!(dev.dword(s0 + 10).unwrap(), 0, "P8 not written");
    assert_eq!(dev.word(s0 + 19).unwrap(), 0, "P13 not written");
}

#[test]
fn a_table_over_the_parameters_it_was_made_from_is_fine() {
    // S0 = T+830: the new table (up to T+839) covers P1-P7, but P8-P13
    // (T+840…) lie past it. All parameters are read before the table is
    // written, so the table is the manual's S-curve and P8-P11 are right.
    let mut dev = Devices::new();
    let s0 = T + 830;
    s_curve_block(&mut dev, s0);
    ecamtbx::execute(&mut dev, s0, 0, T, R).unwrap();
    let expected = s_curve::generate(&s_curve::Params::default()).unwrap();
    assert_eq!(table(&dev), expected.table.points());
    assert_eq!(dev.word(R).unwrap(), 200);
    assert_eq!(dev.dword(s0 + 14).unwrap(), 100, "P10");
    assert_eq!(dev.dword(s0 + 16).unwrap(), 50_000, "P11");
    assert_eq!(dev.word(s0 + 19).unwrap(), 200, "P13");
}

#[test]
fn k2_result_words_inside_the_new_table_are_refused_and_the_old_table_kept() {
    let mut dev = Devices::new();
    key_point_block(&mut dev, 20, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    assert_eq!(before.len(), 20);
    // A second block at T+400, outside the 20-point table (T+38..T+119) but
    // inside the 100 points it asks for (T+38..T+439): its S0/S0+1 would be
    // written over the new table.
    let s0 = T + 400;
    dev.set_word(s0 + 2, 100).unwrap();
    dev.set_word(s0 + 3, K2_CASE.len() as i16).unwrap();
    for (i, &(m, s, curve, res)) in K2_CASE.iter().enumerate() {
        let at = s0 + 8 + 6 * i as u16;
        dev.set_dword(at, m).unwrap();
        dev.set_dword(at + 2, s).unwrap();
        dev.set_word(at + 4, curve).unwrap();
        dev.set_word(at + 5, res).unwrap();
    }
    let err = ecamtbx::execute(&mut dev, s0, 2, T, R).unwrap_err();
    assert_eq!(err.code, 6781);
    assert_eq!(table(&dev), before, "the old table is untouched");
    assert_eq!(dev.word(R).unwrap(), -6781);
    assert_eq!(dev.word(s0).unwrap(), 0, "S0 not written");
    assert_eq!(dev.word(s0 + 1).unwrap(), 0, "S0+1 not written");
    // The same block with D1 moved so the table ends before S0 works.
    ecamtbx::execute(&mut dev, s0, 2, T - 100, R).unwrap();
    assert_eq!(dev.word(s0).unwrap(), 100);
}

#[test]
fn a_failure_writes_nothing_into_the_old_table() {
    // D2 inside the old table (not the new one, which is never made): the
    // negated code is not written there.
    let mut dev = Devices::new();
    key_point_block(&mut dev, 100, K2_CASE);
    ecamtbx::execute(&mut dev, P, 2, T, R).unwrap();
    let before = table(&dev);
    dev.set_word(P + 3, 0).unwrap(); // key points number 0: 6781
    let err = ecamtbx::execute(&mut dev, P, 2, T, T + 60).unwrap_err();
    assert_eq!(err.code, 6781);
    assert_eq!(table(&dev), before);
}
