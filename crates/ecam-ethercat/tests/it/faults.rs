//! Fault reaction: a drive fault injected mid-run stops the line and is
//! reported with its code; a fault reset and a new start recover. Cable
//! loss: the working counter drops, the lost drives are reported, and the
//! line runs again once the cable is back and the faults are reset.

use ecam_engine::drive::{AxisDrive, DriveFault};
use ecam_ethercat::cia402::DriveState;
use ecam_ethercat::emulation::DriveBehaviour;
use ecam_ethercat::line::{CamDrive, CamLine, LineFault, LineState, Master};

use crate::emulated;
use crate::rotary_knife::knife_axis;

fn running_line(
    drives: usize,
) -> (
    CamLine<ecam_core::PointTable>,
    std::sync::Arc<std::sync::Mutex<ecam_ethercat::emulation::EmulatedSegment>>,
) {
    let (segment, emulation) = emulated(drives, DriveBehaviour::default());
    let axes = (0..drives)
        .map(|drive| CamDrive {
            axis: knife_axis(),
            drive,
            master: Master::Virtual,
        })
        .collect();
    let mut line = CamLine::new(segment, axes).unwrap();
    line.virtual_speed = 11;
    start(&mut line);
    (line, emulation)
}

fn start(line: &mut CamLine<ecam_core::PointTable>) {
    line.start().unwrap();
    for _ in 0..20 {
        line.cycle().unwrap();
        if line.state() == LineState::Running {
            return;
        }
    }
    panic!(
        "line did not start: {:?}",
        line.segment()
            .drives()
            .iter()
            .map(|d| d.state())
            .collect::<Vec<_>>()
    );
}

#[test]
fn injected_fault_stops_reports_and_recovers() {
    let (mut line, emulation) = running_line(3);
    for _ in 0..500 {
        assert!(line.cycle().unwrap().new_faults.is_empty());
    }
    emulation
        .lock()
        .unwrap()
        .esc_mut(1)
        .unwrap()
        .drive_mut()
        .inject_fault(0x2310);
    // The drive faults in its next cycle; the master sees it one exchange
    // later and stops the line in that cycle.
    let mut seen = None;
    for cycle in 0..5 {
        let report = line.cycle().unwrap();
        if !report.new_faults.is_empty() {
            seen = Some((cycle, report.new_faults));
            break;
        }
    }
    let (_, faults) = seen.expect("fault not reported");
    assert_eq!(
        faults,
        vec![LineFault {
            drive: Some(1),
            fault: DriveFault::Drive { code: 0x2310 }
        }]
    );
    assert_eq!(line.state(), LineState::Faulted);
    // Stop: the cams hold, the other drives quick-stop, nothing moves.
    let held: Vec<i64> = emulation
        .lock()
        .unwrap()
        .escs()
        .iter()
        .map(|e| i64::from(e.drive().actual()))
        .collect();
    for _ in 0..20 {
        line.cycle().unwrap();
    }
    let emu = emulation.lock().unwrap();
    for (i, esc) in emu.escs().iter().enumerate() {
        assert_eq!(
            i64::from(esc.drive().actual()),
            held[i],
            "drive {i} moved after the stop"
        );
        let expected = if i == 1 {
            DriveState::Fault
        } else {
            DriveState::QuickStopActive
        };
        assert_eq!(esc.drive().state(), expected, "drive {i}");
    }
    drop(emu);
    assert_eq!(
        line.segment().drives()[1].status().fault,
        Some(DriveFault::Drive { code: 0x2310 })
    );
    // A start while faulted is refused.
    assert!(line.start().is_err());

    // Recover: fault reset, then start again.
    line.reset().unwrap();
    for _ in 0..5 {
        line.cycle().unwrap();
    }
    assert_eq!(
        line.segment().drives()[1].state(),
        DriveState::SwitchOnDisabled
    );
    assert_eq!(line.segment().drives()[1].inputs().error_code, 0);
    start(&mut line);
    let before: Vec<i64> = line.segment().drives().iter().map(|d| d.actual()).collect();
    for _ in 0..300 {
        assert!(line.cycle().unwrap().new_faults.is_empty());
    }
    for (i, d) in line.segment().drives().iter().enumerate() {
        assert!(d.actual() > before[i], "drive {i} runs again");
        assert_eq!(d.status().fault, None);
    }
}

#[test]
fn cable_loss_is_detected_reported_and_recovered() {
    let (mut line, emulation) = running_line(4);
    for _ in 0..200 {
        assert!(!line.cycle().unwrap().bus.working_counter_error());
    }
    // Pull the cable between drive 1 and drive 2.
    emulation.lock().unwrap().cut_cable_before(2);
    let report = line.cycle().unwrap();
    assert!(report.bus.working_counter_error());
    assert_eq!(report.bus.working_counter, 6, "two drives answer (3 each)");
    assert_eq!(report.bus.expected_working_counter, 12);
    assert_eq!(report.bus.unreachable, 2);
    let lost: Vec<Option<usize>> = report.new_faults.iter().map(|f| f.drive).collect();
    assert_eq!(lost, vec![Some(2), Some(3)]);
    assert!(
        report
            .new_faults
            .iter()
            .all(|f| f.fault == DriveFault::Communication)
    );
    assert_eq!(line.state(), LineState::Faulted);
    // Every cycle without the cable keeps reporting it.
    for _ in 0..10 {
        let r = line.cycle().unwrap();
        assert!(r.bus.working_counter_error());
        assert_eq!(
            line.segment().drives()[3].status().fault,
            Some(DriveFault::Communication)
        );
    }
    // Cable back: reachable again, then reset and restart.
    emulation.lock().unwrap().reconnect();
    line.cycle().unwrap();
    assert!(line.segment().drives().iter().all(|d| d.reachable()));
    line.reset().unwrap();
    for _ in 0..5 {
        line.cycle().unwrap();
    }
    start(&mut line);
    for _ in 0..100 {
        let r = line.cycle().unwrap();
        assert!(!r.bus.working_counter_error());
        assert!(r.new_faults.is_empty());
    }
}

#[test]
fn no_reply_at_all_is_a_lost_frame() {
    let (mut line, emulation) = running_line(2);
    emulation.lock().unwrap().cut_cable_before(0);
    let report = line.cycle().unwrap();
    assert!(report.bus.frame_lost);
    assert_eq!(report.bus.unreachable, 2);
    assert_eq!(report.new_faults.len(), 2);
    assert_eq!(line.state(), LineState::Faulted);
}
