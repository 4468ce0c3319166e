//! Mnemonics and operand checks: source text → [`Program`]. This file
//! reads the lines and sends each mnemonic to its family, as the
//! interpreter does: `contacts.rs`, `coils.rs`, `moves.rs`,
//! `arithmetic.rs`, `comparison.rs`, `shift.rs`, `pulse_output.rs`,
//! `cam.rs`, and `flow.rs` for labels and jumps; `operands.rs` checks an
//! operand against its place, `form.rs` splits `DMOVP` into its forms.

mod arithmetic;
mod cam;
mod coils;
mod comparison;
mod contacts;
mod flow;
mod form;
mod moves;
mod operands;
mod pulse_output;
mod shift;

use self::flow::{flow_instruction, label};
use self::form::Form;
use self::operands::at;
use super::Program;
use super::error::{ParseError, ParseProblem, StatementError, UnknownHint};
use super::instruction::{Instruction, Statement};
use super::lexer::lines;
use super::operand::Operand;
use super::validate;

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
    super::flow::check(&statements).map_err(|(line, e)| error(line, ParseProblem::Flow(e)))?;
    Ok(Program {
        file: file.to_string(),
        statements,
    })
}

/// One instruction with checked operands, by family.
fn instruction(mnemonic: &str, ops: &[Operand]) -> Result<Instruction, StatementError> {
    if let Some(contact) = contacts::parse(mnemonic, ops) {
        return contact;
    }
    match mnemonic {
        "OUT" => coils::out(ops),
        "SET" => coils::set(mnemonic, ops),
        "RST" => coils::reset(mnemonic, ops),
        "PLS" | "PLF" => coils::pulse(mnemonic, ops),
        _ => match form::split(mnemonic) {
            Some(form) => applied(form, ops),
            None => Err(StatementError::Unknown {
                mnemonic: mnemonic.to_string(),
                hint: UnknownHint::NotListed,
            }),
        },
    }
}

/// An applied instruction, by family.
fn applied(form: Form<'_>, ops: &[Operand]) -> Result<Instruction, StatementError> {
    match form.base {
        "MOV" | "EMOV" | "BMOV" | "FMOV" => moves::parse(form, ops),
        "ADD" | "SUB" | "MUL" | "DIV" | "WAND" | "WOR" | "WXOR" | "NEG" | "INC" | "DEC" => {
            arithmetic::parse(form, ops)
        }
        "CMP" | "ZCP" => comparison::parse(form, ops),
        "SFTL" | "SFTR" => shift::parse(form, ops),
        "ZRST" => coils::zone_reset(form, ops),
        "PLSY" => pulse_output::parse(form, ops),
        _ => cam::parse(form, ops),
    }
}
