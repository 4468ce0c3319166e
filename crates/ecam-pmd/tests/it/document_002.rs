//! Document 002's rules, run through the script runner.
#![allow(clippy::unwrap_used, missing_docs)]

use ecam_pmd::{Report, ScriptRunner, event_bit};

/// Runs `script`; gives the values printed and the errors (line, message).
fn run(script: &str) -> (Vec<i64>, Vec<(usize, String)>) {
    let mut runner = ScriptRunner::new();
    let mut values = Vec::new();
    let mut errors = Vec::new();
    for report in runner.run_script(script) {
        match report {
            Report::Value { value, .. } => values.push(value),
            Report::Error { line, message, .. } => errors.push((line, message)),
        }
    }
    (values, errors)
}

const THREE_ENTRY_CAM: &str = "
SetBufferLength 1 3
WriteBuffer 1 0
WriteBuffer 1 100
WriteBuffer 1 200
SetProfileMode 8
Update
SetCam CamBufferID 1
SetCam CamCounts 100
SetCam CamSource 0x0001
";

#[test]
fn three_entry_table_is_a_straight_line_across_the_seam() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 100 100
Tick 100
GetCommandedPosition
MoveTo 1 101 1
Tick 1
GetCommandedPosition
MoveTo 1 350 249
Tick 249
GetCommandedPosition
MoveTo 1 -1 351
Tick 351
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [200, 202, 700, -2]);
}

#[test]
fn smooth_stop_waits_for_the_end_of_the_table_in_either_direction() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 130 130
Tick 130
SetStopMode 2
Update
GetActivityStatus
MoveTo 1 150 20
Tick 20
GetActivityStatus
GetCommandedPosition
MoveTo 1 201 51
Tick 51
GetActivityStatus
GetCommandedPosition
' again, backwards this time
SetEventAction 0 9
MoveTo 1 160 41
Tick 41
SetStopMode Smooth
Update
MoveTo 1 100 60
Tick 60
GetActivityStatus
GetCommandedPosition
GetEventStatus
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    // Stop requested at input 130 (cycle 100..200): still camming at 150,
    // stopped at 200 with output 400, holding at 201.
    assert_eq!(values[0] >> 13, 1);
    assert_eq!(values[1] >> 13, 1);
    assert_eq!(values[2], 300);
    assert_eq!(values[3] >> 13, 0);
    assert_eq!(values[4], 400);
    // Restarted at master 201 (bumpless, output 400), backwards to 100:
    // the table input 0 of that start is master 201, so the stop happens at
    // master 101 going down, output 400 - 200 = 200.
    assert_eq!(values[5] >> 13, 0);
    assert_eq!(values[6], 200);
    assert_ne!(values[7] & i64::from(event_bit::MOTION_COMPLETE), 0);
}

#[test]
fn abrupt_stop_holds_the_commanded_position() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 30 30
Tick 30
SetStopMode 1
GetActivityStatus
Update
GetActivityStatus
MoveTo 1 90 60
Tick 60
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [0x2400, 0, 60]);
}

#[test]
fn breakpoint_with_abrupt_stop_action() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetBreakpointValue 0 10
SetBreakpoint 0 0x191
SetBreakpointValue 1 40
SetBreakpoint 1 0x121
MoveTo 1 100 100
Tick 100
GetCommandedPosition
GetEventStatus
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    // Started at master 10 (input 0, output 0). The stop is processed when
    // master reaches 40, before that cycle's cam step: the output holds the
    // value of master 39.
    assert_eq!(values[0], 58);
    let expected = event_bit::BREAKPOINT_0 | event_bit::BREAKPOINT_1 | event_bit::MOTION_COMPLETE;
    assert_eq!(values[1], i64::from(expected));
}

#[test]
fn start_without_counts_or_buffer_is_a_motion_error() {
    let (values, errors) = run("
SetBufferLength 1 3
SetProfileMode 8
Update
SetCam CamCounts 100
SetEventAction 0 9
GetActivityStatus
GetEventStatus
ResetEventStatus 0
SetCam CamBufferID 1
SetEventAction 0 9
GetActivityStatus
GetEventStatus
");
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [0, i64::from(event_bit::MOTION_ERROR), 0x2400, 0]);
}

#[test]
fn start_outside_cam_mode_does_nothing() {
    let (values, errors) = run("
SetBufferLength 1 3
SetEventAction 0 9
GetActivityStatus
GetEventStatus
");
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [0, 0]);
}

#[test]
fn cam_parameters_need_cam_mode_and_an_inactive_cam() {
    let script = format!(
        "SetCam CamCounts 100
GetCam CamCounts
{THREE_ENTRY_CAM}
SetCam CamStartCount 50
SetEventAction 0 9
SetCam CamCounts 200
GetCam CamCounts
SetProfileMode 0
Update
GetProfileMode
SetStopMode 1
Update
SetProfileMode 0
Update
GetProfileMode
SetProfileMode 8
Update
GetCam CamCounts
GetCam CamStartCount
"
    );
    let (values, errors) = run(&script);
    let lines: Vec<usize> = errors.iter().map(|e| e.0).collect();
    assert_eq!(lines, [1, 2, 16, 19], "{errors:?}");
    assert!(
        errors[0]
            .1
            .contains("not in the ElectronicCam profile mode")
    );
    assert!(errors[2].1.contains("is active"));
    assert!(errors[3].1.contains("in motion"));
    // CamCounts unchanged by the refused SetCam, mode unchanged by the
    // refused Update; leaving and re-entering cam mode resets to defaults.
    assert_eq!(values, [100, 8, 0, 0, 0]);
}

#[test]
fn bad_commands_say_why_and_change_nothing() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetCam CamStartCount 20
SetCamm CamCounts 5
SetCam CamCounts
SetCam CamCounts 1
SetCam CamCounts 536870913
SetCam CamStartCount 101
SetCam CamSource 0x0300
SetCam CamSource 0x0009
SetCam CamBufferID 32
SetCam CamOutputOffset 3
SetCam 6 1
SetBufferWriteIndex 1 3
WriteBuffer 1 0x80000000
SetBreakpoint 0 0x1F1
SetBreakpoint 2 0x191
Axis 4
MoveTo 1 10 -1
SetProfileMode 5
GetCam CamCounts
GetCam CamStartCount
GetCam CamSource
GetCam CamBufferID
ReadBuffer 1 0
ReadBuffer 1 2
"
    );
    let (values, errors) = run(&script);
    assert_eq!(errors.len(), 17, "{errors:?}");
    let text: Vec<&str> = errors.iter().map(|e| e.1.as_str()).collect();
    assert_eq!(text[0], "unknown command 'SetCamm'");
    assert_eq!(text[1], "SetCam takes 2 arguments (PARAM VALUE), got 1");
    assert!(text[2].starts_with("CamCounts 1 is out of range"));
    assert!(text[4].starts_with("CamStartCount 101 is out of range"));
    assert!(text[8].contains("read only"));
    assert!(text[9].contains("unknown cam parameter"));
    assert!(text[10].starts_with("index 3 is past the length of buffer 1"));
    assert!(text[14].starts_with("no axis 4"));
    assert_eq!(values, [100, 20, 1, 1, 0, 200]);
}

#[test]
fn buffer_writes_take_over_at_the_next_seam_and_the_shape_is_locked() {
    // [0, 100, 200] over 100 counts; at input 75 the last value becomes 300.
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 75 75
Tick 75
GetCommandedPosition
SetBufferWriteIndex 1 2
WriteBuffer 1 300
Tick 1
GetCommandedPosition
MoveTo 1 100 25
Tick 25
GetCommandedPosition
MoveTo 1 150 50
Tick 50
GetCommandedPosition
MoveTo 1 200 50
Tick 50
GetCommandedPosition
SetBufferLength 1 4
SetBufferStart 1 8
"
    );
    let (values, errors) = run(&script);
    // The old table runs to its end (200) without a step; from the seam on
    // the new one continues from there: 200 + [0, 100, 300].
    assert_eq!(values, [150, 150, 200, 300, 500]);
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(errors[0].1.contains("active cam on axis 0"));
}

#[test]
fn time_source_advances_one_count_per_cycle() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetCam CamSource 0x0200
SetEventAction 0 9
Tick 25
GetCommandedPosition
GetCam CamSource
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [50, 0x200]);
}

#[test]
fn cam_on_commanded_position_of_another_cam() {
    // Axis 0 follows axis 1's actual position; axis 2 follows axis 0's
    // commanded position through the same table (twice the slope again).
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
Axis 2
SetProfileMode 8
Update
SetCam CamBufferID 1
SetCam CamCounts 100
SetCam CamSource 0x0100
SetEventAction 0 9
MoveTo 1 10 10
Tick 10
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [40]);
}

#[test]
fn crossing_trigger_on_commanded_position() {
    let script = format!(
        "{THREE_ENTRY_CAM}
Axis 1
SetActualPosition 50
Axis 0
SetBreakpointValue 0 20
SetBreakpoint 0 0x591
MoveTo 1 0 50
Tick 40
GetActivityStatus
Tick 1
GetActivityStatus
GetCam CamInputOffset
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    // Axis 1 goes down from 50: it crosses 20 on the way to 19 (cycle 31)
    // — already active at cycle 40.
    assert_eq!(values[0] >> 13, 1);
    assert_eq!(values[2], -19);
}

#[test]
fn profile_mode_takes_effect_on_update_and_parameters_go_by_number() {
    let (values, errors) = run("\u{feff}SetProfileMode 8
GetProfileMode
SetCam 1 100
Update
GetProfileMode
SetCam 1 100
SetCam 2 40
SetCam 3 0x0102
GetCam 1
GetCam 2
GetCam 3
GetCam 4
GetCam 5
GetCam 0
");
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert_eq!(errors[0].0, 3);
    assert_eq!(values, [0, 8, 100, 40, 0x0102, 0, 0, 0]);
}

#[test]
fn positions_and_offsets_read_back_as_signed_32_bit_registers() {
    // An incremental cam (stroke 10^9 per table cycle) driven by time runs
    // past 2^31. GetCam returns "a signed 32 bit value" (document 002) and
    // the position registers are 32 bits: the readings wrap like the
    // device's registers, while the motion itself stays continuous.
    let script = "
SetBufferLength 0 2
WriteBuffer 0 0
WriteBuffer 0 1000000000
SetProfileMode 8
Update
SetCam CamBufferID 0
SetCam CamCounts 2
SetCam CamSource 0x0200
SetEventAction 0 9
Tick 6
GetCommandedPosition
GetActualPosition
GetCam CamOutputOffset
Tick 1
GetCommandedPosition
";
    let (values, errors) = run(script);
    assert!(errors.is_empty(), "{errors:?}");
    let wrap = |v: i64| i64::from(v as i32);
    // Started at time 0 (input 0); 6 cycles = 3 table cycles = 3e9 counts.
    assert_eq!(values[0], wrap(3_000_000_000));
    assert_eq!(values[1], wrap(3_000_000_000));
    assert_eq!(values[2], wrap(3_000_000_000), "offset after three wraps");
    assert_eq!(values[3], wrap(3_500_000_000));
    for v in values {
        assert!(
            i32::try_from(v).is_ok(),
            "{v} is not a 32-bit register value"
        );
    }
}

#[test]
fn a_cam_the_engine_must_stop_raises_motion_error_not_motion_complete() {
    // Axis 1 runs an incremental cam on time (2^32 - 1 counts per 2 cycles);
    // axis 0 cams on axis 1's commanded position through the same steep
    // table, so its output leaves the 64-bit range within a few cycles.
    let script = "
SetBufferLength 0 2
WriteBuffer 0 -2147483648
WriteBuffer 0 2147483647
Axis 1
SetProfileMode 8
Update
SetCam CamBufferID 0
SetCam CamCounts 2
SetCam CamSource 0x0200
SetEventAction 0 9
Axis 0
SetProfileMode 8
Update
SetCam CamBufferID 0
SetCam CamCounts 2
SetCam CamSource 0x0101
SetEventAction 0 9
Tick 10
GetActivityStatus
GetEventStatus
";
    let (values, errors) = run(script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values[0] >> 13, 0, "the cam is no longer active");
    assert_ne!(
        values[1] & i64::from(event_bit::MOTION_ERROR),
        0,
        "MotionError"
    );
    assert_eq!(values[1] & i64::from(event_bit::MOTION_COMPLETE), 0);
}

#[test]
fn a_smooth_stop_is_not_lost_when_a_mode_change_is_also_pending() {
    use ecam_pmd::ScriptRunner;
    let mut runner = ScriptRunner::new();
    let script = "\
SetBufferStart 1 0
SetBufferLength 1 3
WriteBuffer 1 0
WriteBuffer 1 100
WriteBuffer 1 200
Axis 0
SetProfileMode 8
Update
SetCam CamBufferID 1
SetCam CamCounts 100
SetCam CamSource 0x0001
SetEventAction 0 9
MoveTo 1 50 50
Tick 50
SetProfileMode 0
SetStopMode 2
Update
MoveTo 1 150 100
Tick 100
GetCommandedPosition
GetActivityStatus
";
    let lines: Vec<String> = runner
        .run_script(script)
        .iter()
        .map(ecam_pmd::Report::to_json)
        .collect();
    assert!(
        lines
            .iter()
            .any(|l| l.contains("\"cmd\":\"Update\"") && l.contains("error")),
        "the mode change is refused in motion: {lines:?}"
    );
    // The smooth stop still took effect: the cam stopped at the table end
    // (input 100, output 200) although the master went on to 150.
    assert!(
        lines
            .iter()
            .any(|l| l.contains("GetCommandedPosition") && l.contains("\"value\":200")),
        "{lines:?}"
    );
}

#[test]
fn a_smooth_stop_on_the_table_end_going_forwards_stops_there_at_once() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 100 100
Tick 100
SetStopMode Smooth
Update
GetActivityStatus
GetEventStatus
MoveTo 1 250 150
Tick 150
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    // On the table end (input 100, output 200): inactive at once, motion
    // complete, and no second table as the master goes on to 250.
    assert_eq!(values[0], 0);
    assert_ne!(values[1] & i64::from(event_bit::MOTION_COMPLETE), 0);
    assert_eq!(values[2], 200);
}

#[test]
fn a_smooth_stop_on_the_table_start_going_backwards_stops_there_at_once() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 60 60
Tick 60
MoveTo 1 0 60
Tick 60
SetStopMode Smooth
Update
GetActivityStatus
Tick 10
GetCommandedPosition
GetEventStatus
SetCam CamCounts 50
GetCam CamCounts
"
    );
    let (values, errors) = run(&script);
    // The master rests on the table start: the stop must not wait for it
    // to pass the start, and the cam's parameters are free again.
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values[0], 0);
    assert_eq!(values[1], 0);
    assert_ne!(values[2] & i64::from(event_bit::MOTION_COMPLETE), 0);
    assert_eq!(values[3], 50);
}

#[test]
fn a_smooth_stop_on_a_table_end_lets_the_same_update_change_the_mode() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 200 200
Tick 200
SetProfileMode Trapezoidal
SetStopMode Smooth
Update
GetProfileMode
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [0, 400]);
}

#[test]
fn a_smooth_stop_breakpoint_on_the_table_end_runs_no_extra_table() {
    // Breakpoint 1 on axis 0: smooth stop (3) when the time reaches 105
    // (trigger 7), i.e. 0x730. The master reached the table end (input
    // 100) at time 100 and rests there when it fires.
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
SetBreakpointValue 1 105
SetBreakpoint 1 0x730
MoveTo 1 100 100
Tick 110
GetActivityStatus
MoveTo 1 250 150
Tick 150
GetCommandedPosition
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [0, 200]);
}

#[test]
fn an_abrupt_stop_holds_a_simulated_move_where_it_is() {
    let (values, errors) = run("
Axis 1
MoveTo 1 100 100
Tick 40
GetActivityStatus
SetStopMode Abrupt
Update
GetActivityStatus
Tick 60
GetActualPosition
GetCommandedPosition
");
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values[0], i64::from(ecam_pmd::activity_bit::IN_MOTION));
    assert_eq!(values[1..], [0, 40, 40]);
}

#[test]
fn a_breakpoint_abrupt_stop_holds_a_simulated_move() {
    // Breakpoint 0 of axis 1: abrupt stop (2) when axis 1's actual position
    // is at least 40 (trigger 1), i.e. 0x121. The move steps before the
    // breakpoints, so it holds the position that fired it.
    let (values, errors) = run("
Axis 1
SetBreakpointValue 0 40
SetBreakpoint 0 0x121
MoveTo 1 100 100
Tick 100
GetActualPosition
GetEventStatus
");
    assert!(errors.is_empty(), "{errors:?}");
    // A simulated move is not a cam: no MotionComplete, as when it arrives.
    assert_eq!(values, [40, i64::from(event_bit::BREAKPOINT_0)]);
}

#[test]
fn a_smooth_stop_of_a_simulated_move_also_holds_at_once() {
    let (values, errors) = run("
Axis 1
MoveTo 1 -100 50
Tick 10
SetStopMode Smooth
Update
Tick 50
GetActualPosition
GetActivityStatus
");
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [-20, 0]);
}

#[test]
fn stopping_the_cam_master_holds_the_cam_output() {
    let script = format!(
        "{THREE_ENTRY_CAM}
SetEventAction 0 9
MoveTo 1 100 100
Tick 30
Axis 1
SetStopMode Abrupt
Update
Tick 70
Axis 0
GetCommandedPosition
GetActivityStatus
"
    );
    let (values, errors) = run(&script);
    assert!(errors.is_empty(), "{errors:?}");
    // The master stopped at 30: the cam (still active) holds 2 × 30.
    assert_eq!(values[0], 60);
    assert_eq!(values[1] >> 13, 1);
}

#[test]
fn an_abrupt_stop_of_a_simulated_move_lets_the_same_update_change_the_mode() {
    let (values, errors) = run("
Axis 1
MoveTo 1 100 100
Tick 10
SetProfileMode ElectronicCam
SetStopMode Abrupt
Update
GetProfileMode
Tick 10
GetActualPosition
");
    assert!(errors.is_empty(), "{errors:?}");
    assert_eq!(values, [8, 10]);
}
