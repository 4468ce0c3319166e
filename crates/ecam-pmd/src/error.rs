//! Why the motion processor refused a command.
//!
//! A refused command changes nothing: every check runs before any state is
//! written, so the processor (and a running cam) is left exactly as it was.

use core::fmt;

/// A command the motion processor refused.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PmdError {
    /// An axis number outside `0..axis_count` (axes are numbered from 0 in
    /// codes; document 002's comments number them from 1).
    NoSuchAxis {
        /// The axis asked for.
        axis: i64,
        /// How many axes this processor has.
        count: u8,
    },
    /// A value outside the range the command allows.
    OutOfRange {
        /// What the value is, as the document names it.
        what: &'static str,
        /// The value given.
        value: i64,
        /// The allowed range, in words.
        allowed: &'static str,
    },
    /// A buffer index at or past the buffer's length.
    IndexPastLength {
        /// The buffer.
        buffer: u8,
        /// The index given.
        index: i64,
        /// The buffer's length.
        length: u32,
    },
    /// `WriteBuffer` on a buffer whose length is 0.
    EmptyBuffer {
        /// The buffer.
        buffer: u8,
    },
    /// A buffer that would reach past the end of external memory.
    PastMemory {
        /// The buffer.
        buffer: u8,
        /// Its start address (dwords).
        start: u32,
        /// Its length (dwords).
        length: u32,
    },
    /// Start or length of a buffer that an active cam is reading.
    BufferInUse {
        /// The buffer.
        buffer: u8,
        /// The camming axis.
        axis: u8,
    },
    /// `SetCam`/`GetCam` on an axis not (yet) in the ElectronicCam profile mode.
    NotInCamMode {
        /// The axis.
        axis: u8,
    },
    /// `SetCam` on an axis whose cam is active.
    CamActive {
        /// The axis.
        axis: u8,
    },
    /// `SetCam` on a read-only parameter.
    ReadOnly {
        /// The parameter's name.
        param: &'static str,
    },
    /// Switching into or out of cam mode while the axis moves.
    InMotion {
        /// The axis.
        axis: u8,
    },
    /// A simulation command that would fight the cam for the commanded position.
    AxisCamming {
        /// The axis.
        axis: u8,
    },
    /// A code this emulation knows but does not simulate (e.g. a limit-switch event).
    NotSimulated {
        /// What the code is.
        what: &'static str,
        /// The code.
        code: i64,
    },
}

impl fmt::Display for PmdError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::NoSuchAxis { axis, count } => {
                write!(
                    f,
                    "no axis {axis}: axes are numbered 0 to {}",
                    count.saturating_sub(1)
                )
            }
            Self::OutOfRange {
                what,
                value,
                allowed,
            } => {
                write!(f, "{what} {value} is out of range: {allowed}")
            }
            Self::IndexPastLength {
                buffer,
                index,
                length,
            } => write!(
                f,
                "index {index} is past the length of buffer {buffer} ({length}); use 0 to {}",
                length.saturating_sub(1)
            ),
            Self::EmptyBuffer { buffer } => {
                write!(f, "buffer {buffer} has length 0: SetBufferLength first")
            }
            Self::PastMemory {
                buffer,
                start,
                length,
            } => write!(
                f,
                "buffer {buffer} (start {start:#x}, length {length}) would end past external memory ({:#x} dwords)",
                crate::buffer::MEMORY_DWORDS
            ),
            Self::BufferInUse { buffer, axis } => write!(
                f,
                "buffer {buffer} is the table of the active cam on axis {axis}: stop the cam before moving or resizing it"
            ),
            Self::NotInCamMode { axis } => write!(
                f,
                "axis {axis} is not in the ElectronicCam profile mode: SetProfileMode 8 and Update first"
            ),
            Self::CamActive { axis } => {
                write!(
                    f,
                    "the cam on axis {axis} is active: stop it before changing its parameters"
                )
            }
            Self::ReadOnly { param } => write!(f, "{param} is read only"),
            Self::InMotion { axis } => write!(
                f,
                "axis {axis} is in motion: it cannot switch into or out of the ElectronicCam profile mode now"
            ),
            Self::AxisCamming { axis } => write!(
                f,
                "axis {axis} is camming: its positions come from the cam; stop the cam first"
            ),
            Self::NotSimulated { what, code } => {
                write!(f, "{what} {code} is not simulated by this emulation")
            }
        }
    }
}

impl std::error::Error for PmdError {}
