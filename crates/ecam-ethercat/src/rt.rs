//! The real-time cycle: a thread that wakes on absolute deadlines
//! (`clock_nanosleep` with `TIMER_ABSTIME` on `CLOCK_MONOTONIC`, so errors
//! never accumulate), asks for `SCHED_FIFO` and a CPU of its own where the
//! system permits, and records how late each wake-up was.

use std::ops::ControlFlow;
use std::thread::{self, JoinHandle};
use std::time::Duration;

use nix::sched::{CpuSet, sched_setaffinity};
use nix::sys::time::TimeSpec;
use nix::time::{ClockId, ClockNanosleepFlags, clock_gettime, clock_nanosleep};
use nix::unistd::Pid;
use thread_priority::{
    RealtimeThreadSchedulePolicy, ThreadPriority, ThreadPriorityValue, ThreadSchedulePolicy,
    set_thread_priority_and_policy, thread_native_id,
};

/// How the cycle thread runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RtConfig {
    /// Cycle period.
    pub period: Duration,
    /// `SCHED_FIFO` priority 1–99 (`None`: keep the normal scheduler).
    pub fifo_priority: Option<u8>,
    /// CPU to pin the thread to (`None`: any).
    pub cpu: Option<usize>,
}

impl Default for RtConfig {
    fn default() -> Self {
        Self {
            period: Duration::from_millis(1),
            fifo_priority: Some(80),
            cpu: None,
        }
    }
}

/// What the thread got from the system: each request is either granted
/// or refused with the reason (no privilege, no such CPU), and the cycle
/// runs either way.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct RtSetup {
    /// `SCHED_FIFO`: `None` when not asked, else granted or why not.
    pub fifo: Option<Result<u8, String>>,
    /// Pinning: `None` when not asked, else the CPU or why not.
    pub pinned: Option<Result<usize, String>>,
}

impl core::fmt::Display for RtSetup {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match &self.fifo {
            None => f.write_str("normal scheduling")?,
            Some(Ok(p)) => write!(f, "SCHED_FIFO priority {p}")?,
            Some(Err(e)) => write!(f, "SCHED_FIFO refused ({e}), normal scheduling")?,
        }
        match &self.pinned {
            None => Ok(()),
            Some(Ok(cpu)) => write!(f, ", pinned to CPU {cpu}"),
            Some(Err(e)) => write!(f, ", not pinned ({e})"),
        }
    }
}

/// Applies `config` to the calling thread.
pub fn configure_current_thread(config: &RtConfig) -> RtSetup {
    let fifo = config.fifo_priority.map(|priority| {
        let value =
            ThreadPriorityValue::try_from(priority.clamp(1, 99)).map_err(|e| e.to_string())?;
        set_thread_priority_and_policy(
            thread_native_id(),
            ThreadPriority::Crossplatform(value),
            ThreadSchedulePolicy::Realtime(RealtimeThreadSchedulePolicy::Fifo),
        )
        .map(|()| priority.clamp(1, 99))
        .map_err(|e| format!("{e:?}; needs root, CAP_SYS_NICE or an rtprio limit"))
    });
    let pinned = config.cpu.map(|cpu| {
        let mut set = CpuSet::new();
        set.set(cpu).map_err(|e| format!("CPU {cpu}: {e}"))?;
        sched_setaffinity(Pid::from_raw(0), &set)
            .map(|()| cpu)
            .map_err(|e| format!("CPU {cpu}: {e}"))
    });
    RtSetup { fifo, pinned }
}

/// Upper bounds of the lateness buckets, µs (the last bucket is open).
pub const BUCKETS_US: [u64; 10] = [1, 2, 5, 10, 20, 50, 100, 200, 500, 1000];

/// How late the cycle thread woke, bucketed.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LatenessHistogram {
    /// Wake-ups per bucket: `counts[i]` below `BUCKETS_US[i]` µs (and at or
    /// above the previous bound); the last entry counts the rest.
    pub counts: [u64; BUCKETS_US.len() + 1],
    /// Worst lateness.
    pub max: Duration,
    /// Sum of all lateness, for the mean.
    pub total: Duration,
    /// Deadlines missed by more than a whole period (cycles skipped).
    pub overruns: u64,
}

impl LatenessHistogram {
    /// Adds one wake-up.
    pub fn record(&mut self, lateness: Duration) {
        let us = u64::try_from(lateness.as_micros()).unwrap_or(u64::MAX);
        let bucket = BUCKETS_US
            .iter()
            .position(|&b| us < b)
            .unwrap_or(BUCKETS_US.len());
        self.counts[bucket] = self.counts[bucket].saturating_add(1);
        self.max = self.max.max(lateness);
        self.total = self.total.saturating_add(lateness);
    }

    /// Wake-ups recorded.
    pub fn count(&self) -> u64 {
        self.counts.iter().sum()
    }

    /// Mean lateness.
    pub fn mean(&self) -> Duration {
        match u32::try_from(self.count()) {
            Ok(0) => Duration::ZERO,
            Ok(n) => self.total / n,
            Err(_) => Duration::from_nanos(
                u64::try_from(self.total.as_nanos() / u128::from(self.count())).unwrap_or(u64::MAX),
            ),
        }
    }
}

impl core::fmt::Display for LatenessHistogram {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        writeln!(
            f,
            "{} wake-ups, mean {:?}, max {:?}, {} overruns",
            self.count(),
            self.mean(),
            self.max,
            self.overruns
        )?;
        let mut low = 0;
        for (i, count) in self.counts.iter().enumerate() {
            match BUCKETS_US.get(i) {
                Some(high) => writeln!(f, "  {low:>4}–{high:<4} µs {count:>10}")?,
                None => writeln!(f, "  ≥{low:<8} µs {count:>10}")?,
            }
            low = BUCKETS_US.get(i).copied().unwrap_or(low);
        }
        Ok(())
    }
}

/// A clock of absolute deadlines, one period apart.
#[derive(Debug)]
pub struct CycleClock {
    next: Duration,
    period: Duration,
}

impl CycleClock {
    /// Starts with the first deadline one period from now.
    pub fn start(period: Duration) -> nix::Result<Self> {
        let now = monotonic()?;
        Ok(Self {
            next: now + period,
            period,
        })
    }

    /// Sleeps until the next deadline and returns how late the wake-up
    /// was. A deadline already missed by more than a period is not caught
    /// up cycle by cycle: the clock skips to the next deadline ahead and
    /// records an overrun.
    pub fn wait(&mut self, histogram: &mut LatenessHistogram) -> nix::Result<Duration> {
        let deadline = TimeSpec::from_duration(self.next);
        loop {
            match clock_nanosleep(
                ClockId::CLOCK_MONOTONIC,
                ClockNanosleepFlags::TIMER_ABSTIME,
                &deadline,
            ) {
                Ok(_) => break,
                Err(nix::errno::Errno::EINTR) => continue,
                Err(e) => return Err(e),
            }
        }
        let now = monotonic()?;
        let lateness = now.saturating_sub(self.next);
        histogram.record(lateness);
        self.next += self.period;
        if now > self.next {
            let behind = now - self.next;
            let skipped = behind.as_nanos() / self.period.as_nanos().max(1) + 1;
            histogram.overruns = histogram
                .overruns
                .saturating_add(u64::try_from(skipped).unwrap_or(u64::MAX));
            self.next += self.period * u32::try_from(skipped).unwrap_or(u32::MAX);
        }
        Ok(lateness)
    }
}

impl CycleClock {
    /// Moves the next deadline by `ns` (positive: later); the distributed
    /// clock lock steers the cycle with it.
    pub fn shift(&mut self, ns: i64) {
        let by = Duration::from_nanos(ns.unsigned_abs());
        self.next = if ns >= 0 {
            self.next.saturating_add(by)
        } else {
            self.next.saturating_sub(by)
        };
    }

    /// Time left until the next deadline (zero when it has passed).
    pub fn until_next(&self) -> Duration {
        monotonic().map_or(Duration::ZERO, |now| self.next.saturating_sub(now))
    }

    /// Starts afresh one period from now (after a blocking step such as
    /// bringing the segment up again), without counting overruns.
    pub fn restart(&mut self) {
        if let Ok(now) = monotonic() {
            self.next = now + self.period;
        }
    }
}

fn monotonic() -> nix::Result<Duration> {
    let t = clock_gettime(ClockId::CLOCK_MONOTONIC)?;
    Ok(Duration::from(t))
}

/// What a finished cycle thread reports.
#[derive(Clone, Debug, Default)]
pub struct RtReport {
    /// What scheduling the thread got.
    pub setup: RtSetup,
    /// Wake-up lateness.
    pub lateness: LatenessHistogram,
    /// Cycles run.
    pub cycles: u64,
    /// Why the thread ended early (clock failure).
    pub error: Option<String>,
}

/// Starts the cycle thread: configures it, then calls `body` once per
/// period with the cycle number until it returns `Break`.
pub fn spawn<F>(config: RtConfig, mut body: F) -> std::io::Result<JoinHandle<RtReport>>
where
    F: FnMut(u64) -> ControlFlow<()> + Send + 'static,
{
    thread::Builder::new()
        .name("ecam-cycle".into())
        .spawn(move || {
            let mut report = RtReport {
                setup: configure_current_thread(&config),
                ..RtReport::default()
            };
            let mut clock = match CycleClock::start(config.period) {
                Ok(clock) => clock,
                Err(e) => {
                    report.error = Some(format!("monotonic clock: {e}"));
                    return report;
                }
            };
            loop {
                if let Err(e) = clock.wait(&mut report.lateness) {
                    report.error = Some(format!("clock_nanosleep: {e}"));
                    return report;
                }
                let cycle = report.cycles;
                report.cycles = report.cycles.saturating_add(1);
                if body(cycle).is_break() {
                    return report;
                }
            }
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histogram_buckets() {
        let mut h = LatenessHistogram::default();
        h.record(Duration::from_nanos(500));
        h.record(Duration::from_micros(7));
        h.record(Duration::from_micros(5000));
        assert_eq!(h.counts[0], 1);
        assert_eq!(h.counts[3], 1);
        assert_eq!(h.counts[10], 1);
        assert_eq!(h.count(), 3);
        assert_eq!(h.max, Duration::from_micros(5000));
        assert!(h.to_string().contains("3 wake-ups"));
    }

    #[test]
    fn thread_runs_the_requested_cycles_and_reports() {
        let config = RtConfig {
            period: Duration::from_micros(500),
            fifo_priority: None,
            cpu: Some(0),
        };
        let handle = spawn(config, |cycle| {
            if cycle + 1 >= 100 {
                ControlFlow::Break(())
            } else {
                ControlFlow::Continue(())
            }
        })
        .unwrap();
        let report = handle.join().unwrap();
        assert_eq!(report.cycles, 100);
        assert_eq!(report.lateness.count(), 100);
        assert!(report.error.is_none());
        assert!(report.setup.fifo.is_none());
        assert!(report.setup.pinned.is_some());
    }
}
