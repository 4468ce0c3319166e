//! What the operator hears about a state directory at start: what opening
//! it dropped, set aside or rewrote, whether it is read-only, and what the
//! restore gave back. Text only; the binary logs it.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use crate::{Journal, Recovery, Shared, Slot};

/// How loud a [`Notice`] is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NoticeLevel {
    /// Worth knowing.
    Info,
    /// Something was dropped, skipped or overridden.
    Warn,
    /// Writes will be refused.
    Error,
}

/// One line for the operator.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Notice {
    /// How loud.
    pub level: NoticeLevel,
    /// The line.
    pub text: String,
}

fn notice(level: NoticeLevel, text: String) -> Notice {
    Notice { level, text }
}

/// Longest list of device names one line gives.
const NAMES_SHOWN: usize = 32;

/// `M8145, D8140, … and 3 more`.
fn names(slots: impl ExactSizeIterator<Item = Slot>) -> String {
    let total = slots.len();
    let mut text: Vec<String> = slots
        .take(NAMES_SHOWN)
        .map(|s| s.device().to_string())
        .collect();
    if total > NAMES_SHOWN {
        text.push(format!("and {} more", total - NAMES_SHOWN));
    }
    text.join(", ")
}

/// What opening the state directory `dir` dropped, set aside or rewrote,
/// and whether it is read-only.
#[must_use]
pub fn open_notices(dir: &Path, recovery: &Recovery, journal: &Journal) -> Vec<Notice> {
    use NoticeLevel::{Error, Info, Warn};
    let dir = dir.display();
    let mut out = Vec::new();
    for dropped in &recovery.dropped {
        out.push(notice(
            Warn,
            format!("state {dir}: --recover-state: {dropped}"),
        ));
    }
    for aside in &recovery.set_aside {
        out.push(notice(
            Warn,
            format!(
                "state {dir}: --recover-state: damaged file kept as {}",
                aside.display()
            ),
        ));
    }
    match journal.read_only() {
        Some(err) => out.push(notice(
            Error,
            format!(
                "state {dir}: READ-ONLY: cannot compact the state files ({err}); \
                 they are left as they were and every write is refused until a restart \
                 with space to spare"
            ),
        )),
        None if recovery.old_format => out.push(notice(
            Info,
            format!(
                "state {dir}: state files without checksums (an older version's) \
                 loaded and rewritten with checksums"
            ),
        )),
        None => {}
    }
    out
}

/// What the state directory `dir` gave back once the first scan period
/// has run: special devices skipped, restored values the first scan
/// changed, and the counts (the last notice).
#[must_use]
pub fn restore_notices(
    shared: &Shared,
    dir: &Path,
    recovery: &Recovery,
    restored: &BTreeMap<Slot, i32>,
) -> Vec<Notice> {
    use NoticeLevel::{Info, Warn};
    let dir = dir.display();
    let mut out = Vec::new();
    let skipped = &recovery.skipped_special;
    if !skipped.is_empty() {
        out.push(notice(
            Warn,
            format!(
                "state {dir}: not restoring {}: special devices are the PLC's own, \
                 set up afresh at start (these records, kept by an older version, are now dropped)",
                names(skipped.iter().copied())
            ),
        ));
    }
    let overridden = shared.read(|devices| crate::overridden(restored, devices));
    for o in overridden.iter().take(NAMES_SHOWN) {
        out.push(notice(
            Warn,
            format!(
                "state {dir}: {} restored as {}, but it is {} after the first scan \
                 period (the program or the hardware sets it at start)",
                o.slot.device(),
                o.restored,
                o.now
            ),
        ));
    }
    if overridden.len() > NAMES_SHOWN {
        out.push(notice(
            Warn,
            format!(
                "state {dir}: and {} more restored values the first scan period changed",
                overridden.len() - NAMES_SHOWN
            ),
        ));
    }
    let mut summary = format!(
        "state {dir}: {} values restored ({} journal records replayed{})",
        restored.len(),
        recovery.replayed,
        if recovery.torn_tail {
            ", an unacknowledged torn last record dropped"
        } else {
            ""
        }
    );
    if !skipped.is_empty() {
        let _ = write!(
            summary,
            ", {} skipped (special devices, never restored)",
            skipped.len()
        );
    }
    if !recovery.dropped.is_empty() {
        let records: usize = recovery.dropped.iter().map(|d| d.records).sum();
        let _ = write!(
            summary,
            ", {records} damaged records dropped by --recover-state (listed above)"
        );
    }
    if !overridden.is_empty() {
        let _ = write!(
            summary,
            ", {} changed by the first scan period (listed above)",
            overridden.len()
        );
    }
    out.push(notice(Info, summary));
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_long_name_list_is_cut_with_a_count() {
        let slots: Vec<Slot> = (0..40u16)
            .map(|n| Slot::of(ecam_plc::Device::D(n)).unwrap())
            .collect();
        let text = names(slots.into_iter());
        assert!(text.ends_with("and 8 more"), "{text}");
        assert_eq!(text.matches(", ").count(), NAMES_SHOWN);
    }
}
