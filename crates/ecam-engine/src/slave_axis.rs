//! One slave, several couplings (beyond the documents): a cam, a gear and
//! a superimposed move summed on the same axis, through the master the
//! slave sees (direction-guarded, phase-shifted, registration-corrected),
//! with a modulo (rotary) slave's position reported beside the
//! accumulated one.
//!
//! Per tick, in this order:
//!
//! 1. the master: a single turn unwrapped, a coarse master tracked
//!    ([`SlaveConfig::master_filter`]), fixed point with 32 fraction bits;
//! 2. the direction guard ([`DirectionGuard`]): the master the slave follows;
//! 3. registration ([`RegistrationConfig`]): a latch this tick corrects
//!    the phase (or the slave), ramped over a master distance;
//! 4. phasing ([`Phasing`]): the shift of the master the slave sees;
//! 5. the cam ([`CamPart`]) ticked with that master (its fraction too);
//! 6. the gear ([`GearIn`], [`GearInPos`]) on the same master;
//! 7. the superimposed move ([`MoveSuperimposed`]) over time;
//! 8. the sum, whole turns of a modulo slave's seams added, goes out as
//!    pulses under the axis' frequency ceiling (the backlog is flagged,
//!    never dropped).
//!
//! Each part is exact on its own (the cam and the gear are integer
//! functions of the master seen, the timed moves end on whole units), so
//! the sum is exact: the slave is the cam's part plus the gear's plus the
//! superimposed move's plus the registration offset, to the pulse, every
//! tick. The cam itself runs unchanged: an axis that uses none of this
//! pays nothing for it (this is a separate type around the cam).

use ecam_core::CamCurve;

use crate::cam_part::CamPart;
use crate::config::effective_frequency;
use crate::direction_guard::Guard;
use crate::gear::Gear;
use crate::master::TurnUnwrap;
use crate::phasing::PhaseShift;
use crate::pulse::PulseOutput;
use crate::registration::Registration;
use crate::speed::MasterSpeed;
use crate::superimposed::Superimposed;
use crate::timed_move::{ONE, to_units, whole};
use crate::{
    CouplingError, DirectionGuard, GearIn, GearInPos, GearOut, GearStatus, GuardStatus,
    LatchSource, MAX_FREQUENCY_HZ, MasterFilter, MasterPosition, MasterTracker, ModuloAxis,
    ModuloPosition, MoveSuperimposed, Phasing, PhasingStatus, RegistrationConfig,
    RegistrationStatus, SuperimposedStatus, TickInput, TickOutput,
};

/// The settings of a slave axis around its cam.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SlaveConfig {
    /// The axis' pulse ceiling in Hz (the same rule as
    /// [`crate::AxisConfig::max_frequency_hz`]): the sum of the parts goes
    /// out under it.
    pub max_frequency_hz: i64,
    /// How master readings become the position followed. The cam's own
    /// filter should stay [`MasterFilter::Direct`]: the slave axis hands it
    /// the tracked master with its fraction.
    pub master_filter: MasterFilter,
    /// A rotary slave: its position in the turn is reported, and seams of
    /// a periodic cam drop whole turns as the start mode says. (Which turn
    /// a cam engages in is the cam's [`crate::SlaveAlign::Modulo`].)
    pub modulo: Option<ModuloAxis>,
    /// Follow the master in one direction only.
    pub guard: Option<DirectionGuard>,
    /// Print-mark correction.
    pub registration: Option<RegistrationConfig>,
}

impl Default for SlaveConfig {
    fn default() -> Self {
        Self {
            max_frequency_hz: i64::from(MAX_FREQUENCY_HZ),
            master_filter: MasterFilter::Direct,
            modulo: None,
            guard: None,
            registration: None,
        }
    }
}

/// What goes into one tick of a slave axis.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SlaveInput {
    /// The master reading and the cam's inputs (start input, watch, tick
    /// length, output enable), as for [`crate::CamAxis::tick`].
    pub tick: TickInput,
    /// A touch-probe latch this tick (PLCopen `MC_TouchProbe`
    /// `RecordedPosition`): the master position (as read, a single-turn
    /// master's turn position included) or the slave position at the
    /// mark, as [`RegistrationConfig::source`] says.
    pub latch: Option<i64>,
}

/// Everything a slave axis reports after a tick.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SlaveOutput {
    /// The cam's own output (its `slave` is the cam's part; its pulse
    /// fields are not the axis').
    pub cam: TickOutput,
    /// The commanded slave: the sum of the parts (accumulated on a modulo
    /// slave).
    pub slave: i64,
    /// Pulses emitted this tick, signed.
    pub pulses: i64,
    /// Direction of the last pulses.
    pub direction_forward: bool,
    /// Cumulative emitted position.
    pub emitted: i64,
    /// Commanded minus emitted.
    pub backlog: i64,
    /// The command asked for more than the ceiling: pulses are owed.
    pub pulse_delayed: bool,
    /// Any part is moving or pulses are owed.
    pub busy: bool,
    /// A modulo slave's place in the turn and whole turns.
    pub modulo: Option<ModuloPosition>,
    /// The master the slave sees (guarded, shifted, corrected), counts.
    pub master_seen: f64,
    /// The gear's part and state.
    pub gear: GearStatus,
    /// The superimposed move's part and state.
    pub superimposed: SuperimposedStatus,
    /// The phase shift and its state.
    pub phasing: PhasingStatus,
    /// Registration's counts and correction.
    pub registration: Option<RegistrationStatus>,
    /// The direction guard's state.
    pub guard: Option<GuardStatus>,
    /// A gear command that could not be carried out at this tick (its
    /// sync position passed meanwhile); the gear kept what it did.
    pub fault: Option<CouplingError>,
}

/// A gear command waiting for the next tick's master.
#[derive(Clone, Copy, Debug, PartialEq)]
enum GearCommand {
    In(GearIn),
    InPos(GearInPos),
    Out(GearOut),
}

/// How many commands each coupling has taken (a function block tells by
/// them when another command took over).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Commands {
    /// `MC_GearIn`, `MC_GearInPos`, `MC_GearOut`.
    pub gear: u64,
    /// `MC_Phasing`.
    pub phasing: u64,
    /// `MC_MoveSuperimposed`, `MC_HaltSuperimposed`.
    pub superimposed: u64,
}

/// A slave axis: a cam plus a gear, a superimposed move, phasing,
/// registration, a direction guard and a modulo, summed.
///
/// ```
/// use core::num::NonZeroU64;
/// use ecam_core::PointTable;
/// use ecam_engine::{
///     AxisConfig, CamAxis, Coupling, GearIn, GearRamp, MoveLimits, MoveSuperimposed,
///     SlaveAxis, SlaveConfig, SlaveInput, TickInput, Zoom,
/// };
///
/// let table = PointTable::from_pairs(&[(0, 0), (1000, 500)])?;
/// let config = AxisConfig { coupling: Coupling::Repeat { min_stroke: 1 }, ..AxisConfig::default() };
/// let mut cam = CamAxis::new(table, config)?;
/// cam.arm()?;
/// let mut axis = SlaveAxis::new(cam, SlaveConfig::default())?;
/// axis.gear_in(&GearIn { ratio: Zoom::signed(2, 1)?, ramp: GearRamp::Immediate })?;
/// axis.move_superimposed(&MoveSuperimposed {
///     distance: 100,
///     limits: MoveLimits::new(10_000.0, 1e6, 1e6)?,
/// })?;
/// let mut out = *axis.tick(&SlaveInput { tick: TickInput::at(0, 1000), latch: None });
/// for master in 1..=2000 {
///     out = *axis.tick(&SlaveInput { tick: TickInput::at(master, 1000), latch: None });
/// }
/// // cam 1000 (two cycles of 500) + gear 2 × 2000 + superimposed 100:
/// assert_eq!(out.cam.slave, 1000);
/// assert_eq!(out.gear.slave, 4000);
/// assert_eq!(out.slave, 5100);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct SlaveAxis<K: CamPart> {
    cam: K,
    config: SlaveConfig,
    turn: Option<TurnUnwrap>,
    tracker: MasterTracker,
    guard: Option<Guard>,
    registration: Option<Registration>,
    phase: PhaseShift,
    superimposed: Superimposed,
    gear: Gear,
    speed: MasterSpeed,
    pulse: PulseOutput,
    commanded: i64,
    /// Whole modulo turns the seams added, not yet handed to the cam.
    turns: i128,
    last_cycle: i64,
    seen: i128,
    /// At least one tick has run (the master seen is known).
    started: bool,
    /// Gear commands take effect at the next tick, on its master.
    pending_gear: Option<GearCommand>,
    commands: Commands,
    cam_status: Option<K::Status>,
    last: SlaveOutput,
}

/// An acceleration ramp must be a finite number above zero.
fn check_ramp(ramp: crate::GearRamp) -> Result<(), CouplingError> {
    match ramp {
        crate::GearRamp::Acceleration(a) if !(a.is_finite() && a > 0.0) => {
            Err(CouplingError::BadLimit)
        }
        _ => Ok(()),
    }
}

/// Fixed point (32 fraction bits) of a master position.
fn fixed(p: MasterPosition) -> i128 {
    (i128::from(p.counts) << 32) | i128::from(p.fraction)
}

fn clamp(v: i128) -> i64 {
    i64::try_from(v).unwrap_or(if v < 0 { i64::MIN } else { i64::MAX })
}

impl<K: CamPart> SlaveAxis<K> {
    /// A slave axis around `cam`, the slave standing where the cam's part does.
    ///
    /// # Errors
    /// [`CouplingError::BadRegistration`] for registration settings that do
    /// not fit together.
    pub fn new(cam: K, config: SlaveConfig) -> Result<Self, CouplingError> {
        let registration = config.registration.map(Registration::new).transpose()?;
        let commanded = cam.engine().commanded();
        Ok(Self {
            turn: cam.engine().config().single_turn.map(TurnUnwrap::new),
            cam,
            config,
            tracker: MasterTracker::new(config.master_filter),
            guard: config.guard.map(Guard::new),
            registration,
            phase: PhaseShift::new(),
            superimposed: Superimposed::new(),
            gear: Gear::new(),
            speed: MasterSpeed::new(),
            pulse: PulseOutput::at(commanded),
            commanded,
            turns: 0,
            last_cycle: 0,
            seen: 0,
            started: false,
            pending_gear: None,
            commands: Commands::default(),
            cam_status: None,
            last: SlaveOutput {
                slave: commanded,
                emitted: commanded,
                direction_forward: true,
                ..SlaveOutput::default()
            },
        })
    }

    /// The cam.
    pub fn cam(&self) -> &K {
        &self.cam
    }

    /// The cam, to arm, stop or change it (a start is best asked for
    /// between ticks, as on a plain cam axis).
    pub fn cam_mut(&mut self) -> &mut K {
        &mut self.cam
    }

    /// The cam's status of the last tick (`None` before the first).
    pub fn cam_status(&self) -> Option<&K::Status> {
        self.cam_status.as_ref()
    }

    /// The settings.
    pub fn config(&self) -> &SlaveConfig {
        &self.config
    }

    /// The output of the last tick.
    pub fn status(&self) -> &SlaveOutput {
        &self.last
    }

    /// The commands taken so far.
    pub fn commands(&self) -> Commands {
        self.commands
    }

    /// Declares where the slave stands (no pulses are sent for it): the
    /// cam's part is set so that the sum is `position`.
    ///
    /// # Errors
    /// [`crate::EngineError::Busy`] while the cam is active, the gear
    /// coupled or a timed move running.
    pub fn set_slave_position(&mut self, position: i64) -> Result<(), CouplingError> {
        let others = i128::from(self.gear.status().slave)
            + i128::from(self.superimposed.pulses())
            + self.turns_pulses()
            + self.slave_correction();
        if self.gear.status().state != crate::GearState::Off
            || self.superimposed.status().active
            || self.phase.status().active
        {
            return Err(crate::EngineError::Busy.into());
        }
        let part = i128::from(position) - others;
        self.cam
            .set_position(i64::try_from(part).map_err(|_| crate::EngineError::SlaveOverflow)?)?;
        self.commanded = position;
        self.pulse = PulseOutput::at(position);
        self.last.slave = position;
        self.last.emitted = position;
        self.last.backlog = 0;
        self.last.pulse_delayed = false;
        Ok(())
    }

    fn turns_pulses(&self) -> i128 {
        self.config
            .modulo
            .map_or(0, |m| self.turns * i128::from(m.modulo()))
    }

    fn slave_correction(&self) -> i128 {
        match &self.registration {
            Some(r) if r.source() == LatchSource::Slave => whole(r.current()),
            _ => 0,
        }
    }

    /// `MC_GearIn`: couple the gear's part at the ratio, from where it
    /// stands (see [`crate::GearRamp`] for how it gets there).
    ///
    /// # Errors
    /// [`CouplingError::BadLimit`] for an acceleration that is not a
    /// finite number above zero.
    pub fn gear_in(&mut self, command: &GearIn) -> Result<(), CouplingError> {
        check_ramp(command.ramp)?;
        self.pending_gear = Some(GearCommand::In(*command));
        self.commands.gear += 1;
        Ok(())
    }

    /// `MC_GearInPos`: reach the sync point, then follow at the ratio.
    ///
    /// # Errors
    /// [`CouplingError::SyncPassed`] when the master, moving as it moves
    /// now, has already passed the sync position.
    pub fn gear_in_pos(&mut self, command: &GearInPos) -> Result<(), CouplingError> {
        if self.started {
            // Checked now on the last master; carried out at the next tick.
            let mut trial = self.gear;
            trial.gear_in_pos(command, self.seen, self.speed.velocity())?;
        }
        self.pending_gear = Some(GearCommand::InPos(*command));
        self.commands.gear += 1;
        Ok(())
    }

    /// `MC_GearOut`: bring the gear's ratio to 0 and leave its part there.
    ///
    /// # Errors
    /// As [`SlaveAxis::gear_in`].
    pub fn gear_out(&mut self, command: &GearOut) -> Result<(), CouplingError> {
        check_ramp(command.ramp)?;
        self.pending_gear = Some(GearCommand::Out(*command));
        self.commands.gear += 1;
        Ok(())
    }

    /// `MC_PhasingAbsolute` / `MC_PhasingRelative`: shift the master the
    /// slave sees, ramped over time.
    ///
    /// # Errors
    /// [`CouplingError::BadLimit`] when the shift does not fit.
    pub fn phasing(&mut self, command: &Phasing) -> Result<(), CouplingError> {
        self.phase.command(command)?;
        self.commands.phasing += 1;
        Ok(())
    }

    /// Brings a running phase shift to rest at `deceleration` counts/s²,
    /// on a whole count.
    ///
    /// # Errors
    /// [`CouplingError::BadLimit`] for a deceleration that is not a finite
    /// number above zero.
    pub fn halt_phasing(&mut self, deceleration: f64) -> Result<(), CouplingError> {
        if !(deceleration.is_finite() && deceleration > 0.0) {
            return Err(CouplingError::BadLimit);
        }
        self.phase.halt(deceleration);
        self.commands.phasing += 1;
        Ok(())
    }

    /// `MC_MoveSuperimposed`: add a distance to the slave over time.
    ///
    /// # Errors
    /// [`CouplingError::AboveCeiling`] when its velocity is above the
    /// axis' pulse ceiling.
    pub fn move_superimposed(&mut self, command: &MoveSuperimposed) -> Result<(), CouplingError> {
        let ceiling = effective_frequency(self.config.max_frequency_hz);
        self.superimposed.command(command, ceiling)?;
        self.commands.superimposed += 1;
        Ok(())
    }

    /// `MC_HaltSuperimposed`: bring the superimposed move to rest at
    /// `deceleration` pulses/s², on a whole pulse; what it covered stays.
    ///
    /// # Errors
    /// [`CouplingError::BadLimit`] for a deceleration that is not a finite
    /// number above zero.
    pub fn halt_superimposed(&mut self, deceleration: f64) -> Result<(), CouplingError> {
        if !(deceleration.is_finite() && deceleration > 0.0) {
            return Err(CouplingError::BadLimit);
        }
        self.superimposed.halt(deceleration);
        self.commands.superimposed += 1;
        Ok(())
    }

    /// Holds the gear, the phase shift and the superimposed move where they
    /// stand (a velocity step, as a cam's immediate stop); the cam is
    /// stopped through [`SlaveAxis::cam_mut`].
    pub fn stop_couplings(&mut self) {
        self.pending_gear = None;
        self.gear.stop();
        self.phase.stop();
        self.superimposed.stop();
        self.commands.gear += 1;
        self.commands.phasing += 1;
        self.commands.superimposed += 1;
    }

    /// The seam jump of the cam's table (after slave zoom) crossed forwards
    /// or backwards, in pulses.
    fn seam_jump(&self, forward: bool) -> f64 {
        let engine = self.cam.engine();
        let curve = engine.curve();
        let step =
            (curve.slave_first() - curve.slave_last()) as f64 * engine.config().slave_zoom.ratio();
        if forward { step } else { -step }
    }

    /// One control cycle. No allocation; the work is the cam's plus a
    /// bounded amount per coupling.
    pub fn tick(&mut self, input: &SlaveInput) -> &SlaveOutput {
        let t = &input.tick;
        if !t.output_enabled {
            // Inhibited: every part holds, as the cam does (it stops itself).
            self.pending_gear = None;
            self.gear.stop();
            self.phase.stop();
            self.superimposed.stop();
        }
        let raw = match &mut self.turn {
            Some(u) => u.update(t.master),
            None => t.master,
        };
        let m = fixed(self.tracker.update(raw, t.master_fraction, t.dt_us));
        let g = match &mut self.guard {
            Some(guard) => guard.update(m),
            None => m,
        };
        let phase = self.phase.advance(t.dt_us);
        let mut master_correction = 0;
        let mut slave_correction = 0;
        if let Some(reg) = &mut self.registration {
            if let Some(latch) = input.latch {
                match reg.source() {
                    LatchSource::Master => {
                        let latch = match self.cam.engine().config().single_turn {
                            // A turn position: the one nearest the reading.
                            Some(turn) => {
                                let turn = i128::from(turn.get());
                                let d = (i128::from(latch) - i128::from(t.master)).rem_euclid(turn);
                                let d = if 2 * d > turn { d - turn } else { d };
                                i128::from(raw) + d
                            }
                            None => i128::from(latch),
                        };
                        reg.latch(latch * ONE + (g - m) + phase, g);
                    }
                    LatchSource::Slave => reg.latch(i128::from(latch) * ONE, g),
                }
            }
            let correction = reg.correction_at(g);
            match reg.source() {
                LatchSource::Master => master_correction = correction,
                LatchSource::Slave => slave_correction = whole(correction),
            }
        }
        let seen = g + phase + master_correction;
        self.seen = seen;
        let seen_position = MasterPosition {
            counts: clamp(seen >> 32),
            fraction: (seen & (ONE - 1)) as u32,
        };
        self.speed.update(seen_position, t.dt_us);
        let master = match self.cam.engine().config().single_turn {
            Some(turn) => {
                let turn = i128::from(turn.get());
                clamp(i128::from(seen_position.counts).rem_euclid(turn))
            }
            None => seen_position.counts,
        };
        let status = self.cam.tick_cam(&TickInput {
            master,
            master_fraction: seen_position.fraction,
            ..*t
        });
        let cam = *K::output(&status);
        self.cam_status = Some(status);
        if let Some(modulo) = self.config.modulo
            && cam.events.seam_jump
            && cam.cycle != self.last_cycle
        {
            let forward = cam.cycle > self.last_cycle;
            self.turns += modulo.seam_turns(self.seam_jump(forward));
        }
        self.last_cycle = cam.cycle;
        let mut fault = None;
        if let Some(command) = self.pending_gear.take() {
            // The change starts from where the gear is at this master, with
            // the ratio it has here: no tick stands still in between.
            self.gear.at(seen);
            let (speed, velocity) = (self.speed.bound(), self.speed.velocity());
            let done = match command {
                GearCommand::In(c) => self.gear.gear_in(&c, seen, speed),
                GearCommand::InPos(c) => self.gear.gear_in_pos(&c, seen, velocity),
                GearCommand::Out(c) => self.gear.gear_out(&c, seen, speed),
            };
            fault = done.err();
        }
        self.started = true;
        let gear = self.gear.at(seen);
        let superimposed = self.superimposed.advance(t.dt_us);
        let sum = i128::from(cam.slave)
            + i128::from(gear)
            + i128::from(superimposed)
            + slave_correction
            + self.turns_pulses();
        let sum = clamp(sum);
        if let Some(reg) = &mut self.registration {
            match reg.source() {
                LatchSource::Master => reg.watch(g + phase),
                LatchSource::Slave => reg.watch(i128::from(sum) * ONE),
            }
        }
        let hz = effective_frequency(self.config.max_frequency_hz);
        self.commanded = sum;
        let pulses = self.pulse.step(sum, t.output_enabled, hz, t.dt_us);
        if self.turns != 0 && !cam.state.is_active() {
            // Hand the seams' whole turns to the idle cam, so that its
            // next start picks its turn from where the slave really is.
            let part = i128::from(cam.slave) + self.turns_pulses();
            if let Ok(part) = i64::try_from(part)
                && self.cam.set_position(part).is_ok()
            {
                self.turns = 0;
            }
        }
        self.report(cam, sum, pulses, seen, fault)
    }

    fn report(
        &mut self,
        cam: TickOutput,
        sum: i64,
        pulses: i64,
        seen: i128,
        fault: Option<CouplingError>,
    ) -> &SlaveOutput {
        let backlog = self.pulse.backlog(sum);
        let gear = self.gear.status();
        let superimposed = self.superimposed.status();
        let phasing = self.phase.status();
        let out = &mut self.last;
        out.cam = cam;
        out.slave = sum;
        out.pulses = pulses;
        out.direction_forward = self.pulse.forward;
        out.emitted = self.pulse.emitted;
        out.backlog = backlog;
        out.pulse_delayed = backlog != 0;
        out.busy = cam.initialised
            || backlog != 0
            || gear.state != crate::GearState::Off
            || superimposed.active
            || phasing.active;
        out.modulo = self.config.modulo.map(|m| m.locate(sum));
        out.master_seen = to_units(seen);
        out.gear = gear;
        out.superimposed = superimposed;
        out.phasing = phasing;
        out.registration = self.registration.as_mut().map(Registration::status);
        out.guard = self.guard.as_ref().map(Guard::status);
        out.fault = fault;
        out
    }
}

impl<C: CamCurve> SlaveAxis<crate::CamAxis<C>> {
    /// A slave axis around a cam built from `curve` and `config`.
    ///
    /// # Errors
    /// As [`crate::CamAxis::new`] and [`SlaveAxis::new`].
    pub fn with_cam(
        curve: C,
        config: crate::AxisConfig,
        slave: SlaveConfig,
    ) -> Result<Self, CouplingError> {
        Self::new(crate::CamAxis::new(curve, config)?, slave)
    }
}
