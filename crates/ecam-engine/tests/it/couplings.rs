//! The couplings beyond the documents, one worked case each: modulo slave
//! start modes, gear (exact ratio, sync position), phasing under limits,
//! gear + cam + superimposed summed, registration, direction guards, cam
//! switches; through the engine's `SlaveAxis` and the PLCopen facade.

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::plcopen::{CamIn, CamOut, CamTableSelect};
use ecam_engine::plcopen_slave::{McSlaveAxis, SlaveStatus};
use ecam_engine::plcopen_slave_blocks::{
    DigitalCamSwitchBlock, GearInBlock, GearInPosBlock, MoveSuperimposedBlock, PhasingBlock,
};
use ecam_engine::{
    AxisConfig, CamAxis, CamSwitch, Coupling, CouplingError, DigitalCamSwitch, DirectionGuard,
    GearIn, GearInPos, GearOut, GearRamp, GearState, GuardDirection, GuardResume, LatchSource,
    ModuloAxis, ModuloStart, MoveLimits, MoveSuperimposed, Phasing, PhasingMode,
    RegistrationConfig, SlaveAlign, SlaveAxis, SlaveConfig, SlaveInput, SlaveOutput,
    SwitchDirection, SwitchMode, TRACKS, TickInput, TrackOptions, Zoom,
};

const TICK_US: u32 = 1000;

fn input(master: i64) -> SlaveInput {
    SlaveInput {
        tick: TickInput::at(master, TICK_US),
        latch: None,
    }
}

fn nz(v: u64) -> NonZeroU64 {
    NonZeroU64::new(v).unwrap()
}

/// A knife: one revolution (36 000 pulses) per 10 000 master counts.
fn knife() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (10_000, 36_000)]).unwrap()
}

fn modulo_axis(start: ModuloStart, slave_start: i64) -> SlaveAxis<CamAxis<PointTable>> {
    let modulo = ModuloAxis::new(36_000, start).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Periodic,
        slave_align: SlaveAlign::Modulo {
            axis: modulo,
            offset: 0,
        },
        ..AxisConfig::default()
    };
    let mut axis = SlaveAxis::with_cam(
        knife(),
        config,
        SlaveConfig {
            modulo: Some(modulo),
            ..SlaveConfig::default()
        },
    )
    .unwrap();
    axis.set_slave_position(slave_start).unwrap();
    axis.cam_mut().arm().unwrap();
    axis
}

#[test]
fn modulo_start_modes_pick_their_turn_and_seams_run_on() {
    // The knife stands at 35 000 (one turn is 36 000); the table says 0.
    let cases = [
        (ModuloStart::Absolute, 0),
        (ModuloStart::Relative, 35_000),
        (ModuloStart::EndlessPositive, 36_000),
        (ModuloStart::EndlessNegative, 0),
        (ModuloStart::Nearest, 36_000),
    ];
    for (start, target) in cases {
        let mut axis = modulo_axis(start, 35_000);
        let first = *axis.tick(&input(0));
        assert_eq!(first.slave, target, "{start:?}");
        let mut last = first;
        for m in 1..=30_000 {
            last = *axis.tick(&input(m));
            let p = last.modulo.unwrap();
            assert!((0..36_000).contains(&p.position));
            assert_eq!(
                i128::from(p.turns) * 36_000 + i128::from(p.position),
                i128::from(last.slave)
            );
        }
        match start {
            // The seams of a knife table are whole turns: the endless and
            // nearest modes run on, three more turns.
            ModuloStart::EndlessPositive | ModuloStart::Nearest | ModuloStart::EndlessNegative => {
                assert_eq!(last.slave, target + 3 * 36_000, "{start:?}");
            }
            // Absolute and relative keep the table's jump back each seam:
            // at the third seam the slave is back where the table started.
            ModuloStart::Absolute | ModuloStart::Relative => {
                assert_eq!(last.slave, target, "{start:?}");
            }
        }
        assert_eq!(last.modulo.unwrap().position, target % 36_000);
    }
}

#[test]
fn endless_positive_never_turns_the_knife_back() {
    let mut axis = modulo_axis(ModuloStart::EndlessPositive, 20_000);
    let mut emitted = 0;
    for m in 0..200_000 {
        let out = *axis.tick(&input(m * 3));
        assert!(out.pulses >= 0, "turned back at master {}", m * 3);
        emitted = out.emitted;
    }
    assert!(emitted > 20 * 36_000);
}

#[test]
fn a_gear_keeps_its_exact_ratio_over_a_billion_counts() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 0)]).unwrap();
    let mut axis =
        SlaveAxis::with_cam(table, AxisConfig::default(), SlaveConfig::default()).unwrap();
    axis.gear_in(&GearIn {
        ratio: Zoom::signed(7, 3).unwrap(),
        ramp: GearRamp::Distance(nz(3000)),
    })
    .unwrap();
    axis.tick(&input(0));
    let mut out = SlaveOutput::default();
    for m in 1..=3000 {
        out = *axis.tick(&input(m));
    }
    assert_eq!(out.gear.state, GearState::InGear);
    assert_eq!(out.slave, 3500, "the blend covers 3000 × 7/3 / 2");
    // Large steps, forwards and backwards: always 3500 + (m − 3000) × 7/3.
    let mut m = 3000i64;
    for step in [999_999_937i64, -123_456_789, 5, -876_543_153] {
        m += step;
        let slave = axis.tick(&input(m)).slave;
        let exact = 3500 + ((i128::from(m) - 3000) * 7).div_euclid(3);
        let exact = exact + i128::from(((i128::from(m) - 3000) * 7).rem_euclid(3) * 2 >= 3);
        assert_eq!(i128::from(slave), exact, "at master {m}");
    }
}

#[test]
fn gear_in_pos_meets_its_sync_point_through_the_blocks() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 0)]).unwrap();
    let mut axis = McSlaveAxis::new(table, SlaveConfig::default()).unwrap();
    let mut block = GearInPosBlock::default();
    let command = GearInPos {
        ratio: Zoom::signed(3, 2).unwrap(),
        master_sync: 20_000,
        slave_sync: 100_000,
        master_start_distance: NonZeroU64::new(8000),
    };
    let mut status = axis.tick(0, TICK_US);
    let mut started_at = None;
    let mut synced_at = None;
    for m in 1..=30_000i64 {
        let out = block.call(&mut axis, true, &command, &status);
        if out.start_sync && started_at.is_none() {
            started_at = Some(m);
        }
        if out.in_sync && synced_at.is_none() {
            synced_at = Some(m);
        }
        status = axis.tick(m, TICK_US);
        if m == 20_000 {
            assert_eq!(status.axis.slave, 100_000);
        }
    }
    assert_eq!(started_at, Some(12_001));
    assert_eq!(synced_at, Some(20_001));
    assert_eq!(status.axis.slave, 100_000 + 15_000);
    assert_eq!(
        axis.gear_in_pos(&GearInPos {
            master_sync: 0,
            ..command
        }),
        Err(CouplingError::SyncPassed)
    );
}

#[test]
fn phasing_keeps_to_its_limits_and_lands_on_the_shift() {
    // A straight cam, 2 pulses per count; the master at 20 counts per ms.
    let table = PointTable::from_pairs(&[(0, 0), (1000, 2000)]).unwrap();
    let mut axis = McSlaveAxis::new(table, SlaveConfig::default()).unwrap();
    axis.cam_table_select(CamTableSelect {
        slave_absolute: false,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let (v, a) = (2000.0, 20_000.0);
    let command = Phasing {
        shift: 777,
        mode: PhasingMode::Absolute,
        limits: MoveLimits::new(v, a, a).unwrap(),
    };
    let mut block = PhasingBlock::default();
    let mut status = axis.tick(0, TICK_US);
    let mut shifts = vec![0.0];
    let mut done_at = None;
    for ms in 1..=2000i64 {
        let out = block.call(&mut axis, true, &command, &status);
        if out.done && done_at.is_none() {
            done_at = Some(ms);
        }
        status = axis.tick(ms * 20, TICK_US);
        shifts.push(status.axis.phasing.shift);
    }
    let dt = f64::from(TICK_US) * 1e-6;
    for w in shifts.windows(3) {
        let v1 = (w[1] - w[0]) / dt;
        let v2 = (w[2] - w[1]) / dt;
        assert!(v1 <= v + 1e-6 && v1 >= -1e-6, "velocity {v1}");
        assert!(
            ((v2 - v1) / dt).abs() <= a + 1.0,
            "acceleration {}",
            (v2 - v1) / dt
        );
    }
    // 777 at 2000/s with 20 000/s²: 0.1 s up, 0.2885 s cruise, 0.1 s down.
    let done_at = done_at.unwrap();
    assert!((489..=492).contains(&done_at), "done at {done_at} ms");
    assert_eq!(status.axis.phasing.shift, 777.0);
    assert_eq!(status.axis.slave, 2 * (2000 * 20 + 777));
}

#[test]
fn gear_cam_and_superimposed_sum_exactly_each_with_its_status() {
    let table = PointTable::from_pairs(&[(0, 0), (500, 300), (1000, 1000)]).unwrap();
    let mut axis = McSlaveAxis::new(table.clone(), SlaveConfig::default()).unwrap();
    axis.cam_table_select(CamTableSelect {
        slave_absolute: false,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let mut gear = GearInBlock::default();
    let mut superimposed = MoveSuperimposedBlock::default();
    let gear_in = GearIn {
        ratio: Zoom::signed(-1, 4).unwrap(),
        ramp: GearRamp::Acceleration(50_000.0),
    };
    let shift = MoveSuperimposed {
        distance: 1234,
        limits: MoveLimits::new(5000.0, 100_000.0, 50_000.0).unwrap(),
    };
    let mut status: SlaveStatus = axis.tick(0, TICK_US);
    let mut in_gear = false;
    let mut moved = false;
    for ms in 1..=3000i64 {
        let g = gear.call(&mut axis, ms >= 100, &gear_in, &status);
        let s = superimposed.call(&mut axis, ms >= 500, &shift, &status);
        in_gear |= g.in_gear;
        moved |= s.done;
        status = axis.tick(ms * 7, TICK_US);
        let a = status.axis;
        assert_eq!(
            a.slave,
            a.cam.slave + a.gear.slave + a.superimposed.position
        );
        assert!(status.cam.active);
    }
    assert!(in_gear && moved);
    let a = status.axis;
    // Each part on its own: the cam of the master, the move's distance.
    let mut cam = CamAxis::new(
        table,
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
    )
    .unwrap();
    cam.arm().unwrap();
    let _ = cam.tick(&TickInput::at(0, TICK_US));
    assert_eq!(a.cam.slave, cam.tick(&TickInput::at(21_000, TICK_US)).slave);
    assert_eq!(a.superimposed.position, 1234);
    assert_eq!(a.slave, a.cam.slave + a.gear.slave + 1234);
    // The gear's part now moves at exactly −1/4 of the master.
    let before = a.gear.slave;
    let after = axis.tick(21_000 + 4000, TICK_US).axis.gear.slave;
    assert_eq!(after - before, -1000);
    // A cam-out does not end the gear, nor a gear-out the cam.
    axis.cam_out(CamOut::Hold);
    axis.gear_out(&GearOut {
        ramp: GearRamp::Immediate,
    })
    .unwrap();
    let out = axis.tick(26_000, TICK_US);
    assert_eq!(out.axis.gear.state, GearState::Off);
}

/// A rotary knife's registration: marks on the material every 10 010
/// master counts (the material is a little long), the first 300 late.
fn registration_run(missing: &[usize]) -> Vec<SlaveOutput> {
    let config = RegistrationConfig {
        source: LatchSource::Master,
        cycle: nz(10_000),
        expected: 2000,
        window: 800,
        max_correction: 120,
        ramp: nz(2000),
    };
    let mut axis = SlaveAxis::with_cam(
        knife(),
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
        SlaveConfig {
            registration: Some(config),
            ..SlaveConfig::default()
        },
    )
    .unwrap();
    axis.cam_mut().arm().unwrap();
    let marks: Vec<i64> = (0..40)
        .filter(|i| !missing.contains(i))
        .map(|i| 2300 + 10_010 * i as i64)
        .collect();
    let mut outs = Vec::new();
    let mut next = 0;
    for m in (0..400_000).step_by(7) {
        let latch = match marks.get(next) {
            Some(&mark) if mark <= m => {
                next += 1;
                Some(mark)
            }
            _ => None,
        };
        outs.push(*axis.tick(&SlaveInput {
            tick: TickInput::at(m, TICK_US),
            latch,
        }));
    }
    outs
}

#[test]
fn registration_converges_to_the_mark_within_its_limit() {
    let outs = registration_run(&[]);
    let marks: Vec<_> = outs
        .iter()
        .filter_map(|o| o.registration.filter(|r| r.mark))
        .collect();
    assert_eq!(marks.len(), 40);
    for r in &marks {
        assert!(r.last_correction.abs() <= 120, "{r:?}");
    }
    // 300 late at 120 per mark: 3 marks to take it out, then only the 10
    // counts per cycle the material adds.
    for r in &marks[4..] {
        assert!(r.last_error.abs() <= 10, "{r:?}");
    }
    let last = outs.last().unwrap().registration.unwrap();
    assert_eq!(last.missed, 0);
    assert_eq!(last.correction, -(300.0 + 39.0 * 10.0));
    // The cut follows the marks: no reversal of the knife.
    assert!(outs.iter().all(|o| o.pulses >= 0));
}

#[test]
fn missed_marks_are_counted_and_the_next_mark_corrects() {
    let outs = registration_run(&[10, 11, 25]);
    let last = outs.last().unwrap().registration.unwrap();
    assert_eq!(last.missed, 3);
    assert_eq!(last.marks, 37);
    assert_eq!(last.correction, -(300.0 + 39.0 * 10.0));
}

#[test]
fn a_forward_guard_holds_through_a_reversal_and_goes_on_without_a_jump() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 3000)]).unwrap();
    for resume in [GuardResume::AtOnce, GuardResume::AtReversalPoint] {
        let mut axis = SlaveAxis::with_cam(
            table.clone(),
            AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                ..AxisConfig::default()
            },
            SlaveConfig {
                guard: Some(DirectionGuard {
                    direction: GuardDirection::Forward,
                    resume,
                }),
                ..SlaveConfig::default()
            },
        )
        .unwrap();
        axis.cam_mut().arm().unwrap();
        // Forwards to 5000, back to 2000, forwards to 9000.
        let masters = (0..=5000).chain((2000..5000).rev()).chain(2001..=9000);
        let mut last = *axis.tick(&input(0));
        for m in masters {
            let out = *axis.tick(&input(m));
            assert!(out.pulses >= 0 && out.pulses <= 3, "{resume:?} at {m}");
            last = out;
        }
        let guard = last.guard.unwrap();
        match resume {
            GuardResume::AtOnce => {
                assert_eq!(guard.lost, 3000.0);
                assert_eq!(last.slave, 3 * (9000 + 3000));
            }
            GuardResume::AtReversalPoint => {
                assert_eq!(guard.lost, 0.0);
                assert_eq!(last.slave, 3 * 9000);
            }
        }
    }
}

#[test]
fn cam_switch_tracks_through_the_block() {
    let mut options = [TrackOptions::default(); TRACKS];
    options[2].on_compensation_us = -5000;
    options[2].off_compensation_us = -5000;
    let mut block =
        DigitalCamSwitchBlock::new(DigitalCamSwitch::new(NonZeroU64::new(10_000), options));
    let cams = [
        CamSwitch {
            track: 0,
            first_on: 2000,
            mode: SwitchMode::Position { last_on: 3000 },
            direction: SwitchDirection::Both,
        },
        CamSwitch {
            track: 2,
            first_on: 9000,
            mode: SwitchMode::Position { last_on: 500 },
            direction: SwitchDirection::Positive,
        },
        CamSwitch {
            track: 5,
            first_on: 4000,
            mode: SwitchMode::Time {
                duration_us: 20_000,
            },
            direction: SwitchDirection::Both,
        },
    ];
    // 10 counts per ms: a compensation of −5 ms is 50 counts early.
    let mut first_on = [None; 6];
    let mut on_ticks = [0u32; 6];
    let mut was = 0u32;
    for ms in 0..3000i64 {
        let out = block.call(true, &cams, ms * 10, TICK_US, u32::MAX);
        assert!(out.in_operation);
        for t in 0..6 {
            if out.outputs & (1 << t) != 0 {
                on_ticks[t] += 1;
                if was & (1 << t) == 0 && ms > 0 {
                    first_on[t].get_or_insert(ms * 10);
                }
            }
        }
        was = out.outputs;
    }
    assert_eq!(first_on[0], Some(2000));
    assert_eq!(first_on[2], Some(8950));
    assert_eq!(first_on[5], Some(4000));
    // Three passes over 30 000 counts: 101 ticks each for track 0, 20 ms for the time cam.
    assert_eq!(on_ticks[0], 3 * 101);
    assert_eq!(on_ticks[5], 3 * 20);
    let bad = [CamSwitch {
        track: 40,
        ..cams[0]
    }];
    assert_eq!(
        block.call(true, &bad, 0, TICK_US, u32::MAX).error_id,
        Some(CouplingError::BadTrack)
    );
}

#[test]
fn a_slave_latch_corrects_the_slave_itself() {
    // A feed roll geared 1:1 to the master carries the material; the marks
    // are on it, every 1000 pulses, the first 50 late; a slave latch
    // corrects the slave by at most 20 per mark, ramped over 100 counts.
    let flat = PointTable::from_pairs(&[(0, 0), (1000, 0)]).unwrap();
    let config = RegistrationConfig {
        source: LatchSource::Slave,
        cycle: nz(1000),
        expected: 200,
        window: 300,
        max_correction: 20,
        ramp: nz(100),
    };
    let mut axis = SlaveAxis::with_cam(
        flat,
        AxisConfig::default(),
        SlaveConfig {
            registration: Some(config),
            ..SlaveConfig::default()
        },
    )
    .unwrap();
    axis.gear_in(&GearIn {
        ratio: Zoom::signed(1, 1).unwrap(),
        ramp: GearRamp::Immediate,
    })
    .unwrap();
    let marks: Vec<i64> = (0..20).map(|i| 250 + 1000 * i).collect();
    let mut latch = None;
    let mut last = axis.tick(&input(0)).slave;
    let mut errors = Vec::new();
    for m in 1..=20_500 {
        let out = *axis.tick(&SlaveInput {
            tick: TickInput::at(m, TICK_US),
            latch: latch.take(),
        });
        assert!(out.pulses >= 0);
        // The probe latches where the slave passed a mark (given next tick).
        latch = marks.iter().copied().find(|&p| last < p && p <= out.slave);
        last = out.slave;
        if let Some(r) = out.registration.filter(|r| r.mark) {
            assert!(r.last_correction.abs() <= 20);
            errors.push(r.last_error);
        }
    }
    // 50 late, 20 a mark: 50, 30, 10, then in place; the slave is taken
    // on by 50 so that the marks it carries pass where expected.
    assert_eq!(&errors[..4], &[50, 30, 10, 0]);
    assert!(errors[4..].iter().all(|&e| e == 0));
    let r = axis.status().registration.unwrap();
    assert_eq!(r.correction, 50.0);
    assert_eq!(axis.status().slave, axis.status().gear.slave + 50);
}
