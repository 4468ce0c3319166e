//! Offsets of the DECAM register block at S2 (document 003, section 5).
//!
//! Word `S2 + offset`; 32-bit values occupy two words, low word first. The
//! manual labels some rows inconsistently; the comments say which reading
//! this implementation takes (see `docs/plc.md`).

use ecam_core::register_image;

/// Version of the cam function; the controller shows 5200.
pub const VERSION: u16 = 0;
/// The version number written to offset 0.
pub const VERSION_NUMBER: i16 = 5200;
/// Flag register (see [`crate::decam::flags`]).
pub const FLAGS: u16 = 1;
/// Error register: 6781 for a parameter error, the offending section number
/// for a table error (6782), 6783 for a bad section count.
pub const ERROR: u16 = 2;
/// Function register read at start (delay start, start position, zooms,
/// external start, start from current position).
pub const FUNCTION: u16 = 3;
/// Function register read every tick (sync enable, stop after this cycle).
pub const CONTROL: u16 = 4;
/// Start register: 0 stop, 1 cyclic, 2 noncyclic, anything else stop.
pub const START: u16 = 5;
/// Maximum output frequency in Hz (32-bit).
pub const MAX_FREQUENCY: u16 = 6;
/// Index of the Y output driven by the sync window (0–255 = Y0–Y377).
pub const SYNC_OUTPUT: u16 = 8;
/// Lower threshold of the sync window (32-bit; the manual mislabels its
/// high word, document 003 row 10 — offsets 9/10 are the lower threshold).
pub const SYNC_LOW: u16 = 9;
/// Upper threshold of the sync window (32-bit, offsets 11/12).
pub const SYNC_HIGH: u16 = 11;
/// "Remaining master pulses": this implementation shows the master counts
/// left before a delayed or position start engages (0 otherwise).
pub const MASTER_REMAINING: u16 = 13;
/// Repeat count of a noncyclic cam: 0 runs once, n runs n + 1 cycles, 0xFFFF forever.
pub const REPEAT: u16 = 14;
/// Delay in master counts after the start signal (32-bit unsigned).
pub const DELAY: u16 = 15;
/// Master position at which a noncyclic cam starts (32-bit).
pub const START_POSITION: u16 = 17;
/// Current slave position after slave zoom (32-bit); with function bit 6 the
/// slave position the cam starts from.
pub const SLAVE_ZOOMED: u16 = 19;
/// Current slave position before slave zoom (32-bit).
pub const SLAVE_RAW: u16 = 21;
/// Slave zoom denominator (1–65535).
pub const SLAVE_ZOOM_DEN: u16 = 23;
/// Slave zoom numerator (1–65535).
pub const SLAVE_ZOOM_NUM: u16 = 24;
/// Current master position in the cycle after master zoom (32-bit).
pub const MASTER_ZOOMED: u16 = 25;
/// Current master position in the cycle before master zoom (32-bit); with
/// function bit 6 the master position the cam starts from.
pub const MASTER_RAW: u16 = 27;
/// Master zoom denominator (1–65535).
pub const MASTER_ZOOM_DEN: u16 = 29;
/// Master zoom numerator (1–65535).
pub const MASTER_ZOOM_NUM: u16 = 30;
/// What happens at the end of the table (reserved in the manual; ecam's
/// home for the midCAMend rule "the cam stops when the curve completes"):
/// ECAMTBX writes [`TABLE_END_STOP`] for a midCAMend table and
/// [`TABLE_END_REPEAT`] for every other.
pub const TABLE_END: u16 = 31;
/// Offset 31 value: the table repeats as the mode says.
pub const TABLE_END_REPEAT: u16 = 0;
/// Offset 31 value: the table runs one pass and the cam stops at its end.
pub const TABLE_END_STOP: u16 = 1;
// The table image (offsets 38 on) has its home in
// `ecam_core::register_image`; these are its offsets as register numbers.

/// Number of table points ("sections"), 2–512.
pub const SECTIONS: u16 = register_image::SECTION_COUNT_OFFSET as u16;
/// Offset of the table; always 40 (the controller writes it).
pub const TABLE_OFFSET: u16 = register_image::TABLE_OFFSET_OFFSET as u16;
/// First word of the table: point i is at `TABLE + 4 i` (master, slave; 32-bit each).
pub const TABLE: u16 = register_image::TABLE_OFFSET as u16;
/// Most points a table may hold.
pub const MAX_SECTIONS: u16 = register_image::MAX_SECTIONS as u16;
/// Words per table point.
pub const WORDS_PER_SECTION: u16 = register_image::WORDS_PER_SECTION as u16;

/// The size of a block whose table holds the most points (40 + 4 × 512
/// words): how far a block's registers can reach.
pub const MAX_BLOCK_WORDS: u32 = block_words(MAX_SECTIONS);

/// The size in words of a block whose table holds `points` points
/// (offsets 0 to 40 + 4·points − 1), from `register_image::block_len`;
/// so also the offset of point number `points` (point `i` of a table is
/// at `S2 + block_words(i)`). The one home of the block's size; `u32`, so
/// that a block that would run past D8511 (or past any count) shows it.
pub const fn block_words(points: u16) -> u32 {
    // At most 40 + 4 × 65535: exact in u32.
    register_image::block_len(points as usize) as u32
}
