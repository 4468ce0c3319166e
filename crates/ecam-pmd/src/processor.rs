//! The motion processor: axes, buffer memory, time, and the commands of document 002.
//!
//! Commands apply between cycles; [`MotionProcessor::tick`] runs one
//! processor cycle: simulated moves, then breakpoints, then cams (in axis
//! order, so a cam sourcing a lower-numbered cam axis sees this cycle's
//! position). Every command checks everything before it writes anything,
//! so a refused command leaves the processor as it was.

use std::cell::RefCell;
use std::rc::Rc;

use crate::axis::{Axis, LinearMove, Motion, ProfileMode, StopMode, event_bit};
use crate::breakpoint::{Action, Breakpoint, BreakpointWord, Event, Trigger};
use crate::{
    BufferCam, BufferId, BufferMemory, CamParam, CamSettings, PmdError, RunningCam, SharedMemory,
    SourceRegister,
};

/// Most axes a processor may have (the breakpoint word's source-axis field is 4 bits).
pub const MAX_AXES: u8 = 16;

/// A simulated motion processor with cam profile mode.
#[derive(Debug)]
pub struct MotionProcessor {
    axes: Vec<Axis>,
    memory: SharedMemory,
    time: i64,
}

impl Default for MotionProcessor {
    /// A four-axis processor, like the Magellan parts document 002 was written for.
    fn default() -> Self {
        Self::with_axes(4)
    }
}

fn check_i32(what: &'static str, value: i64) -> Result<i64, PmdError> {
    i32::try_from(value)
        .map(i64::from)
        .map_err(|_| PmdError::OutOfRange {
            what,
            value,
            allowed: "a signed 32-bit number",
        })
}

/// A position or offset as the processor's 32-bit register holds it.
///
/// Document 002: "GetCam ... return[s] a signed 32 bit value", and the
/// position registers are 32 bits wide. The face keeps positions unwrapped
/// (an incremental cam may run past 2^31 counts, and a cam input must not
/// jump there), and reports them the way the device does: wrapped to a
/// signed 32-bit value, like any 32-bit counter.
fn register_value(value: i64) -> i64 {
    i64::from(value as i32)
}

impl MotionProcessor {
    /// A processor with `count` axes (clamped to 1..=[`MAX_AXES`]).
    pub fn with_axes(count: u8) -> Self {
        let count = count.clamp(1, MAX_AXES);
        Self {
            axes: (0..count).map(|_| Axis::default()).collect(),
            memory: Rc::new(RefCell::new(BufferMemory::new())),
            time: 0,
        }
    }

    /// Number of axes.
    pub fn axis_count(&self) -> u8 {
        u8::try_from(self.axes.len()).unwrap_or(MAX_AXES)
    }

    /// Cycles run since power-up (the cam time base).
    pub fn time(&self) -> i64 {
        self.time
    }

    fn axis(&self, axis: u8) -> Result<&Axis, PmdError> {
        self.axes
            .get(usize::from(axis))
            .ok_or(PmdError::NoSuchAxis {
                axis: i64::from(axis),
                count: self.axis_count(),
            })
    }

    fn axis_mut(&mut self, axis: u8) -> Result<&mut Axis, PmdError> {
        let count = self.axis_count();
        self.axes
            .get_mut(usize::from(axis))
            .ok_or(PmdError::NoSuchAxis {
                axis: i64::from(axis),
                count,
            })
    }

    /// Checks an axis number given as a plain integer.
    ///
    /// # Errors
    /// [`PmdError::NoSuchAxis`].
    pub fn check_axis(&self, axis: i64) -> Result<u8, PmdError> {
        u8::try_from(axis)
            .ok()
            .filter(|&a| a < self.axis_count())
            .ok_or(PmdError::NoSuchAxis {
                axis,
                count: self.axis_count(),
            })
    }

    fn buffer_user(&self, buffer: BufferId) -> Option<u8> {
        self.axes
            .iter()
            .position(|a| a.motion.is_camming() && a.cam.buffer == buffer)
            .and_then(|i| u8::try_from(i).ok())
    }

    fn with_memory<T>(
        &self,
        f: impl FnOnce(&mut BufferMemory) -> Result<T, PmdError>,
    ) -> Result<T, PmdError> {
        // Only this type borrows the memory mutably and never across a call
        // into a cam, so the borrow is always free.
        let mut memory = self.memory.borrow_mut();
        f(&mut memory)
    }

    // ----- buffers -----

    /// `SetBufferStart buffer address`.
    ///
    /// # Errors
    /// Bad ID or address, or the buffer is an active cam's table.
    pub fn set_buffer_start(&mut self, buffer: i64, address: i64) -> Result<(), PmdError> {
        let id = BufferId::new(buffer)?;
        if let Some(axis) = self.buffer_user(id) {
            return Err(PmdError::BufferInUse {
                buffer: id.get(),
                axis,
            });
        }
        self.with_memory(|m| m.set_start(id, address))
    }

    /// `SetBufferLength buffer length`.
    ///
    /// # Errors
    /// Bad ID or length, or the buffer is an active cam's table.
    pub fn set_buffer_length(&mut self, buffer: i64, length: i64) -> Result<(), PmdError> {
        let id = BufferId::new(buffer)?;
        if let Some(axis) = self.buffer_user(id) {
            return Err(PmdError::BufferInUse {
                buffer: id.get(),
                axis,
            });
        }
        self.with_memory(|m| m.set_length(id, length))
    }

    /// `SetBufferWriteIndex buffer index`.
    ///
    /// # Errors
    /// Bad ID, or an index at or past the buffer's length.
    pub fn set_buffer_write_index(&mut self, buffer: i64, index: i64) -> Result<(), PmdError> {
        let id = BufferId::new(buffer)?;
        self.with_memory(|m| m.set_write_index(id, index))
    }

    /// `WriteBuffer buffer value`. A running cam on this buffer sees the new value.
    ///
    /// # Errors
    /// Bad ID, a value that is not signed 32-bit, or an empty buffer.
    pub fn write_buffer(&mut self, buffer: i64, value: i64) -> Result<(), PmdError> {
        let id = BufferId::new(buffer)?;
        self.with_memory(|m| m.write(id, value))
    }

    /// Value `index` of `buffer` (what a cam reads).
    ///
    /// # Errors
    /// Bad ID, or an index at or past the buffer's length.
    pub fn read_buffer(&self, buffer: i64, index: i64) -> Result<i64, PmdError> {
        let id = BufferId::new(buffer)?;
        let memory = self.memory.borrow();
        let length = memory.window(id).length;
        let i =
            u32::try_from(index)
                .ok()
                .filter(|&i| i < length)
                .ok_or(PmdError::IndexPastLength {
                    buffer: id.get(),
                    index,
                    length,
                })?;
        Ok(i64::from(memory.read(id, i)))
    }

    // ----- modes -----

    /// `SetProfileMode mode`: takes effect at the next `Update`.
    ///
    /// # Errors
    /// Unknown axis or mode.
    pub fn set_profile_mode(&mut self, axis: u8, mode: i64) -> Result<(), PmdError> {
        let mode = ProfileMode::decode(mode)?;
        self.axis_mut(axis)?.pending_mode = mode;
        Ok(())
    }

    /// `GetProfileMode`: the mode in effect.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn profile_mode(&self, axis: u8) -> Result<ProfileMode, PmdError> {
        Ok(self.axis(axis)?.mode)
    }

    /// `SetStopMode mode`: performed at the next `Update`.
    ///
    /// # Errors
    /// Unknown axis or mode.
    pub fn set_stop_mode(&mut self, axis: u8, mode: i64) -> Result<(), PmdError> {
        let mode = StopMode::decode(mode)?;
        self.axis_mut(axis)?.pending_stop = mode;
        Ok(())
    }

    /// `Update`: performs the pending stop, then puts the pending profile
    /// mode into effect. Entering or leaving ElectronicCam resets the cam
    /// parameters to their defaults (document 002 allows it; a fresh start
    /// is the predictable choice).
    ///
    /// # Errors
    /// [`PmdError::InMotion`] when the mode would switch into or out of cam
    /// mode while the axis still moves after this `Update`'s stop (an
    /// abrupt stop, a smooth one on an end of the table, or any stop of a
    /// simulated move brings it to rest first). The mode then stays as it
    /// was (the change stays pending), but the stop still takes effect.
    pub fn update(&mut self, axis: u8) -> Result<(), PmdError> {
        let a = self.axis_mut(axis)?;
        let switching = a.pending_mode != a.mode;
        // The stop comes first and always takes effect: losing a stop because
        // a mode change was also pending would leave the axis moving against
        // the user's intent. The mode change is then judged on the axis as the
        // stop left it; refused in motion, it stays pending for a later Update.
        match core::mem::take(&mut a.pending_stop) {
            StopMode::None => {}
            StopMode::Abrupt => Self::stop_abrupt(a),
            StopMode::Smooth => Self::stop_smooth(a),
        }
        if switching && a.in_motion() {
            return Err(PmdError::InMotion { axis });
        }
        if switching {
            a.mode = a.pending_mode;
            a.cam = CamSettings::default();
        }
        Ok(())
    }

    /// An abrupt stop holds the axis where it is: a cam's commanded
    /// position, or a simulated move's position (document 002: "the
    /// commanded position [stays] at whatever value it has when the stop is
    /// processed").
    fn stop_abrupt(a: &mut Axis) {
        if core::mem::take(&mut a.motion).is_camming() {
            a.event_status |= event_bit::MOTION_COMPLETE;
        }
    }

    /// A cam stops at the next end of its table; a smooth stop on the input
    /// exactly at an end of the table takes effect at once: the cam is
    /// released now, so the axis is at rest for the rest of this `Update`
    /// (a pending mode change) and later commands.
    ///
    /// A simulated move stops at once too. A smooth stop decelerates with
    /// the profile's deceleration, and a `MoveTo` has none: its velocity
    /// steps at its start and its end, so its own deceleration is a step
    /// and the stop is where it is now. Letting it run on to its target
    /// instead would ignore the stop.
    fn stop_smooth(a: &mut Axis) {
        match &mut a.motion {
            Motion::Still => {}
            Motion::Moving(_) => a.motion = Motion::Still,
            Motion::Camming(cam) => {
                cam.stop_smooth();
                if !cam.active() {
                    a.motion = Motion::Still;
                    a.event_status |= event_bit::MOTION_COMPLETE;
                }
            }
        }
    }

    // ----- cam parameters -----

    /// `SetCam param value`.
    ///
    /// # Errors
    /// Axis not in cam mode, cam active, read-only parameter or value out of range.
    pub fn set_cam(&mut self, axis: u8, param: CamParam, value: i64) -> Result<(), PmdError> {
        let count = self.axis_count();
        let a = self.axis_mut(axis)?;
        if a.mode != ProfileMode::ElectronicCam {
            return Err(PmdError::NotInCamMode { axis });
        }
        if a.motion.is_camming() {
            return Err(PmdError::CamActive { axis });
        }
        a.cam.set(param, value, count)
    }

    /// `GetCam param`; positions and offsets come back as signed 32-bit
    /// register values (wrapped, as on the device).
    ///
    /// # Errors
    /// Axis not in cam mode.
    pub fn get_cam(&self, axis: u8, param: CamParam) -> Result<i64, PmdError> {
        let a = self.axis(axis)?;
        if a.mode != ProfileMode::ElectronicCam {
            return Err(PmdError::NotInCamMode { axis });
        }
        Ok(register_value(a.cam.get(param)))
    }

    // ----- breakpoints and events -----

    fn breakpoint_index(id: i64) -> Result<usize, PmdError> {
        match id {
            0 => Ok(0),
            1 => Ok(1),
            _ => Err(PmdError::OutOfRange {
                what: "breakpoint ID",
                value: id,
                allowed: "0 or 1",
            }),
        }
    }

    /// `SetBreakpointValue id value`.
    ///
    /// # Errors
    /// Unknown axis, ID other than 0/1, value not signed 32-bit.
    pub fn set_breakpoint_value(&mut self, axis: u8, id: i64, value: i64) -> Result<(), PmdError> {
        let i = Self::breakpoint_index(id)?;
        let value = check_i32("breakpoint value", value)?;
        if let Some(bp) = self.axis_mut(axis)?.breakpoints.get_mut(i) {
            bp.value = value;
        }
        Ok(())
    }

    /// `SetBreakpoint id word` (layout in [`crate::breakpoint`]); arms or disables it.
    ///
    /// # Errors
    /// Unknown axis or ID, or a word that does not decode.
    pub fn set_breakpoint(&mut self, axis: u8, id: i64, word: i64) -> Result<(), PmdError> {
        let i = Self::breakpoint_index(id)?;
        let decoded = BreakpointWord::decode(word, self.axis_count())?;
        let was_below = match decoded {
            Some(w) => {
                let src = self.axis(w.source_axis)?;
                let value = self.axis(axis)?.breakpoints.get(i).map_or(0, |b| b.value);
                let watched = match w.trigger {
                    Trigger::CommandedCrossed => src.commanded,
                    _ => src.actual,
                };
                watched < value
            }
            None => false,
        };
        if let Some(bp) = self.axis_mut(axis)?.breakpoints.get_mut(i) {
            bp.word = decoded;
            bp.was_below = was_below;
        }
        Ok(())
    }

    /// `SetEventAction event action`: with the immediate event (0) the action runs now.
    ///
    /// # Errors
    /// Unknown axis, event or action.
    pub fn set_event_action(&mut self, axis: u8, event: i64, action: i64) -> Result<(), PmdError> {
        let Event::Immediate = Event::decode(event)?;
        let action = Action::decode(action)?;
        self.axis(axis)?;
        self.perform(axis, action);
        Ok(())
    }

    /// `ResetEventStatus mask`: clears the event bits that are 0 in `mask`.
    ///
    /// # Errors
    /// Unknown axis, mask not 16-bit.
    pub fn reset_event_status(&mut self, axis: u8, mask: i64) -> Result<(), PmdError> {
        let mask = u16::try_from(mask).map_err(|_| PmdError::OutOfRange {
            what: "event mask",
            value: mask,
            allowed: "0 to 0xFFFF",
        })?;
        self.axis_mut(axis)?.event_status &= mask;
        Ok(())
    }

    fn perform(&mut self, axis: u8, action: Action) {
        match action {
            Action::None => {}
            Action::Update => {
                if self.update(axis).is_err() {
                    if let Ok(a) = self.axis_mut(axis) {
                        a.event_status |= event_bit::INSTRUCTION_ERROR;
                    }
                }
            }
            Action::AbruptStop => {
                if let Ok(a) = self.axis_mut(axis) {
                    Self::stop_abrupt(a);
                }
            }
            Action::SmoothStop => {
                if let Ok(a) = self.axis_mut(axis) {
                    Self::stop_smooth(a);
                }
            }
            Action::StartCam => self.start_cam(axis),
        }
    }

    /// The `StartCam` action (9). Outside cam mode, or with the cam already
    /// active, nothing happens (document 002). Without `CamCounts`, a
    /// `CamBufferID` set by `SetCam`, a buffer of at least two values, or with
    /// `CamStartCount` past `CamCounts`, the cam does not start and the axis
    /// gets a MotionError event.
    fn start_cam(&mut self, axis: u8) {
        let memory = Rc::clone(&self.memory);
        let Ok(a) = self.axis_mut(axis) else {
            return;
        };
        if a.mode != ProfileMode::ElectronicCam || a.motion.is_camming() {
            return;
        }
        let cam = a.cam;
        let values = memory.borrow().window(cam.buffer).length;
        let ready =
            cam.counts >= 2 && cam.buffer_defined && values >= 2 && cam.start_count <= cam.counts;
        if !ready {
            a.event_status |= event_bit::MOTION_ERROR;
            return;
        }
        let table = BufferCam::new(memory, cam.buffer, cam.counts, values);
        match RunningCam::start(table, cam.start_count, a.commanded) {
            // The cam takes the axis over from a simulated move.
            Ok(running) => a.motion = Motion::Camming(Box::new(running)),
            Err(_) => {
                a.event_status |= event_bit::MOTION_ERROR;
                return;
            }
        }
        // The cam engages at the input of this instant (document 002: "triggered
        // at an input value"); later cycles follow from there. Within a cycle
        // the input does not change after the breakpoints, so the cycle's own
        // cam step repeats this one harmlessly.
        self.run_cam(usize::from(axis));
    }

    // ----- status -----

    /// `GetCommandedPosition`, as the 32-bit register shows it (wrapped).
    ///
    /// # Errors
    /// Unknown axis.
    pub fn commanded_position(&self, axis: u8) -> Result<i64, PmdError> {
        Ok(register_value(self.axis(axis)?.commanded))
    }

    /// `GetActualPosition`, as the 32-bit register shows it (wrapped).
    ///
    /// # Errors
    /// Unknown axis.
    pub fn actual_position(&self, axis: u8) -> Result<i64, PmdError> {
        Ok(register_value(self.axis(axis)?.actual))
    }

    /// `GetActivityStatus`: bit 10 in motion; bits 15:13 = 1 while the cam is active.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn activity_status(&self, axis: u8) -> Result<u16, PmdError> {
        Ok(self.axis(axis)?.activity_status())
    }

    /// `GetEventStatus` (bits in [`crate::event_bit`]).
    ///
    /// # Errors
    /// Unknown axis.
    pub fn event_status(&self, axis: u8) -> Result<u16, PmdError> {
        Ok(self.axis(axis)?.event_status)
    }

    /// Whether the cam of `axis` is active.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn cam_active(&self, axis: u8) -> Result<bool, PmdError> {
        Ok(self.axis(axis)?.motion.is_camming())
    }

    // ----- simulation -----

    /// Sets the actual position; the commanded position moves by the same
    /// amount (the simulated servo has no following error). Cancels a
    /// simulated move.
    ///
    /// # Errors
    /// Unknown axis, position not signed 32-bit, or the axis is camming.
    pub fn set_actual_position(&mut self, axis: u8, position: i64) -> Result<(), PmdError> {
        let position = check_i32("position", position)?;
        let a = self.axis_mut(axis)?;
        if a.motion.is_camming() {
            return Err(PmdError::AxisCamming { axis });
        }
        let delta = position.saturating_sub(a.actual);
        a.actual = position;
        a.commanded = a.commanded.saturating_add(delta);
        a.motion = Motion::Still;
        Ok(())
    }

    /// Drives the axis' actual and commanded position linearly to `position`
    /// over the next `ticks` cycles (0: at once).
    ///
    /// # Errors
    /// Unknown axis, position not signed 32-bit, ticks negative or past
    /// 2^32 − 1, or the axis is camming.
    pub fn move_to(&mut self, axis: u8, position: i64, ticks: i64) -> Result<(), PmdError> {
        let position = check_i32("position", position)?;
        let ticks = u32::try_from(ticks).map_err(|_| PmdError::OutOfRange {
            what: "ticks",
            value: ticks,
            allowed: "0 to 4294967295 cycles",
        })?;
        let a = self.axis_mut(axis)?;
        if a.motion.is_camming() {
            return Err(PmdError::AxisCamming { axis });
        }
        if ticks == 0 {
            a.actual = position;
            a.commanded = position;
            a.motion = Motion::Still;
        } else {
            a.motion = Motion::Moving(LinearMove {
                from: a.actual,
                to: position,
                ticks,
                done: 0,
            });
        }
        Ok(())
    }

    /// Runs one processor cycle.
    pub fn tick(&mut self) {
        self.time = self.time.saturating_add(1);
        for a in &mut self.axes {
            if let Motion::Moving(m) = &mut a.motion {
                let pos = m.step();
                let done = m.finished();
                a.actual = pos;
                a.commanded = pos;
                if done {
                    a.motion = Motion::Still;
                }
            }
        }
        self.check_breakpoints();
        for i in 0..self.axes.len() {
            self.run_cam(i);
        }
    }

    /// Runs `count` cycles.
    pub fn run(&mut self, count: u64) {
        for _ in 0..count {
            self.tick();
        }
    }

    fn check_breakpoints(&mut self) {
        for i in 0..self.axes.len() {
            for b in 0..2 {
                let Some(bp) = self.axes.get(i).and_then(|a| a.breakpoints.get(b)).copied() else {
                    continue;
                };
                let Some(word) = bp.word else { continue };
                let Some(src) = self.axes.get(usize::from(word.source_axis)) else {
                    continue;
                };
                if !bp.fires(src.actual, src.commanded, self.time) {
                    continue;
                }
                let Some(a) = self.axes.get_mut(i) else {
                    continue;
                };
                if let Some(slot) = a.breakpoints.get_mut(b) {
                    *slot = Breakpoint { word: None, ..bp };
                }
                a.event_status |= if b == 0 {
                    event_bit::BREAKPOINT_0
                } else {
                    event_bit::BREAKPOINT_1
                };
                if let Ok(axis) = u8::try_from(i) {
                    self.perform(axis, word.action);
                }
            }
        }
    }

    /// The cam input of axis `i` now: its source register's value.
    fn cam_input(&self, i: usize) -> i64 {
        let Some(a) = self.axes.get(i) else { return 0 };
        let source = a.cam.source;
        let src = self.axes.get(usize::from(source.axis));
        match source.register {
            SourceRegister::Time => self.time,
            SourceRegister::Actual => src.map_or(0, |s| s.actual),
            SourceRegister::Commanded => src.map_or(0, |s| s.commanded),
        }
    }

    fn run_cam(&mut self, i: usize) {
        let input = self.cam_input(i);
        let Some(a) = self.axes.get_mut(i) else {
            return;
        };
        let Motion::Camming(cam) = &mut a.motion else {
            return;
        };
        let out = cam.tick(input);
        a.commanded = out.commanded;
        a.actual = out.commanded;
        a.cam.output_offset = out.output_offset;
        a.cam.input_offset = out.input_offset;
        if !out.active {
            // A cam the engine had to stop (overflow) did not complete its
            // motion: flag it as the MotionError it is, not as a normal end.
            a.event_status |= if cam.fault().is_some() {
                event_bit::MOTION_ERROR
            } else {
                event_bit::MOTION_COMPLETE
            };
            a.motion = Motion::Still;
        }
    }
}
