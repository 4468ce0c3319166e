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
    // The cycle the master starts in counts as the first (the start rule):
    // 1000 is that cycle's origin, where the table gives 0.
    assert_eq!(out.slave, 200);
}

#[test]
fn a_start_passed_backwards_starts_now_by_default() {
    let mut axis = armed_at_1000(MissedActivation::StartNow);
    let out = axis.tick(&TickInput::at(500, TICK_US));
    assert!(out.events.activation_missed);
    assert!(out.events.engaged);
    assert_eq!(out.state, AxisState::Running);
    assert_eq!(
        out.slave, -500,
        "engaged at 1000 (0) and followed back to 500"
    );
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

mod single_turn {
    //! On a single-turn master the activation position is a place in the
    //! turn: it comes round every turn, a pass across the wrap point counts
    //! by its direction, and a backward pass across it is a missed
    //! activation like any other.
    use core::num::NonZeroU64;

    use super::*;

    const TURN: u64 = 3600;

    /// A turn-long line (slave = master in the turn), started at 3500.
    fn armed_in_the_turn(policy: MissedActivation, at: i64) -> CamAxis<PointTable> {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            single_turn: NonZeroU64::new(TURN),
            start: StartMode::AtMasterPosition {
                position: 3500,
                after_edge: false,
            },
            ..AxisConfig::default()
        };
        let table = PointTable::from_pairs(&[(0, 0), (3600, 3600)]).unwrap();
        let mut axis = CamAxis::new(table, config).unwrap();
        axis.set_missed_activation(policy);
        let _ = axis.tick(&TickInput::at(at, TICK_US));
        axis.arm().unwrap();
        let _ = axis.tick(&TickInput::at(at, TICK_US));
        axis
    }

    #[test]
    fn a_start_place_already_passed_comes_round_in_the_next_turn() {
        // Armed at 3550: 3500 is behind; the master wraps (3590 → 10) and
        // reaches 3500 again a turn later: no miss, it engages there.
        let mut axis = armed_in_the_turn(MissedActivation::NextPass, 3550);
        for raw in [3590, 10, 1000, 2000, 3000, 3490] {
            let out = axis.tick(&TickInput::at(raw, TICK_US));
            assert_eq!(out.state, AxisState::Armed, "raw {raw}");
            assert!(!out.activation_missed);
        }
        let out = axis.tick(&TickInput::at(3510, TICK_US));
        assert!(out.events.engaged && !out.activation_missed);
        // Unwrapped 7110, a turn on: the start rule counts the turn it
        // engages in as the first, so the slave takes the table value.
        assert_eq!(out.slave, 3510);
    }

    #[test]
    fn a_forward_wrap_across_the_start_place_engages_there() {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            single_turn: NonZeroU64::new(TURN),
            start: StartMode::AtMasterPosition {
                position: 5,
                after_edge: false,
            },
            ..AxisConfig::default()
        };
        let table = PointTable::from_pairs(&[(0, 0), (3600, 3600)]).unwrap();
        let mut axis = CamAxis::new(table, config).unwrap();
        let _ = axis.tick(&TickInput::at(3590, TICK_US));
        axis.arm().unwrap();
        let _ = axis.tick(&TickInput::at(3590, TICK_US));
        // 3590 → 20 passes 3600 + 5 forwards.
        let out = axis.tick(&TickInput::at(20, TICK_US));
        assert!(out.events.engaged && !out.events.activation_missed);
        assert_eq!(
            out.slave, 20,
            "engaged at 5 in the next turn, followed to 20"
        );
    }

    #[test]
    fn a_backward_wrap_across_the_start_place_is_missed_next_pass() {
        // Armed at 100; the master turns back through 0 to 3400, passing
        // 3500 backwards across the wrap point.
        let mut axis = armed_in_the_turn(MissedActivation::NextPass, 100);
        let out = axis.tick(&TickInput::at(3400, TICK_US));
        assert!(out.events.activation_missed && out.activation_missed);
        assert_eq!(out.state, AxisState::Armed);
        let out = axis.tick(&TickInput::at(3450, TICK_US));
        assert!(!out.events.activation_missed && out.activation_missed);
        let out = axis.tick(&TickInput::at(3550, TICK_US));
        assert!(out.events.engaged && !out.activation_missed);
    }

    #[test]
    fn a_backward_wrap_across_the_start_place_is_missed_start_now() {
        let mut axis = armed_in_the_turn(MissedActivation::StartNow, 100);
        let out = axis.tick(&TickInput::at(3400, TICK_US));
        assert!(out.events.activation_missed && out.events.engaged);
        // Engaged at 3500 of the turn before (unwrapped −100): the start
        // rule puts the slave on the table value ahead of it in the table's
        // direction (3500, less than a turn), then it follows back to 3400.
        assert_eq!(out.state, AxisState::Running);
        assert_eq!(out.slave, 3400);
    }

    #[test]
    fn a_switch_place_passed_backwards_across_the_wrap_follows_the_policy() {
        let config = AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            single_turn: NonZeroU64::new(TURN),
            ..AxisConfig::default()
        };
        let table = PointTable::from_pairs(&[(0, 0), (3600, 3600)]).unwrap();
        let steep = PointTable::from_pairs(&[(0, 0), (3600, 7200)]).unwrap();
        let mut axis = CamAxis::new(table, config).unwrap();
        axis.set_missed_activation(MissedActivation::NextPass);
        axis.arm().unwrap();
        let _ = axis.tick(&TickInput::at(100, TICK_US));
        axis.switch_curve(
            steep,
            SwitchAt::MasterPosition {
                position: 3500,
                blend: None,
            },
        )
        .unwrap();
        let out = axis.tick(&TickInput::at(3400, TICK_US));
        assert!(out.events.activation_missed && !out.events.table_switched);
        assert!(axis.has_queued_curve());
        // Forwards across 3500 of the same turn: the switch takes effect.
        let out = axis.tick(&TickInput::at(3550, TICK_US));
        assert!(out.events.table_switched && !out.activation_missed);
        assert!(!axis.has_queued_curve());
    }
}
