//! What `--state` keeps, as a PLC with a battery would (the ranges are
//! [`ecam_plc::Retention`], the FX3U defaults):
//!
//! - **Special devices** (D8000–D8511, M8000–M8511) are the PLC's own: it
//!   sets them up at start (M8000, clocks, pulse counters) and acts on them
//!   (M8145 stops Y0's pulses). A client's write to one takes effect at
//!   once but is never kept: restored after a restart it would, say, keep
//!   Y0 stopped for ever with nothing saying why.
//! - **Ordinary devices written from outside** (any other D, M, X) keep
//!   their last acknowledged value, latched or not: the contract that an
//!   acknowledged write survives `kill -9` is what users' setpoint scripts
//!   rely on, and a value an HMI downloaded is the user's, not the scan's.
//! - **Latched devices the program writes** (D200–D7999, M500–M7679,
//!   C100–C199, C220–C255) are saved every [`SAVE_PERIOD`] and at a clean
//!   shutdown ([`LatchedImage`]), as a real FX keeps them through a power
//!   cut. Non-latched values the program computes start from zero again.
//!
//! A saved image is one ordinary journal record holding only the latched
//! devices whose value differs from what a restart would restore, so the
//! journal stays in the format older state directories have, and its order
//! (client writes and saved images interleaved) decides which value wins.

use std::collections::BTreeMap;
use std::time::Duration;

use ecam_plc::{C_COUNT, C_LATCHED, D_LATCHED, Device, Devices, M_LATCHED, Retention};

use crate::write::{Slot, WriteBatch};

/// How often the latched values the program wrote are saved: a crash loses
/// at most this much of the program's latched work (never a client write).
pub const SAVE_PERIOD: Duration = Duration::from_secs(1);

/// Whether a value of `slot` is kept across a restart at all.
pub fn is_kept(slot: Slot) -> bool {
    slot.device().retention() != Retention::Special
}

/// `batch` without the devices that are not kept, or `None` when every
/// device of it is kept (the common case, which then costs no copy).
pub(crate) fn kept(batch: &WriteBatch) -> Option<WriteBatch> {
    if batch.writes().iter().all(|&(slot, _)| is_kept(slot)) {
        return None;
    }
    let mut kept = WriteBatch::new();
    for &(slot, value) in batch.writes().iter().filter(|(s, _)| is_kept(*s)) {
        kept.slot(slot, value);
    }
    Some(kept)
}

/// The value `slot` holds in `devices`, as [`WriteBatch::writes`] gives it.
pub(crate) fn value_of(devices: &Devices, slot: Slot) -> i32 {
    // Slots only hold devices that exist, so these reads cannot fail.
    match slot {
        Slot::D(n) => devices.word(n).map(i32::from).unwrap_or(0),
        Slot::M(_) | Slot::X(_) => devices.bit(slot.device()).map(i32::from).unwrap_or(0),
        Slot::C(n) => devices.counter(n).unwrap_or(0),
    }
}

/// The latched devices' values, copied out of device memory so the scan
/// lock is held only for a copy of fixed size (no allocation after
/// [`LatchedImage::new`]); compared and written out after the lock is gone.
#[derive(Clone, Debug)]
pub struct LatchedImage {
    d: Vec<u16>,
    m: Vec<bool>,
    c: Vec<(u16, i32)>,
}

impl Default for LatchedImage {
    fn default() -> Self {
        Self::new()
    }
}

impl LatchedImage {
    /// An image of all-zero latched devices.
    pub fn new() -> Self {
        let counters: Vec<u16> = (0..C_COUNT)
            .filter(|&n| C_LATCHED.iter().any(|r| r.contains(&n)))
            .collect();
        Self {
            d: vec![0; D_LATCHED.len()],
            m: vec![false; M_LATCHED.len()],
            c: counters.into_iter().map(|n| (n, 0)).collect(),
        }
    }

    /// Copies the latched devices of `devices` into the image.
    pub fn capture(&mut self, devices: &Devices) {
        let words = devices.words();
        let (start, end) = (usize::from(D_LATCHED.start), usize::from(D_LATCHED.end));
        if let Some(latched) = words.get(start..end) {
            self.d.copy_from_slice(latched);
        }
        for (bit, n) in self.m.iter_mut().zip(M_LATCHED) {
            *bit = devices.bit(Device::M(n)).unwrap_or(false);
        }
        for (n, value) in &mut self.c {
            *value = devices.counter(*n).unwrap_or(0);
        }
    }

    /// The latched devices whose value in the image differs from what a
    /// restart would restore from `persisted` (a device with no kept value
    /// starts at zero), in device order.
    pub fn changes(&self, persisted: &BTreeMap<Slot, i32>) -> WriteBatch {
        let mut batch = WriteBatch::new();
        let mut note = |slot: Slot, value: i32| {
            if persisted.get(&slot).copied().unwrap_or(0) != value {
                batch.slot(slot, value);
            }
        };
        for (n, &word) in D_LATCHED.zip(&self.d) {
            note(Slot::D(n), i32::from(word as i16));
        }
        for (n, &bit) in M_LATCHED.zip(&self.m) {
            note(Slot::M(n), i32::from(bit));
        }
        for &(n, value) in &self.c {
            note(Slot::C(n), value);
        }
        batch
    }
}

/// A restored value the program's first scan changed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Overridden {
    /// The device.
    pub slot: Slot,
    /// The value restored.
    pub restored: i32,
    /// Its value after the first scan.
    pub now: i32,
}

/// The devices of `restored` whose value in `devices` (after the first scan)
/// is no longer the one restored: the program or the hardware set them at
/// start (a DECAM block, a counter reset on M8002).
pub fn overridden(restored: &BTreeMap<Slot, i32>, devices: &Devices) -> Vec<Overridden> {
    restored
        .iter()
        .filter_map(|(&slot, &value)| {
            let now = value_of(devices, slot);
            (now != value).then_some(Overridden {
                slot,
                restored: value,
                now,
            })
        })
        .collect()
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn special_devices_are_never_kept() {
        for slot in [Slot::M(8145), Slot::D(8140), Slot::M(8000), Slot::D(8511)] {
            assert!(!is_kept(slot), "{slot:?}");
        }
        for slot in [
            Slot::D(0),
            Slot::D(199),
            Slot::D(7999),
            Slot::M(0),
            Slot::M(7999),
            Slot::X(0),
            Slot::C(231),
        ] {
            assert!(is_kept(slot), "{slot:?}");
        }
    }

    #[test]
    fn kept_drops_only_special_devices() {
        let mut batch = WriteBatch::new();
        batch.word(100, 1);
        assert_eq!(kept(&batch), None);
        batch.bit(Device::M(8145), true).word(7999, 2).word(8000, 3);
        let mut expected = WriteBatch::new();
        expected.word(100, 1).word(7999, 2);
        assert_eq!(kept(&batch), Some(expected));
    }

    #[test]
    fn values_the_first_scan_changed_are_named() {
        let restored = BTreeMap::from([
            (Slot::D(2000), 5),
            (Slot::D(2001), 0),
            (Slot::C(231), 70000),
            (Slot::M(600), 1),
        ]);
        let mut devices = Devices::new();
        devices.set_word(2000, 5).unwrap();
        devices.set_m(600, true).unwrap();
        assert_eq!(
            overridden(&restored, &devices),
            [Overridden {
                slot: Slot::C(231),
                restored: 70000,
                now: 0
            }]
        );
    }

    #[test]
    fn the_image_holds_latched_devices_only() {
        let mut devices = Devices::new();
        for n in [0, 199, 200, 7999, 8000] {
            devices.set_word(n, -7).unwrap();
        }
        for n in [499, 500, 7679, 7680, 8145] {
            devices.set_m(n, true).unwrap();
        }
        for n in [99, 100, 219, 220, 255] {
            devices.set_counter(n, 70000).unwrap();
        }
        let mut image = LatchedImage::new();
        image.capture(&devices);
        let changes = image.changes(&BTreeMap::new());
        let mut expected = WriteBatch::new();
        expected
            .word(200, -7i16 as u16)
            .word(7999, -7i16 as u16)
            .bit(Device::M(500), true)
            .bit(Device::M(7679), true)
            .slot(Slot::C(100), 70000)
            .slot(Slot::C(220), 70000)
            .slot(Slot::C(255), 70000);
        assert_eq!(changes, expected);
        assert_eq!(value_of(&devices, Slot::C(100)), 70000 - 65536);
    }

    #[test]
    fn only_values_a_restart_would_get_wrong_are_saved() {
        let mut devices = Devices::new();
        devices.set_word(300, 5).unwrap();
        devices.set_word(301, 6).unwrap();
        devices.set_m(600, true).unwrap();
        let mut image = LatchedImage::new();
        image.capture(&devices);
        // D300 is already kept as 5; D400 was kept as 9 and is now 0 again.
        let persisted = BTreeMap::from([(Slot::D(300), 5), (Slot::D(400), 9)]);
        let mut expected = WriteBatch::new();
        expected.word(301, 6).word(400, 0).bit(Device::M(600), true);
        assert_eq!(image.changes(&persisted), expected);
    }
}
