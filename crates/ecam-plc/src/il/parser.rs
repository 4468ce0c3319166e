//! Mnemonics and operand checks: source text → [`Program`].

use super::Program;
use super::error::ParseError;
use super::flow;
use super::instruction::{
    ArithOp, BitDest, BitRef, Contact, Dest, Exec, FloatSource, IndexBase, IndexReg, Indexed,
    Instruction, Join, LogicOp, MasterSpec, Relation, Source, Statement, Width, ZoneDevice,
};
use super::lexer::lines;
use super::operand::{Modified, Operand};
use super::validate;
use crate::devices::{C_32BIT_FIRST, D_COUNT, Device, M_COUNT, XY_COUNT};

/// Parses and checks a program. `file` names the source in error messages
/// (`file:line: message`). Lines after `END` are ignored, as on the PLC.
///
/// # Errors
/// The first problem found: unknown mnemonic, wrong operand count or kind,
/// unknown or out-of-range device, constant out of range, unbalanced
/// ANB/ORB/MPS/MRD/MPP, a CJ/CALL to a missing label, a duplicate label, a
/// subroutine label before FEND, SRET in the main program, a subroutine
/// without SRET, recursive or too deeply nested CALLs.
///
/// ```
/// let program = ecam_plc::il::parse("LD X0\nOUT Y0\nEND\n", "demo.il").unwrap();
/// assert_eq!(program.statements.len(), 2);
/// let err = ecam_plc::il::parse("LD X0\nOUT Q9\n", "demo.il").unwrap_err();
/// assert!(err.to_string().starts_with("demo.il:2: "));
/// ```
pub fn parse(source: &str, file: &str) -> Result<Program, ParseError> {
    let error = |line: usize, message: String| ParseError {
        file: file.to_string(),
        line,
        message,
    };
    let mut statements = Vec::new();
    // Editors on Windows often save a UTF-8 byte-order mark; it is not part
    // of the first mnemonic.
    let source = source.strip_prefix('\u{feff}').unwrap_or(source);
    for line in lines(source) {
        let (mnemonic, operand_tokens) = match line.tokens.split_first() {
            Some(split) => split,
            None => continue,
        };
        let mnemonic = mnemonic.to_ascii_uppercase();
        if mnemonic == "END" {
            if !operand_tokens.is_empty() {
                return Err(error(line.number, "END takes no operands".into()));
            }
            break;
        }
        if let Some(label) = label(&mnemonic) {
            if !operand_tokens.is_empty() {
                return Err(error(
                    line.number,
                    format!(
                        "a pointer label {mnemonic} stands alone on its line",
                        mnemonic = ecam_core::excerpt::excerpt(&mnemonic)
                    ),
                ));
            }
            statements.push(Statement {
                line: line.number,
                instruction: Instruction::Label(label.map_err(|m| error(line.number, m))?),
            });
            continue;
        }
        if let Some(flow) = flow_instruction(&mnemonic, operand_tokens) {
            statements.push(Statement {
                line: line.number,
                instruction: flow.map_err(|m| error(line.number, m))?,
            });
            continue;
        }
        let mut operands = Vec::with_capacity(operand_tokens.len());
        for (i, token) in operand_tokens.iter().enumerate() {
            let operand = Operand::parse(token).map_err(|m| {
                error(
                    line.number,
                    format!(
                        "{mnemonic} operand {}: {m}",
                        i + 1,
                        mnemonic = ecam_core::excerpt::excerpt(&mnemonic)
                    ),
                )
            })?;
            operands.push(operand);
        }
        let instruction = instruction(&mnemonic, &operands).map_err(|m| error(line.number, m))?;
        statements.push(Statement {
            line: line.number,
            instruction,
        });
    }
    validate::check(&statements).map_err(|(line, message)| error(line, message))?;
    flow::check(&statements).map_err(|(line, message)| error(line, message))?;
    Ok(Program {
        file: file.to_string(),
        statements,
    })
}

/// `Some` when `mnemonic` is a pointer label `Pn` (P and digits only):
/// its number, or why it is not a usable label.
fn label(mnemonic: &str) -> Option<Result<u8, String>> {
    let digits = mnemonic.strip_prefix('P')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(pointer_number(mnemonic).and_then(|n| {
        if n == flow::END_POINTER {
            Err("P63 is the END pointer (`CJ P63` jumps to END); it cannot label a line".into())
        } else {
            Ok(n)
        }
    }))
}

/// The n of a pointer `Pn`, n = 0–127.
fn pointer_number(token: &str) -> Result<u8, String> {
    let upper = token.to_ascii_uppercase();
    let number = upper
        .strip_prefix('P')
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        .ok_or_else(|| {
            format!(
                "expected a pointer P0–P127, found `{token}`",
                token = ecam_core::excerpt::excerpt(token)
            )
        })?;
    match number.parse::<u8>() {
        Ok(n) if usize::from(n) < flow::POINTER_COUNT => Ok(n),
        _ => Err(format!(
            "pointer {upper} out of range: the LX3V has P0–P{}",
            flow::POINTER_COUNT - 1
        )),
    }
}

/// CJ/CJP/CALL/CALLP/SRET/FEND, whose operand is a pointer rather than a
/// device: `None` for other mnemonics.
fn flow_instruction(mnemonic: &str, tokens: &[&str]) -> Option<Result<Instruction, String>> {
    let pointer = |exec: Exec, call: bool| -> Result<Instruction, String> {
        match tokens {
            [token] => {
                let pointer = pointer_number(token).map_err(|m| {
                    format!(
                        "{mnemonic} operand 1: {m}",
                        mnemonic = ecam_core::excerpt::excerpt(mnemonic)
                    )
                })?;
                if call && pointer == flow::END_POINTER {
                    return Err(format!(
                        "{mnemonic} P63: P63 is the END pointer, only CJ may use it"
                    ));
                }
                Ok(if call {
                    Instruction::Call { exec, pointer }
                } else {
                    Instruction::Jump { exec, pointer }
                })
            }
            _ => Err(format!(
                "{mnemonic} expects 1 operand (Pn), found {}",
                tokens.len()
            )),
        }
    };
    let bare = |instruction: Instruction| -> Result<Instruction, String> {
        if tokens.is_empty() {
            Ok(instruction)
        } else {
            Err(format!(
                "{mnemonic} takes no operands",
                mnemonic = ecam_core::excerpt::excerpt(mnemonic)
            ))
        }
    };
    Some(match mnemonic {
        "CJ" => pointer(Exec::Continuous, false),
        "CJP" => pointer(Exec::Pulse, false),
        "CALL" => pointer(Exec::Continuous, true),
        "CALLP" => pointer(Exec::Pulse, true),
        "SRET" => bare(Instruction::SubReturn),
        "FEND" => bare(Instruction::MainEnd),
        _ => return None,
    })
}

/// Checks the operand count; the message names the expected operands.
fn arity(mnemonic: &str, operands: &[Operand], names: &[&str]) -> Result<(), String> {
    if operands.len() == names.len() {
        Ok(())
    } else {
        Err(format!(
            "{mnemonic} expects {} operand{} ({}), found {}",
            names.len(),
            if names.len() == 1 { "" } else { "s" },
            names.join(" "),
            operands.len()
        ))
    }
}

fn wrong(mnemonic: &str, index: usize, operand: &Operand, expected: &str) -> String {
    // Say why an index-modified operand that is otherwise of the right
    // kind (`DECAM D0Z0 …`) does not fit.
    let note = if matches!(operand, Operand::Indexed(..)) && !expected.contains("index-modified") {
        " (this operand cannot be index-modified)"
    } else {
        ""
    };
    format!(
        "{mnemonic} operand {}: expected {expected}, found {}{note}",
        index + 1,
        operand.describe()
    )
}

/// Splits `DMOVP` into (Double, "MOV", Pulse) for the applied instructions
/// that have 32-bit and pulse forms.
fn applied(mnemonic: &str) -> Option<(Width, &str, Exec)> {
    const BASES: [&str; 22] = [
        "MOV", "EMOV", "ADD", "SUB", "MUL", "DIV", "INC", "DEC", "NEG", "WAND", "WOR", "WXOR",
        "CMP", "ZCP", "BMOV", "FMOV", "SFTL", "SFTR", "ZRST", "PLSY", "ECAM", "ECAMTBX",
    ];
    // The 32-bit word logic is DAND/DOR/DXOR, not DWAND.
    for (double, word) in [("DAND", "WAND"), ("DOR", "WOR"), ("DXOR", "WXOR")] {
        match mnemonic.strip_prefix(double) {
            Some("") => return Some((Width::Double, word, Exec::Continuous)),
            Some("P") => return Some((Width::Double, word, Exec::Pulse)),
            _ => {}
        }
    }
    if mnemonic.starts_with("DW") {
        return None;
    }
    let (width, rest) = match mnemonic.strip_prefix('D') {
        Some(rest)
            if BASES.contains(&rest)
                || rest.strip_suffix('P').is_some_and(|r| BASES.contains(&r)) =>
        {
            (Width::Double, rest)
        }
        _ => (Width::Word, mnemonic),
    };
    let (base, exec) = match rest.strip_suffix('P') {
        Some(base) if BASES.contains(&base) => (base, Exec::Pulse),
        _ => (rest, Exec::Continuous),
    };
    BASES.contains(&base).then_some((width, base, exec))
}

fn instruction(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, String> {
    let contact = || -> Result<BitRef, String> {
        arity(mnemonic, ops, &["device"])?;
        bit_source(mnemonic, 0, &ops[0])
    };
    Ok(match mnemonic {
        "LD" => Instruction::Load(Contact::Open, contact()?),
        "LDI" => Instruction::Load(Contact::Closed, contact()?),
        "LDP" => Instruction::Load(Contact::Rising, contact()?),
        "LDF" => Instruction::Load(Contact::Falling, contact()?),
        "AND" => Instruction::And(Contact::Open, contact()?),
        "ANI" => Instruction::And(Contact::Closed, contact()?),
        "ANDP" => Instruction::And(Contact::Rising, contact()?),
        "ANDF" => Instruction::And(Contact::Falling, contact()?),
        "OR" => Instruction::Or(Contact::Open, contact()?),
        "ORI" => Instruction::Or(Contact::Closed, contact()?),
        "ORP" => Instruction::Or(Contact::Rising, contact()?),
        "ORF" => Instruction::Or(Contact::Falling, contact()?),
        "ANB" | "ORB" | "MPS" | "MRD" | "MPP" | "NOP" => {
            arity(mnemonic, ops, &[])?;
            match mnemonic {
                "ANB" => Instruction::AndBlock,
                "ORB" => Instruction::OrBlock,
                "MPS" => Instruction::Push,
                "MRD" => Instruction::Read,
                "MPP" => Instruction::Pop,
                _ => Instruction::Nop,
            }
        }
        "OUT" => out(ops)?,
        "SET" => {
            arity(mnemonic, ops, &["Y/M/Dn.b"])?;
            Instruction::Set(coil(mnemonic, 0, &ops[0])?)
        }
        "RST" => {
            arity(mnemonic, ops, &["Y/M/D/C/T/V/Z/Dn.b"])?;
            match ops[0] {
                Operand::Device(
                    d @ (Device::Y(_) | Device::M(_) | Device::D(_) | Device::C(_)),
                ) => Instruction::Reset(BitRef::Device(d)),
                Operand::WordBit(b) => Instruction::Reset(BitRef::WordBit(b)),
                Operand::Timer(n) => Instruction::Reset(BitRef::Timer(n)),
                Operand::Indexed(Modified::Device(d @ (Device::Y(_) | Device::M(_))), by) => {
                    Instruction::Reset(BitRef::Indexed(d, by))
                }
                // RST Vn/Zn clears the register while the power flow is on:
                // exactly what a continuous `MOV K0 Zn` does.
                Operand::Index(register) => Instruction::Move {
                    width: Width::Word,
                    exec: Exec::Continuous,
                    src: Source::Constant(0),
                    dst: Dest::Index(register),
                },
                ref other => {
                    return Err(wrong(
                        mnemonic,
                        0,
                        other,
                        "a Y, M, D, C, T, V or Z device or a bit Dn.b",
                    ));
                }
            }
        }
        "PLS" | "PLF" => {
            arity(mnemonic, ops, &["Y/M"])?;
            Instruction::Pulse {
                rising: mnemonic == "PLS",
                dest: bit_dest(mnemonic, 0, &ops[0])?,
            }
        }
        _ if comparison(mnemonic).is_some() => compare_contact(mnemonic, ops)?,
        _ => match applied(mnemonic) {
            Some((width, base, exec)) => applied_instruction(mnemonic, width, base, exec, ops)?,
            None => {
                return Err(format!(
                    "unknown instruction `{mnemonic}` (see docs/plc-instructions.md for the supported list)"
                ));
            }
        },
    })
}

/// Splits `ANDD<>` into (And, Double, NotEqual).
fn comparison(mnemonic: &str) -> Option<(Join, Width, Relation)> {
    let (join, rest) = [("LD", Join::Load), ("AND", Join::And), ("OR", Join::Or)]
        .into_iter()
        .find_map(|(prefix, join)| mnemonic.strip_prefix(prefix).map(|rest| (join, rest)))?;
    let (width, rest) = match rest.strip_prefix('D') {
        Some(rest) => (Width::Double, rest),
        None => (Width::Word, rest),
    };
    let relation = match rest {
        "=" => Relation::Equal,
        "<>" => Relation::NotEqual,
        ">" => Relation::Greater,
        "<" => Relation::Less,
        ">=" => Relation::GreaterOrEqual,
        "<=" => Relation::LessOrEqual,
        _ => return None,
    };
    Some((join, width, relation))
}

fn compare_contact(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, String> {
    let Some((join, width, relation)) = comparison(mnemonic) else {
        return Err(format!(
            "unknown instruction `{mnemonic}`",
            mnemonic = ecam_core::excerpt::excerpt(mnemonic)
        ));
    };
    arity(mnemonic, ops, &["S1", "S2"])?;
    let operand = |index: usize| -> Result<Source, String> {
        let source = source(mnemonic, index, &ops[index], width)?;
        // The FX manual: a 32-bit counter in a 16-bit comparison is an
        // error; say so at load instead of comparing its low word.
        match source {
            Source::Counter(n) if width == Width::Word && n >= C_32BIT_FIRST => {
                let prefix = match join {
                    Join::Load => "LD",
                    Join::And => "AND",
                    Join::Or => "OR",
                };
                let relation = mnemonic.get(prefix.len()..).unwrap_or("");
                Err(format!(
                    "{mnemonic} operand {}: C{n} is a 32-bit counter: use the 32-bit form {prefix}D{relation}",
                    index + 1,
                ))
            }
            other => Ok(other),
        }
    };
    Ok(Instruction::CompareContact {
        join,
        relation,
        width,
        s1: operand(0)?,
        s2: operand(1)?,
    })
}

fn out(ops: &[Operand]) -> Result<Instruction, String> {
    match ops {
        [Operand::Timer(timer)] => Err(format!(
            "OUT T{timer} needs a set value: expected OUT T{timer} K<value> or OUT T{timer} D<n>"
        )),
        [Operand::Timer(timer), set] => {
            let preset = source("OUT", 1, set, Width::Word)?;
            match preset {
                preset if !is_set_value(preset) => Err(wrong(
                    "OUT",
                    1,
                    set,
                    "a K/H constant or a D register (optionally index-modified, D10Z0)",
                )),
                // FX timers take a set value of 0-32767.
                Source::Constant(v) if v < 0 => Err(format!(
                    "OUT T{timer} operand 2: set value {v} is out of range for a timer (K0 to K32767)"
                )),
                preset => Ok(Instruction::OutTimer {
                    timer: *timer,
                    preset,
                }),
            }
        }
        [Operand::Device(Device::C(counter))] => Err(format!(
            "OUT C{counter} needs a set value: expected OUT C{counter} K<value> or OUT C{counter} D<n>"
        )),
        [op] => Ok(Instruction::Out(coil("OUT", 0, op)?)),
        [Operand::Device(Device::C(counter)), set] => {
            let width = if *counter >= C_32BIT_FIRST {
                Width::Double
            } else {
                Width::Word
            };
            let set_value = source("OUT", 1, set, width)?;
            if !is_set_value(set_value) {
                return Err(wrong(
                    "OUT",
                    1,
                    set,
                    "a K/H constant or a D register (optionally index-modified, D10Z0)",
                ));
            }
            // FX 16-bit counters count up to a set value of 0-32767; a
            // negative one would make the contact on from the first scan.
            if let (Width::Word, Source::Constant(v)) = (width, set_value) {
                if v < 0 {
                    return Err(format!(
                        "OUT C{counter} operand 2: set value {v} is out of range for a 16-bit counter (K0 to K32767)"
                    ));
                }
            }
            Ok(Instruction::OutCounter {
                counter: *counter,
                set_value,
            })
        }
        [first, _] => Err(wrong(
            "OUT",
            0,
            first,
            "a counter C or a timer T (two operands are only for OUT Cn/Tn K<set value>)",
        )),
        _ => Err(format!(
            "OUT expects 1 operand (Y/M/Dn.b) or 2 (Cn/Tn K<set value>), found {}",
            ops.len()
        )),
    }
}

/// The set value of a timer or counter coil: a K/H constant or a D
/// register, which may be index-modified (FX3U).
fn is_set_value(source: Source) -> bool {
    matches!(
        source,
        Source::Constant(_)
            | Source::Register(_)
            | Source::Indexed(Indexed {
                base: IndexBase::Register(_),
                ..
            })
    )
}

fn applied_instruction(
    mnemonic: &str,
    width: Width,
    base: &str,
    exec: Exec,
    ops: &[Operand],
) -> Result<Instruction, String> {
    let no_double = || {
        if width == Width::Double {
            Err(format!(
                "unknown instruction `{mnemonic}` ({base} has no 32-bit D form)"
            ))
        } else {
            Ok(())
        }
    };
    let no_pulse = || {
        if exec == Exec::Pulse {
            Err(format!(
                "unknown instruction `{mnemonic}` ({base} has no P form)"
            ))
        } else {
            Ok(())
        }
    };
    Ok(match base {
        "MOV" => {
            arity(mnemonic, ops, &["S", "D"])?;
            Instruction::Move {
                width,
                exec,
                src: source(mnemonic, 0, &ops[0], width)?,
                dst: word_dest(mnemonic, 1, &ops[1], width)?,
            }
        }
        "EMOV" => {
            if width != Width::Double {
                return Err(format!(
                    "unknown instruction `{mnemonic}` (the float move is DEMOV)"
                ));
            }
            arity(mnemonic, ops, &["S", "D"])?;
            let src = match ops[0] {
                Operand::Float(v) => FloatSource::Constant(v),
                Operand::Decimal(v) => FloatSource::Constant(v as f32),
                Operand::Device(Device::D(n)) => {
                    FloatSource::Register(register(mnemonic, 0, n, Width::Double)?)
                }
                ref other => {
                    return Err(wrong(
                        mnemonic,
                        0,
                        other,
                        "an E constant (E1.6667) or a D register",
                    ));
                }
            };
            let dst = match ops[1] {
                Operand::Device(Device::D(n)) => register(mnemonic, 1, n, Width::Double)?,
                ref other => return Err(wrong(mnemonic, 1, other, "a D register")),
            };
            Instruction::FloatMove { exec, src, dst }
        }
        "ADD" | "SUB" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Arith {
                op: if base == "ADD" {
                    ArithOp::Add
                } else {
                    ArithOp::Sub
                },
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: word_dest(mnemonic, 2, &ops[2], width)?,
            }
        }
        "MUL" | "DIV" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            let s1 = source(mnemonic, 0, &ops[0], width)?;
            let s2 = source(mnemonic, 1, &ops[1], width)?;
            let words: u16 = if width == Width::Double { 4 } else { 2 };
            // A 16-bit MUL's product is 32 bits wide: K1–K8 groups take it.
            let digits = if base == "MUL" || width == Width::Double {
                8
            } else {
                4
            };
            let dst = match result_dest(mnemonic, 2, &ops[2], width, digits)? {
                Dest::Register(n) if n.checked_add(words - 1).is_some_and(|l| l < D_COUNT) => {
                    Dest::Register(n)
                }
                Dest::Register(n) => {
                    return Err(format!(
                        "{mnemonic} operand 3: the result takes {words} registers from D{n}, past D8511"
                    ));
                }
                dst @ (Dest::Group(_)
                | Dest::Indexed(Indexed {
                    base: IndexBase::Register(_) | IndexBase::Group(_),
                    ..
                })) => dst,
                // 16-bit MUL into Zn is allowed by the FX3U (low word only);
                // we keep the result where the user can see all of it.
                _ => {
                    return Err(wrong(
                        mnemonic,
                        2,
                        &ops[2],
                        "a D register or a word group KnM/KnY (optionally index-modified)",
                    ));
                }
            };
            if base == "MUL" {
                Instruction::Multiply {
                    width,
                    exec,
                    s1,
                    s2,
                    dst,
                }
            } else {
                Instruction::Divide {
                    width,
                    exec,
                    s1,
                    s2,
                    dst,
                }
            }
        }
        "WAND" | "WOR" | "WXOR" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Logic {
                op: match base {
                    "WAND" => LogicOp::And,
                    "WOR" => LogicOp::Or,
                    _ => LogicOp::Xor,
                },
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: word_dest(mnemonic, 2, &ops[2], width)?,
            }
        }
        "NEG" => {
            arity(mnemonic, ops, &["D"])?;
            Instruction::Negate {
                width,
                exec,
                dst: word_dest(mnemonic, 0, &ops[0], width)?,
            }
        }
        "INC" | "DEC" => {
            arity(mnemonic, ops, &["D"])?;
            Instruction::Step {
                up: base == "INC",
                width,
                exec,
                dst: word_dest(mnemonic, 0, &ops[0], width)?,
            }
        }
        "CMP" => {
            arity(mnemonic, ops, &["S1", "S2", "D"])?;
            Instruction::Compare {
                width,
                exec,
                s1: source(mnemonic, 0, &ops[0], width)?,
                s2: source(mnemonic, 1, &ops[1], width)?,
                dst: three_bits(mnemonic, 2, &ops[2])?,
            }
        }
        "ZCP" => {
            arity(mnemonic, ops, &["S1 (low)", "S2 (high)", "S3", "D"])?;
            Instruction::ZoneCompare {
                width,
                exec,
                low: source(mnemonic, 0, &ops[0], width)?,
                high: source(mnemonic, 1, &ops[1], width)?,
                value: source(mnemonic, 2, &ops[2], width)?,
                dst: three_bits(mnemonic, 3, &ops[3])?,
            }
        }
        "BMOV" => {
            no_double()?;
            arity(mnemonic, ops, &["S", "D", "n"])?;
            Instruction::BlockMove {
                exec,
                src: block(mnemonic, 0, &ops[0])?,
                dst: block(mnemonic, 1, &ops[1])?,
                count: block_count(mnemonic, 2, &ops[2])?,
            }
        }
        "SFTL" | "SFTR" => {
            no_double()?;
            arity(mnemonic, ops, &["S", "D", "n1", "n2"])?;
            let count = |i: usize| match ops[i] {
                Operand::Decimal(n) if (1..=i64::from(SHIFT_MAX)).contains(&n) => Ok(n as u16),
                ref other => Err(wrong(
                    mnemonic,
                    i,
                    other,
                    &format!("a K constant 1 to {SHIFT_MAX}"),
                )),
            };
            let (length, places) = (count(2)?, count(3)?);
            if places > length {
                return Err(format!(
                    "{mnemonic}: n2 = {places} is more than n1 = {length} (the shift cannot be longer than the block)"
                ));
            }
            let src = match ops[0] {
                Operand::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_))) => d,
                ref other => return Err(wrong(mnemonic, 0, other, "an X, Y or M bit")),
            };
            let dst = bit_dest(mnemonic, 1, &ops[1])?.0;
            for (index, first, bits) in [(0, src, places), (1, dst, length)] {
                if !bits_exist(first, bits) {
                    return Err(format!(
                        "{mnemonic} operand {}: {bits} bits from {first} run past the last device",
                        index + 1
                    ));
                }
            }
            Instruction::BitShift {
                left: base == "SFTL",
                exec,
                src,
                dst,
                length,
                places,
            }
        }
        "FMOV" => {
            arity(mnemonic, ops, &["S", "D", "n"])?;
            Instruction::Fill {
                width,
                exec,
                src: source(mnemonic, 0, &ops[0], width)?,
                dst: block(mnemonic, 1, &ops[1])?,
                count: block_count(mnemonic, 2, &ops[2])?,
            }
        }
        "ZRST" => {
            no_double()?;
            arity(mnemonic, ops, &["D1", "D2"])?;
            let (kind, first, last) = match (ops[0], ops[1]) {
                (Operand::Device(Device::M(a)), Operand::Device(Device::M(b))) => {
                    (ZoneDevice::M, a, b)
                }
                (Operand::Device(Device::Y(a)), Operand::Device(Device::Y(b))) => {
                    (ZoneDevice::Y, a, b)
                }
                (Operand::Device(Device::D(a)), Operand::Device(Device::D(b))) => {
                    (ZoneDevice::D, a, b)
                }
                (Operand::Device(Device::C(a)), Operand::Device(Device::C(b))) => {
                    (ZoneDevice::C, a, b)
                }
                _ => {
                    return Err(format!(
                        "{mnemonic} expects two devices of the same kind (M, Y, D or C), found {} {}",
                        ops[0].describe(),
                        ops[1].describe()
                    ));
                }
            };
            if first > last {
                return Err(format!(
                    "{mnemonic}: the first device must not come after the last"
                ));
            }
            Instruction::ZoneReset {
                exec,
                kind,
                first,
                last,
            }
        }
        "PLSY" => {
            no_pulse()?;
            arity(
                mnemonic,
                ops,
                &["S1 (frequency)", "S2 (pulses)", "D (Y0-Y3)"],
            )?;
            Instruction::PulseOutput {
                width,
                frequency: source(mnemonic, 0, &ops[0], width)?,
                count: source(mnemonic, 1, &ops[1], width)?,
                output: pulse_output(mnemonic, 2, &ops[2])?,
            }
        }
        "ECAM" => {
            no_pulse()?;
            if width != Width::Double {
                return Err(format!(
                    "unknown instruction `{mnemonic}` (the E-cam instruction is DECAM)"
                ));
            }
            arity(
                mnemonic,
                ops,
                &[
                    "S1 (master)",
                    "S2 (block)",
                    "S3 (start)",
                    "D1 (Y0-Y3)",
                    "D2 (direction Y)",
                ],
            )?;
            let master = match ops[0] {
                Operand::Device(Device::C(n)) => MasterSpec::Counter(n),
                Operand::Device(Device::D(n)) => {
                    MasterSpec::Register(register(mnemonic, 0, n, Width::Double)?)
                }
                Operand::Decimal(k) if (1..=i64::from(u32::MAX)).contains(&k) => {
                    MasterSpec::TimeBase(k as u32)
                }
                ref other => {
                    return Err(wrong(
                        mnemonic,
                        0,
                        other,
                        "a counter C, a D register or a time base K1 or more",
                    ));
                }
            };
            let block = match ops[1] {
                Operand::Device(Device::D(n)) => n,
                ref other => return Err(wrong(mnemonic, 1, other, "a D register")),
            };
            let start = match ops[2] {
                Operand::Device(d @ (Device::X(_) | Device::M(_))) => d,
                ref other => return Err(wrong(mnemonic, 2, other, "an X or M device")),
            };
            let direction = match ops[4] {
                Operand::Device(d @ Device::Y(_)) => d,
                ref other => return Err(wrong(mnemonic, 4, other, "a Y output")),
            };
            Instruction::Decam {
                master,
                block,
                start,
                pulse_output: pulse_output(mnemonic, 3, &ops[3])?,
                direction,
            }
        }
        _ => {
            // ECAMTBX: the only base left in `applied`'s list.
            no_double()?;
            no_pulse()?;
            arity(mnemonic, ops, &["S0", "S1", "D1", "D2"])?;
            let d = |i: usize| match ops[i] {
                Operand::Device(Device::D(n)) => Ok(n),
                ref other => Err(wrong(mnemonic, i, other, "a D register")),
            };
            Instruction::Ecamtbx {
                params: d(0)?,
                kind: source(mnemonic, 1, &ops[1], Width::Double)?,
                table: d(2)?,
                result: d(3)?,
            }
        }
    })
}

fn bit_source(mnemonic: &str, index: usize, op: &Operand) -> Result<BitRef, String> {
    match op {
        Operand::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_) | Device::C(_))) => {
            Ok(BitRef::Device(*d))
        }
        Operand::WordBit(b) => Ok(BitRef::WordBit(*b)),
        Operand::Timer(n) => Ok(BitRef::Timer(*n)),
        Operand::Indexed(
            Modified::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_) | Device::C(_))),
            by,
        ) => Ok(BitRef::Indexed(*d, *by)),
        Operand::Indexed(Modified::Timer(n), by) => Ok(BitRef::IndexedTimer(*n, *by)),
        other => Err(wrong(
            mnemonic,
            index,
            other,
            "a bit device X, Y, M, a counter contact C, a timer contact T (each optionally index-modified, C5Z0) or a bit of a register Dn.b",
        )),
    }
}

/// Operand of OUT and SET: Y, M or `Dn.b`.
fn coil(mnemonic: &str, index: usize, op: &Operand) -> Result<BitRef, String> {
    match op {
        Operand::Device(d @ (Device::Y(_) | Device::M(_))) => Ok(BitRef::Device(*d)),
        Operand::WordBit(b) => Ok(BitRef::WordBit(*b)),
        Operand::Indexed(Modified::Device(d @ (Device::Y(_) | Device::M(_))), by) => {
            Ok(BitRef::Indexed(*d, *by))
        }
        other => Err(wrong(
            mnemonic,
            index,
            other,
            "an output Y, a relay M (optionally index-modified, M0Z1) or a bit of a register Dn.b",
        )),
    }
}

fn bit_dest(mnemonic: &str, index: usize, op: &Operand) -> Result<BitDest, String> {
    match op {
        Operand::Device(d @ (Device::Y(_) | Device::M(_))) => Ok(BitDest(*d)),
        other => Err(wrong(mnemonic, index, other, "an output Y or a relay M")),
    }
}

/// The result bits of CMP/ZCP: M or Y, with the two bits after it.
fn three_bits(mnemonic: &str, index: usize, op: &Operand) -> Result<Device, String> {
    let dst = bit_dest(mnemonic, index, op)?.0;
    let last_ok = match dst {
        Device::M(n) => n.checked_add(2).is_some_and(|l| l < M_COUNT),
        Device::Y(n) => n.checked_add(2).is_some_and(|l| l < XY_COUNT),
        _ => false,
    };
    if last_ok {
        Ok(dst)
    } else {
        Err(format!(
            "{mnemonic} operand {}: {dst} and the two bits after it must exist",
            index + 1
        ))
    }
}

/// Longest SFTL/SFTR block (FX3U: n1 ≤ 1024).
const SHIFT_MAX: u16 = 1024;

/// Whether `bits` consecutive bit devices from `first` exist.
fn bits_exist(first: Device, bits: u16) -> bool {
    let (n, count) = match first {
        Device::X(n) | Device::Y(n) => (n, XY_COUNT),
        Device::M(n) => (n, M_COUNT),
        _ => return false,
    };
    u32::from(n) + u32::from(bits) <= u32::from(count)
}

/// Most words BMOV/FMOV move at once (FX3U: n ≤ 512).
pub(crate) const BLOCK_MAX: i32 = 512;

/// A block of BMOV/FMOV: the first D register, optionally index-modified
/// (the length is checked when the instruction runs).
fn block(mnemonic: &str, index: usize, op: &Operand) -> Result<Dest, String> {
    match *op {
        Operand::Device(Device::D(n)) => Ok(Dest::Register(n)),
        Operand::Indexed(Modified::Device(Device::D(n)), by) => Ok(Dest::Indexed(Indexed {
            base: IndexBase::Register(n),
            by: modifier(mnemonic, index, op, by, Width::Word)?,
        })),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a D register (optionally index-modified)",
        )),
    }
}

/// n of BMOV/FMOV: K1–K512, or a D register read at run time (the blocks
/// are checked against D8511 when the instruction runs, as their start
/// may be index-modified).
fn block_count(mnemonic: &str, index: usize, op: &Operand) -> Result<Source, String> {
    match *op {
        Operand::Decimal(n) if (1..=i64::from(BLOCK_MAX)).contains(&n) => {
            Ok(Source::Constant(n as i32))
        }
        Operand::Decimal(n) => Err(format!(
            "{mnemonic} operand {}: n = {n} is out of range (K1 to K{BLOCK_MAX})",
            index + 1
        )),
        Operand::Device(Device::D(n)) => Ok(Source::Register(n)),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a K constant 1-512 or a D register",
        )),
    }
}

fn register(mnemonic: &str, index: usize, n: u16, width: Width) -> Result<u16, String> {
    if width == Width::Double && n.checked_add(1).is_none_or(|hi| hi >= D_COUNT) {
        return Err(format!(
            "{mnemonic} operand {}: D{n} has no D{} for the high word",
            index + 1,
            u32::from(n) + 1
        ));
    }
    Ok(n)
}

fn source(mnemonic: &str, index: usize, op: &Operand, width: Width) -> Result<Source, String> {
    let out_of_range = |range: &str| {
        format!(
            "{mnemonic} operand {}: {} is out of range ({range})",
            index + 1,
            op.describe()
        )
    };
    match (*op, width) {
        (Operand::Decimal(v), _) => constant(v, None, width)
            .map(Source::Constant)
            .map_err(|range| out_of_range(&range)),
        (Operand::Hex(v), _) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
            .map(Source::Constant)
            .map_err(|range| out_of_range(&range)),
        (Operand::Device(Device::D(n)), _) => {
            Ok(Source::Register(register(mnemonic, index, n, width)?))
        }
        (Operand::Device(Device::C(n)), _) => Ok(Source::Counter(n)),
        (Operand::Timer(n), Width::Word) => Ok(Source::Timer(n)),
        (Operand::Group(g), Width::Word) if g.digits > 4 => Err(format!(
            "{mnemonic} operand {}: {g} has {} digits; a 16-bit instruction takes K1 to K4",
            index + 1,
            g.digits
        )),
        (Operand::Group(g), _) => Ok(Source::Group(g)),
        (Operand::Index(reg), _) => Ok(Source::Index(index_register(mnemonic, index, reg, width)?)),
        (Operand::Indexed(base, by), _) => {
            let by = modifier(mnemonic, index, op, by, width)?;
            let base = match base {
                Modified::Decimal(v) => constant(v, None, width)
                    .map(IndexBase::Constant)
                    .map_err(|range| out_of_range(&range))?,
                Modified::Hex(v) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
                    .map(IndexBase::Constant)
                    .map_err(|range| out_of_range(&range))?,
                Modified::Device(Device::D(n)) => {
                    IndexBase::Register(register(mnemonic, index, n, width)?)
                }
                Modified::Device(Device::C(n)) => IndexBase::Counter(n),
                Modified::Timer(n) if width == Width::Word => IndexBase::Timer(n),
                Modified::Group(g) if width == Width::Word && g.digits > 4 => {
                    return Err(format!(
                        "{mnemonic} operand {}: {g} has {} digits; a 16-bit instruction takes K1 to K4",
                        index + 1,
                        g.digits
                    ));
                }
                Modified::Group(g) => IndexBase::Group(g),
                _ => {
                    return Err(wrong(
                        mnemonic,
                        index,
                        op,
                        "a K/H constant, D, C, (16 bit) T or a word group, index-modified",
                    ));
                }
            };
            Ok(Source::Indexed(Indexed { base, by }))
        }
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a K/H constant, a D register, a counter C, a word group KnM/KnX/KnY, an index register V/Z or (16 bit) a timer T",
        )),
    }
}

/// A K (`hex` = None) or H constant at the instruction's width: its value,
/// or the allowed range for the message. H constants are bit patterns
/// (HFFFF is −1 at 16 bit).
fn constant(value: i64, hex: Option<u64>, width: Width) -> Result<i32, String> {
    match (hex, width) {
        (None, Width::Word) => i16::try_from(value)
            .map(i32::from)
            .map_err(|_| "K-32768 to K32767".to_string()),
        (None, Width::Double) => {
            i32::try_from(value).map_err(|_| "K-2147483648 to K2147483647".to_string())
        }
        (Some(v), Width::Word) => u16::try_from(v)
            .map(|v| i32::from(v as i16))
            .map_err(|_| "H0 to HFFFF".to_string()),
        (Some(v), Width::Double) => u32::try_from(v)
            .map(|v| v as i32)
            .map_err(|_| "H0 to HFFFFFFFF".to_string()),
    }
}

/// An index register as a whole operand: at 32 bit only Zn, which names
/// the pair Vn:Zn (FX3U).
fn index_register(
    mnemonic: &str,
    index: usize,
    reg: IndexReg,
    width: Width,
) -> Result<IndexReg, String> {
    match (reg, width) {
        (IndexReg::V(n), Width::Double) => Err(format!(
            "{mnemonic} operand {}: a 32-bit instruction names the pair V{n}:Z{n} by Z{n} (Z low word, V high word)",
            index + 1
        )),
        _ => Ok(reg),
    }
}

/// The modifier of an index-modified operand: at 32 bit only Zn (the
/// offset is then the 32-bit pair Vn:Zn, FX3U rule).
fn modifier(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    by: IndexReg,
    width: Width,
) -> Result<IndexReg, String> {
    match (by, width) {
        (IndexReg::V(n), Width::Double) => Err(format!(
            "{mnemonic} operand {}: {}: a 32-bit instruction is modified by Z{n} (the pair V{n}:Z{n}), not by V{n}",
            index + 1,
            op.describe()
        )),
        _ => Ok(by),
    }
}

/// The destination of a word instruction: D, C, V/Z, a word group KnM/KnY
/// (not KnX: inputs are driven from outside), each optionally
/// index-modified.
fn word_dest(mnemonic: &str, index: usize, op: &Operand, width: Width) -> Result<Dest, String> {
    let digits = if width == Width::Double { 8 } else { 4 };
    result_dest(mnemonic, index, op, width, digits)
}

/// [`word_dest`] for a result up to `max_digits` × 4 bits wide (a 16-bit
/// MUL's product fills K8).
fn result_dest(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
    max_digits: u8,
) -> Result<Dest, String> {
    let group = |g: crate::il::WordGroup| -> Result<crate::il::WordGroup, String> {
        if g.kind == crate::il::GroupKind::X {
            return Err(format!(
                "{mnemonic} operand {}: {} is an input group; inputs X are driven from outside, write KnM or KnY",
                index + 1,
                op.describe()
            ));
        }
        if g.digits > max_digits {
            return Err(format!(
                "{mnemonic} operand {}: {g} has {} digits; this result takes K1 to K{max_digits}",
                index + 1,
                g.digits
            ));
        }
        Ok(g)
    };
    match *op {
        Operand::Device(Device::D(n)) => Ok(Dest::Register(register(mnemonic, index, n, width)?)),
        Operand::Device(Device::C(n)) => Ok(Dest::Counter(n)),
        Operand::Group(g) => Ok(Dest::Group(group(g)?)),
        Operand::Index(reg) => Ok(Dest::Index(index_register(mnemonic, index, reg, width)?)),
        Operand::Indexed(base, by) => {
            let by = modifier(mnemonic, index, op, by, width)?;
            let base = match base {
                Modified::Device(Device::D(n)) => {
                    IndexBase::Register(register(mnemonic, index, n, width)?)
                }
                Modified::Device(Device::C(n)) => IndexBase::Counter(n),
                Modified::Group(g) => IndexBase::Group(group(g)?),
                _ => {
                    return Err(wrong(
                        mnemonic,
                        index,
                        op,
                        "D, C or a word group KnM/KnY, index-modified",
                    ));
                }
            };
            Ok(Dest::Indexed(Indexed { base, by }))
        }
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a D register, a counter C, an index register V/Z or a word group KnM/KnY",
        )),
    }
}

fn pulse_output(mnemonic: &str, index: usize, op: &Operand) -> Result<u8, String> {
    match *op {
        Operand::Device(Device::Y(n)) if n <= 3 => Ok(n as u8),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a pulse output Y0, Y1, Y2 or Y3",
        )),
    }
}
