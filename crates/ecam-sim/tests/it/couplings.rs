//! The coupling scenarios of `examples/scenarios/` (modulo, phasing, gear,
//! registration, direction, cam-switch), each run and checked on its
//! trace; and the scenario keys of the couplings refused when wrong.

use std::path::{Path, PathBuf};

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, GearState, TickInput};
use ecam_sim::{CouplingTick, Row, Scenario, SimulateError, Summary, simulate, simulate_couplings};

fn path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/scenarios")
        .join(name)
}

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).unwrap()
}

/// Runs a scenario text; every tick's row and report.
fn run_text(text: &str) -> (Summary, Vec<(Row, CouplingTick)>) {
    let scenario = Scenario::parse(text, &path("")).unwrap();
    let mut ticks = Vec::new();
    let summary = simulate_couplings(&scenario, |row, tick, _| {
        ticks.push((*row, *tick));
        Ok::<(), std::convert::Infallible>(())
    })
    .unwrap();
    (summary, ticks)
}

fn run(name: &str) -> (Summary, Vec<(Row, CouplingTick)>) {
    run_text(&text(name))
}

fn never_back(ticks: &[(Row, CouplingTick)]) {
    for (row, _) in ticks {
        assert!(row.pulses >= 0, "turned back at t = {}", row.t);
    }
}

/// The cam of `points` (repeat) at `master`, computed afresh.
fn cam_at(points: &[(i64, i64)], master: i64) -> i64 {
    let table = PointTable::from_pairs(points).unwrap();
    let mut axis = CamAxis::new(
        table,
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            ..AxisConfig::default()
        },
    )
    .unwrap();
    axis.arm().unwrap();
    let _ = axis.tick(&TickInput::at(0, 1000));
    axis.tick(&TickInput::at(master, 1000)).slave
}

#[test]
fn modulo_knife_turns_on_forwards_and_reports_its_place_in_the_turn() {
    let (summary, ticks) = run("modulo-knife.toml");
    never_back(&ticks);
    for (_, t) in &ticks {
        let m = t.axis.modulo.unwrap();
        assert!((0..36_000).contains(&m.position));
        assert_eq!(m.turns * 36_000 + m.position, t.axis.slave);
    }
    // Parked at 30 000; the table's 0° one turn on; five cuts.
    assert_eq!(ticks[0].1.axis.slave, 30_000);
    assert_eq!(summary.final_slave, 36_000 + 5 * 36_000);
    assert_eq!(
        (summary.modulo_position, summary.modulo_turns),
        (Some(0), Some(6))
    );
    assert_eq!(summary.seam_jumps, 5);
    // Absolute: back to 0° in the same turn first, back a turn every seam.
    let absolute = text("modulo-knife.toml").replace("\"endless-positive\"", "\"absolute\"");
    let (summary, ticks) = run_text(&absolute);
    assert!(ticks.iter().any(|(r, _)| r.pulses < 0));
    assert_eq!(summary.final_slave, 0);
    assert_eq!(summary.modulo_position, Some(0));
}

#[test]
fn phasing_keeps_to_its_limits_and_the_slave_ends_on_the_shifted_cam() {
    let (summary, ticks) = run("phasing-shift.toml");
    never_back(&ticks);
    let dt = 1e-3;
    let shifts: Vec<f64> = ticks.iter().map(|(_, t)| t.axis.phasing.shift).collect();
    let mut peak = 0.0f64;
    for w in shifts.windows(3) {
        let (v1, v2) = ((w[1] - w[0]) / dt, (w[2] - w[1]) / dt);
        peak = peak.max(v1.abs());
        assert!(v1.abs() <= 2000.0 + 1e-6, "shift velocity {v1}");
        assert!(
            ((v2 - v1) / dt).abs() <= 20_000.0 + 1e-3,
            "shift acceleration"
        );
    }
    assert!(peak > 1999.0, "the shift reaches its velocity limit");
    assert_eq!(summary.phase_shift, Some(1000.0));
    assert_eq!(summary.plcopen_steps, Some(4));
    let points = [(0, 0), (5000, 5000), (15_000, 35_000), (20_000, 40_000)];
    assert_eq!(summary.final_slave, cam_at(&points, 60_000 + 1000));
}

#[test]
fn gear_cam_and_superimposed_sum_exactly() {
    let (summary, ticks) = run("gear-cam-superimposed.toml");
    never_back(&ticks);
    let points = [(0, 0), (5000, 0), (15_000, 8000), (20_000, 8000)];
    let mut line: Option<(i64, i64)> = None;
    for (row, t) in &ticks {
        let a = &t.axis;
        assert_eq!(
            a.slave,
            a.cam.slave + a.gear.slave + a.superimposed.position
        );
        assert!(row.pulses.abs() <= 50, "50 kHz in 1 ms ticks");
        if a.gear.state == GearState::InGear {
            // In gear: exactly half the master's travel, rounded once.
            let (m0, g0) = *line.get_or_insert((row.master, a.gear.slave));
            let travel = row.master - m0;
            let half = if travel >= 0 {
                (travel + 1) / 2
            } else {
                -((1 - travel) / 2)
            };
            assert!((a.gear.slave - g0 - half).abs() <= 1);
        }
    }
    assert!(line.is_some());
    assert_eq!(summary.superimposed, Some(6000));
    assert_eq!(summary.cam_slave, Some(cam_at(&points, 60_000)));
    assert_eq!(
        summary.final_slave,
        summary.cam_slave.unwrap() + summary.gear_slave.unwrap() + 6000
    );
    assert_eq!(ticks.last().unwrap().1.axis.gear.state, GearState::Off);
}

#[test]
fn registration_converges_to_the_mark_and_never_exceeds_its_limit() {
    let (summary, ticks) = run("registration-print-marks.toml");
    never_back(&ticks);
    let marks: Vec<_> = ticks
        .iter()
        .filter_map(|(_, t)| t.axis.registration.filter(|r| r.mark))
        .collect();
    assert_eq!(marks.len(), 11);
    for r in &marks {
        assert!(r.last_correction.abs() <= 150, "{r:?}");
    }
    // 600 late at 150 a mark: in sync with the mark from the fifth on,
    // every later error only the 10 counts (20 after the missing mark)
    // the material adds per cycle.
    assert_eq!(marks[0].last_error, 600);
    for r in &marks[5..] {
        assert!(r.last_error.abs() <= 20, "{r:?}");
        assert_eq!(r.last_correction, -r.last_error);
    }
    assert_eq!(summary.registration_missed, Some(1));
    assert_eq!(summary.registration_rejected, Some(0));
    assert_eq!(summary.registration_correction, Some(-710.0));
}

#[test]
fn the_direction_guard_never_reverses_the_slave() {
    let points = [(0, 0), (2000, 1000), (8000, 7000), (10_000, 8000)];
    let (summary, ticks) = run("direction-guard.toml");
    never_back(&ticks);
    assert_eq!(summary.pulses_reverse, 0);
    assert_eq!(summary.direction_changes, 0);
    assert_eq!(summary.guard_lost, Some(3000.0));
    assert_eq!(summary.final_slave, cam_at(&points, 32_000 + 3000));
    // Held from the feed's first step back until it moves forwards again
    // (it stands still from 2.8 s to 3.0 s).
    let held: Vec<_> = ticks
        .iter()
        .filter(|(_, t)| t.axis.guard.unwrap().held)
        .map(|(r, _)| r.t)
        .collect();
    assert_eq!(held.len(), 1200, "{:?}", (held.first(), held.last()));
    assert!(held.first().is_some_and(|&t| t > 1.8) && held.last().is_some_and(|&t| t <= 3.0));
    let at_reversal = text("direction-guard.toml").replace("\"at-once\"", "\"at-reversal-point\"");
    let (summary, ticks) = run_text(&at_reversal);
    never_back(&ticks);
    assert_eq!(summary.guard_lost, Some(0.0));
    assert_eq!(summary.final_slave, cam_at(&points, 32_000));
}

#[test]
fn cam_switch_tracks_switch_where_their_cams_say() {
    let (summary, ticks) = run("cam-switch-glue.toml");
    let mut edges: Vec<(u32, bool, i64)> = Vec::new();
    let mut was = 0u32;
    for (row, t) in &ticks {
        for track in 0..3 {
            let bit = 1 << track;
            if (t.tracks ^ was) & bit != 0 {
                edges.push((track, t.tracks & bit != 0, row.master % 10_000));
            }
        }
        was = t.tracks;
    }
    let of = |track, on| -> Vec<i64> {
        edges
            .iter()
            .filter(|e| e.0 == track && e.1 == on)
            .map(|e| e.2)
            .collect()
    };
    // 5 ms early on, 3 ms early off at 10 counts per ms.
    assert_eq!(of(0, true), [1950, 1950, 1950]);
    assert_eq!(of(0, false), [2980, 2980, 2980]);
    // The label printer: 20 ms from 6000.
    assert_eq!(of(1, true), [6000, 6000, 6000]);
    assert_eq!(of(1, false), [6200, 6200, 6200]);
    // Over the wrap: on at 9500, off after 500.
    assert_eq!(of(2, true), [0, 9500, 9500, 9500]);
    assert_eq!(of(2, false), [510, 510, 510]);
    assert_eq!(summary.cam_switch_toggles, Some(19));
}

#[test]
fn coupling_scenarios_also_run_through_simulate() {
    // `simulate` (what `ecam simulate` calls) sees the axis' sum.
    let scenario = Scenario::load(&path("gear-cam-superimposed.toml")).unwrap();
    let mut last = 0;
    let summary = simulate(&scenario, |row, out, _| {
        assert_eq!(row.slave, out.slave);
        last = out.slave;
        Ok::<(), std::convert::Infallible>(())
    })
    .unwrap();
    assert_eq!(summary.final_slave, last);
}

#[test]
fn wrong_coupling_keys_are_refused_with_a_message() {
    let base = text("phasing-shift.toml");
    let err = |t: &str| format!("{:#}", Scenario::parse(t, &path("")).err().unwrap());
    assert!(err(&base.replace("MC_CamIn = {}", "MC_CamInn = {}")).contains("MC_CamInn"));
    assert!(
        err(&base.replace("MC_CamIn = {}", "MC_CamIn = {}\nMC_CamOut = {}"))
            .contains("exactly one block")
    );
    assert!(err(&format!("{base}\n[cam]\nkind = \"repeat\"\n")).contains("MC_CamTableSelect"));
    assert!(
        err(&base.replace(
            "velocity = 2000, acceleration = 20000 }",
            "velocity = 0, acceleration = 20000 }"
        ))
        .contains("above zero")
    );
    assert!(
        err(&base.replace("MC_CamIn = {}", "MC_CamIn = { ramp_distance = 5 }"))
            .contains("ramp_distance only applies")
    );
    let modulo = text("modulo-knife.toml");
    assert!(
        err(&modulo.replace("slave = 30000", "slave = 30000\nslave_align = \"relative\""))
            .contains("[modulo]")
    );
    assert!(err(&modulo.replace("modulo = 36000", "modulo = 0")).contains("modulo"));
    let reg = text("registration-print-marks.toml");
    assert!(err(&reg.replace("ramp = 2000", "ramp = 100")).contains("ramp"));
    let switches = text("cam-switch-glue.toml");
    assert!(
        err(&switches.replace("track = 2\nfirst_on = 9500", "track = 40\nfirst_on = 9500"))
            .contains("31")
    );
    assert!(
        err(&switches.replace("last_on = 3000", "last_on = 3000\nduration_s = 1.0"))
            .contains("exactly one of")
    );
}

#[test]
fn a_step_the_engine_refuses_names_the_step() {
    let base = text("gear-cam-superimposed.toml");
    // A superimposed velocity above the axis' 50 kHz.
    let fast = base.replace("velocity = 8000,", "velocity = 80000,");
    let scenario = Scenario::parse(&fast, &path("")).unwrap();
    let err = format!(
        "{:#}",
        simulate(&scenario, |_, _, _| Ok::<(), std::convert::Infallible>(()))
            .err()
            .unwrap()
    );
    assert!(err.contains("[[plcopen]] 4 MC_MoveSuperimposed"), "{err}");
}

#[test]
fn a_step_refused_and_a_scenario_without_couplings_are_typed_errors() {
    let base = text("gear-cam-superimposed.toml");
    let fast = base.replace("velocity = 8000,", "velocity = 80000,");
    let scenario = Scenario::parse(&fast, &path("")).unwrap();
    let err = simulate_couplings(&scenario, |_, _, _| Ok::<(), std::convert::Infallible>(()));
    assert!(
        matches!(
            err,
            Err(SimulateError::Step {
                number: 4,
                block: "MC_MoveSuperimposed",
                ..
            })
        ),
        "{err:?}"
    );
    // A plain cam scenario is `simulate`'s, not the slave axis'.
    let plain = Scenario::parse(&text("001-repeat.toml"), &path("")).unwrap();
    let err = simulate_couplings(&plain, |_, _, _| Ok::<(), std::convert::Infallible>(()));
    assert!(matches!(err, Err(SimulateError::NoCouplings)), "{err:?}");
}
