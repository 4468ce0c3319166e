//! The format of a state directory's two files, and how damage to them is
//! found.
//!
//! Each record (one request in the journal, up to 32 values in the
//! snapshot) is one line `@SEQ CRC RECORD`: its sequence number (1, 2, 3…
//! in each file), the CRC-32 of `SEQ RECORD` as 8 hex digits, and the
//! record as [`WriteBatch::to_line`] writes it. The checksum finds a
//! changed character; the sequence a removed, repeated or moved record.
//! The snapshot starts with [`SNAPSHOT_HEADER`] and ends with
//! `end COUNT CRC`, the number of records and the CRC-32 of every byte
//! before the marker, so a snapshot cut short or emptied is found too.
//!
//! Files written before checksums existed (no `@` records, no end marker)
//! are read as they always were, once: the compaction at start rewrites
//! them in this format.

use core::fmt;
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use crate::journal::JournalError;
use crate::retain;
use crate::write::{LineError, Slot, WriteBatch};

/// First line of a snapshot in the checksummed format.
pub const SNAPSHOT_HEADER: &str =
    "# ecam serve snapshot v2: @SEQ CRC32 RECORD lines, then end COUNT CRC32";

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

/// Damage that `--recover-state` stepped over, and what it cost.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Dropped {
    /// The file.
    pub path: PathBuf,
    /// 1-based line.
    pub line: usize,
    /// What is wrong there.
    pub damage: Damage,
    /// Records not restored because of it (this one and, in the journal,
    /// every later one; 0 when what is lost cannot be counted, as the end
    /// of a snapshot cut short).
    pub records: usize,
}

impl fmt::Display for Dropped {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}: {}: ",
            self.path.display(),
            self.line,
            self.damage
        )?;
        match (self.records, &self.damage) {
            (0, Damage::Missing | Damage::Empty) => f.write_str("whatever it held is lost"),
            (0, Damage::CutShort | Damage::NoEndMarker) => f.write_str("whatever followed is lost"),
            (0, Damage::NotText { .. }) => {
                f.write_str("the records before it are kept; whatever it held is lost")
            }
            (0, _) => f.write_str("the records that check out are kept"),
            (1, _) => f.write_str("1 record dropped"),
            (n, _) => write!(f, "{n} records dropped (this one and all after it)"),
        }
    }
}

fn checksum(seq: u64, record: &str) -> u32 {
    let mut hasher = crc32fast::Hasher::new();
    hasher.update(seq.to_string().as_bytes());
    hasher.update(b" ");
    hasher.update(record.as_bytes());
    hasher.finalize()
}

/// Record `seq` holding `record`, with its newline.
pub(crate) fn record_line(seq: u64, record: &str) -> String {
    format!("@{seq} {:08x} {record}\n", checksum(seq, record))
}

fn digits(text: &str) -> bool {
    !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit())
}

fn hex8(text: &str) -> Option<u32> {
    (text.len() == 8 && text.bytes().all(|b| b.is_ascii_hexdigit()))
        .then(|| u32::from_str_radix(text, 16).ok())
        .flatten()
}

/// The sequence number and record of a line, checked.
fn parse_record(line: &str) -> Result<(u64, &str), Damage> {
    let rest = line.strip_prefix('@').ok_or(Damage::NotARecord)?;
    let (seq, rest) = rest.split_once(' ').ok_or(Damage::NotARecord)?;
    let (crc, record) = rest.split_once(' ').ok_or(Damage::NotARecord)?;
    let seq: u64 = digits(seq)
        .then(|| seq.parse().ok())
        .flatten()
        .ok_or(Damage::NotARecord)?;
    let crc = hex8(crc).ok_or(Damage::NotARecord)?;
    if checksum(seq, record) == crc {
        Ok((seq, record))
    } else {
        Err(Damage::ChecksumMismatch)
    }
}

/// The text of a snapshot holding `values`.
pub(crate) fn snapshot_text(values: &BTreeMap<Slot, i32>) -> String {
    let mut text = format!("{SNAPSHOT_HEADER}\n");
    let entries: Vec<(Slot, i32)> = values.iter().map(|(&s, &v)| (s, v)).collect();
    let mut count = 0;
    // 32 values a line keeps the file readable.
    for chunk in entries.chunks(32) {
        let mut batch = WriteBatch::new();
        for &(slot, value) in chunk {
            batch.slot(slot, value);
        }
        count += 1;
        text.push_str(&record_line(count, &batch.to_line()));
    }
    let crc = crc32fast::hash(text.as_bytes());
    text.push_str(&format!("end {count} {crc:08x}\n"));
    text
}

/// The values read so far, and what to do on damage.
#[derive(Debug, Default)]
pub(crate) struct Replay {
    /// Kept values, last write winning.
    pub values: BTreeMap<Slot, i32>,
    /// Special devices found and left out.
    pub skipped: BTreeSet<Slot>,
    /// Step over damage (recording it here) rather than stop.
    pub recover: bool,
    /// Damage stepped over.
    pub dropped: Vec<Dropped>,
}

impl Replay {
    fn apply(&mut self, batch: &WriteBatch) {
        for &(slot, value) in batch.writes() {
            if retain::is_kept(slot) {
                self.values.insert(slot, value);
            } else {
                self.skipped.insert(slot);
            }
        }
    }

    /// Stops with `damage`, or notes it when recovering.
    pub(crate) fn damage(
        &mut self,
        path: &Path,
        line: usize,
        damage: Damage,
        records: usize,
    ) -> Result<(), JournalError> {
        if self.recover {
            self.dropped.push(Dropped {
                path: path.to_path_buf(),
                line,
                damage,
                records,
            });
            Ok(())
        } else {
            Err(JournalError::Corrupt {
                path: path.to_path_buf(),
                line,
                damage,
            })
        }
    }
}

/// Which format a file was in.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    /// With checksums (or empty).
    Checked,
    /// Written before checksums existed.
    Old,
}

/// Reads a snapshot's `text` (from `path`) into `replay`.
pub(crate) fn read_snapshot(
    text: &str,
    path: &Path,
    replay: &mut Replay,
) -> Result<Format, JournalError> {
    if text.is_empty() {
        replay.damage(path, 1, Damage::Empty, 0)?;
        return Ok(Format::Checked);
    }
    let pieces: Vec<&str> = text.split_inclusive('\n').collect();
    let first = pieces.first().map_or("", |p| p.trim_end_matches('\n'));
    let checked = first == SNAPSHOT_HEADER
        || pieces
            .iter()
            .any(|p| p.starts_with('@') || p.starts_with("end "));
    if !checked {
        read_old_snapshot(&pieces, path, replay)?;
        return Ok(Format::Old);
    }
    if first != SNAPSHOT_HEADER {
        replay.damage(path, 1, Damage::NoHeader, 0)?;
    }
    // Recovering, a damaged record already said the file is damaged: the
    // end marker's count and checksum would only say it again.
    let damaged_before = replay.dropped.len();
    let mut offset = pieces.first().map_or(0, |p| p.len());
    let mut expected = 1;
    let mut count = 0;
    let mut ended = false;
    for (k, piece) in pieces.iter().enumerate().skip(1) {
        let number = k + 1;
        let Some(line) = piece.strip_suffix('\n') else {
            replay.damage(path, number, Damage::CutShort, 0)?;
            return Ok(Format::Checked);
        };
        if ended {
            replay.damage(path, number, Damage::AfterEnd, 0)?;
            return Ok(Format::Checked);
        }
        if let Some(marker) = line.strip_prefix("end ") {
            ended = true;
            let parsed = marker
                .split_once(' ')
                .filter(|(n, _)| digits(n))
                .and_then(|(n, crc)| Some((n.parse::<u64>().ok()?, hex8(crc)?)));
            let damage = match parsed {
                None => Some(Damage::BadEndMarker),
                Some((marker, _)) if marker != count => Some(Damage::EndCount {
                    marker,
                    found: count,
                }),
                Some((_, crc)) => text
                    .get(..offset)
                    .filter(|before| crc32fast::hash(before.as_bytes()) == crc)
                    .is_none()
                    .then_some(Damage::FileChecksumMismatch),
            };
            let repeated = replay.dropped.len() > damaged_before
                && !matches!(damage, Some(Damage::BadEndMarker));
            if let Some(damage) = damage.filter(|_| !repeated) {
                replay.damage(path, number, damage, 0)?;
            }
            continue;
        }
        offset += piece.len();
        count += 1;
        match parse_record(line) {
            Ok((seq, record)) => {
                if seq != expected {
                    // Recovering, the record itself checks out: keep it
                    // (snapshot records are independent of each other).
                    replay.damage(
                        path,
                        number,
                        Damage::Sequence {
                            expected,
                            found: seq,
                        },
                        0,
                    )?;
                }
                expected = seq.saturating_add(1);
                match WriteBatch::parse_line(record) {
                    Ok(batch) => replay.apply(&batch),
                    Err(err) => replay.damage(path, number, Damage::Unreadable(err), 1)?,
                }
            }
            Err(damage) => {
                expected = expected.saturating_add(1);
                replay.damage(path, number, damage, 1)?;
            }
        }
    }
    if !ended {
        replay.damage(path, pieces.len() + 1, Damage::NoEndMarker, 0)?;
    }
    Ok(Format::Checked)
}

/// A snapshot written before checksums: a `#` header, then plain records.
fn read_old_snapshot(
    pieces: &[&str],
    path: &Path,
    replay: &mut Replay,
) -> Result<(), JournalError> {
    if !pieces.first().is_some_and(|p| p.starts_with('#')) {
        replay.damage(path, 1, Damage::NoHeader, 0)?;
    }
    for (k, piece) in pieces.iter().enumerate() {
        let Some(line) = piece.strip_suffix('\n') else {
            // Old snapshots were renamed into place whole, always ending in
            // a newline: this one was cut short, maybe inside a number.
            return replay.damage(path, k + 1, Damage::CutShort, 0);
        };
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        match WriteBatch::parse_line(line) {
            Ok(batch) => replay.apply(&batch),
            Err(err) => replay.damage(path, k + 1, Damage::Unreadable(err), 1)?,
        }
    }
    Ok(())
}

/// What [`read_journal`] found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct JournalRead {
    /// Records replayed.
    pub records: usize,
    /// Whether a torn last line was dropped.
    pub torn: bool,
    /// The journal's format.
    pub format: Format,
}

/// Replays a journal's `text` (from `path`) into `replay`. A last line
/// without its newline was never acknowledged and is dropped when it is
/// the beginning of a record, printable text; anything else there (the
/// zeroes of a file whose blocks were lost) is damage. Recovering, the
/// first damaged record and every later one are dropped, so what is
/// restored is a state the server really was in.
pub(crate) fn read_journal(
    text: &str,
    path: &Path,
    replay: &mut Replay,
) -> Result<JournalRead, JournalError> {
    let pieces: Vec<&str> = text.split_inclusive('\n').collect();
    let format = if pieces
        .iter()
        .find(|p| !p.trim().is_empty())
        .is_none_or(|p| p.starts_with('@'))
    {
        Format::Checked
    } else {
        Format::Old
    };
    let complete = pieces.iter().filter(|p| p.ends_with('\n')).count();
    let mut read = JournalRead {
        records: 0,
        torn: false,
        format,
    };
    let mut expected = 1;
    for (k, piece) in pieces.iter().enumerate() {
        let Some(line) = piece.strip_suffix('\n') else {
            if piece.chars().all(|c| c == ' ' || c.is_ascii_graphic()) {
                read.torn = true;
            } else {
                let damage = Damage::NotText { bytes: piece.len() };
                replay.damage(path, k + 1, damage, 0)?;
            }
            break;
        };
        let damage = match format {
            Format::Old => {
                let line = line.trim();
                if line.is_empty() || line.starts_with('#') {
                    continue;
                }
                match WriteBatch::parse_line(line) {
                    Ok(batch) => {
                        replay.apply(&batch);
                        read.records += 1;
                        continue;
                    }
                    Err(err) => Damage::Unreadable(err),
                }
            }
            Format::Checked => match parse_record(line) {
                Ok((seq, record)) if seq == expected => match WriteBatch::parse_line(record) {
                    Ok(batch) => {
                        replay.apply(&batch);
                        read.records += 1;
                        expected += 1;
                        continue;
                    }
                    Err(err) => Damage::Unreadable(err),
                },
                Ok((found, _)) => Damage::Sequence { expected, found },
                Err(damage) => damage,
            },
        };
        replay.damage(path, k + 1, damage, complete - k)?;
        break;
    }
    Ok(read)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use std::fs;
    use std::sync::atomic::{AtomicUsize, Ordering};

    use proptest::prelude::*;

    use super::*;
    use crate::journal::{
        DAMAGED_SUFFIX, JOURNAL_FILE, Journal, JournalError, OnDamage, Recovery, SNAPSHOT_FILE,
    };

    /// A snapshot of two records (D0–D39) and a journal of three.
    fn snapshot() -> String {
        snapshot_text(&(0..40).map(|n| (Slot::D(n), i32::from(n) + 1)).collect())
    }

    const JOURNAL: [&str; 3] = ["D0 100", "D1 101 102", "M5 1"];

    fn journal() -> String {
        (1..).zip(JOURNAL).map(|(n, r)| record_line(n, r)).collect()
    }

    /// The values after the snapshot and the first `records` journal records.
    fn state_after(records: usize) -> BTreeMap<Slot, i32> {
        let mut values: BTreeMap<Slot, i32> =
            (0..40).map(|n| (Slot::D(n), i32::from(n) + 1)).collect();
        for record in &JOURNAL[..records] {
            for &(slot, value) in WriteBatch::parse_line(record).unwrap().writes() {
                values.insert(slot, value);
            }
        }
        values
    }

    /// Opens a state directory holding `snapshot` and `journal` (written as
    /// bytes: damage need not be text), then removes it.
    fn open(
        snapshot: &[u8],
        journal: &[u8],
        on_damage: OnDamage,
    ) -> Result<(BTreeMap<Slot, i32>, Recovery), JournalError> {
        static NEXT: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "ecam-state-file-{}-{}",
            std::process::id(),
            NEXT.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join(SNAPSHOT_FILE), snapshot).unwrap();
        fs::write(dir.join(JOURNAL_FILE), journal).unwrap();
        let opened = Journal::open_with(&dir, on_damage).map(|(j, r)| (j.persisted().clone(), r));
        fs::remove_dir_all(&dir).unwrap();
        opened
    }

    fn refused(snapshot: &str, journal: &str) -> (String, usize, Damage) {
        match open(snapshot.as_bytes(), journal.as_bytes(), OnDamage::Refuse) {
            Err(JournalError::Corrupt { path, line, damage }) => (
                path.file_name().unwrap().to_string_lossy().into_owned(),
                line,
                damage,
            ),
            other => panic!("not refused: {other:?}\n{snapshot}\n{journal}"),
        }
    }

    fn lines(text: &str) -> Vec<&str> {
        text.split_inclusive('\n').collect()
    }

    #[test]
    fn the_examples_of_docs_modbus_md_check_out() {
        assert_eq!(record_line(1, "D100 3183"), "@1 0587aff6 D100 3183\n");
        let values = BTreeMap::from([(Slot::D(1), 1), (Slot::D(100), 5)]);
        assert_eq!(
            snapshot_text(&values),
            format!("{SNAPSHOT_HEADER}\n@1 52072eaf D1 1;D100 5\nend 1 c1a9c447\n")
        );
    }

    #[test]
    fn undamaged_files_restore_everything() {
        let (values, recovery) = open(
            snapshot().as_bytes(),
            journal().as_bytes(),
            OnDamage::Refuse,
        )
        .unwrap();
        assert_eq!(values, state_after(3));
        assert_eq!(recovery.replayed, 3);
        assert!(!recovery.old_format && recovery.dropped.is_empty());
    }

    #[test]
    fn a_snapshot_cut_at_any_byte_is_refused() {
        let snapshot = snapshot();
        for cut in 0..snapshot.len() {
            let (file, _, damage) = refused(&snapshot[..cut], "");
            assert_eq!(file, SNAPSHOT_FILE, "cut at {cut}: {damage}");
        }
    }

    #[test]
    fn a_journal_cut_at_any_byte_restores_the_records_before_the_cut() {
        let journal = journal();
        for cut in 0..=journal.len() {
            let (values, recovery) = open(
                snapshot().as_bytes(),
                &journal.as_bytes()[..cut],
                OnDamage::Refuse,
            )
            .unwrap();
            let whole = journal[..cut].matches('\n').count();
            assert_eq!(values, state_after(whole), "cut at {cut}");
            assert_eq!(
                recovery.torn_tail,
                !journal[..cut].ends_with('\n') && cut > 0
            );
        }
    }

    #[test]
    fn a_zeroed_journal_or_a_zeroed_tail_is_damage_not_a_torn_record() {
        let journal = journal();
        let zeroed = vec![0u8; journal.len()];
        let mut tail = journal.as_bytes()[..lines(&journal)[0].len()].to_vec();
        tail.extend_from_slice(&[0u8; 4096]);
        let mut junk = journal.as_bytes().to_vec();
        junk.extend_from_slice(&[0x40, 0x31, 0xFF, 0xFE]);
        for (bytes, line) in [(zeroed, 1), (tail, 2), (junk, 4)] {
            match open(snapshot().as_bytes(), &bytes, OnDamage::Refuse) {
                Err(JournalError::Corrupt {
                    line: at,
                    damage: Damage::NotText { .. },
                    ..
                }) => assert_eq!(at, line),
                other => panic!("not refused: {other:?}"),
            }
            let (values, recovery) =
                open(snapshot().as_bytes(), &bytes, OnDamage::Recover).unwrap();
            assert_eq!(values, state_after(line - 1));
            assert!(!recovery.torn_tail);
            assert_eq!(recovery.dropped.len(), 1);
            let said = recovery.dropped[0].to_string();
            assert!(said.contains(&format!("journal.log:{line}: ")), "{said}");
            assert!(said.contains("zeroed or overwritten"), "{said}");
            assert_eq!(recovery.set_aside.len(), 1, "kept as journal.log.damaged");
        }
        // A torn tail of text is still an unacknowledged write.
        let mut torn = journal.into_bytes();
        torn.extend_from_slice(b"@4 0123");
        let (values, recovery) = open(snapshot().as_bytes(), &torn, OnDamage::Refuse).unwrap();
        assert_eq!(values, state_after(3));
        assert!(recovery.torn_tail);
    }

    #[test]
    fn a_changed_digit_anywhere_is_refused() {
        for (text, in_journal) in [(snapshot(), false), (journal(), true)] {
            for (at, byte) in text.bytes().enumerate().filter(|(_, b)| b.is_ascii_digit()) {
                let mut damaged = text.clone().into_bytes();
                damaged[at] = if byte == b'9' { b'0' } else { byte + 1 };
                let damaged = String::from_utf8(damaged).unwrap();
                let (file, line, damage) = if in_journal {
                    refused(&snapshot(), &damaged)
                } else {
                    refused(&damaged, &journal())
                };
                let expected = if in_journal {
                    JOURNAL_FILE
                } else {
                    SNAPSHOT_FILE
                };
                assert_eq!(file, expected, "{damage}");
                assert_eq!(
                    line,
                    text[..at].matches('\n').count() + 1,
                    "{damage} at {at}"
                );
            }
        }
    }

    #[test]
    fn a_removed_record_is_refused_but_the_last_journal_one() {
        let snapshot = snapshot();
        for remove in 1..lines(&snapshot).len() {
            let mut kept = lines(&snapshot);
            kept.remove(remove);
            let (file, line, damage) = refused(&kept.concat(), &journal());
            assert_eq!(
                (file.as_str(), line),
                (SNAPSHOT_FILE, remove + 1),
                "{damage}"
            );
        }
        let (file, line, damage) = refused(&snapshot, &lines(&journal())[1..].concat());
        assert_eq!((file.as_str(), line), (JOURNAL_FILE, 1));
        assert_eq!(
            damage,
            Damage::Sequence {
                expected: 1,
                found: 2
            }
        );
        let whole = journal();
        let mut kept = lines(&whole);
        kept.remove(1);
        assert_eq!(refused(&snapshot, &kept.concat()).1, 2);
        // A last record removed is a write never made: nothing tells them apart.
        let (values, _) = open(
            snapshot.as_bytes(),
            lines(&journal())[..2].concat().as_bytes(),
            OnDamage::Refuse,
        )
        .unwrap();
        assert_eq!(values, state_after(2));
    }

    #[test]
    fn a_repeated_or_moved_record_is_refused() {
        for (text, in_journal) in [(snapshot(), false), (journal(), true)] {
            let original = lines(&text);
            let records = if in_journal {
                0..original.len()
            } else {
                1..original.len() - 1
            };
            for k in records.clone() {
                let mut repeated = original.clone();
                repeated.insert(k, original[k]);
                let mut variants = vec![(repeated.concat(), k + 2)];
                if k + 1 < records.end {
                    let mut swapped = original.clone();
                    swapped.swap(k, k + 1);
                    variants.push((swapped.concat(), k + 1));
                }
                for (damaged, line) in variants {
                    let (file, at, damage) = if in_journal {
                        refused(&snapshot(), &damaged)
                    } else {
                        refused(&damaged, &journal())
                    };
                    assert_eq!(
                        file,
                        if in_journal {
                            JOURNAL_FILE
                        } else {
                            SNAPSHOT_FILE
                        }
                    );
                    assert_eq!(at, line, "{damage}\n{damaged}");
                }
            }
        }
    }

    #[test]
    fn empty_garbage_and_endless_snapshots_are_refused() {
        assert_eq!(refused("", ""), (SNAPSHOT_FILE.into(), 1, Damage::Empty));
        assert_eq!(refused("PK\u{3}\u{4} not a snapshot\nat all\n", "").1, 1);
        let snapshot = snapshot();
        let endless: String = lines(&snapshot)[..3].concat();
        assert_eq!(
            refused(&endless, ""),
            (SNAPSHOT_FILE.into(), 4, Damage::NoEndMarker)
        );
        let after = format!("{snapshot}D7 7\n");
        assert_eq!(
            refused(&after, ""),
            (SNAPSHOT_FILE.into(), 5, Damage::AfterEnd)
        );
        let garbage_journal = "\u{0}\u{1}garbage\nmore garbage\n";
        assert_eq!(refused(&snapshot, garbage_journal).0, JOURNAL_FILE);
    }

    #[test]
    fn a_deleted_snapshot_is_refused() {
        let dir =
            std::env::temp_dir().join(format!("ecam-state-file-{}-deleted", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        fs::write(dir.join(JOURNAL_FILE), journal()).unwrap();
        let err = Journal::open(&dir).unwrap_err();
        assert!(
            matches!(
                &err,
                JournalError::Corrupt {
                    line: 1,
                    damage: Damage::Missing,
                    ..
                }
            ),
            "{err}"
        );
        assert!(
            err.to_string()
                .ends_with("snapshot.txt:1: missing, though the journal is there")
        );
        let (journal, recovery) = Journal::open_with(&dir, OnDamage::Recover).unwrap();
        assert_eq!(journal.persisted().len(), 4);
        assert!(journal.read_only().is_none());
        assert_eq!(recovery.dropped.len(), 1);
        assert!(recovery.set_aside.is_empty());
        drop(journal);
        assert!(Journal::open(&dir).is_ok());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_changed_header_is_refused() {
        let damaged = snapshot().replacen("snapshot v2", "snapshot v3", 1);
        assert_eq!(refused(&damaged, "").2, Damage::NoHeader);
    }

    #[test]
    fn an_old_snapshot_cut_inside_a_number_is_refused() {
        let old = "# ecam serve snapshot: the last kept value of each D, M, X and C device\nD100 12345;M3 1\n";
        let (values, recovery) = open(old.as_bytes(), b"D1 7\n", OnDamage::Refuse).unwrap();
        assert_eq!(values.len(), 3);
        assert!(recovery.old_format);
        let cut = &old[..old.len() - 9];
        assert_eq!(refused(cut, "").2, Damage::CutShort);
    }

    #[test]
    fn old_files_load_once_and_are_rewritten_with_checksums() {
        let dir = std::env::temp_dir().join(format!("ecam-state-file-{}-old", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        fs::write(
            dir.join(SNAPSHOT_FILE),
            "# ecam serve snapshot: the last kept value of each D, M, X and C device\nD100 5 6;M3 1\n",
        )
        .unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D100 7\nX17 1\n").unwrap();
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert!(recovery.old_format);
        assert_eq!(recovery.replayed, 2);
        let values = journal.persisted().clone();
        assert_eq!(values.get(&Slot::D(100)), Some(&7));
        drop(journal);
        let snapshot = fs::read_to_string(dir.join(SNAPSHOT_FILE)).unwrap();
        assert!(snapshot.starts_with(SNAPSHOT_HEADER), "{snapshot}");
        assert_eq!(fs::read_to_string(dir.join(JOURNAL_FILE)).unwrap(), "");
        let (journal, recovery) = Journal::open(&dir).unwrap();
        assert!(!recovery.old_format);
        assert_eq!(journal.persisted(), &values);
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn recovering_keeps_the_journal_before_its_first_damage_and_sets_the_files_aside() {
        let dir =
            std::env::temp_dir().join(format!("ecam-state-file-{}-recover", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let journal = journal().replacen("101", "901", 1);
        fs::write(dir.join(SNAPSHOT_FILE), snapshot()).unwrap();
        fs::write(dir.join(JOURNAL_FILE), &journal).unwrap();
        assert!(Journal::open(&dir).is_err());
        let (opened, recovery) = Journal::open_with(&dir, OnDamage::Recover).unwrap();
        assert_eq!(opened.persisted(), &state_after(1));
        assert_eq!(recovery.dropped.len(), 1);
        let dropped = &recovery.dropped[0];
        assert_eq!(
            (dropped.line, &dropped.damage, dropped.records),
            (2, &Damage::ChecksumMismatch, 2)
        );
        let message = dropped.to_string();
        assert!(
            message.contains("journal.log:2: checksum mismatch: 2 records dropped"),
            "{message}"
        );
        let aside = dir.join(format!("{JOURNAL_FILE}{DAMAGED_SUFFIX}"));
        assert_eq!(recovery.set_aside, std::slice::from_ref(&aside));
        assert_eq!(fs::read_to_string(&aside).unwrap(), journal);
        drop(opened);
        // What was recovered is consistent again: a plain start takes it.
        let (again, recovery) = Journal::open(&dir).unwrap();
        assert_eq!(again.persisted(), &state_after(1));
        assert!(recovery.dropped.is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn recovering_a_cut_snapshot_keeps_its_whole_records() {
        let snapshot = snapshot();
        let cut = &snapshot[..lines(&snapshot)[..2].concat().len() + 10];
        let (values, recovery) =
            open(cut.as_bytes(), journal().as_bytes(), OnDamage::Recover).unwrap();
        let first_record: BTreeMap<Slot, i32> =
            (0..32).map(|n| (Slot::D(n), i32::from(n) + 1)).collect();
        let mut expected = first_record;
        for record in JOURNAL {
            for &(slot, value) in WriteBatch::parse_line(record).unwrap().writes() {
                expected.insert(slot, value);
            }
        }
        assert_eq!(values, expected);
        assert_eq!(recovery.dropped[0].damage, Damage::CutShort);
        assert_eq!(recovery.dropped[0].line, 3);
        assert_eq!(recovery.set_aside.len(), 1);
    }

    #[test]
    fn a_full_disk_at_start_leaves_the_files_and_opens_read_only() {
        let dir = std::env::temp_dir().join(format!("ecam-state-file-{}-full", std::process::id()));
        let _ = fs::remove_dir_all(&dir);
        fs::create_dir_all(&dir).unwrap();
        let old = "# ecam serve snapshot: old\nD100 5\n";
        fs::write(dir.join(SNAPSHOT_FILE), old).unwrap();
        fs::write(dir.join(JOURNAL_FILE), "D100 6\n").unwrap();
        // The temporary snapshot cannot be created, as on a full disk.
        fs::create_dir(dir.join(format!("{SNAPSHOT_FILE}.tmp"))).unwrap();
        let (mut journal, recovery) = Journal::open(&dir).unwrap();
        assert!(recovery.old_format);
        assert!(matches!(journal.read_only(), Some(JournalError::Io { .. })));
        assert_eq!(journal.persisted().get(&Slot::D(100)), Some(&6));
        let mut batch = WriteBatch::new();
        batch.word(100, 7);
        assert!(matches!(
            journal.append(&batch),
            Err(JournalError::ReadOnly)
        ));
        assert_eq!(journal.persisted().get(&Slot::D(100)), Some(&6));
        drop(journal);
        assert_eq!(fs::read_to_string(dir.join(SNAPSHOT_FILE)).unwrap(), old);
        assert_eq!(
            fs::read_to_string(dir.join(JOURNAL_FILE)).unwrap(),
            "D100 6\n"
        );
        // Space again: the next start compacts.
        fs::remove_dir(dir.join(format!("{SNAPSHOT_FILE}.tmp"))).unwrap();
        let (journal, _) = Journal::open(&dir).unwrap();
        assert!(journal.read_only().is_none());
        assert_eq!(journal.persisted().get(&Slot::D(100)), Some(&6));
        fs::remove_dir_all(&dir).unwrap();
    }

    /// One kind of damage at a place given as a fraction of the file.
    #[derive(Clone, Debug)]
    enum Harm {
        Cut(f64),
        Byte(f64, u8),
        RemoveLine(f64),
        RepeatLine(f64),
        SwapLines(f64),
        InsertLine(f64, String),
    }

    fn harm(text: &str, harm: &Harm) -> Vec<u8> {
        let at = |f: f64, n: usize| ((f * n as f64) as usize).min(n.saturating_sub(1));
        let mut lines: Vec<Vec<u8>> = lines(text).iter().map(|l| l.as_bytes().to_vec()).collect();
        let n = lines.len();
        match harm {
            Harm::Cut(f) => return text.as_bytes()[..at(*f, text.len())].to_vec(),
            Harm::Byte(f, b) => {
                let mut bytes = text.as_bytes().to_vec();
                let k = at(*f, bytes.len());
                bytes[k] = *b;
                return bytes;
            }
            Harm::RemoveLine(f) => {
                lines.remove(at(*f, n));
            }
            Harm::RepeatLine(f) => {
                let k = at(*f, n);
                lines.insert(k, lines[k].clone());
            }
            Harm::SwapLines(f) => {
                let k = at(*f, n - 1);
                lines.swap(k, k + 1);
            }
            Harm::InsertLine(f, line) => lines.insert(at(*f, n), format!("{line}\n").into_bytes()),
        }
        lines.concat()
    }

    fn any_harm() -> impl Strategy<Value = Harm> {
        prop_oneof![
            (0.0..1.0f64).prop_map(Harm::Cut),
            (0.0..1.0f64, any::<u8>()).prop_map(|(f, b)| Harm::Byte(f, b)),
            (0.0..1.0f64).prop_map(Harm::RemoveLine),
            (0.0..1.0f64).prop_map(Harm::RepeatLine),
            (0.0..1.0f64).prop_map(Harm::SwapLines),
            (0.0..1.0f64, "[ -~]{0,20}").prop_map(|(f, l)| Harm::InsertLine(f, l)),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Whatever the damage: a damaged snapshot is refused; a damaged
        /// journal is refused or gives the state after some of its first
        /// records (a cut, or its last records removed, looks like writes
        /// never made); recovering always starts, and says what it dropped
        /// whenever a plain start refused.
        #[test]
        fn any_damage_is_refused_or_harmless(damage in any_harm(), in_journal in any::<bool>()) {
            let (snapshot, journal) = (snapshot(), journal());
            let (s, j) = if in_journal {
                (snapshot.clone().into_bytes(), harm(&journal, &damage))
            } else {
                (harm(&snapshot, &damage), journal.clone().into_bytes())
            };
            let unchanged = s == snapshot.as_bytes() && j == journal.as_bytes();
            match open(&s, &j, OnDamage::Refuse) {
                Ok((values, _)) if unchanged => prop_assert_eq!(values, state_after(3)),
                Ok((values, _)) => {
                    prop_assert!(in_journal, "damaged snapshot accepted: {:?}", String::from_utf8_lossy(&s));
                    prop_assert!((0..=3).any(|k| values == state_after(k)), "{:?}", String::from_utf8_lossy(&j));
                }
                Err(JournalError::Corrupt { .. }) => {
                    let (_, recovery) = open(&s, &j, OnDamage::Recover).unwrap();
                    prop_assert!(!recovery.dropped.is_empty());
                }
                Err(err) => prop_assert!(false, "{err}"),
            }
        }
    }
}
