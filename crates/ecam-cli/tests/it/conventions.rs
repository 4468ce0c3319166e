//! The conventions of a well-kept command-line tool (issue 28): quiet on a
//! closed pipe, one exit-code scheme, `-v`/`-q` on every command,
//! completions that offer names, a progress bar only where a person
//! watches, help texts that describe their own command.

use std::io::Read;
use std::process::{Command, Stdio};

use crate::common::{ecam, ok, scratch_dir};

fn bin() -> Command {
    Command::new(env!("CARGO_BIN_EXE_ecam"))
}

#[test]
fn a_closed_pipe_ends_the_command_quietly() {
    // The reader takes one line and closes the pipe, as `| head -1` does.
    let mut child = bin()
        .args(["law", "cycloid", "--points", "100000"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdout = child.stdout.take().unwrap();
    let mut first = [0u8; 16];
    stdout.read_exact(&mut first).unwrap();
    drop(stdout);
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(0), "{err}");
    assert!(err.is_empty(), "nothing on stderr: {err}");
}

#[test]
fn usage_mistakes_exit_2_failures_1() {
    let dir = scratch_dir("conventions-exit");
    let table = dir.join("t.csv");
    std::fs::write(&table, "master,slave\n0,0\n10,x\n").unwrap();
    let program = "../../examples/plc/decam_cyclic.il";
    for usage in [
        vec!["law", "cycloid", "--points", "1"],
        vec!["plc", "run", program, "--ms", "1", "--set", "D100"],
        vec!["plc", "run", program, "--ms", "1", "--set", "D100=99999"],
        vec!["plc", "run", program, "--ms", "1", "--dump", "D2019:0"],
        vec!["plc", "run", program, "--ms", "1", "--wire", "Y1-X0"],
        vec!["plc", "run", program, "--ms", "1", "--load", "M10=t.csv"],
        vec![
            "pmd",
            "run",
            "../../examples/pmd/three_entry.pmd",
            "--define",
            "a",
        ],
        vec![
            "table",
            "show",
            "t.csv",
            "--master-speed",
            "1",
            "--units",
            "inch",
            "--unit-per-pulse",
            "1",
        ],
    ] {
        assert_eq!(ecam(&usage).status.code(), Some(2), "{usage:?}");
    }
    for failure in [
        vec!["table", "show", table.to_str().unwrap()],
        vec!["plc", "run", "no-such-program.il", "--ms", "1"],
        vec!["simulate", "no-such-scenario.toml"],
    ] {
        assert_eq!(ecam(&failure).status.code(), Some(1), "{failure:?}");
    }
}

#[test]
fn verbose_and_quiet_change_every_commands_messages() {
    let dir = scratch_dir("conventions-verbosity");
    let out = dir.join("t.csv");
    let commands: Vec<Vec<&str>> = vec![
        vec!["law", "--list"],
        vec!["table", "gen", "rotary-cut", "-o", out.to_str().unwrap()],
        vec!["table", "show", "../../examples/tables/doc001.csv"],
        vec![
            "simulate",
            "../../examples/scenarios/002-linear-incremental.toml",
        ],
        vec![
            "plc",
            "run",
            "../../examples/plc/decam_cyclic.il",
            "--ms",
            "10",
        ],
        vec!["pmd", "run", "../../examples/pmd/three_entry.pmd"],
        vec!["mc", "run", "../../examples/mc/single_turn_start.mc"],
        vec!["completions", "bash"],
        vec!["man"],
    ];
    for args in commands {
        let run = |flag: &str| {
            let mut all = vec![flag];
            all.extend(&args);
            let out = ecam(&all);
            assert!(out.status.success(), "{all:?}");
            String::from_utf8(out.stderr).unwrap()
        };
        let (verbose, quiet) = (run("-v"), run("-q"));
        assert!(
            verbose.contains("debug: "),
            "{args:?}: -v says more: {verbose:?}"
        );
        assert!(!quiet.contains("debug: "), "{args:?}");
    }
    // What a command reports beside its output is `info`: -q hides it.
    let generate = ["table", "gen", "rotary-cut", "-o", out.to_str().unwrap()];
    let said = String::from_utf8(ecam(&generate).stderr).unwrap();
    assert!(said.contains("regime: "), "{said}");
    let mut quiet = vec!["-q"];
    quiet.extend(generate);
    assert_eq!(String::from_utf8(ecam(&quiet).stderr).unwrap(), "");
}

#[test]
fn completions_offer_laws_generators_and_choices_not_files() {
    let bash = ok(ecam(&["completions", "bash"]));
    assert!(
        bash.contains("cycloid") && bash.contains("modified-sine"),
        "laws"
    );
    assert!(
        bash.contains("rotary-cut") && bash.contains("keypoints"),
        "generators"
    );
    // `--accel` offers the curves' names (not file names).
    let accel = bash
        .lines()
        .skip_while(|l| !l.trim_start().starts_with("--accel)"))
        .nth(1)
        .unwrap();
    assert!(
        accel.contains("uniform uniform-acceleration b-type") && !accel.contains("compgen -f"),
        "{accel}"
    );
    assert!(
        bash.contains("mid-all") && bash.contains("\"mm deg\""),
        "choices"
    );
}

#[test]
fn each_generator_says_what_it_is() {
    let help = ok(ecam(&["table", "gen", "--help"]));
    assert!(
        !help.contains("Output options shared by every generator"),
        "{help}"
    );
    assert!(help.contains("rotary-cut  ECAMTBX K100"), "{help}");
    let dir = scratch_dir("conventions-man");
    ok(ecam(&["man", "--dir", dir.to_str().unwrap()]));
    let page = std::fs::read_to_string(dir.join("ecam-table-gen-fly-saw.1")).unwrap();
    assert!(
        page.contains("K101") && !page.contains("Output options shared"),
        "{page}"
    );
}

#[test]
fn a_long_run_shows_a_progress_bar_on_a_terminal_only() {
    // `script` gives the run a terminal; a pipe (the second run) never
    // sees the bar. The run takes well over a second of real time: 30 s
    // simulated in a debug build, 1000 s in an optimised one (`cargo test
    // --release`), which simulates them some 15 times faster.
    let ecam_bin = env!("CARGO_BIN_EXE_ecam");
    let ms = if cfg!(debug_assertions) {
        30_000
    } else {
        300_000
    };
    let args =
        format!("plc run ../../examples/plc/decam_cyclic.il --wire Y1:X0 --ms {ms} --dump D2001");
    let Ok(out) = Command::new("script")
        .args(["-qec", &format!("{ecam_bin} {args}"), "/dev/null"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
    else {
        // util-linux's `script` is part of every Debian; say so if not.
        panic!("this test needs `script` (util-linux)");
    };
    let seen = String::from_utf8_lossy(&out.stdout);
    assert!(
        seen.contains("running [") && seen.contains('%'),
        "no bar: {seen:?}"
    );
    let piped = ecam(&args.split(' ').collect::<Vec<_>>());
    let err = String::from_utf8_lossy(&piped.stderr);
    assert!(!err.contains('%'), "{err}");
}
