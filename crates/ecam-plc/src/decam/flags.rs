//! Bits of the flag register (offset 1) and of the two function registers
//! (offsets 3 and 4), document 003 sections 5 and 5.1.

/// Flag bit 0: initialisation done, the cam is ready or running. Set by the
/// controller when a mode is accepted; cleared by it when a noncyclic run
/// ends; the program may also reset it.
pub const INIT_DONE: u16 = 1 << 0;
/// Flag bit 1: a cam cycle completed. Latched; the program resets it.
pub const CYCLE_COMPLETE: u16 = 1 << 1;
/// Flag bit 2: pulse output lags the commanded slave (frequency limit).
pub const PULSE_DELAYED: u16 = 1 << 2;
/// Flag bit 3: some error is present.
pub const ERROR: u16 = 1 << 3;
/// Flag bit 4: parameter error (6781).
pub const PARAMETER_ERROR: u16 = 1 << 4;
/// Flag bit 5: table error (6782 or 6783).
pub const TABLE_ERROR: u16 = 1 << 5;
/// Flag bit 6: cyclic mode active.
pub const CYCLIC: u16 = 1 << 6;
/// Flag bit 7: noncyclic mode active.
pub const NONCYCLIC: u16 = 1 << 7;
/// Flag bit 8 (unused by the manual): the register block has an error
/// (offset 2 shows which) while the cam runs on; it keeps the last good
/// table and settings. Bits 3–5 are set only while the error keeps the cam
/// from running.
pub const KEPT_LAST_GOOD: u16 = 1 << 8;
/// Flag bit 9: the cam stopped at the end of a cycle (noncyclic run done, or
/// stop-after-cycle done); cleared at the next start.
pub const CURRENT_CYCLE_COMPLETE: u16 = 1 << 9;
/// Flag bit 10: the master is inside the sync window while the cam runs.
pub const IN_SYNC_AREA: u16 = 1 << 10;
/// Flag bit 11: the master is the virtual time base (S1 = Kn).
pub const TIME_BASE: u16 = 1 << 11;
/// Bits the program owns once set: the controller only sets them.
pub const LATCHED: u16 = INIT_DONE | CYCLE_COMPLETE;

/// Function register (offset 3) bit 0: delay start (offsets 15/16).
pub const FN_DELAY_START: u16 = 1 << 0;
/// Function register bit 1: start at a master position (offsets 17/18).
pub const FN_START_AT_POSITION: u16 = 1 << 1;
/// Function register bit 2: master zoom (offsets 29/30).
pub const FN_MASTER_ZOOM: u16 = 1 << 2;
/// Function register bit 3: slave zoom (offsets 23/24).
pub const FN_SLAVE_ZOOM: u16 = 1 << 3;
/// Function register bit 5: wait for a rising edge of S3.
pub const FN_EXTERNAL_START: u16 = 1 << 5;
/// Function register bit 6: start from the current position (master from
/// offsets 27/28, slave from 19/20).
pub const FN_FROM_CURRENT: u16 = 1 << 6;

/// Control register (offset 4) bit 0: drive the sync output. The register
/// table says bit 1, section 5.1 and the cyclic example (D2004 bit 0) say bit 0.
pub const CTL_SYNC_ENABLE: u16 = 1 << 0;
/// Control register bit 1: stop at the end of the current cycle. The
/// register table says bit 2; sections 4.1.2, 4.2.2 and 5.1 say bit 1.
pub const CTL_STOP_AFTER_CYCLE: u16 = 1 << 1;
