//! The master sources of documents 002 and 003: a wrapping 32-bit counter,
//! the K × 100 µs time base, and another axis' commanded or actual position.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU32;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, TickInput, TimeBase, Unwrap32};

fn line(stroke: i64) -> PointTable {
    PointTable::from_pairs(&[(0, 0), (1000, stroke)]).unwrap()
}

fn repeat_axis(stroke: i64, hz: i64) -> CamAxis<PointTable> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        max_frequency_hz: hz,
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(line(stroke), config).unwrap();
    axis.arm().unwrap();
    axis
}

#[test]
fn counter_wrapping_through_zero_downwards() {
    let mut counter = Unwrap32::new(1500);
    let mut axis = repeat_axis(2000, 0);
    // Started half a cycle into its second cycle: the table value there.
    assert_eq!(
        axis.tick(&TickInput::at(counter.position(), 1_000_000))
            .emitted,
        1000
    );
    // Count down 3000 through zero: the raw counter wraps to 0xFFFF_F448.
    let master = counter.update(1500u32.wrapping_sub(3000));
    assert_eq!(master, -1500);
    let out = axis.tick(&TickInput::at(master, 1_000_000));
    assert_eq!(out.slave, -5000);
    assert_eq!(out.pulses, -6000);
}

#[test]
fn time_base_k10_drives_one_count_per_millisecond() {
    let mut time = TimeBase::new(NonZeroU32::new(10).unwrap());
    let mut axis = repeat_axis(500, 0);
    let mut out = axis.tick(&TickInput::at(time.position(), 100));
    // 2.5 s of 100 µs ticks: 2500 counts, 2.5 cycles of 500 pulses.
    for _ in 0..25_000 {
        out = axis.tick(&TickInput::at(time.advance(100), 100));
    }
    assert_eq!(out.master, 2500);
    assert_eq!(out.slave, 1250);
    assert_eq!(out.emitted, 1250);
}

#[test]
fn another_axis_commanded_or_actual_position_as_master() {
    // Axis A follows a time-like master; B follows A's commanded position,
    // C follows A's actual (emitted, frequency-limited) output.
    let mut a = repeat_axis(3000, 100_000);
    let mut b = repeat_axis(1000, 0);
    let mut c = repeat_axis(1000, 0);
    for i in 0..=200 {
        let out_a = a.tick(&TickInput::at(i * 50, 1000));
        let out_b = b.tick(&TickInput::at(out_a.slave, 1000));
        let out_c = c.tick(&TickInput::at(out_a.emitted, 1000));
        assert_eq!(out_b.slave, out_a.slave);
        assert_eq!(out_c.slave, out_a.emitted);
    }
    // A commands 150 pulses per 1 ms tick but may only send 100.
    assert!(a.status().backlog > 0);
    assert!(c.status().slave < b.status().slave);
}
