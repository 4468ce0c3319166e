//! One cam axis: the tick that runs every step in order.
//!
//! Per tick: master (unwrap) → start (arm, edge, delay, position,
//! breakpoint) → coupling (exact cycle, zoom, offsets; ramp-in; one-shot end;
//! end-of-cycle stop) → pulses (frequency limit, backlog) → sync windows →
//! output. No step allocates or loops over anything but the four sync
//! windows; the curve lookup is O(1) through the cursor while the master
//! moves continuously.

use core::num::NonZeroU64;

use ecam_core::{CamCurve, Cursor};

use crate::MissedActivation;
use crate::blend::{Blend, BlendEnd};
use crate::config::effective_frequency;
use crate::coupling::{Engagement, Geometry, Place, Sample};
use crate::master::TurnUnwrap;
use crate::offset_ramp::OffsetRamp;
use crate::pulse::PulseOutput;
use crate::ramp::Ramp;
use crate::ramp_in::{RampDirection, RampInLimits};
use crate::scaling::ScalingRamp;
use crate::speed::MasterSpeed;
use crate::start::{StartStep, StartWatch};
use crate::stop::{CycleEnd, StopAt};
use crate::switch::{Pending, Takeover, Trigger};
use crate::sync::active_windows;
use crate::{
    AxisConfig, AxisState, EngineError, Events, MasterTracker, OffsetChange, RampIn, SlaveAlign,
    StopKind, SwitchAt, SyncWindow, TickInput, TickOutput, Zoom,
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
    /// What a backward pass of an activation position does.
    missed_policy: MissedActivation,
    /// An activation was missed since the last arm, engage or switch.
    missed: bool,
    /// The master's speed for sizing a ramp-in (see `speed.rs`).
    speed: MasterSpeed,
    last: TickOutput,
}

/// The life of an axis; each phase holds what only it has, so a stopping
/// axis without a cycle end, or a running one without an engagement,
/// cannot be built.
#[derive(Clone, Debug)]
enum Phase<C> {
    /// Not coupled; the slave holds.
    Idle,
    /// Waiting for the start condition.
    Armed(Armed),
    /// Following the cam.
    Running(Engaged<C>),
    /// Following the cam to the end of the current cycle.
    Stopping(Engaged<C>, CycleEnd),
    /// A one-shot ended or an end-of-cycle stop completed; the slave holds.
    Finished,
}

/// An armed axis' start watch.
#[derive(Clone, Copy, Debug)]
struct Armed {
    watch: StartWatch,
    /// The master of the last tick since arming: delays and crossings
    /// count from the first tick after arming, not from motion before it.
    previous: Option<i64>,
    /// The start came and a delay is being counted.
    delaying: bool,
}

/// What an engaged axis has.
#[derive(Clone, Debug)]
struct Engaged<C> {
    engagement: Engagement,
    ramp: Option<Ramp>,
    /// The place followed at the last tick (where a stop is measured from).
    place: Place,
    /// A table waiting for the next seam ([`CamAxis::queue_curve`]).
    queued: Option<(C, AfterPass)>,
    /// The blend for the queued table's seam switch.
    seam_blend: Option<NonZeroU64>,
    /// A table waiting for a master position or the next tick
    /// ([`CamAxis::switch_curve`]); never together with `queued`.
    pending: Option<Pending<C>>,
    /// The blend from the last switch's old cam, while it runs.
    blend: Option<Blend>,
    /// An offset change being ramped in ([`CamAxis::change_offsets`]).
    offsets: Option<OffsetRamp>,
    /// A slave-scaling change being ramped in
    /// ([`CamAxis::change_slave_scaling`]).
    scaling: Option<ScalingRamp>,
    /// The master followed at the last tick, counts × 2^32 plus the
    /// fraction (where a switch position is crossed from).
    followed: i128,
}

impl<C> Engaged<C> {
    /// A table switch, blend, offset or scaling change is under way.
    fn changing(&self) -> bool {
        self.offsets.is_some()
            || self.scaling.is_some()
            || self.blend.is_some()
            || self.pending.is_some()
            || self.queued.is_some()
    }

    /// The engagement in effect at `master`, an offset ramp included.
    fn engagement_at(&self, master: i64) -> Result<Engagement, EngineError> {
        match &self.offsets {
            Some(ramp) => ramp.apply(&self.engagement, master),
            None => Ok(self.engagement),
        }
    }
}

impl<C> Phase<C> {
    fn state(&self) -> AxisState {
        match self {
            Self::Idle => AxisState::Idle,
            Self::Armed(Armed { delaying: true, .. }) => AxisState::Delaying,
            Self::Armed(_) => AxisState::Armed,
            Self::Running(_) => AxisState::Running,
            Self::Stopping(..) => AxisState::Stopping,
            Self::Finished => AxisState::Finished,
        }
    }

    fn engaged(&self) -> Option<&Engaged<C>> {
        match self {
            Self::Running(e) | Self::Stopping(e, _) => Some(e),
            _ => None,
        }
    }
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
        match &mut self.phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => {
                if geometry.extent == crate::coupling::Extent::Single {
                    return Err(EngineError::NoSeam);
                }
                engaged.pending = None;
                engaged.seam_blend = None;
                engaged.queued = Some((curve, then));
            }
            Phase::Idle | Phase::Armed(_) | Phase::Finished => {
                self.geometry = geometry;
                self.cursor = Cursor::new();
                self.retired = Some(core::mem::replace(&mut self.curve, curve));
            }
        }
        Ok(())
    }

    /// Hands a new table to the axis, taking over where `at` says. Idle,
    /// armed or finished, it replaces the table at once. While the cam is
    /// running, [`SwitchAt::NextSeam`] is [`CamAxis::queue_curve`]; with
    /// [`SwitchAt::MasterPosition`] and [`SwitchAt::Now`] the new cam takes
    /// over at that master position (or this tick's master), aligned to
    /// the master as [`AxisConfig::master_align`] says (as at engage) and
    /// anchored on the old cam there: the slave's position is continuous.
    /// With a blend distance the velocity is too: the slave's velocity
    /// moves from the old cam's to the new cam's over that master travel
    /// and stays between them (see docs/engine.md, "Changing the table
    /// while engaged"). A second call before the switch replaces the
    /// waiting table; a switch that comes due while a blend runs waits for
    /// its end. `events.table_switched` marks the tick of the switch; the
    /// old table can be taken back with [`CamAxis::take_retired_curve`].
    ///
    /// # Errors
    /// As [`CamAxis::queue_curve`]; [`EngineError::Busy`] for a position
    /// or at-once switch during an end-of-cycle stop. The running cam is
    /// left untouched.
    pub fn switch_curve(&mut self, curve: C, at: SwitchAt) -> Result<(), EngineError> {
        let (trigger, blend) = match at {
            SwitchAt::NextSeam { blend } => {
                self.queue_curve(curve)?;
                if let Phase::Running(engaged) | Phase::Stopping(engaged, _) = &mut self.phase {
                    engaged.seam_blend = blend;
                }
                return Ok(());
            }
            SwitchAt::MasterPosition { position, blend } => (Trigger::Position(position), blend),
            SwitchAt::Now { blend } => (Trigger::Now, blend),
        };
        Geometry::new(&curve, &self.config)?;
        match &mut self.phase {
            Phase::Running(engaged) if engaged.offsets.is_some() || engaged.scaling.is_some() => {
                Err(EngineError::Busy)
            }
            Phase::Running(engaged) => {
                engaged.queued = None;
                engaged.pending = Some(Pending::new(Takeover::Table(curve), trigger, blend));
                Ok(())
            }
            Phase::Stopping(..) => Err(EngineError::Busy),
            Phase::Idle | Phase::Armed(_) | Phase::Finished => self.queue_curve(curve),
        }
    }

    /// True while a queued table waits for the next seam, a master
    /// position or the next tick.
    pub fn has_queued_curve(&self) -> bool {
        self.phase
            .engaged()
            .is_some_and(|e| e.queued.is_some() || e.pending.is_some())
    }

    /// Changes the master and slave offsets of the running cam by
    /// `change`, ramped in over `change.distance` master counts from the
    /// master the axis followed last (PLCopen `MasterOffset` and
    /// `SlaveOffset` changed in sync; see docs/engine.md, "Offsets on the
    /// fly"). Position, velocity and acceleration stay continuous; the
    /// final offsets are exact.
    ///
    /// # Errors
    /// [`EngineError::NotRunning`] unless the cam is running;
    /// [`EngineError::Busy`] while a table switch waits or blends, or an
    /// offset change is still being ramped in.
    pub fn change_offsets(&mut self, change: OffsetChange) -> Result<(), EngineError> {
        let mden = self.geometry.master_den();
        match &mut self.phase {
            Phase::Running(engaged) => {
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                engaged.offsets = Some(OffsetRamp::new(change, from, mden));
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// Changes the slave scaling (slave zoom) of the running cam, ramped
    /// in over `distance` master counts from the master the axis followed
    /// last (PLCopen `SlaveScaling` changed in sync; see docs/engine.md,
    /// "Scaling on the fly"): the command moves from the cam with the old
    /// scaling to the cam with the new one, position and velocity
    /// continuous; afterwards it is exactly the cam with the new scaling
    /// and [`AxisConfig::slave_zoom`] reads the new value.
    ///
    /// # Errors
    /// As [`CamAxis::change_offsets`].
    pub fn change_slave_scaling(
        &mut self,
        zoom: Zoom,
        distance: NonZeroU64,
    ) -> Result<(), EngineError> {
        let target = self.geometry.with_slave_zoom(zoom);
        match &mut self.phase {
            Phase::Running(engaged) => {
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                let from = i64::try_from(engaged.followed >> 32).unwrap_or(i64::MAX);
                engaged.scaling = Some(ScalingRamp::new(target, from, distance));
                self.config.slave_zoom = zoom;
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// Changes the master scaling (master zoom) of the running cam at the
    /// next whole master count (as [`SwitchAt::Now`]): the cam's phase (its
    /// table input) and the slave's position are kept there and from then
    /// on the table runs at the new scaling; with `blend` the velocity
    /// moves from the old to the new over that master travel, as a table
    /// switch's blend does. Afterwards [`AxisConfig::master_zoom`] reads
    /// the new value and the cam is an exact function of the master again.
    ///
    /// # Errors
    /// As [`CamAxis::change_offsets`], and as [`CamAxis::new`] for a
    /// scaling that does not fit the table.
    pub fn change_master_scaling(
        &mut self,
        zoom: Zoom,
        blend: Option<NonZeroU64>,
    ) -> Result<(), EngineError> {
        Geometry::new(
            &self.curve,
            &AxisConfig {
                master_zoom: zoom,
                ..self.config
            },
        )?;
        match &mut self.phase {
            Phase::Running(engaged) => {
                if engaged.changing() {
                    return Err(EngineError::Busy);
                }
                engaged.pending = Some(Pending::new(
                    Takeover::MasterScaling(zoom),
                    Trigger::Now,
                    blend,
                ));
                Ok(())
            }
            _ => Err(EngineError::NotRunning),
        }
    }

    /// True while an offset change is being ramped in.
    pub fn is_changing_offsets(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.offsets.is_some())
    }

    /// True while a switch's blend runs.
    pub fn is_blending(&self) -> bool {
        self.phase.engaged().is_some_and(|e| e.blend.is_some())
    }

    /// The table the last switch or replacement retired, if not yet taken.
    pub fn take_retired_curve(&mut self) -> Option<C> {
        self.retired.take()
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
    /// [`SwitchAt::MasterPosition`] switch): take effect there
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
    /// [`EngineError::Busy`] while the cam is engaged.
    pub fn arm(&mut self) -> Result<(), EngineError> {
        match self.phase {
            Phase::Running(_) | Phase::Stopping(..) => Err(EngineError::Busy),
            Phase::Armed(_) => Ok(()),
            Phase::Idle | Phase::Finished => {
                self.missed = false;
                self.phase = Phase::Armed(Armed {
                    watch: StartWatch::arm_with(self.config.start, self.missed_policy),
                    previous: None,
                    delaying: false,
                });
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
            (Phase::Armed(_), _) => {
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

    /// Ends a run: a table still queued is the one to restart with.
    fn end_run(&mut self, engaged: Engaged<C>) {
        let Engaged {
            queued,
            pending,
            scaling,
            ..
        } = engaged;
        // The configuration already names the new scaling.
        if let Some(ramp) = scaling {
            self.geometry = ramp.target;
        }
        let mut next = queued.map(|(curve, _)| curve);
        match pending.map(|p| p.takeover) {
            Some(Takeover::Table(curve)) => next = Some(curve),
            Some(Takeover::MasterScaling(zoom)) => {
                let config = AxisConfig {
                    master_zoom: zoom,
                    ..self.config
                };
                if let Ok(geometry) = Geometry::new(&self.curve, &config) {
                    self.config = config;
                    self.geometry = geometry;
                }
            }
            None => {}
        }
        if let Some(curve) = next
            && let Ok(geometry) = Geometry::new(&curve, &self.config)
        {
            self.geometry = geometry;
            self.cursor = Cursor::new();
            self.retired = Some(core::mem::replace(&mut self.curve, curve));
        }
    }

    /// Leaves any active phase for `Idle` at once (output inhibit, fault).
    fn halt(&mut self) {
        let phase = core::mem::replace(&mut self.phase, Phase::Idle);
        match phase {
            Phase::Running(engaged) | Phase::Stopping(engaged, _) => self.end_run(engaged),
            Phase::Finished => self.phase = Phase::Finished,
            Phase::Idle | Phase::Armed(_) => {}
        }
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
        self.speed.update(estimate, input.dt_us);
        let edge = input.start_input && !self.last_start_input;
        self.last_start_input = input.start_input;

        let mut events = core::mem::take(&mut self.pending_events);
        let mut fault = None;
        let mut sample = None;

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
            fault = Some(EngineError::MasterStep);
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
            match self.engage(at) {
                Ok(()) => events.engaged = true,
                Err(e) => {
                    fault = Some(e);
                    self.halt();
                    events.stopped = true;
                }
            }
        }

        let phase = core::mem::replace(&mut self.phase, Phase::Idle);
        let followed = match phase {
            Phase::Running(engaged) => self.follow(engaged, None, master, estimate.fraction),
            Phase::Stopping(engaged, end) => {
                self.follow(engaged, Some(end), master, estimate.fraction)
            }
            other => Ok((other, None, Events::default())),
        };
        match followed {
            Ok((phase, followed, happened)) => {
                self.phase = phase;
                sample = followed;
                events.merge(happened);
            }
            Err(e) => {
                // The engaged phase was taken out: the axis is idle now.
                fault = Some(e);
                events.stopped = true;
            }
        }

        let hz = effective_frequency(self.config.max_frequency_hz);
        let pulses = self
            .pulse
            .step(self.commanded, input.output_enabled, hz, input.dt_us);
        self.report(master, sample, pulses, events, fault)
    }

    fn engage(&mut self, at: i64) -> Result<(), EngineError> {
        let mut engagement = Engagement::new(
            &self.geometry,
            &self.config,
            &self.curve,
            &mut self.cursor,
            at,
            self.commanded,
        )?;
        let place = self
            .geometry
            .locate(engagement.table_input(&self.geometry, at));
        let ramp_in = match self.ramp_limits {
            Some(limits) => self.limited_ramp(limits, &mut engagement, place)?,
            None => self.config.ramp_in,
        };
        self.phase = Phase::Running(Engaged {
            engagement,
            ramp: ramp_in.map(|ramp| Ramp::new(ramp, at, self.commanded)),
            place,
            queued: None,
            seam_blend: None,
            pending: None,
            blend: None,
            offsets: None,
            scaling: None,
            followed: i128::from(at) << 32,
        });
        Ok(())
    }

    /// The place of `master` under `geometry` (a one-shot held in its span).
    fn resolve_on(&self, geometry: &Geometry, engagement: &Engagement, master: i64) -> Place {
        let mut t = engagement.table_input(geometry, master);
        if let Some((begin, end)) = engagement.span {
            t = t.clamp(begin, end);
        }
        geometry.locate(t)
    }

    /// The ramp-in that keeps to `limits` for the engagement at `place`,
    /// after moving its target by whole strokes for a restricted direction.
    fn limited_ramp(
        &mut self,
        limits: RampInLimits,
        engagement: &mut Engagement,
        place: Place,
    ) -> Result<Option<RampIn>, EngineError> {
        let hold = i128::from(self.commanded);
        let mut cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
        let wrong_way = |slave: i64| {
            let gap = i128::from(slave) - hold;
            match limits.direction {
                RampDirection::Either => false,
                RampDirection::Positive => gap < 0,
                RampDirection::Negative => gap > 0,
            }
        };
        if wrong_way(cam.slave) {
            let stroke = self.geometry.stroke_pulses();
            if stroke == 0.0 {
                return Err(EngineError::RampDirection);
            }
            let gap = (i128::from(cam.slave) - hold) as f64;
            let strokes = libm::ceil(libm::fabs(gap / stroke));
            let toward = match limits.direction {
                RampDirection::Negative => -1.0,
                _ => 1.0,
            };
            let n = strokes * toward * libm::copysign(1.0, stroke);
            engagement.add_strokes(n as i128);
            cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
            if wrong_way(cam.slave) {
                // Rounding left it a pulse short: one stroke more.
                engagement.add_strokes(libm::copysign(1.0, n) as i128);
                cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
            }
        }
        let gap = (i128::from(cam.slave) - hold) as f64;
        let needed = limits.distance(gap, cam.velocity_ratio, self.speed.bound())?;
        let configured = self.config.ramp_in.map(|r| r.distance.get());
        Ok(match (needed, configured) {
            (Some(a), Some(b)) => NonZeroU64::new(a.max(b)),
            (Some(d), None) | (None, Some(d)) => NonZeroU64::new(d),
            // A master at rest gives no speed to size the ramp for: one
            // master count per 1/1.875 pulse of gap.
            (None, None) => NonZeroU64::new(libm::ceil(1.875 * libm::fabs(gap)).max(1.0) as u64),
        }
        .map(|distance| RampIn { distance }))
    }

    /// Where the cam stands for `master`: the place (clamped to a one-shot's
    /// span or to the end of a requested end-of-cycle stop), whether a
    /// one-shot finished, and whether the stop was reached (and forwards).
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
        let cam = engaged.engagement_at(master)?.sample(
            &self.geometry,
            &self.curve,
            &mut self.cursor,
            place,
        )?;
        let (slave, ratio) = match (&engaged.blend, &engaged.scaling) {
            (Some(blend), _) => {
                let blended = blend.command(master)?;
                (blended.slave, blended.velocity_ratio)
            }
            (None, Some(scaling)) => {
                let new = engaged.engagement_at(master)?.sample(
                    &scaling.target,
                    &self.curve,
                    &mut self.cursor,
                    place,
                )?;
                scaling.mix(
                    master,
                    (cam.slave, cam.velocity_ratio),
                    (new.slave, new.velocity_ratio),
                )
            }
            (None, None) => (cam.slave, cam.velocity_ratio),
        };
        match engaged
            .ramp
            .and_then(|ramp| Some((ramp, ramp.blend(master, slave)?)))
        {
            Some((ramp, blended)) => Ok((cam, blended, ratio * ramp.weight(master), true)),
            None => Ok((cam, slave, ratio, false)),
        }
    }

    /// Carries out a waiting position or at-once switch at master `at`:
    /// the new cam is aligned to the master as at engage and anchored on
    /// the old cam's position there; a blend then carries the slave from
    /// the old cam's velocity to the new cam's.
    fn switch_at(&mut self, engaged: &mut Engaged<C>, at: i64) -> Result<(), EngineError> {
        let Some(pending) = engaged.pending.take() else {
            return Ok(());
        };
        let place = self.resolve(&engaged.engagement, None, at).place;
        let old =
            engaged
                .engagement
                .sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
        match pending.takeover {
            Takeover::Table(curve) => {
                let geometry = Geometry::new(&curve, &self.config)?;
                let mut cursor = Cursor::new();
                let config = AxisConfig {
                    slave_align: SlaveAlign::Relative,
                    ..self.config
                };
                let engagement =
                    Engagement::new(&geometry, &config, &curve, &mut cursor, at, old.slave)?;
                engaged.engagement = engagement;
                self.geometry = geometry;
                self.cursor = cursor;
                self.retired = Some(core::mem::replace(&mut self.curve, curve));
            }
            Takeover::MasterScaling(zoom) => {
                let config = AxisConfig {
                    master_zoom: zoom,
                    ..self.config
                };
                let geometry = Geometry::new(&self.curve, &config)?;
                let mut engagement =
                    engaged
                        .engagement
                        .with_master_rescaled(&self.geometry, &geometry, at)?;
                let place = self.resolve_on(&geometry, &engagement, at);
                let new = engagement.sample(&geometry, &self.curve, &mut self.cursor, place)?;
                // Anchored: the new table unit may round the phase.
                engagement.shift_output(i128::from(old.slave) - i128::from(new.slave))?;
                engaged.engagement = engagement;
                self.geometry = geometry;
                self.config = config;
            }
        }
        engaged.blend = match pending.blend {
            Some(distance) => {
                let engagement = engaged.engagement;
                Some(self.blend_onto(&engagement, at, distance, old.slave, old.velocity_ratio)?)
            }
            None => None,
        };
        Ok(())
    }

    /// Takes a queued table over at the seam between the last place and
    /// `to`, if one waits; gives back the engagement on the new table.
    fn switch_at_seam(&mut self, engaged: &mut Engaged<C>, to: Place) -> Result<bool, EngineError> {
        let from = engaged.place;
        // A seam crossed while a blend runs is not taken: the switch waits
        // for the next seam after the blend.
        if from.k == to.k
            || engaged.queued.is_none()
            || engaged.blend.is_some()
            || engaged.offsets.is_some()
            || engaged.scaling.is_some()
        {
            return Ok(false);
        }
        let forward = to.k > from.k;
        // The first boundary crossed: the end of the last cycle going
        // forwards, its start going backwards.
        let at_seam = if forward {
            self.geometry.cycle_end(from.k)
        } else {
            Geometry::cycle_start(from.k)
        };
        let old =
            engaged
                .engagement
                .sample(&self.geometry, &self.curve, &mut self.cursor, at_seam)?;
        let Some((curve, then)) = engaged.queued.take() else {
            return Ok(false);
        };
        // A blend starts at the last whole master count before the seam,
        // on the old cam there.
        let blend_from = match engaged.seam_blend.take() {
            Some(distance) => {
                let at = engaged
                    .engagement
                    .master_at_seam(&self.geometry, from.k, forward);
                let place = self.resolve(&engaged.engagement, None, at).place;
                // Exactly on the seam: seen from the old cycle's side.
                let there = if place.k == from.k {
                    engaged.engagement.sample(
                        &self.geometry,
                        &self.curve,
                        &mut self.cursor,
                        place,
                    )?
                } else {
                    old
                };
                Some((at, distance, there.slave, there.velocity_ratio))
            }
            None => None,
        };
        let geometry = Geometry::new(&curve, &self.config)?;
        let mut cursor = Cursor::new();
        let mut next = engaged.engagement.across_seam(
            &self.geometry,
            &geometry,
            &curve,
            &mut cursor,
            from.k,
            forward,
            old.slave,
        )?;
        if then == AfterPass::Finish {
            next.finish_after_first_pass(&geometry, forward);
        }
        self.geometry = geometry;
        self.cursor = cursor;
        self.retired = Some(core::mem::replace(&mut self.curve, curve));
        engaged.engagement = next;
        if let Some((at, distance, p0, v0)) = blend_from {
            engaged.blend = Some(self.blend_onto(&engaged.engagement, at, distance, p0, v0)?);
        }
        Ok(true)
    }

    /// A blend from the slave at `p0` with velocity ratio `v0` at master
    /// `at` onto the (new) cam of `engagement`.
    fn blend_onto(
        &mut self,
        engagement: &Engagement,
        at: i64,
        distance: NonZeroU64,
        p0: i64,
        v0: f64,
    ) -> Result<Blend, EngineError> {
        let mut ends = [BlendEnd {
            slave: 0,
            velocity_ratio: 0.0,
        }; 2];
        for (end, master) in ends.iter_mut().zip(Blend::ends(at, distance.get())?) {
            let place = self.resolve(engagement, None, master).place;
            let cam = engagement.sample(&self.geometry, &self.curve, &mut self.cursor, place)?;
            *end = BlendEnd {
                slave: cam.slave,
                velocity_ratio: cam.velocity_ratio,
            };
        }
        Blend::start(at, distance.get(), p0, v0, ends)
    }

    /// Follows the cam for one tick; gives the phase after it, what was
    /// followed and what happened.
    fn follow(
        &mut self,
        mut engaged: Engaged<C>,
        stop_at: Option<CycleEnd>,
        master: i64,
        fraction: u32,
    ) -> Result<(Phase<C>, Option<FollowSample>, Events), EngineError> {
        let mut events = Events::default();
        if let Some(ramp) = engaged.offsets
            && ramp.finished(master)
        {
            engaged.engagement = ramp.apply(&engaged.engagement, master)?;
            engaged.offsets = None;
        }
        if let Some(ramp) = engaged.scaling
            && ramp.finished(master)
        {
            self.geometry = ramp.target;
            engaged.scaling = None;
        }
        let mut here = self.resolve(&engaged.engagement_at(master)?, stop_at.as_ref(), master);
        if here.stopped.is_none() && self.switch_at_seam(&mut engaged, here.place)? {
            events.table_switched = true;
            events.cycle_completed = true;
            here = self.resolve(&engaged.engagement, stop_at.as_ref(), master);
            // Cycle indices restart with the new table.
            engaged.place = here.place;
        }
        if let Some(shift) = engaged.blend.as_ref().and_then(|b| b.finished(master)) {
            engaged.engagement.shift_output(shift)?;
            engaged.blend = None;
        }
        if here.stopped.is_none() && stop_at.is_none() {
            let blending = engaged.blend.is_some();
            let previous = engaged.followed;
            let now = (i128::from(master) << 32) | i128::from(fraction);
            let policy = self.missed_policy;
            let fired = engaged
                .pending
                .as_mut()
                .map(|p| p.fires(previous, now, blending, policy));
            events.activation_missed |= fired.is_some_and(|f| f.missed);
            if let Some(at) = fired.and_then(|f| f.at) {
                self.switch_at(&mut engaged, at)?;
                events.table_switched = true;
                here = self.resolve(&engaged.engagement, None, master);
                engaged.place = here.place;
            }
        }
        engaged.followed = (i128::from(master) << 32) | i128::from(fraction);
        let place = here.place;
        let (cam, mut slave, velocity_ratio, ramping) =
            self.command_at(&mut engaged, place, master)?;
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
            let (_, next_slave, _, _) = self.command_at(&mut engaged, ahead.place, next_master)?;
            let gap = i128::from(next_slave) - i128::from(slave);
            let step = (gap * i128::from(fraction) + (1 << 31)) >> 32;
            slave =
                i64::try_from(i128::from(slave) + step).map_err(|_| EngineError::SlaveOverflow)?;
        }
        if !ramping {
            engaged.ramp = None;
        }
        let blending = engaged.blend.is_some();
        self.commanded = slave;
        if engaged.place.k != place.k {
            events.cycle_completed = true;
            events.seam_jump |= self.geometry.jumps_at_seam;
        }
        engaged.place = place;
        let followed = FollowSample {
            cam,
            velocity_ratio,
            following: !ramping
                && !blending
                && engaged.offsets.is_none()
                && engaged.scaling.is_none(),
            input_offset: engaged.engagement.input_offset(&self.geometry),
            cycle: place.k.saturating_sub(engaged.engagement.k_engage),
        };
        let phase = if let Some(forward) = here.stopped {
            events.cycle_completed |= forward;
            events.stopped = true;
            self.end_run(engaged);
            Phase::Finished
        } else if here.finished {
            events.finished = true;
            events.cycle_completed = true;
            self.end_run(engaged);
            Phase::Finished
        } else {
            match stop_at {
                Some(end) => Phase::Stopping(engaged, end),
                None => Phase::Running(engaged),
            }
        };
        Ok((phase, Some(followed), events))
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
        let state = self.state();
        out.state = state;
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
            if state.is_engaged() {
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
        out.sync = if state.is_engaged() {
            active_windows(&self.config.sync_windows, out.master_in_cycle)
        } else {
            0
        };
        out.in_sync = out.sync != 0;
        out.initialised = state.is_active();
        out.busy = out.initialised || out.backlog != 0;
        if events.engaged || events.table_switched {
            self.missed = false;
        }
        self.missed |= events.activation_missed;
        out.activation_missed = self.missed;
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
