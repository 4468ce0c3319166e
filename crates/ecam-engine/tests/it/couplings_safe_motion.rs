//! Safe motion of a slave axis with several couplings (cam + gear +
//! superimposed move + phasing, behind a direction guard): the properties
//! of `safe_motion.rs`, extended.
//!
//! Over random monotonic tables, ratios, distances, limits and master
//! motions:
//! - the pulses of every tick stay within the axis' ceiling;
//! - with every coupling moving forwards and a forward-only guard, the
//!   slave never turns back, whatever the master does;
//! - the slave is exactly the sum of its parts, every tick;
//! - zero drift: once the timed moves are done, a master that wanders and
//!   comes back to where it was brings the slave back to exactly where it
//!   was, every pulse emitted.

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, CamAxis, Coupling, DirectionGuard, GearIn, GearRamp, GuardDirection, GuardResume,
    MoveLimits, MoveSuperimposed, Phasing, PhasingMode, SlaveAlign, SlaveAxis, SlaveConfig,
    SlaveInput, SlaveOutput, TickInput, Zoom,
};
use proptest::prelude::*;

use crate::safe_motion::{any_monotonic_table, reversals};

const TICK_US: u32 = 100;

fn tick(axis: &mut SlaveAxis<CamAxis<PointTable>>, master: i64) -> SlaveOutput {
    *axis.tick(&SlaveInput {
        tick: TickInput::at(master, TICK_US),
        latch: None,
    })
}

/// Master speed segments: (counts per second, ticks).
fn any_motion(backwards: bool) -> impl Strategy<Value = Vec<(i64, u32)>> {
    let low = if backwards { -30_000i64 } else { 0 };
    prop::collection::vec((low..60_000, 1u32..300), 1..8)
}

#[derive(Clone, Debug)]
struct Couplings {
    ratio: Zoom,
    blend: u64,
    distance: i64,
    shift: i64,
    limits: (f64, f64),
    resume: GuardResume,
}

fn any_couplings() -> impl Strategy<Value = Couplings> {
    (
        (1i32..6, 1u16..6),
        1u64..5000,
        0i64..5000,
        0i64..3000,
        (100.0f64..20_000.0, 1_000.0f64..1e6),
        prop_oneof![
            Just(GuardResume::AtOnce),
            Just(GuardResume::AtReversalPoint)
        ],
    )
        .prop_map(
            |((n, d), blend, distance, shift, limits, resume)| Couplings {
                ratio: Zoom::signed(n, d).unwrap(),
                blend,
                distance,
                shift,
                limits,
                resume,
            },
        )
}

fn axis_with(
    table: &PointTable,
    c: &Couplings,
    hz: i64,
    guard: bool,
) -> SlaveAxis<CamAxis<PointTable>> {
    let config = AxisConfig {
        coupling: Coupling::Repeat { min_stroke: 1 },
        // Bumpless: an absolute engage may ask for a jump back.
        slave_align: SlaveAlign::Relative,
        ..AxisConfig::default()
    };
    let mut cam = CamAxis::new(table.clone(), config).unwrap();
    cam.arm().unwrap();
    let slave = SlaveConfig {
        max_frequency_hz: hz,
        guard: guard.then_some(DirectionGuard {
            direction: GuardDirection::Forward,
            resume: c.resume,
        }),
        ..SlaveConfig::default()
    };
    let mut axis = SlaveAxis::new(cam, slave).unwrap();
    let limits = MoveLimits::new(c.limits.0, c.limits.1, c.limits.1).unwrap();
    axis.gear_in(&GearIn {
        ratio: c.ratio,
        ramp: GearRamp::Distance(NonZeroU64::new(c.blend).unwrap()),
    })
    .unwrap();
    axis.move_superimposed(&MoveSuperimposed {
        distance: c.distance,
        limits,
    })
    .unwrap();
    axis.phasing(&Phasing {
        shift: c.shift,
        mode: PhasingMode::Relative,
        limits,
    })
    .unwrap();
    axis
}

/// Runs the motion; returns every tick's output and the masters read.
fn run(
    axis: &mut SlaveAxis<CamAxis<PointTable>>,
    motion: &[(i64, u32)],
    rest: u32,
) -> (Vec<SlaveOutput>, Vec<i64>) {
    let mut micro = 0i64;
    let mut outs = Vec::new();
    let mut masters = Vec::new();
    let segments = motion.iter().copied().chain(core::iter::once((0, rest)));
    for (speed, ticks) in segments {
        for _ in 0..ticks {
            micro += speed * i64::from(TICK_US);
            let m = micro.div_euclid(1_000_000);
            masters.push(m);
            outs.push(tick(axis, m));
        }
    }
    (outs, masters)
}

proptest! {
    // The drift test rejects runs whose couplings never settle; the
    // reject budget grows with the cases so a long run is not cut short.
    #![proptest_config(ProptestConfig {
        max_global_rejects: crate::cases(48).saturating_mul(50),
        ..ProptestConfig::with_cases(crate::cases(48))
    })]

    #[test]
    fn a_guarded_slave_with_every_coupling_never_turns_back(
        table in any_monotonic_table(),
        couplings in any_couplings(),
        hz in prop_oneof![Just(200_000i64), 20_000i64..200_000],
        motion in any_motion(true),
    ) {
        let mut axis = axis_with(&table, &couplings, hz, true);
        let (outs, _) = run(&mut axis, &motion, 3000);
        let ceiling = u128::from(hz.unsigned_abs()) * u128::from(TICK_US);
        for (i, o) in outs.iter().enumerate() {
            prop_assert!(u128::from(o.pulses.unsigned_abs()) * 1_000_000 < ceiling + 1_000_000,
                "tick {i}: {} pulses above {hz} Hz", o.pulses);
            prop_assert!(o.pulses >= 0, "tick {i}: the slave turned back");
            prop_assert_eq!(
                o.slave,
                o.cam.slave + o.gear.slave + o.superimposed.position,
                "tick {}: the sum of the parts", i
            );
            if let Some(g) = o.guard {
                prop_assert!(g.lost >= 0.0);
            }
        }
    }

    #[test]
    fn couplings_follow_the_master_without_drift(
        table in any_monotonic_table(),
        couplings in any_couplings(),
        motion in any_motion(false),
        wander in any_motion(true),
    ) {
        // No guard: every part is a function of the master once the timed
        // moves are done.
        let mut axis = axis_with(&table, &couplings, 200_000, false);
        let (outs, masters) = run(&mut axis, &motion, 30_000);
        let settled = *outs.last().unwrap();
        prop_assume!(!settled.phasing.active && !settled.superimposed.active);
        prop_assume!(settled.gear.state == ecam_engine::GearState::InGear);
        prop_assert!(reversals(outs.iter().map(|o| o.pulses)) == 0);
        let home = *masters.last().unwrap();
        // Wander (both ways), then come back home at rest.
        let mut micro = home * 1_000_000;
        for &(speed, ticks) in &wander {
            for _ in 0..ticks {
                micro += speed * i64::from(TICK_US);
                tick(&mut axis, micro.div_euclid(1_000_000));
            }
        }
        let mut back = tick(&mut axis, home);
        for _ in 0..crate::ticks_to_drain(back.backlog, 200_000, TICK_US) {
            back = tick(&mut axis, home);
        }
        prop_assert_eq!(back.slave, settled.slave);
        prop_assert_eq!(back.emitted, back.slave);
        prop_assert_eq!(back.backlog, 0);
    }
}

/// A knife table of one turn (`modulo` pulses) per cycle, monotonic.
fn any_knife(modulo: i64) -> impl Strategy<Value = PointTable> {
    prop::collection::vec(1i64..100, 1..6).prop_map(move |weights| {
        let total: i64 = weights.iter().sum();
        let mut points = vec![(0i64, 0i64)];
        let (mut m, mut s) = (0i64, 0i64);
        for w in &weights {
            m += 400;
            s += w * modulo / total;
            points.push((m, s));
        }
        points.last_mut().unwrap().1 = modulo;
        PointTable::from_pairs(&points).unwrap()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(48)))]

    #[test]
    fn an_endless_positive_knife_never_turns_back(
        table in any_knife(36_000),
        start in 0i64..200_000,
        ramp in prop::option::of(1u64..3000),
        motion in any_motion(false),
    ) {
        use ecam_engine::{ModuloAxis, ModuloStart, RampIn};
        let modulo = ModuloAxis::new(36_000, ModuloStart::EndlessPositive).unwrap();
        let config = AxisConfig {
            coupling: Coupling::Periodic,
            slave_align: SlaveAlign::Modulo { axis: modulo, offset: 0 },
            ramp_in: ramp.map(|d| RampIn { distance: NonZeroU64::new(d).unwrap() }),
            ..AxisConfig::default()
        };
        let mut axis = SlaveAxis::with_cam(
            table,
            config,
            SlaveConfig { modulo: Some(modulo), ..SlaveConfig::default() },
        )
        .unwrap();
        axis.set_slave_position(start).unwrap();
        axis.cam_mut().arm().unwrap();
        let (outs, _) = run(&mut axis, &motion, 3000);
        for (i, o) in outs.iter().enumerate() {
            prop_assert!(o.pulses >= 0, "tick {i}: the knife turned back");
            let m = o.modulo.unwrap();
            prop_assert!((0..36_000).contains(&m.position));
            prop_assert_eq!(i128::from(m.turns) * 36_000 + i128::from(m.position), i128::from(o.slave));
        }
        let first = outs.first().unwrap().slave;
        prop_assert!(first >= start && first < start + 36_000, "engaged ahead, within a turn");
    }

    #[test]
    fn registration_never_exceeds_its_limit_nor_turns_the_knife_back(
        late in -700i64..700,
        stretch in -20i64..20,
        max in 10u64..200,
        extra_ramp in 0u64..3000,
    ) {
        use ecam_engine::{LatchSource, RegistrationConfig};
        let max_i = i64::try_from(max).unwrap();
        let config = RegistrationConfig {
            source: LatchSource::Master,
            cycle: NonZeroU64::new(10_000).unwrap(),
            expected: 2000,
            window: 800,
            max_correction: max,
            ramp: NonZeroU64::new(2 * max + extra_ramp).unwrap(),
        };
        let knife = PointTable::from_pairs(&[(0, 0), (3000, 6000), (7000, 30_000), (10_000, 36_000)])
            .unwrap();
        let mut axis = SlaveAxis::with_cam(
            knife,
            AxisConfig { coupling: Coupling::Repeat { min_stroke: 1 }, ..AxisConfig::default() },
            SlaveConfig { registration: Some(config), ..SlaveConfig::default() },
        )
        .unwrap();
        axis.cam_mut().arm().unwrap();
        let marks: Vec<i64> = (0..30).map(|i| 2000 + late + (10_000 + stretch) * i).collect();
        let mut next = 0;
        let mut corrections = Vec::new();
        let mut rejected = 0;
        for m in (0..310_000).step_by(13) {
            let latch = match marks.get(next) {
                Some(&mark) if mark <= m => {
                    next += 1;
                    Some(mark)
                }
                _ => None,
            };
            let o = *axis.tick(&SlaveInput { tick: TickInput::at(m, TICK_US), latch });
            prop_assert!(o.pulses >= 0, "the knife turned back at {m}");
            if let Some(r) = o.registration.filter(|r| r.mark) {
                prop_assert!(r.last_correction.abs() <= max_i);
                corrections.push(r);
            }
            rejected = o.registration.map_or(0, |r| r.rejected);
        }
        // Every mark is taken, or rejected once it lies outside the window.
        prop_assert_eq!(corrections.len() + usize::try_from(rejected).unwrap(), 30);
        // While the material stretches less per cycle than a mark may
        // correct, each mark gains `max − |stretch|` on the error: converged
        // within ceil(|late| / (max − |stretch|)) + 1 marks, then only the
        // stretch is left at each mark. Stretching more, the error grows
        // by `|stretch| − max` a mark, and a mark that starts near the
        // window's edge leaves it (late = 569, stretch = 18, max = 10: the
        // 30th mark is 801 counts out, 800 allowed).
        if stretch.unsigned_abs() >= max {
            return Ok(());
        }
        prop_assert_eq!(corrections.len(), 30);
        let gain = max - stretch.unsigned_abs();
        let settle = usize::try_from(late.unsigned_abs().div_ceil(gain) + 1).unwrap();
        for r in corrections.iter().skip(settle) {
            prop_assert!(r.last_error.abs() <= stretch.abs(), "{r:?}");
        }
    }
}
