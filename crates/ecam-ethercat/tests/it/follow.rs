//! Drives following pulse outputs (`ecam serve --ethercat`'s line): the
//! target is exactly the scaled pulse total from where the drive stood at
//! enabling, never a jump; a fault stops and a reset-then-enable sent back
//! to back recovers without a jump; a drive that cannot enable is reported
//! instead of hanging the line.

use std::time::Duration;

use ecam_engine::drive::AxisDrive;
use ecam_ethercat::cia402::DriveState;
use ecam_ethercat::emulation::DriveBehaviour;
use ecam_ethercat::follow::{FollowError, FollowLine, Follower, Scale};
use ecam_ethercat::supervisor::{FaultCause, LineFault, LineState, RECOVERY_TIMEOUT};

use crate::emulated;

fn line(drives: usize, followers: Vec<Follower>) -> FollowLine {
    let (segment, _) = emulated(drives, DriveBehaviour::default());
    FollowLine::new(segment, followers, crate::LOST, Duration::ZERO).unwrap()
}

/// Cycles with fixed pulse totals until the line runs.
fn run_up(line: &mut FollowLine, emitted: &[i64; 4]) {
    line.start().unwrap();
    for _ in 0..20 {
        line.cycle(emitted).unwrap();
        if line.state() == LineState::Running {
            return;
        }
    }
    panic!("line did not start");
}

#[test]
fn targets_are_the_exact_scaled_pulse_total_from_where_the_drive_stood() {
    let scale = Scale::new(25, 9).unwrap();
    let mut line = line(
        2,
        vec![
            Follower {
                output: 0,
                drive: 0,
                scale,
            },
            Follower {
                output: 0,
                drive: 1,
                scale: Scale::new(-1, 1).unwrap(),
            },
        ],
    );
    // Pulses emitted before the drives are enabled are not followed.
    let mut emitted = [1234, 0, 0, 0];
    run_up(&mut line, &emitted);
    let start: Vec<i64> = line.segment().drives().iter().map(|d| d.actual()).collect();
    let base = emitted[0];
    let mut last_target = line.target_of(0).unwrap();
    for cycle in 1..=3000i64 {
        // An uneven speed: 0–6 pulses per cycle.
        emitted[0] += cycle % 7;
        let report = line.cycle(&emitted).unwrap();
        assert_eq!(report.seen.new_faults, 0);
        let target = line.target_of(0).unwrap();
        // Exact, from the totals: no drift however the cycles fall.
        assert_eq!(
            target - start[0],
            scale.counts(emitted[0]) - scale.counts(base)
        );
        assert!(target - last_target <= 25 * 6 / 9 + 1, "no jump");
        assert!(target >= last_target, "no reversal");
        last_target = target;
        assert_eq!(line.target_of(1).unwrap() - start[1], -(emitted[0] - base));
    }
    // The drives get there (the emulation lags a few cycles).
    for _ in 0..10 {
        line.cycle(&emitted).unwrap();
    }
    let d = line.segment().drives();
    assert_eq!(d[0].actual(), last_target);
    assert_eq!(d[0].status().following_error, 0);
    assert_eq!(d[1].actual(), start[1] - (emitted[0] - base));
}

#[test]
fn fault_stops_and_reset_then_enable_back_to_back_recovers_without_a_jump() {
    let (segment, emulation) = emulated(2, DriveBehaviour::default());
    let followers = (0..2)
        .map(|drive| Follower {
            output: drive as u8,
            drive,
            scale: Scale::ONE,
        })
        .collect();
    let mut line = FollowLine::new(segment, followers, crate::LOST, Duration::ZERO).unwrap();
    let mut emitted = [0i64; 4];
    run_up(&mut line, &emitted);
    for _ in 0..100 {
        emitted[0] += 5;
        emitted[1] += 3;
        line.cycle(&emitted).unwrap();
    }
    emulation
        .lock()
        .unwrap()
        .esc_mut(1)
        .unwrap()
        .drive_mut()
        .inject_fault(0x7500);
    let mut faults = Vec::new();
    for _ in 0..5 {
        emitted[0] += 5;
        line.cycle(&emitted).unwrap();
        faults.extend_from_slice(line.new_faults());
        if !faults.is_empty() {
            break;
        }
    }
    assert_eq!(
        faults,
        vec![LineFault::new(Some(1), FaultCause::Drive { code: 0x7500 })]
    );
    assert_eq!(line.state(), LineState::Faulted);
    assert!(matches!(
        line.start(),
        Err(FollowError::State(LineState::Faulted))
    ));
    // The PLC goes on pulsing while the line stands: the drives stay put.
    for _ in 0..50 {
        emitted[0] += 5;
        line.cycle(&emitted).unwrap();
    }
    let held: Vec<i64> = line.segment().drives().iter().map(|d| d.actual()).collect();
    for _ in 0..20 {
        emitted[0] += 5;
        line.cycle(&emitted).unwrap();
    }
    let now: Vec<i64> = line.segment().drives().iter().map(|d| d.actual()).collect();
    assert_eq!(now, held, "nothing moves while faulted");
    // Reset and enable in the same cycle, as two coil writes would land.
    line.reset().unwrap();
    line.start().unwrap();
    let mut previous = held.clone();
    for _ in 0..30 {
        line.cycle(&emitted).unwrap();
        assert!(line.new_faults().is_empty(), "{:?}", line.new_faults());
        let now: Vec<i64> = line.segment().drives().iter().map(|d| d.actual()).collect();
        assert_eq!(now, previous, "re-enabling does not move a standing drive");
        previous = now;
        if line.state() == LineState::Running {
            break;
        }
    }
    assert_eq!(line.state(), LineState::Running);
    assert_eq!(
        line.segment().drives()[1].state(),
        DriveState::OperationEnabled
    );
    // And it follows again from there.
    for _ in 0..20 {
        emitted[1] += 3;
        line.cycle(&emitted).unwrap();
    }
    assert!(line.segment().drives()[1].actual() > held[1]);
}

#[test]
fn a_fault_that_a_reset_does_not_clear_is_reported_not_waited_for() {
    let (segment, emulation) = emulated(1, DriveBehaviour::default());
    let mut line = FollowLine::new(
        segment,
        vec![Follower {
            output: 0,
            drive: 0,
            scale: Scale::ONE,
        }],
        crate::LOST,
        Duration::ZERO,
    )
    .unwrap();
    let emitted = [0i64; 4];
    run_up(&mut line, &emitted);
    let inject = |code| {
        emulation
            .lock()
            .unwrap()
            .esc_mut(0)
            .unwrap()
            .drive_mut()
            .inject_fault(code)
    };
    inject(0x4310);
    for _ in 0..5 {
        line.cycle(&emitted).unwrap();
    }
    assert_eq!(line.state(), LineState::Faulted);
    line.reset().unwrap();
    line.start().unwrap();
    // The fault comes back every cycle (an overheated stage): the line is
    // faulted again once the recovery timeout has passed, not stuck.
    let limit = RECOVERY_TIMEOUT.as_millis() as usize + 50;
    let mut reported = Vec::new();
    for _ in 0..limit {
        inject(0x4310);
        line.cycle(&emitted).unwrap();
        reported.extend_from_slice(line.new_faults());
        if line.state() == LineState::Faulted {
            break;
        }
    }
    assert_eq!(line.state(), LineState::Faulted);
    assert!(!reported.is_empty());
}

#[test]
fn bad_bindings_are_refused() {
    let (segment, _) = emulated(1, DriveBehaviour::default());
    let follower = |output, drive| Follower {
        output,
        drive,
        scale: Scale::ONE,
    };
    assert!(matches!(
        FollowLine::new(segment, vec![follower(0, 3)], 1, Duration::ZERO),
        Err(FollowError::NoSuchDrive {
            drive: 3,
            drives: 1
        })
    ));
    let (segment, _) = emulated(1, DriveBehaviour::default());
    assert!(matches!(
        FollowLine::new(segment, vec![follower(4, 0)], 1, Duration::ZERO),
        Err(FollowError::NoSuchOutput(4))
    ));
    let (segment, _) = emulated(1, DriveBehaviour::default());
    assert!(matches!(
        FollowLine::new(
            segment,
            vec![follower(0, 0), follower(1, 0)],
            1,
            Duration::ZERO
        ),
        Err(FollowError::DriveTwice(0))
    ));
    let (segment, _) = emulated(1, DriveBehaviour::default());
    assert!(matches!(
        FollowLine::new(segment, vec![], 1, Duration::ZERO),
        Err(FollowError::Empty)
    ));
}
