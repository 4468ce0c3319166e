//! What can go wrong with a state directory: the error that stops its use
//! ([`JournalError`]) and what is wrong with a line of one of its files
//! ([`Damage`]). Their own file so that the journal and the file format,
//! which both report them, do not import each other.

use core::fmt;
use std::io;
use std::path::{Path, PathBuf};

use crate::write::LineError;

/// What is wrong with a line of a state file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Damage {
    /// The snapshot is missing beside a journal (the server writes the
    /// snapshot first, so only a deleted one is missing).
    Missing,
    /// The snapshot is empty (it always holds a header and an end marker).
    Empty,
    /// The snapshot's first line is not a snapshot header.
    NoHeader,
    /// The snapshot's last line has no newline: the file was cut short.
    CutShort,
    /// The snapshot has no end marker: the file was cut short.
    NoEndMarker,
    /// Text after the snapshot's end marker.
    AfterEnd,
    /// The end marker is not `end COUNT CRC`.
    BadEndMarker,
    /// The end marker counts another number of records than the file holds.
    EndCount {
        /// The count the marker gives.
        marker: u64,
        /// The records in the file.
        found: u64,
    },
    /// The end marker's checksum over the file does not match.
    FileChecksumMismatch,
    /// A line that is not a record `@SEQ CRC RECORD`.
    NotARecord,
    /// A record whose checksum does not match its content.
    ChecksumMismatch,
    /// A record out of sequence: one removed, repeated or moved.
    Sequence {
        /// The sequence number due.
        expected: u64,
        /// The one found.
        found: u64,
    },
    /// A record (or, in an old-format file, a line) that cannot be read.
    Unreadable(LineError),
    /// The journal's last line, without its newline, holds what no record
    /// has (a NUL, another control character, bytes that are not UTF-8):
    /// not a write cut short by a crash but a file zeroed or overwritten,
    /// whose records are lost.
    NotText {
        /// Bytes in that line (invalid UTF-8 counted as read).
        bytes: usize,
    },
}

impl fmt::Display for Damage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Missing => f.write_str("missing, though the journal is there"),
            Self::Empty => f.write_str("empty file (a snapshot holds a header and an end marker)"),
            Self::NoHeader => f.write_str("not an ecam snapshot header"),
            Self::CutShort => f.write_str("cut short (no newline at the end of the file)"),
            Self::NoEndMarker => f.write_str("no end marker: the file was cut short"),
            Self::AfterEnd => f.write_str("text after the end marker"),
            Self::BadEndMarker => f.write_str("not an end marker `end COUNT CRC`"),
            Self::EndCount { marker, found } => write!(
                f,
                "the end marker counts {marker} records, the file holds {found}"
            ),
            Self::FileChecksumMismatch => f.write_str("checksum mismatch over the whole file"),
            Self::NotARecord => f.write_str("not a record `@SEQ CRC RECORD`"),
            Self::ChecksumMismatch => f.write_str("checksum mismatch"),
            Self::Sequence { expected, found } if found < expected => write!(
                f,
                "record {found} where {expected} was due: a record repeated or moved"
            ),
            Self::Sequence { expected, found } => write!(
                f,
                "record {found} where {expected} was due: a record removed or moved"
            ),
            Self::Unreadable(err) => write!(f, "unreadable record: {err}"),
            Self::NotText { bytes } => write!(
                f,
                "{bytes} bytes that are not text at the end of the file (NULs or other \
                 control characters): it was zeroed or overwritten, not cut short by a crash"
            ),
        }
    }
}

/// Why the state directory cannot be used.
#[derive(Debug)]
pub enum JournalError {
    /// A file operation failed.
    Io {
        /// The file or directory.
        path: PathBuf,
        /// The operating system's error.
        source: io::Error,
    },
    /// A damaged state file (not a torn last journal line).
    Corrupt {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong there.
        damage: Damage,
    },
    /// An earlier append failed and could not be undone: the journal's end
    /// is unknown, so no more writes are accepted until a restart.
    Broken,
    /// The compaction at start failed (see [`Journal::read_only`](crate::Journal::read_only)): the
    /// old files were left as they were, and no write is accepted until a
    /// restart.
    ReadOnly,
}

impl fmt::Display for JournalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Corrupt { path, line, damage } => {
                write!(f, "{}:{line}: {damage}", path.display())
            }
            Self::Broken => f.write_str(
                "an earlier journal write failed and could not be undone; restart the server",
            ),
            Self::ReadOnly => f.write_str(
                "the state directory is read-only: its compaction at start failed \
                 (free some space and restart the server)",
            ),
        }
    }
}

impl std::error::Error for JournalError {}

/// A file operation's error on `path`, as [`JournalError::Io`].
pub(crate) fn io_error(path: &Path) -> impl FnOnce(io::Error) -> JournalError + '_ {
    move |source| JournalError::Io {
        path: path.to_path_buf(),
        source,
    }
}
