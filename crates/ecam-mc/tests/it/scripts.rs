//! The script language (`ecam mc run`): every document-001 example in
//! `examples/mc/` run through the library's runner, checked against the
//! document's numbers; and the language's errors.
#![allow(clippy::unwrap_used, missing_docs)]

use std::path::PathBuf;

use ecam_mc::script::{Report, Script, ScriptRunner, run_file, run_file_with};

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/mc")
        .join(name)
}

/// The values `GetCommandPosition AXIS` printed, in order.
fn positions(reports: &[Report], axis: usize) -> Vec<i64> {
    reports
        .iter()
        .filter(|r| r.cmd() == "GetCommandPosition" && r.axis() == axis)
        .filter_map(Report::value)
        .collect()
}

fn run(name: &str) -> Vec<Report> {
    run_file(example(name)).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn repeat_example_is_continuous_at_every_seam() {
    let reports = run("repeat.mc");
    assert_eq!(
        positions(&reports, 1),
        [
            500, // master 0
            1000, 1500, 1250, 1000, 1500, 2000, // first cycle, to 30000
            2500, 3000, 2750, 2500, 3000, 3500, // second: +1500
            4000, 4500, 4250, 4000, 4500, 5000, // third: +3000
            // back down from 90000, every 10000 to -10000
            4000, 4500, 3500, 2500, 3000, 2000, 1000, 1500, 500, -500,
        ]
    );
    assert_eq!(
        reports.last().map(Report::to_json).unwrap(),
        r#"{"cmd":"GetECAMStatus","axis":1,"running":true,"fault":null}"#
    );
}

#[test]
fn periodic_example_jumps_back_at_the_seam() {
    let reports = run("periodic.mc");
    assert_eq!(
        positions(&reports, 1),
        [
            500, 1000, 1500, 1250, 1000, 1500, 500, // 0 to 30000: back to 500
            1000, 1500, 1250, 1000, 1500, 500, // 35000 to 60000
            500, 510, // 30000, 30100
        ]
    );
}

#[test]
fn single_turn_repeat_example_keeps_the_slave_across_wraps() {
    let reports = run("single_turn_repeat.mc");
    assert_eq!(
        reports.first().map(Report::to_json).unwrap(),
        r#"{"cmd":"GetSingleTurn","axis":0,"value":30000}"#
    );
    assert_eq!(
        positions(&reports, 1),
        [
            500, 1000, 1500, 1250, 1000, 1500, 2000, 2500, 3000, 2750, 2500, 3000, 3500, 4000,
            4500, 4250
        ]
    );
    // The master ended 2.5 turns on, at 15000 within its turn.
    assert_eq!(positions(&reports, 0), [15000]);
}

#[test]
fn single_turn_start_example_begins_at_minus_2000() {
    let reports = run("single_turn_start.mc");
    assert_eq!(positions(&reports, 1), [-2000, -1500, -1000, -500, 0]);
}

#[test]
fn incomplete_turn_example_is_extended_with_the_end_values() {
    let reports = run("incomplete_turn.mc");
    assert_eq!(
        positions(&reports, 1),
        [
            1000, 1000, 1000, 2500, 4000, 3000, 3000, // 0 .. 27500: flat, rise, fall, flat
            3000, 3000, 6000, 5000, 5000, // 30000 .. 60000: the same 2000 higher
        ]
    );
}

#[test]
fn user_unit_example_joins_only_ends_a_unit_apart() {
    let reports = run("user_unit.mc");
    assert_eq!(positions(&reports, 1), [3000, 0, 3000], "1000 pulses/unit");
    assert_eq!(positions(&reports, 3), [3000, 400, 3400], "100 pulses/unit");
}

#[test]
fn every_example_is_checked() {
    let mut names: Vec<String> = std::fs::read_dir(example(""))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".mc"))
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "incomplete_turn.mc",
            "periodic.mc",
            "repeat.mc",
            "single_turn_repeat.mc",
            "single_turn_start.mc",
            "user_unit.mc"
        ]
    );
}

fn run_text(
    text: &str,
) -> (
    Vec<Report>,
    Result<(), ecam_mc::script::ScriptError>,
    ScriptRunner,
) {
    let script = Script::parse(text, "t.mc").unwrap();
    let mut runner = ScriptRunner::new(script.axis_count());
    let mut reports = Vec::new();
    let result = runner.run(&script, |r| reports.push(r.clone()));
    (reports, result, runner)
}

#[test]
fn a_refused_command_ends_the_run_at_its_line_and_changes_nothing() {
    let (reports, result, runner) = run_text(
        "ECAMTable t 0 0, 100 50\n\
         StartECAM 0 1 Repeat t\n\
         GetCommandPosition 1\n\
         SetCommandPosition 1 7\n\
         GetCommandPosition 1\n",
    );
    assert_eq!(positions(&reports, 1), [0]);
    assert_eq!(
        result.unwrap_err().to_string(),
        "t.mc:4: SetCommandPosition: axis 1 follows an E-CAM: `StopECAM 1` before setting or moving it"
    );
    assert_eq!(runner.controller().position(1).unwrap(), 0);
    assert!(runner.controller().ecam_running(1));

    let (_, result, _) = run_text("StopECAM 1");
    assert_eq!(
        result.unwrap_err().to_string(),
        "t.mc:1: StopECAM: no E-CAM drives axis 1"
    );
    let (_, result, runner) =
        run_text("ECAMTable t 0 0, 100 50\nMoveTo 1 500 10\nStartECAM 0 1 Normal t");
    assert!(
        result
            .unwrap_err()
            .problem
            .to_string()
            .contains("is moving (MoveTo)")
    );
    assert!(!runner.controller().ecam_running(1));
    // A single-turn table reaching outside the turn: the engine's refusal.
    let (_, result, runner) =
        run_text("SetSingleTurn 0 50\nECAMTable t 0 0, 100 50\nStartECAM 0 1 Repeat t");
    let err = result.unwrap_err();
    assert_eq!(err.line, Some(3), "{err}");
    assert!(!runner.controller().ecam_running(1));
}

#[test]
fn a_bad_line_stops_the_script_before_anything_runs() {
    let dir = std::env::temp_dir().join(format!("ecam-mc-script-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.mc");
    std::fs::write(
        &path,
        "GetCommandPosition 0\nTrace never.csv\nTick 5\nStartECAM 0 1 Sideways t\n",
    )
    .unwrap();
    let mut seen = Vec::new();
    let err = run_file_with(&path, |r| seen.push(r.clone())).unwrap_err();
    assert_eq!(err.path, path);
    assert_eq!(err.line, Some(4));
    assert!(
        err.to_string().ends_with(
            ":4: StartECAM: unknown E-CAM type 'sideways': use Normal, Periodic or Repeat"
        ),
        "{err}"
    );
    assert!(seen.is_empty(), "nothing ran");
    assert!(!dir.join("never.csv").exists(), "nothing ran");
    let missing = run_file(dir.join("missing.mc")).unwrap_err();
    assert_eq!(missing.line, None);
    assert!(
        missing
            .to_string()
            .contains("missing.mc: cannot read the script"),
        "{missing}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn table_files_are_read_relative_to_the_script() {
    let dir = std::env::temp_dir().join(format!("ecam-mc-tables-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("cams")).unwrap();
    std::fs::write(dir.join("cams/up.csv"), "master,slave\n0,0\n1000,100\n").unwrap();
    std::fs::write(dir.join("cams/bad.csv"), "master,slave\n0,0\n1000,1.5\n").unwrap();
    std::fs::write(
        dir.join("ok.mc"),
        "ECAMTableFile up cams/up.csv\nStartECAM 0 1 Repeat up\nMoveTo 0 2500 25\nTick 25\nGetCommandPosition 1\n",
    )
    .unwrap();
    std::fs::write(dir.join("bad.mc"), "\nECAMTableFile up cams/bad.csv\n").unwrap();
    assert_eq!(positions(&run_file(dir.join("ok.mc")).unwrap(), 1), [250]);
    let err = run_file(dir.join("bad.mc")).unwrap_err().to_string();
    assert!(
        err.contains(":2: ECAMTableFile: in table file")
            && err.ends_with("line 3: slave `1.5` is not an integer"),
        "{err}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn trace_writes_one_row_per_cycle() {
    let dir = std::env::temp_dir().join(format!("ecam-mc-trace-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let script = dir.join("trace.mc");
    std::fs::write(
        &script,
        "SetSingleTurn 0 300\n\
         ECAMTable t 0 0, 300 30\n\
         StartECAM 0 1 Repeat t\n\
         Trace out.csv 0 1\n\
         MoveTo 0 400 4\n\
         Tick 5\n\
         Trace Off\n\
         Tick 3\n",
    )
    .unwrap();
    run_file(&script).unwrap();
    let csv = std::fs::read_to_string(dir.join("out.csv")).unwrap();
    assert_eq!(
        csv,
        "cycle,axis0,axis1\n0,0,0\n1,100,10\n2,200,20\n3,0,30\n4,100,40\n5,100,40\n"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_engine_fault_shows_in_the_status() {
    let (reports, result, _) = run_text(
        "SetSingleTurn 0 30000\n\
         SetMaxMasterStep 0 9000\n\
         ECAMTable doc 0 500, 10000 1500, 20000 1000, 30000 2000\n\
         StartECAM 0 1 Repeat doc\n\
         MoveTo 0 20000 1\n\
         Tick 1\n\
         GetECAMStatus 1\n",
    );
    result.unwrap();
    let Some(Report::ECamStatus { running, fault, .. }) = reports.last() else {
        panic!("{reports:?}");
    };
    assert!(!running);
    assert_eq!(*fault, Some(ecam_engine::EngineError::MasterStep));
}

mod never_panics {
    use ecam_mc::script::{Script, ScriptRunner};
    use proptest::prelude::*;

    fn number() -> impl Strategy<Value = String> {
        prop_oneof![
            Just(i64::MIN.to_string()),
            Just(i64::MAX.to_string()),
            Just("-1".to_owned()),
            Just("0".to_owned()),
            Just("30000".to_owned()),
            Just("99999999999999999999".to_owned()),
            Just("x".to_owned()),
            (-100_000i64..100_000).prop_map(|n| n.to_string()),
        ]
    }

    fn line() -> impl Strategy<Value = String> {
        let axis = prop_oneof![Just("0"), Just("1"), Just("2"), Just("-1")];
        (0usize..12, axis, number(), number(), 0u8..4).prop_map(|(k, axis, a, b, small)| match k {
            0 => format!("SetSingleTurn {axis} {a}"),
            1 => format!("SetUserUnit {axis} {a}"),
            2 => format!("SetMaxMasterStep {axis} {a}"),
            3 => format!("SetCommandPosition {axis} {a}"),
            4 => format!("MoveTo {axis} {a} {small}"),
            5 => format!("ECAMTable t 0 {a}, {b} {a}, 40000 {b}"),
            6 => format!("StartECAM 0 {axis} Repeat t"),
            7 => format!("StartECAM {axis} 1 Periodic t"),
            8 => format!("StopECAM {axis}"),
            9 => format!("Tick {small}"),
            10 => format!("GetECAMStatus {axis}"),
            _ => format!("GetCommandPosition {axis}"),
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(crate::cases(256)))]

        /// Any script, however wrong, is parsed or refused with a message,
        /// and runs or stops at a line: never a panic.
        #[test]
        fn random_scripts_never_panic(lines in prop::collection::vec(line(), 1..24)) {
            let text = format!("ECAMTable t 0 0, 30000 1500\n{}", lines.join("\n"));
            match Script::parse(&text, "fuzz.mc") {
                Ok(script) => {
                    let mut runner = ScriptRunner::new(script.axis_count());
                    let mut printed = 0usize;
                    if let Err(e) = runner.run(&script, |_| printed += 1) {
                        prop_assert!(e.line.is_some_and(|l| l >= 2), "{e}");
                    }
                }
                Err(e) => prop_assert!(!e.problem.to_string().is_empty() && e.line.is_some(), "{e}"),
            }
        }
    }
}
