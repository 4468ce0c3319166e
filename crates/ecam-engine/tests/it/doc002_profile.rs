//! Document 002 (motion processor electronic-cam profile mode): incremental
//! tables, CamStartCount, the bumpless output offset, breakpoint starts,
//! abrupt and smooth stops.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Compare, Coupling, MasterAlign, SlaveAlign, StartMode,
    StopKind, TickInput,
};

/// Three evenly spaced values over CamCounts = 100 (input 0, 50, 100).
fn three_entries() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (50, 100), (100, 200)]).unwrap()
}

fn incremental(start: StartMode, start_count: i64) -> AxisConfig {
    AxisConfig {
        // Document 002: first != last defines an incremental cam.
        coupling: Coupling::Repeat { min_stroke: 1 },
        start,
        master_align: MasterAlign::StartAt(start_count),
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    }
}

fn tick(axis: &mut CamAxis<PointTable>, master: i64) -> ecam_engine::TickOutput {
    axis.tick(&TickInput::at(master, 1_000_000))
}

#[test]
fn incremental_table_continues_past_its_end() {
    let mut a = CamAxis::new(three_entries(), incremental(StartMode::Immediate, 0)).unwrap();
    a.arm().unwrap();
    assert_eq!(tick(&mut a, 0).slave, 0);
    assert_eq!(tick(&mut a, 100).slave, 200);
    // "when the input increases from 100 to 101 counts the output will
    // increase from 200 to 202 counts"
    let out = tick(&mut a, 101);
    assert_eq!(out.slave, 202);
    assert_eq!(out.output_offset, 200);
    // And the other way round the seam: first to last.
    assert_eq!(tick(&mut a, 0).slave, 0);
    let out = tick(&mut a, -1);
    assert_eq!(out.slave, -2);
    assert_eq!(out.output_offset, -200);
    assert!(!out.direction_forward);
}

#[test]
fn a_start_never_bumps_the_commanded_position() {
    // CamStartCount 40, started by a breakpoint when the source reaches 1000,
    // with the slave standing at 5000.
    let start = StartMode::Breakpoint {
        compare: Compare::AtLeast,
        value: 1000,
    };
    let mut a = CamAxis::new(three_entries(), incremental(start, 40)).unwrap();
    a.set_slave_position(5000).unwrap();
    a.arm().unwrap();
    for m in [0, 500, 999] {
        let out = a.tick(&TickInput {
            watch: m,
            ..TickInput::at(m, 1000)
        });
        assert_eq!(out.state, AxisState::Armed);
        assert_eq!(out.slave, 5000);
    }
    let out = a.tick(&TickInput {
        watch: 1000,
        ..TickInput::at(1000, 1000)
    });
    assert!(out.events.engaged);
    assert_eq!(out.slave, 5000);
    assert_eq!(out.pulses, 0);
    // CamInputOffset = 40 - 1000, CamOutputOffset = 5000 - table(40) = 5000 - 80.
    assert_eq!(out.input_offset, -960);
    assert_eq!(out.output_offset, 4920);
    assert_eq!(tick(&mut a, 1060).slave, 5120);
}

/// The typical command sequence: 32 sections of 10 counts (CamCounts 320),
/// start when axis 2 >= 1000, smooth stop requested when it reaches 1600.
fn sequence_axis() -> CamAxis<PointTable> {
    let pairs: Vec<(i64, i64)> = (0..=32).map(|i| (i * 10, i * i)).collect();
    let table = PointTable::from_pairs(&pairs).unwrap();
    let start = StartMode::Breakpoint {
        compare: Compare::AtLeast,
        value: 1000,
    };
    let mut a = CamAxis::new(table, incremental(start, 0)).unwrap();
    a.arm().unwrap();
    a
}

fn feed(a: &mut CamAxis<PointTable>, master: i64) -> ecam_engine::TickOutput {
    a.tick(&TickInput {
        watch: master,
        ..TickInput::at(master, 1_000_000)
    })
}

#[test]
fn smooth_stop_waits_for_the_end_of_the_table_forwards() {
    let mut a = sequence_axis();
    let mut m = 0;
    while m < 1600 {
        m += 7;
        feed(&mut a, m);
    }
    a.stop(StopKind::EndOfCycle);
    assert_eq!(a.state(), AxisState::Stopping);
    // Engaged at 1000 with start count 0: cycles end at 1320, 1640, ...
    let mut out = feed(&mut a, m);
    while out.state == AxisState::Stopping {
        m += 7;
        out = feed(&mut a, m);
    }
    assert_eq!(out.state, AxisState::Finished);
    assert!(out.events.stopped);
    // Two strokes of 1024 after two whole cycles.
    assert_eq!(out.slave, 2 * 1024);
    assert!((1640..1647).contains(&m));
    // The slave holds afterwards.
    assert_eq!(feed(&mut a, m + 500).slave, 2048);
}

#[test]
fn smooth_stop_backwards_stops_at_the_table_start() {
    let mut a = sequence_axis();
    for m in (0..=1500).step_by(5) {
        feed(&mut a, m);
    }
    a.stop(StopKind::EndOfCycle);
    // Backwards: the current cycle began at 1320.
    let mut m = 1500;
    let out = loop {
        m -= 9;
        let out = feed(&mut a, m);
        if out.state != AxisState::Stopping {
            break out;
        }
    };
    assert_eq!(out.slave, 1024);
    assert!(out.events.stopped);
}

#[test]
fn abrupt_stop_holds_the_commanded_position() {
    let mut a = sequence_axis();
    let mut last = 0;
    for m in (0..=1234).step_by(3) {
        last = feed(&mut a, m).slave;
    }
    a.stop(StopKind::Immediate);
    let out = feed(&mut a, 2000);
    assert_eq!(out.state, AxisState::Idle);
    assert!(out.events.stopped);
    assert_eq!(out.slave, last);
}

#[test]
fn evenly_spaced_buffer_table_from_ecam_core() {
    use ecam_core::UniformTable;
    // The document's own form: only the output column is stored.
    let table = UniformTable::new(vec![0, 100, 200], 100).unwrap();
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        master_align: MasterAlign::StartAt(0),
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    let _ = a.tick(&TickInput::at(0, 1_000_000));
    assert_eq!(a.tick(&TickInput::at(100, 1_000_000)).slave, 200);
    assert_eq!(a.tick(&TickInput::at(101, 1_000_000)).slave, 202);

    // A fractional spacing (100/3 counts per entry) stays exact over many cycles.
    let table = UniformTable::new(vec![0, 7, 50, 90], 100).unwrap();
    let mut a = CamAxis::new(table, config).unwrap();
    a.arm().unwrap();
    let _ = a.tick(&TickInput::at(0, 1_000_000));
    let out = a.tick(&TickInput::at(100 * 1_000_003, u32::MAX));
    assert_eq!(out.slave, 90 * 1_000_003);
    assert_eq!(out.cycle, 1_000_003);
}
