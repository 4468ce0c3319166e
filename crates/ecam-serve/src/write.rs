//! A batch of device writes from one client request, and its one-line text
//! form (the record of the journal and the snapshot).
//!
//! Only D words and M/X bits are written from outside: Y outputs belong to
//! the program and counters to the hardware. Counter values appear only in
//! records of latched values the program itself wrote (see
//! [`LatchedImage`](crate::LatchedImage)). A line holds runs of consecutive devices, separated
//! by `;`, each run the first device's name and its values:
//! `D100 5 -3 7;M0 1 0;X17 1;C231 70000` (X/Y names in octal, words as
//! signed 16-bit values, bits 0/1, counters as their signed value). One
//! request is one line, so a batch is restored whole or not at all.

use core::fmt;
use std::fmt::Write as _;

use ecam_plc::{C_32BIT_FIRST, Device, Devices};

/// One device whose value can be kept: a data register, a writable bit, or
/// a counter's value.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Slot {
    /// `Dn`.
    D(u16),
    /// `Mn`.
    M(u16),
    /// `Xn` (index, not octal name).
    X(u16),
    /// `Cn`, the counter's current value.
    C(u16),
}

impl Slot {
    /// The slot for `device`, if it is a D, M, X or C that exists.
    pub fn of(device: Device) -> Option<Self> {
        let device = device.check().ok()?;
        match device {
            Device::D(n) => Some(Self::D(n)),
            Device::M(n) => Some(Self::M(n)),
            Device::X(n) => Some(Self::X(n)),
            Device::C(n) => Some(Self::C(n)),
            Device::Y(_) => None,
        }
    }

    /// The device.
    pub const fn device(self) -> Device {
        match self {
            Self::D(n) => Device::D(n),
            Self::M(n) => Device::M(n),
            Self::X(n) => Device::X(n),
            Self::C(n) => Device::C(n),
        }
    }

    /// The next slot of the same kind (`D7` → `D8`), if it exists.
    fn next(self) -> Option<Self> {
        let step = |n: u16| n.checked_add(1);
        Self::of(match self {
            Self::D(n) => Device::D(step(n)?),
            Self::M(n) => Device::M(step(n)?),
            Self::X(n) => Device::X(step(n)?),
            Self::C(n) => Device::C(step(n)?),
        })
    }

    const fn is_bit(self) -> bool {
        matches!(self, Self::M(_) | Self::X(_))
    }

    /// Whether `value` can be held by this slot: a 16-bit pattern for D
    /// (read back signed), 0/1 for bits, the counter's range for C.
    fn holds(self, value: i64) -> Option<i32> {
        let value = match self {
            Self::D(_) if (-32768..=65535).contains(&value) => i32::from(value as u16 as i16),
            Self::M(_) | Self::X(_) if value == 0 || value == 1 => value as i32,
            Self::C(n) if n < C_32BIT_FIRST => i32::from(i16::try_from(value).ok()?),
            Self::C(_) => i32::try_from(value).ok()?,
            _ => return None,
        };
        Some(value)
    }
}

/// Values written by one request, in request order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct WriteBatch {
    writes: Vec<(Slot, i32)>,
}

/// A journal or snapshot line that cannot be read.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LineError(String);

impl fmt::Display for LineError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LineError {}

impl WriteBatch {
    /// An empty batch.
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds `Dn = value` (raw 16-bit pattern).
    pub fn word(&mut self, n: u16, value: u16) -> &mut Self {
        self.writes.push((Slot::D(n), i32::from(value as i16)));
        self
    }

    /// Adds `slot = value` as [`Journal`](crate::Journal) keeps it
    /// (`value` as [`Self::writes`] gives it back; a counter value outside
    /// the counter's range, or a bit other than 0/1, is stored as the
    /// device would hold it).
    pub fn slot(&mut self, slot: Slot, value: i32) -> &mut Self {
        let value = match slot {
            Slot::D(_) => i32::from(value as i16),
            Slot::M(_) | Slot::X(_) => i32::from(value != 0),
            Slot::C(n) if n < C_32BIT_FIRST => i32::from(value as i16),
            Slot::C(_) => value,
        };
        self.writes.push((slot, value));
        self
    }

    /// Adds a bit (`device` must be M or X; others are ignored, so callers
    /// check writability first, as [`writable_coil_range`](crate::writable_coil_range) does).
    pub fn bit(&mut self, device: Device, on: bool) -> &mut Self {
        if let Some(slot) = Slot::of(device).filter(|s| s.is_bit()) {
            self.writes.push((slot, i32::from(on)));
        }
        self
    }

    /// True when the batch writes nothing.
    pub fn is_empty(&self) -> bool {
        self.writes.is_empty()
    }

    /// The writes, in order.
    pub fn writes(&self) -> &[(Slot, i32)] {
        &self.writes
    }

    /// The data-register writes, in order: `(n, value)` for each `Dn`.
    pub fn words(&self) -> impl Iterator<Item = (u16, i16)> + '_ {
        self.writes.iter().filter_map(|&(slot, value)| match slot {
            Slot::D(n) => Some((n, value as i16)),
            Slot::M(_) | Slot::X(_) | Slot::C(_) => None,
        })
    }

    /// Writes the batch into device memory, in order.
    pub fn apply(&self, devices: &mut Devices) {
        for &(slot, value) in &self.writes {
            // Slots only hold devices that exist, so these cannot fail.
            let _ = match slot {
                Slot::D(n) => devices.set_word(n, value as i16),
                Slot::M(_) | Slot::X(_) => devices.set_bit(slot.device(), value != 0),
                Slot::C(n) => devices.set_counter(n, value),
            };
        }
    }

    /// The one-line text form (without the newline).
    pub fn to_line(&self) -> String {
        let mut line = String::new();
        let mut expected: Option<Slot> = None;
        for &(slot, value) in &self.writes {
            if expected != Some(slot) {
                if !line.is_empty() {
                    line.push(';');
                }
                let _ = write!(line, "{}", slot.device());
            }
            let _ = write!(line, " {value}");
            expected = slot.next();
        }
        line
    }

    /// Reads a line written by [`Self::to_line`].
    ///
    /// # Errors
    /// A device that is not D, M, X or C, a run past the device's end, a
    /// word outside -32768..=65535, a bit other than 0/1 or a counter value
    /// outside the counter's range.
    pub fn parse_line(line: &str) -> Result<Self, LineError> {
        let mut batch = Self::new();
        for run in line.split(';') {
            let mut fields = run.split_whitespace();
            let name = fields.next().ok_or_else(|| {
                LineError(format!(
                    "empty run in `{line}`",
                    line = ecam_core::excerpt::excerpt(line)
                ))
            })?;
            let mut slot = Device::parse(name).ok().and_then(Slot::of).ok_or_else(|| {
                LineError(format!(
                    "`{name}` is not a D, M, X or C device",
                    name = ecam_core::excerpt::excerpt(name)
                ))
            })?;
            let mut values = fields.peekable();
            if values.peek().is_none() {
                return Err(LineError(format!(
                    "`{name}` has no value",
                    name = ecam_core::excerpt::excerpt(name)
                )));
            }
            while let Some(text) = values.next() {
                let value: i64 = text.parse().map_err(|_| {
                    LineError(format!(
                        "`{text}` is not a number",
                        text = ecam_core::excerpt::excerpt(text)
                    ))
                })?;
                let value = slot.holds(value).ok_or_else(|| {
                    LineError(format!(
                        "`{text}` is not a value for {}",
                        slot.device(),
                        text = ecam_core::excerpt::excerpt(text)
                    ))
                })?;
                batch.writes.push((slot, value));
                if values.peek().is_some() {
                    slot = slot.next().ok_or_else(|| {
                        LineError(format!(
                            "the run at `{name}` goes past the device's end",
                            name = ecam_core::excerpt::excerpt(name)
                        ))
                    })?;
                }
            }
        }
        Ok(batch)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn lines_group_consecutive_devices() {
        let mut batch = WriteBatch::new();
        batch
            .word(100, 5)
            .word(101, 0xFFFD)
            .word(102, 7)
            .bit(Device::M(0), true)
            .bit(Device::M(1), false)
            .bit(Device::X(15), true)
            .bit(Device::X(16), true)
            .bit(Device::Y(0), true);
        assert_eq!(batch.to_line(), "D100 5 -3 7;M0 1 0;X17 1 1");
        assert_eq!(WriteBatch::parse_line(&batch.to_line()), Ok(batch));
    }

    #[test]
    fn bad_lines_are_refused() {
        for line in [
            "",
            "D100",
            "Y7 1",
            "C256 5",
            "C100 40000",
            "C231 2147483648",
            "M0 2",
            "D0 70000",
            "D8511 1 2",
            "D1 x",
            "D1 1;",
        ] {
            assert!(WriteBatch::parse_line(line).is_err(), "{line:?}");
        }
    }

    #[test]
    fn counters_keep_their_width() {
        let mut batch = WriteBatch::new();
        batch.slot(Slot::C(199), 40000).slot(Slot::C(200), 70000);
        assert_eq!(batch.to_line(), "C199 -25536 70000");
        assert_eq!(
            WriteBatch::parse_line("C199 -25536 70000"),
            Ok(batch.clone())
        );
        let mut devices = Devices::new();
        batch.apply(&mut devices);
        assert_eq!(devices.counter(199), Ok(-25536));
        assert_eq!(devices.counter(200), Ok(70000));
    }

    #[test]
    fn apply_writes_in_order() {
        let mut batch = WriteBatch::new();
        batch.word(3, 1).word(3, 2).bit(Device::X(15), true);
        let mut devices = Devices::new();
        batch.apply(&mut devices);
        assert_eq!(devices.word(3), Ok(2));
        assert_eq!(devices.bit(Device::X(15)), Ok(true));
    }

    fn slot() -> impl Strategy<Value = Slot> {
        prop_oneof![
            (0u16..8512).prop_map(Slot::D),
            (0u16..8512).prop_map(Slot::M),
            (0u16..256).prop_map(Slot::X),
            (0u16..256).prop_map(Slot::C),
        ]
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(500))]
        #[test]
        fn every_batch_survives_its_line(writes in prop::collection::vec((slot(), any::<i32>()), 1..40)) {
            let mut batch = WriteBatch::new();
            for (slot, value) in writes {
                batch.slot(slot, value);
            }
            prop_assert_eq!(WriteBatch::parse_line(&batch.to_line()), Ok(batch));
        }
    }
}
