//! One cam axis: the tick that runs every step in order.
//!
//! Per tick: master (unwrap) → start (arm, edge, delay, position,
//! breakpoint) → coupling (exact cycle, zoom, offsets; ramp-in; one-shot end;
//! end-of-cycle stop) → pulses (frequency limit, backlog) → sync windows →
//! output. No step allocates or loops over anything but the four sync
//! windows; the curve lookup is O(1) through the cursor while the master
//! moves continuously.

use ecam_core::{CamCurve, Cursor};

use crate::config::effective_frequency;
use crate::coupling::{Engagement, Geometry, Place, Sample};
use crate::master::TurnUnwrap;
use crate::pulse::PulseOutput;
use crate::ramp::Ramp;
use crate::start::{StartStep, StartWatch};
use crate::stop::{CycleEnd, StopAt};
use crate::sync::active_windows;
use crate::{
    AxisConfig, AxisState, EngineError, Events, MasterTracker, StopKind, SyncWindow, TickInput,
    TickOutput,
};

/// A slave axis coupled to a master through a cam curve.
///
/// The caller owns the loop: call [`CamAxis::tick`] once per control cycle
/// with the master reading; it returns everything the cycle produced. Build
/// it once; nothing allocates afterwards.
#[derive(Clone, Debug)]
pub struct CamAxis<C> {
    curve: C,
    config: AxisConfig,
    geometry: Geometry,
    cursor: Cursor,
    state: AxisState,
    start: Option<StartWatch>,
    engagement: Option<Engagement>,
    ramp: Option<Ramp>,
    cycle_end: Option<CycleEnd>,
    turn: Option<TurnUnwrap>,
    tracker: MasterTracker,
    /// The last unwrapped reading (for the master-step guard).
    last_reading: Option<i64>,
    /// A table waiting for the next seam ([`CamAxis::queue_curve`]).
    pending: Option<C>,
    /// What the axis does after the waiting table's first pass.
    pending_then: AfterPass,
    /// The table a switch replaced, for the caller to take back
    /// ([`CamAxis::take_retired_curve`]): dropping it inside `tick` would
    /// free memory in the control cycle.
    retired: Option<C>,
    commanded: i64,
    pulse: PulseOutput,
    last_master: Option<i64>,
    last_start_input: bool,
    last_place: Option<Place>,
    /// Events of a stop that took effect between ticks, reported by the next tick.
    pending_events: Events,
    last: TickOutput,
}

impl<C: CamCurve> CamAxis<C> {
    /// An idle axis with the slave at 0.
    ///
    /// # Errors
    /// The curve does not fit the configuration: [`EngineError::EmptyCycle`],
    /// [`EngineError::BadTurn`], [`EngineError::TableOutsideTurn`].
    pub fn new(curve: C, config: AxisConfig) -> Result<Self, EngineError> {
        let geometry = Geometry::new(&curve, &config)?;
        Ok(Self {
            curve,
            config,
            geometry,
            cursor: Cursor::new(),
            state: AxisState::Idle,
            start: None,
            engagement: None,
            ramp: None,
            cycle_end: None,
            turn: config.single_turn.map(TurnUnwrap::new),
            tracker: MasterTracker::new(config.master_filter),
            last_reading: None,
            pending: None,
            pending_then: AfterPass::Repeat,
            retired: None,
            commanded: 0,
            pulse: PulseOutput::at(0),
            last_master: None,
            last_start_input: false,
            last_place: None,
            pending_events: Events::default(),
            last: TickOutput {
                direction_forward: true,
                ..TickOutput::default()
            },
        })
    }

    /// The configuration in use.
    pub fn config(&self) -> &AxisConfig {
        &self.config
    }

    /// The cam curve in use.
    pub fn curve(&self) -> &C {
        &self.curve
    }

    /// The current state.
    pub fn state(&self) -> AxisState {
        self.state
    }

    /// The commanded slave position now.
    pub fn commanded(&self) -> i64 {
        self.commanded
    }

    /// The output of the last tick.
    pub fn status(&self) -> &TickOutput {
        &self.last
    }

    fn ensure_inactive(&self) -> Result<(), EngineError> {
        if self.state.is_active() {
            Err(EngineError::Busy)
        } else {
            Ok(())
        }
    }

    /// Replaces the configuration.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while armed or running (the running cam is
    /// left untouched); otherwise as [`CamAxis::new`].
    pub fn set_config(&mut self, config: AxisConfig) -> Result<(), EngineError> {
        self.ensure_inactive()?;
        let geometry = Geometry::new(&self.curve, &config)?;
        if config.single_turn != self.config.single_turn {
            self.turn = config.single_turn.map(TurnUnwrap::new);
            self.last_master = None;
            self.last_reading = None;
            self.tracker.reset();
        }
        if config.master_filter != self.config.master_filter {
            self.tracker = MasterTracker::new(config.master_filter);
        }
        self.config = config;
        self.geometry = geometry;
        Ok(())
    }

    /// Replaces the cam curve and gives the old one back.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while armed or running; otherwise as
    /// [`CamAxis::new`] (the old curve stays in place).
    pub fn replace_curve(&mut self, curve: C) -> Result<C, EngineError> {
        self.ensure_inactive()?;
        self.geometry = Geometry::new(&curve, &self.config)?;
        self.cursor = Cursor::new();
        Ok(core::mem::replace(&mut self.curve, curve))
    }

    /// Hands a new table to the axis. Idle, armed or finished, it replaces
    /// the table at once. While the cam is engaged it takes over at the next
    /// seam (cycle boundary) the master crosses, in either direction: the
    /// new table's cycle starts there and the output continues from the
    /// slave position at the seam, without a step (velocity is continuous
    /// when the tables' slopes agree at the seam). A second call before the
    /// seam replaces the waiting table. After the switch the old table can
    /// be taken back with [`CamAxis::take_retired_curve`].
    ///
    /// # Errors
    /// As [`CamAxis::new`] for a table that does not fit the configuration,
    /// and [`EngineError::NoSeam`] for an engaged normal (non-repeating)
    /// cam; the running cam is left untouched.
    pub fn queue_curve(&mut self, curve: C) -> Result<(), EngineError> {
        self.queue_curve_then(curve, AfterPass::Repeat)
    }

    /// As [`CamAxis::queue_curve`], and says what follows the new table's
    /// first pass: with [`AfterPass::Finish`] the axis runs the table once
    /// from the seam and finishes at its end (the PLC's midCAMend table,
    /// which ends at standstill). Idle or armed, `then` is ignored: the
    /// configuration's coupling decides.
    ///
    /// # Errors
    /// As [`CamAxis::queue_curve`].
    pub fn queue_curve_then(&mut self, curve: C, then: AfterPass) -> Result<(), EngineError> {
        let geometry = Geometry::new(&curve, &self.config)?;
        if !self.state.is_engaged() {
            self.geometry = geometry;
            self.cursor = Cursor::new();
            self.pending = None;
            self.retired = Some(core::mem::replace(&mut self.curve, curve));
            return Ok(());
        }
        if geometry.extent == crate::coupling::Extent::Single {
            return Err(EngineError::NoSeam);
        }
        self.pending = Some(curve);
        self.pending_then = then;
        Ok(())
    }

    /// True while a queued table waits for the next seam.
    pub fn has_queued_curve(&self) -> bool {
        self.pending.is_some()
    }

    /// The table the last switch or replacement retired, if not yet taken.
    pub fn take_retired_curve(&mut self) -> Option<C> {
        self.retired.take()
    }

    /// Changes the sync windows; allowed while running (document 003
    /// function register 4 may change during execution).
    pub fn set_sync_windows(&mut self, windows: [SyncWindow; 4]) {
        self.config.sync_windows = windows;
    }

    /// Changes the pulse frequency limit; allowed while running.
    pub fn set_max_frequency(&mut self, hz: i64) {
        self.config.max_frequency_hz = hz;
    }

    /// Declares where the slave output stands now (commanded and emitted):
    /// no pulses are sent for it.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while armed or running.
    pub fn set_slave_position(&mut self, position: i64) -> Result<(), EngineError> {
        self.ensure_inactive()?;
        self.commanded = position;
        let forward = self.pulse.forward;
        self.pulse = PulseOutput::at(position);
        self.pulse.forward = forward;
        self.last.slave = position;
        self.last.emitted = position;
        self.last.backlog = 0;
        self.last.pulse_delayed = false;
        Ok(())
    }

    /// Accepts the emitted position as the commanded one, dropping the
    /// backlog (e.g. after the output was inhibited). While a cam is
    /// engaged the next tick commands the cam again.
    pub fn discard_backlog(&mut self) {
        self.commanded = self.pulse.emitted;
    }

    /// Waits for the start condition of [`AxisConfig::start`]. Arming an
    /// armed axis changes nothing; a finished axis can be armed again.
    ///
    /// # Errors
    /// [`EngineError::Busy`] while the cam is engaged.
    pub fn arm(&mut self) -> Result<(), EngineError> {
        match self.state {
            AxisState::Running | AxisState::Stopping => Err(EngineError::Busy),
            AxisState::Armed | AxisState::Delaying => Ok(()),
            AxisState::Idle | AxisState::Finished => {
                self.start = Some(StartWatch::arm(self.config.start));
                // Delays and position crossings count from the first tick
                // after arming, not from master motion before it.
                self.last_master = None;
                self.state = AxisState::Armed;
                Ok(())
            }
        }
    }

    /// Stops the cam. [`StopKind::Immediate`] holds the slave where it is
    /// and goes idle; [`StopKind::EndOfCycle`] keeps following to the end of
    /// the current cycle (either direction), or, requested while the master
    /// is exactly on a cycle end, finishes there at once. Either cancels a
    /// pending start. The next tick reports what a stop here did.
    pub fn stop(&mut self, kind: StopKind) {
        match (self.state, kind) {
            (AxisState::Running, StopKind::EndOfCycle) => {
                // Engaging records the place, so a running axis always has
                // one; without it there is no cycle to finish, and the stop
                // must still happen rather than be lost.
                let at = self.last_place.map_or(
                    StopAt::Here {
                        completes_cycle: false,
                    },
                    |place| CycleEnd::of(&self.geometry, place),
                );
                match at {
                    StopAt::Ahead(end) => {
                        self.cycle_end = Some(end);
                        self.state = AxisState::Stopping;
                    }
                    StopAt::Here { completes_cycle } => {
                        self.halt();
                        self.state = AxisState::Finished;
                        self.pending_events.stopped = true;
                        self.pending_events.cycle_completed |= completes_cycle;
                    }
                }
            }
            (AxisState::Stopping, StopKind::EndOfCycle) => {}
            (state, _) if state.is_active() => {
                self.halt();
                self.pending_events.stopped = true;
            }
            _ => {}
        }
    }

    /// Stops immediately and cancels any pending start.
    pub fn disengage(&mut self) {
        self.stop(StopKind::Immediate);
    }

    fn halt(&mut self) {
        if let Some(curve) = self.pending.take() {
            // A stop ends the run: the waiting table is the one to restart with.
            if let Ok(geometry) = Geometry::new(&curve, &self.config) {
                self.geometry = geometry;
                self.cursor = Cursor::new();
                self.retired = Some(core::mem::replace(&mut self.curve, curve));
            }
        }
        self.state = AxisState::Idle;
        self.start = None;
        self.engagement = None;
        self.ramp = None;
        self.cycle_end = None;
    }

    /// One control cycle. Never allocates, never panics; O(1) while the
    /// master moves continuously (a jump costs one binary search).
    #[must_use = "the tick's output holds the pulses to emit"]
    pub fn tick(&mut self, input: &TickInput) -> TickOutput {
        let reading = match &mut self.turn {
            Some(turn) => turn.update(input.master),
            None => input.master,
        };
        let step = self.last_reading.map_or(0, |last| reading.abs_diff(last));
        self.last_reading = Some(reading);
        let estimate = self
            .tracker
            .update(reading, input.master_fraction, input.dt_us);
        let master = estimate.counts;
        let previous = self.last_master.unwrap_or(master);
        self.last_master = Some(master);
        let edge = input.start_input && !self.last_start_input;
        self.last_start_input = input.start_input;

        let mut events = core::mem::take(&mut self.pending_events);
        let mut fault = None;
        let mut sample = None;

        if !input.output_enabled && self.state.is_active() {
            self.halt();
            events.stopped = true;
        }

        if self.state.is_active()
            && self
                .config
                .max_master_step
                .is_some_and(|limit| step > limit.get())
        {
            fault = Some(EngineError::MasterStep);
            self.halt();
            events.stopped = true;
        }

        if matches!(self.state, AxisState::Armed | AxisState::Delaying)
            && let Some(start) = &mut self.start
        {
            match start.step(previous, master, edge, input.watch) {
                StartStep::Waiting => {}
                StartStep::Delaying => self.state = AxisState::Delaying,
                StartStep::Engage(at) => match self.engage(at) {
                    Ok(()) => events.engaged = true,
                    Err(e) => {
                        fault = Some(e);
                        self.halt();
                        events.stopped = true;
                    }
                },
            }
        }

        if self.state.is_engaged() {
            match self.follow(master, estimate.fraction, &mut events) {
                Ok(s) => sample = Some(s),
                Err(e) => {
                    fault = Some(e);
                    self.halt();
                    events.stopped = true;
                }
            }
        }

        let hz = effective_frequency(self.config.max_frequency_hz);
        let pulses = self
            .pulse
            .step(self.commanded, input.output_enabled, hz, input.dt_us);
        self.report(master, sample, pulses, events, fault)
    }

    fn engage(&mut self, at: i64) -> Result<(), EngineError> {
        let engagement = Engagement::new(
            &self.geometry,
            &self.config,
            &self.curve,
            &mut self.cursor,
            at,
            self.commanded,
        )?;
        self.last_place = Some(
            self.geometry
                .locate(engagement.table_input(&self.geometry, at)),
        );
        self.engagement = Some(engagement);
        self.ramp = self
            .config
            .ramp_in
            .map(|ramp| Ramp::new(ramp, at, self.commanded));
        self.cycle_end = None;
        self.start = None;
        self.state = AxisState::Running;
        Ok(())
    }

    /// Where the cam stands for `master`: the place (clamped to a one-shot's
    /// span or to the end of a requested end-of-cycle stop), whether a
    /// one-shot finished, and whether the stop was reached (and forwards).
    fn resolve(&self, engagement: &Engagement, master: i64) -> Resolved {
        let geo = &self.geometry;
        let t = engagement.table_input(geo, master);
        let mut finished = false;
        let t = match engagement.span {
            Some((_, end)) if t >= end => {
                finished = true;
                end
            }
            Some((begin, _)) => t.max(begin),
            None => t,
        };
        let mut place = geo.locate(t);
        let mut stopped = None;
        if self.state == AxisState::Stopping
            && let Some(end) = self.cycle_end
            && let Some((at, forward)) = end.reached(geo, t)
        {
            place = at;
            stopped = Some(forward);
            finished = false;
        }
        Resolved {
            place,
            finished,
            stopped,
        }
    }

    /// The commanded slave at `place` for `master`, ramp-in included;
    /// returns the cam sample, the commanded position, the velocity ratio
    /// and whether a ramp-in is still blending.
    fn command_at(
        &mut self,
        engagement: &Engagement,
        place: Place,
        master: i64,
    ) -> Result<(Sample, i64, f64, bool), EngineError> {
        let cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
        match self
            .ramp
            .and_then(|ramp| Some((ramp, ramp.blend(master, cam.slave)?)))
        {
            Some((ramp, blended)) => {
                Ok((cam, blended, cam.velocity_ratio * ramp.weight(master), true))
            }
            None => Ok((cam, cam.slave, cam.velocity_ratio, false)),
        }
    }

    /// Takes a queued table over at the seam between `from` and `to` (cycle
    /// indices of the last and this tick's place), if one waits.
    fn switch_at_seam(
        &mut self,
        engagement: Engagement,
        from: Place,
        to: Place,
    ) -> Result<Option<Engagement>, EngineError> {
        if from.k == to.k || self.pending.is_none() {
            return Ok(None);
        }
        let forward = to.k > from.k;
        // The first boundary crossed: the end of the last cycle going
        // forwards, its start going backwards.
        let at_seam = if forward {
            self.geometry.cycle_end(from.k)
        } else {
            Geometry::cycle_start(from.k)
        };
        let old = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, at_seam)?;
        let Some(curve) = self.pending.take() else {
            return Ok(None);
        };
        let geometry = Geometry::new(&curve, &self.config)?;
        let mut cursor = Cursor::new();
        let mut next = engagement.across_seam(
            &self.geometry,
            &geometry,
            &curve,
            &mut cursor,
            from.k,
            forward,
            old.slave,
        )?;
        if self.pending_then == AfterPass::Finish {
            next.finish_after_first_pass(&geometry, forward);
        }
        self.geometry = geometry;
        self.cursor = cursor;
        self.retired = Some(core::mem::replace(&mut self.curve, curve));
        Ok(Some(next))
    }

    fn follow(
        &mut self,
        master: i64,
        fraction: u32,
        events: &mut Events,
    ) -> Result<FollowSample, EngineError> {
        let Some(mut engagement) = self.engagement else {
            return Err(EngineError::Busy);
        };
        let mut here = self.resolve(&engagement, master);
        if here.stopped.is_none()
            && let Some(last) = self.last_place
            && let Some(next) = self.switch_at_seam(engagement, last, here.place)?
        {
            engagement = next;
            self.engagement = Some(next);
            events.table_switched = true;
            events.cycle_completed = true;
            here = self.resolve(&engagement, master);
            // Cycle indices restart with the new table.
            self.last_place = Some(here.place);
        }
        let place = here.place;
        let (cam, mut slave, velocity_ratio, ramping) =
            self.command_at(&engagement, place, master)?;
        if fraction != 0 && here.stopped.is_none() && !here.finished {
            // Between whole master counts (an exact time base, or a coarse
            // master's estimate) the command moves along the straight line
            // to the next count's value: exact at every whole count, and
            // monotonic in between.
            let next_master = master.saturating_add(1);
            let ahead = self.resolve(&engagement, next_master);
            let (_, next_slave, _, _) = self.command_at(&engagement, ahead.place, next_master)?;
            let gap = i128::from(next_slave) - i128::from(slave);
            let step = (gap * i128::from(fraction) + (1 << 31)) >> 32;
            slave =
                i64::try_from(i128::from(slave) + step).map_err(|_| EngineError::SlaveOverflow)?;
        }
        if !ramping {
            self.ramp = None;
        }
        self.commanded = slave;
        if self.last_place.is_some_and(|p| p.k != place.k) {
            events.cycle_completed = true;
            events.seam_jump |= self.geometry.jumps_at_seam;
        }
        self.last_place = Some(place);
        if let Some(forward) = here.stopped {
            events.cycle_completed |= forward;
            events.stopped = true;
            self.halt();
            self.state = AxisState::Finished;
        } else if here.finished {
            events.finished = true;
            events.cycle_completed = true;
            self.halt();
            self.state = AxisState::Finished;
        }
        Ok(FollowSample {
            cam,
            velocity_ratio,
            following: !ramping,
            input_offset: engagement.input_offset(&self.geometry),
            cycle: place.k.saturating_sub(engagement.k_engage),
        })
    }

    fn report(
        &mut self,
        master: i64,
        sample: Option<FollowSample>,
        pulses: i64,
        events: Events,
        fault: Option<EngineError>,
    ) -> TickOutput {
        let mut out = self.last;
        out.state = self.state;
        out.master = master;
        out.velocity_ratio = 0.0;
        out.following = false;
        if let Some(s) = sample {
            let place = s.cam.place;
            out.master_in_cycle = self.geometry.input_in_cycle(place);
            out.master_in_cycle_raw = self.geometry.raw_in_cycle(place);
            out.cycle =
                i64::try_from(s.cycle).unwrap_or(if s.cycle < 0 { i64::MIN } else { i64::MAX });
            out.slave_unzoomed = s.cam.unzoomed;
            out.input_offset = s.input_offset;
            out.output_offset = self.commanded.saturating_sub(s.cam.in_cycle_zoomed);
            if self.state.is_engaged() {
                out.velocity_ratio = s.velocity_ratio;
                out.following = s.following;
            }
        }
        out.slave = self.commanded;
        out.pulses = pulses;
        out.direction_forward = self.pulse.forward;
        out.emitted = self.pulse.emitted;
        out.backlog = self.pulse.backlog(self.commanded);
        out.pulse_delayed = out.backlog != 0;
        out.sync = if self.state.is_engaged() {
            active_windows(&self.config.sync_windows, out.master_in_cycle)
        } else {
            0
        };
        out.in_sync = out.sync != 0;
        out.initialised = self.state.is_active();
        out.busy = out.initialised || out.backlog != 0;
        out.events = events;
        out.fault = fault;
        self.last = out;
        out
    }
}

/// What an axis does once a table queued at the seam has run its first pass.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum AfterPass {
    /// Keep repeating it as the coupling says.
    #[default]
    Repeat,
    /// Finish at the end of the pass (the slave holds there).
    Finish,
}

/// Where the cam stands for one master position.
#[derive(Clone, Copy, Debug)]
struct Resolved {
    place: Place,
    finished: bool,
    /// The end-of-cycle stop was reached; `true` at the forward end.
    stopped: Option<bool>,
}

/// What following the cam produced this tick (kept out of the public output).
#[derive(Clone, Copy, Debug)]
struct FollowSample {
    cam: Sample,
    velocity_ratio: f64,
    following: bool,
    input_offset: i64,
    cycle: i128,
}
