//! Mnemonics and operand checks: source text → [`Program`].

use super::Program;
use super::error::{
    OperandError, ParseError, ParseProblem, StatementError, TokenError, UnknownHint,
};
use super::flow;
use super::instruction::{
    ArithOp, BitDest, BitRef, Contact, Dest, Exec, FloatSource, IndexBase, Indexed, Instruction,
    Join, LogicOp, MasterSpec, Relation, Source, Statement, Width, ZoneDevice,
};
use super::lexer::lines;
use super::limits::{BLOCK_MAX, END_POINTER, POINTER_COUNT, SHIFT_COUNT, SHIFT_MAX};
use super::operand::{Modified, Operand};
use super::validate;
use crate::device::{C_32BIT_FIRST, D_COUNT, Device, M_COUNT, XY_COUNT};
use crate::index_register::IndexReg;

/// Parses and checks a program (see [`Program::parse`]).
pub(crate) fn parse(source: &str, file: &str) -> Result<Program, ParseError> {
    let error = |line: usize, problem: ParseProblem| ParseError {
        file: file.to_string(),
        line,
        problem,
    };
    let statement_error = |line: usize, e: StatementError| error(line, ParseProblem::Statement(e));
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
                return Err(statement_error(
                    line.number,
                    StatementError::NoOperands { mnemonic },
                ));
            }
            break;
        }
        if let Some(label) = label(&mnemonic) {
            if !operand_tokens.is_empty() {
                return Err(statement_error(
                    line.number,
                    StatementError::LabelNotAlone { label: mnemonic },
                ));
            }
            statements.push(Statement {
                line: line.number,
                instruction: Instruction::Label(
                    label.map_err(|e| statement_error(line.number, e))?,
                ),
            });
            continue;
        }
        if let Some(flow) = flow_instruction(&mnemonic, operand_tokens) {
            statements.push(Statement {
                line: line.number,
                instruction: flow.map_err(|e| statement_error(line.number, e))?,
            });
            continue;
        }
        let mut operands = Vec::with_capacity(operand_tokens.len());
        for (i, token) in operand_tokens.iter().enumerate() {
            let operand = Operand::parse(token)
                .map_err(|e| statement_error(line.number, at(&mnemonic, i, e)))?;
            operands.push(operand);
        }
        let instruction =
            instruction(&mnemonic, &operands).map_err(|e| statement_error(line.number, e))?;
        statements.push(Statement {
            line: line.number,
            instruction,
        });
    }
    validate::check(&statements).map_err(|(line, e)| error(line, ParseProblem::Stack(e)))?;
    flow::check(&statements).map_err(|(line, e)| error(line, ParseProblem::Flow(e)))?;
    Ok(Program {
        file: file.to_string(),
        statements,
    })
}

/// `Some` when `mnemonic` is a pointer label `Pn` (P and digits only):
/// its number, or why it is not a usable label.
fn label(mnemonic: &str) -> Option<Result<u8, StatementError>> {
    let digits = mnemonic.strip_prefix('P')?;
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    Some(match pointer_number(mnemonic) {
        Ok(n) if n == END_POINTER => Err(StatementError::EndPointerLabel),
        Ok(n) => Ok(n),
        Err(e) => Err(StatementError::BadLabel(e)),
    })
}

/// The n of a pointer `Pn`, n = 0–127.
fn pointer_number(token: &str) -> Result<u8, TokenError> {
    let upper = token.to_ascii_uppercase();
    let number = upper
        .strip_prefix('P')
        .filter(|d| !d.is_empty() && d.bytes().all(|b| b.is_ascii_digit()))
        .ok_or_else(|| TokenError::PointerSyntax(token.to_string()))?;
    match number.parse::<u8>() {
        Ok(n) if usize::from(n) < POINTER_COUNT => Ok(n),
        _ => Err(TokenError::PointerRange(upper)),
    }
}

/// CJ/CJP/CALL/CALLP/SRET/FEND, whose operand is a pointer rather than a
/// device: `None` for other mnemonics.
fn flow_instruction(
    mnemonic: &str,
    tokens: &[&str],
) -> Option<Result<Instruction, StatementError>> {
    let pointer = |exec: Exec, call: bool| -> Result<Instruction, StatementError> {
        match tokens {
            [token] => {
                let pointer = pointer_number(token).map_err(|e| at(mnemonic, 0, e))?;
                if call && pointer == END_POINTER {
                    return Err(StatementError::CallEndPointer {
                        mnemonic: mnemonic.to_string(),
                    });
                }
                Ok(if call {
                    Instruction::Call { exec, pointer }
                } else {
                    Instruction::Jump { exec, pointer }
                })
            }
            _ => Err(StatementError::FlowArity {
                mnemonic: mnemonic.to_string(),
                found: tokens.len(),
            }),
        }
    };
    let bare = |instruction: Instruction| -> Result<Instruction, StatementError> {
        if tokens.is_empty() {
            Ok(instruction)
        } else {
            Err(StatementError::NoOperands {
                mnemonic: mnemonic.to_string(),
            })
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
fn arity(
    mnemonic: &str,
    operands: &[Operand],
    names: &'static [&'static str],
) -> Result<(), StatementError> {
    if operands.len() == names.len() {
        Ok(())
    } else {
        Err(StatementError::Arity {
            mnemonic: mnemonic.to_string(),
            names,
            found: operands.len(),
        })
    }
}

/// The problem of operand `index` (from 0) of `mnemonic`.
fn at(mnemonic: &str, index: usize, problem: impl Into<OperandError>) -> StatementError {
    StatementError::Operand {
        mnemonic: mnemonic.to_string(),
        position: index + 1,
        problem: problem.into(),
    }
}

/// Operand `index` of `mnemonic` is of the wrong kind.
fn wrong(
    mnemonic: &str,
    index: usize,
    operand: &Operand,
    expected: &'static str,
) -> StatementError {
    at(
        mnemonic,
        index,
        OperandError::Wrong {
            expected,
            found: operand.describe(),
            indexed: matches!(operand, Operand::Indexed(..)),
        },
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

fn instruction(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let contact = || -> Result<BitRef, StatementError> {
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
                return Err(StatementError::Unknown {
                    mnemonic: mnemonic.to_string(),
                    hint: UnknownHint::NotListed,
                });
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

fn compare_contact(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    let Some((join, width, relation)) = comparison(mnemonic) else {
        return Err(StatementError::Unknown {
            mnemonic: mnemonic.to_string(),
            hint: UnknownHint::Comparison,
        });
    };
    arity(mnemonic, ops, &["S1", "S2"])?;
    let operand = |index: usize| -> Result<Source, StatementError> {
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
                Err(at(
                    mnemonic,
                    index,
                    OperandError::Counter32 {
                        counter: n,
                        instead: format!("{prefix}D{relation}"),
                    },
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

fn out(ops: &[Operand]) -> Result<Instruction, StatementError> {
    match ops {
        [Operand::Timer(timer)] => Err(StatementError::TimerNeedsSetValue(*timer)),
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
                Source::Constant(v) if v < 0 => Err(at(
                    &format!("OUT T{timer}"),
                    1,
                    OperandError::TimerSetValue(v),
                )),
                preset => Ok(Instruction::OutTimer {
                    timer: *timer,
                    preset,
                }),
            }
        }
        [Operand::Device(Device::C(counter))] => {
            Err(StatementError::CounterNeedsSetValue(*counter))
        }
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
                    return Err(at(
                        &format!("OUT C{counter}"),
                        1,
                        OperandError::CounterSetValue(v),
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
        _ => Err(StatementError::OutArity(ops.len())),
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
) -> Result<Instruction, StatementError> {
    let unknown = |hint| StatementError::Unknown {
        mnemonic: mnemonic.to_string(),
        hint,
    };
    let no_double = || {
        if width == Width::Double {
            Err(unknown(UnknownHint::NoDoubleForm(base.to_string())))
        } else {
            Ok(())
        }
    };
    let no_pulse = || {
        if exec == Exec::Pulse {
            Err(unknown(UnknownHint::NoPulseForm(base.to_string())))
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
                return Err(unknown(UnknownHint::FloatMove));
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
                    return Err(at(
                        mnemonic,
                        2,
                        OperandError::ResultPastEnd { words, register: n },
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
                ref other => Err(wrong(mnemonic, i, other, SHIFT_COUNT)),
            };
            let (length, places) = (count(2)?, count(3)?);
            if places > length {
                return Err(StatementError::ShiftLonger {
                    mnemonic: mnemonic.to_string(),
                    places,
                    length,
                });
            }
            let src = match ops[0] {
                Operand::Device(d @ (Device::X(_) | Device::Y(_) | Device::M(_))) => d,
                ref other => return Err(wrong(mnemonic, 0, other, "an X, Y or M bit")),
            };
            let dst = bit_dest(mnemonic, 1, &ops[1])?.0;
            for (index, first, bits) in [(0, src, places), (1, dst, length)] {
                if !bits_exist(first, bits) {
                    return Err(at(
                        mnemonic,
                        index,
                        OperandError::BitsPastEnd { bits, first },
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
                    return Err(StatementError::ZoneKinds {
                        mnemonic: mnemonic.to_string(),
                        first: ops[0].describe(),
                        second: ops[1].describe(),
                    });
                }
            };
            if first > last {
                return Err(StatementError::ZoneOrder {
                    mnemonic: mnemonic.to_string(),
                });
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
                return Err(unknown(UnknownHint::Ecam));
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

fn bit_source(mnemonic: &str, index: usize, op: &Operand) -> Result<BitRef, StatementError> {
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
fn coil(mnemonic: &str, index: usize, op: &Operand) -> Result<BitRef, StatementError> {
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

fn bit_dest(mnemonic: &str, index: usize, op: &Operand) -> Result<BitDest, StatementError> {
    match op {
        Operand::Device(d @ (Device::Y(_) | Device::M(_))) => Ok(BitDest(*d)),
        other => Err(wrong(mnemonic, index, other, "an output Y or a relay M")),
    }
}

/// The result bits of CMP/ZCP: M or Y, with the two bits after it.
fn three_bits(mnemonic: &str, index: usize, op: &Operand) -> Result<Device, StatementError> {
    let dst = bit_dest(mnemonic, index, op)?.0;
    let last_ok = match dst {
        Device::M(n) => n.checked_add(2).is_some_and(|l| l < M_COUNT),
        Device::Y(n) => n.checked_add(2).is_some_and(|l| l < XY_COUNT),
        _ => false,
    };
    if last_ok {
        Ok(dst)
    } else {
        Err(at(mnemonic, index, OperandError::ThreeBits(dst)))
    }
}

/// Whether `bits` consecutive bit devices from `first` exist.
fn bits_exist(first: Device, bits: u16) -> bool {
    let (n, count) = match first {
        Device::X(n) | Device::Y(n) => (n, XY_COUNT),
        Device::M(n) => (n, M_COUNT),
        _ => return false,
    };
    u32::from(n) + u32::from(bits) <= u32::from(count)
}

/// A block of BMOV/FMOV: the first D register, optionally index-modified
/// (the length is checked when the instruction runs).
fn block(mnemonic: &str, index: usize, op: &Operand) -> Result<Dest, StatementError> {
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
fn block_count(mnemonic: &str, index: usize, op: &Operand) -> Result<Source, StatementError> {
    match *op {
        Operand::Decimal(n) if (1..=i64::from(BLOCK_MAX)).contains(&n) => {
            Ok(Source::Constant(n as i32))
        }
        Operand::Decimal(n) => Err(at(mnemonic, index, OperandError::BlockCount(n))),
        Operand::Device(Device::D(n)) => Ok(Source::Register(n)),
        _ => Err(wrong(
            mnemonic,
            index,
            op,
            "a K constant 1-512 or a D register",
        )),
    }
}

fn register(mnemonic: &str, index: usize, n: u16, width: Width) -> Result<u16, StatementError> {
    if width == Width::Double && n.checked_add(1).is_none_or(|hi| hi >= D_COUNT) {
        return Err(at(mnemonic, index, OperandError::NoHighWord(n)));
    }
    Ok(n)
}

fn source(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
) -> Result<Source, StatementError> {
    let out_of_range = |range: &'static str| {
        at(
            mnemonic,
            index,
            OperandError::OutOfRange {
                operand: op.describe(),
                range,
            },
        )
    };
    match (*op, width) {
        (Operand::Decimal(v), _) => constant(v, None, width)
            .map(Source::Constant)
            .map_err(out_of_range),
        (Operand::Hex(v), _) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
            .map(Source::Constant)
            .map_err(out_of_range),
        (Operand::Device(Device::D(n)), _) => {
            Ok(Source::Register(register(mnemonic, index, n, width)?))
        }
        (Operand::Device(Device::C(n)), _) => Ok(Source::Counter(n)),
        (Operand::Timer(n), Width::Word) => Ok(Source::Timer(n)),
        (Operand::Group(g), Width::Word) if g.digits > 4 => Err(at(
            mnemonic,
            index,
            OperandError::GroupTooWide16 {
                group: g.to_string(),
                digits: g.digits,
            },
        )),
        (Operand::Group(g), _) => Ok(Source::Group(g)),
        (Operand::Index(reg), _) => Ok(Source::Index(index_register(mnemonic, index, reg, width)?)),
        (Operand::Indexed(base, by), _) => {
            let by = modifier(mnemonic, index, op, by, width)?;
            let base = match base {
                Modified::Decimal(v) => constant(v, None, width)
                    .map(IndexBase::Constant)
                    .map_err(out_of_range)?,
                Modified::Hex(v) => constant(i64::try_from(v).unwrap_or(i64::MAX), Some(v), width)
                    .map(IndexBase::Constant)
                    .map_err(out_of_range)?,
                Modified::Device(Device::D(n)) => {
                    IndexBase::Register(register(mnemonic, index, n, width)?)
                }
                Modified::Device(Device::C(n)) => IndexBase::Counter(n),
                Modified::Timer(n) if width == Width::Word => IndexBase::Timer(n),
                Modified::Group(g) if width == Width::Word && g.digits > 4 => {
                    return Err(at(
                        mnemonic,
                        index,
                        OperandError::GroupTooWide16 {
                            group: g.to_string(),
                            digits: g.digits,
                        },
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
fn constant(value: i64, hex: Option<u64>, width: Width) -> Result<i32, &'static str> {
    match (hex, width) {
        (None, Width::Word) => i16::try_from(value)
            .map(i32::from)
            .map_err(|_| "K-32768 to K32767"),
        (None, Width::Double) => i32::try_from(value).map_err(|_| "K-2147483648 to K2147483647"),
        (Some(v), Width::Word) => u16::try_from(v)
            .map(|v| i32::from(v as i16))
            .map_err(|_| "H0 to HFFFF"),
        (Some(v), Width::Double) => u32::try_from(v)
            .map(|v| v as i32)
            .map_err(|_| "H0 to HFFFFFFFF"),
    }
}

/// An index register as a whole operand: at 32 bit only Zn, which names
/// the pair Vn:Zn (FX3U).
fn index_register(
    mnemonic: &str,
    index: usize,
    reg: IndexReg,
    width: Width,
) -> Result<IndexReg, StatementError> {
    match (reg, width) {
        (IndexReg::V(n), Width::Double) => Err(at(mnemonic, index, OperandError::PairByV(n))),
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
) -> Result<IndexReg, StatementError> {
    match (by, width) {
        (IndexReg::V(n), Width::Double) => Err(at(
            mnemonic,
            index,
            OperandError::ModifierV {
                operand: op.describe(),
                n,
            },
        )),
        _ => Ok(by),
    }
}

/// The destination of a word instruction: D, C, V/Z, a word group KnM/KnY
/// (not KnX: inputs are driven from outside), each optionally
/// index-modified.
fn word_dest(
    mnemonic: &str,
    index: usize,
    op: &Operand,
    width: Width,
) -> Result<Dest, StatementError> {
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
) -> Result<Dest, StatementError> {
    let group = |g: crate::il::WordGroup| -> Result<crate::il::WordGroup, StatementError> {
        if g.kind == crate::il::GroupKind::X {
            return Err(at(mnemonic, index, OperandError::InputGroup(op.describe())));
        }
        if g.digits > max_digits {
            return Err(at(
                mnemonic,
                index,
                OperandError::GroupTooWide {
                    group: g.to_string(),
                    digits: g.digits,
                    max: max_digits,
                },
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

fn pulse_output(mnemonic: &str, index: usize, op: &Operand) -> Result<u8, StatementError> {
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
