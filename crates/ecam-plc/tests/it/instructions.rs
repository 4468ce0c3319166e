//! Every IL instruction, executed through the scan cycle.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Device;
use ecam_plc::Plc;
use ecam_plc::Program;
use ecam_plc::Wire;
use ecam_plc::sim::{RunLength, Timing, run};

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn bit(plc: &Plc, device: &str) -> bool {
    plc.devices().bit(Device::parse(device).unwrap()).unwrap()
}

fn set(plc: &mut Plc, device: &str, on: bool) {
    plc.devices_mut()
        .set_bit(Device::parse(device).unwrap(), on)
        .unwrap();
}

#[test]
fn contacts_follow_fx_logic() {
    let mut p = plc(
        "LD X0\nAND X1\nOUT Y0\nLD X0\nOR X1\nOUT Y1\nLDI X0\nOUT Y2\nLD X0\nANI X1\nOUT Y3\nLD X0\nORI X1\nOUT Y4\n",
    );
    for (x0, x1) in [(false, false), (false, true), (true, false), (true, true)] {
        set(&mut p, "X0", x0);
        set(&mut p, "X1", x1);
        p.scan();
        assert_eq!(bit(&p, "Y0"), x0 && x1);
        assert_eq!(bit(&p, "Y1"), x0 || x1);
        assert_eq!(bit(&p, "Y2"), !x0);
        assert_eq!(bit(&p, "Y3"), x0 && !x1);
        assert_eq!(bit(&p, "Y4"), x0 || !x1);
    }
}

#[test]
fn blocks_combine_with_anb_and_orb() {
    let mut p =
        plc("LD X0\nOR X1\nLD X2\nOR X3\nANB\nOUT Y0\nLD X0\nAND X1\nLD X2\nAND X3\nORB\nOUT Y1\n");
    for bits in 0u8..16 {
        let x: Vec<bool> = (0..4).map(|i| bits & (1 << i) != 0).collect();
        for (i, on) in x.iter().enumerate() {
            set(&mut p, &format!("X{i}"), *on);
        }
        p.scan();
        assert_eq!(
            bit(&p, "Y0"),
            (x[0] || x[1]) && (x[2] || x[3]),
            "{bits:04b}"
        );
        assert_eq!(
            bit(&p, "Y1"),
            (x[0] && x[1]) || (x[2] && x[3]),
            "{bits:04b}"
        );
    }
}

#[test]
fn mps_mrd_mpp_keep_the_branch_point() {
    let mut p = plc(
        "LD X0\nMPS\nAND X1\nOUT Y1\nMRD\nAND X2\nOUT Y2\nMPP\nANI X1\nOUT Y3\nLD X5\nOUT Y5\n",
    );
    set(&mut p, "X0", true);
    set(&mut p, "X2", true);
    p.scan();
    assert!(!bit(&p, "Y1"));
    assert!(bit(&p, "Y2"));
    assert!(bit(&p, "Y3"));
    assert!(!bit(&p, "Y5"));
    set(&mut p, "X0", false);
    set(&mut p, "X5", true);
    p.scan();
    assert!(!bit(&p, "Y2") && !bit(&p, "Y3") && bit(&p, "Y5"));
}

#[test]
fn edge_contacts_fire_once() {
    let mut p = plc(
        "LDP X0\nOUT Y0\nLDF X0\nOUT Y1\nLD M8000\nANDP X0\nOUT Y2\nLDI M8000\nORP X0\nOUT Y3\n",
    );
    let mut seen = Vec::new();
    for x0 in [false, true, true, false, false] {
        set(&mut p, "X0", x0);
        p.scan();
        seen.push((bit(&p, "Y0"), bit(&p, "Y1"), bit(&p, "Y2"), bit(&p, "Y3")));
    }
    assert_eq!(
        seen,
        vec![
            (false, false, false, false),
            (true, false, true, true),
            (false, false, false, false),
            (false, true, false, false),
            (false, false, false, false)
        ]
    );
}

#[test]
fn set_rst_pls_plf() {
    let mut p = plc("LD X0\nSET M0\nLD X1\nRST M0\nLD X0\nPLS M1\nLD X0\nPLF M2\n");
    set(&mut p, "X0", true);
    p.scan();
    assert!(bit(&p, "M0") && bit(&p, "M1") && !bit(&p, "M2"));
    p.scan();
    assert!(bit(&p, "M0") && !bit(&p, "M1"));
    set(&mut p, "X0", false);
    p.scan();
    assert!(bit(&p, "M0") && bit(&p, "M2"));
    set(&mut p, "X1", true);
    p.scan();
    assert!(!bit(&p, "M0") && !bit(&p, "M2"));
}

#[test]
fn moves_and_zone_reset() {
    let mut p = plc(
        "LD M8000\nMOV K-5 D0\nDMOV K100000 D2\nDEMOV E1.6667 D106\nMOV H8000 D4\nDMOV D2 D10\nDEMOV D106 D20\nMOV K9 C5\nLD X0\nZRST D0 D3\nZRST M10 M12\nRST D10\n",
    );
    p.devices_mut().set_m(11, true).unwrap();
    p.scan();
    let d = p.devices();
    assert_eq!(d.word(0), Ok(-5));
    assert_eq!(d.dword(2), Ok(100_000));
    assert_eq!(d.float(106), Ok(1.6667));
    assert_eq!(d.word(4), Ok(i16::MIN));
    assert_eq!(d.dword(10), Ok(100_000));
    assert_eq!(d.float(20), Ok(1.6667));
    assert_eq!(d.counter(5), Ok(9));
    set(&mut p, "X0", true);
    p.scan();
    let d = p.devices();
    assert_eq!(
        (d.word(0), d.word(1), d.word(2), d.word(3), d.word(4)),
        (Ok(0), Ok(0), Ok(0), Ok(0), Ok(i16::MIN))
    );
    assert_eq!(d.m(11), Ok(false));
    assert_eq!(d.word(10), Ok(0));
}

#[test]
fn continuous_and_pulse_forms() {
    let mut p = plc("LD X0\nADD D0 K1 D0\nADDP D1 K1 D1\nMOVP D0 D2\n");
    set(&mut p, "X0", true);
    for _ in 0..3 {
        p.scan();
    }
    assert_eq!(p.devices().word(0), Ok(3), "ADD runs every scan while on");
    assert_eq!(
        p.devices().word(1),
        Ok(1),
        "ADDP runs once per rising power flow"
    );
    assert_eq!(p.devices().word(2), Ok(1));
    set(&mut p, "X0", false);
    p.scan();
    set(&mut p, "X0", true);
    p.scan();
    assert_eq!(p.devices().word(1), Ok(2));
}

#[test]
fn add_sub_wrap_and_set_flags() {
    let mut p = plc(
        "LD M8000\nADD K32767 K1 D0\nSUB K5 K5 D1\nDADD K2147483647 K1 D2\nDSUB K-2147483648 K1 D4\nSUB K-32768 K1 D6\n",
    );
    p.scan();
    let d = p.devices();
    assert_eq!(d.word(0), Ok(i16::MIN));
    assert_eq!(d.word(1), Ok(0));
    assert_eq!(d.dword(2), Ok(i32::MIN));
    assert_eq!(d.dword(4), Ok(i32::MAX));
    assert_eq!(d.word(6), Ok(i16::MAX));
    // Flags belong to the last ADD/SUB executed (SUB K-32768 K1: borrow).
    assert_eq!(
        (d.m(8020), d.m(8021), d.m(8022)),
        (Ok(false), Ok(true), Ok(false))
    );
    let mut p = plc("LD M8000\nSUB K5 K5 D1\n");
    p.scan();
    assert_eq!(p.devices().m(8020), Ok(true));
}

#[test]
fn compare_sets_three_bits() {
    let mut p = plc("LD M8000\nCMP D0 K10 M0\nDCMP D0 K10 M10\n");
    for (value, expected) in [
        (5, [false, false, true]),
        (10, [false, true, false]),
        (11, [true, false, false]),
    ] {
        p.devices_mut().set_dword(0, value).unwrap();
        p.scan();
        let got: Vec<bool> = (0..3).map(|i| p.devices().m(i).unwrap()).collect();
        assert_eq!(got, expected);
        let got: Vec<bool> = (10..13).map(|i| p.devices().m(i).unwrap()).collect();
        assert_eq!(got, expected);
    }
    // 16-bit CMP sees the low word only.
    p.devices_mut().set_dword(0, 0x0001_0005).unwrap();
    p.scan();
    assert_eq!(p.devices().m(2), Ok(true));
    assert_eq!(p.devices().m(10), Ok(true));
}

#[test]
fn special_relays_and_operation_errors() {
    let mut p = plc("LD M8002\nOUT M0\nLD M8000\nOUT M1\nLD X0\nPLSY D0 K10 Y0\n");
    p.scan();
    assert!(bit(&p, "M0") && bit(&p, "M1"));
    p.scan();
    assert!(!bit(&p, "M0") && bit(&p, "M1"));
    assert_eq!(p.devices().m(8067), Ok(false));
    p.devices_mut().set_word(0, -1).unwrap();
    set(&mut p, "X0", true);
    let errors = p.scan();
    assert_eq!(errors.len(), 1);
    assert_eq!(errors[0].line, 6);
    assert_eq!(errors[0].error.code, 6705);
    assert_eq!(p.devices().word(8067), Ok(6705));
    assert_eq!(p.devices().m(8067), Ok(true));
}

#[test]
fn m8067_is_set_when_the_instruction_fails_so_later_rungs_see_it() {
    // Set only at the end of the scan before: the rung after the failing
    // PLSY missed it, and a program's RST M8067 later in the scan was undone.
    let mut p = plc("LD X0\nPLSY D0 K10 Y0\nLD M8067\nOUT Y7\nLD X1\nRST M8067\n");
    p.devices_mut().set_word(0, -1).unwrap();
    set(&mut p, "X0", true);
    p.scan();
    assert!(bit(&p, "Y7"), "the same scan sees M8067");
    set(&mut p, "X0", false);
    set(&mut p, "X1", true);
    p.scan();
    assert_eq!(p.devices().m(8067), Ok(false), "the program's reset holds");
    assert_eq!(
        p.devices().word(8067),
        Ok(6705),
        "D8067 keeps the last code"
    );
}

#[test]
fn counters_count_coil_edges_and_reset() {
    let mut p = plc(
        "LD X0\nOUT C0 K3\nLD C0\nOUT Y0\nLD X1\nRST C0\nLD X0\nOUT C200 K-2\nLD M8000\nMOV C200 D0\n",
    );
    p.devices_mut().set_m(8200, true).unwrap();
    for x0 in [true, false, true, false, true, false, true, false] {
        set(&mut p, "X0", x0);
        p.scan();
    }
    assert_eq!(p.devices().counter(0), Ok(3));
    assert!(bit(&p, "Y0"));
    assert_eq!(
        p.devices().counter(200),
        Ok(-4),
        "C200 counts down while M8200 is on"
    );
    assert_eq!(p.devices().word(0), Ok(-4));
    set(&mut p, "X1", true);
    p.scan();
    assert_eq!(p.devices().counter(0), Ok(0));
    assert!(
        bit(&p, "Y0"),
        "the contact was read before RST in this scan"
    );
    p.scan();
    assert!(!bit(&p, "Y0"));
}

#[test]
fn plsy_frequency_is_exact_and_count_stops_it() {
    let mut p = plc("LD M8000\nDPLSY K3333 K0 Y0\nLD M8000\nPLSY K1000 K25 Y1\n");
    let ms =
        |plc: &mut Plc, ms| run(plc, Timing::default(), RunLength::Millis(ms), |_| {}).unwrap();
    assert!(ms(&mut p, 3000).is_empty());
    assert_eq!(p.devices().dword(8140), Ok(9999), "3333 Hz for 3 s");
    assert_eq!(p.devices().dword(8142), Ok(25));
    assert_eq!(p.devices().m(8147), Ok(true), "Y0 busy (endless)");
    assert_eq!(p.devices().m(8148), Ok(false), "Y1 done");
    assert_eq!(p.devices().m(8029), Ok(true));
}

#[test]
fn plsy_follows_its_power_flow_and_the_stop_flag() {
    let mut p = plc("LD X0\nDPLSY D0 K0 Y2\n");
    p.devices_mut().set_dword(0, 10_000).unwrap();
    let ms =
        |plc: &mut Plc, ms| run(plc, Timing::default(), RunLength::Millis(ms), |_| {}).unwrap();
    ms(&mut p, 10);
    assert_eq!(p.devices().dword(8150), Ok(0), "no power flow, no pulses");
    set(&mut p, "X0", true);
    ms(&mut p, 10);
    assert_eq!(p.devices().dword(8150), Ok(100));
    assert_eq!(p.devices().m(8149), Ok(true));
    p.devices_mut().set_dword(0, 20_000).unwrap();
    ms(&mut p, 10);
    assert_eq!(
        p.devices().dword(8150),
        Ok(300),
        "frequency changes while running"
    );
    p.devices_mut().set_m(8152, true).unwrap();
    ms(&mut p, 10);
    assert_eq!(p.devices().dword(8150), Ok(300), "M8152 stops Y2 at once");
    assert_eq!(p.devices().m(8149), Ok(false));
    p.devices_mut().set_m(8152, false).unwrap();
    ms(&mut p, 10);
    assert_eq!(
        p.devices().dword(8150),
        Ok(300),
        "a stopped PLSY restarts only after its power flow was off"
    );
    set(&mut p, "X0", false);
    ms(&mut p, 1);
    set(&mut p, "X0", true);
    ms(&mut p, 10);
    assert_eq!(p.devices().dword(8150), Ok(500));
}

#[test]
fn wire_feeds_the_high_speed_counter() {
    let mut p =
        plc("LD M8000\nOUT C231 K2147483647\nDPLSY K20000 K5000 Y1\nLD M8000\nDMOV C231 D100\n");
    p.hardware_mut().add_wire(Wire::parse("Y1:X0").unwrap());
    run(&mut p, Timing::default(), RunLength::Millis(300), |_| {}).unwrap();
    assert_eq!(p.devices().counter(231), Ok(5000));
    assert_eq!(p.devices().dword(8142), Ok(5000));
    assert_eq!(p.devices().dword(100), Ok(5000));
    assert!(
        !bit(&p, "X0"),
        "a wire feeds the counter, it does not toggle X0"
    );
}

#[test]
fn the_same_wire_twice_counts_each_pulse_once() {
    // `--wire Y1:X0 --wire Y1:X0` used to double every count.
    let mut p = plc("LD M8000\nOUT C231 K2147483647\nDPLSY K20000 K500 Y1\n");
    p.hardware_mut().add_wire(Wire::parse("Y1:X0").unwrap());
    p.hardware_mut().add_wire(Wire::parse("Y1:X0").unwrap());
    run(&mut p, Timing::default(), RunLength::Millis(100), |_| {}).unwrap();
    assert_eq!(p.devices().counter(231), Ok(500));
}

#[test]
fn counter_without_its_coil_does_not_count() {
    let mut p = plc("LD M8000\nDPLSY K20000 K100 Y1\n");
    p.hardware_mut().add_wire(Wire::parse("Y1:X0").unwrap());
    run(&mut p, Timing::default(), RunLength::Millis(20), |_| {}).unwrap();
    assert_eq!(p.devices().counter(231), Ok(0));
}

#[test]
fn input_edges_count_on_high_speed_counters() {
    let mut p = plc("LD M8000\nOUT C235 K2\nLD C235\nOUT Y7\n");
    set(&mut p, "X0", true);
    run(&mut p, Timing::default(), RunLength::Scans(2), |_| {}).unwrap();
    assert_eq!(p.devices().counter(235), Ok(1));
    set(&mut p, "X0", false);
    run(&mut p, Timing::default(), RunLength::Scans(1), |_| {}).unwrap();
    set(&mut p, "X0", true);
    run(&mut p, Timing::default(), RunLength::Scans(2), |_| {}).unwrap();
    assert_eq!(p.devices().counter(235), Ok(2));
    assert!(bit(&p, "Y7"));
}

#[test]
fn simulated_time_and_scan_count() {
    let mut p = plc("LD M8000\nADD D0 K1 D0\n");
    let mut times = Vec::new();
    run(
        &mut p,
        Timing {
            scan_us: 2000,
            tick_us: 300,
        },
        RunLength::Millis(7),
        |plc| times.push(plc.now_us()),
    )
    .unwrap();
    assert_eq!(times, vec![0, 2000, 4000, 6000]);
    assert_eq!(p.now_us(), 7000);
    assert_eq!(p.devices().word(0), Ok(4));
    assert!(
        run(
            &mut p,
            Timing {
                scan_us: 0,
                tick_us: 100
            },
            RunLength::Scans(1),
            |_| {}
        )
        .is_err()
    );
}

#[test]
fn clock_relays_follow_simulated_time() {
    let mut p = plc("LD M8011\nOUT Y0\nLDP M8012\nADDP D0 K1 D0\n");
    let mut y0 = Vec::new();
    run(&mut p, Timing::default(), RunLength::Millis(20), |plc| {
        y0.push(bit(plc, "Y0"))
    })
    .unwrap();
    let expected: Vec<bool> = (0..20).map(|ms| ms % 10 < 5).collect();
    assert_eq!(y0, expected);
    run(&mut p, Timing::default(), RunLength::Millis(980), |_| {}).unwrap();
    assert_eq!(p.devices().word(0), Ok(10), "ten 100 ms periods in 1 s");
}

#[test]
fn inc_dec_wrap_without_flags() {
    let mut p = plc("LD M8000\nINC D0\nDECP D1\nDINC D2\nLD X0\nDDEC D4\nINC C10\n");
    p.devices_mut().set_word(0, i16::MAX).unwrap();
    p.devices_mut().set_dword(2, -1).unwrap();
    p.scan();
    p.scan();
    let d = p.devices();
    assert_eq!(d.word(0), Ok(i16::MIN + 1));
    assert_eq!(d.word(1), Ok(-1), "DECP once");
    assert_eq!(d.dword(2), Ok(1));
    assert_eq!(d.dword(4), Ok(0), "no power flow");
    assert_eq!(d.m(8022), Ok(false));
    set(&mut p, "X0", true);
    p.scan();
    assert_eq!(p.devices().dword(4), Ok(-1));
    assert_eq!(p.devices().counter(10), Ok(1));
}
