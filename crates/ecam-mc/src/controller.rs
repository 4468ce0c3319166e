//! The motion controller: axes with document 001's settings and E-CAM channels.

use core::num::NonZeroU64;

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, CamAxis, EngineError, MasterAlign, SlaveAlign, StartMode, TickInput,
};

use crate::{CamType, McError, SingleTurn, UserUnit};

/// Control-cycle time handed to the engine. The controller reads the
/// commanded slave position, so the pulse limit this feeds never lags it.
const CYCLE_US: u32 = 1000;

/// What an E-CAM follows and how (document 001's E-CAM data).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ECamData {
    /// The axis whose command position is the master.
    pub master_axis: usize,
    /// The axis the cam commands.
    pub slave_axis: usize,
    /// Normal, Periodic or Repeat.
    pub cam_type: CamType,
    /// The E-CAM table: (master, slave) points, master increasing.
    pub table: PointTable,
}

#[derive(Clone, Copy, Debug, Default)]
struct Axis {
    position: i64,
    single_turn: Option<SingleTurn>,
    user_unit: UserUnit,
    /// Largest step per cycle accepted from this axis as a master.
    max_step: Option<NonZeroU64>,
    /// Why the E-CAM this axis followed stopped by itself, if it did.
    fault: Option<EngineError>,
}

#[derive(Clone, Debug)]
struct Channel {
    master: usize,
    slave: usize,
    cam: CamAxis<PointTable>,
}

/// A motion controller with `n` axes and E-CAM channels between them.
///
/// Positions are command positions in pulses. A single-turn axis keeps its
/// position in `[0, turn)`; a master that is single-turn is unwrapped by the
/// engine, so between two [`MotionController::tick`]s it must move less
/// than half a turn.
#[derive(Clone, Debug)]
pub struct MotionController {
    axes: Vec<Axis>,
    cams: Vec<Channel>,
}

impl MotionController {
    /// A controller with `axis_count` axes, all at 0, not single-turn, one
    /// pulse per user unit.
    pub fn new(axis_count: usize) -> Self {
        Self {
            axes: vec![Axis::default(); axis_count],
            cams: Vec::new(),
        }
    }

    /// How many axes the controller has (numbered from 0).
    pub fn axis_count(&self) -> usize {
        self.axes.len()
    }

    fn axis(&self, axis: usize) -> Result<&Axis, McError> {
        self.axes.get(axis).ok_or(McError::NoSuchAxis {
            axis,
            count: self.axes.len(),
        })
    }

    fn axis_mut(&mut self, axis: usize) -> Result<&mut Axis, McError> {
        let count = self.axes.len();
        self.axes
            .get_mut(axis)
            .ok_or(McError::NoSuchAxis { axis, count })
    }

    fn in_use(&self, axis: usize) -> bool {
        self.cams
            .iter()
            .any(|c| c.master == axis || c.slave == axis)
    }

    /// `SetSingleTurn`: makes the axis single-turn over `turn` counts (or
    /// not, with `None`); its position is wrapped into the turn at once.
    ///
    /// # Errors
    /// Unknown axis, or the axis takes part in a running E-CAM.
    pub fn set_single_turn(
        &mut self,
        axis: usize,
        turn: Option<SingleTurn>,
    ) -> Result<(), McError> {
        if self.in_use(axis) {
            return Err(McError::AxisInUse { axis });
        }
        let a = self.axis_mut(axis)?;
        a.single_turn = turn;
        if let Some(turn) = turn {
            a.position = turn.wrap(a.position);
        }
        Ok(())
    }

    /// The axis' single-turn range, if any.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn single_turn(&self, axis: usize) -> Result<Option<SingleTurn>, McError> {
        Ok(self.axis(axis)?.single_turn)
    }

    /// Sets the largest step per cycle a cam accepts from `axis` as its
    /// master; a larger one stops the cam with
    /// [`EngineError::MasterStep`] (reported by [`MotionController::fault`]).
    /// On a single-turn master a step of more than half a turn cannot be
    /// told from a step the other way round (the cam would run backwards):
    /// set this below half a turn to fault instead. `None` (the default)
    /// accepts any step.
    ///
    /// # Errors
    /// Unknown axis, or the axis takes part in a running E-CAM.
    pub fn set_max_master_step(
        &mut self,
        axis: usize,
        step: Option<NonZeroU64>,
    ) -> Result<(), McError> {
        if self.in_use(axis) {
            return Err(McError::AxisInUse { axis });
        }
        self.axis_mut(axis)?.max_step = step;
        Ok(())
    }

    /// Sets how many pulses make a user unit on `axis` (used when it is a
    /// Repeat cam's slave).
    ///
    /// # Errors
    /// Unknown axis, or the axis takes part in a running E-CAM.
    pub fn set_user_unit(&mut self, axis: usize, unit: UserUnit) -> Result<(), McError> {
        if self.in_use(axis) {
            return Err(McError::AxisInUse { axis });
        }
        self.axis_mut(axis)?.user_unit = unit;
        Ok(())
    }

    /// Moves an axis (e.g. the master) to `position`, wrapped into its turn
    /// if single-turn. Cams follow at the next [`MotionController::tick`].
    ///
    /// # Errors
    /// Unknown axis, or the axis is a running E-CAM's slave.
    pub fn set_position(&mut self, axis: usize, position: i64) -> Result<(), McError> {
        if self.cams.iter().any(|c| c.slave == axis) {
            return Err(McError::SlaveBusy { axis });
        }
        let a = self.axis_mut(axis)?;
        a.position = a.single_turn.map_or(position, |t| t.wrap(position));
        Ok(())
    }

    /// The axis' command position.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn position(&self, axis: usize) -> Result<i64, McError> {
        Ok(self.axis(axis)?.position)
    }

    /// Starts an E-CAM now, at the master's current position.
    ///
    /// The slave takes the table's position for the master, by the
    /// engine's start rule (docs/mc.md, "Starting"): cycles count from the
    /// one the master is in, and a Repeat cam lands on the equivalent
    /// position (table value plus whole strokes) nearest the slave's
    /// command position: ahead of it, less than one stroke on, for a table
    /// that never turns back; either way for one that does (document 001:
    /// master 20000, slave −1500 → −2000). Normal and Periodic cams take
    /// the table value itself.
    ///
    /// # Errors
    /// Unknown or equal axes, a slave already camming, or a table the
    /// engine refuses (e.g. one reaching outside the master's turn).
    pub fn start_ecam(&mut self, data: ECamData) -> Result<(), McError> {
        let master = *self.axis(data.master_axis)?;
        let slave = *self.axis(data.slave_axis)?;
        if data.master_axis == data.slave_axis {
            return Err(McError::SameAxis {
                axis: data.slave_axis,
            });
        }
        if self.cams.iter().any(|c| c.slave == data.slave_axis) {
            return Err(McError::SlaveBusy {
                axis: data.slave_axis,
            });
        }
        let config = AxisConfig {
            coupling: data.cam_type.coupling(slave.user_unit),
            start: StartMode::Immediate,
            master_align: MasterAlign::Absolute,
            slave_align: SlaveAlign::Absolute,
            single_turn: master.single_turn.map(SingleTurn::counts),
            max_master_step: master.max_step,
            ..AxisConfig::default()
        };
        let mut cam = CamAxis::new(data.table, config)?;
        cam.set_slave_position(slave.position)?;
        cam.arm()?;
        let out = cam.tick(&TickInput::at(master.position, CYCLE_US));
        if let Some(fault) = out.fault {
            return Err(McError::Engine(fault));
        }
        if let Some(a) = self.axes.get_mut(data.slave_axis) {
            a.position = out.slave;
            a.fault = None;
        }
        self.cams.push(Channel {
            master: data.master_axis,
            slave: data.slave_axis,
            cam,
        });
        Ok(())
    }

    /// Stops the E-CAM driving `slave_axis`; the slave keeps its position.
    /// Gives whether there was one.
    pub fn stop_ecam(&mut self, slave_axis: usize) -> bool {
        let before = self.cams.len();
        self.cams.retain(|c| c.slave != slave_axis);
        self.cams.len() != before
    }

    /// Whether an E-CAM drives `slave_axis`.
    pub fn ecam_running(&self, slave_axis: usize) -> bool {
        self.cams.iter().any(|c| c.slave == slave_axis)
    }

    /// One control cycle: every E-CAM reads its master and commands its
    /// slave, in the order they were started.
    ///
    /// A cam the engine stops with a fault (e.g. a slave position that
    /// would overflow) ends here: the slave keeps its last command
    /// position, becomes free again, and [`MotionController::fault`] says why.
    pub fn tick(&mut self) {
        let axes = &mut self.axes;
        self.cams.retain_mut(|channel| {
            let master = axes.get(channel.master).map_or(0, |a| a.position);
            let out = channel.cam.tick(&TickInput::at(master, CYCLE_US));
            let Some(slave) = axes.get_mut(channel.slave) else {
                return false;
            };
            slave.position = out.slave;
            match out.fault {
                Some(fault) => {
                    slave.fault = Some(fault);
                    false
                }
                None => true,
            }
        });
    }

    /// Why the E-CAM that drove `slave_axis` stopped by itself (an engine
    /// fault in [`MotionController::tick`]); cleared when a cam is started
    /// on that axis again.
    ///
    /// # Errors
    /// Unknown axis.
    pub fn fault(&self, slave_axis: usize) -> Result<Option<EngineError>, McError> {
        Ok(self.axis(slave_axis)?.fault)
    }

    /// Moves `master_axis` to `position` and runs one cycle; gives the
    /// command position of `slave_axis` (a convenience for stepping a plot).
    ///
    /// # Errors
    /// As [`MotionController::set_position`] and [`MotionController::position`].
    pub fn drive(
        &mut self,
        master_axis: usize,
        position: i64,
        slave_axis: usize,
    ) -> Result<i64, McError> {
        self.set_position(master_axis, position)?;
        self.tick();
        self.position(slave_axis)
    }
}
