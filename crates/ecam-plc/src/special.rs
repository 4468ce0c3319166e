//! Special devices of the LX3V (document 003, "Special address", and the FX
//! family conventions the LX3V follows): what the scan cycle and the simulated
//! hardware maintain, and where.

/// M8000: on while the PLC runs.
pub const M_RUNNING: u16 = 8000;
/// M8001: off while the PLC runs (the inverse of M8000).
pub const M_NOT_RUNNING: u16 = 8001;
/// M8002: on during the first scan only.
pub const M_FIRST_SCAN: u16 = 8002;
/// M8003: off during the first scan only.
pub const M_NOT_FIRST_SCAN: u16 = 8003;
/// M8004: on while an error stops the PLC (here: the watchdog, M8061);
/// D8004 gives that flag's number.
pub const M_ERROR: u16 = 8004;
/// D8004: the number of the error flag that is on (8061).
pub const D_ERROR: u16 = 8004;
/// D8000: the watchdog time, ms (see [`crate::watchdog`]).
pub const D_WATCHDOG: u16 = 8000;
/// D8010, D8011, D8012: the current, shortest and longest scan time since
/// the start, in 0.1 ms (as the FX3U; how a scan is timed: [`crate::watchdog`]).
pub const D_SCAN_TIME: [u16; 3] = [8010, 8011, 8012];
/// M8061: PLC hardware error (here: the watchdog timer error); the PLC stops.
pub const M_HARDWARE_ERROR: u16 = 8061;
/// D8061: the code of the PLC hardware error (6105: watchdog timer).
pub const D_HARDWARE_ERROR: u16 = 8061;
/// Clock relays M8011 (10 ms), M8012 (100 ms), M8013 (1 s), M8014 (1 min),
/// with their periods in µs: on for the first half of every period, counted
/// from t = 0 of simulated time, updated at the start of each scan.
pub const M_CLOCKS: [(u16, u64); 4] = [
    (8011, 10_000),
    (8012, 100_000),
    (8013, 1_000_000),
    (8014, 60_000_000),
];
/// M8020: zero flag of ADD/SUB.
pub const M_ZERO: u16 = 8020;
/// M8021: borrow flag of ADD/SUB (result below the signed range, wrapped).
pub const M_BORROW: u16 = 8021;
/// M8022: carry flag of ADD/SUB (result above the signed range, wrapped).
pub const M_CARRY: u16 = 8022;
/// M8029: instruction complete (a PLSY/DPLSY finished its pulse count).
pub const M_EXECUTION_COMPLETE: u16 = 8029;
/// M8067: operation error flag (latched until the PLC is restarted).
pub const M_OPERATION_ERROR: u16 = 8067;
/// D8067: code of the last operation error.
pub const D_OPERATION_ERROR: u16 = 8067;

/// Low word of the 32-bit output-pulse counter of Y0..Y3 (D8140/41, D8142/43,
/// D8150/51, D8152/53); they count down when the output runs in reverse.
pub const D_PULSE_COUNT: [u16; 4] = [8140, 8142, 8150, 8152];
/// Immediate-stop flags of Y0..Y3 (M8145, M8146, M8152, M8153).
pub const M_STOP: [u16; 4] = [8145, 8146, 8152, 8153];
/// Busy flags of Y0..Y3 (M8147..M8150): on while the output emits pulses.
pub const M_BUSY: [u16; 4] = [8147, 8148, 8149, 8150];

/// Counting direction of the 32-bit counter Cn is M(8000 + n), i.e. M8200 for C200 …
/// M8255 for C255 (on = count down), the FX convention.
pub const M_COUNTER_DIRECTION_BASE: u16 = 8000;
