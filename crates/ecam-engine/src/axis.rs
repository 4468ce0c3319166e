//! One cam axis: the tick that runs every step in order.
//!
//! Per tick: master (unwrap) → start (arm, edge, delay, position,
//! breakpoint) → coupling (exact cycle, zoom, offsets; ramp-in; one-shot end;
//! end-of-cycle stop) → pulses (frequency limit, backlog) → sync windows →
//! output. No step allocates or loops over anything but the four sync
//! windows; the curve lookup is O(1) through the cursor while the master
//! moves continuously.
//!
//! The steps with more to them live beside this file: `phase` (what each
//! phase of the axis holds), `engage` (engagement and ramp-in), `online`
//! (changes requested while the cam runs) and `takeover` (carrying out a
//! table switch inside the tick).

use ecam_core::{CamCurve, Cursor};

use crate::MissedActivation;
use crate::config::effective_frequency;
use crate::coupling::{Engagement, Geometry, Place, Sample};
use crate::master::TurnUnwrap;
use crate::pulse::PulseOutput;
use crate::ramp_in::{LimitedLength, RampInLimits};
use crate::speed::MasterSpeed;
use crate::start::{StartStep, StartWatch};
use crate::steady::{Steady, SteadySample};
use crate::stop::{CycleEnd, StopAt};
use crate::sync::active_windows;
use crate::{
    AxisConfig, AxisState, EngineError, Events, MasterFilter, MasterPosition, MasterTracker,
    StopKind, SyncWindow, TickInput, TickOutput,
};

mod between_counts;
mod cam_out;
mod engage;
mod landing;
mod lane;
mod lane_constants;
mod online;
mod phase;
mod plan;
mod prepared;
mod ramp_tick;
#[cfg(test)]
mod steady_tests;
mod switch_tick;
mod takeover;
mod underway;

pub use online::AfterPass;
use phase::{Armed, Engaged, Phase};
use underway::Change;

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
    /// Where the axis is in its life, with what only that phase has.
    phase: Phase<C>,
    turn: Option<TurnUnwrap>,
    tracker: MasterTracker,
    /// The last unwrapped reading (for the master-step guard).
    last_reading: Option<i64>,
    /// The table a switch replaced, for the caller to take back
    /// ([`CamAxis::take_retired_curve`]): dropping it inside `tick` would
    /// free memory in the control cycle.
    retired: Option<C>,
    commanded: i64,
    pulse: PulseOutput,
    last_start_input: bool,
    /// Events of a stop that took effect between ticks, reported by the next tick.
    pending_events: Events,
    /// Limits a ramp-in keeps to ([`CamAxis::set_ramp_in_limits`]).
    ramp_limits: Option<RampInLimits>,
    /// What sizes the ramp-in under limits that engaged on the last tick,
    /// unsized (`Ramp::to_size`): the next tick sizes it before anything
    /// reads it ([`CamAxis::size_ramp_in`]).
    ramp_sizing: Option<LimitedLength>,
    /// What a backward pass of an activation position does.
    missed_policy: MissedActivation,
    /// An activation was missed since the last arm, engage or switch.
    missed: bool,
    /// The master's speed for sizing a ramp-in (see `speed.rs`).
    speed: MasterSpeed,
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
            phase: Phase::Idle,
            turn: config.single_turn.map(TurnUnwrap::new),
            tracker: MasterTracker::new(config.master_filter),
            last_reading: None,
            retired: None,
            commanded: 0,
            pulse: PulseOutput::at(0),
            last_start_input: false,
            pending_events: Events::default(),
            ramp_limits: None,
            ramp_sizing: None,
            missed_policy: MissedActivation::StartNow,
            missed: false,
            speed: MasterSpeed::new(),
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
        self.phase.state()
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
        if self.state().is_active() {
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

    /// Sets the limits the next ramp-ins keep to (PLCopen ramp-in with
    /// limits, `ramp_in_pos`, `ramp_in_neg`; see docs/engine.md, "Ramp-in
    /// under limits"): at engage the ramp's master distance becomes the
    /// longer of [`AxisConfig::ramp_in`]'s and the one the limits need at
    /// the master's speed then, and the gap is closed in the allowed
    /// direction. With limits a ramp-in happens even without
    /// [`AxisConfig::ramp_in`]. `None` removes them.
    pub fn set_ramp_in_limits(&mut self, limits: Option<RampInLimits>) {
        self.ramp_limits = limits;
    }

    /// Chooses what a backward pass of an activation position does (a
    /// [`crate::StartMode::AtMasterPosition`] start, a
    /// [`crate::SwitchAt::MasterPosition`] switch): take effect there
    /// ([`MissedActivation::StartNow`], the default and the behaviour
    /// before this setting) or wait for the next forward pass
    /// ([`MissedActivation::NextPass`]). Either way the tick reports
    /// `events.activation_missed` and `activation_missed` stays set until
    /// the next arm, engage or switch. Takes effect at the next arm for
    /// starts, at once for switches.
    pub fn set_missed_activation(&mut self, policy: MissedActivation) {
        self.missed_policy = policy;
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
    /// [`EngineError::Busy`] while the cam is engaged or the slave moves at
    /// velocity after a cam-out (stop it first).
    pub fn arm(&mut self) -> Result<(), EngineError> {
        match self.phase {
            Phase::Running(_) | Phase::Stopping(..) | Phase::Velocity(_) => Err(EngineError::Busy),
            Phase::Armed(_) => Ok(()),
            Phase::Idle | Phase::Finished => {
                self.missed = false;
                self.phase = Phase::Armed(Armed {
                    watch: StartWatch::arm_with(
                        self.config.start,
                        self.missed_policy,
                        self.config.single_turn,
                    ),
                    previous: None,
                    delaying: false,
                    ready: None,
                });
                self.prepare_engagement();
                Ok(())
            }
        }
    }

    /// Stops the cam. [`StopKind::Immediate`] holds the slave where it is
    /// and goes idle; [`StopKind::EndOfCycle`] keeps following to the end of
    /// the current cycle (either direction), or, requested while the master
    /// is exactly on a cycle end, finishes there at once. Either cancels a
    /// pending start, and either holds a slave moving at velocity after
    /// [`CamAxis::cam_out_at_velocity`] where it is (for a stop under a
    /// deceleration limit see [`CamAxis::stop_decelerating`]). The next
    /// tick reports what a stop here did.
    pub fn stop(&mut self, kind: StopKind) {
        let phase = core::mem::replace(&mut self.phase, Phase::Idle);
        self.phase = match (phase, kind) {
            (Phase::Running(engaged), StopKind::EndOfCycle) => {
                match CycleEnd::of(&self.geometry, engaged.place) {
                    StopAt::Ahead(end) => Phase::Stopping(engaged, end),
                    StopAt::Here { completes_cycle } => {
                        self.pending_events.stopped = true;
                        self.pending_events.cycle_completed |= completes_cycle;
                        self.end_run(engaged);
                        Phase::Finished
                    }
                }
            }
            (stopping @ Phase::Stopping(..), StopKind::EndOfCycle) => stopping,
            (Phase::Running(engaged) | Phase::Stopping(engaged, _), StopKind::Immediate) => {
                self.pending_events.stopped = true;
                self.end_run(engaged);
                Phase::Idle
            }
            (Phase::Armed(_) | Phase::Velocity(_), _) => {
                self.pending_events.stopped = true;
                Phase::Idle
            }
            (other, _) => other,
        };
    }

    /// Stops immediately and cancels any pending start.
    pub fn disengage(&mut self) {
        self.stop(StopKind::Immediate);
    }

    /// Leaves any active phase for `Idle` at once (output inhibit, fault).
    fn halt(&mut self) {
        let phase = core::mem::replace(&mut self.phase, Phase::Idle);
        match phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => self.end_run(engaged),
            Phase::Finished => self.phase = Phase::Finished,
            Phase::Idle | Phase::Armed(_) | Phase::Velocity(_) => {}
        }
    }

    /// One control cycle. Never allocates, never panics; O(1) while the
    /// master moves continuously (a jump costs one binary search).
    #[must_use = "the tick's output holds the pulses to emit"]
    pub fn tick(&mut self, input: &TickInput) -> TickOutput {
        *self.step(input, true)
    }

    /// [`CamAxis::tick`] without the copy: the axis updates its output
    /// record in place and lends it (the same record
    /// [`CamAxis::status`] reads). For loops over many axes where the
    /// 120-byte copy per tick shows; the results are the same.
    #[inline]
    pub fn tick_in_place(&mut self, input: &TickInput) -> &TickOutput {
        self.step(input, true)
    }

    /// [`CamAxis::tick`]; `steady_allowed = false` takes the general path
    /// even for a settled cam (tests compare the two).
    #[inline(always)]
    fn step(&mut self, input: &TickInput, steady_allowed: bool) -> &TickOutput {
        let reading = match &mut self.turn {
            Some(turn) => turn.update(input.master),
            None => input.master,
        };
        let step = self.last_reading.map_or(0, |last| reading.abs_diff(last));
        self.last_reading = Some(reading);
        let estimate = match self.tracker.filter() {
            // Direct readings need no tracker state (nothing reads it back).
            MasterFilter::Direct => MasterPosition {
                counts: reading,
                fraction: input.master_fraction,
            },
            MasterFilter::Interpolate { .. } => {
                self.tracker
                    .update(reading, input.master_fraction, input.dt_us)
            }
        };
        let master = estimate.counts;
        self.speed.update(estimate, input.dt_us);
        let edge = input.start_input && !self.last_start_input;
        self.last_start_input = input.start_input;

        let mut events = core::mem::take(&mut self.pending_events);
        let mut fault = None;
        let mut sample = None;

        // A running cam with its output on and the master within its step
        // limit has nothing to supervise; everything else (inhibit, the
        // step guard, a start) is handled out of line, keeping this path
        // short.
        let quiet = input.output_enabled
            && matches!(self.phase, Phase::Running(_))
            && self
                .config
                .max_master_step
                .is_none_or(|limit| step <= limit.get());
        if !quiet {
            // The engaging tick of a ramp-in at a whole count comes back
            // answered from the engagement (`engage.rs`).
            let whole = steady_allowed && estimate.fraction == 0;
            if let Some(opened) =
                self.supervise(input, step, edge, master, whole, &mut events, &mut fault)
            {
                let hz = effective_frequency(self.config.max_frequency_hz);
                self.commanded = opened.slave;
                let pulses = self
                    .pulse
                    .step(self.commanded, input.output_enabled, hz, input.dt_us);
                return self.report::<false>(master, Some(opened), pulses, events, fault);
            }
        }

        // A settled cam at a whole master count: the steady tick, from the
        // engagement's constants (same results, see `steady.rs`).
        let mut settled = None;
        if steady_allowed
            && estimate.fraction == 0
            && let Phase::Running(engaged) = &mut self.phase
            && let Some(constants) = engaged.underway.steady()
            && let Some(cam) = constants.sample(master, &self.curve, &mut self.cursor)
        {
            let (place, followed) = (&mut engaged.place, &mut engaged.followed);
            step_to(
                place,
                followed,
                &cam,
                i128::from(master) << 32,
                self.geometry.jumps_at_seam,
                &mut events,
            );
            settled = Some(FollowSample::of_steady(
                &cam,
                constants,
                cam.slave,
                cam.velocity_ratio,
                true,
            ));
        }
        let hz = effective_frequency(self.config.max_frequency_hz);
        // A running cam with a ramp, blend or change on top: the general
        // tick's fast lane (`lane.rs`), from the same constants.
        if steady_allowed && settled.is_none() && estimate.fraction == 0 {
            if let Some((ended, followed, happened)) = self.lane(master) {
                if ended {
                    self.finish_run();
                }
                events.merge(happened);
                self.commanded = followed.slave;
                let pulses = self
                    .pulse
                    .step(self.commanded, input.output_enabled, hz, input.dt_us);
                return self.report::<false>(master, Some(followed), pulses, events, fault);
            }
        }
        if let Some(followed) = settled {
            self.commanded = followed.slave;
            let pulses = self
                .pulse
                .step(self.commanded, input.output_enabled, hz, input.dt_us);
            // Still running: the report's state is known.
            return self.report::<true>(master, Some(followed), pulses, events, fault);
        }
        self.follow_general(
            &mut events,
            &mut fault,
            &mut sample,
            estimate,
            input.dt_us,
            steady_allowed,
        );
        let pulses = self
            .pulse
            .step(self.commanded, input.output_enabled, hz, input.dt_us);
        self.report::<false>(master, sample, pulses, events, fault)
    }

    /// The checks before following: output inhibit, the master-step
    /// guard, and an armed axis' start (which may engage the cam); the
    /// engaging tick's sample when the engagement answered it (`whole`:
    /// the tick is at a whole master count on the fast route, see
    /// `engage.rs`).
    #[inline(never)]
    #[allow(clippy::too_many_arguments)]
    fn supervise(
        &mut self,
        input: &TickInput,
        step: u64,
        edge: bool,
        master: i64,
        whole: bool,
        events: &mut Events,
        fault: &mut Option<EngineError>,
    ) -> Option<FollowSample> {
        if !input.output_enabled && self.state().is_active() {
            self.halt();
            events.stopped = true;
        }

        if self.state().is_active()
            && self
                .config
                .max_master_step
                .is_some_and(|limit| step > limit.get())
        {
            *fault = Some(EngineError::MasterStep);
            self.halt();
            events.stopped = true;
        }

        let start = match &mut self.phase {
            Phase::Armed(armed) => {
                let previous = armed.previous.unwrap_or(master);
                armed.previous = Some(master);
                let step = armed.watch.step(previous, master, edge, input.watch);
                armed.delaying |= step == StartStep::Delaying;
                events.activation_missed |= armed.watch.take_missed();
                step
            }
            _ => StartStep::Waiting,
        };
        if let StartStep::Engage(at) = start {
            // Answered only where the tick's own master is the engage
            // master (a start position the master passed engages behind it).
            match self.engage(at, whole && at == master) {
                Ok(opened) => {
                    events.engaged = true;
                    return opened;
                }
                Err(e) => {
                    *fault = Some(e);
                    self.halt();
                    events.stopped = true;
                }
            }
        }
        None
    }

    /// The phase and the rest of the axis borrowed apart: the phase is
    /// large, so it is followed in place rather than moved out and back.
    #[inline(always)]
    fn split(&mut self) -> (&mut Phase<C>, Coupled<'_, C>) {
        let Self {
            phase,
            curve,
            geometry,
            cursor,
            config,
            retired,
            commanded,
            missed_policy,
            ..
        } = self;
        (
            phase,
            Coupled {
                curve,
                geometry,
                cursor,
                config,
                retired,
                commanded,
                missed_policy: *missed_policy,
                prepared: true,
            },
        )
    }

    /// Sizes the ramp-in under limits the last tick engaged with, if
    /// any (`Ramp::to_size`): what every tick that may read a ramp-in
    /// calls first. Taken either way: an engagement that ended since
    /// leaves nothing to size.
    #[inline(always)]
    fn size_ramp_in(&mut self) {
        if let Some(length) = self.ramp_sizing.take() {
            self.size_ramp_in_now(length);
        }
    }

    /// [`CamAxis::size_ramp_in`]'s work, out of line: one tick in a run.
    #[inline(never)]
    fn size_ramp_in_now(&mut self, length: LimitedLength) {
        if let Phase::Running(engaged) | Phase::Stopping(engaged, _) = &mut self.phase {
            engaged.underway.size_ramp_in(length.distance());
        }
    }

    /// The fast lane for an engaged phase (`lane.rs`); `None` for any
    /// other phase or when the lane leaves the tick to the general path.
    #[inline(always)]
    fn lane(&mut self, master: i64) -> Option<lane::Followed> {
        self.size_ramp_in();
        let (phase, mut coupled) = self.split();
        match phase {
            Phase::Running(engaged) => {
                // A ramp-in alone, a switch or a seam table waiting alone:
                // their own ticks (`ramp_tick.rs`, `switch_tick.rs`),
                // called from here so that they skip the lane's frame too.
                let alone = if engaged.underway.ramps_in_alone() {
                    let mut events = Events::default();
                    engaged
                        .ramp_in_tick(
                            master,
                            coupled.curve,
                            coupled.cursor,
                            coupled.geometry,
                            &mut events,
                        )
                        .map(|sample| (false, sample, events))
                } else {
                    match engaged.underway.waiting_alone() {
                        Some(true) => coupled.seam_tick(engaged, master),
                        Some(false) => coupled.switch_tick(engaged, master),
                        None => None,
                    }
                };
                alone.or_else(|| coupled.follow_lane(engaged, None, master))
            }
            Phase::Stopping(engaged, end) => {
                let end = *end;
                coupled.follow_lane(engaged, Some(&end), master)
            }
            _ => None,
        }
    }

    /// Ends the engaged phase's run where it stands: `Finished`.
    fn finish_run(&mut self) {
        if let Phase::Running(engaged) | Phase::Stopping(engaged, _) =
            core::mem::replace(&mut self.phase, Phase::Idle)
        {
            self.end_run(engaged);
            self.phase = Phase::Finished;
        }
    }

    /// The general tick for any phase: follows the cam in place when
    /// engaged (the phase is large, so it is borrowed apart from the rest
    /// of the axis rather than moved out and back) and moves on to the
    /// next phase when the run ended.
    fn follow_general(
        &mut self,
        events: &mut Events,
        fault: &mut Option<EngineError>,
        sample: &mut Option<FollowSample>,
        at: MasterPosition,
        dt_us: u32,
        steady_allowed: bool,
    ) {
        let (master, fraction) = (at.counts, at.fraction);
        self.size_ramp_in();
        // A settled cam between whole counts: the steady tick's two
        // samples (`between_counts.rs`), unless `steady_allowed` is off.
        if steady_allowed
            && fraction != 0
            && let Phase::Running(engaged) = &mut self.phase
            && let Some(followed) = engaged.between_counts_tick(
                master,
                fraction,
                &self.curve,
                &mut self.cursor,
                self.geometry.jumps_at_seam,
                events,
            )
        {
            self.commanded = followed.slave;
            *sample = Some(followed);
            return;
        }
        let (phase, mut coupled) = self.split();
        coupled.prepared = steady_allowed;
        let followed = match phase {
            Phase::Running(engaged) => coupled.follow(engaged, None, master, fraction),
            Phase::Stopping(engaged, end) => {
                let end = *end;
                coupled.follow(engaged, Some(end), master, fraction)
            }
            Phase::Velocity(coast) => {
                let (at, rest) = coast.advance(dt_us);
                *coupled.commanded = at;
                let stopped = Events {
                    stopped: rest,
                    ..Events::default()
                };
                Ok((rest, None, stopped))
            }
            _ => Ok((false, None, Events::default())),
        };
        match followed {
            Ok((ended, followed, happened)) => {
                if ended {
                    // A cam's run ends in `Finished`, a coast at rest in `Idle`.
                    self.finish_run();
                }
                *sample = followed;
                events.merge(happened);
            }
            Err(e) => {
                // The engaged phase is given up: the axis is idle now.
                self.phase = Phase::Idle;
                *fault = Some(e);
                events.stopped = true;
            }
        }
    }

    /// Fills the output record in place. `RUNNING`: the steady tick's
    /// report, where the axis is known to be running (the state and what
    /// follows from it fold away).
    #[inline(always)]
    fn report<const RUNNING: bool>(
        &mut self,
        master: i64,
        sample: Option<FollowSample>,
        pulses: i64,
        events: Events,
        fault: Option<EngineError>,
    ) -> &TickOutput {
        let state = if RUNNING {
            AxisState::Running
        } else {
            self.state()
        };
        debug_assert_eq!(state, self.state());
        if events.engaged || events.table_switched {
            self.missed = false;
        }
        self.missed |= events.activation_missed;
        let backlog = self.pulse.backlog(self.commanded);
        let out = &mut self.last;
        out.state = state;
        out.master = master;
        out.velocity_ratio = 0.0;
        out.following = false;
        if let Some(s) = sample {
            out.master_in_cycle = s.master_in_cycle;
            out.master_in_cycle_raw = s.master_in_cycle_raw;
            out.cycle = s.cycle;
            out.slave_unzoomed = s.unzoomed;
            out.input_offset = s.input_offset;
            out.output_offset = self.commanded.saturating_sub(s.in_cycle_zoomed);
            if state.is_engaged() {
                out.velocity_ratio = s.velocity_ratio;
                out.following = s.following;
            }
        }
        out.slave = self.commanded;
        out.pulses = pulses;
        out.direction_forward = self.pulse.forward;
        out.emitted = self.pulse.emitted;
        out.backlog = backlog;
        out.pulse_delayed = backlog != 0;
        out.sync = if state.is_engaged() {
            active_windows(&self.config.sync_windows, out.master_in_cycle)
        } else {
            0
        };
        out.in_sync = out.sync != 0;
        out.initialised = state.is_active();
        out.busy = out.initialised || backlog != 0;
        out.activation_missed = self.missed;
        out.events = events;
        out.fault = fault;
        out
    }
}

/// The parts of an axis that following the cam reads and changes beside
/// its phase, borrowed apart from it (`follow_general`).
pub(super) struct Coupled<'a, C> {
    pub(super) curve: &'a mut C,
    pub(super) geometry: &'a mut Geometry,
    pub(super) cursor: &'a mut Cursor,
    pub(super) config: &'a mut AxisConfig,
    /// Where a switch puts the table it replaced.
    pub(super) retired: &'a mut Option<C>,
    pub(super) commanded: &'a mut i64,
    pub(super) missed_policy: MissedActivation,
    /// The general tick may take a switch's prepared landing
    /// (`takeover.rs`); off for the reference route (`steady_allowed`
    /// off), which works every landing out, so that the steady-vs-general
    /// property test holds the two to the same results.
    pub(super) prepared: bool,
}

impl<C: CamCurve> Coupled<'_, C> {
    /// Where the cam stands for `master`: the place (clamped to a one-shot's
    /// span or to the end of a requested end-of-cycle stop), whether a
    /// one-shot finished, and whether the stop was reached (and forwards).
    #[inline(always)]
    fn resolve(
        &self,
        engagement: &Engagement,
        stop_at: Option<&CycleEnd>,
        master: i64,
    ) -> Resolved {
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
        if let Some(end) = stop_at
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
        engaged: &mut Engaged<C>,
        place: Place,
        master: i64,
    ) -> Result<(Sample, i64, f64, bool), EngineError> {
        let (ramp_in, change) = engaged.underway.parts();
        let engagement = match change.and_then(Change::offsets) {
            Some(ramp) => ramp.apply(&engaged.engagement, master)?,
            None => engaged.engagement,
        };
        let cam = engagement.sample(self.geometry, &*self.curve, self.cursor, place)?;
        let (slave, ratio) = match change {
            Some(Change::Blend(blend, _)) => {
                let blended = blend.command(master)?;
                (blended.slave, blended.velocity_ratio)
            }
            Some(Change::Scaling(scaling, _)) => {
                let new = engagement.sample(&scaling.target, &*self.curve, self.cursor, place)?;
                scaling.mix(
                    master,
                    (cam.slave, cam.velocity_ratio),
                    (new.slave, new.velocity_ratio),
                )
            }
            _ => (cam.slave, cam.velocity_ratio),
        };
        match ramp_in.and_then(|ramp| Some((ramp, ramp.blend(master, slave)?))) {
            Some((ramp, blended)) => Ok((cam, blended, ratio * ramp.weight(master), true)),
            None => Ok((cam, slave, ratio, false)),
        }
    }

    /// Follows the cam for one tick, in place; gives whether the run ended
    /// (a stop reached or a one-shot finished: the caller ends it), what
    /// was followed and what happened.
    fn follow(
        &mut self,
        engaged: &mut Engaged<C>,
        stop_at: Option<CycleEnd>,
        master: i64,
        fraction: u32,
    ) -> Result<(bool, Option<FollowSample>, Events), EngineError> {
        let mut events = Events::default();
        engaged.lane = None;
        // Ramps and blends end where the position itself reaches their
        // end, not its whole count (below the position when the master
        // runs backwards), so the straight line between counts never
        // jumps from a ramp's value to the final cam's mid-count.
        let at = MasterPosition {
            counts: master,
            fraction,
        };
        match engaged.underway.change() {
            Some(Change::Offsets(ramp, _)) if ramp.finished_at(at) => {
                let ramp = *ramp;
                engaged.engagement = ramp.apply(&engaged.engagement, master)?;
                engaged.underway.end_change();
            }
            Some(Change::Scaling(ramp, _)) if ramp.finished_at(at) => {
                *self.geometry = ramp.target;
                engaged.underway.end_change();
            }
            _ => {}
        }
        let mut here = self.resolve(&engaged.engagement_at(master)?, stop_at.as_ref(), master);
        if here.stopped.is_none() && self.switch_at_seam(engaged, here.place)? {
            events.table_switched = true;
            events.cycle_completed = true;
            here = self.resolve(&engaged.engagement, stop_at.as_ref(), master);
            // Cycle indices restart with the new table.
            engaged.place = here.place;
        }
        // A table waiting alone for the seam (a queued table's every tick
        // until the seam takes it): no blend to end, no switch to fire.
        let seam_wait = engaged.underway.waits_alone_for_seam();
        if !seam_wait {
            engaged.end_blend(at)?;
        }
        if !seam_wait && here.stopped.is_none() && stop_at.is_none() {
            let blending = engaged.blend().is_some();
            let previous = engaged.followed;
            let now = (i128::from(master) << 32) | i128::from(fraction);
            let policy = self.missed_policy;
            let turn = self.config.single_turn;
            let fired = engaged
                .underway
                .change_mut()
                .and_then(Change::pending_mut)
                .map(|p| p.fires(previous, now, blending, policy, turn));
            events.activation_missed |= fired.is_some_and(|f| f.missed);
            if let Some(switch) = fired.and_then(|f| f.at) {
                self.switch_at(engaged, switch)?;
                events.table_switched = true;
                here = self.resolve(&engaged.engagement, None, master);
                engaged.place = here.place;
                // A master that moved past the whole blend in this very
                // tick is on the new cam already, not at the blend's end.
                engaged.end_blend(at)?;
            }
        }
        engaged.followed = (i128::from(master) << 32) | i128::from(fraction);
        let place = here.place;
        let (cam, mut slave, velocity_ratio, ramping) = self.command_at(engaged, place, master)?;
        if fraction != 0 && here.stopped.is_none() && !here.finished {
            // Between whole master counts (an exact time base, or a coarse
            // master's estimate) the command moves along the straight line
            // to the next count's value: exact at every whole count, and
            // monotonic in between.
            let next_master = master.saturating_add(1);
            let ahead = self.resolve(
                &engaged.engagement_at(next_master)?,
                stop_at.as_ref(),
                next_master,
            );
            // Across a seam, aim at the seam: a table may be queued for it
            // (now, or by a call before the next tick), and then the old
            // cam past the seam is not where the slave goes. Aiming beyond
            // it would command a slave the switch then takes back, a
            // reversal the master never made.
            // A table waiting there with a blend: aim where the blend
            // will be (it starts before the seam, see `seam_blend_aim`).
            let blend_aim = match stop_at {
                None if ahead.place.k != place.k => {
                    self.seam_blend_aim(engaged, place.k, ahead.place.k > place.k, next_master)
                }
                _ => None,
            };
            let next_slave = match blend_aim {
                Some(value) => value,
                None => {
                    let aim = if ahead.place.k != place.k {
                        if ahead.place.k > place.k {
                            self.geometry.cycle_end(place.k)
                        } else {
                            Geometry::cycle_start(place.k)
                        }
                    } else {
                        ahead.place
                    };
                    self.command_at(engaged, aim, next_master)?.1
                }
            };
            let gap = i128::from(next_slave) - i128::from(slave);
            let step = (gap * i128::from(fraction) + (1 << 31)) >> 32;
            slave =
                i64::try_from(i128::from(slave) + step).map_err(|_| EngineError::SlaveOverflow)?;
        }
        if engaged.ramp_in().is_some_and(|ramp| ramp.finished_at(at)) {
            engaged.underway.end_ramp_in();
        }
        // Following the cam itself: no ramp-in blending, and no ramp or
        // blend (a table may wait).
        let following = !ramping
            && engaged
                .underway
                .change()
                .is_none_or(|change| matches!(change, Change::Waiting(_)));
        *self.commanded = slave;
        if engaged.place.k != place.k {
            events.cycle_completed = true;
            events.seam_jump |= self.geometry.jumps_at_seam;
        }
        engaged.place = place;
        let followed = FollowSample {
            master_in_cycle: self.geometry.input_in_cycle(place),
            master_in_cycle_raw: self.geometry.raw_in_cycle(place),
            cycle: clamp_i64(place.k.saturating_sub(engaged.engagement.k_engage)),
            unzoomed: cam.unzoomed,
            in_cycle_zoomed: cam.in_cycle_zoomed,
            velocity_ratio,
            following,
            input_offset: engaged.engagement.input_offset(self.geometry),
            slave,
        };
        // Nothing under way: the next ticks can take the steady path, from
        // the constants of the engagement as it is now (a stop drops them).
        // Nothing this tick did can have changed a settled engagement, so
        // the constants are refreshed here rather than dropped on entry.
        if engaged.underway.is_settled() {
            let steady = match stop_at {
                None => engaged.engagement.steady(self.geometry),
                Some(_) => None,
            };
            engaged.underway.settle(steady);
        }
        let ended = if let Some(forward) = here.stopped {
            events.cycle_completed |= forward;
            events.stopped = true;
            true
        } else if here.finished {
            events.finished = true;
            events.cycle_completed = true;
            true
        } else {
            false
        };
        Ok((ended, Some(followed), events))
    }
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
    /// Table input in the cycle after master zoom (floor).
    master_in_cycle: i64,
    /// The same before master zoom (floor).
    master_in_cycle_raw: i64,
    /// Cycles since engaging.
    cycle: i64,
    /// Table value plus accumulated strokes, before slave zoom.
    unzoomed: i64,
    /// The table value in the cycle after slave zoom.
    in_cycle_zoomed: i64,
    velocity_ratio: f64,
    following: bool,
    input_offset: i64,
    /// The commanded slave.
    slave: i64,
}

impl FollowSample {
    /// What the axis followed when the steady tick's `constants` gave
    /// `cam`, with the command (`slave`, `velocity_ratio`) and whether it
    /// is the cam itself (`following`) as the tick made them.
    #[inline(always)]
    fn of_steady(
        cam: &SteadySample,
        constants: &Steady,
        slave: i64,
        velocity_ratio: f64,
        following: bool,
    ) -> Self {
        Self {
            master_in_cycle: cam.master_in_cycle,
            master_in_cycle_raw: cam.master_in_cycle_raw,
            cycle: clamp_i64(i128::from(cam.k) - i128::from(constants.k_engage)),
            unzoomed: cam.unzoomed,
            in_cycle_zoomed: cam.in_cycle_zoomed,
            velocity_ratio,
            following,
            input_offset: constants.input_offset,
            slave,
        }
    }
}

/// Moves what an engaged axis followed (its `place` and `followed`
/// master) to the steady sample `cam` at master `now` (counts × 2³² plus
/// the fraction): a cycle completed (and a seam jump where the table
/// jumps there) when `cam` lies in another cycle than the last tick's
/// place. The two fields alone, so that the steady constants the sample
/// came from can stay borrowed.
#[inline(always)]
fn step_to(
    place: &mut Place,
    followed: &mut i128,
    cam: &SteadySample,
    now: i128,
    jumps_at_seam: bool,
    events: &mut Events,
) {
    let k = i128::from(cam.k);
    if place.k != k {
        events.cycle_completed = true;
        events.seam_jump |= jumps_at_seam;
    }
    *place = Place {
        k,
        r_num: i128::from(cam.r_num),
    };
    *followed = now;
}

/// `v` clamped into `i64`.
fn clamp_i64(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}
