//! Durable writes: what `ecam serve --state DIR` keeps across a crash.
//!
//! Every write a client makes (Modbus 0x05/0x06/0x0F/0x10, HTTP `POST
//! /api/devices`) is appended to `DIR/journal.log` as one checksummed
//! record (`state_file.rs` and `docs/modbus.md` give the format) and the
//! file is `fdatasync`ed *before* the response is sent, so an acknowledged
//! write survives `kill -9` and a power cut. A write the server could not
//! make durable is refused (Modbus exception 04, HTTP 500) and not applied.
//!
//! On start the server reads `DIR/snapshot.txt`, replays the journal over
//! it (last write wins), and compacts: the result is written to a temporary
//! file, synced, renamed over the snapshot, and the journal is emptied. A
//! crash between those steps leaves a journal whose replay is idempotent. A
//! last journal line without its newline is a write that was cut off before
//! it was acknowledged: it is dropped. Any other damage (a checksum that
//! does not match, a record missing, repeated or moved, a snapshot cut
//! short) stops the start with the file and line, rather than guess — or,
//! with [`OnDamage::Recover`], restores the last consistent state and lists
//! what it dropped ([`Recovery::dropped`]). A compaction that fails at start
//! (a full disk) leaves the old files as they were and the journal
//! read-only ([`Journal::read_only`]). The same compaction runs while
//! serving once the journal holds [`COMPACT_AFTER`] records or
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
use crate::state_error::{Damage, JournalError, io_error};
use crate::state_file::{self, Dropped, Format, Replay};
use crate::write::{Slot, WriteBatch};

/// Journal file name inside the state directory.
pub const JOURNAL_FILE: &str = "journal.log";
/// Snapshot file name inside the state directory.
pub const SNAPSHOT_FILE: &str = "snapshot.txt";
/// Appended to the name of a damaged file [`OnDamage::Recover`] set aside.
pub const DAMAGED_SUFFIX: &str = ".damaged";
/// Journal records after which the journal is compacted into the snapshot.
pub const COMPACT_AFTER: usize = 4096;
/// Journal size after which it is compacted whatever its record count: a
/// save of latched values can be one long line every second.
pub const COMPACT_AFTER_BYTES: u64 = 8 << 20;

/// What [`Journal::open_with`] does with a damaged state file.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum OnDamage {
    /// Stop with the file, the line and what is wrong
    /// ([`JournalError::Corrupt`]).
    #[default]
    Refuse,
    /// Restore the last consistent state: every snapshot record whose
    /// checksum matches, and the journal up to its first damaged record.
    /// What is dropped is listed in [`Recovery::dropped`], and the damaged
    /// files are kept beside the new ones with [`DAMAGED_SUFFIX`].
    Recover,
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
    /// Damage [`OnDamage::Recover`] stepped over, in file order.
    pub dropped: Vec<Dropped>,
    /// Damaged files set aside (renamed with [`DAMAGED_SUFFIX`]).
    pub set_aside: Vec<PathBuf>,
    /// Whether a file was in the format without checksums (rewritten with
    /// them by the compaction at start, unless it failed).
    pub old_format: bool,
}

/// The open journal of a state directory and the values it keeps.
#[derive(Debug)]
pub struct Journal {
    dir: PathBuf,
    /// `None` when read-only.
    file: Option<File>,
    len: u64,
    records: usize,
    compact_after: usize,
    compact_after_bytes: u64,
    broken: bool,
    read_only: Option<JournalError>,
    compaction_failure: Option<JournalError>,
    persisted: BTreeMap<Slot, i32>,
}

/// The text of `path`, `None` if there is no such file.
fn read_optional(path: &Path) -> Result<Option<String>, JournalError> {
    match fs::read(path) {
        Ok(bytes) => Ok(Some(String::from_utf8_lossy(&bytes).into_owned())),
        Err(err) if err.kind() == io::ErrorKind::NotFound => Ok(None),
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

fn damaged_name(path: &Path) -> PathBuf {
    let mut name = path.as_os_str().to_owned();
    name.push(DAMAGED_SUFFIX);
    PathBuf::from(name)
}

impl Journal {
    /// Opens (creating it if needed) the state directory `dir`: loads the
    /// snapshot, replays the journal and compacts both; a damaged file
    /// stops it ([`OnDamage::Refuse`]).
    ///
    /// # Errors
    /// File errors, or damage (with its file and line).
    pub fn open(dir: &Path) -> Result<(Self, Recovery), JournalError> {
        Self::open_with(dir, OnDamage::Refuse)
    }

    /// Opens the state directory `dir` as [`Self::open`] does, doing
    /// `on_damage` with damaged files. When the compaction fails (a full
    /// disk), the old files are left as they were and the journal is
    /// opened read-only ([`Self::read_only`]) rather than failing.
    ///
    /// # Errors
    /// `dir` cannot be created or read, or (with [`OnDamage::Refuse`]) a
    /// damaged file.
    pub fn open_with(dir: &Path, on_damage: OnDamage) -> Result<(Self, Recovery), JournalError> {
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
        let mut replay = Replay {
            recover: on_damage == OnDamage::Recover,
            ..Replay::default()
        };
        let snapshot = read_optional(&snapshot_path)?;
        let journal = read_optional(&journal_path)?;
        let snapshot_format = match &snapshot {
            Some(text) => state_file::read_snapshot(text, &snapshot_path, &mut replay)?,
            None if journal.is_some() => {
                replay.damage(&snapshot_path, 1, Damage::Missing, 0)?;
                Format::Checked
            }
            None => Format::Checked,
        };
        let snapshot_damages = replay.dropped.len();
        let journal = journal.unwrap_or_default();
        let read = state_file::read_journal(&journal, &journal_path, &mut replay)?;
        // A missing snapshot is damage, but there is no file to set aside.
        let snapshot_damaged = snapshot_damages > 0 && snapshot.is_some();
        let journal_damaged = replay.dropped.len() > snapshot_damages;

        let mut set_aside = Vec::new();
        let mut journal = Self {
            dir: dir.to_path_buf(),
            file: None,
            len: 0,
            records: 0,
            compact_after: COMPACT_AFTER,
            compact_after_bytes: COMPACT_AFTER_BYTES,
            broken: false,
            read_only: None,
            compaction_failure: None,
            persisted: replay.values,
        };
        let aside = |damaged: bool, path: &Path| damaged.then(|| damaged_name(path));
        let compacted = journal.compact_at_open(
            aside(snapshot_damaged, &snapshot_path),
            aside(journal_damaged, &journal_path),
            &mut set_aside,
        );
        if let Err(err) = compacted {
            journal.read_only = Some(err);
        }
        Ok((
            journal,
            Recovery {
                replayed: read.records,
                torn_tail: read.torn,
                skipped_special: replay.skipped,
                dropped: replay.dropped,
                set_aside,
                old_format: snapshot_format == Format::Old || read.format == Format::Old,
            },
        ))
    }

    /// Writes the snapshot and starts an empty journal, setting aside the
    /// damaged old files under the names given (each pushed to `set_aside`
    /// once renamed). On failure the old files are still in place.
    fn compact_at_open(
        &mut self,
        snapshot_aside: Option<PathBuf>,
        journal_aside: Option<PathBuf>,
        set_aside: &mut Vec<PathBuf>,
    ) -> Result<(), JournalError> {
        write_snapshot(&self.dir, &self.persisted, snapshot_aside.as_deref())?;
        if let Some(aside) = snapshot_aside {
            set_aside.push(aside);
        }
        let path = self.dir.join(JOURNAL_FILE);
        if let Some(aside) = journal_aside {
            fs::rename(&path, &aside).map_err(io_error(&aside))?;
            set_aside.push(aside);
        }
        let file = File::create(&path).map_err(io_error(&path))?;
        file.sync_all().map_err(io_error(&path))?;
        sync_dir(&self.dir)?;
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .map_err(io_error(&path))?;
        self.file = Some(file);
        Ok(())
    }

    /// Why the journal is read-only, if it is: the compaction at start
    /// failed (a full disk, say), the old files were left as they were,
    /// and every write is refused with [`JournalError::ReadOnly`].
    pub fn read_only(&self) -> Option<&JournalError> {
        self.read_only.as_ref()
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
    /// that fails). [`JournalError::ReadOnly`] when [`Self::read_only`].
    pub fn append(&mut self, batch: &WriteBatch) -> Result<(), JournalError> {
        if self.broken {
            return Err(JournalError::Broken);
        }
        let kept = retain::kept(batch);
        let batch = kept.as_ref().unwrap_or(batch);
        if batch.is_empty() {
            return Ok(());
        }
        let Some(file) = self.file.as_mut() else {
            return Err(JournalError::ReadOnly);
        };
        let seq = u64::try_from(self.records).map_or(u64::MAX, |n| n.saturating_add(1));
        let line = state_file::record_line(seq, &batch.to_line());
        let path = self.dir.join(JOURNAL_FILE);
        let written = file
            .write_all(line.as_bytes())
            .and_then(|()| file.sync_data());
        if let Err(err) = written {
            if file
                .set_len(self.len)
                .and_then(|()| file.sync_data())
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
        write_snapshot(&self.dir, &self.persisted, None)?;
        let path = self.dir.join(JOURNAL_FILE);
        let Some(file) = self.file.as_mut() else {
            return Err(JournalError::ReadOnly);
        };
        // Appends go to the end whatever the cursor, so truncating the
        // open append handle is enough.
        file.set_len(0)
            .and_then(|()| file.sync_all())
            .map_err(io_error(&path))?;
        self.len = 0;
        self.records = 0;
        Ok(())
    }
}

/// Writes `values` as the new snapshot: temporary file, sync, rename (the
/// old snapshot first renamed to `old_aside`, if given), sync the
/// directory. On failure the old snapshot is untouched and the temporary
/// file removed, so a full disk gets its space back.
fn write_snapshot(
    dir: &Path,
    values: &BTreeMap<Slot, i32>,
    old_aside: Option<&Path>,
) -> Result<(), JournalError> {
    let tmp = dir.join(format!("{SNAPSHOT_FILE}.tmp"));
    let text = state_file::snapshot_text(values);
    let written = File::create(&tmp).and_then(|mut file| {
        file.write_all(text.as_bytes())
            .and_then(|()| file.sync_all())
    });
    if let Err(err) = written {
        let _ = fs::remove_file(&tmp);
        return Err(io_error(&tmp)(err));
    }
    let target = dir.join(SNAPSHOT_FILE);
    if let Some(aside) = old_aside {
        fs::rename(&target, aside).map_err(io_error(aside))?;
    }
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
        fs::write(dir.join(SNAPSHOT_FILE), "# ecam serve snapshot\n").unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D1 1\nD2 2\nD3 3").unwrap();
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(
            recovery,
            Recovery {
                replayed: 2,
                torn_tail: true,
                old_format: true,
                ..Recovery::default()
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
        fs::write(dir.join(SNAPSHOT_FILE), "# ecam serve snapshot\n").unwrap();
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
            state_file::record_line(1, "D7999 1")
        );
        fs::remove_dir_all(&dir).unwrap();
    }
}
