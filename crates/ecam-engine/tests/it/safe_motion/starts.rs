//! Safe motion at the edges of a run: starts and restarts with the master
//! and the slave anywhere (the start rule, docs/engine.md).
//!
//! Over random monotonic tables (rising or falling), slave zooms of either
//! sign, master and slave start positions, every start mode, and the way
//! each face sets the engine up (the PLC's cyclic, noncyclic and HFFFF
//! cams, the motion processor's bumpless cam, the motion controller's
//! Repeat cam on a linear or single-turn master, the engine API's absolute
//! starts, the PLCopen facade's relative, bumpless and ramp-in starts),
//! with the master running forwards and a stop and restart in the middle:
//! - no tick sends a pulse against the cam's direction (a monotonic table
//!   never asks for one, at a start or a restart included);
//! - a start or restart moves the slave less than one stroke, plus what
//!   the cam itself moves in that tick;
//! - the pulses of every tick stay within the frequency ceiling.

use core::num::NonZeroU64;

use ecam_core::{CamCurve, PointTable};
use ecam_engine::plcopen::{ActivationMode, CamIn, CamInStartMode, CamTableSelect, McCamAxis};
use ecam_engine::{
    AxisConfig, CamAxis, Compare, Coupling, MasterAlign, MasterFilter, SlaveAlign, StartMode,
    StopKind, TickInput, TickOutput, Zoom,
};
use proptest::prelude::*;

use super::{TICK_US, any_monotonic_table};

/// How a face sets the engine up for a run.
#[derive(Clone, Copy, Debug)]
enum Face {
    /// The PLC's cyclic cam (start register 1): absolute, strokes
    /// accumulate, a counter master followed through the tracker.
    PlcCyclic,
    /// The PLC's noncyclic cam (start register 2), `repeats` as offset 14
    /// (0xFFFF: for ever): from the table's first point, relative.
    PlcNoncyclic { repeats: u16 },
    /// The motion processor: `CamStartCount`, bumpless.
    Pmd { start_count_per_mille: u16 },
    /// The motion controller's Repeat cam, absolute, on a linear or a
    /// single-turn master.
    McRepeat { single_turn: bool },
    /// The engine API with an absolute slave (either name of it).
    Engine { nearest: bool, one_shot: bool },
    /// The PLCopen facade with a relative master or slave.
    PlcOpen {
        master_absolute: bool,
        mode: CamInStartMode,
        activation: ActivationMode,
    },
}

fn any_face() -> impl Strategy<Value = Face> {
    let plcopen_mode = prop_oneof![
        Just(CamInStartMode::Relative),
        Just(CamInStartMode::Bumpless),
        (1u64..3000).prop_map(|d| CamInStartMode::RampIn {
            distance: NonZeroU64::new(d).unwrap()
        }),
    ];
    let activation = prop_oneof![
        Just(ActivationMode::Immediate),
        Just(ActivationMode::NextCycle),
        (0i64..3000).prop_map(ActivationMode::AtMasterPosition),
    ];
    prop_oneof![
        Just(Face::PlcCyclic),
        prop_oneof![Just(0u16), Just(3), Just(u16::MAX)]
            .prop_map(|repeats| Face::PlcNoncyclic { repeats }),
        (0u16..=1000).prop_map(|p| Face::Pmd {
            start_count_per_mille: p
        }),
        any::<bool>().prop_map(|single_turn| Face::McRepeat { single_turn }),
        (any::<bool>(), any::<bool>())
            .prop_map(|(nearest, one_shot)| Face::Engine { nearest, one_shot }),
        (any::<bool>(), plcopen_mode, activation).prop_map(
            |(master_absolute, mode, activation)| {
                Face::PlcOpen {
                    master_absolute,
                    mode,
                    activation,
                }
            }
        ),
    ]
}

/// A start mode, its thresholds measured from where the master stands.
#[derive(Clone, Copy, Debug)]
enum Start {
    Immediate,
    Edge { after: u32 },
    Delay { counts: u64, after_edge: bool },
    Position { ahead: i64, after_edge: bool },
    Breakpoint { ahead: i64 },
}

fn any_start() -> impl Strategy<Value = Start> {
    prop_oneof![
        Just(Start::Immediate),
        (0u32..50).prop_map(|after| Start::Edge { after }),
        (0u64..3000, any::<bool>())
            .prop_map(|(counts, after_edge)| Start::Delay { counts, after_edge }),
        (0i64..3000, any::<bool>())
            .prop_map(|(ahead, after_edge)| Start::Position { ahead, after_edge }),
        (0i64..3000).prop_map(|ahead| Start::Breakpoint { ahead }),
    ]
}

impl Start {
    fn mode(self, master: i64) -> StartMode {
        match self {
            Self::Immediate => StartMode::Immediate,
            Self::Edge { .. } => StartMode::OnRisingEdge,
            Self::Delay { counts, after_edge } => StartMode::AfterDelay { counts, after_edge },
            Self::Position { ahead, after_edge } => StartMode::AtMasterPosition {
                position: master + ahead,
                after_edge,
            },
            Self::Breakpoint { ahead } => StartMode::Breakpoint {
                compare: Compare::AtLeast,
                value: master + ahead,
            },
        }
    }

    /// The start input at tick `i` after arming: an edge some ticks on.
    fn input(self, i: u32) -> bool {
        match self {
            Self::Edge { after } => i > after,
            _ => i > 3,
        }
    }
}

/// One axis driven as a face drives it.
enum Driven {
    Engine(Box<CamAxis<PointTable>>, Start),
    PlcOpen(Box<McCamAxis<PointTable>>, CamIn),
}

impl Driven {
    fn new(face: Face, start: Start, table: &PointTable, slave_zoom: Zoom, coarse: bool) -> Self {
        let span = table.master_span();
        let base = AxisConfig {
            slave_zoom,
            master_filter: if coarse {
                MasterFilter::INTERPOLATE
            } else {
                MasterFilter::Direct
            },
            ..AxisConfig::default()
        };
        let config = match face {
            Face::PlcCyclic => AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                ..base
            },
            Face::PlcNoncyclic { repeats } => AxisConfig {
                coupling: Coupling::OneShot { repeats },
                master_align: MasterAlign::StartAt(table.master_first()),
                slave_align: SlaveAlign::Relative,
                ..base
            },
            Face::Pmd {
                start_count_per_mille,
            } => AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                master_align: MasterAlign::StartAt(span * i64::from(start_count_per_mille) / 1000),
                slave_align: SlaveAlign::Relative,
                ..base
            },
            Face::McRepeat { single_turn } => AxisConfig {
                coupling: Coupling::Repeat { min_stroke: 1 },
                single_turn: single_turn.then(|| NonZeroU64::new(span as u64).unwrap()),
                ..base
            },
            Face::Engine { nearest, one_shot } => AxisConfig {
                coupling: if one_shot {
                    Coupling::OneShot { repeats: 2 }
                } else {
                    Coupling::Repeat { min_stroke: 1 }
                },
                slave_align: if nearest {
                    SlaveAlign::NearestEquivalent
                } else {
                    SlaveAlign::Absolute
                },
                ..base
            },
            Face::PlcOpen {
                master_absolute,
                mode,
                activation,
            } => {
                let mut axis = McCamAxis::new(table.clone()).unwrap();
                axis.select(CamTableSelect {
                    periodic: true,
                    master_absolute,
                    slave_absolute: false,
                    ..CamTableSelect::default()
                })
                .unwrap();
                let cam_in = CamIn {
                    slave_scaling: slave_zoom,
                    start_mode: mode,
                    activation,
                    ..CamIn::default()
                };
                return Self::PlcOpen(Box::new(axis), cam_in);
            }
        };
        Self::Engine(
            Box::new(CamAxis::new(table.clone(), config).unwrap()),
            start,
        )
    }

    fn set_slave(&mut self, slave: i64) {
        match self {
            Self::Engine(axis, _) => axis.set_slave_position(slave).unwrap(),
            Self::PlcOpen(axis, _) => axis.set_slave_position(slave).unwrap(),
        }
    }

    /// Arms (or cams in) with the thresholds measured from `master`.
    fn arm(&mut self, master: i64, single_turn: Option<i64>) {
        match self {
            Self::Engine(axis, start) => {
                let mut mode = start.mode(master);
                if let (
                    Some(turn),
                    StartMode::AtMasterPosition {
                        position,
                        after_edge,
                    },
                ) = (single_turn, mode)
                {
                    // A single-turn master's start position is a place in the turn.
                    mode = StartMode::AtMasterPosition {
                        position: position.rem_euclid(turn),
                        after_edge,
                    };
                }
                let config = AxisConfig {
                    start: mode,
                    ..*axis.config()
                };
                axis.set_config(config).unwrap();
                axis.arm().unwrap();
            }
            Self::PlcOpen(axis, cam_in) => {
                let activation = match cam_in.activation {
                    ActivationMode::AtMasterPosition(ahead) => {
                        ActivationMode::AtMasterPosition(master + ahead)
                    }
                    other => other,
                };
                axis.cam_in(&CamIn {
                    activation,
                    ..*cam_in
                })
                .unwrap();
            }
        }
    }

    fn stop(&mut self, end_of_cycle: bool) {
        let kind = if end_of_cycle {
            StopKind::EndOfCycle
        } else {
            StopKind::Immediate
        };
        match self {
            Self::Engine(axis, _) => axis.stop(kind),
            Self::PlcOpen(axis, _) => axis.stop(),
        }
    }

    fn active(&self) -> bool {
        match self {
            Self::Engine(axis, _) => axis.state().is_active(),
            Self::PlcOpen(axis, _) => axis.axis().state().is_active(),
        }
    }

    fn tick(&mut self, master: i64, watch: i64, input: bool) -> TickOutput {
        match self {
            Self::Engine(axis, _) => axis.tick(&TickInput {
                start_input: input,
                watch,
                ..TickInput::at(master, TICK_US)
            }),
            Self::PlcOpen(axis, _) => axis.tick(master, TICK_US).output,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(96)))]

    #[test]
    fn starts_and_restarts_from_anywhere_never_reverse_and_move_less_than_a_stroke(
        table in any_monotonic_table(),
        falling in any::<bool>(),
        face in any_face(),
        start in any_start(),
        slave_zoom in (1i32..6, any::<bool>(), 1u16..6)
            .prop_map(|(n, neg, d)| Zoom::signed(if neg { -n } else { n }, d).unwrap()),
        master0 in -2_000_000i64..2_000_000,
        slave0 in -2_000_000i64..2_000_000,
        coarse in any::<bool>(),
        hz in prop_oneof![Just(200_000i64), 20_000i64..200_000],
        speeds in prop::collection::vec((0i64..60_000, 1u32..400), 1..6),
        stop_after in 1usize..1500,
        end_of_cycle in any::<bool>(),
    ) {
        let table = if falling {
            let points: Vec<(i64, i64)> =
                table.points().iter().map(|p| (p.master, -p.slave)).collect();
            PointTable::from_pairs(&points).unwrap()
        } else {
            table
        };
        let span = table.master_span();
        let single_turn = match face {
            // The turn must be well above a tick's step to unwrap.
            Face::McRepeat { single_turn: true } if span >= 100 => Some(span),
            _ => None,
        };
        let face = match face {
            Face::McRepeat { .. } => Face::McRepeat { single_turn: single_turn.is_some() },
            other => other,
        };
        let mut driven = Driven::new(face, start, &table, slave_zoom, coarse);
        let hz = match &mut driven {
            Driven::Engine(axis, _) => {
                axis.set_max_frequency(hz);
                hz
            }
            // The facade keeps the engine's default ceiling.
            Driven::PlcOpen(..) => 200_000,
        };
        driven.set_slave(slave0);

        // The cam's direction for a forward master, its stroke in pulses
        // and the most it moves per master count.
        let zoom = f64::from(slave_zoom.signed_num()) / f64::from(slave_zoom.den());
        let stroke = table.stroke() as f64 * zoom;
        let direction = stroke.signum() as i64;
        let steepest = table
            .points()
            .windows(2)
            .map(|w| (w[1].slave - w[0].slave).abs() as f64 / (w[1].master - w[0].master) as f64)
            .fold(0.0, f64::max)
            * zoom.abs();
        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(TICK_US);

        let reading = |m: i64| single_turn.map_or(m, |turn| m.rem_euclid(turn));
        let mut micro = master0 * 1_000_000;
        let mut master = master0;
        // One tick before arming, so a start threshold counts from here.
        let mut last = driven.tick(reading(master), master, false);
        driven.arm(master, single_turn);
        let (mut armed_at, mut restarted, mut engages) = (0u32, false, 0);
        let ticks: Vec<i64> = speeds
            .iter()
            .flat_map(|&(v, n)| std::iter::repeat_n(v, n as usize))
            .chain(std::iter::repeat_n(0, 300))
            .collect();
        for (i, &speed) in ticks.iter().enumerate() {
            micro += speed * i64::from(TICK_US);
            let step = micro.div_euclid(1_000_000) - master;
            master += step;
            let input = start.input(armed_at);
            armed_at += 1;
            let out = driven.tick(reading(master), master, input);
            prop_assert!(
                u128::from(out.pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000,
                "tick {i}: {} pulses above {hz} Hz", out.pulses
            );
            prop_assert!(
                out.pulses == 0 || out.pulses.signum() == direction,
                "tick {i}: {} pulses against the cam's direction {direction}", out.pulses
            );
            if out.events.engaged {
                engages += 1;
                // Less than a stroke, plus the cam's own motion this tick
                // (the master reached the start inside it) and rounding.
                let travel = ((out.slave - last.slave) * direction) as f64;
                let own = steepest * (step as f64 + 1.0) + 2.0;
                prop_assert!(
                    travel >= 0.0 && travel < stroke.abs() + own,
                    "tick {i}: the start moved the slave {travel} (stroke {stroke})"
                );
            }
            last = out;
            if i == stop_after && driven.active() {
                driven.stop(end_of_cycle);
            }
            if i > stop_after && !restarted && !driven.active() && out.backlog == 0 {
                // The restart: from wherever the slave and master now are.
                driven.arm(master, single_turn);
                armed_at = 0;
                restarted = true;
            }
        }
        prop_assert!(engages <= 2);
    }
}
