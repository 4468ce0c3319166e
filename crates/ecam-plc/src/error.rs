//! What a [`ParseError`](crate::ParseError) holds, to match on: the
//! problem of the line ([`ParseProblem`]) and the enums behind it, one per
//! concern (a statement, an operand against its instruction, an operand's
//! token, the logic-block stack, program flow).
//!
//! The other errors sit next to what returns them: [`crate::OperationError`]
//! (an instruction at run time, with the FX codes), [`crate::DeviceError`],
//! [`crate::ViewError`], [`crate::WireError`], [`crate::sim::TimingError`]
//! and [`crate::decam::BlockError`].

pub use crate::il::{
    FlowError, OperandError, ParseProblem, StackError, StatementError, TokenError, UnknownHint,
};
