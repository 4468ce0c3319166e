//! The syntax tree the parser builds: each mnemonic and operand form
//! becomes the instruction the interpreter runs (what a program does with
//! them is tested through `Plc` in `tests/it/`).

use super::instruction::WordBit;
use super::*;
use crate::device::Device;

fn one(line: &str) -> Instruction {
    let program = parse(&format!("LD M8000\n{line}\n"), "t.il").unwrap();
    program.statements[1].instruction.clone()
}

fn parse(source: &str, file: &str) -> Result<Program, ParseError> {
    Program::parse(source, file)
}

#[test]
fn contacts_and_stack_instructions() {
    let src = "ld x0\nLDI X1\nANB\nANDP M5\nORF C231\nMPS\nANI Y7\nOUT Y0\nMRD\nOUT Y1\nMPP\nOUT Y2\nEND\nGARBAGE";
    let program = parse(src, "t.il").unwrap();
    let got: Vec<_> = program
        .statements
        .iter()
        .map(|s| s.instruction.clone())
        .collect();
    assert_eq!(
        got[0],
        Instruction::Load(Contact::Open, BitRef::Device(Device::X(0)))
    );
    assert_eq!(
        got[1],
        Instruction::Load(Contact::Closed, BitRef::Device(Device::X(1)))
    );
    assert_eq!(got[2], Instruction::AndBlock);
    assert_eq!(
        got[3],
        Instruction::And(Contact::Rising, BitRef::Device(Device::M(5)))
    );
    assert_eq!(
        got[4],
        Instruction::Or(Contact::Falling, BitRef::Device(Device::C(231)))
    );
    assert_eq!(got[5], Instruction::Push);
    assert_eq!(got[8], Instruction::Read);
    assert_eq!(got[10], Instruction::Pop);
    assert_eq!(got.len(), 12, "lines after END are ignored");
    assert_eq!(program.statements[11].line, 12);
}

#[test]
fn applied_instructions_and_their_forms() {
    assert_eq!(
        one("MOV K100 D0"),
        Instruction::Move {
            width: Width::Word,
            exec: Exec::Continuous,
            src: Source::Constant(100),
            dst: Dest::Register(0)
        }
    );
    assert_eq!(
        one("DMOVP HFFFFFFFF D10"),
        Instruction::Move {
            width: Width::Double,
            exec: Exec::Pulse,
            src: Source::Constant(-1),
            dst: Dest::Register(10)
        }
    );
    assert_eq!(
        one("DEMOV E1.6667 D106"),
        Instruction::FloatMove {
            exec: Exec::Continuous,
            src: FloatSource::Constant(1.6667),
            dst: 106
        }
    );
    assert_eq!(
        one("DSUB C231 D0 D2"),
        Instruction::Arith {
            op: ArithOp::Sub,
            width: Width::Double,
            exec: Exec::Continuous,
            s1: Source::Counter(231),
            s2: Source::Register(0),
            dst: Dest::Register(2)
        }
    );
    assert_eq!(
        one("ZRST M0 M10"),
        Instruction::ZoneReset {
            exec: Exec::Continuous,
            kind: ZoneDevice::M,
            first: 0,
            last: 10
        }
    );
    assert_eq!(
        one("DPLSY K20000 K0 Y1"),
        Instruction::PulseOutput {
            width: Width::Double,
            frequency: Source::Constant(20000),
            count: Source::Constant(0),
            output: 1
        }
    );
    assert_eq!(
        one("DECAM C231 D2000 X000 Y000 Y001"),
        Instruction::Decam {
            master: MasterSpec::Counter(231),
            block: 2000,
            start: Device::X(0),
            pulse_output: 0,
            direction: Device::Y(1)
        }
    );
    assert_eq!(
        one("DECAM K10 D1000 M5 Y2 Y5"),
        Instruction::Decam {
            master: MasterSpec::TimeBase(10),
            block: 1000,
            start: Device::M(5),
            pulse_output: 2,
            direction: Device::Y(5)
        }
    );
    assert_eq!(
        one("ECAMTBX D100 K100 D1000 D200"),
        Instruction::Ecamtbx {
            params: 100,
            kind: Source::Constant(100),
            table: 1000,
            result: 200
        }
    );
    assert_eq!(
        one("OUT C231 K2147483647"),
        Instruction::OutCounter {
            counter: 231,
            set_value: Source::Constant(i32::MAX)
        }
    );
    assert!(matches!(
        one("CMPP K1 D0 M10"),
        Instruction::Compare {
            exec: Exec::Pulse,
            ..
        }
    ));
    assert!(matches!(
        one("PLF M3"),
        Instruction::Pulse { rising: false, .. }
    ));
}

#[test]
fn a_utf8_byte_order_mark_and_crlf_line_ends_are_accepted() {
    // "unknown instruction `\u{feff}LD`" before.
    let program = parse("\u{feff}LD M8000\r\nMOV K5 D0\r\nEND\r\n", "t.il").unwrap();
    assert_eq!(program.statements.len(), 2);
    assert!(matches!(
        program.statements[0].instruction,
        Instruction::Load(..)
    ));
}

#[test]
fn mnemonics_parse_into_join_width_and_relation() {
    let program = parse(
        "LD= D0 K5\nANDD<> D2 C235\nOR>= C0 H10\nOUT Y0\nLDD<= K-1 D4\nOR< D0 D1\nAND> D0 K0\nOUT Y1\n",
        "t.il",
    )
    .unwrap();
    let got: Vec<_> = program
        .statements
        .iter()
        .map(|s| s.instruction.clone())
        .collect();
    assert_eq!(
        got[0],
        Instruction::CompareContact {
            join: Join::Load,
            relation: Relation::Equal,
            width: Width::Word,
            s1: Source::Register(0),
            s2: Source::Constant(5),
        }
    );
    assert_eq!(
        got[1],
        Instruction::CompareContact {
            join: Join::And,
            relation: Relation::NotEqual,
            width: Width::Double,
            s1: Source::Register(2),
            s2: Source::Counter(235),
        }
    );
    assert_eq!(
        got[2],
        Instruction::CompareContact {
            join: Join::Or,
            relation: Relation::GreaterOrEqual,
            width: Width::Word,
            s1: Source::Counter(0),
            s2: Source::Constant(16),
        }
    );
    assert!(matches!(
        got[4],
        Instruction::CompareContact {
            join: Join::Load,
            relation: Relation::LessOrEqual,
            width: Width::Double,
            ..
        }
    ));
}

#[test]
fn flow_instructions_parse() {
    let program = parse(
        "LD X0\nCJ P1\nLD X1\ncallp p2\nP1\nLD X2\nOUT Y0\nFEND\nP2\nLD M8000\nINC D0\nSRET\nEND\n",
        "t.il",
    )
    .unwrap();
    let got: Vec<_> = program
        .statements
        .iter()
        .map(|s| s.instruction.clone())
        .collect();
    assert_eq!(
        got[1],
        Instruction::Jump {
            exec: Exec::Continuous,
            pointer: 1
        }
    );
    assert_eq!(
        got[3],
        Instruction::Call {
            exec: Exec::Pulse,
            pointer: 2
        }
    );
    assert_eq!(got[4], Instruction::Label(1));
    assert_eq!(got[7], Instruction::MainEnd);
    assert_eq!(got[11], Instruction::SubReturn);
}

#[test]
fn word_bits_parse_as_contacts_and_coils() {
    let program = parse(
        "ld d2001.0\nANI D2001.F\nOUT d10.a\nLDI D0.1\nSET D1.2\nRST D2001.1\n",
        "t.il",
    )
    .unwrap();
    let bit = |register, bit| BitRef::WordBit(WordBit { register, bit });
    let got: Vec<_> = program
        .statements
        .iter()
        .map(|s| s.instruction.clone())
        .collect();
    assert_eq!(got[0], Instruction::Load(Contact::Open, bit(2001, 0)));
    assert_eq!(got[1], Instruction::And(Contact::Closed, bit(2001, 15)));
    assert_eq!(got[2], Instruction::Out(bit(10, 10)));
    assert_eq!(got[3], Instruction::Load(Contact::Closed, bit(0, 1)));
    assert_eq!(got[4], Instruction::Set(bit(1, 2)));
    assert_eq!(got[5], Instruction::Reset(bit(2001, 1)));
}

#[test]
fn word_groups_parse_as_sources() {
    let program = parse("LD M8000\nMOV k2x10 D0\n", "t.il").unwrap();
    assert_eq!(
        program.statements[1].instruction,
        Instruction::Move {
            width: Width::Word,
            exec: Exec::Continuous,
            src: Source::Group(WordGroup {
                kind: GroupKind::X,
                first: 8,
                digits: 2
            }),
            dst: Dest::Register(0),
        }
    );
}
