//! Errors of the IL parser, with the file and line they come from: one
//! enum per concern (an operand's token, an operand against its
//! instruction, a statement, the logic-block stack, program flow).

use core::fmt;

use ecam_core::excerpt::excerpt;

use crate::operation_error::OperationError;

/// A program that cannot be loaded: `file:line: problem`.
#[derive(Clone, Debug, PartialEq)]
pub struct ParseError {
    /// Source file name as given to [`crate::Program::parse`].
    pub file: String,
    /// 1-based line number.
    pub line: usize,
    /// What was expected and what was found.
    pub problem: ParseProblem,
}

impl fmt::Display for ParseError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: {}", self.file, self.line, self.problem)
    }
}

impl std::error::Error for ParseError {}

/// Why a line cannot be loaded.
#[derive(Clone, Debug, PartialEq)]
pub enum ParseProblem {
    /// The line is not a valid instruction.
    Statement(StatementError),
    /// The line misuses the logic-block or MPS stack.
    Stack(StackError),
    /// The line breaks a rule of program flow (labels, CJ, CALL/SRET, FEND).
    Flow(FlowError),
    /// The E-cam face refuses a DECAM's operands (operation error 6781).
    Decam(OperationError),
}

impl fmt::Display for ParseProblem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Statement(e) => write!(f, "{e}"),
            Self::Stack(e) => write!(f, "{e}"),
            Self::Flow(e) => write!(f, "{e}"),
            Self::Decam(e) => write!(f, "{e}"),
        }
    }
}

/// A token that is not an operand (each variant holds the token as written).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TokenError {
    /// `V8`, `Z9`: past V7/Z7.
    IndexRegisterRange(String),
    /// `D0Z0.1`: a bit of an index-modified register.
    BitOfIndexed(String),
    /// `D10V9`: the modifier is past V7/Z7.
    ModifierRange {
        /// The token.
        token: String,
        /// The modifier as written.
        by: String,
    },
    /// A modifier that is not V or Z.
    NotModifier(String),
    /// `D0Z0Z1`: two modifiers.
    TwoModifiers {
        /// The token.
        token: String,
        /// The operand before the last modifier.
        base: String,
    },
    /// `E1.5Z0`.
    FloatModified(String),
    /// A modifier on an operand the FX does not modify.
    CannotModify {
        /// The token.
        token: String,
        /// The operand before the modifier.
        base: String,
    },
    /// `Z0V1`: an index register modified.
    IndexRegisterModified(String),
    /// `K1.5`.
    NotK(String),
    /// `H+1`, `HG`.
    NotH(String),
    /// `T256`.
    TimerRange(String),
    /// `Einf`, `E1,5`.
    NotE(String),
    /// `D9000`.
    DeviceRange(String),
    /// `Q1`, `X8`.
    UnknownDevice(String),
    /// `M0.1`: only D registers have bits.
    BitOfNonRegister(String),
    /// `D8512.0`.
    WordBitRange(String),
    /// `D.1`.
    NotWordBit(String),
    /// `D0.G`, `D0.10`.
    BitNumber(String),
    /// `K9M0`.
    GroupDigits(String),
    /// `K4D0`.
    NotGroup(String),
    /// `K8M8500`: the group runs past its device range.
    GroupPastEnd {
        /// The token.
        token: String,
        /// The device letter (X, Y or M).
        kind: String,
    },
    /// `Q5` where a pointer is expected.
    PointerSyntax(String),
    /// `P128` (the pointer in upper case).
    PointerRange(String),
}

impl fmt::Display for TokenError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::IndexRegisterRange(t) => {
                write!(
                    f,
                    "index register `{t}` is out of range (V0-V7, Z0-Z7)",
                    t = excerpt(t)
                )
            }
            Self::BitOfIndexed(t) => write!(
                f,
                "`{t}`: a bit of an index-modified register is not allowed (the FX refuses Dn.b with V/Z); use D(n+offset).b or a word group",
                t = excerpt(t)
            ),
            Self::ModifierRange { token, by } => write!(
                f,
                "`{token}`: index register `{by}` is out of range (V0-V7, Z0-Z7)",
                token = excerpt(token),
                by = excerpt(by)
            ),
            Self::NotModifier(t) => write!(
                f,
                "`{t}`: the modifier must be an index register V0-V7 or Z0-Z7",
                t = excerpt(t)
            ),
            Self::TwoModifiers { token, base } => write!(
                f,
                "`{token}`: an operand takes one index modifier; an index register cannot modify {base}",
                token = excerpt(token),
                base = excerpt(base)
            ),
            Self::FloatModified(t) => write!(
                f,
                "`{t}`: an E constant cannot be index-modified (K and H constants can)",
                t = excerpt(t)
            ),
            Self::CannotModify { token, base } => write!(
                f,
                "`{token}`: an index register cannot modify {base} (the FX modifies D, C, T, X, Y, M, word groups and K/H constants)",
                token = excerpt(token),
                base = excerpt(base)
            ),
            Self::IndexRegisterModified(t) => {
                write!(
                    f,
                    "`{t}`: an index register cannot be index-modified",
                    t = excerpt(t)
                )
            }
            Self::NotK(t) => write!(
                f,
                "`{t}` is not a K constant (expected K and a decimal integer, e.g. K100)",
                t = excerpt(t)
            ),
            Self::NotH(t) => write!(
                f,
                "`{t}` is not an H constant (expected H and hex digits, e.g. H1F)",
                t = excerpt(t)
            ),
            Self::TimerRange(t) => write!(
                f,
                "device `{t}` is out of range (timers T0-T255)",
                t = excerpt(t)
            ),
            Self::NotE(t) => write!(
                f,
                "`{t}` is not an E constant (expected E and a finite decimal number, e.g. E1.6667)",
                t = excerpt(t)
            ),
            Self::DeviceRange(t) => write!(
                f,
                "device `{t}` is out of range (D0-D8511, M0-M8511, X0-X377 and Y0-Y377 octal, C0-C255)",
                t = excerpt(t)
            ),
            Self::UnknownDevice(t) => write!(
                f,
                "unknown device `{t}` (expected D, M, X, Y, C, T and a number, X/Y in octal, or a K/H/E constant)",
                t = excerpt(t)
            ),
            Self::BitOfNonRegister(t) => write!(
                f,
                "`{t}`: only data registers D have addressable bits (Dn.b, b = 0-F)",
                t = excerpt(t)
            ),
            Self::WordBitRange(t) => {
                write!(f, "device `{t}` is out of range (D0-D8511)", t = excerpt(t))
            }
            Self::NotWordBit(t) => write!(
                f,
                "`{t}` is not a bit of a word (expected Dn.b with b = 0-F, e.g. D2001.0)",
                t = excerpt(t)
            ),
            Self::BitNumber(t) => write!(
                f,
                "`{t}`: the bit number must be one hex digit 0-F (e.g. D2001.F)",
                t = excerpt(t)
            ),
            Self::GroupDigits(t) => {
                write!(
                    f,
                    "`{t}`: a word group has 1 to 8 digits (K1M0 to K8M0)",
                    t = excerpt(t)
                )
            }
            Self::NotGroup(t) => write!(
                f,
                "`{t}` is not a word group (expected Kn and an X, Y or M device, e.g. K4M0)",
                t = excerpt(t)
            ),
            Self::GroupPastEnd { token, kind } => {
                write!(
                    f,
                    "word group `{token}` runs past the last {kind} device",
                    token = excerpt(token)
                )
            }
            Self::PointerSyntax(t) => {
                write!(f, "expected a pointer P0–P127, found `{t}`", t = excerpt(t))
            }
            Self::PointerRange(p) => write!(
                f,
                "pointer {p} out of range: the LX3V has P0–P{}",
                super::limits::POINTER_COUNT - 1,
                p = excerpt(p)
            ),
        }
    }
}

impl std::error::Error for TokenError {}

/// An operand that does not fit its instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum OperandError {
    /// The token is not an operand at all.
    Token(TokenError),
    /// An operand of the wrong kind.
    Wrong {
        /// What the instruction takes there.
        expected: &'static str,
        /// The operand as it reads.
        found: String,
        /// The operand is index-modified and this place does not take that.
        indexed: bool,
    },
    /// A 32-bit counter in a 16-bit comparison contact.
    Counter32 {
        /// The counter.
        counter: u16,
        /// The 32-bit form to use (`LDD=`).
        instead: String,
    },
    /// A negative constant set value of a timer (`OUT T0 K-1`).
    TimerSetValue(i32),
    /// A negative constant set value of a 16-bit counter.
    CounterSetValue(i32),
    /// A MUL/DIV result that runs past D8511.
    ResultPastEnd {
        /// The registers the result takes.
        words: u16,
        /// The first register.
        register: u16,
    },
    /// SFTL/SFTR bits that run past the last device.
    BitsPastEnd {
        /// How many bits.
        bits: u16,
        /// The first bit.
        first: crate::Device,
    },
    /// CMP/ZCP result bits that run past the last device.
    ThreeBits(crate::Device),
    /// BMOV/FMOV n out of 1–512.
    BlockCount(i64),
    /// A 32-bit operand Dn without Dn+1.
    NoHighWord(u16),
    /// A constant out of the instruction's range.
    OutOfRange {
        /// The operand as it reads.
        operand: String,
        /// The range allowed.
        range: &'static str,
    },
    /// A word group of more than 4 digits in a 16-bit instruction.
    GroupTooWide16 {
        /// The group.
        group: String,
        /// Its digits.
        digits: u8,
    },
    /// A word group too wide for the result it takes.
    GroupTooWide {
        /// The group.
        group: String,
        /// Its digits.
        digits: u8,
        /// The most digits the result takes.
        max: u8,
    },
    /// An input group KnX as a destination.
    InputGroup(String),
    /// Vn standing for a 32-bit index register (the pair is named by Zn).
    PairByV(u8),
    /// A 32-bit operand modified by Vn (only Zn, the pair Vn:Zn).
    ModifierV {
        /// The operand as it reads.
        operand: String,
        /// n.
        n: u8,
    },
}

impl fmt::Display for OperandError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Token(e) => write!(f, "{e}"),
            Self::Wrong {
                expected,
                found,
                indexed,
            } => {
                write!(f, "expected {expected}, found {found}")?;
                // Say why an index-modified operand that is otherwise of the
                // right kind (`DECAM D0Z0 …`) does not fit.
                if *indexed && !expected.contains("index-modified") {
                    f.write_str(" (this operand cannot be index-modified)")?;
                }
                Ok(())
            }
            Self::Counter32 { counter, instead } => write!(
                f,
                "C{counter} is a 32-bit counter: use the 32-bit form {instead}"
            ),
            Self::TimerSetValue(v) => write!(
                f,
                "set value {v} is out of range for a timer (K0 to K32767)"
            ),
            Self::CounterSetValue(v) => write!(
                f,
                "set value {v} is out of range for a 16-bit counter (K0 to K32767)"
            ),
            Self::ResultPastEnd { words, register } => write!(
                f,
                "the result takes {words} registers from D{register}, past D8511"
            ),
            Self::BitsPastEnd { bits, first } => {
                write!(f, "{bits} bits from {first} run past the last device")
            }
            Self::ThreeBits(dst) => write!(f, "{dst} and the two bits after it must exist"),
            Self::BlockCount(n) => write!(
                f,
                "n = {n} is out of range (K1 to K{})",
                super::limits::BLOCK_MAX
            ),
            Self::NoHighWord(n) => {
                write!(f, "D{n} has no D{} for the high word", u32::from(*n) + 1)
            }
            Self::OutOfRange { operand, range } => {
                write!(f, "{operand} is out of range ({range})")
            }
            Self::GroupTooWide16 { group, digits } => write!(
                f,
                "{group} has {digits} digits; a 16-bit instruction takes K1 to K4"
            ),
            Self::GroupTooWide { group, digits, max } => write!(
                f,
                "{group} has {digits} digits; this result takes K1 to K{max}"
            ),
            Self::InputGroup(group) => write!(
                f,
                "{group} is an input group; inputs X are driven from outside, write KnM or KnY"
            ),
            Self::PairByV(n) => write!(
                f,
                "a 32-bit instruction names the pair V{n}:Z{n} by Z{n} (Z low word, V high word)"
            ),
            Self::ModifierV { operand, n } => write!(
                f,
                "{operand}: a 32-bit instruction is modified by Z{n} (the pair V{n}:Z{n}), not by V{n}"
            ),
        }
    }
}

impl std::error::Error for OperandError {}

impl From<TokenError> for OperandError {
    fn from(e: TokenError) -> Self {
        Self::Token(e)
    }
}

/// Why a mnemonic is not an instruction the LX3V has.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum UnknownHint {
    /// Not in the list at all.
    NotListed,
    /// A comparison-contact name that does not parse.
    Comparison,
    /// The instruction has no 32-bit `D` form.
    NoDoubleForm(String),
    /// The instruction has no pulse `P` form.
    NoPulseForm(String),
    /// `EMOV`: the float move is DEMOV.
    FloatMove,
    /// `ECAM`: the E-cam instruction is DECAM.
    Ecam,
}

/// A line that is not a valid instruction.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StatementError {
    /// An operand that does not fit (`position` from 1).
    Operand {
        /// The mnemonic (for a timer or counter coil, `OUT Tn`/`OUT Cn`).
        mnemonic: String,
        /// The operand's place, from 1.
        position: usize,
        /// What is wrong with it.
        problem: OperandError,
    },
    /// Too many or too few operands.
    Arity {
        /// The mnemonic.
        mnemonic: String,
        /// The operands it takes, by name.
        names: &'static [&'static str],
        /// How many were given.
        found: usize,
    },
    /// END, SRET, FEND with operands.
    NoOperands {
        /// The mnemonic.
        mnemonic: String,
    },
    /// CJ/CALL without exactly one pointer.
    FlowArity {
        /// The mnemonic.
        mnemonic: String,
        /// How many operands were given.
        found: usize,
    },
    /// A pointer label with something after it.
    LabelNotAlone {
        /// The label.
        label: String,
    },
    /// A pointer label out of range.
    BadLabel(TokenError),
    /// P63 as a label.
    EndPointerLabel,
    /// `CALL P63`.
    CallEndPointer {
        /// The mnemonic.
        mnemonic: String,
    },
    /// An instruction the LX3V does not have.
    Unknown {
        /// The mnemonic.
        mnemonic: String,
        /// Why, or what to write instead.
        hint: UnknownHint,
    },
    /// `OUT Tn` without a set value.
    TimerNeedsSetValue(u16),
    /// `OUT Cn` without a set value.
    CounterNeedsSetValue(u16),
    /// OUT with no or more than two operands.
    OutArity(usize),
    /// SFTL/SFTR with n2 > n1.
    ShiftLonger {
        /// The mnemonic.
        mnemonic: String,
        /// n2.
        places: u16,
        /// n1.
        length: u16,
    },
    /// ZRST over two kinds of devices.
    ZoneKinds {
        /// The mnemonic.
        mnemonic: String,
        /// The first operand as it reads.
        first: String,
        /// The second operand as it reads.
        second: String,
    },
    /// ZRST whose first device comes after its last.
    ZoneOrder {
        /// The mnemonic.
        mnemonic: String,
    },
}

impl fmt::Display for StatementError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Operand {
                mnemonic,
                position,
                problem,
            } => write!(
                f,
                "{mnemonic} operand {position}: {problem}",
                mnemonic = excerpt(mnemonic)
            ),
            Self::Arity {
                mnemonic,
                names,
                found,
            } => write!(
                f,
                "{mnemonic} expects {} operand{} ({}), found {found}",
                names.len(),
                if names.len() == 1 { "" } else { "s" },
                names.join(" "),
                mnemonic = excerpt(mnemonic)
            ),
            Self::NoOperands { mnemonic } => write!(
                f,
                "{mnemonic} takes no operands",
                mnemonic = excerpt(mnemonic)
            ),
            Self::FlowArity { mnemonic, found } => {
                write!(
                    f,
                    "{mnemonic} expects 1 operand (Pn), found {found}",
                    mnemonic = excerpt(mnemonic)
                )
            }
            Self::LabelNotAlone { label } => {
                write!(
                    f,
                    "a pointer label {label} stands alone on its line",
                    label = excerpt(label)
                )
            }
            Self::BadLabel(e) => write!(f, "{e}"),
            Self::EndPointerLabel => f.write_str(
                "P63 is the END pointer (`CJ P63` jumps to END); it cannot label a line",
            ),
            Self::CallEndPointer { mnemonic } => write!(
                f,
                "{mnemonic} P63: P63 is the END pointer, only CJ may use it",
                mnemonic = excerpt(mnemonic)
            ),
            Self::Unknown { mnemonic, hint } => {
                write!(
                    f,
                    "unknown instruction `{mnemonic}`",
                    mnemonic = excerpt(mnemonic)
                )?;
                match hint {
                    UnknownHint::NotListed => {
                        f.write_str(" (see docs/plc-instructions.md for the supported list)")
                    }
                    UnknownHint::Comparison => Ok(()),
                    UnknownHint::NoDoubleForm(base) => {
                        write!(f, " ({base} has no 32-bit D form)", base = excerpt(base))
                    }
                    UnknownHint::NoPulseForm(base) => {
                        write!(f, " ({base} has no P form)", base = excerpt(base))
                    }
                    UnknownHint::FloatMove => f.write_str(" (the float move is DEMOV)"),
                    UnknownHint::Ecam => f.write_str(" (the E-cam instruction is DECAM)"),
                }
            }
            Self::TimerNeedsSetValue(t) => write!(
                f,
                "OUT T{t} needs a set value: expected OUT T{t} K<value> or OUT T{t} D<n>"
            ),
            Self::CounterNeedsSetValue(c) => write!(
                f,
                "OUT C{c} needs a set value: expected OUT C{c} K<value> or OUT C{c} D<n>"
            ),
            Self::OutArity(found) => write!(
                f,
                "OUT expects 1 operand (Y/M/Dn.b) or 2 (Cn/Tn K<set value>), found {found}"
            ),
            Self::ShiftLonger {
                mnemonic,
                places,
                length,
            } => write!(
                f,
                "{mnemonic}: n2 = {places} is more than n1 = {length} (the shift cannot be longer than the block)",
                mnemonic = excerpt(mnemonic)
            ),
            Self::ZoneKinds {
                mnemonic,
                first,
                second,
            } => write!(
                f,
                "{mnemonic} expects two devices of the same kind (M, Y, D or C), found {first} {second}",
                mnemonic = excerpt(mnemonic)
            ),
            Self::ZoneOrder { mnemonic } => write!(
                f,
                "{mnemonic}: the first device must not come after the last",
                mnemonic = excerpt(mnemonic)
            ),
        }
    }
}

impl std::error::Error for StatementError {}

/// A misuse of the logic-block or MPS stack, found at load time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum StackError {
    /// A contact, MPS or output with no LD before it.
    NoPowerFlow {
        /// What needs the power flow.
        what: &'static str,
    },
    /// ANB/ORB with fewer than two blocks.
    TwoBlocks,
    /// MPS deeper than the FX's 11 levels.
    MpsDepth,
    /// MRD with no MPS open.
    ReadWithoutPush,
    /// MPP with no MPS open.
    PopWithoutPush,
    /// An output while blocks are not joined.
    BlocksOpen(usize),
    /// An MPS never popped.
    PushNotClosed,
}

impl fmt::Display for StackError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoPowerFlow { what } => write!(
                f,
                "{what} has no power flow: expected LD/LDI/LDP/LDF before it"
            ),
            Self::TwoBlocks => {
                f.write_str("ANB/ORB needs two logic blocks: expected a second LD before it")
            }
            Self::MpsDepth => write!(
                f,
                "MPS nested deeper than {} levels",
                super::limits::MPS_DEPTH
            ),
            Self::ReadWithoutPush => f.write_str("MRD without a matching MPS before it"),
            Self::PopWithoutPush => f.write_str("MPP without a matching MPS before it"),
            Self::BlocksOpen(blocks) => write!(
                f,
                "{blocks} logic blocks are open: expected ANB or ORB to join them before this output"
            ),
            Self::PushNotClosed => {
                f.write_str("MPS is never closed: expected an MPP for its last branch")
            }
        }
    }
}

impl std::error::Error for StackError {}

/// A break of the rules of program flow, found at load time.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FlowError {
    /// A label past P127.
    PointerRange(u8),
    /// A label given twice.
    DuplicateLabel {
        /// n of Pn.
        pointer: u8,
        /// The line of its first use.
        first_line: usize,
    },
    /// CJ or CALL to a label the program does not have.
    NoLabel {
        /// `CJ` or `CALL`.
        mnemonic: &'static str,
        /// n of Pn.
        pointer: u8,
    },
    /// CJ across FEND.
    JumpAcrossEnd(u8),
    /// CALL to a label in the main program.
    CallIntoMain {
        /// n of Pn.
        pointer: u8,
        /// The label's line.
        label_line: usize,
    },
    /// SRET before FEND.
    ReturnInMain,
    /// A subroutine without SRET.
    NeverReturns,
    /// CALLs nested deeper than the FX3U's five levels.
    TooDeep {
        /// n of Pn.
        pointer: u8,
        /// The levels from this CALL.
        levels: usize,
    },
    /// A subroutine that calls itself.
    Recursive(u8),
}

impl fmt::Display for FlowError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::PointerRange(n) => write!(f, "pointer P{n} out of range"),
            Self::DuplicateLabel {
                pointer,
                first_line,
            } => write!(
                f,
                "duplicate label P{pointer}: already at line {first_line}"
            ),
            Self::NoLabel { mnemonic, pointer } => write!(
                f,
                "{mnemonic} P{pointer}: no label P{pointer} in the program",
                mnemonic = excerpt(mnemonic)
            ),
            Self::JumpAcrossEnd(pointer) => write!(
                f,
                "CJ P{pointer}: the label is on the other side of FEND (a jump stays in the main program or in the subroutines)"
            ),
            Self::CallIntoMain {
                pointer,
                label_line,
            } => write!(
                f,
                "CALL P{pointer}: the subroutine label must come after FEND (line {label_line} is in the main program)"
            ),
            Self::ReturnInMain => {
                f.write_str("SRET in the main program: subroutines go after FEND")
            }
            Self::NeverReturns => {
                f.write_str("subroutine never returns: expected SRET after its label")
            }
            Self::TooDeep { pointer, levels } => write!(
                f,
                "CALL P{pointer}: subroutines nested deeper than {} levels ({levels} levels from here)",
                super::limits::CALL_DEPTH
            ),
            Self::Recursive(inner) => write!(
                f,
                "CALL P{inner}: recursive subroutine call (P{inner} is already running)"
            ),
        }
    }
}

impl std::error::Error for FlowError {}
