//! How `ecam serve` times a scan for the watchdog (D8000): the CPU time
//! the scan thread spends on it. Wall time would count the moments the
//! host gives the thread to others (a loaded machine, a suspended
//! process) and stop a healthy program; CPU time is the program's own
//! work, as an FX's scan time is.

use ecam_plc::watchdog::ScanTimer;

/// The calling thread's CPU time ([`ScanTimer`] for real-time scans);
/// wall time where the platform has no thread clock.
#[derive(Debug, Default)]
pub struct ThreadCpuTime {
    start_ns: u64,
}

/// The calling thread's CPU time, ns.
#[cfg(unix)]
fn now_ns() -> u64 {
    use nix::time::{ClockId, clock_gettime};
    clock_gettime(ClockId::CLOCK_THREAD_CPUTIME_ID).map_or(0, |t| {
        u64::try_from(t.tv_sec())
            .unwrap_or(0)
            .saturating_mul(1_000_000_000)
            .saturating_add(u64::try_from(t.tv_nsec()).unwrap_or(0))
    })
}

/// Wall time since the first call, ns.
#[cfg(not(unix))]
fn now_ns() -> u64 {
    static ORIGIN: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
    let elapsed = ORIGIN.get_or_init(std::time::Instant::now).elapsed();
    u64::try_from(elapsed.as_nanos()).unwrap_or(u64::MAX)
}

impl ScanTimer for ThreadCpuTime {
    fn start(&mut self) {
        self.start_ns = now_ns();
    }

    fn elapsed_us(&mut self, _instructions: u64) -> u64 {
        now_ns().saturating_sub(self.start_ns) / 1000
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    #[test]
    fn sleeping_is_not_scan_time_but_work_is() {
        let mut t = ThreadCpuTime::default();
        t.start();
        std::thread::sleep(std::time::Duration::from_millis(50));
        let slept = t.elapsed_us(0);
        let mut x = 0u64;
        while t.elapsed_us(0) < slept + 20_000 {
            x = std::hint::black_box(x.wrapping_add(1));
        }
        assert!(slept < 20_000, "a 50 ms sleep counted {slept} us");
    }
}
