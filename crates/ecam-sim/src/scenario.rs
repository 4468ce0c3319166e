//! Scenario files: a cam, a master motion, a start and a stop, written in
//! TOML. Every key is described in `docs/simulate.md`.
//!
//! Parsing is strict (unknown keys are errors, so a typo cannot silently fall
//! back to a default) and turns the file into engine types up front: a bad
//! scenario fails before the first tick.

use std::num::{NonZeroU32, NonZeroU64};
use std::path::Path;

use ecam_core::CamCurve;
use ecam_engine::{
    AxisConfig, Compare, Coupling, LinearMove, MasterAlign, MasterFilter, SlaveAlign, StartMode,
    StopKind, SwitchAt, SyncWindow, Zoom,
};
use serde::Deserialize;

use crate::error::ScenarioError;
use crate::trigger::{StopTrigger, micros, trigger};

/// The TOML file as written.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawScenario {
    #[serde(default = "default_tick_us")]
    tick_us: u32,
    duration_s: Option<f64>,
    #[serde(default)]
    trace_every: Option<u64>,
    table: toml::Table,
    #[serde(default)]
    cam: RawCam,
    #[serde(default)]
    start: RawStart,
    #[serde(default)]
    stop: Option<RawStop>,
    #[serde(default)]
    sync: Vec<RawSync>,
    master: RawMaster,
    #[serde(default)]
    switch: Vec<RawSwitch>,
    modulo: Option<crate::couplings::RawModulo>,
    direction_guard: Option<crate::couplings::RawGuard>,
    registration: Option<crate::couplings::RawRegistration>,
    cam_switches: Option<crate::couplings::RawCamSwitches>,
    #[serde(default)]
    plcopen: Vec<crate::steps::RawStep>,
}

/// `[[switch]]`: another table takes over at the next seam once the
/// trigger fires.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawSwitch {
    at_s: Option<f64>,
    master_at_least: Option<i64>,
    master_at_most: Option<i64>,
    table: toml::Table,
    #[serde(default)]
    mode: RawSwitchMode,
    position: Option<i64>,
    blend: Option<u64>,
}

/// Where a `[[switch]]`'s table takes over.
#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawSwitchMode {
    /// At the next seam (PLCopen buffered).
    #[default]
    Seam,
    /// When the master reaches `position`.
    Position,
    /// At once (PLCopen aborting).
    Now,
}

fn default_tick_us() -> u32 {
    100
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum CamKind {
    #[default]
    Periodic,
    Repeat,
    OneShot,
    Normal,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
struct RawCam {
    #[serde(default)]
    kind: CamKind,
    #[serde(default)]
    repeats: u16,
    min_stroke: Option<u64>,
    single_turn: Option<u64>,
    master_zoom: Option<[u16; 2]>,
    slave_zoom: Option<[u16; 2]>,
    #[serde(default)]
    max_frequency_hz: i64,
    ramp_in: Option<u64>,
    #[serde(default)]
    master_filter: RawMasterFilter,
    max_interval_us: Option<u32>,
    max_master_step: Option<u64>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawMasterFilter {
    #[default]
    Direct,
    Interpolate,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum StartKind {
    #[default]
    Immediate,
    RisingEdge,
    AfterDelay,
    AtPosition,
    Breakpoint,
}

#[derive(Deserialize, Debug, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawMasterAlign {
    Absolute,
    Offset,
    StartAt,
    StartAtUnzoomed,
}

#[derive(Deserialize, Debug, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawSlaveAlign {
    Absolute,
    Offset,
    Relative,
    Nearest,
    At,
}

#[derive(Deserialize, Debug, Clone, Copy)]
enum RawCompare {
    #[serde(rename = ">=")]
    AtLeast,
    #[serde(rename = "<=")]
    AtMost,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
struct RawStart {
    #[serde(default)]
    mode: StartKind,
    #[serde(default)]
    master: i64,
    #[serde(default)]
    slave: i64,
    delay: Option<u64>,
    position: Option<i64>,
    #[serde(default)]
    after_edge: bool,
    compare: Option<RawCompare>,
    value: Option<i64>,
    master_align: Option<RawMasterAlign>,
    master_value: Option<i64>,
    slave_align: Option<RawSlaveAlign>,
    slave_value: Option<i64>,
    #[serde(default)]
    input: Vec<[f64; 2]>,
}

#[derive(Deserialize, Debug, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawStopKind {
    Immediate,
    EndOfCycle,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawStop {
    at_s: Option<f64>,
    master_at_least: Option<i64>,
    master_at_most: Option<i64>,
    kind: RawStopKind,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawSync {
    low: i64,
    high: i64,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawMaster {
    #[serde(default)]
    moves: Vec<[f64; 2]>,
    update_us: Option<u64>,
}

/// One linear master move: reach `target` after `duration_us`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MasterMove {
    /// Duration of the move in microseconds (0 = a jump).
    pub duration_us: u64,
    /// Master position at its end.
    pub target: i64,
}

/// A stop requested by time or master position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StopAt {
    /// When.
    pub trigger: StopTrigger,
    /// Abrupt or at the end of the cycle.
    pub kind: StopKind,
}

impl StopAt {
    /// Whether the stop fires on a tick at `t_us` with the master at `master`.
    pub fn fires(&self, t_us: u64, master: i64) -> bool {
        self.trigger.fires(t_us, master)
    }
}

/// A table handed to the running cam once `trigger` fired; it takes over
/// where `at` says (the next seam, a master position, at once), the slave
/// continuing from where it stands (`CamAxis::switch_curve`).
pub struct TableSwitch {
    /// When the switch is requested (the time or master position of the
    /// request, not of the switch itself).
    pub trigger: StopTrigger,
    /// Where the new table takes over, and over what master travel the
    /// velocity blends onto it.
    pub at: SwitchAt,
    /// The new table.
    pub curve: Box<dyn CamCurve>,
}

/// A checked scenario, ready to run.
pub struct Scenario {
    /// Control cycle in microseconds.
    pub tick_us: u32,
    /// Total simulated time in microseconds.
    pub duration_us: u64,
    /// Write every n-th tick to the trace (the first and last are always written).
    pub trace_every: u64,
    /// The cam.
    pub curve: Box<dyn CamCurve>,
    /// Engine configuration.
    pub config: AxisConfig,
    /// Master position at t = 0 (unwrapped counts).
    pub master_start: i64,
    /// A coarse master: the reading changes only every this many µs.
    pub master_update_us: Option<NonZeroU64>,
    /// Slave position at t = 0.
    pub slave_start: i64,
    /// Master moves, one after another from `master_start`.
    pub moves: Vec<MasterMove>,
    /// Times the start input is high: `[on, off)` in microseconds.
    pub start_input: Vec<(u64, u64)>,
    /// Optional stop.
    pub stop: Option<StopAt>,
    /// Table switches, in the order they are requested.
    pub switches: Vec<TableSwitch>,
    /// The couplings beyond the cam (`[modulo]`, `[direction_guard]`,
    /// `[registration]`, `[cam_switches]`, `[[plcopen]]`): the scenario
    /// then runs on a slave axis.
    pub couplings: Option<crate::couplings::Couplings>,
}

impl Scenario {
    /// Reads and checks the scenario at `path`; relative table files are
    /// resolved against the scenario's folder.
    ///
    /// # Errors
    /// Unreadable file, TOML errors, unknown keys, inconsistent settings, or
    /// a table or configuration the core or engine refuses.
    pub fn load(path: &Path) -> Result<Self, ScenarioError> {
        let text = std::fs::read_to_string(path).map_err(|source| ScenarioError::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let base = path.parent().map(Path::to_path_buf).unwrap_or_default();
        Self::parse(&text, &base).map_err(|error| ScenarioError::In {
            path: path.to_path_buf(),
            error: Box::new(error),
        })
    }

    /// Parses scenario text; `base` is the folder relative table files are in.
    ///
    /// # Errors
    /// As [`Scenario::load`].
    pub fn parse(text: &str, base: &Path) -> Result<Self, ScenarioError> {
        let at_least_one = |key: &str, unit| ScenarioError::AtLeastOne {
            key: key.to_string(),
            unit,
        };
        let raw: RawScenario = toml::from_str(text).map_err(ScenarioError::Toml)?;
        if raw.tick_us == 0 {
            return Err(at_least_one("tick_us", ""));
        }
        if raw.trace_every == Some(0) {
            return Err(at_least_one("trace_every", " (1 writes every tick)"));
        }
        unused_keys(&raw.cam, &raw.start)?;
        // One run, one budget: its tables' generators and its ticks.
        let mut budget = ecam_core::budget::Budget::per_run();
        let curve =
            ecam_design::load_table_within(&raw.table, base, &mut budget).map_err(|error| {
                ScenarioError::Table {
                    place: "[table]".to_string(),
                    error: Box::new(error),
                }
            })?;
        let moves = raw
            .master
            .moves
            .iter()
            .enumerate()
            .map(|(i, &[duration, target])| {
                let duration_us = micros(duration, &format!("[master] moves[{i}] duration"))?;
                if !target.is_finite() || target.abs() > 4.5e15 {
                    return Err(ScenarioError::TargetRange { index: i, target });
                }
                if target.fract() != 0.0 {
                    return Err(ScenarioError::TargetFraction { index: i, target });
                }
                Ok(MasterMove {
                    duration_us,
                    target: target as i64,
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        let moves_us = moves
            .iter()
            .try_fold(0u64, |acc, m| acc.checked_add(m.duration_us))
            .ok_or(ScenarioError::MovesTooLong)?;
        let duration_us = match raw.duration_s {
            Some(d) => micros(d, "duration_s")?,
            None => moves_us,
        };
        if duration_us == 0 {
            return Err(ScenarioError::NothingToSimulate);
        }
        let ticks = duration_us.div_ceil(u64::from(raw.tick_us.max(1)));
        let limit = ecam_core::limits::MAX_SIMULATED_TICKS;
        if ticks > limit || budget.cycles(ticks).is_err() {
            return Err(ScenarioError::TooManyTicks {
                ticks,
                tick_us: raw.tick_us,
            });
        }
        let start_input = raw
            .start
            .input
            .iter()
            .enumerate()
            .map(|(i, &[on, off])| {
                let what = format!("[start] input[{i}]");
                let (on, off) = (micros(on, &what)?, micros(off, &what)?);
                if off <= on {
                    return Err(ScenarioError::InputOrder { index: i });
                }
                Ok((on, off))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let stop = raw
            .stop
            .map(|s| -> Result<StopAt, ScenarioError> {
                let trigger = trigger(s.at_s, s.master_at_least, s.master_at_most, "[stop]")?;
                Ok(StopAt {
                    trigger,
                    kind: match s.kind {
                        RawStopKind::Immediate => StopKind::Immediate,
                        RawStopKind::EndOfCycle => StopKind::EndOfCycle,
                    },
                })
            })
            .transpose()?;
        let switches =
            raw.switch
                .iter()
                .enumerate()
                .map(|(i, s)| -> Result<TableSwitch, ScenarioError> {
                    let what = format!("[[switch]] {}", i + 1);
                    let trigger = trigger(s.at_s, s.master_at_least, s.master_at_most, &what)?;
                    let curve = ecam_design::load_table_within(&s.table, base, &mut budget)
                        .map_err(|error| ScenarioError::Table {
                            place: format!("{what} table"),
                            error: Box::new(error),
                        })?;
                    let blend = match s.blend {
                        Some(b) => Some(
                            NonZeroU64::new(b)
                                .ok_or_else(|| at_least_one(&format!("{what} blend"), " count"))?,
                        ),
                        None => None,
                    };
                    let at = match (s.mode, s.position) {
                        (RawSwitchMode::Seam, None) => SwitchAt::NextSeam { blend },
                        (RawSwitchMode::Now, None) => SwitchAt::Now { blend },
                        (RawSwitchMode::Position, Some(position)) => {
                            SwitchAt::MasterPosition { position, blend }
                        }
                        (RawSwitchMode::Position, None) => {
                            return Err(ScenarioError::SwitchPositionMissing { what });
                        }
                        (_, Some(_)) => return Err(ScenarioError::SwitchPositionUnused { what }),
                    };
                    Ok(TableSwitch { trigger, at, curve })
                })
                .collect::<Result<Vec<_>, _>>()?;
        if raw.sync.len() > 4 {
            return Err(ScenarioError::TooManySyncWindows {
                got: raw.sync.len(),
            });
        }
        let mut sync_windows = [SyncWindow::OFF; 4];
        for (slot, w) in sync_windows.iter_mut().zip(&raw.sync) {
            if w.high < w.low {
                return Err(ScenarioError::SyncOrder {
                    low: w.low,
                    high: w.high,
                });
            }
            *slot = SyncWindow::new(w.low, w.high);
        }
        let plcopen = !raw.plcopen.is_empty();
        if plcopen {
            crate::couplings::plcopen_reads_no_cam_keys(
                raw.cam.kind != CamKind::Periodic
                    || raw.cam.master_zoom.is_some()
                    || raw.cam.slave_zoom.is_some()
                    || raw.cam.ramp_in.is_some()
                    || raw.cam.single_turn.is_some()
                    || raw.cam.max_master_step.is_some()
                    || !raw.sync.is_empty(),
                !matches!(raw.start.mode, StartKind::Immediate)
                    || raw.start.master_align.is_some()
                    || raw.start.slave_align.is_some(),
                !raw.switch.is_empty(),
            )?;
        }
        let mut config = AxisConfig {
            coupling: coupling(&raw.cam),
            start: start_mode(&raw.start)?,
            master_align: master_align(&raw.start)?,
            slave_align: slave_align(&raw.start, &raw.cam)?,
            master_zoom: zoom(raw.cam.master_zoom, "master_zoom")?,
            slave_zoom: zoom(raw.cam.slave_zoom, "slave_zoom")?,
            single_turn: match raw.cam.single_turn {
                Some(t) => {
                    Some(NonZeroU64::new(t).ok_or_else(|| at_least_one("[cam] single_turn", ""))?)
                }
                None => None,
            },
            max_frequency_hz: raw.cam.max_frequency_hz,
            sync_windows,
            ramp_in: match raw.cam.ramp_in {
                Some(d) => Some(ecam_engine::RampIn {
                    distance: NonZeroU64::new(d)
                        .ok_or_else(|| at_least_one("[cam] ramp_in", " count"))?,
                }),
                None => None,
            },
            master_filter: match (raw.cam.master_filter, raw.cam.max_interval_us) {
                (RawMasterFilter::Direct, None) => MasterFilter::Direct,
                (RawMasterFilter::Direct, Some(_)) => {
                    return Err(ScenarioError::IntervalNeedsInterpolate);
                }
                (RawMasterFilter::Interpolate, None) => MasterFilter::INTERPOLATE,
                (RawMasterFilter::Interpolate, Some(us)) => MasterFilter::Interpolate {
                    max_interval_us: NonZeroU32::new(us)
                        .ok_or_else(|| at_least_one("[cam] max_interval_us", ""))?,
                },
            },
            max_master_step: match raw.cam.max_master_step {
                Some(step) => Some(
                    NonZeroU64::new(step)
                        .ok_or_else(|| at_least_one("[cam] max_master_step", ""))?,
                ),
                None => None,
            },
        };
        let couplings = crate::couplings::assemble(
            crate::couplings::RawCouplings {
                modulo: raw.modulo.as_ref(),
                guard: raw.direction_guard.as_ref(),
                registration: raw.registration.as_ref(),
                cam_switches: raw.cam_switches.as_ref(),
                steps: &raw.plcopen,
            },
            &mut config,
            base,
        )?;
        let master_update_us = match raw.master.update_us {
            Some(us) => {
                Some(NonZeroU64::new(us).ok_or_else(|| at_least_one("[master] update_us", ""))?)
            }
            None => None,
        };
        Ok(Self {
            tick_us: raw.tick_us,
            duration_us,
            trace_every: raw.trace_every.unwrap_or(1).max(1),
            curve,
            config,
            master_start: raw.start.master,
            master_update_us,
            slave_start: raw.start.slave,
            moves,
            start_input,
            stop,
            switches,
            couplings,
        })
    }

    /// The master as the axis reads it at `t_us`: a coarse master
    /// (`[master] update_us`) shows the position of its last update.
    pub fn master_read_at(&self, t_us: u64) -> i64 {
        match self.master_update_us {
            Some(every) => self.master_at(t_us - t_us % every.get()),
            None => self.master_at(t_us),
        }
    }

    /// Ticks after tick 0 (the state at t = 0) until the duration: the
    /// last tick lands on it.
    pub fn ticks(&self) -> u64 {
        self.duration_us.div_ceil(u64::from(self.tick_us))
    }

    /// Master position (unwrapped) at `t_us`: linear within each move.
    pub fn master_at(&self, t_us: u64) -> i64 {
        let mut from = self.master_start;
        let mut begin = 0u64;
        for m in &self.moves {
            let end = begin.saturating_add(m.duration_us);
            if t_us < end {
                let span = NonZeroU64::new(m.duration_us).unwrap_or(NonZeroU64::MIN);
                return LinearMove::position_after(from, m.target, t_us - begin, span);
            }
            from = m.target;
            begin = end;
        }
        from
    }

    /// Level of the start input at `t_us`.
    pub fn start_input_at(&self, t_us: u64) -> bool {
        self.start_input
            .iter()
            .any(|&(on, off)| (on..off).contains(&t_us))
    }

    /// What the engine receives as master: the raw turn position on a
    /// single-turn master, the unwrapped position otherwise.
    pub fn master_input(&self, master: i64) -> i64 {
        match self.config.single_turn {
            Some(turn) => {
                let turn = i64::try_from(turn.get()).unwrap_or(i64::MAX);
                master.rem_euclid(turn)
            }
            None => master,
        }
    }
}

/// Refuses keys that the chosen `kind`/`mode`/alignment never reads: like a
/// typo, a `delay` under an immediate start or `repeats` on a periodic cam
/// would otherwise be silently ignored, and the run would not be the one the
/// user wrote.
fn unused_keys(cam: &RawCam, start: &RawStart) -> Result<(), ScenarioError> {
    let cam_kind = match cam.kind {
        CamKind::Periodic => "periodic",
        CamKind::Repeat => "repeat",
        CamKind::OneShot => "one-shot",
        CamKind::Normal => "normal",
    };
    if cam.kind != CamKind::OneShot && cam.repeats != 0 {
        return Err(ScenarioError::UnusedCamKey {
            key: "repeats",
            applies_to: "one-shot",
            kind: cam_kind,
        });
    }
    if cam.kind != CamKind::Repeat && cam.min_stroke.is_some() {
        return Err(ScenarioError::UnusedCamKey {
            key: "min_stroke",
            applies_to: "repeat",
            kind: cam_kind,
        });
    }
    let mode = match start.mode {
        StartKind::Immediate => "immediate",
        StartKind::RisingEdge => "rising-edge",
        StartKind::AfterDelay => "after-delay",
        StartKind::AtPosition => "at-position",
        StartKind::Breakpoint => "breakpoint",
    };
    let only = |given: bool, key: &'static str, modes: &'static str| {
        if given {
            return Err(ScenarioError::UnusedStartKey { key, modes, mode });
        }
        Ok(())
    };
    let delayed = matches!(start.mode, StartKind::AfterDelay);
    let positioned = matches!(start.mode, StartKind::AtPosition);
    let breakpoint = matches!(start.mode, StartKind::Breakpoint);
    only(
        !delayed && start.delay.is_some(),
        "delay",
        "\"after-delay\"",
    )?;
    only(
        !positioned && start.position.is_some(),
        "position",
        "\"at-position\"",
    )?;
    only(
        !(delayed || positioned) && start.after_edge,
        "after_edge",
        "\"after-delay\" or \"at-position\"",
    )?;
    let edge = matches!(start.mode, StartKind::RisingEdge) || start.after_edge;
    if !edge && !start.input.is_empty() {
        return Err(ScenarioError::UnusedInput { mode });
    }
    only(
        !breakpoint && start.compare.is_some(),
        "compare",
        "\"breakpoint\"",
    )?;
    only(
        !breakpoint && start.value.is_some(),
        "value",
        "\"breakpoint\"",
    )?;
    let master_value_used = matches!(
        start.master_align,
        Some(RawMasterAlign::Offset | RawMasterAlign::StartAt | RawMasterAlign::StartAtUnzoomed)
    );
    if !master_value_used && start.master_value.is_some() {
        return Err(ScenarioError::UnusedAlignValue {
            key: "master_value",
            aligns: "master_align = \"offset\", \"start-at\" or \"start-at-unzoomed\"",
        });
    }
    let slave_value_used = matches!(
        start.slave_align,
        Some(RawSlaveAlign::Offset | RawSlaveAlign::At)
    );
    if !slave_value_used && start.slave_value.is_some() {
        return Err(ScenarioError::UnusedAlignValue {
            key: "slave_value",
            aligns: "slave_align = \"offset\" or \"at\"",
        });
    }
    Ok(())
}

fn coupling(cam: &RawCam) -> Coupling {
    match cam.kind {
        CamKind::Periodic => Coupling::Periodic,
        CamKind::Repeat => Coupling::Repeat {
            min_stroke: cam.min_stroke.unwrap_or(1),
        },
        CamKind::OneShot => Coupling::OneShot {
            repeats: cam.repeats,
        },
        CamKind::Normal => Coupling::Normal,
    }
}

/// `[start] SETTING needs NEEDS`.
fn needs(setting: &'static str, needs: &'static str) -> ScenarioError {
    ScenarioError::StartNeeds { setting, needs }
}

fn start_mode(start: &RawStart) -> Result<StartMode, ScenarioError> {
    Ok(match start.mode {
        StartKind::Immediate => StartMode::Immediate,
        StartKind::RisingEdge => StartMode::OnRisingEdge,
        StartKind::AfterDelay => StartMode::AfterDelay {
            counts: start
                .delay
                .ok_or_else(|| needs("mode = \"after-delay\"", "delay = <master counts>"))?,
            after_edge: start.after_edge,
        },
        StartKind::AtPosition => StartMode::AtMasterPosition {
            position: start
                .position
                .ok_or_else(|| needs("mode = \"at-position\"", "position = <master counts>"))?,
            after_edge: start.after_edge,
        },
        StartKind::Breakpoint => StartMode::Breakpoint {
            compare: match start
                .compare
                .ok_or_else(|| needs("mode = \"breakpoint\"", "compare = \">=\" or \"<=\""))?
            {
                RawCompare::AtLeast => Compare::AtLeast,
                RawCompare::AtMost => Compare::AtMost,
            },
            value: start
                .value
                .ok_or_else(|| needs("mode = \"breakpoint\"", "value = <master counts>"))?,
        },
    })
}

fn master_align(start: &RawStart) -> Result<MasterAlign, ScenarioError> {
    let value = || {
        start
            .master_value
            .ok_or_else(|| needs("this master_align", "master_value = <counts>"))
    };
    Ok(match start.master_align {
        None | Some(RawMasterAlign::Absolute) => MasterAlign::Absolute,
        Some(RawMasterAlign::Offset) => MasterAlign::Offset(value()?),
        Some(RawMasterAlign::StartAt) => MasterAlign::StartAt(value()?),
        Some(RawMasterAlign::StartAtUnzoomed) => MasterAlign::StartAtUnzoomed(value()?),
    })
}

/// Document 001: a Repeat cam on a single-turn master starts at the curve
/// position nearest the current slave, so that is the default there.
fn slave_align(start: &RawStart, cam: &RawCam) -> Result<SlaveAlign, ScenarioError> {
    let value = || {
        start
            .slave_value
            .ok_or_else(|| needs("this slave_align", "slave_value = <pulses>"))
    };
    Ok(match start.slave_align {
        None if cam.kind == CamKind::Repeat && cam.single_turn.is_some() => {
            SlaveAlign::NearestEquivalent
        }
        None | Some(RawSlaveAlign::Absolute) => SlaveAlign::Absolute,
        Some(RawSlaveAlign::Offset) => SlaveAlign::Offset(value()?),
        Some(RawSlaveAlign::Relative) => SlaveAlign::Relative,
        Some(RawSlaveAlign::Nearest) => SlaveAlign::NearestEquivalent,
        Some(RawSlaveAlign::At) => SlaveAlign::At(value()?),
    })
}

fn zoom(ratio: Option<[u16; 2]>, what: &'static str) -> Result<Zoom, ScenarioError> {
    match ratio {
        None => Ok(Zoom::ONE),
        Some([num, den]) => Zoom::new(num, den).map_err(|error| ScenarioError::Zoom {
            what,
            num,
            den,
            error,
        }),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    const DOC001: &str = r#"
tick_us = 100
[table]
points = [[0, 500], [10000, 1500], [20000, 1000], [30000, 2000]]
[cam]
kind = "repeat"
[master]
moves = [[1.0, 60000], [0.5, 60000]]
"#;

    #[test]
    fn master_moves_are_linear_and_exact_at_the_end() {
        let s = Scenario::parse(DOC001, Path::new(".")).unwrap();
        assert_eq!(s.duration_us, 1_500_000);
        assert_eq!(s.master_at(0), 0);
        assert_eq!(s.master_at(500_000), 30000);
        assert_eq!(s.master_at(1_000_000), 60000);
        assert_eq!(s.master_at(1_400_000), 60000);
        assert_eq!(s.config.coupling, Coupling::Repeat { min_stroke: 1 });
    }

    #[test]
    fn unknown_keys_are_refused() {
        let text = DOC001.replace("kind = \"repeat\"", "knd = \"repeat\"");
        let err = Scenario::parse(&text, Path::new(".")).err().unwrap();
        assert!(format!("{err:#}").contains("knd"));
    }

    #[test]
    fn single_turn_repeat_defaults_to_the_nearest_equivalent() {
        let text = DOC001.replace(
            "kind = \"repeat\"",
            "kind = \"repeat\"\nsingle_turn = 30000",
        );
        let s = Scenario::parse(&text, Path::new(".")).unwrap();
        assert_eq!(s.config.slave_align, SlaveAlign::NearestEquivalent);
        assert_eq!(s.master_input(35000), 5000);
        assert_eq!(s.master_input(-1), 29999);
    }

    #[test]
    fn keys_the_chosen_mode_never_reads_are_refused() {
        let err = |extra: &str| {
            let text = format!("{DOC001}\n{extra}\n");
            format!(
                "{:#}",
                Scenario::parse(&text, Path::new(".")).err().unwrap()
            )
        };
        // A delay without mode = "after-delay" would silently start at once.
        assert!(err("[start]\ndelay = 500").contains("delay only applies"));
        assert!(err("[start]\nposition = 5").contains("position only applies"));
        assert!(err("[start]\nafter_edge = true").contains("after_edge"));
        assert!(err("[start]\ncompare = \">=\"").contains("compare"));
        assert!(err("[start]\nmode = \"rising-edge\"\nvalue = 3").contains("value only applies"));
        assert!(err("[start]\nmaster_value = 3").contains("master_value"));
        assert!(err("[start]\ninput = [[0.1, 0.2]]").contains("input is only read"));
        assert!(
            err("[start]\nslave_align = \"relative\"\nslave_value = 3").contains("slave_value")
        );
        let periodic = DOC001.replace("kind = \"repeat\"", "kind = \"periodic\"\nrepeats = 2");
        let e = Scenario::parse(&periodic, Path::new(".")).err().unwrap();
        assert!(format!("{e:#}").contains("repeats only applies"));
        let periodic = DOC001.replace("kind = \"repeat\"", "min_stroke = 10");
        let e = Scenario::parse(&periodic, Path::new(".")).err().unwrap();
        assert!(format!("{e:#}").contains("min_stroke only applies"));
        // The keys a mode does read still work.
        let ok =
            format!("{DOC001}\n[start]\nmode = \"after-delay\"\ndelay = 500\nafter_edge = true\n");
        assert!(Scenario::parse(&ok, Path::new(".")).is_ok());
    }

    #[test]
    fn trace_every_zero_and_huge_targets_are_explained() {
        let text = format!("trace_every = 0\n{DOC001}");
        let e = Scenario::parse(&text, Path::new(".")).err().unwrap();
        assert!(format!("{e:#}").contains("trace_every must be at least 1"));
        let text = DOC001.replace("[[1.0, 60000]", "[[1.0, 9223372036854775807]");
        let e = format!(
            "{:#}",
            Scenario::parse(&text, Path::new(".")).err().unwrap()
        );
        assert!(e.contains("out of range"), "{e}");
        assert!(!e.contains("whole number"), "{e}");
    }

    #[test]
    fn incomplete_start_settings_name_the_missing_key() {
        let text = format!("{DOC001}\n[start]\nmode = \"after-delay\"\n");
        let err = Scenario::parse(&text, Path::new(".")).err().unwrap();
        assert!(format!("{err:#}").contains("delay"));
    }
}
