//! The watchdog timer (D8000), the FX way: a scan that runs longer than
//! D8000 ms stops the program with the watchdog timer error, 6105 in
//! D8061 with M8061 on (the FX3U's "PLC hardware error" pair; M8004 on and
//! D8004 = 8061 say which error flag is set), every output off, until the
//! PLC is started again (a new [`crate::Plc`]; `ecam serve` restarted).
//!
//! How long a scan ran is for the caller to say ([`ScanTimer`]): in
//! simulated time ([`ModeledScanTime`], the default) it is counted from the
//! instructions executed, so runs are repeatable on any machine; `ecam
//! serve` measures the scan thread's CPU time, so a busy host or a
//! suspended process does not trip it.

use core::fmt;

/// FX3U error code of a watchdog timer error (in D8061).
pub const CODE_WATCHDOG: u16 = 6105;
/// D8000 at power-on, ms (the FX3U's default).
pub const DEFAULT_WATCHDOG_MS: u16 = 200;
/// Simulated time one instruction takes, ns: 10⁶ instructions are the
/// default 200 ms. The FX3U's own figures run from 0.065 µs (a contact) to
/// several µs (applied instructions); 0.2 µs is a plain program's mean.
pub const MODELED_NS_PER_INSTRUCTION: u64 = 200;
/// Instructions between two looks at the timer (a look at a CPU clock is
/// a system call; a scan overruns by at most this many instructions).
pub const CHECK_EVERY: u64 = 1024;

/// Measures how long the current scan has run.
pub trait ScanTimer: Send {
    /// The scan starts now.
    fn start(&mut self);
    /// µs since [`ScanTimer::start`], `instructions` having been executed.
    fn elapsed_us(&mut self, instructions: u64) -> u64;
}

/// Simulated scan time: [`MODELED_NS_PER_INSTRUCTION`] per instruction.
#[derive(Clone, Copy, Debug, Default)]
pub struct ModeledScanTime;

impl ScanTimer for ModeledScanTime {
    fn start(&mut self) {}

    fn elapsed_us(&mut self, instructions: u64) -> u64 {
        instructions.saturating_mul(MODELED_NS_PER_INSTRUCTION) / 1000
    }
}

/// The watchdog time a D8000 value gives, µs: values outside 1–32767 ms
/// (a program's `MOV K0 D8000`) read as the default.
pub fn limit_us(d8000: i16) -> u64 {
    let ms = u16::try_from(d8000)
        .ok()
        .filter(|&ms| ms > 0)
        .unwrap_or(DEFAULT_WATCHDOG_MS);
    u64::from(ms) * 1000
}

/// What stopped the program.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Fault {
    /// A scan ran longer than the watchdog time.
    Watchdog {
        /// The line of the last jump taken (the loop), or of the
        /// instruction the scan had reached.
        line: usize,
        /// How long the scan had run when it was stopped, µs.
        scan_us: u64,
        /// D8000 at the start of that scan, ms.
        limit_ms: u64,
    },
}

impl Fault {
    /// The error code (D8061).
    pub fn code(&self) -> u16 {
        match self {
            Self::Watchdog { .. } => CODE_WATCHDOG,
        }
    }

    /// The source line it names.
    pub fn line(&self) -> usize {
        match self {
            Self::Watchdog { line, .. } => *line,
        }
    }
}

impl fmt::Display for Fault {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Watchdog {
                scan_us, limit_ms, ..
            } => write!(
                f,
                "watchdog timer error {CODE_WATCHDOG}: a scan ran {}.{} ms, over the \
                 watchdog time D8000 = {limit_ms} ms; the program is stopped, every output off",
                scan_us / 1000,
                scan_us % 1000 / 100
            ),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn d8000_outside_its_range_reads_as_the_default() {
        assert_eq!(limit_us(200), 200_000);
        assert_eq!(limit_us(1), 1_000);
        assert_eq!(limit_us(32767), 32_767_000);
        assert_eq!(limit_us(0), 200_000);
        assert_eq!(limit_us(-5), 200_000);
    }

    #[test]
    fn a_million_modeled_instructions_are_the_default_watchdog_time() {
        let mut t = ModeledScanTime;
        t.start();
        assert_eq!(
            t.elapsed_us(1_000_000),
            u64::from(DEFAULT_WATCHDOG_MS) * 1000
        );
    }
}
