//! One run of the cam: the engine axis from the start condition to the end
//! of the run, and how the register block configures it.

use ecam_core::{CamCurve, PointTable};
use ecam_engine::{
    AfterPass, AxisConfig, AxisState, CamAxis, Coupling, EngineError, MasterAlign, MasterFilter,
    SlaveAlign, StartMode, StopKind, TickInput, TickOutput, Zoom,
};

use super::block::{LiveSettings, StartSetup, ZoomRatio};
use super::start_gate::CamMode;

/// What the start register accepted: it holds from the start until a stop.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Start {
    pub(super) mode: CamMode,
    /// Function bit 5: each run waits for an S3 edge.
    pub(super) external_start: bool,
}

/// Where the cam and the slave stand when a run is triggered.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Origin {
    /// Registers 27/28 (function bit 6: the master to start from).
    pub(super) master_raw: i64,
    /// Registers 19/20 (function bit 6: the slave to start from).
    pub(super) slave_zoomed: i64,
    /// The output's pulse counter (where the slave stands otherwise).
    pub(super) output_counter: i64,
}

/// A triggered run: the engine axis armed or following, and what the
/// status registers need to know about it.
#[derive(Clone, Debug)]
pub(super) struct Run {
    pub(super) start: Start,
    axis: CamAxis<PointTable>,
    /// A table (and its single-pass mark) written while the cam runs,
    /// waiting for the next seam.
    queued: Option<(PointTable, bool)>,
    /// The table in use runs one pass and stops (offset 31, midCAMend).
    single_pass: bool,
    /// Control bit 1 asked for the stop after this cycle.
    pub(super) stop_requested: bool,
    /// Counts to wait (delay start) and the travel so far, for offset 13.
    delay: Option<u64>,
    start_position: Option<i64>,
    travel: u64,
    last_master: i64,
    /// The master the cam engaged at.
    engaged_at: Option<i64>,
    /// The engine stopped the cam on a fault: nothing more is sent.
    faulted: bool,
}

impl Run {
    /// Builds and arms the engine axis for a run of `setup`.
    ///
    /// # Errors
    /// The engine's refusal (the block checks rule out all it knows).
    pub(super) fn arm(
        start: Start,
        setup: &StartSetup,
        origin: Origin,
        time_base: bool,
        master_now: i64,
    ) -> Result<Self, EngineError> {
        let noncyclic = start.mode == CamMode::Noncyclic;
        // A midCAMend table runs once from its start, whichever the mode.
        let single_pass = setup.single_pass;
        // Document 003 restricts delay and start position to the noncyclic cam.
        let delay = setup.delay.filter(|_| noncyclic).map(u64::from);
        let start_position = setup.start_position.filter(|_| noncyclic);
        let start_mode = match (delay, start_position) {
            (Some(counts), _) => StartMode::AfterDelay {
                counts,
                after_edge: false,
            },
            (None, Some(position)) => StartMode::AtMasterPosition {
                position,
                after_edge: false,
            },
            (None, None) => StartMode::Immediate,
        };
        let table = setup.table.clone();
        let master_align = if setup.from_current {
            MasterAlign::StartAtUnzoomed(origin.master_raw)
        } else if noncyclic || single_pass {
            MasterAlign::StartAt(table.master_first())
        } else {
            MasterAlign::Absolute
        };
        let (slave_align, slave_now) = if setup.from_current {
            (SlaveAlign::At(origin.slave_zoomed), origin.slave_zoomed)
        } else if noncyclic {
            (SlaveAlign::Relative, origin.output_counter)
        } else {
            (SlaveAlign::Absolute, origin.output_counter)
        };
        // A pulse output cannot jump: at a seam the slave goes on from where
        // it stands (the stroke accumulates), in the cyclic cam as in the
        // noncyclic one; an out-and-back table has no stroke and repeats
        // as it is (docs/plc.md, "Seams").
        let config = AxisConfig {
            coupling: if single_pass {
                Coupling::OneShot { repeats: 0 }
            } else if noncyclic {
                Coupling::OneShot {
                    repeats: setup.repeats,
                }
            } else {
                Coupling::Repeat { min_stroke: 1 }
            },
            // A counter or register master changes in whole counts at its
            // own rate; the time base is exact time with its fraction.
            master_filter: if time_base {
                MasterFilter::Direct
            } else {
                MasterFilter::INTERPOLATE
            },
            start: start_mode,
            master_align,
            slave_align,
            master_zoom: zoom(setup.master_zoom),
            slave_zoom: zoom(setup.slave_zoom),
            max_frequency_hz: i64::from(setup.max_frequency_hz),
            ..AxisConfig::default()
        };
        let mut axis = CamAxis::new(table, config)?;
        axis.set_slave_position(slave_now)?;
        axis.arm()?;
        Ok(Self {
            start,
            axis,
            queued: None,
            single_pass,
            stop_requested: false,
            delay,
            start_position,
            travel: 0,
            last_master: master_now,
            engaged_at: None,
            faulted: false,
        })
    }

    /// The last tick's output.
    pub(super) fn status(&self) -> &TickOutput {
        self.axis.status()
    }

    /// The master span of the table the cam follows now (the one taken at
    /// the last seam, not one still waiting).
    pub(super) fn table_span(&self) -> i64 {
        self.axis.curve().master_span()
    }

    /// A table written while the cam runs takes over at the next seam
    /// (`docs/plc.md`, "Changing the table while the cam runs"): the engine
    /// continues the slave from where it stands at the seam, so the output
    /// never steps.
    pub(super) fn offer_table(&mut self, table: &PointTable, single_pass: bool) {
        let waiting = match &self.queued {
            Some((queued, queued_single)) => (queued, *queued_single),
            None => (self.axis.curve(), self.single_pass),
        };
        if waiting == (table, single_pass) {
            return;
        }
        let then = if single_pass {
            AfterPass::Finish
        } else {
            AfterPass::Repeat
        };
        if self.axis.queue_curve_then(table.clone(), then).is_ok() {
            self.queued = self
                .axis
                .has_queued_curve()
                .then(|| (table.clone(), single_pass));
        }
    }

    /// One engine tick; `live` is offset 4's stop-after-cycle request.
    pub(super) fn tick(
        &mut self,
        master: i64,
        master_fraction: u32,
        dt_us: u32,
        live: Option<LiveSettings>,
    ) -> TickOutput {
        // Bit 1 set before the start means "run this cycle, then stop": the
        // request waits until the master has left the place the cam engaged
        // at, where the engine would take it as a stop on the table end.
        if live.is_some_and(|l| l.stop_after_cycle)
            && !self.stop_requested
            && self.axis.state() == AxisState::Running
            && self
                .engaged_at
                .is_some_and(|at| at != self.axis.status().master)
        {
            self.axis.stop(StopKind::EndOfCycle);
            self.stop_requested = true;
        }
        let out = self.axis.tick(&TickInput {
            master,
            master_fraction,
            dt_us,
            ..TickInput::default()
        });
        if out.events.engaged {
            self.engaged_at = Some(out.master);
        }
        self.faulted |= out.fault.is_some();
        if out.events.table_switched {
            if let Some((_, single_pass)) = self.queued.take() {
                self.single_pass = single_pass;
            }
            drop(self.axis.take_retired_curve());
        }
        // Offset 13 counts the travel of the master the cam follows (the
        // tracker's estimate), the same position the start watches.
        let step = out.master.abs_diff(self.last_master);
        self.last_master = out.master;
        if matches!(out.state, AxisState::Armed | AxisState::Delaying) {
            self.travel = self.travel.saturating_add(step);
        }
        out
    }

    /// Offset 13: master counts left before a delayed or position start.
    pub(super) fn master_remaining(&self) -> u64 {
        let out = self.axis.status();
        match out.state {
            AxisState::Armed | AxisState::Delaying => match self.delay {
                Some(delay) => delay.saturating_sub(self.travel),
                None => self.start_position.map_or(0, |p| p.abs_diff(out.master)),
            },
            _ => 0,
        }
    }

    /// The engine no longer follows (finished or stopped) and every pulse
    /// it commanded has gone out, or it stopped on a fault (whose last
    /// command is no position to go to): the run is over.
    pub(super) fn over(&self) -> bool {
        let out = self.axis.status();
        matches!(out.state, AxisState::Finished | AxisState::Idle)
            && (out.backlog == 0 || self.faulted)
    }

    /// Flag bit 10: the cam follows and the window holds the master.
    pub(super) fn in_sync(&self, live: Option<LiveSettings>) -> bool {
        let out = self.axis.status();
        out.state.is_engaged() && live.is_some_and(|l| l.in_window(out.master_in_cycle))
    }
}

fn zoom(ratio: ZoomRatio) -> Zoom {
    Zoom::new(ratio.num.get(), ratio.den.get()).unwrap_or(Zoom::ONE)
}
