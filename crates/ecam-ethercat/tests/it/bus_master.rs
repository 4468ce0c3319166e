//! A master from the bus: drive 0 is a line shaft geared 1:1 to the
//! virtual master; the knife on drive 1 follows drive 0's actual position
//! as the drive reports it, not the command.

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign, TickInput};
use ecam_ethercat::emulation::DriveBehaviour;
use ecam_ethercat::line::{CamDrive, CamLine, LineState, Master};

use crate::emulated;
use crate::rotary_knife::knife_axis;

#[test]
fn knife_follows_the_line_shaft_actual_position() {
    let behaviour = DriveBehaviour {
        lag_cycles: 4,
        ..DriveBehaviour::default()
    };
    let (segment, _emulation) = emulated(2, behaviour);
    let shaft = CamAxis::new(
        PointTable::from_pairs(&[(0, 0), (1000, 1000)]).unwrap(),
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            slave_align: SlaveAlign::Relative,
            ..AxisConfig::default()
        },
    )
    .unwrap();
    let axes = vec![
        CamDrive {
            axis: shaft,
            drive: 0,
            master: Master::Virtual,
        },
        CamDrive {
            axis: knife_axis(),
            drive: 1,
            master: Master::DriveActual { position: 0 },
        },
    ];
    let mut line = CamLine::new(segment, axes, crate::LOST, std::time::Duration::ZERO).unwrap();
    line.virtual_speed = 9;
    line.start().unwrap();
    while line.state() != LineState::Running {
        line.cycle().unwrap();
    }
    let mut reference = knife_axis();
    reference.set_slave_position(0).unwrap();
    reference.arm().unwrap();
    for cycle in 0..3000 {
        // The master this cycle's tick reads: the shaft's last actual.
        let shaft_actual = line.segment().drives()[0].actual();
        let report = line.cycle().unwrap();
        assert!(line.new_faults().is_empty());
        let expected = reference.tick(&TickInput::at(shaft_actual, 1000)).slave;
        assert_eq!(line.outputs()[1].slave, expected, "cycle {cycle}");
        // The shaft trails the virtual master by a constant 7 cycles: the
        // drive's 4-cycle lag, its inputs one exchange late, the reading
        // taken before this cycle's master step, and the shaft cam's
        // first step after arming.
        if cycle > 10 {
            assert_eq!(shaft_actual, report.virtual_master - 9 * 7, "cycle {cycle}");
        }
    }
    assert!(
        line.segment().drives()[1].actual() > 8000,
        "the knife turned"
    );
}
