//! Durable writes: what `ecam serve --state DIR` keeps across a crash.
//!
//! Every write a client makes (Modbus 0x05/0x06/0x0F/0x10, HTTP `POST
//! /api/devices`) is appended to `DIR/journal.log` as one line (see
//! [`WriteBatch::to_line`]) and the file is `fdatasync`ed *before* the response is
//! sent, so an acknowledged write survives `kill -9` and a power cut. A
//! write the server could not make durable is refused (Modbus exception 04,
//! HTTP 500) and not applied.
//!
//! On start the server reads `DIR/snapshot.txt`, replays the journal over
//! it (last write wins), and compacts: the result is written to a temporary
//! file, synced, renamed over the snapshot, and the journal is emptied. A
//! crash between those steps leaves a journal whose replay is idempotent. A
//! last journal line without its newline is a write that was cut off before
//! it was acknowledged: it is dropped. Any other unreadable line stops the
//! server with the file and line, rather than guess. The same compaction
//! runs while serving once the journal holds [`COMPACT_AFTER`] records or
//! [`COMPACT_AFTER_BYTES`] bytes.
//!
//! What is kept (see [`is_kept`](crate::is_kept) for the rules): the last value
//! *written from outside* to each ordinary D, M and X device, and the
//! latched devices' values the program itself wrote, saved periodically.
//! Special devices (D8000–D8511, M8000–M8511) are never kept: a write to
//! them takes effect but is not journalled, and records for them in state
//! files written by older versions are skipped on open and dropped by the
//! compaction that follows.

use std::collections::{BTreeMap, BTreeSet};
use std::fs::{self, File, OpenOptions};
use std::io::{self, Write as _};
use std::path::{Path, PathBuf};

use ecam_plc::Devices;

use crate::retain;
use crate::write::{Slot, WriteBatch};

/// Journal file name inside the state directory.
pub const JOURNAL_FILE: &str = "journal.log";
/// Snapshot file name inside the state directory.
pub const SNAPSHOT_FILE: &str = "snapshot.txt";
/// Journal records after which the journal is compacted into the snapshot.
pub const COMPACT_AFTER: usize = 4096;
/// Journal size after which it is compacted whatever its record count: a
/// save of latched values can be one long line every second.
pub const COMPACT_AFTER_BYTES: u64 = 8 << 20;

const SNAPSHOT_HEADER: &str =
    "# ecam serve snapshot: the last kept value of each D, M, X and C device\n";

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
    /// A record that cannot be read (not a torn last line).
    Corrupt {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// An earlier append failed and could not be undone: the journal's end
    /// is unknown, so no more writes are accepted until a restart.
    Broken,
}

impl std::fmt::Display for JournalError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Io { path, source } => write!(f, "{}: {source}", path.display()),
            Self::Corrupt {
                path,
                line,
                message,
            } => write!(
                f,
                "{}:{line}: {message} (fix or remove the line to start)",
                path.display()
            ),
            Self::Broken => f.write_str(
                "an earlier journal write failed and could not be undone; restart the server",
            ),
        }
    }
}

impl std::error::Error for JournalError {}

fn io_error(path: &Path) -> impl FnOnce(io::Error) -> JournalError + '_ {
    move |source| JournalError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// What [`Journal::open`] found.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Recovery {
    /// Records replayed from the journal.
    pub replayed: usize,
    /// Whether a torn last record was dropped.
    pub torn_tail: bool,
    /// Special devices whose records were skipped (written by an older
    /// version, which journalled them).
    pub skipped_special: BTreeSet<Slot>,
}

/// The open journal of a state directory and the values it keeps.
#[derive(Debug)]
pub struct Journal {
    dir: PathBuf,
    file: File,
    len: u64,
    records: usize,
    compact_after: usize,
    compact_after_bytes: u64,
    broken: bool,
    compaction_failure: Option<JournalError>,
    persisted: BTreeMap<Slot, i32>,
}

/// Applies every line of `text` (from `path`) to `values`, leaving out the
/// devices that are not kept (added to `skipped`); returns the records read
/// and whether a torn last line was dropped.
fn replay(
    text: &str,
    path: &Path,
    values: &mut BTreeMap<Slot, i32>,
    skipped: &mut BTreeSet<Slot>,
    allow_torn_tail: bool,
) -> Result<(usize, bool), JournalError> {
    let complete = text.ends_with('\n') || text.is_empty();
    let lines: Vec<&str> = text.lines().collect();
    let mut records = 0;
    let mut torn = false;
    for (k, line) in lines.iter().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        // A last line without its newline was never acknowledged, whether
        // or not what reached the disk happens to parse. (The snapshot is
        // renamed into place whole, so it has no torn lines.)
        if allow_torn_tail && !complete && k + 1 == lines.len() {
            torn = true;
            continue;
        }
        let batch = WriteBatch::parse_line(line).map_err(|err| JournalError::Corrupt {
            path: path.to_path_buf(),
            line: k + 1,
            message: err.to_string(),
        })?;
        for &(slot, value) in batch.writes() {
            if retain::is_kept(slot) {
                values.insert(slot, value);
            } else {
                skipped.insert(slot);
            }
        }
        records += 1;
    }
    Ok((records, torn))
}

fn read_optional(path: &Path) -> Result<String, JournalError> {
    match fs::read(path) {
        Ok(bytes) => Ok(String::from_utf8_lossy(&bytes).into_owned()),
        Err(err) if err.kind() == io::ErrorKind::NotFound => Ok(String::new()),
        Err(err) => Err(io_error(path)(err)),
    }
}

/// Makes a rename or a new file in `dir` durable (POSIX needs the
/// directory synced; Windows cannot open a directory as a file and
/// commits renames with the file system's own journal).
fn sync_dir(dir: &Path) -> Result<(), JournalError> {
    #[cfg(unix)]
    {
        File::open(dir)
            .and_then(|d| d.sync_all())
            .map_err(io_error(dir))
    }
    #[cfg(not(unix))]
    {
        let _ = dir;
        Ok(())
    }
}

impl Journal {
    /// Opens (creating it if needed) the state directory `dir`: loads the
    /// snapshot, replays the journal and compacts both.
    ///
    /// # Errors
    /// File errors, or a corrupt record (with its file and line).
    pub fn open(dir: &Path) -> Result<(Self, Recovery), JournalError> {
        if dir.exists() && !dir.is_dir() {
            // create_dir_all would only say "File exists".
            return Err(JournalError::Io {
                path: dir.to_path_buf(),
                source: io::Error::other("exists but is not a directory: give a directory path"),
            });
        }
        fs::create_dir_all(dir).map_err(io_error(dir))?;
        let snapshot_path = dir.join(SNAPSHOT_FILE);
        let journal_path = dir.join(JOURNAL_FILE);
        let mut persisted = BTreeMap::new();
        let mut skipped_special = BTreeSet::new();
        let snapshot = read_optional(&snapshot_path)?;
        replay(
            &snapshot,
            &snapshot_path,
            &mut persisted,
            &mut skipped_special,
            false,
        )?;
        let journal = read_optional(&journal_path)?;
        let (replayed, torn_tail) = replay(
            &journal,
            &journal_path,
            &mut persisted,
            &mut skipped_special,
            true,
        )?;

        write_snapshot(dir, &persisted)?;
        let file = File::create(&journal_path).map_err(io_error(&journal_path))?;
        file.sync_all().map_err(io_error(&journal_path))?;
        sync_dir(dir)?;
        let file = OpenOptions::new()
            .append(true)
            .open(&journal_path)
            .map_err(io_error(&journal_path))?;
        Ok((
            Self {
                dir: dir.to_path_buf(),
                file,
                len: 0,
                records: 0,
                compact_after: COMPACT_AFTER,
                compact_after_bytes: COMPACT_AFTER_BYTES,
                broken: false,
                compaction_failure: None,
                persisted,
            },
            Recovery {
                replayed,
                torn_tail,
                skipped_special,
            },
        ))
    }

    /// The last value kept for each device: what a restart restores.
    pub fn persisted(&self) -> &BTreeMap<Slot, i32> {
        &self.persisted
    }

    /// Records in the journal since the last compaction.
    pub fn records(&self) -> usize {
        self.records
    }

    /// Writes every kept value into `devices` (before the first scan).
    pub fn restore_into(&self, devices: &mut Devices) {
        let mut batch = WriteBatch::new();
        for (&slot, &value) in &self.persisted {
            batch.slot(slot, value);
        }
        batch.apply(devices);
    }

    /// Appends `batch`, without the devices that are not kept (special
    /// devices), as one record and syncs it to disk. When this returns `Ok`,
    /// the write survives a crash.
    ///
    /// # Errors
    /// The file could not be written or synced; the record is then cut off
    /// again so the journal stays readable ([`JournalError::Broken`] if even
    /// that fails).
    pub fn append(&mut self, batch: &WriteBatch) -> Result<(), JournalError> {
        if self.broken {
            return Err(JournalError::Broken);
        }
        let kept = retain::kept(batch);
        let batch = kept.as_ref().unwrap_or(batch);
        if batch.is_empty() {
            return Ok(());
        }
        let mut line = batch.to_line();
        line.push('\n');
        let path = self.dir.join(JOURNAL_FILE);
        let written = self
            .file
            .write_all(line.as_bytes())
            .and_then(|()| self.file.sync_data());
        if let Err(err) = written {
            if self
                .file
                .set_len(self.len)
                .and_then(|()| self.file.sync_data())
                .is_err()
            {
                self.broken = true;
            }
            return Err(io_error(&path)(err));
        }
        self.len = self.len.saturating_add(line.len() as u64);
        self.records += 1;
        for &(slot, value) in batch.writes() {
            self.persisted.insert(slot, value);
        }
        if self.records >= self.compact_after || self.len >= self.compact_after_bytes {
            // The record is already durable, so this write stands whatever
            // happens here; a failed compaction is retried on the next one.
            if let Err(err) = self.compact() {
                self.compaction_failure = Some(err);
            }
        }
        Ok(())
    }

    /// The failure of the last compaction [`Self::append`] tried, if it
    /// failed and was not taken yet. The append itself stood: its record
    /// was durable before the compaction began, which is retried on the
    /// next append.
    pub fn take_compaction_failure(&mut self) -> Option<JournalError> {
        self.compaction_failure.take()
    }

    /// Folds the journal into the snapshot and empties it.
    fn compact(&mut self) -> Result<(), JournalError> {
        write_snapshot(&self.dir, &self.persisted)?;
        let path = self.dir.join(JOURNAL_FILE);
        // Appends go to the end whatever the cursor, so truncating the
        // open append handle is enough.
        self.file
            .set_len(0)
            .and_then(|()| self.file.sync_all())
            .map_err(io_error(&path))?;
        self.len = 0;
        self.records = 0;
        Ok(())
    }
}

/// Writes `values` as the new snapshot: temporary file, sync, rename, sync
/// the directory.
fn write_snapshot(dir: &Path, values: &BTreeMap<Slot, i32>) -> Result<(), JournalError> {
    let tmp = dir.join(format!("{SNAPSHOT_FILE}.tmp"));
    let mut text = String::from(SNAPSHOT_HEADER);
    let entries: Vec<(Slot, i32)> = values.iter().map(|(&s, &v)| (s, v)).collect();
    // 32 values a line keeps the file readable.
    for chunk in entries.chunks(32) {
        let mut batch = WriteBatch::new();
        for &(slot, value) in chunk {
            batch.slot(slot, value);
        }
        text.push_str(&batch.to_line());
        text.push('\n');
    }
    let mut file = File::create(&tmp).map_err(io_error(&tmp))?;
    file.write_all(text.as_bytes())
        .and_then(|()| file.sync_all())
        .map_err(io_error(&tmp))?;
    let target = dir.join(SNAPSHOT_FILE);
    fs::rename(&tmp, &target).map_err(io_error(&target))?;
    sync_dir(dir)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use ecam_plc::Device;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("ecam-journal-{}-{name}", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        dir
    }

    #[test]
    fn appended_writes_come_back_after_reopening() {
        let dir = scratch("reopen");
        let (mut journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(recovery, Recovery::default());
        let mut batch = WriteBatch::new();
        batch.word(100, 5).word(101, 6).bit(Device::M(3), true);
        journal.append(&batch).unwrap();
        let mut later = WriteBatch::new();
        later.word(100, 7).bit(Device::X(15), true);
        journal.append(&later).unwrap();
        drop(journal);

        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(recovery.replayed, 2);
        let mut devices = Devices::new();
        journal.restore_into(&mut devices);
        assert_eq!(devices.word(100), Ok(7));
        assert_eq!(devices.word(101), Ok(6));
        assert_eq!(devices.bit(Device::M(3)), Ok(true));
        assert_eq!(devices.bit(Device::X(15)), Ok(true));
        // Compacted: the journal is empty, the snapshot holds everything.
        assert_eq!(fs::read_to_string(dir.join(JOURNAL_FILE)).unwrap(), "");
        let (again, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(recovery.replayed, 0);
        assert_eq!(again.persisted(), journal.persisted());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_file_given_as_the_state_directory_says_so() {
        let path = scratch("not-a-dir");
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        let _ = fs::remove_dir_all(&path);
        fs::write(&path, "").unwrap();
        let message = Journal::open(&path).err().unwrap().to_string();
        assert!(message.contains("is not a directory"), "{message}");
        fs::remove_file(&path).unwrap();
    }

    #[test]
    fn a_torn_last_record_is_dropped_and_others_kept() {
        let dir = scratch("torn");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D1 1\nD2 2\nD3 3").unwrap();
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(
            recovery,
            Recovery {
                replayed: 2,
                torn_tail: true,
                skipped_special: BTreeSet::new(),
            }
        );
        assert_eq!(journal.persisted().get(&Slot::D(2)), Some(&2));
        assert_eq!(journal.persisted().get(&Slot::D(3)), None);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_corrupt_record_names_its_line() {
        let dir = scratch("corrupt");
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D1 1\nY7 1\nD2 2\n").unwrap();
        let err = Journal::open(&dir).unwrap_err();
        assert!(
            matches!(err, JournalError::Corrupt { line: 2, .. }),
            "{err}"
        );
        assert!(err.to_string().contains("journal.log:2"));
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn compaction_keeps_the_last_values() {
        let dir = scratch("compact");
        let (mut journal, _) = Journal::open(&dir).unwrap();
        // Every append is synced: a small threshold keeps the test quick.
        journal.compact_after = 40;
        for k in 0..60 {
            let mut batch = WriteBatch::new();
            batch.word((k % 50) as u16, k as u16);
            journal.append(&batch).unwrap();
        }
        assert_eq!(journal.records(), 20);
        let expected = journal.persisted().clone();
        drop(journal);
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(recovery.replayed, 20);
        assert_eq!(journal.persisted(), &expected);
        assert_eq!(expected.get(&Slot::D(9)), Some(&59));
        assert_eq!(expected.get(&Slot::D(10)), Some(&10));
        assert_eq!(expected.get(&Slot::D(49)), Some(&49));
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_failed_compaction_is_left_for_the_caller_and_the_write_stands() {
        let dir = scratch("compact-fails");
        let (mut journal, _) = Journal::open(&dir).unwrap();
        journal.compact_after = 1;
        // The open journal file outlives its directory; the snapshot cannot.
        fs::remove_dir_all(&dir).unwrap();
        let mut batch = WriteBatch::new();
        batch.word(100, 5);
        assert!(journal.append(&batch).is_ok());
        assert!(matches!(
            journal.take_compaction_failure(),
            Some(JournalError::Io { .. })
        ));
        assert!(journal.take_compaction_failure().is_none());
        assert_eq!(journal.records(), 1);
        assert_eq!(journal.persisted().get(&Slot::D(100)), Some(&5));
    }

    #[test]
    fn a_long_journal_is_compacted_by_size() {
        let dir = scratch("compact-bytes");
        let (mut journal, _) = Journal::open(&dir).unwrap();
        journal.compact_after_bytes = 100;
        let mut batch = WriteBatch::new();
        for n in 200..240 {
            batch.word(n, 12345);
        }
        journal.append(&batch).unwrap();
        assert_eq!(journal.records(), 0);
        assert_eq!(fs::read_to_string(dir.join(JOURNAL_FILE)).unwrap(), "");
        drop(journal);
        let (journal, _) = Journal::open(&dir).unwrap();
        assert_eq!(journal.persisted().len(), 40);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn special_devices_from_old_state_files_are_skipped_and_dropped() {
        let dir = scratch("special");
        fs::create_dir_all(&dir).unwrap();
        // As an older version wrote them: M8145 (stop Y0) and D8140 kept.
        fs::write(
            dir.join(SNAPSHOT_FILE),
            "# old\nD100 5;D7998 1 2 3 4;M8145 1\n",
        )
        .unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D8140 9;M499 1 1\n").unwrap();
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(
            recovery.skipped_special,
            BTreeSet::from([Slot::D(8000), Slot::D(8001), Slot::D(8140), Slot::M(8145)])
        );
        assert_eq!(recovery.replayed, 1);
        let kept: Vec<Slot> = journal.persisted().keys().copied().collect();
        assert_eq!(
            kept,
            [
                Slot::D(100),
                Slot::D(7998),
                Slot::D(7999),
                Slot::M(499),
                Slot::M(500)
            ]
        );
        let mut devices = Devices::new();
        journal.restore_into(&mut devices);
        assert_eq!(devices.m(8145), Ok(false));
        assert_eq!(devices.word(8140), Ok(0));
        // The compaction at open dropped them: a second open skips nothing.
        drop(journal);
        let (_, recovery) = Journal::open(&dir).unwrap();
        assert!(recovery.skipped_special.is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn writes_to_special_devices_are_not_journalled() {
        let dir = scratch("special-append");
        let (mut journal, _) = Journal::open(&dir).unwrap();
        let mut stop = WriteBatch::new();
        stop.bit(Device::M(8145), true);
        journal.append(&stop).unwrap();
        assert_eq!(journal.records(), 0);
        let mut mixed = WriteBatch::new();
        mixed.word(7999, 1).word(8000, 2).bit(Device::M(8146), true);
        journal.append(&mixed).unwrap();
        assert_eq!(journal.records(), 1);
        assert_eq!(
            fs::read_to_string(dir.join(JOURNAL_FILE)).unwrap(),
            "D7999 1\n"
        );
        fs::remove_dir_all(&dir).unwrap();
    }
}
