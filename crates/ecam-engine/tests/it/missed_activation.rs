//! An activation position (a start or a table switch at a master
//! position) passed backwards: reported as an event and a status, handled
//! as the caller's `MissedActivation` policy says.

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, Coupling, MissedActivation, StartMode, SwitchAt, TickInput,
};

const TICK_US: u32 = 100;

fn line(slope: i64) -> PointTable {
    PointTable::from_pairs(&[(0, 0), (1000, 1000 * slope)]).unwrap()
}

fn armed_at_1000(policy: MissedActivation) -> CamAxis<PointTable> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        start: StartMode::AtMasterPosition {
            position: 1000,
            after_edge: false,
        },
        ..AxisConfig::default()
    };
    let mut axis = CamAxis::new(line(1), config).unwrap();
    axis.set_missed_activation(policy);
    let _ = axis.tick(&TickInput::at(1500, TICK_US));
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(1500, TICK_US));
    axis
}

#[test]
fn a_start_passed_backwards_waits_for_the_next_forward_pass() {
    let mut axis = armed_at_1000(MissedActivation::NextPass);
    let out = axis.tick(&TickInput::at(500, TICK_US));
    assert!(out.events.activation_missed);
    assert!(out.activation_missed);
    assert_eq!(out.state, AxisState::Armed);
    let out = axis.tick(&TickInput::at(600, TICK_US));
    assert!(!out.events.activation_missed);
    assert!(out.activation_missed, "the status stays until the start");
    let out = axis.tick(&TickInput::at(1200, TICK_US));
    assert!(out.events.engaged);
    assert!(!out.activation_missed);
    assert_eq!(out.slave, 1200);
}

#[test]
fn a_start_passed_backwards_starts_now_by_default() {
    let mut axis = armed_at_1000(MissedActivation::StartNow);
    let out = axis.tick(&TickInput::at(500, TICK_US));
    assert!(out.events.activation_missed);
    assert!(out.events.engaged);
    assert_eq!(out.state, AxisState::Running);
    assert_eq!(out.slave, 500, "engaged at 1000 and followed back to 500");
}

#[test]
fn a_switch_passed_backwards_follows_the_policy() {
    for policy in [MissedActivation::NextPass, MissedActivation::StartNow] {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(line(1), config).unwrap();
        axis.set_missed_activation(policy);
        axis.arm().unwrap();
        let _ = axis.tick(&TickInput::at(500, TICK_US));
        axis.switch_curve(
            line(2),
            SwitchAt::MasterPosition {
                position: 300,
                blend: None,
            },
        )
        .unwrap();
        let out = axis.tick(&TickInput::at(200, TICK_US));
        assert!(out.events.activation_missed);
        assert!(out.activation_missed);
        match policy {
            MissedActivation::NextPass => {
                assert!(!out.events.table_switched);
                assert_eq!(out.slave, 200);
                let out = axis.tick(&TickInput::at(400, TICK_US));
                assert!(out.events.table_switched);
                assert!(!out.activation_missed);
                assert_eq!(out.slave, 300 + 2 * 100);
            }
            MissedActivation::StartNow => {
                assert!(out.events.table_switched);
                assert_eq!(out.slave, 300 - 2 * 100);
            }
        }
    }
}
