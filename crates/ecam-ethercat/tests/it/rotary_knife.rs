//! 10,000 cycles of a rotary-knife cam on 8 emulated drives: every target
//! the drives receive is the engine's commanded position, exactly, and
//! every actual position is that target `lag` cycles later.

use ecam_core::PointTable;
use ecam_core::generator::rotary_cut::{Params, generate};
use ecam_engine::drive::AxisDrive;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, TickInput};
use ecam_ethercat::emulation::DriveBehaviour;
use ecam_ethercat::line::{CamDrive, CamLine, LineState, Master};

pub(crate) fn knife_axis() -> CamAxis<PointTable> {
    let table = generate(&Params::default()).unwrap().table;
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    CamAxis::new(table, config).unwrap()
}

#[test]
fn ten_thousand_cycles_on_eight_drives_are_exact() {
    const LAG: usize = 3;
    let behaviour = DriveBehaviour {
        lag_cycles: LAG,
        ..DriveBehaviour::default()
    };
    let (segment, emulation) = crate::emulated(8, behaviour);
    let axes = (0..8)
        .map(|drive| CamDrive {
            axis: knife_axis(),
            drive,
            master: Master::Virtual,
        })
        .collect();
    let mut line = CamLine::new(segment, axes, crate::LOST, std::time::Duration::ZERO).unwrap();
    // 7 master counts per 1 ms cycle, uneven against the 3000-count cut.
    line.virtual_speed = 7;
    line.start().unwrap();
    let mut guard = 0;
    while line.state() != LineState::Running {
        line.cycle().unwrap();
        guard += 1;
        assert!(
            guard < 20,
            "drives did not enable: {:?}",
            line.segment().drives()[0].state()
        );
    }
    // The same cam on the bare engine, fed the same master positions.
    let mut reference = knife_axis();
    reference.set_slave_position(0).unwrap();
    reference.arm().unwrap();
    let mut history: Vec<Vec<i64>> = Vec::new();
    for cycle in 0..10_000 {
        let report = line.cycle().unwrap();
        let expected = reference
            .tick(&TickInput::at(report.virtual_master, 1000))
            .slave;
        assert!(
            line.new_faults().is_empty(),
            "cycle {cycle}: {:?}",
            line.new_faults()
        );
        assert!(
            !report.bus.working_counter_error(),
            "cycle {cycle}: {:?}",
            report.bus
        );
        let commanded: Vec<i64> = line.outputs().iter().map(|o| o.slave).collect();
        assert!(
            commanded.iter().all(|&c| c == expected),
            "cycle {cycle}: {commanded:?} vs {expected}"
        );
        let emulation = emulation.lock().unwrap();
        for (i, esc) in emulation.escs().iter().enumerate() {
            assert_eq!(
                i64::from(esc.drive().target()),
                commanded[i],
                "cycle {cycle} drive {i}"
            );
            if history.len() >= LAG {
                let sent = history[history.len() - LAG][i];
                assert_eq!(
                    i64::from(esc.drive().actual()),
                    sent,
                    "cycle {cycle} drive {i} actual"
                );
            }
        }
        history.push(commanded);
    }
    // 70,000 master counts: 23 cuts of 3000 and 1000 counts into the
    // next; each cut turns the knife by 1000 pulses.
    assert_eq!(line.virtual_master(), 70_000);
    assert!(reference.commanded() > 23 * 1000 && reference.commanded() < 24 * 1000);
    // The master side saw the same actual positions (one exchange late).
    for (i, drive) in line.segment().drives().iter().enumerate() {
        let status = drive.status();
        assert_eq!(status.actual, history[history.len() - LAG][i]);
        assert_eq!(status.fault, None);
    }
}

/// 64 drives: the process image no longer fits one frame, so ethercrab
/// splits it; the cams stay exact and the working counter stays whole.
#[test]
fn sixty_four_drives_over_two_frames_stay_exact() {
    let behaviour = DriveBehaviour {
        lag_cycles: 1,
        ..DriveBehaviour::default()
    };
    let (segment, emulation) = crate::emulated(64, behaviour);
    let axes = (0..64)
        .map(|drive| CamDrive {
            axis: knife_axis(),
            drive,
            master: Master::Virtual,
        })
        .collect();
    let mut line = CamLine::new(segment, axes, crate::LOST, std::time::Duration::ZERO).unwrap();
    line.virtual_speed = 5;
    line.start().unwrap();
    while line.state() != LineState::Running {
        line.cycle().unwrap();
        assert_ne!(line.state(), LineState::Faulted, "{:?}", line.faults());
    }
    let mut previous: Option<Vec<i64>> = None;
    for cycle in 0..300 {
        let report = line.cycle().unwrap();
        assert!(
            !report.bus.working_counter_error(),
            "cycle {cycle}: {:?}",
            report.bus
        );
        let commanded: Vec<i64> = line.outputs().iter().map(|o| o.slave).collect();
        let emulation = emulation.lock().unwrap();
        for (i, esc) in emulation.escs().iter().enumerate() {
            assert_eq!(
                i64::from(esc.drive().target()),
                commanded[i],
                "cycle {cycle} drive {i}"
            );
            if let Some(previous) = &previous {
                assert_eq!(
                    i64::from(esc.drive().actual()),
                    previous[i],
                    "cycle {cycle} drive {i}"
                );
            }
        }
        previous = Some(commanded);
    }
}
