//! The one cycle driver: the real-time thread both `ecam ethercat run`
//! (cams on drives) and `ecam serve --ethercat` (drives following the
//! PLC's pulse outputs) use.
//!
//! Each cycle, on absolute deadlines steered to the drives' SYNC0
//! ([`crate::dc`]): take the queued commands, run the line's cycle (its
//! exchange sends and receives the frame on this thread), count lost and
//! late replies, publish the status ([`crate::monitor`]), then spend what
//! is left of the cycle on at most one acyclic step (diagnosing a drive
//! that left OP, bringing drives back after a reset). Nothing in the loop
//! prints, allocates or takes a lock another thread holds (the fault log
//! has a fixed capacity; reading the emulation for an injected fault and
//! bringing a whole segment up again after a reset are the exceptions,
//! both outside running motion).
//!
//! The end is one rule for both commands: a stop (the cycle count
//! reached, Ctrl-C, SIGTERM, a server ending) decelerates the line to
//! rest, the drives are disabled, and [`GOODBYE_CYCLES`] more cycles make
//! sure they heard it.

use std::sync::atomic::{AtomicI64, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::thread::{self, JoinHandle};
use std::time::Duration;

use ecam_core::CamCurve;
use ecam_engine::drive::AxisDrive;

use crate::dc::Sync0Lock;
use crate::emulation::EmulatedSegment;
use crate::follow::{FollowLine, PULSE_OUTPUTS};
use crate::line::CamLine;
use crate::link::LinkStats;
use crate::monitor::{DriveCell, LineCommand, LineCounters, LineMonitor};
use crate::rt::{CycleClock, LatenessHistogram, RtConfig, RtSetup, configure_current_thread};
use crate::segment::{CycleReport, Segment};
use crate::supervisor::{LineFault, LineState};

/// Cycles the drives are given to hear "disable" before the driver ends.
pub const GOODBYE_CYCLES: u32 = 5;
/// Longest a stop may take beyond its ramp before the drives are disabled
/// regardless.
const STOP_GRACE: Duration = Duration::from_secs(3);
/// Faults the summary keeps (more are counted, not kept).
const FAULT_LOG: usize = 256;
/// A reset by `--recover` waits until frames have flowed this long.
const RECOVER_AFTER: Duration = Duration::from_millis(100);
/// Time kept free at the end of a cycle when an acyclic step runs.
const STEP_MARGIN: Duration = Duration::from_micros(100);

/// An exchange that failed outright (not a lost frame: ethercrab refused
/// the frame). Counted; the cycle goes on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ExchangeFailed;

impl core::fmt::Display for ExchangeFailed {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("the process-data exchange failed")
    }
}

impl std::error::Error for ExchangeFailed {}

/// A line the driver cycles.
pub trait Line {
    /// Where the line is.
    fn state(&self) -> LineState;
    /// The segment.
    fn segment(&self) -> &Segment;
    /// Enable the drives (from stopped).
    fn start(&mut self);
    /// Stop: decelerate to rest, then disable.
    fn stop(&mut self);
    /// Clear the faults; false when the segment could not be brought up
    /// again.
    fn reset(&mut self) -> bool;
    /// One cycle.
    ///
    /// # Errors
    /// The exchange failed outright (counted; the cycle goes on).
    fn cycle(&mut self) -> Result<CycleReport, ExchangeFailed>;
    /// One acyclic step within `budget`.
    fn acyclic_step(&mut self, budget: Duration);
    /// Not moving and not enabled.
    fn at_rest(&self) -> bool;
    /// The faults holding the line.
    fn faults(&self) -> &[LineFault];
    /// The faults first seen in the last cycle.
    fn new_faults(&self) -> &[LineFault];
    /// Codes and emergencies added to reported faults so far
    /// ([`crate::supervisor::Supervisor::annotations`]).
    fn annotations(&self) -> u64;
    /// The target last sent to a drive.
    fn target_of(&self, position: usize) -> i64;
    /// Virtual master position (0 where there is none).
    fn virtual_master(&self) -> i64 {
        0
    }
}

impl<C: CamCurve> Line for CamLine<C> {
    fn state(&self) -> LineState {
        CamLine::state(self)
    }
    fn segment(&self) -> &Segment {
        CamLine::segment(self)
    }
    fn start(&mut self) {
        let _ = CamLine::start(self);
    }
    fn stop(&mut self) {
        CamLine::stop(self);
    }
    fn reset(&mut self) -> bool {
        !matches!(CamLine::reset(self), Err(crate::line::LineError::Bus(_)))
    }
    fn cycle(&mut self) -> Result<CycleReport, ExchangeFailed> {
        CamLine::cycle(self)
            .map(|r| r.bus)
            .map_err(|_| ExchangeFailed)
    }
    fn acyclic_step(&mut self, budget: Duration) {
        CamLine::acyclic_step(self, budget);
    }
    fn at_rest(&self) -> bool {
        CamLine::at_rest(self)
    }
    fn faults(&self) -> &[LineFault] {
        CamLine::faults(self)
    }
    fn new_faults(&self) -> &[LineFault] {
        CamLine::new_faults(self)
    }
    fn annotations(&self) -> u64 {
        self.supervisor().annotations()
    }
    fn target_of(&self, position: usize) -> i64 {
        self.axes()
            .iter()
            .zip(self.outputs())
            .find(|(a, _)| a.drive == position)
            .map_or_else(
                || {
                    self.segment()
                        .drives()
                        .get(position)
                        .map_or(0, |d| d.actual())
                },
                |(_, out)| out.slave,
            )
    }
    fn virtual_master(&self) -> i64 {
        CamLine::virtual_master(self)
    }
}

/// The pulse totals a PLC publishes for a following line, one per output
/// (written by the PLC's thread, read by the cycle; no lock).
#[derive(Debug, Default)]
pub struct PulseTotals {
    totals: [AtomicI64; PULSE_OUTPUTS as usize],
}

impl PulseTotals {
    /// Totals all zero.
    pub fn new() -> Self {
        Self::default()
    }

    /// Publishes the totals (the PLC's thread).
    pub fn publish(&self, totals: [i64; PULSE_OUTPUTS as usize]) {
        for (slot, v) in self.totals.iter().zip(totals) {
            slot.store(v, Ordering::Release);
        }
    }

    /// The totals last published.
    pub fn read(&self) -> [i64; PULSE_OUTPUTS as usize] {
        std::array::from_fn(|i| self.totals[i].load(Ordering::Acquire))
    }
}

/// Drives following a PLC's outputs, with where the pulse totals come
/// from.
#[derive(Debug)]
pub struct Following {
    /// The line.
    pub line: FollowLine,
    /// The totals the PLC publishes.
    pub pulses: Arc<PulseTotals>,
}

impl Line for Following {
    fn state(&self) -> LineState {
        self.line.state()
    }
    fn segment(&self) -> &Segment {
        self.line.segment()
    }
    fn start(&mut self) {
        let _ = self.line.start();
    }
    fn stop(&mut self) {
        self.line.stop();
    }
    fn reset(&mut self) -> bool {
        !matches!(self.line.reset(), Err(crate::follow::FollowError::Bus(_)))
    }
    fn cycle(&mut self) -> Result<CycleReport, ExchangeFailed> {
        let totals = self.pulses.read();
        self.line
            .cycle(&totals)
            .map(|r| r.bus)
            .map_err(|_| ExchangeFailed)
    }
    fn acyclic_step(&mut self, budget: Duration) {
        self.line.acyclic_step(budget);
    }
    fn at_rest(&self) -> bool {
        self.line.at_rest()
    }
    fn faults(&self) -> &[LineFault] {
        self.line.faults()
    }
    fn new_faults(&self) -> &[LineFault] {
        self.line.new_faults()
    }
    fn annotations(&self) -> u64 {
        self.line.supervisor().annotations()
    }
    fn target_of(&self, position: usize) -> i64 {
        self.line.target_of(position).unwrap_or_else(|| {
            self.line
                .segment()
                .drives()
                .get(position)
                .map_or(0, |d| d.actual())
        })
    }
}

/// How the driver runs.
#[derive(Clone, Debug)]
pub struct DriverConfig {
    /// The cycle thread's period, priority and CPU.
    pub rt: RtConfig,
    /// Stop after this many cycles (`None`: until a stop is asked).
    pub cycles: Option<u64>,
    /// Enable the drives at once.
    pub enable_at_start: bool,
    /// The line's stop time (a stop that takes longer than this and a
    /// grace of three seconds disables the drives regardless).
    pub stop: Duration,
    /// Reset a faulted line by itself once frames flow again, and start
    /// it again when the drives are back (`ecam ethercat run --recover`).
    pub recover: bool,
    /// The emulated segment, for injected faults.
    pub emulation: Option<Arc<Mutex<EmulatedSegment>>>,
}

/// What a finished driver reports.
#[derive(Clone, Debug, Default)]
pub struct Summary {
    /// What scheduling the thread got.
    pub setup: RtSetup,
    /// The counters at the end.
    pub counters: LineCounters,
    /// Wake-up lateness of the run's cycles.
    pub lateness: LatenessHistogram,
    /// The frames' lead before SYNC0.
    pub sync0: Option<Sync0Lock>,
    /// Every fault seen, with the cycle it was seen in.
    pub faults: Vec<(u64, LineFault)>,
    /// Faults seen beyond what the log keeps.
    pub faults_dropped: u64,
    /// Resets the driver made by itself (`recover`).
    pub recoveries: u64,
    /// Cycles of the stop (deceleration, disable, goodbye).
    pub stop_cycles: u64,
    /// The line's state at the end.
    pub state: Option<LineState>,
    /// Each drive's actual position at the end.
    pub actual: Vec<i64>,
    /// The link's counts.
    pub link: LinkStats,
    /// Why the driver ended early (clock failure).
    pub error: Option<String>,
}

fn cells<L: Line>(line: &L) -> impl Iterator<Item = DriveCell> + '_ {
    let segment = line.segment();
    segment
        .drives()
        .iter()
        .zip(segment.al_states())
        .enumerate()
        .map(move |(position, (d, al))| {
            let status = d.status();
            DriveCell {
                state: d.state(),
                statusword: d.inputs().statusword,
                error_code: d.inputs().error_code,
                al_state: *al,
                reachable: d.reachable(),
                enabled: status.enabled,
                missed: d.missed_cycles(),
                actual: status.actual,
                target: line.target_of(position),
                following_error: status.following_error,
            }
        })
}

/// Starts the cycle thread. `after_cycle` runs at the end of every cycle
/// (a PLC paced by the bus is woken there); it must not block.
///
/// # Errors
/// The thread could not be started.
pub fn spawn<L, F>(
    mut line: L,
    config: DriverConfig,
    monitor: Arc<LineMonitor>,
    mut after_cycle: F,
) -> std::io::Result<JoinHandle<Summary>>
where
    L: Line + Send + 'static,
    F: FnMut(&L) + Send + 'static,
{
    thread::Builder::new()
        .name("ecam-ethercat-cycle".into())
        .spawn(move || {
            let mut driver = Driver::new(&line, &config);
            driver.run(&mut line, &config, &monitor, &mut after_cycle);
            driver.summary(&line)
        })
}

/// Runs the cycle on the calling thread (which it configures for real
/// time) until the line has stopped; for lines that cannot move to another
/// thread.
pub fn run_here<L, F>(
    mut line: L,
    config: DriverConfig,
    monitor: &LineMonitor,
    mut after_cycle: F,
) -> Summary
where
    L: Line,
    F: FnMut(&L),
{
    let mut driver = Driver::new(&line, &config);
    driver.run(&mut line, &config, monitor, &mut after_cycle);
    driver.summary(&line)
}

/// The driver's state between cycles.
struct Driver {
    summary: Summary,
    lock: Sync0Lock,
    lost_in_a_row: u64,
    faulted_for: u64,
    flowing_for: u64,
    recover_after: u64,
    recovering: bool,
    /// Where the faults holding the line start in the summary's log.
    episode_start: usize,
    /// The line's annotations the log has taken.
    annotations_seen: u64,
}

impl Driver {
    fn new<L: Line>(line: &L, config: &DriverConfig) -> Self {
        let segment = line.segment().config();
        let cycles = |d: Duration| {
            u64::try_from(d.as_nanos() / config.rt.period.as_nanos().max(1)).unwrap_or(u64::MAX)
        };
        Self {
            summary: Summary {
                faults: Vec::with_capacity(FAULT_LOG),
                ..Summary::default()
            },
            lock: Sync0Lock::new(segment.cycle, segment.sync0_shift),
            lost_in_a_row: 0,
            faulted_for: 0,
            flowing_for: 0,
            recover_after: cycles(RECOVER_AFTER).max(1),
            recovering: false,
            episode_start: 0,
            annotations_seen: 0,
        }
    }

    fn run<L: Line, F: FnMut(&L)>(
        &mut self,
        line: &mut L,
        config: &DriverConfig,
        monitor: &LineMonitor,
        after_cycle: &mut F,
    ) {
        self.summary.setup = configure_current_thread(&config.rt);
        monitor.set_scheduling(self.summary.setup.to_string());
        let mut clock = match CycleClock::start(config.rt.period) {
            Ok(clock) => clock,
            Err(e) => {
                self.summary.error = Some(format!("monotonic clock: {e}"));
                return;
            }
        };
        if config.enable_at_start {
            line.start();
        }
        let mut stopping: Option<u64> = None;
        let mut goodbye = GOODBYE_CYCLES;
        let stop_limit = u64::try_from(
            (config.stop + STOP_GRACE).as_nanos() / config.rt.period.as_nanos().max(1),
        )
        .unwrap_or(u64::MAX);
        loop {
            if stopping.is_none() {
                let done = config
                    .cycles
                    .is_some_and(|n| self.summary.counters.cycles >= n);
                if done || monitor.stop_requested() {
                    line.stop();
                    stopping = Some(0);
                }
            }
            let mut scratch = LatenessHistogram::default();
            let lateness = if stopping.is_none() {
                &mut self.summary.lateness
            } else {
                &mut scratch
            };
            if let Err(e) = clock.wait(lateness) {
                self.summary.error = Some(format!("clock_nanosleep: {e}"));
                break;
            }
            match &mut stopping {
                None => self.obey(line, config, monitor, &mut clock),
                Some(n) => {
                    *n += 1;
                    self.summary.stop_cycles += 1;
                    if *n > stop_limit && !line.at_rest() {
                        // The ramp took too long: disable regardless.
                        line.stop();
                    }
                }
            }
            self.cycle(line, stopping.is_none(), &mut clock);
            if stopping.is_none() && config.recover {
                self.recover(line, &mut clock);
            }
            let c = &mut self.summary.counters;
            c.lateness_max_ns =
                u64::try_from(self.summary.lateness.max.as_nanos()).unwrap_or(u64::MAX);
            c.lateness_mean_ns =
                u64::try_from(self.summary.lateness.mean().as_nanos()).unwrap_or(u64::MAX);
            c.overruns = self.summary.lateness.overruns;
            c.virtual_master = line.virtual_master();
            monitor.publish(
                line.state(),
                c,
                cells(line),
                line.faults(),
                self.summary.faults_dropped + self.summary.faults.len() as u64,
            );
            after_cycle(line);
            let left = clock.until_next().saturating_sub(STEP_MARGIN);
            if !left.is_zero() {
                line.acyclic_step(left);
            }
            if stopping.is_some() && line.at_rest() {
                if goodbye == 0 {
                    break;
                }
                goodbye -= 1;
            }
        }
    }

    /// Takes the queued commands (a few per cycle).
    fn obey<L: Line>(
        &mut self,
        line: &mut L,
        config: &DriverConfig,
        monitor: &LineMonitor,
        clock: &mut CycleClock,
    ) {
        for _ in 0..4 {
            let Some(command) = monitor.take_command() else {
                return;
            };
            match command {
                LineCommand::Enable => line.start(),
                LineCommand::Disable => line.stop(),
                LineCommand::Reset => {
                    if line.state() == LineState::Faulted {
                        line.reset();
                        // Bringing the segment up again blocks; the clock
                        // starts afresh rather than count it as overruns.
                        clock.restart();
                    }
                }
                LineCommand::InjectFault { drive, code } => {
                    if let Some(emulation) = &config.emulation {
                        let mut segment = emulation.lock().unwrap_or_else(PoisonError::into_inner);
                        if let Some(esc) = segment.esc_mut(drive) {
                            esc.drive_mut().inject_fault(code);
                        }
                    }
                }
            }
        }
    }

    fn cycle<L: Line>(&mut self, line: &mut L, running: bool, clock: &mut CycleClock) {
        let report = line.cycle();
        let c = &mut self.summary.counters;
        if running {
            c.cycles += 1;
        }
        match report {
            Ok(bus) => {
                if bus.frame_lost {
                    c.lost_cycles += 1;
                    self.lost_in_a_row += 1;
                    c.lost_in_a_row_max = c.lost_in_a_row_max.max(self.lost_in_a_row);
                } else {
                    self.lost_in_a_row = 0;
                    let measure = line.state() == LineState::Running;
                    clock.shift(self.lock.step(bus.dc_system_time, measure));
                    c.sync0_lead_ns = self.lock.lead(bus.dc_system_time);
                }
                if bus.working_counter_error() {
                    c.working_counter_errors += 1;
                }
            }
            Err(ExchangeFailed) => c.exchange_errors += 1,
        }
        c.late_replies = line.segment().link_stats().late_discarded;
        let cycle = c.cycles;
        if line.faults().is_empty() {
            self.episode_start = self.summary.faults.len();
        }
        for &fault in line.new_faults() {
            if self.summary.faults.len() < FAULT_LOG {
                self.summary.faults.push((cycle, fault));
            } else {
                self.summary.faults_dropped += 1;
            }
        }
        self.take_annotations(line);
    }

    /// A fault's AL status code or emergency arrives cycles after the
    /// fault: the log takes them from the line's faults.
    fn take_annotations<L: Line>(&mut self, line: &L) {
        let annotations = line.annotations();
        if annotations == self.annotations_seen {
            return;
        }
        self.annotations_seen = annotations;
        let start = self.episode_start.min(self.summary.faults.len());
        for (_, logged) in &mut self.summary.faults[start..] {
            if let Some(now) = line.faults().iter().find(|f| {
                f.drive == logged.drive
                    && core::mem::discriminant(&f.cause) == core::mem::discriminant(&logged.cause)
            }) {
                *logged = *now;
            }
        }
    }

    /// `recover`: a faulted line is reset once frames have flowed for
    /// [`RECOVER_AFTER`] (so the drives' real states are known), and
    /// started again once the drives are back.
    fn recover<L: Line>(&mut self, line: &mut L, clock: &mut CycleClock) {
        let flowing = line
            .segment()
            .drives()
            .iter()
            .all(|d| d.missed_cycles() == 0);
        self.flowing_for = if flowing { self.flowing_for + 1 } else { 0 };
        match line.state() {
            LineState::Faulted => {
                self.faulted_for += 1;
                if self.flowing_for > self.recover_after
                    || self.faulted_for > 10 * self.recover_after
                {
                    self.faulted_for = 0;
                    if line.reset() {
                        self.summary.recoveries += 1;
                        self.recovering = true;
                    }
                    clock.restart();
                }
            }
            LineState::Stopped if self.recovering => {
                self.recovering = false;
                line.start();
            }
            _ => self.faulted_for = 0,
        }
    }

    fn summary<L: Line>(mut self, line: &L) -> Summary {
        self.take_annotations(line);
        self.summary.state = Some(line.state());
        self.summary.actual = line.segment().drives().iter().map(|d| d.actual()).collect();
        self.summary.link = line.segment().link_stats();
        self.summary.counters.late_replies = self.summary.link.late_discarded;
        self.summary.sync0 = Some(self.lock);
        self.summary
    }
}
