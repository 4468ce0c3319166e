//! One instruction drives a pulse output at a time (the FX rule): a second
//! DECAM, PLSY or DPLSY on a busy output waits and takes it once released.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Device;
use ecam_plc::Plc;
use ecam_plc::Program;

fn plc(src: &str) -> Plc {
    Plc::new(Program::parse(src, "t.il").unwrap()).unwrap()
}

fn set(plc: &mut Plc, device: &str, on: bool) {
    plc.devices_mut()
        .set_bit(Device::parse(device).unwrap(), on)
        .unwrap();
}

/// `ms` milliseconds: a scan, then ten 100 µs ticks, per millisecond.
fn run_ms(plc: &mut Plc, ms: u32) {
    for _ in 0..ms {
        assert!(plc.scan().is_empty());
        for _ in 0..10 {
            plc.hardware_tick(100);
        }
    }
}

fn dword(plc: &Plc, n: u16) -> i32 {
    plc.devices().dword(n).unwrap()
}

/// A cyclic cam at `block`: master 0..10000, slave 0..`stroke`, start
/// register 1.
fn cyclic_cam(plc: &mut Plc, block: u16, stroke: i32) {
    let dev = plc.devices_mut();
    dev.set_word(block + 38, 2).unwrap();
    dev.set_dword(block + 44, 10_000).unwrap();
    dev.set_dword(block + 46, stroke).unwrap();
    dev.set_word(block + 5, 1).unwrap();
}

/// Flag bit 6: cyclic mode accepted.
fn cyclic_active(plc: &Plc, block: u16) -> bool {
    plc.devices().word(block + 1).unwrap() & (1 << 6) != 0
}

const TWO_CAMS: &str = "LD M0\nDECAM K1 D2000 X0 Y0 Y4\nLD M1\nDECAM K1 D3000 X1 Y0 Y5\n";

#[test]
fn two_cams_on_y0_only_the_first_moves_it_until_it_lets_go() {
    let mut p = plc(TWO_CAMS);
    cyclic_cam(&mut p, 2000, 1000);
    cyclic_cam(&mut p, 3000, 5000);
    set(&mut p, "M0", true);
    set(&mut p, "M1", true);
    run_ms(&mut p, 50);
    // K1: one master count per 100 µs, so 500 counts: cam 1 at slave 50.
    assert_eq!(dword(&p, 2019), 50);
    assert_eq!(dword(&p, 8140), 50, "Y0 carries cam 1 alone");
    assert!(cyclic_active(&p, 2000));
    assert!(!cyclic_active(&p, 3000), "cam 2 waits: no mode accepted");
    assert_eq!(dword(&p, 3019), 0, "cam 2 has not moved");
    assert_eq!(p.devices().m(8147), Ok(true));
    assert_eq!(p.devices().m(8067), Ok(false), "waiting is no error (FX)");

    // Cam 1 loses its power flow: cam 2, still enabled, takes Y0.
    set(&mut p, "M0", false);
    run_ms(&mut p, 50);
    assert_eq!(dword(&p, 2019), 50, "cam 1 holds where it stopped");
    assert!(cyclic_active(&p, 3000));
    let slave = dword(&p, 3019);
    // Its time base read 0 when it took Y0: 50 ms later, 500 counts. It
    // started where cam 1 left Y0 (50): its table rises, so the start rule
    // takes the table value ahead of 50, one stroke on (5000), rather than
    // 50 reverse pulses back to 0.
    assert_eq!(slave, 5250, "cam 2 follows its own master (500 counts)");
    assert_eq!(dword(&p, 8140), slave, "Y0 now carries cam 2 alone");

    // Cam 1 enabled again: Y0 is cam 2's, so cam 1 waits in turn.
    set(&mut p, "M0", true);
    run_ms(&mut p, 20);
    assert!(!cyclic_active(&p, 2000));
    assert_eq!(dword(&p, 2019), 50);
    assert_eq!(dword(&p, 8140), dword(&p, 3019));
}

#[test]
fn a_cam_waits_for_a_running_dplsy_on_its_output() {
    let mut p = plc("LD M2\nDPLSY K10000 K100 Y0\nLD M0\nDECAM K1 D2000 X0 Y0 Y4\n");
    cyclic_cam(&mut p, 2000, 1000);
    set(&mut p, "M0", true);
    set(&mut p, "M2", true);
    run_ms(&mut p, 5);
    assert_eq!(dword(&p, 8140), 50, "the DPLSY alone: 10 pulses/ms");
    assert!(!cyclic_active(&p, 2000), "the cam waits");
    run_ms(&mut p, 15);
    // The 100 pulses ended at 10 ms; the cam took Y0 then (its time base
    // reading 0 from that instant) with the output at 100: its table rises,
    // so the start rule puts it on the table value ahead of 100 (one
    // stroke, 1000, on), never reverse pulses back to 0.
    assert!(cyclic_active(&p, 2000));
    assert_eq!(dword(&p, 2019), 1010, "master 100 counts");
    assert_eq!(dword(&p, 8140), 1010, "D8140 is the cam's slave");
    assert_eq!(p.devices().m(8029), Ok(true), "the DPLSY finished");
}

#[test]
fn a_dplsy_waits_for_a_running_cam_and_starts_when_it_stops() {
    let mut p = plc("LD M0\nDECAM K1 D2000 X0 Y0 Y4\nLD M2\nDPLSY K10000 K0 Y0\n");
    cyclic_cam(&mut p, 2000, 1000);
    set(&mut p, "M0", true);
    run_ms(&mut p, 10);
    set(&mut p, "M2", true);
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 2019), 20);
    assert_eq!(dword(&p, 8140), 20, "no DPLSY pulse while the cam runs");
    assert_eq!(p.devices().m(8029), Ok(false));

    // The cam stops (power flow off in this scan, effective in its ticks);
    // the DPLSY, power flow still on, starts at the next scan.
    set(&mut p, "M0", false);
    run_ms(&mut p, 1);
    let stopped = dword(&p, 8140);
    assert_eq!(stopped, 20, "the cam stopped in the first tick");
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 8140), stopped + 100, "the DPLSY now drives Y0");
    assert_eq!(dword(&p, 2019), 20, "the cam stays stopped");
}

#[test]
fn two_pulse_trains_on_one_output_do_not_add_up() {
    let mut p = plc("LD M0\nDPLSY K1000 K0 Y1\nLD M1\nDPLSY K5000 K0 Y1\n");
    set(&mut p, "M0", true);
    set(&mut p, "M1", true);
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 8142), 10, "1 kHz only");
    // The waiting one losing its power flow does not stop the running one.
    set(&mut p, "M1", false);
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 8142), 20);
    set(&mut p, "M1", true);
    set(&mut p, "M0", false);
    // The first releases Y1 as it executes; the second, later in the same
    // scan, takes it at once.
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 8142), 20 + 50, "then 5 kHz alone");
}

#[test]
fn an_external_start_edge_while_another_holds_the_output_is_ignored() {
    let mut p = plc("LD M2\nDPLSY K10000 K100 Y0\nLD M0\nDECAM K1 D2000 X0 Y0 Y4\n");
    cyclic_cam(&mut p, 2000, 1000);
    p.devices_mut().set_word(2003, 1 << 5).unwrap(); // external start (S3)
    set(&mut p, "M0", true);
    run_ms(&mut p, 2);
    assert_eq!(p.hardware().owner(0), None, "waiting for S3 holds nothing");
    set(&mut p, "M2", true);
    run_ms(&mut p, 2);
    set(&mut p, "X0", true);
    run_ms(&mut p, 2);
    assert_eq!(dword(&p, 8140), 40, "the DPLSY alone");
    assert_eq!(dword(&p, 2019), 0, "the edge was ignored");
    run_ms(&mut p, 10);
    assert_eq!(dword(&p, 8140), 100, "no new edge, no start");
    set(&mut p, "X0", false);
    run_ms(&mut p, 1);
    set(&mut p, "X0", true);
    run_ms(&mut p, 5);
    assert!(dword(&p, 2019) > 0);
    assert_eq!(dword(&p, 8140), dword(&p, 2019), "the cam drives Y0 now");
}

/// Handing Y0 over from one DECAM to a second one (docs/plc.md, "Two
/// DECAMs on one output"): the first stops at the end of its cycle (offset
/// 4 bit 1), the second, started noncyclic with endless repeats (start
/// register 2, repeat count HFFFF) and waiting for Y0, takes it within a
/// scan and moves relative to the pulse counter: no position step and no
/// reversal, a standstill of at most one scan between the two.
#[test]
fn a_second_cam_takes_the_output_over_where_the_first_stopped() {
    let mut p = plc(TWO_CAMS);
    cyclic_cam(&mut p, 2000, 1000);
    cyclic_cam(&mut p, 3000, 2000);
    p.devices_mut().set_word(3000 + 14, -1).unwrap();
    p.devices_mut().set_word(3000 + 5, 2).unwrap();
    set(&mut p, "M0", true);
    set(&mut p, "M1", true);
    run_ms(&mut p, 500);
    // Stop cam 1 at the end of its cycle (master 10000 = 1000 ms).
    p.devices_mut().set_word(2000 + 4, 0b10).unwrap();
    let mut last = dword(&p, 8140);
    let mut still = 0;
    let mut handed_over = None;
    for ms in 500..2000 {
        run_ms(&mut p, 1);
        let now = dword(&p, 8140);
        let step = now - last;
        assert!(step >= 0, "ms {ms}: reversed by {step}");
        // 10 master counts per ms: cam 1 moves 1 pulse a ms, cam 2 2.
        assert!(step <= 3, "ms {ms}: a step of {step} pulses");
        if step == 0 {
            still += 1;
        }
        // Flag bit 7: noncyclic mode accepted (cam 2 has Y0).
        if handed_over.is_none() && p.devices().word(3000 + 1).unwrap() & (1 << 7) != 0 {
            handed_over = Some(ms);
        }
        last = now;
    }
    assert_eq!(dword(&p, 2019), 1000, "cam 1 stopped at its cycle end");
    assert!(still <= 1, "standing still for {still} ms");
    assert!(
        handed_over.is_some_and(|ms| (999..=1001).contains(&ms)),
        "{handed_over:?}"
    );
    // From then on Y0 carries cam 2 (relative to 1000, 2 pulses per ms).
    assert_eq!(dword(&p, 8140), dword(&p, 3019));
    assert!(dword(&p, 8140) >= 1000 + 2 * 990, "{}", dword(&p, 8140));
}
