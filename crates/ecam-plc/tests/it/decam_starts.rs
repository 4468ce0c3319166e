//! The start rule on the PLC face (docs/plc.md, "The start rule"): a DECAM
//! started or restarted with the master and Y0's pulse counter anywhere,
//! cyclic or noncyclic (HFFFF included), on a monotonic table and a master
//! that runs forwards: the pulse counter never moves against the table's
//! direction, the direction output never changes once set, a start moves
//! the knife less than one stroke (plus what the cam moves in that tick),
//! and no tick sends more pulses than the 200 kHz ceiling allows.

use proptest::prelude::*;

use crate::decam_support::Rig;

fn any_monotonic_points() -> impl Strategy<Value = Vec<(i32, i32)>> {
    (
        prop::collection::vec((1i32..500, 0i32..800), 1..6),
        any::<bool>(),
    )
        .prop_map(|(steps, falling)| {
            let sign = if falling { -1 } else { 1 };
            let mut points = vec![(0, 0)];
            let (mut m, mut s) = (0, 0);
            for (dm, ds) in steps {
                m += dm;
                s += ds;
                points.push((m, sign * s));
            }
            if s == 0 {
                points.last_mut().unwrap().1 = sign;
            }
            points
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(crate::cases(64)))]

    #[test]
    fn a_cam_started_anywhere_never_reverses_and_moves_less_than_a_stroke(
        points in any_monotonic_points(),
        mode in prop_oneof![Just((1i16, 0u16)), Just((2, 0)), Just((2, 0xFFFF))],
        master0 in -1_000_000i64..1_000_000,
        counter0 in -1_000_000i32..1_000_000,
        speeds in prop::collection::vec(0i64..6, 1..5),
        restart_after in 100u32..800,
    ) {
        let mut rig = Rig::new(&points);
        let (start, repeats) = mode;
        rig.set(14, repeats as i16);
        rig.master = master0;
        rig.dev.set_dword(8140, counter0).unwrap();
        let stroke = i64::from(points.last().unwrap().1);
        let direction = stroke.signum();
        let steepest = points
            .windows(2)
            .map(|w| f64::from((w[1].1 - w[0].1).abs()) / f64::from(w[1].0 - w[0].0))
            .fold(0.0, f64::max);
        let mut last = i64::from(rig.pulses());
        let mut direction_out: Option<bool> = None;
        // Where a start took the commanded knife (offsets 19/20), from the
        // pulse counter it stood at: less than one stroke on, plus what the
        // cam moves in the start's own tick.
        let check_start = |rig: &Rig, from: i64, step: i64| -> Result<(), TestCaseError> {
            let travel = (i64::from(rig.reg_d(19)) - from) * direction;
            let own = steepest * step as f64 + 1.0;
            prop_assert!(travel >= 0, "the start went back {travel}");
            prop_assert!((travel as f64) < stroke.abs() as f64 + own,
                "the start moved {travel} (stroke {stroke})");
            Ok(())
        };
        rig.start(start);
        prop_assert!(rig.flag(6) || rig.flag(7), "started");
        check_start(&rig, i64::from(counter0), 0)?;
        let first = i64::from(rig.pulses()) - last;
        prop_assert!(first.abs() <= 20 && (first == 0 || first.signum() == direction));
        last += first;
        let mut ticks = 0u32;
        for &speed in &speeds {
            for _ in 0..400 {
                if ticks.is_multiple_of(10) {
                    rig.scan();
                }
                ticks += 1;
                let restart = ticks == restart_after + 10;
                if ticks == restart_after {
                    // Stop, and start again 1 ms later (the 100 µs rule).
                    rig.set(5, 0);
                }
                if restart {
                    rig.set(5, start);
                }
                let from = i64::from(rig.pulses());
                rig.tick(speed);
                if restart {
                    check_start(&rig, from, speed)?;
                }
                let now = i64::from(rig.pulses());
                let moved = now - last;
                prop_assert!(moved.abs() <= 20, "tick {ticks}: {moved} pulses above 200 kHz");
                prop_assert!(
                    moved == 0 || moved.signum() == direction,
                    "tick {ticks}: {moved} pulses against the table's direction"
                );
                if moved != 0 {
                    let forward = rig.y(4);
                    prop_assert!(direction_out.is_none_or(|d| d == forward), "Y4 changed");
                    direction_out = Some(forward);
                }
                last = now;
            }
        }
    }
}
