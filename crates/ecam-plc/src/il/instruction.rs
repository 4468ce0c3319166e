//! The checked instructions a [`super::Program`] is made of.

use crate::device::Device;
use crate::index_register::IndexReg;

/// A statement: an instruction and the source line it came from.
#[derive(Clone, Debug, PartialEq)]
pub struct Statement {
    /// 1-based source line.
    pub line: usize,
    /// The instruction.
    pub instruction: Instruction,
}

/// How a contact reads its device.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Contact {
    /// Normally open (LD, AND, OR): the device's state.
    Open,
    /// Normally closed (LDI, ANI, ORI): the inverse.
    Closed,
    /// Rising edge (LDP, ANDP, ORP): on for one execution after off → on.
    Rising,
    /// Falling edge (LDF, ANDF, ORF): on for one execution after on → off.
    Falling,
}

/// How a contact joins the power flow: LD starts a block, AND puts the
/// contact in series, OR in parallel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Join {
    /// LD…: a new logic block.
    Load,
    /// AND…: in series with the block.
    And,
    /// OR…: in parallel with the block.
    Or,
}

/// The relation of a comparison contact (`LD=`, `AND<>`, `ORD>=`, …).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Relation {
    /// `=`.
    Equal,
    /// `<>`.
    NotEqual,
    /// `>`.
    Greater,
    /// `<`.
    Less,
    /// `>=`.
    GreaterOrEqual,
    /// `<=`.
    LessOrEqual,
}

impl Relation {
    /// Whether `s1 relation s2` holds (signed BIN comparison, as the FX does).
    pub fn holds(self, s1: i32, s2: i32) -> bool {
        match self {
            Self::Equal => s1 == s2,
            Self::NotEqual => s1 != s2,
            Self::Greater => s1 > s2,
            Self::Less => s1 < s2,
            Self::GreaterOrEqual => s1 >= s2,
            Self::LessOrEqual => s1 <= s2,
        }
    }
}

/// Operand width of an applied instruction.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Width {
    /// 16-bit (MOV, ADD, ...).
    Word,
    /// 32-bit, the `D` prefix (DMOV, DADD, ...): Dn low word, Dn+1 high word.
    Double,
}

/// When an applied instruction runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Exec {
    /// Every scan while its power flow is on (the FX default).
    Continuous,
    /// Once, in the scan its power flow turns on (the `P` suffix: MOVP).
    Pulse,
}

/// A numeric source operand.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Source {
    /// A K (decimal) or H (hex) constant, already range-checked for the width.
    Constant(i32),
    /// Data register Dn (Dn, Dn+1 for 32-bit).
    Register(u16),
    /// Current value of counter Cn.
    Counter(u16),
    /// Current value of timer Tn (in its clock units).
    Timer(u16),
    /// A word group `KnM`/`KnX`/`KnY`: n × 4 bits read as a number.
    Group(WordGroup),
    /// An index register as a value: Vn or Zn at 16 bit; at 32 bit `Zn`
    /// names the pair Vn (high word) : Zn (low word), as on the FX3U.
    Index(IndexReg),
    /// An operand modified by an index register (`D10V0`, `K4M0Z1`,
    /// `K10Z0`): the address (or, for a K/H constant, the value) is offset
    /// at run time.
    Indexed(Indexed),
}

/// What an index register modifies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexBase {
    /// A K/H constant: the register's value is added to it.
    Constant(i32),
    /// Dn: the register n + offset.
    Register(u16),
    /// Cn: counter n + offset.
    Counter(u16),
    /// Tn: timer n + offset.
    Timer(u16),
    /// KnM/KnX/KnY: the group starts offset bits later (X/Y: the offset
    /// counts in the octal numbering, as on the FX).
    Group(WordGroup),
}

/// An operand and the index register that modifies it (`D10V0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Indexed {
    /// The operand as written before the modifier.
    pub base: IndexBase,
    /// The modifier. In a 32-bit instruction only Zn is allowed and the
    /// offset is the 32-bit pair Vn:Zn (FX3U rule).
    pub by: IndexReg,
}

impl core::fmt::Display for Indexed {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.base {
            IndexBase::Constant(v) => write!(f, "K{v}")?,
            IndexBase::Register(n) => write!(f, "D{n}")?,
            IndexBase::Counter(n) => write!(f, "C{n}")?,
            IndexBase::Timer(n) => write!(f, "T{n}")?,
            IndexBase::Group(g) => write!(f, "{g}")?,
        }
        write!(f, "{}", self.by)
    }
}

/// Where a word instruction (MOV, ADD, INC, MUL …) writes its result.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dest {
    /// Dn (Dn, Dn+1 at 32 bit).
    Register(u16),
    /// Current value of counter Cn.
    Counter(u16),
    /// Vn/Zn; at 32 bit Zn names the pair Vn:Zn.
    Index(IndexReg),
    /// `KnM`/`KnY`: only the group's n × 4 bits are written.
    Group(WordGroup),
    /// Dn, Cn or a group modified by an index register.
    Indexed(Indexed),
}

impl core::fmt::Display for Dest {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Register(n) => write!(f, "D{n}"),
            Self::Counter(n) => write!(f, "C{n}"),
            Self::Index(r) => write!(f, "{r}"),
            Self::Group(g) => write!(f, "{g}"),
            Self::Indexed(i) => write!(f, "{i}"),
        }
    }
}

/// The bit devices a word group is made of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GroupKind {
    /// Inputs X (numbered in octal).
    X,
    /// Outputs Y (numbered in octal).
    Y,
    /// Auxiliary relays M.
    M,
}

/// `KnM0`, `K2X10`, …: `digits` × 4 consecutive bits from `first`, the
/// lowest bit first (FX "digit specification").
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WordGroup {
    /// X, Y or M.
    pub kind: GroupKind,
    /// Index of the first bit (X/Y already decoded from octal).
    pub first: u16,
    /// n of Kn: 1–8 digits of 4 bits.
    pub digits: u8,
}

impl WordGroup {
    /// The device of the `i`-th bit of the group.
    pub fn bit(&self, i: u16) -> Option<crate::device::Device> {
        let n = self.first.checked_add(i)?;
        Some(match self.kind {
            GroupKind::X => crate::device::Device::X(n),
            GroupKind::Y => crate::device::Device::Y(n),
            GroupKind::M => crate::device::Device::M(n),
        })
    }
}

impl core::fmt::Display for WordGroup {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self.bit(0) {
            Some(first) => write!(f, "K{}{first}", self.digits),
            None => write!(f, "K{}?", self.digits),
        }
    }
}

/// One bit of a data register, `Dn.b` with b = 0–F (the FX3 family's bit
/// specification of a word device): `D2001.0` is bit 0 of D2001.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct WordBit {
    /// The register n of `Dn.b`.
    pub register: u16,
    /// The bit b, 0..=15.
    pub bit: u8,
}

impl core::fmt::Display for WordBit {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        write!(f, "D{}.{:X}", self.register, self.bit)
    }
}

/// The operand of a contact or of OUT/SET/RST: a device, or a bit of a
/// data register.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BitRef {
    /// X, Y, M, a counter contact C (contacts), or D/C for RST.
    Device(Device),
    /// `Dn.b`.
    WordBit(WordBit),
    /// Timer Tn: its contact, or (RST) the whole timer.
    Timer(u16),
    /// An X, Y or M bit, or (contacts only) a counter's contact, modified
    /// by an index register (`X0Z0`, `M0Z1`, `C5Z0`): the number is offset
    /// at run time (X/Y in octal numbering).
    Indexed(Device, IndexReg),
    /// A timer's contact modified by an index register (`T0Z1`; contacts only).
    IndexedTimer(u16, IndexReg),
}

/// A bit device that instructions may drive: Y or M.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BitDest(pub Device);

/// A device range of ZRST.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ZoneDevice {
    /// Mn..=Mm.
    M,
    /// Yn..=Ym (indices decoded from octal).
    Y,
    /// Dn..=Dm.
    D,
    /// Cn..=Cm (value and contact).
    C,
}

/// ADD or SUB.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArithOp {
    /// S1 + S2.
    Add,
    /// S1 − S2.
    Sub,
}

/// WAND/WOR/WXOR (DAND/DOR/DXOR): a bitwise operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LogicOp {
    /// S1 AND S2.
    And,
    /// S1 OR S2.
    Or,
    /// S1 XOR S2.
    Xor,
}

/// Master operand of DECAM as written in the program (S1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MasterSpec {
    /// Cn: a counter (high-speed counters count pulses on their input).
    Counter(u16),
    /// Dn: a 32-bit register.
    Register(u16),
    /// Kn: the internal time base, n × 100 µs per master count.
    TimeBase(u32),
}

/// One instruction with checked operands.
#[derive(Clone, Debug, PartialEq)]
pub enum Instruction {
    /// LD/LDI/LDP/LDF: starts a logic block.
    Load(Contact, BitRef),
    /// AND/ANI/ANDP/ANDF: series contact.
    And(Contact, BitRef),
    /// OR/ORI/ORP/ORF: parallel contact.
    Or(Contact, BitRef),
    /// Comparison contact `LD=` … `ORD>=`: on while `s1 relation s2`.
    CompareContact {
        /// LD, AND or OR form.
        join: Join,
        /// The comparison.
        relation: Relation,
        /// 16 bit (`LD=`) or 32 bit (`LDD=`).
        width: Width,
        /// First operand.
        s1: Source,
        /// Second operand.
        s2: Source,
    },
    /// ANB: the last two blocks in series.
    AndBlock,
    /// ORB: the last two blocks in parallel.
    OrBlock,
    /// MPS: push the power flow.
    Push,
    /// MRD: read the pushed power flow.
    Read,
    /// MPP: pop the pushed power flow.
    Pop,
    /// OUT Y/M/Dn.b: the coil follows the power flow.
    Out(BitRef),
    /// OUT Cn K/D: counter coil with its set value.
    OutCounter {
        /// Counter number.
        counter: u16,
        /// Set value (K constant, or Dn: 16-bit for C0–C199, 32-bit for C200+).
        set_value: Source,
    },
    /// OUT Tn K/D: timer coil with its set value (clock units, 0–32767).
    OutTimer {
        /// Timer number.
        timer: u16,
        /// Set value: a K constant 0–32767 or a 16-bit register.
        preset: Source,
    },
    /// SET Y/M/Dn.b.
    Set(BitRef),
    /// RST Y/M/D/C/Dn.b.
    Reset(BitRef),
    /// PLS (rising) / PLF (falling): the coil is on for one scan on the edge.
    Pulse {
        /// True for PLS, false for PLF.
        rising: bool,
        /// The coil.
        dest: BitDest,
    },
    /// `MOV`/`DMOV`(`P`) S D.
    Move {
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// Source.
        src: Source,
        /// Destination: D, C, V/Z, a word group KnM/KnY, or one of them index-modified.
        dst: Dest,
    },
    /// `DEMOV`(`P`) S D: 32-bit float move (E constant or Dn).
    FloatMove {
        /// Continuous or pulse form.
        exec: Exec,
        /// Constant value, or the register pair holding a float.
        src: FloatSource,
        /// Destination register pair.
        dst: u16,
    },
    /// `ZRST`(`P`) D1 D2.
    ZoneReset {
        /// Continuous or pulse form.
        exec: Exec,
        /// Device kind.
        kind: ZoneDevice,
        /// First index.
        first: u16,
        /// Last index (inclusive).
        last: u16,
    },
    /// `ADD`/`SUB`/`DADD`/`DSUB`(`P`) S1 S2 D.
    Arith {
        /// ADD or SUB.
        op: ArithOp,
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// First operand.
        s1: Source,
        /// Second operand.
        s2: Source,
        /// Destination: D, C, V/Z, a word group KnM/KnY, or one of them index-modified.
        dst: Dest,
    },
    /// `MUL`/`DMUL`(`P`) S1 S2 D: the signed product, twice as wide as the
    /// operands, in D, D+1 (16 bit) or D…D+3 (32 bit), low word first.
    Multiply {
        /// 16 or 32 bit operands.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// Multiplicand.
        s1: Source,
        /// Multiplier.
        s2: Source,
        /// First register of the product, or a word group (which takes
        /// the product's low bits).
        dst: Dest,
    },
    /// `DIV`/`DDIV`(`P`) S1 S2 D: quotient in D (D, D+1 for 32 bit),
    /// remainder in D+1 (D+2, D+3); truncated toward zero, the remainder has
    /// the dividend's sign.
    Divide {
        /// 16 or 32 bit operands.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// Dividend.
        s1: Source,
        /// Divisor.
        s2: Source,
        /// First register of quotient and remainder, or a word group
        /// (which takes the quotient only, as on the FX).
        dst: Dest,
    },
    /// `WAND`/`WOR`/`WXOR`, `DAND`/`DOR`/`DXOR`(`P`) S1 S2 D.
    Logic {
        /// The bitwise operation.
        op: LogicOp,
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// First operand.
        s1: Source,
        /// Second operand.
        s2: Source,
        /// Destination: D, C, V/Z, a word group KnM/KnY, or one of them index-modified.
        dst: Dest,
    },
    /// `NEG`/`DNEG`(`P`) D: two's complement in place (wrapping: NEG of
    /// −32768 is −32768).
    Negate {
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// The register, counter, index register or word group.
        dst: Dest,
    },
    /// `INC`/`DEC`/`DINC`/`DDEC`(`P`) D: add or subtract 1, wrapping, no flags (FX).
    Step {
        /// True for INC, false for DEC.
        up: bool,
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// The register, counter, index register or word group.
        dst: Dest,
    },
    /// `CMP`/`DCMP`(`P`) S1 S2 D: D = S1>S2, D+1 = S1=S2, D+2 = S1<S2.
    Compare {
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// First operand.
        s1: Source,
        /// Second operand.
        s2: Source,
        /// First of three bits (M or Y).
        dst: Device,
    },
    /// `ZCP`/`DZCP`(`P`) S1 S2 S3 D: D = S3 < S1, D+1 = S1 ≤ S3 ≤ S2,
    /// D+2 = S3 > S2 (a lower limit above the upper one is taken as the
    /// upper one too, as on the FX3U).
    ZoneCompare {
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// Lower limit.
        low: Source,
        /// Upper limit.
        high: Source,
        /// The value compared.
        value: Source,
        /// First of three bits (M or Y).
        dst: Device,
    },
    /// `BMOV`(`P`) S D n: copy n consecutive registers from S to D, as if
    /// through a buffer (overlapping blocks copy correctly).
    BlockMove {
        /// Continuous or pulse form.
        exec: Exec,
        /// First source register (D, optionally index-modified).
        src: Dest,
        /// First destination register (D, optionally index-modified).
        dst: Dest,
        /// Number of words, 1–512 (K or D).
        count: Source,
    },
    /// `FMOV`/`DFMOV`(`P`) S D n: write S into n consecutive registers
    /// (32 bit: n register pairs) from D.
    Fill {
        /// 16 or 32 bit.
        width: Width,
        /// Continuous or pulse form.
        exec: Exec,
        /// The value.
        src: Source,
        /// First destination register (D, optionally index-modified).
        dst: Dest,
        /// Number of words (pairs), 1–512 (K or D).
        count: Source,
    },
    /// `SFTL`/`SFTR`(`P`) S D n1 n2: shift the n1 bits from D by n2 places
    /// toward higher (SFTL) or lower (SFTR) numbers; the n2 bits from S fill
    /// the freed places, the n2 bits shifted out are lost.
    BitShift {
        /// True for SFTL, false for SFTR.
        left: bool,
        /// Continuous or pulse form.
        exec: Exec,
        /// First bit shifted in (X, Y or M).
        src: Device,
        /// First bit of the shifted block (Y or M).
        dst: Device,
        /// Length of the block, n1.
        length: u16,
        /// Places per shift, n2 (1 ≤ n2 ≤ n1).
        places: u16,
    },
    /// PLSY/DPLSY S1 S2 D: pulses at S1 Hz, S2 pulses (0 = endless), on Y0..Y3.
    PulseOutput {
        /// 16 or 32 bit operands.
        width: Width,
        /// Frequency in Hz.
        frequency: Source,
        /// Pulse count, 0 = endless.
        count: Source,
        /// Output 0..=3.
        output: u8,
    },
    /// DECAM S1 S2 S3 D1 D2.
    Decam {
        /// S1: master.
        master: MasterSpec,
        /// S2: first register of the E-cam block.
        block: u16,
        /// S3: external start signal (X or M).
        start: Device,
        /// D1: pulse output 0..=3.
        pulse_output: u8,
        /// D2: direction output (Y).
        direction: Device,
    },
    /// ECAMTBX S0 S1 D1 D2.
    Ecamtbx {
        /// S0: parameter block.
        params: u16,
        /// S1: table kind (K0/K1/K2/K100/K101 or a register holding it).
        kind: Source,
        /// D1: table block (sections at D1+38, data from D1+40).
        table: u16,
        /// D2: result register.
        result: u16,
    },
    /// `Pn` standing alone on a line: the pointer label of CJ and CALL
    /// (P0–P127, P63 excepted).
    Label(u8),
    /// `CJ`/`CJP Pn`: while the power flow is on, continue at label Pn,
    /// skipping the instructions between (they keep their outputs). `CJ P63`
    /// jumps to the end of the main program.
    Jump {
        /// Continuous or pulse form.
        exec: Exec,
        /// The pointer number n of Pn.
        pointer: u8,
    },
    /// `CALL`/`CALLP Pn`: run the subroutine at label Pn (after FEND) up to
    /// its SRET, then continue after the CALL.
    Call {
        /// Continuous or pulse form.
        exec: Exec,
        /// The pointer number n of Pn.
        pointer: u8,
    },
    /// `SRET`: end of a subroutine.
    SubReturn,
    /// `FEND`: end of the main program; subroutines follow it.
    MainEnd,
    /// NOP.
    Nop,
}

/// Source of DEMOV.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum FloatSource {
    /// E constant.
    Constant(f32),
    /// Dn, Dn+1 holding an IEEE-754 float.
    Register(u16),
}
