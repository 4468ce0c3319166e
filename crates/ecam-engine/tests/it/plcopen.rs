//! The PLCopen-shaped face: MC_CamTableSelect / MC_CamIn / MC_CamOut.
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::Zoom;
use ecam_engine::plcopen::{
    ActivationMode, BufferMode, CamIn, CamInStartMode, CamOut, CamTableSelect, McCamAxis,
};

fn table() -> PointTable {
    PointTable::from_pairs(&[(0, 0), (400, 100), (1000, 600)]).unwrap()
}

#[test]
fn relative_master_starts_the_table_at_its_beginning() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.select(CamTableSelect {
        periodic: true,
        master_absolute: false,
        slave_absolute: false,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.set_slave_position(50).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let s = axis.tick(12_345, 1000);
    assert!(s.active && s.in_sync && s.busy);
    assert_eq!(s.output.slave, 50);
    assert_eq!(axis.tick(12_745, 1000).output.slave, 150);
    // Periodic with a stroke: one full table later the slave has moved 600.
    let s = axis.tick(13_345, 1000);
    assert!(s.end_of_profile);
    assert_eq!(s.output.slave, 650);
}

#[test]
fn absolute_offsets_and_scaling() {
    let mut axis = McCamAxis::new(table()).unwrap();
    let params = CamIn {
        master_offset: 400,
        slave_offset: 7,
        master_scaling: Zoom::new(1, 2).unwrap(),
        slave_scaling: Zoom::new(2, 1).unwrap(),
        start_mode: CamInStartMode::Absolute,
        ..CamIn::default()
    };
    axis.cam_in(&params).unwrap();
    // master 1100 → table input 550 + 400 = 950 → table 558.3 → ×2 + 7.
    assert_eq!(axis.tick(1100, 1_000_000).output.slave, 1124);
}

#[test]
fn non_periodic_table_ends_the_coupling() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.select(CamTableSelect {
        periodic: false,
        master_absolute: false,
        slave_absolute: true,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    assert!(axis.tick(0, 1_000_000).active);
    let s = axis.tick(1000, 1_000_000);
    assert!(s.end_of_profile);
    assert!(!s.active && !s.busy);
    assert_eq!(s.output.slave, 600);
    assert_eq!(axis.tick(3000, 1_000_000).output.slave, 600);
}

#[test]
fn ramp_in_reports_in_sync_when_done_and_cam_out_holds() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::RampIn {
            distance: NonZeroU64::new(100).unwrap(),
        },
        ..CamIn::default()
    })
    .unwrap();
    assert!(!axis.tick(500, 1_000_000).in_sync);
    assert!(!axis.tick(550, 1_000_000).in_sync);
    let s = axis.tick(600, 1_000_000);
    assert!(s.in_sync);
    // The same inputs again while engaged change nothing.
    axis.cam_in(&CamIn::default()).unwrap();
    axis.cam_out(CamOut::Hold);
    let held = axis.tick(700, 1_000_000);
    assert!(!held.active && !held.in_sync);
    assert_eq!(held.output.slave, s.output.slave);
}

#[test]
fn cam_in_while_engaged_switches_tables_aborting_with_a_blend() {
    let line = |slope: i64| PointTable::from_pairs(&[(0, 0), (1000, 1000 * slope)]).unwrap();
    let mut axis = McCamAxis::new(line(1)).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    for m in 0..=500 {
        let _ = axis.tick(m, 1000);
    }
    axis.select_table(line(3), CamTableSelect::default())
        .unwrap();
    let params = CamIn {
        blend: NonZeroU64::new(200).unwrap(),
        ..CamIn::default()
    };
    axis.cam_in(&params).unwrap();
    let mut last = 500;
    for m in 501..=800 {
        let s = axis.tick(m, 1000);
        let step = s.output.slave - last;
        assert!((1..=3).contains(&step), "master {m}: step {step}");
        assert_eq!(s.in_sync, m >= 700, "master {m}");
        last = s.output.slave;
    }
    assert_eq!(axis.tick(801, 1000).output.slave - last, 3);
    assert!(axis.take_retired_table().is_some());
}

#[test]
fn cam_in_while_engaged_buffered_switches_at_the_seam() {
    let line = |slope: i64| PointTable::from_pairs(&[(0, 0), (1000, 1000 * slope)]).unwrap();
    let mut axis = McCamAxis::new(line(1)).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let _ = axis.tick(300, 1_000_000);
    axis.select_table(line(2), CamTableSelect::default())
        .unwrap();
    axis.cam_in(&CamIn {
        buffer_mode: BufferMode::Buffered,
        ..CamIn::default()
    })
    .unwrap();
    assert_eq!(axis.tick(900, 1_000_000).output.slave, 900);
    // Blended over CamIn::blend (1000 counts) from the last count before
    // the seam: the velocity goes from 1 to 2 per count without a step.
    let s = axis.tick(1100, 1_000_000);
    assert!(s.output.events.table_switched);
    assert_eq!(s.output.slave, 1101);
    let a = axis.tick(2100, 1_000_000).output.slave;
    assert_eq!(axis.tick(2200, 1_000_000).output.slave - a, 200);
}

#[test]
fn cam_in_while_engaged_ramps_offsets_in_and_activation_at_a_position() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn {
        activation: ActivationMode::AtMasterPosition(100),
        ..CamIn::default()
    })
    .unwrap();
    assert!(!axis.tick(50, 1_000_000).active);
    assert!(axis.tick(150, 1_000_000).active);
    axis.cam_in(&CamIn {
        slave_offset: 40,
        activation: ActivationMode::AtMasterPosition(100),
        blend: NonZeroU64::new(100).unwrap(),
        ..CamIn::default()
    })
    .unwrap();
    let s = axis.tick(200, 1_000_000);
    assert!(!s.in_sync, "ramping the offset in");
    // Past the ramp: exactly the table (400 → 100) plus the new offset.
    let s = axis.tick(400, 1_000_000);
    assert!(s.in_sync);
    assert_eq!(s.output.slave, 100 + 40);
}

#[test]
fn in_sync_waits_for_the_pulse_backlog() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    // 400 counts in 100 µs: 100 pulses owed against 20 per tick at 200 kHz.
    let s = axis.tick(400, 100);
    assert!(s.output.following && !s.in_sync);
    let mut s = s;
    for _ in 0..10 {
        s = axis.tick(400, 100);
    }
    assert!(s.in_sync);
}

/// PLCopen: periodic with an absolute slave re-evaluates the table each
/// cycle (the slave jumps back where first ≠ last); relative accumulates.
#[test]
fn periodic_absolute_re_evaluates_relative_accumulates() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    assert_eq!(axis.tick(999, 1_000_000).output.slave, 599);
    assert_eq!(axis.tick(1400, 1_000_000).output.slave, 100);
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::Relative,
        ..CamIn::default()
    })
    .unwrap();
    let _ = axis.tick(0, 1_000_000);
    assert_eq!(axis.tick(1400, 1_000_000).output.slave, 700);
}

/// PLCopen: non-periodic with an absolute master runs over the table's own
/// master range, then keeps the slave coupled at the last value.
#[test]
fn non_periodic_absolute_master_stays_coupled_at_the_end() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.select(CamTableSelect {
        periodic: false,
        master_absolute: true,
        slave_absolute: true,
        ..CamTableSelect::default()
    })
    .unwrap();
    axis.cam_in(&CamIn::default()).unwrap();
    let s = axis.tick(400, 1_000_000);
    assert!(!s.end_of_profile);
    assert_eq!(s.output.slave, 100);
    let s = axis.tick(1500, 1_000_000);
    assert!(s.end_of_profile && s.active && s.in_sync);
    assert_eq!(s.output.slave, 600);
    let s = axis.tick(700, 1_000_000);
    assert!(!s.end_of_profile && s.active);
    assert_eq!(s.output.slave, 350);
}

#[test]
fn cam_out_at_end_of_cycle_finishes_the_cycle() {
    let mut axis = McCamAxis::new(table()).unwrap();
    axis.cam_in(&CamIn {
        start_mode: CamInStartMode::Relative,
        ..CamIn::default()
    })
    .unwrap();
    let _ = axis.tick(0, 1_000_000);
    let _ = axis.tick(400, 1_000_000);
    axis.cam_out_at_end_of_cycle();
    assert!(axis.tick(900, 1_000_000).active);
    let s = axis.tick(1300, 1_000_000);
    assert!(!s.active);
    assert_eq!(s.output.slave, 600);
}

#[test]
fn cam_in_with_master_sync_position() {
    use ecam_engine::plcopen::SyncAt;
    let line = PointTable::from_pairs(&[(0, 0), (1000, 2000)]).unwrap();
    let mut axis = McCamAxis::new(line).unwrap();
    axis.cam_in(&CamIn {
        sync_at: Some(SyncAt {
            position: 3000,
            start_distance: NonZeroU64::new(500).unwrap(),
            forward: true,
        }),
        ..CamIn::default()
    })
    .unwrap();
    for m in (2000..=3200).step_by(10) {
        let s = axis.tick(m, 1_000_000);
        assert_eq!(s.active, m >= 2500, "master {m}");
        assert_eq!(s.in_sync, m >= 3000, "master {m}");
    }
}

mod blocks {
    use super::*;
    use ecam_engine::EngineError;
    use ecam_engine::plcopen_blocks::{CamInBlock, TableSelectBlock};

    #[test]
    fn execute_edges_latched_errors_and_command_aborted() {
        let mut axis = McCamAxis::new(table()).unwrap();
        let mut first = CamInBlock::default();
        let mut second = CamInBlock::default();
        let params = CamIn::default();
        let s = axis.tick(0, 1_000_000);
        let out = first.call(&mut axis, true, &params, &s);
        assert!(out.busy && !out.error);
        let s = axis.tick(100, 1_000_000);
        let out = first.call(&mut axis, true, &params, &s);
        assert!(out.active && out.in_sync && out.busy);

        // A second MC_CamIn that cannot be done (offset and scaling at once):
        // its error latches until its next rising edge; the first keeps control.
        let bad = CamIn {
            slave_offset: 5,
            slave_scaling: Zoom::new(2, 1).unwrap(),
            ..CamIn::default()
        };
        let out = second.call(&mut axis, true, &bad, &s);
        assert_eq!(out.error_id, Some(EngineError::Busy));
        let s = axis.tick(200, 1_000_000);
        assert!(second.call(&mut axis, false, &bad, &s).error);
        assert!(first.call(&mut axis, true, &params, &s).active);

        // A second MC_CamIn that is accepted aborts the first.
        let good = CamIn {
            slave_offset: 5,
            ..CamIn::default()
        };
        let out = second.call(&mut axis, true, &good, &s);
        assert!(!out.error && out.busy);
        let s = axis.tick(300, 1_000_000);
        let out = first.call(&mut axis, true, &params, &s);
        assert!(out.command_aborted && !out.busy && !out.active);
        // Holding Execute does not issue it again.
        let out = first.call(&mut axis, true, &params, &s);
        assert!(out.command_aborted);

        // MC_CamOut aborts the second.
        axis.cam_out(CamOut::Hold);
        let s = axis.tick(400, 1_000_000);
        assert!(second.call(&mut axis, true, &good, &s).command_aborted);
    }

    #[test]
    fn table_select_is_done_on_the_rising_edge() {
        let mut axis = McCamAxis::new(table()).unwrap();
        let mut block = TableSelectBlock::default();
        let mut next = Some(PointTable::from_pairs(&[(0, 0), (100, 50)]).unwrap());
        let out = block.call(&mut axis, true, &mut next, CamTableSelect::default());
        assert!(out.done && !out.error);
        assert!(next.is_none());
        // Held high: nothing more happens, Done stays.
        assert!(
            block
                .call(&mut axis, true, &mut next, CamTableSelect::default())
                .done
        );
        assert!(axis.take_retired_table().is_some());
    }
}

mod inputs {
    //! The facade inputs not covered above: ExecutionMode, the refused
    //! blending modes, ActivationMode next cycle, ramp limits, scalings
    //! changed while engaged.
    use core::num::{NonZeroU32, NonZeroU64};

    use ecam_core::PointTable;
    use ecam_engine::plcopen::{
        ActivationMode, BufferMode, CamIn, CamInStartMode, CamTableSelect, ExecutionMode, McCamAxis,
    };
    use ecam_engine::plcopen_blocks::TableSelectBlock;
    use ecam_engine::{EngineError, RampDirection, RampInLimits, Zoom};

    fn line(slope: i64) -> PointTable {
        PointTable::from_pairs(&[(0, 0), (1000, 1000 * slope)]).unwrap()
    }

    #[test]
    fn execution_mode_queued_takes_over_at_the_seam_busy_until_then() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.cam_in(&CamIn {
            start_mode: CamInStartMode::Relative,
            ..CamIn::default()
        })
        .unwrap();
        let _ = axis.tick(0, 1000);
        let _ = axis.tick(300, 1000);
        let mut block = TableSelectBlock::default();
        let mut next = Some(line(2));
        let queued = CamTableSelect {
            execution_mode: ExecutionMode::Queued,
            ..CamTableSelect::default()
        };
        let out = block.call(&mut axis, true, &mut next, queued);
        assert!(out.busy && !out.done && !out.error);
        assert!(axis.has_queued_table());
        assert_eq!(axis.tick(900, 1000).output.slave, 900);
        assert!(block.call(&mut axis, true, &mut next, queued).busy);
        // No MC_CamIn needed: the table takes over at the seam by itself.
        let s = axis.tick(1100, 1000);
        assert!(s.output.events.table_switched);
        assert_eq!(s.output.slave, 1200);
        let out = block.call(&mut axis, true, &mut next, queued);
        assert!(out.done && !out.busy);
    }

    #[test]
    fn execution_mode_immediate_waits_for_the_next_cam_in() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.cam_in(&CamIn::default()).unwrap();
        let _ = axis.tick(100, 1000);
        let mut block = TableSelectBlock::default();
        let mut next = Some(line(2));
        let out = block.call(&mut axis, true, &mut next, CamTableSelect::default());
        assert!(out.done && !out.busy);
        assert!(!axis.has_queued_table());
        // Still the old table until MC_CamIn switches.
        assert_eq!(axis.tick(1500, 1000).output.slave, 500);
    }

    #[test]
    fn table_select_errors_latch_until_the_next_edge() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.select(CamTableSelect {
            periodic: false,
            ..CamTableSelect::default()
        })
        .unwrap();
        axis.cam_in(&CamIn::default()).unwrap();
        let _ = axis.tick(100, 1000);
        let mut block = TableSelectBlock::default();
        let mut next = Some(line(2));
        // Queued on a non-periodic cam: no seam to wait for.
        let queued = CamTableSelect {
            periodic: false,
            execution_mode: ExecutionMode::Queued,
            ..CamTableSelect::default()
        };
        let out = block.call(&mut axis, true, &mut next, queued);
        assert!(out.error && !out.done && !out.busy);
        assert_eq!(out.error_id, Some(EngineError::NoSeam));
        assert!(block.call(&mut axis, true, &mut next, queued).error);
        // Another interpretation while engaged is refused.
        let _ = block.call(&mut axis, false, &mut next, queued);
        let mut next = Some(line(2));
        let out = block.call(&mut axis, true, &mut next, CamTableSelect::default());
        assert_eq!(out.error_id, Some(EngineError::Busy));
    }

    #[test]
    fn blending_buffer_modes_are_refused_with_the_supported_ones_named() {
        for mode in [
            BufferMode::BlendingLow,
            BufferMode::BlendingPrevious,
            BufferMode::BlendingNext,
            BufferMode::BlendingHigh,
        ] {
            let mut axis = McCamAxis::new(line(1)).unwrap();
            let err = axis
                .cam_in(&CamIn {
                    buffer_mode: mode,
                    ..CamIn::default()
                })
                .unwrap_err();
            assert_eq!(err, EngineError::UnsupportedBufferMode);
            let text = err.to_string();
            assert!(
                text.contains("aborting") && text.contains("buffered"),
                "{text}"
            );
            assert!(!axis.tick(0, 1000).busy, "nothing changed");
        }
    }

    #[test]
    fn activation_next_cycle_idle_engages_at_the_next_cycle_start() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        let _ = axis.tick(1234, 1000);
        axis.cam_in(&CamIn {
            activation: ActivationMode::NextCycle,
            master_offset: 100,
            ..CamIn::default()
        })
        .unwrap();
        // Table input = master + 100: cycle starts at masters 900, 1900, ...
        for m in (1240..1900).step_by(20) {
            assert!(!axis.tick(m, 1000).active, "master {m}");
        }
        let s = axis.tick(1910, 1000);
        assert!(s.active && s.output.events.engaged);
        assert_eq!(s.output.slave, 10);
    }

    #[test]
    fn activation_next_cycle_engaged_switches_at_the_seam() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.cam_in(&CamIn {
            start_mode: CamInStartMode::Relative,
            ..CamIn::default()
        })
        .unwrap();
        let _ = axis.tick(0, 1000);
        let _ = axis.tick(200, 1000);
        axis.select_table(line(2), CamTableSelect::default())
            .unwrap();
        axis.cam_in(&CamIn {
            start_mode: CamInStartMode::Relative,
            activation: ActivationMode::NextCycle,
            ..CamIn::default()
        })
        .unwrap();
        assert!(!axis.tick(999, 1000).output.events.table_switched);
        assert!(axis.tick(1001, 1000).output.events.table_switched);
    }

    #[test]
    fn ramp_limits_keep_the_direction() {
        // Absolute slave at 0, table value 500 at master 500: ramp_in_neg
        // must not move forwards, so it closes the gap a stroke lower.
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.select(CamTableSelect {
            slave_absolute: true,
            ..CamTableSelect::default()
        })
        .unwrap();
        let _ = axis.tick(500, 1000);
        axis.cam_in(&CamIn {
            start_mode: CamInStartMode::Relative,
            ramp_limits: Some(RampInLimits {
                max_jerk: None,
                max_velocity: NonZeroU32::new(100_000).unwrap(),
                max_acceleration: NonZeroU64::new(10_000_000).unwrap(),
                direction: RampDirection::Positive,
            }),
            ..CamIn::default()
        })
        .unwrap();
        let mut last = axis.tick(500, 1000).output.slave;
        let mut m = 500;
        for _ in 0..2000 {
            m += 1;
            let s = axis.tick(m, 1000);
            assert!(s.output.slave >= last, "master {m}: went back");
            last = s.output.slave;
        }
        assert!(axis.tick(m, 1000).in_sync);
    }

    #[test]
    fn scalings_changed_in_sync_are_ramped_not_stepped() {
        let mut axis = McCamAxis::new(line(1)).unwrap();
        axis.cam_in(&CamIn {
            start_mode: CamInStartMode::Relative,
            ..CamIn::default()
        })
        .unwrap();
        let _ = axis.tick(0, 1000);
        let _ = axis.tick(100, 1000);
        let slave = CamIn {
            start_mode: CamInStartMode::Relative,
            slave_scaling: Zoom::new(2, 1).unwrap(),
            blend: NonZeroU64::new(200).unwrap(),
            ..CamIn::default()
        };
        axis.cam_in(&slave).unwrap();
        let mut last = 100;
        for m in 101..=400 {
            let s = axis.tick(m, 1000);
            // The mix of old and new adds a little while the weight moves
            // (the gap between them grows with the position), never a step.
            let step = s.output.slave - last;
            assert!((1..=4).contains(&step), "master {m}: step {step}");
            last = s.output.slave;
        }
        assert_eq!(axis.tick(401, 1000).output.slave - last, 2);
        // Master scaling: phase kept, velocity blended to the new ratio.
        let master = CamIn {
            master_scaling: Zoom::new(1, 2).unwrap(),
            ..slave
        };
        axis.cam_in(&master).unwrap();
        let mut last = axis.tick(401, 1000).output.slave;
        for m in 402..=800 {
            let s = axis.tick(m, 1000);
            let step = s.output.slave - last;
            assert!((0..=2).contains(&step), "master {m}: step {step}");
            last = s.output.slave;
        }
        let a = axis.tick(1000, 1000).output.slave;
        assert_eq!(axis.tick(1100, 1000).output.slave - a, 100);
    }
}
