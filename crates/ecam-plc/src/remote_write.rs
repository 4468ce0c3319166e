//! Writes from outside the program (a Modbus client, the HTTP API, the
//! designer's "Write to PLC") into the registers of the program's cam
//! blocks: where a whole table may be loaded, and which writes a running
//! cam refuses (docs/modbus.md, "Writes into cam blocks").
//!
//! A running cam takes a table written into its block at the next seam
//! (docs/plc.md); a table that would be invalid there is not taken and the
//! cam runs on with its last good one. That is the right answer for the
//! program, which writes table words scan by scan, but not for a client:
//! its write is refused before anything changes, with the error the block
//! would show, so the client hears at once that the table it sent cannot
//! run. And a table load aimed at the wrong D address (a block the
//! program does not name, overlapping one it does) would write over a
//! running table or the PLC's special registers: it is refused too.

use core::fmt;
use core::ops::Range;

use crate::decam::{BlockError, check_table_at, offsets};
use crate::device::SPECIAL_FIRST;
use crate::devices::Devices;
use crate::scan::Plc;

/// Why a write from outside was refused; nothing was written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum WriteRefusal {
    /// A table load into the block at `D{block}` would reach the special
    /// registers (D8000–D8511), which are the PLC's own.
    SpecialRegisters {
        /// The block named.
        block: u16,
        /// One past the last register the load would write.
        end: u32,
    },
    /// A table load into the block at `D{block}` would overlap the block
    /// at `D{named}`, which the program's DECAM uses.
    OverlapsCamBlock {
        /// The block named.
        block: u16,
        /// The program's block it would write into.
        named: u16,
    },
    /// The write would leave the table of the running cam at `D{block}`
    /// invalid: the block would refuse it at the next seam with `error`.
    RunningTable {
        /// The running cam's block.
        block: u16,
        /// What the block would show (6781 for offset 31, 6782, 6783).
        error: BlockError,
    },
}

impl WriteRefusal {
    /// The PLC error code the refused write would have caused, if any.
    pub fn code(&self) -> Option<u16> {
        match self {
            Self::RunningTable { error, .. } => Some(error.code()),
            Self::SpecialRegisters { .. } | Self::OverlapsCamBlock { .. } => None,
        }
    }
}

impl fmt::Display for WriteRefusal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::SpecialRegisters { block, end } => write!(
                f,
                "a table at D{block} would reach D{} and the special registers D{SPECIAL_FIRST}-D8511 are the PLC's own: choose a block whose table ends below D{SPECIAL_FIRST}",
                end.saturating_sub(1)
            ),
            Self::OverlapsCamBlock { block, named } => write!(
                f,
                "a table at D{block} would overlap the registers of the program's DECAM block at D{named}: load into D{named} itself, or into a block clear of it"
            ),
            Self::RunningTable { block, error } => write!(
                f,
                "the cam of the block at D{block} is running and this write would leave its table invalid: {} ({}); nothing was written",
                error.to_operation_error(*block).message,
                error.code()
            ),
        }
    }
}

impl std::error::Error for WriteRefusal {}

/// The registers of the program's block at `D{block}` as they stand: the
/// 40 words and the table its point count (offset 38) gives, or the 40
/// words alone while that count is not a table's.
fn occupied(devices: &Devices, block: u16) -> Range<u32> {
    let count = devices
        .word(block.saturating_add(offsets::SECTIONS))
        .ok()
        .and_then(|c| u16::try_from(c).ok())
        .filter(|c| (2..=offsets::MAX_SECTIONS).contains(c))
        .unwrap_or(0);
    u32::from(block)..u32::from(block) + offsets::block_words(count)
}

fn overlap(a: &Range<u32>, b: &Range<u32>) -> bool {
    a.start < b.end && b.start < a.end
}

/// Whether register `n` is one of the table words of the block at
/// `D{block}` (offset 31, or offset 38 up to the largest table).
fn table_word(block: u16, n: u16) -> bool {
    let (block, n) = (u32::from(block), u32::from(n));
    n == block + u32::from(offsets::TABLE_END)
        || (block + u32::from(offsets::SECTIONS)..block + offsets::MAX_BLOCK_WORDS).contains(&n)
}

impl Plc {
    /// The register blocks (S2) the program's DECAM instructions name, in
    /// program order.
    pub fn cam_blocks(&self) -> impl Iterator<Item = u16> + '_ {
        self.decams().iter().map(|d| d.operands().block)
    }

    /// Checks that a table of `points` points may be loaded into the block
    /// at `D{block}` (its words from offset 38): the block with that table
    /// must end below D8000, and may not overlap a block the program names
    /// other than itself. A block the program names is the place for its
    /// table; any other block is a staging area clear of them.
    ///
    /// # Errors
    /// [`WriteRefusal::SpecialRegisters`], [`WriteRefusal::OverlapsCamBlock`].
    pub fn check_table_load(&self, block: u16, points: u16) -> Result<(), WriteRefusal> {
        check_table_load(self.devices(), self.cam_blocks(), block, points)
    }

    /// Checks data-register writes `(register, value)` from outside against
    /// the running cams: a write into the table words of a running cam's
    /// block (offset 31, offset 38 on) is taken at its next seam, as the
    /// program's are, unless it would leave that table invalid. A table
    /// that is already invalid (the cam runs on its last good one) may be
    /// written towards a valid one in steps.
    ///
    /// # Errors
    /// [`WriteRefusal::RunningTable`] with the error the block would show.
    pub fn check_register_writes(&self, writes: &[(u16, i16)]) -> Result<(), WriteRefusal> {
        check_register_writes(self.devices(), self.running_cams(), writes)
    }
}

/// [`Plc::check_table_load`] against a copy of the PLC: its device memory
/// and the blocks its DECAMs name (a server checks its clients' writes
/// against the copy they see, without waiting for a scan).
///
/// # Errors
/// [`WriteRefusal::SpecialRegisters`], [`WriteRefusal::OverlapsCamBlock`].
pub fn check_table_load(
    devices: &Devices,
    named: impl Iterator<Item = u16>,
    block: u16,
    points: u16,
) -> Result<(), WriteRefusal> {
    let target = u32::from(block)..u32::from(block) + offsets::block_words(points);
    if target.end > u32::from(SPECIAL_FIRST) {
        return Err(WriteRefusal::SpecialRegisters {
            block,
            end: target.end,
        });
    }
    let mut named = named;
    match named.find(|&named| named != block && overlap(&target, &occupied(devices, named))) {
        Some(named) => Err(WriteRefusal::OverlapsCamBlock { block, named }),
        None => Ok(()),
    }
}

/// [`Plc::check_register_writes`] against a copy of the PLC: its device
/// memory and the blocks of the cams running.
///
/// # Errors
/// [`WriteRefusal::RunningTable`] with the error the block would show.
pub fn check_register_writes(
    devices: &Devices,
    running: impl Iterator<Item = u16>,
    writes: &[(u16, i16)],
) -> Result<(), WriteRefusal> {
    let touched = |&block: &u16| {
        writes.iter().any(|&(n, _)| table_word(block, n)) && check_table_at(devices, block).is_ok()
    };
    let mut after: Option<Devices> = None;
    for block in running.filter(touched) {
        let after = after.get_or_insert_with(|| {
            let mut copy = devices.clone();
            for &(n, value) in writes {
                let _ = copy.set_word(n, value);
            }
            copy
        });
        if let Err(error) = check_table_at(after, block) {
            return Err(WriteRefusal::RunningTable { block, error });
        }
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    /// A cyclic cam at D2000 on a K1 time base, started, and a second
    /// block at D3000 that the program names but never starts.
    fn running() -> Plc {
        let program = crate::Program::parse(
            "LD M8000\nDECAM K1 D2000 X0 Y0 Y4\nLD M1\nDECAM K1 D3000 X1 Y1 Y5\n",
            "t.il",
        )
        .unwrap();
        let mut plc = Plc::new(program).unwrap();
        let d = plc.devices_mut();
        d.set_word(2038, 3).unwrap();
        d.set_dword(2044, 500).unwrap();
        d.set_dword(2046, 50).unwrap();
        d.set_dword(2048, 1000).unwrap();
        d.set_dword(2050, 100).unwrap();
        d.set_word(2005, 1).unwrap();
        plc.scan();
        plc.hardware_tick(100);
        assert!(plc.cam_running(2000));
        plc
    }

    #[test]
    fn a_table_load_goes_to_a_named_block_or_clear_of_them() {
        let plc = running();
        assert_eq!(plc.cam_blocks().collect::<Vec<_>>(), [2000, 3000]);
        assert_eq!(plc.check_table_load(2000, 100), Ok(()));
        assert_eq!(plc.check_table_load(3000, 512), Ok(()));
        // D2000's block is D2000..D2051 (3 points): D2001 overlaps it.
        assert_eq!(
            plc.check_table_load(2001, 2),
            Err(WriteRefusal::OverlapsCamBlock {
                block: 2001,
                named: 2000
            })
        );
        assert_eq!(plc.check_table_load(2052, 2), Ok(()));
        // D1990 with 3 points reaches D2041.
        assert!(plc.check_table_load(1990, 3).is_err());
        // A named block's table may not spill into the next named block.
        assert!(plc.check_table_load(2000, 300).is_err());
        // Never into the special registers.
        let err = plc.check_table_load(7990, 2).unwrap_err();
        assert_eq!(
            err,
            WriteRefusal::SpecialRegisters {
                block: 7990,
                end: 8038
            }
        );
        assert!(err.to_string().contains("D8037"), "{err}");
        assert!(plc.check_table_load(8000, 2).is_err());
        assert_eq!(plc.check_table_load(7952, 2), Ok(()));
    }

    #[test]
    fn a_write_that_breaks_a_running_table_is_refused_with_the_blocks_error() {
        let plc = running();
        // Point 2's master (D2048) down to 400: not above point 1's 500.
        let err = plc
            .check_register_writes(&[(2048, 400), (2049, 0)])
            .unwrap_err();
        assert_eq!(
            err,
            WriteRefusal::RunningTable {
                block: 2000,
                error: BlockError::Table { section: 2 }
            }
        );
        assert_eq!(err.code(), Some(6782));
        assert!(err.to_string().contains("D2048"), "{err}");
        // A point count of 1, or an end action of 7.
        assert_eq!(
            plc.check_register_writes(&[(2038, 1)])
                .map_err(|e| e.code()),
            Err(Some(6783))
        );
        assert_eq!(
            plc.check_register_writes(&[(2031, 7)])
                .map_err(|e| e.code()),
            Err(Some(6781))
        );
        // A valid new table is taken at the seam; other words are free.
        assert_eq!(plc.check_register_writes(&[(2048, 900)]), Ok(()));
        assert_eq!(plc.check_register_writes(&[(2004, 1), (2019, 5)]), Ok(()));
        // The block the program names but does not run takes anything.
        assert_eq!(plc.check_register_writes(&[(3038, 0)]), Ok(()));
    }

    #[test]
    fn an_invalid_running_table_may_be_mended_in_steps() {
        let mut plc = running();
        plc.devices_mut().set_dword(2048, 400).unwrap();
        plc.scan();
        assert!(plc.cam_running(2000), "runs on with its last good table");
        // Still invalid after this write, but no worse: accepted.
        assert_eq!(plc.check_register_writes(&[(2050, 7)]), Ok(()));
    }
}
