//! Document 003 (LX3VP DECAM): cyclic and noncyclic cams, sync output,
//! repeat count, delay start, start position, start from the current
//! position (bit 6), zoom, the frequency limit and the output counters.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, MasterAlign, SlaveAlign, StartMode, StopKind,
    SyncWindow, TickInput, TickOutput, Zoom,
};

/// Section 4.1.3: a cycle of 50000 master counts, 5000 pulses out.
fn cyclic_table() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (20000, 1000), (30000, 3000), (50000, 5000)]).unwrap()
}

fn tick(a: &mut CamAxis<PointTable>, master: i64) -> TickOutput {
    a.tick(&TickInput::at(master, 100_000))
}

#[test]
fn cyclic_cam_with_sync_output_between_20000_and_30000() {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        sync_windows: [
            SyncWindow::new(20000, 30000),
            SyncWindow::OFF,
            SyncWindow::OFF,
            SyncWindow::OFF,
        ],
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(cyclic_table(), config).unwrap();
    a.arm().unwrap();
    let mut completed = 0;
    for m in (0..=150_000).step_by(500) {
        let out = tick(&mut a, m);
        assert!(out.initialised && out.busy);
        let in_cycle = m % 50000;
        assert_eq!(out.master_in_cycle, in_cycle);
        assert_eq!(
            out.in_sync,
            (20000..=30000).contains(&in_cycle),
            "master {m}"
        );
        completed += usize::from(out.events.cycle_completed);
    }
    assert_eq!(completed, 3);
    assert_eq!(a.status().slave, 15000);
    assert_eq!(a.status().cycle, 3);
    // The enable bit may be changed while running.
    a.set_sync_windows([SyncWindow::OFF; 4]);
    assert!(!tick(&mut a, 175_000).in_sync);
}

#[test]
fn stop_after_the_current_cycle() {
    let mut a = CamAxis::new(
        cyclic_table(),
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
    )
    .unwrap();
    a.arm().unwrap();
    tick(&mut a, 0);
    tick(&mut a, 61_000);
    a.stop(StopKind::EndOfCycle);
    assert_eq!(tick(&mut a, 99_000).state, AxisState::Stopping);
    let out = tick(&mut a, 101_000);
    assert_eq!(out.state, AxisState::Finished);
    assert_eq!(out.slave, 10000);
    assert!(out.events.stopped && out.events.cycle_completed);
    assert!(!out.initialised);
}

/// Section 4.2.3: master 0..100000 is one circle; D1014 = 2 runs three
/// cycles after the start signal X2 rises.
fn noncyclic(repeats: u16) -> CamAxis<PointTable> {
    let table = PointTable::from_pairs(&[(0, 0), (50000, 800), (100000, 0)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::OneShot { repeats },
        start: StartMode::OnRisingEdge,
        master_align: MasterAlign::StartAt(0),
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    a
}

fn with_start(master: i64, start: bool) -> TickInput {
    TickInput {
        start_input: start,
        ..TickInput::at(master, 100_000)
    }
}

#[test]
fn noncyclic_cam_runs_repeats_plus_one_cycles_after_the_start_signal() {
    let mut a = noncyclic(2);
    // The master runs before the start: the slave waits.
    assert_eq!(a.tick(&with_start(12_345, false)).slave, 0);
    assert_eq!(a.tick(&with_start(20_000, false)).state, AxisState::Armed);
    let out = a.tick(&with_start(20_000, true));
    assert!(out.events.engaged);
    let mut finished_at = None;
    let mut cycles = 0;
    for m in (20_000..=400_000).step_by(2500) {
        let out = a.tick(&with_start(m, true));
        cycles += usize::from(out.events.cycle_completed);
        if out.events.finished {
            finished_at = Some(m);
        }
        if m == 70_000 || m == 170_000 {
            assert_eq!(out.slave, 800);
        }
    }
    assert_eq!(finished_at, Some(320_000));
    assert_eq!(cycles, 3);
    assert_eq!(a.state(), AxisState::Finished);
    assert_eq!(a.status().slave, 0);
    assert!(!a.status().initialised);
    // Started again by the next rising edge.
    a.arm().unwrap();
    let _ = a.tick(&with_start(400_000, false));
    let out = a.tick(&with_start(400_000, true));
    assert!(out.events.engaged);
    assert_eq!(a.tick(&with_start(450_000, false)).slave, 800);
}

#[test]
fn repeat_count_ffff_runs_like_a_cyclic_cam() {
    let mut a = noncyclic(0xFFFF);
    let _ = a.tick(&with_start(0, true));
    for m in (0..=5_000_000).step_by(50_000) {
        assert_eq!(a.tick(&with_start(m, true)).state, AxisState::Running);
    }
}

#[test]
fn repeat_count_zero_runs_once() {
    let mut a = noncyclic(0);
    let _ = a.tick(&with_start(0, true));
    assert_eq!(a.tick(&with_start(99_999, true)).state, AxisState::Running);
    let out = a.tick(&with_start(100_000, true));
    assert!(out.events.finished);
    assert_eq!(out.state, AxisState::Finished);
}

#[test]
fn delay_start_counts_master_pulses_after_the_signal() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::OneShot { repeats: 0 },
        start: StartMode::AfterDelay {
            counts: 5000,
            after_edge: true,
        },
        master_align: MasterAlign::StartAt(0),
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    let _ = a.tick(&with_start(0, false));
    assert_eq!(a.tick(&with_start(1000, true)).state, AxisState::Delaying);
    assert_eq!(a.tick(&with_start(5999, true)).state, AxisState::Delaying);
    // The delay ends at 6000 exactly; 100 counts later the table is at 100.
    let out = a.tick(&with_start(6100, true));
    assert!(out.events.engaged);
    assert_eq!(out.slave, 100);
}

#[test]
fn start_at_a_master_position() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 2000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::OneShot { repeats: 0 },
        start: StartMode::AtMasterPosition {
            position: 7000,
            after_edge: false,
        },
        master_align: MasterAlign::StartAt(0),
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    assert_eq!(tick(&mut a, 6000).state, AxisState::Armed);
    let out = tick(&mut a, 7500);
    assert!(out.events.engaged);
    assert_eq!(out.slave, 1000);
    assert_eq!(tick(&mut a, 8000).state, AxisState::Finished);
}

#[test]
fn start_from_the_current_position_bit_6_with_zoom() {
    // Registers 27/28 = 100 (master before zoom), 19/20 = 3000 (slave after zoom).
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        master_align: MasterAlign::StartAtUnzoomed(100),
        slave_align: SlaveAlign::At(3000),
        master_zoom: Zoom::new(2, 1).unwrap(),
        slave_zoom: Zoom::new(3, 1).unwrap(),
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    let out = tick(&mut a, 5000);
    assert_eq!(out.slave, 3000);
    assert_eq!(out.master_in_cycle, 200);
    assert_eq!(out.master_in_cycle_raw, 100);
    // 10 master counts = 20 table counts = 20 table pulses = 60 output pulses.
    let out = tick(&mut a, 5010);
    assert_eq!(out.slave, 3060);
    assert_eq!(out.slave_unzoomed, 220);
    assert!((out.velocity_ratio - 6.0).abs() < 1e-12);
}

#[test]
fn frequency_limit_defaults_to_200k_and_delays_never_drop() {
    let table = PointTable::from_pairs(&[(0, 1000), (1000, 1000)]).unwrap();
    for hz in [0, -1, 1_000_000, 200_000] {
        let config = AxisConfig {
            max_frequency_hz: hz,
            ..AxisConfig::default()
        };
        let mut a = CamAxis::new(table.clone(), config).unwrap();
        a.arm().unwrap();
        // Absolute slave: the commanded jumps to 1000; 200 pulses per ms.
        let out = a.tick(&TickInput::at(0, 1000));
        assert_eq!(out.slave, 1000);
        assert_eq!(out.pulses, 200);
        assert_eq!(out.backlog, 800);
        assert!(out.pulse_delayed);
        let mut total = out.pulses;
        for _ in 0..4 {
            total += a.tick(&TickInput::at(0, 1000)).pulses;
        }
        assert_eq!(total, 1000);
        let out = a.tick(&TickInput::at(0, 1000));
        assert!(!out.pulse_delayed);
        assert_eq!(out.emitted, 1000);
    }
}

#[test]
fn output_counter_counts_down_in_reverse() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let mut a = CamAxis::new(
        table,
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
    )
    .unwrap();
    a.arm().unwrap();
    tick(&mut a, 0);
    assert_eq!(tick(&mut a, 2500).emitted, 2500);
    let out = tick(&mut a, -4000);
    assert_eq!(out.pulses, -6500);
    assert_eq!(out.emitted, -4000);
    assert!(!out.direction_forward);
    // The PLC shows the low 32 bits.
    assert_eq!(out.emitted as i32, -4000);
}

#[test]
fn output_inhibit_stops_immediately_and_keeps_the_backlog() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let mut a = CamAxis::new(
        table,
        AxisConfig {
            max_frequency_hz: 1000,
            ..AxisConfig::default()
        },
    )
    .unwrap();
    a.arm().unwrap();
    tick(&mut a, 0);
    let out = a.tick(&TickInput::at(500, 100_000));
    assert_eq!(out.pulses, 100);
    let out = a.tick(&TickInput {
        output_enabled: false,
        ..TickInput::at(600, 100_000)
    });
    assert_eq!(out.state, AxisState::Idle);
    assert!(out.events.stopped);
    assert_eq!(out.pulses, 0);
    assert_eq!(out.slave, 500);
    assert_eq!(out.backlog, 400);
    assert!(out.busy);
    a.discard_backlog();
    let out = tick(&mut a, 700);
    assert_eq!(out.slave, 100);
    assert!(!out.busy);
}

#[test]
fn configuration_is_refused_while_running() {
    let table = PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap();
    let mut a = CamAxis::new(table.clone(), AxisConfig::default()).unwrap();
    a.arm().unwrap();
    tick(&mut a, 10);
    assert_eq!(
        a.set_config(AxisConfig::default()),
        Err(ecam_engine::EngineError::Busy)
    );
    assert!(a.replace_curve(table).is_err());
    assert!(a.set_slave_position(0).is_err());
    assert_eq!(a.state(), AxisState::Running);
}
