//! The scan loop in real time: the PLC runtime's simulated-time step (one
//! scan, then hardware ticks covering one scan period, [`ecam_plc::sim::run`]
//! with one scan) paced so the PLC's clock follows the wall clock.
//!
//! The loop runs a period whenever the PLC's time is not ahead of the wall
//! clock and sleeps otherwise. If it falls more than [`MAX_LAG`] behind (a
//! busy machine, a suspended process), it does not race through the backlog
//! — a burst of scans would make timers and pulse outputs jump — but skips
//! it, and counts the time skipped in `GET /api/status`.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use ecam_plc::sim::{self, RunLength};

use crate::state::{Event, Shared, lock};

/// Largest lag the loop catches up by running scans back to back.
pub const MAX_LAG: Duration = Duration::from_millis(200);

/// What the loop does next.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step {
    /// The PLC is ahead: sleep this long.
    Wait(Duration),
    /// Run one scan period now.
    Run,
    /// Too far behind: move the clock's origin on by this much, then run.
    Skip(Duration),
}

/// The next step when `elapsed` wall time and `simulated` PLC time have
/// passed since the loop's origin.
pub fn next_step(elapsed: Duration, simulated: Duration, max_lag: Duration) -> Step {
    if simulated > elapsed {
        Step::Wait(simulated - elapsed)
    } else if elapsed - simulated > max_lag {
        Step::Skip(elapsed - simulated)
    } else {
        Step::Run
    }
}

/// Clears `Stats::scanning` when the loop ends, however it ends.
struct Scanning<'a>(&'a AtomicBool);

impl Drop for Scanning<'_> {
    fn drop(&mut self) {
        self.0.store(false, Ordering::Relaxed);
    }
}

/// Runs the PLC on the calling thread until `stop` is set.
pub fn scan_loop(shared: &Shared, stop: &AtomicBool) {
    shared.stats.scanning.store(true, Ordering::Relaxed);
    let _scanning = Scanning(&shared.stats.scanning);
    let mut origin = Instant::now();
    let start_us = shared.with_plc(|plc| plc.now_us());
    while !stop.load(Ordering::Relaxed) {
        let simulated =
            Duration::from_micros(shared.with_plc(|plc| plc.now_us()).saturating_sub(start_us));
        match next_step(origin.elapsed(), simulated, MAX_LAG) {
            Step::Wait(duration) => {
                shared.stats.lag_us.store(0, Ordering::Relaxed);
                // Short naps keep `stop` responsive with long scan periods.
                std::thread::sleep(duration.min(Duration::from_millis(50)));
            }
            Step::Skip(behind) => {
                origin += behind;
                let us = u64::try_from(behind.as_micros()).unwrap_or(u64::MAX);
                shared.stats.skipped_us.fetch_add(us, Ordering::Relaxed);
            }
            Step::Run => {
                let behind = origin.elapsed().saturating_sub(simulated);
                let us = u64::try_from(behind.as_micros()).unwrap_or(u64::MAX);
                shared.stats.lag_us.store(us, Ordering::Relaxed);
                scan_period(shared);
            }
        }
    }
}

/// Ticks of a fieldbus cycle that paces the PLC (`ecam serve
/// --ethercat`): the cycle counts one per cycle whose frame came back and
/// wakes the PLC's thread; nothing blocks the cycle.
#[derive(Debug, Default)]
pub struct BusTicks {
    pending: std::sync::atomic::AtomicU64,
    thread: std::sync::OnceLock<std::thread::Thread>,
}

impl BusTicks {
    /// No ticks yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// One bus cycle done (the cycle's thread): wakes the PLC.
    pub fn tick(&self) {
        self.pending.fetch_add(1, Ordering::Release);
        if let Some(thread) = self.thread.get() {
            thread.unpark();
        }
    }
}

/// Runs the PLC on the calling thread, `scans` scan periods per bus tick,
/// until `stop`: `before` runs before each tick's scans (relays from the
/// line's state), `after` after them (publishing the pulse totals). Ticks
/// that pile up while the PLC is slow are all run: the PLC's clock stays
/// the bus's.
pub fn scan_on_bus_ticks(
    shared: &Shared,
    ticks: &BusTicks,
    scans: u32,
    stop: &AtomicBool,
    mut before: impl FnMut(&Shared),
    mut after: impl FnMut(&Shared),
) {
    let _ = ticks.thread.set(std::thread::current());
    shared.stats.scanning.store(true, Ordering::Relaxed);
    let _scanning = Scanning(&shared.stats.scanning);
    while !stop.load(Ordering::Relaxed) {
        let pending = ticks.pending.swap(0, Ordering::Acquire);
        if pending == 0 {
            std::thread::park_timeout(Duration::from_millis(50));
            continue;
        }
        for _ in 0..pending {
            before(shared);
            for _ in 0..scans {
                scan_period(shared);
            }
            after(shared);
        }
    }
}

/// Runs one scan period now (one scan, then the hardware ticks covering
/// the scan period), between the clients' writes made since the last one
/// and the publication of the image they read, and reports the operation
/// errors it raised: each is counted and kept as the last one, and each
/// distinct one (by line and code) is reported once as
/// [`Event::OperationError`]. A watchdog stop is reported once as
/// [`Event::ProgramStopped`].
pub fn scan_period(shared: &Shared) {
    let timing = shared.info.timing;
    let (result, fault) = shared.exchange(|plc| {
        let result = sim::run(plc, timing, RunLength::Scans(1), |_| {});
        let fault = plc.fault().map(|f| (f.line(), f.code(), f.to_string()));
        (result, fault)
    });
    if let Some((line, code, text)) = fault {
        if !shared.stats.fault_reported.swap(true, Ordering::Relaxed) {
            let file = shared.info.program.as_deref().unwrap_or("program");
            shared.report(Event::ProgramStopped(format!(
                "{file}:{line}: {text} (D8061={code}, M8061=1)"
            )));
        }
    }
    // The timing was checked non-zero at start and one scan period fits
    // any budget, so `run` cannot fail.
    let errors = result.unwrap_or_default();
    for e in errors {
        shared
            .stats
            .operation_errors
            .fetch_add(1, Ordering::Relaxed);
        let file = shared.info.program.as_deref().unwrap_or("program");
        let text = format!("{file}:{}: {} (D8067={})", e.line, e.error, e.error.code);
        // Like `ecam plc run`: each distinct error once on stderr.
        if lock(&shared.stats.reported_errors).insert((e.line, e.error.code)) {
            shared.report(Event::OperationError(text.clone()));
        }
        *lock(&shared.stats.last_operation_error) = Some(text);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use super::*;

    const MS: fn(u64) -> Duration = Duration::from_millis;

    #[test]
    fn waits_while_ahead_runs_while_behind() {
        assert_eq!(next_step(MS(10), MS(12), MAX_LAG), Step::Wait(MS(2)));
        assert_eq!(next_step(MS(10), MS(10), MAX_LAG), Step::Run);
        assert_eq!(next_step(MS(10), MS(9), MAX_LAG), Step::Run);
        assert_eq!(next_step(MS(300), MS(100), MAX_LAG), Step::Run);
    }

    #[test]
    fn skips_a_backlog_over_the_limit() {
        assert_eq!(next_step(MS(1000), MS(10), MAX_LAG), Step::Skip(MS(990)));
    }

    #[test]
    fn each_distinct_operation_error_is_reported_once() {
        use crate::state::ServeInfo;
        use std::sync::{Arc, Mutex};

        // PLSY with a negative frequency: operation error 6705 every scan.
        let source = "LD M8000\nPLSY K-5 K10 Y0\n";
        let plc = ecam_plc::Plc::new(ecam_plc::Program::parse(source, "op.il").unwrap()).unwrap();
        let addr = "127.0.0.1:0".parse().unwrap();
        let info = ServeInfo {
            program: Some("op.il".into()),
            timing: ecam_plc::sim::Timing::default(),
            modbus: addr,
            http: addr,
            state_dir: None,
            limits: Default::default(),
        };
        let heard = Arc::new(Mutex::new(Vec::new()));
        let sink = Arc::clone(&heard);
        let shared = Shared::new(plc, None, info, move |event| {
            if let Event::OperationError(text) = event {
                sink.lock().unwrap().push(text);
            }
        });
        for _ in 0..3 {
            scan_period(&shared);
        }
        let heard = heard.lock().unwrap();
        assert_eq!(heard.len(), 1, "{heard:?}");
        assert!(
            heard[0].starts_with("op.il:2: operation error 6705"),
            "{heard:?}"
        );
        assert!(heard[0].ends_with("(D8067=6705)"), "{heard:?}");
        assert_eq!(shared.stats.operation_errors.load(Ordering::Relaxed), 3);
        assert_eq!(
            lock(&shared.stats.last_operation_error).as_deref(),
            Some(heard[0].as_str())
        );
    }
}
