//! The instruction list (IL) language of the LX3V: one instruction per line,
//! `;` starts a comment, mnemonics and device names are case-insensitive.
//!
//! [`parse`] turns source text into a [`Program`] whose operands are all
//! checked: an unknown device, an operand of the wrong kind or a number out of
//! range is a [`ParseError`] naming the file and line, never a silent zero at
//! run time. `docs/plc-instructions.md` lists every instruction.

mod error;
mod flow;
mod instruction;
mod lexer;
mod operand;
mod parser;
mod validate;

pub(crate) use flow::{CALL_DEPTH, END_POINTER, POINTER_COUNT};
pub(crate) use parser::BLOCK_MAX;
pub(crate) use validate::is_output;

pub use crate::index_register::{INDEX_COUNT, IndexReg};
pub use error::{
    FlowError, OperandError, ParseError, ParseProblem, StackError, StatementError, TokenError,
    UnknownHint,
};
pub use instruction::{
    ArithOp, BitDest, BitRef, Contact, Dest, Exec, FloatSource, GroupKind, IndexBase, Indexed,
    Instruction, Join, LogicOp, MasterSpec, Relation, Source, Statement, Width, WordBit, WordGroup,
    ZoneDevice,
};
pub use parser::parse;

/// A parsed, checked program.
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// Name of the source file (for messages).
    pub file: String,
    /// The statements, in program order (after `END`, nothing is kept).
    pub statements: Vec<Statement>,
}

impl Program {
    /// Number of DECAM instructions (each gets its own E-cam instance).
    pub fn decam_count(&self) -> usize {
        self.statements
            .iter()
            .filter(|s| matches!(s.instruction, Instruction::Decam { .. }))
            .count()
    }
}
