//! The IL parser: accepted forms, and errors that name file:line and what was expected.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use ecam_plc::Program;

fn error(source: &str) -> String {
    Program::parse(source, "prog.il").unwrap_err().to_string()
}

#[test]
fn errors_name_file_line_and_expectation() {
    assert_eq!(
        error("LD X0\n\nOUT Q5\n"),
        "prog.il:3: OUT operand 1: unknown device `Q5` (expected D, M, X, Y, C, T and a number, X/Y in octal, or a K/H/E constant)"
    );
    assert!(
        error("LD X0\nMOV K1 D9000\n")
            .starts_with("prog.il:2: MOV operand 2: device `D9000` is out of range")
    );
    assert!(error("LD X8\n").starts_with("prog.il:1: LD operand 1: unknown device `X8`"));
    assert!(error("LD X0\nFOO D0\n").starts_with("prog.il:2: unknown instruction `FOO`"));
    assert!(error("LD X0\nMOV K1\n").contains("MOV expects 2 operands (S D), found 1"));
    assert!(error("LD D0\n").contains(
        "expected a bit device X, Y, M, a counter contact C, a timer contact T (each optionally index-modified, C5Z0) or a bit of a register Dn.b, found D0"
    ));
    assert!(
        error("LD X0\nOUT X1\n")
            .contains("expected an output Y, a relay M (optionally index-modified, M0Z1) or a bit of a register Dn.b, found X1")
    );
    assert!(error("LD X0\nMOV K40000 D0\n").contains("out of range (K-32768 to K32767)"));
    assert!(error("LD X0\nDMOV K1 D8511\n").contains("D8511 has no D8512"));
    assert!(error("LD X0\nMOV D0 K1\n").contains("expected a D register, a counter C, an index register V/Z or a word group KnM/KnY, found K1"));
    assert!(
        error("LD X0\nPLSY K100 K10 Y4\n").contains("expected a pulse output Y0, Y1, Y2 or Y3")
    );
    assert!(error("LD X0\nDEMOV Efoo D0\n").contains("not an E constant"));
    assert!(error("OUT Y0\n").starts_with("prog.il:1: this instruction has no power flow"));
    assert!(error("LD X0\nANB\n").starts_with("prog.il:2: ANB/ORB needs two logic blocks"));
    assert!(error("LD X0\nMPP\n").starts_with("prog.il:2: MPP without a matching MPS"));
    assert!(error("LD X0\nLD X1\nOUT Y0\n").starts_with("prog.il:3: 2 logic blocks are open"));
    assert!(error("LD X0\nOUT C0\n").contains("needs a set value"));
    assert!(error("LD X0\nZRST D10 D0\n").contains("must not come after"));
    assert!(error("LD X0\nZRST D0 M10\n").contains("same kind"));
    assert!(error("LD X0\nECAM C231 D0 X0 Y0 Y1\n").contains("DECAM"));
    assert!(error("LD X0\nMOVQ K1 D0\n").contains("unknown instruction `MOVQ`"));
    assert!(error("LD X0\nCMP K1 K2 M8510\n").contains("two bits after it"));
    assert!(error("LD X0\nEND K1\n").starts_with("prog.il:2: END takes no operands"));
}

#[test]
fn branches_after_mpp_may_open_blocks() {
    let src = "LD X0\nMPS\nAND X1\nOUT Y1\nMPP\nLD X2\nOR X3\nANB\nOUT Y2\nLD X4\nOUT Y3\n";
    assert!(Program::parse(src, "t.il").is_ok());
}

#[test]
fn an_mps_never_popped_is_refused_at_its_line() {
    // Accepted silently before: the branch point was left open to END.
    assert_eq!(
        error("LD X0\nMPS\nAND X1\nOUT Y0\nMRD\nOUT Y1\nEND\n"),
        "prog.il:2: MPS is never closed: expected an MPP for its last branch"
    );
    assert!(
        error("LD X0\nMPS\nOUT Y0\nMPS\nOUT Y1\nMPP\nOUT Y2\n")
            .starts_with("prog.il:2: MPS is never closed")
    );
}

#[test]
fn a_16_bit_counter_refuses_a_negative_set_value() {
    // K-1 made the contact of C5 on before the first count.
    assert!(
        error("LD X0\nOUT C5 K-1\n")
            .starts_with("prog.il:2: OUT C5 operand 2: set value -1 is out of range")
    );
    assert!(error("LD X0\nOUT C5 HFFFF\n").contains("out of range for a 16-bit counter"));
    // 32-bit counters count both ways: a negative set value is fine.
    assert!(Program::parse("LD X0\nOUT C200 K-1\n", "t.il").is_ok());
    assert!(Program::parse("LD X0\nOUT C5 K0\n", "t.il").is_ok());
}
