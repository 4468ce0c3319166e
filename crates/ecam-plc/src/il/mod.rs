//! The instruction list (IL) language of the LX3V: one instruction per line,
//! `;` starts a comment, mnemonics and device names are case-insensitive.
//!
//! [`Program::parse`] turns source text into a [`Program`] whose operands
//! are all checked: an unknown device, an operand of the wrong kind or a
//! number out of range is a [`ParseError`] naming the file and line, never a
//! silent zero at run time. `docs/plc-instructions.md` lists every
//! instruction. The syntax tree ([`Instruction`] and its operands) is this
//! crate's own: users load and run a [`Program`], they do not build one.

mod error;
mod flow;
mod instruction;
mod lexer;
mod limits;
mod operand;
mod parser;
mod validate;

pub(crate) use limits::{BLOCK_MAX, CALL_DEPTH, END_POINTER, POINTER_COUNT};
pub(crate) use validate::is_output;

pub use error::{
    FlowError, OperandError, ParseError, ParseProblem, StackError, StatementError, TokenError,
    UnknownHint,
};
pub(crate) use instruction::{
    ArithOp, BitDest, BitRef, Contact, Dest, Exec, FloatSource, GroupKind, IndexBase, Indexed,
    Instruction, Join, LogicOp, MasterSpec, Relation, Source, Statement, Width, WordGroup,
    ZoneDevice,
};

/// A parsed, checked instruction-list program, ready for [`crate::Plc::new`].
#[derive(Clone, Debug, PartialEq)]
pub struct Program {
    /// Name of the source file (for messages).
    pub(crate) file: String,
    /// The statements, in program order (after `END`, nothing is kept).
    pub(crate) statements: Vec<Statement>,
}

impl Program {
    /// Parses and checks a program. `file` names the source in error
    /// messages (`file:line: message`). Lines after `END` are ignored, as on
    /// the PLC.
    ///
    /// # Errors
    /// The first problem found: unknown mnemonic, wrong operand count or
    /// kind, unknown or out-of-range device, constant out of range,
    /// unbalanced ANB/ORB/MPS/MRD/MPP, a CJ/CALL to a missing label, a
    /// duplicate label, a subroutine label before FEND, SRET in the main
    /// program, a subroutine without SRET, recursive or too deeply nested
    /// CALLs.
    ///
    /// ```
    /// use ecam_plc::Program;
    /// let program = Program::parse("LD X0\nOUT Y0\nEND\n", "demo.il").unwrap();
    /// assert_eq!(program.len(), 2);
    /// let err = Program::parse("LD X0\nOUT Q9\n", "demo.il").unwrap_err();
    /// assert!(err.to_string().starts_with("demo.il:2: "));
    /// ```
    pub fn parse(source: &str, file: &str) -> Result<Self, ParseError> {
        parser::parse(source, file)
    }

    /// The source file's name, as given to [`Program::parse`].
    pub fn file(&self) -> &str {
        &self.file
    }

    /// Number of instructions (comments, blank lines and what follows
    /// `END` are not instructions).
    pub fn len(&self) -> usize {
        self.statements.len()
    }

    /// True for a program without instructions.
    pub fn is_empty(&self) -> bool {
        self.statements.is_empty()
    }
}

#[cfg(test)]
mod tests;
