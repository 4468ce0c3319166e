//! External buffer memory: the RAM cam tables live in.
//!
//! Document 002 places cam tables in external RAM described by the existing
//! buffer commands (`SetBufferStart`, `SetBufferLength`,
//! `SetBufferWriteIndex`, `WriteBuffer`). Values are signed 32-bit dwords and
//! addresses count dwords. Buffers are windows onto one shared memory, so two
//! buffers that overlap see each other's writes, as on the device.

use std::vec;
use std::vec::Vec;

use crate::PmdError;

/// Size of the simulated external memory, in dwords (addresses `0..MEMORY_DWORDS`).
pub const MEMORY_DWORDS: u32 = 1 << 20;

/// Number of buffer IDs (`0..BUFFER_COUNT`); document 002 asks for "a small integer".
pub const BUFFER_COUNT: u8 = 32;

/// A buffer ID checked against [`BUFFER_COUNT`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct BufferId(u8);

impl BufferId {
    /// Buffer 0, the default `CamBufferID`.
    pub const ZERO: BufferId = BufferId(0);

    /// Checks `id`.
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] unless `0 <= id < BUFFER_COUNT`.
    pub fn new(id: i64) -> Result<Self, PmdError> {
        u8::try_from(id)
            .ok()
            .filter(|&id| id < BUFFER_COUNT)
            .map(Self)
            .ok_or(PmdError::OutOfRange {
                what: "bufferID",
                value: id,
                allowed: "a buffer ID from 0 to 31",
            })
    }

    /// The ID as a number.
    pub const fn get(self) -> u8 {
        self.0
    }
}

/// Where one buffer lies in memory and where the next `WriteBuffer` goes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct BufferWindow {
    /// First address (dwords).
    pub start: u32,
    /// Length (dwords).
    pub length: u32,
    /// Index (from `start`) the next `WriteBuffer` writes.
    pub write_index: u32,
}

/// The external memory and its buffer windows.
#[derive(Clone)]
pub struct BufferMemory {
    ram: Vec<i32>,
    windows: [BufferWindow; BUFFER_COUNT as usize],
    /// Counts the writes into memory, so a running cam can tell cheaply
    /// whether its table may have changed.
    revision: u64,
}

impl core::fmt::Debug for BufferMemory {
    /// Shows the buffers that have a length, not the megabytes of memory.
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        let mut map = f.debug_map();
        for (id, w) in self
            .windows
            .iter()
            .enumerate()
            .filter(|(_, w)| w.length > 0)
        {
            map.entry(&id, w);
        }
        map.finish()
    }
}

impl Default for BufferMemory {
    fn default() -> Self {
        Self::new()
    }
}

impl BufferMemory {
    /// Zeroed memory; every buffer starts at 0 with length 0.
    pub fn new() -> Self {
        Self {
            ram: vec![0; MEMORY_DWORDS as usize],
            windows: [BufferWindow::default(); BUFFER_COUNT as usize],
            revision: 0,
        }
    }

    /// How many `WriteBuffer`s the memory has taken: changes whenever any
    /// value may have changed.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// The window of buffer `id`.
    pub fn window(&self, id: BufferId) -> BufferWindow {
        self.windows
            .get(usize::from(id.0))
            .copied()
            .unwrap_or_default()
    }

    fn window_mut(&mut self, id: BufferId) -> Option<&mut BufferWindow> {
        self.windows.get_mut(usize::from(id.0))
    }

    fn check_fits(id: BufferId, start: u32, length: u32) -> Result<(), PmdError> {
        match start.checked_add(length) {
            Some(end) if end <= MEMORY_DWORDS => Ok(()),
            _ => Err(PmdError::PastMemory {
                buffer: id.0,
                start,
                length,
            }),
        }
    }

    /// `SetBufferStart`: moves the buffer; its write index goes back to 0.
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] for a negative or too large address,
    /// [`PmdError::PastMemory`] if the buffer would leave memory.
    pub fn set_start(&mut self, id: BufferId, start: i64) -> Result<(), PmdError> {
        let start = u32::try_from(start)
            .ok()
            .filter(|&s| s < MEMORY_DWORDS)
            .ok_or(PmdError::OutOfRange {
                what: "buffer start address",
                value: start,
                allowed: "0 to 0xFFFFF (dwords)",
            })?;
        let length = self.window(id).length;
        Self::check_fits(id, start, length)?;
        if let Some(w) = self.window_mut(id) {
            w.start = start;
            w.write_index = 0;
        }
        Ok(())
    }

    /// `SetBufferLength`: resizes the buffer; its write index goes back to 0.
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] for a negative or too large length,
    /// [`PmdError::PastMemory`] if the buffer would leave memory.
    pub fn set_length(&mut self, id: BufferId, length: i64) -> Result<(), PmdError> {
        let length = u32::try_from(length)
            .ok()
            .filter(|&l| l <= MEMORY_DWORDS)
            .ok_or(PmdError::OutOfRange {
                what: "buffer length",
                value: length,
                allowed: "0 to 0x100000 dwords",
            })?;
        let start = self.window(id).start;
        Self::check_fits(id, start, length)?;
        if let Some(w) = self.window_mut(id) {
            w.length = length;
            w.write_index = 0;
        }
        Ok(())
    }

    /// `SetBufferWriteIndex`.
    ///
    /// # Errors
    /// [`PmdError::IndexPastLength`] unless `0 <= index < length`.
    pub fn set_write_index(&mut self, id: BufferId, index: i64) -> Result<(), PmdError> {
        let w = self.window(id);
        let index = u32::try_from(index).ok().filter(|&i| i < w.length).ok_or(
            PmdError::IndexPastLength {
                buffer: id.0,
                index,
                length: w.length,
            },
        )?;
        if let Some(w) = self.window_mut(id) {
            w.write_index = index;
        }
        Ok(())
    }

    /// `WriteBuffer`: stores `value` at the write index, which then advances
    /// and wraps to 0 at the buffer's length (the device's circular buffers).
    ///
    /// # Errors
    /// [`PmdError::OutOfRange`] for a value that is not a signed 32-bit
    /// number, [`PmdError::EmptyBuffer`] for a buffer of length 0.
    pub fn write(&mut self, id: BufferId, value: i64) -> Result<(), PmdError> {
        let value = i32::try_from(value).map_err(|_| PmdError::OutOfRange {
            what: "buffer value",
            value,
            allowed: "a signed 32-bit number",
        })?;
        let w = self.window(id);
        if w.length == 0 {
            return Err(PmdError::EmptyBuffer { buffer: id.0 });
        }
        let address = w.start.saturating_add(w.write_index) as usize;
        if let Some(cell) = self.ram.get_mut(address) {
            *cell = value;
        }
        self.revision = self.revision.wrapping_add(1);
        let next = w.write_index.saturating_add(1);
        if let Some(w) = self.window_mut(id) {
            w.write_index = if next >= w.length { 0 } else { next };
        }
        Ok(())
    }

    /// Value `index` of buffer `id` (0 outside the buffer).
    pub fn read(&self, id: BufferId, index: u32) -> i32 {
        let w = self.window(id);
        if index >= w.length {
            return 0;
        }
        let address = w.start.saturating_add(index) as usize;
        self.ram.get(address).copied().unwrap_or(0)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn id(n: i64) -> BufferId {
        BufferId::new(n).unwrap()
    }

    #[test]
    fn writes_advance_and_wrap() {
        let mut m = BufferMemory::new();
        m.set_start(id(2), 0x1000).unwrap();
        m.set_length(id(2), 3).unwrap();
        for v in [10, 20, 30, 40] {
            m.write(id(2), v).unwrap();
        }
        assert_eq!(
            [m.read(id(2), 0), m.read(id(2), 1), m.read(id(2), 2)],
            [40, 20, 30]
        );
        assert_eq!(m.window(id(2)).write_index, 1);
    }

    #[test]
    fn overlapping_buffers_share_memory() {
        let mut m = BufferMemory::new();
        for b in [1, 2] {
            m.set_start(id(b), 100).unwrap();
            m.set_length(id(b), 4).unwrap();
        }
        m.write(id(1), -7).unwrap();
        assert_eq!(m.read(id(2), 0), -7);
    }

    #[test]
    fn bad_requests_change_nothing() {
        let mut m = BufferMemory::new();
        m.set_length(id(3), 2).unwrap();
        m.write(id(3), 5).unwrap();
        let before = m.window(id(3));
        assert!(matches!(
            m.set_write_index(id(3), 2),
            Err(PmdError::IndexPastLength { .. })
        ));
        assert!(m.set_write_index(id(3), -1).is_err());
        assert!(m.write(id(3), 1 << 31).is_err());
        assert!(m.set_start(id(3), i64::from(MEMORY_DWORDS) - 1).is_err());
        assert!(m.set_length(id(3), -1).is_err());
        assert_eq!(m.window(id(3)), before);
        assert!(matches!(
            m.write(id(4), 1),
            Err(PmdError::EmptyBuffer { buffer: 4 })
        ));
        assert!(BufferId::new(32).is_err());
    }
}
