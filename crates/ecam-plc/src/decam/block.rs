//! Reading and checking the register block: what the cam needs at a start
//! ([`StartSetup`]) and what it re-reads every tick ([`LiveSettings`]).

use core::num::NonZeroU16;

use ecam_core::{PointTable, TableError, register_image};

use super::block_error::BlockError;
use super::{flags, offsets};
use crate::device::D_COUNT;
use crate::devices::Devices;

/// Ceiling the manual puts on the output frequency (offsets 6/7).
pub const MAX_FREQUENCY_HZ: u32 = 200_000;

/// An exact zoom ratio `num / den` from two registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ZoomRatio {
    /// Numerator (offset 24 or 30).
    pub num: NonZeroU16,
    /// Denominator (offset 23 or 29).
    pub den: NonZeroU16,
}

impl ZoomRatio {
    /// 1 : 1.
    pub const ONE: Self = Self {
        num: NonZeroU16::MIN,
        den: NonZeroU16::MIN,
    };

    /// `value × num / den`, rounded toward negative infinity (the engine's
    /// `Zoom` does this at run time; this checks the register's meaning).
    #[cfg(test)]
    pub fn apply(self, value: i64) -> i64 {
        let scaled = i128::from(value) * i128::from(self.num.get());
        let den = i128::from(self.den.get());
        let q = scaled.div_euclid(den);
        i64::try_from(q).unwrap_or(if q < 0 { i64::MIN } else { i64::MAX })
    }
}

/// What a start takes from the block (function register, zooms, repeat
/// count, delay, start position, frequency, table).
#[derive(Clone, Debug, PartialEq)]
pub struct StartSetup {
    /// Function bit 0: master counts to wait after the start signal (noncyclic only).
    pub delay: Option<u32>,
    /// Function bit 1: master position to wait for after the start signal (noncyclic only).
    pub start_position: Option<i64>,
    /// Function bit 2: master zoom, else 1:1.
    pub master_zoom: ZoomRatio,
    /// Function bit 3: slave zoom, else 1:1.
    pub slave_zoom: ZoomRatio,
    /// Function bit 5: wait for a rising edge of S3.
    pub external_start: bool,
    /// Function bit 6: start from offsets 27/28 (master) and 19/20 (slave).
    pub from_current: bool,
    /// Offset 14.
    pub repeats: u16,
    /// Offsets 6/7 after the manual's clamp.
    pub max_frequency_hz: u32,
    /// The table at offset 38…
    pub table: PointTable,
    /// Offset 31 (reserved in the manual): 1 when the table is a midCAMend
    /// table that runs one pass and stops at its end (written by ECAMTBX).
    pub single_pass: bool,
}

/// Settings the manual lets a program change while the cam runs (offset 4)
/// and the sync window (offsets 8–12), read every tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiveSettings {
    /// Control bit 0.
    pub sync_enabled: bool,
    /// Control bit 1.
    pub stop_after_cycle: bool,
    /// Offset 8 as a Y index.
    pub sync_output: u16,
    /// Offsets 9/10.
    pub sync_low: i64,
    /// Offsets 11/12.
    pub sync_high: i64,
}

impl LiveSettings {
    /// True when `master` (in-cycle, after zoom) is inside the window, both ends included.
    pub fn in_window(&self, master: i64) -> bool {
        self.sync_low <= master && master <= self.sync_high
    }
}

/// Reads registers of one block; every access was range-checked when the
/// operands were accepted (offsets below 40) or is checked here (the table).
pub(crate) struct Block<'a> {
    devices: &'a Devices,
    base: u16,
}

impl<'a> Block<'a> {
    pub(crate) fn new(devices: &'a Devices, base: u16) -> Self {
        Self { devices, base }
    }

    pub(crate) fn word(&self, offset: u16) -> u16 {
        self.base
            .checked_add(offset)
            .and_then(|n| self.devices.word(n).ok())
            .map_or(0, |w| w as u16)
    }

    pub(crate) fn dword(&self, offset: u16) -> i32 {
        self.base
            .checked_add(offset)
            .and_then(|n| self.devices.dword(n).ok())
            .unwrap_or(0)
    }

    /// Offsets 3, 6/7, 14–18, 23/24, 29/30 and the table.
    pub(crate) fn start_setup(&self) -> Result<StartSetup, BlockError> {
        let function = self.word(offsets::FUNCTION);
        let delay_start = function & flags::FN_DELAY_START != 0;
        let at_position = function & flags::FN_START_AT_POSITION != 0;
        if delay_start && at_position {
            return Err(BlockError::Parameter {
                offset: offsets::FUNCTION,
                reason: "sets both bit 0 (delay start) and bit 1 (start at position); choose one",
            });
        }
        let master_zoom = if function & flags::FN_MASTER_ZOOM != 0 {
            self.zoom(offsets::MASTER_ZOOM_NUM, offsets::MASTER_ZOOM_DEN)?
        } else {
            ZoomRatio::ONE
        };
        let slave_zoom = if function & flags::FN_SLAVE_ZOOM != 0 {
            self.zoom(offsets::SLAVE_ZOOM_NUM, offsets::SLAVE_ZOOM_DEN)?
        } else {
            ZoomRatio::ONE
        };
        Ok(StartSetup {
            delay: delay_start.then(|| self.dword(offsets::DELAY) as u32),
            start_position: at_position.then(|| i64::from(self.dword(offsets::START_POSITION))),
            master_zoom,
            slave_zoom,
            external_start: function & flags::FN_EXTERNAL_START != 0,
            from_current: function & flags::FN_FROM_CURRENT != 0,
            repeats: self.word(offsets::REPEAT),
            max_frequency_hz: clamp_frequency(self.dword(offsets::MAX_FREQUENCY)),
            table: self.table()?,
            single_pass: self.single_pass()?,
        })
    }

    /// Offset 31: whether the table runs one pass (midCAMend).
    fn single_pass(&self) -> Result<bool, BlockError> {
        match self.word(offsets::TABLE_END) {
            offsets::TABLE_END_REPEAT => Ok(false),
            offsets::TABLE_END_STOP => Ok(true),
            _ => Err(BlockError::Parameter {
                offset: offsets::TABLE_END,
                reason: "table end action must be 0 (repeat) or 1 (stop at the table end, midCAMend)",
            }),
        }
    }

    /// The table words (offsets 31, 38 on) checked as a start or a seam
    /// takes them, the rest of the block left aside.
    pub(crate) fn table_check(&self) -> Result<(), BlockError> {
        self.table()?;
        self.single_pass().map(|_| ())
    }

    fn zoom(&self, num_offset: u16, den_offset: u16) -> Result<ZoomRatio, BlockError> {
        let num = NonZeroU16::new(self.word(num_offset)).ok_or(BlockError::Parameter {
            offset: num_offset,
            reason: "zoom numerator is 0; zoom terms must be 1-65535",
        })?;
        let den = NonZeroU16::new(self.word(den_offset)).ok_or(BlockError::Parameter {
            offset: den_offset,
            reason: "zoom denominator is 0; zoom terms must be 1-65535",
        })?;
        Ok(ZoomRatio { num, den })
    }

    /// Offsets 4 and 8–12.
    pub(crate) fn live(&self) -> Result<LiveSettings, BlockError> {
        let control = self.word(offsets::CONTROL);
        let live = LiveSettings {
            sync_enabled: control & flags::CTL_SYNC_ENABLE != 0,
            stop_after_cycle: control & flags::CTL_STOP_AFTER_CYCLE != 0,
            sync_output: self.word(offsets::SYNC_OUTPUT),
            sync_low: i64::from(self.dword(offsets::SYNC_LOW)),
            sync_high: i64::from(self.dword(offsets::SYNC_HIGH)),
        };
        if live.sync_enabled {
            if live.sync_output > 255 {
                return Err(BlockError::Parameter {
                    offset: offsets::SYNC_OUTPUT,
                    reason: "sync output must be a Y index 0-255 (Y0-Y377)",
                });
            }
            if live.sync_low > live.sync_high {
                return Err(BlockError::Parameter {
                    offset: offsets::SYNC_LOW,
                    reason: "lower sync threshold is above the upper threshold (offsets 11/12)",
                });
            }
        }
        Ok(live)
    }

    /// The point table at offsets 38, 40….
    pub(crate) fn table(&self) -> Result<PointTable, BlockError> {
        let count = self.word(offsets::SECTIONS) as i16;
        let fits =
            u32::from(self.base) + offsets::block_words(count.max(0) as u16) <= u32::from(D_COUNT);
        if !(2..=offsets::MAX_SECTIONS as i16).contains(&count) || !fits {
            return Err(BlockError::SectionCount { count });
        }
        // Offsets 40 up to the block's end: below D8512, checked above.
        let words: Vec<i16> = (offsets::block_words(0)..offsets::block_words(count as u16))
            .map(|offset| self.word(offset as u16) as i16)
            .collect();
        register_image::table_from_sections(&words).map_err(|e| match e {
            TableError::MasterNotIncreasing { section }
            | TableError::ValueOutOfRange { section } => BlockError::Table {
                section: u16::try_from(section).unwrap_or(u16::MAX),
            },
            _ => BlockError::SectionCount { count },
        })
    }
}

/// Document 003: "If frequency > 200K or frequency < 0, then the frequency
/// value is 200K". Zero would stop the output for good, so it also means 200 kHz.
pub fn clamp_frequency(raw: i32) -> u32 {
    match u32::try_from(raw) {
        Ok(hz) if (1..=MAX_FREQUENCY_HZ).contains(&hz) => hz,
        _ => MAX_FREQUENCY_HZ,
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    fn block_with_table(points: &[(i32, i32)]) -> Devices {
        let mut dev = Devices::new();
        dev.set_word(38, points.len() as i16).unwrap();
        for (i, &(m, s)) in points.iter().enumerate() {
            let at = offsets::block_words(i as u16) as u16;
            dev.set_dword(at, m).unwrap();
            dev.set_dword(at + 2, s).unwrap();
        }
        dev
    }

    #[test]
    fn frequency_clamps_as_the_manual_says() {
        assert_eq!(clamp_frequency(0), 200_000);
        assert_eq!(clamp_frequency(-5), 200_000);
        assert_eq!(clamp_frequency(250_000), 200_000);
        assert_eq!(clamp_frequency(1000), 1000);
    }

    #[test]
    fn zoom_is_exact_and_floors() {
        let z = ZoomRatio {
            num: NonZeroU16::new(2).unwrap(),
            den: NonZeroU16::new(3).unwrap(),
        };
        assert_eq!(z.apply(3), 2);
        assert_eq!(z.apply(4), 2);
        assert_eq!(z.apply(-1), -1);
    }

    #[test]
    fn reads_a_good_table() {
        let dev = block_with_table(&[(0, 0), (100, 50), (200, 0)]);
        let t = Block::new(&dev, 0).table().unwrap();
        assert_eq!(t.points().len(), 3);
    }

    #[test]
    fn bad_tables_name_the_section() {
        let dev = block_with_table(&[(0, 0), (100, 50), (100, 0)]);
        assert_eq!(
            Block::new(&dev, 0).table(),
            Err(BlockError::Table { section: 2 })
        );
        let dev = block_with_table(&[]);
        assert_eq!(
            Block::new(&dev, 0).table(),
            Err(BlockError::SectionCount { count: 0 })
        );
        let mut dev = block_with_table(&[(0, 0), (1, 1)]);
        dev.set_word(38, 513).unwrap();
        assert_eq!(
            Block::new(&dev, 0).table(),
            Err(BlockError::SectionCount { count: 513 })
        );
    }

    #[test]
    fn zero_zoom_is_a_parameter_error_only_when_enabled() {
        let mut dev = block_with_table(&[(0, 0), (100, 50)]);
        assert!(Block::new(&dev, 0).start_setup().is_ok());
        dev.set_word(3, flags::FN_MASTER_ZOOM as i16).unwrap();
        let err = Block::new(&dev, 0).start_setup().unwrap_err();
        assert_eq!(err.code(), 6781);
    }
}
