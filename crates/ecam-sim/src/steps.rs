//! `[[plcopen]]` steps: PLCopen function blocks called from a scenario
//! file at a time or a master position, so that `MC_CamIn`, `MC_GearIn`,
//! `MC_Phasing`, `MC_CamOut`, `MC_MoveSuperimposed`... can be tried
//! without Rust. Each step is a trigger and exactly one block with its
//! inputs; every key is in `docs/simulate.md`.

use std::num::NonZeroU64;
use std::path::Path;

use ecam_core::CamCurve;
use ecam_engine::plcopen::{
    ActivationMode, BufferMode, CamIn, CamInStartMode, CamOut, CamTableSelect, DEFAULT_BLEND,
    ExecutionMode, SyncAt,
};
use ecam_engine::{
    GearIn, GearInPos, GearOut, GearRamp, MoveLimits, MoveSuperimposed, Phasing, PhasingMode, Zoom,
};
use serde::Deserialize;

use crate::couplings_error::CouplingsError;
use crate::error::ScenarioError;
use crate::trigger::{StopTrigger, trigger};

/// One `[[plcopen]]` step: when, and which block with which inputs.
pub struct PlcopenStep {
    /// When the block is called (its `Execute` rises).
    pub trigger: StopTrigger,
    /// The block.
    pub block: Block,
}

/// A PLCopen function block and its inputs.
pub enum Block {
    /// `MC_CamTableSelect`, with a new table or the scenario's own.
    CamTableSelect {
        /// How the table is read.
        select: CamTableSelect,
        /// A new table (`None`: keep the one selected).
        table: Option<Box<dyn CamCurve>>,
    },
    /// `MC_CamIn`.
    CamIn(CamIn),
    /// `MC_CamOut`.
    CamOut(CamOut),
    /// `MC_GearIn`.
    GearIn(GearIn),
    /// `MC_GearInPos`.
    GearInPos(GearInPos),
    /// `MC_GearOut`.
    GearOut(GearOut),
    /// `MC_PhasingAbsolute` / `MC_PhasingRelative`.
    Phasing(Phasing),
    /// `MC_MoveSuperimposed`.
    MoveSuperimposed(MoveSuperimposed),
    /// `MC_HaltSuperimposed` with this deceleration.
    HaltSuperimposed(f64),
    /// `MC_Stop`: everything holds where it is.
    Stop,
}

impl Block {
    /// The block's PLCopen name.
    pub fn name(&self) -> &'static str {
        match self {
            Self::CamTableSelect { .. } => "MC_CamTableSelect",
            Self::CamIn(_) => "MC_CamIn",
            Self::CamOut(_) => "MC_CamOut",
            Self::GearIn(_) => "MC_GearIn",
            Self::GearInPos(_) => "MC_GearInPos",
            Self::GearOut(_) => "MC_GearOut",
            Self::Phasing(_) => "MC_Phasing",
            Self::MoveSuperimposed(_) => "MC_MoveSuperimposed",
            Self::HaltSuperimposed(_) => "MC_HaltSuperimposed",
            Self::Stop => "MC_Stop",
        }
    }
}

/// `[[plcopen]]` as written.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawStep {
    at_s: Option<f64>,
    master_at_least: Option<i64>,
    master_at_most: Option<i64>,
    #[serde(rename = "MC_CamTableSelect")]
    cam_table_select: Option<RawTableSelect>,
    #[serde(rename = "MC_CamIn")]
    cam_in: Option<RawCamIn>,
    #[serde(rename = "MC_CamOut")]
    cam_out: Option<RawCamOut>,
    #[serde(rename = "MC_GearIn")]
    gear_in: Option<RawGearIn>,
    #[serde(rename = "MC_GearInPos")]
    gear_in_pos: Option<RawGearInPos>,
    #[serde(rename = "MC_GearOut")]
    gear_out: Option<RawGearOut>,
    #[serde(rename = "MC_Phasing")]
    phasing: Option<RawPhasing>,
    #[serde(rename = "MC_MoveSuperimposed")]
    move_superimposed: Option<RawMove>,
    #[serde(rename = "MC_HaltSuperimposed")]
    halt_superimposed: Option<RawHalt>,
    #[serde(rename = "MC_Stop")]
    stop: Option<RawEmpty>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawEmpty {}

fn yes() -> bool {
    true
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawTableSelect {
    #[serde(default = "yes")]
    periodic: bool,
    #[serde(default = "yes")]
    master_absolute: bool,
    #[serde(default = "yes")]
    slave_absolute: bool,
    #[serde(default)]
    execution_mode: RawExecution,
    table: Option<toml::Table>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawExecution {
    #[default]
    Immediate,
    Queued,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawCamIn {
    #[serde(default)]
    master_offset: i64,
    #[serde(default)]
    slave_offset: i64,
    master_scaling: Option<[i32; 2]>,
    slave_scaling: Option<[i32; 2]>,
    #[serde(default)]
    start_mode: RawStartMode,
    ramp_distance: Option<u64>,
    #[serde(default)]
    activation: RawActivation,
    position: Option<i64>,
    #[serde(default)]
    buffer_mode: RawBufferMode,
    blend: Option<u64>,
    sync_position: Option<i64>,
    start_distance: Option<u64>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawStartMode {
    #[default]
    Absolute,
    Relative,
    Bumpless,
    RampIn,
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawActivation {
    #[default]
    Immediate,
    NextCycle,
    AtPosition,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawBufferMode {
    #[default]
    Aborting,
    Buffered,
}

#[derive(Deserialize, Debug, Default)]
#[serde(deny_unknown_fields)]
struct RawCamOut {
    #[serde(default)]
    mode: RawCamOutMode,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawCamOutMode {
    #[default]
    AtVelocity,
    Hold,
    EndOfCycle,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawGearIn {
    ratio: [i32; 2],
    distance: Option<u64>,
    acceleration: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawGearInPos {
    ratio: [i32; 2],
    master_sync: i64,
    slave_sync: i64,
    master_start_distance: Option<u64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawGearOut {
    distance: Option<u64>,
    acceleration: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawPhasing {
    shift: i64,
    #[serde(default)]
    mode: RawPhasingMode,
    velocity: f64,
    acceleration: f64,
    deceleration: Option<f64>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawPhasingMode {
    #[default]
    Absolute,
    Relative,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawMove {
    distance: i64,
    velocity: f64,
    acceleration: f64,
    deceleration: Option<f64>,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawHalt {
    deceleration: f64,
}

fn ratio(r: [i32; 2], what: &str) -> Result<Zoom, CouplingsError> {
    let [num, den] = r;
    let den16 = u16::try_from(den).ok();
    den16
        .and_then(|d| Zoom::signed(num, d).ok())
        .ok_or_else(|| CouplingsError::Ratio {
            what: what.to_string(),
            num,
            den,
        })
}

fn nonzero(v: Option<u64>, what: &str) -> Result<Option<NonZeroU64>, ScenarioError> {
    v.map(|d| {
        NonZeroU64::new(d).ok_or_else(|| ScenarioError::AtLeastOne {
            key: what.to_string(),
            unit: "",
        })
    })
    .transpose()
}

fn ramp(
    distance: Option<u64>,
    acceleration: Option<f64>,
    what: &str,
) -> Result<GearRamp, ScenarioError> {
    Ok(
        match (
            nonzero(distance, &format!("{what} distance"))?,
            acceleration,
        ) {
            (None, None) => GearRamp::Immediate,
            (Some(d), None) => GearRamp::Distance(d),
            (None, Some(a)) if a.is_finite() && a > 0.0 => GearRamp::Acceleration(a),
            (None, Some(value)) => {
                return Err(CouplingsError::AboveZero {
                    key: format!("{what} acceleration"),
                    value,
                }
                .into());
            }
            (Some(_), Some(_)) => {
                return Err(CouplingsError::DistanceOrAcceleration {
                    what: what.to_string(),
                }
                .into());
            }
        },
    )
}

fn limits(v: f64, a: f64, d: Option<f64>, what: &str) -> Result<MoveLimits, CouplingsError> {
    MoveLimits::new(v, a, d.unwrap_or(a)).map_err(|error| CouplingsError::Refused {
        place: what.to_string(),
        error,
    })
}

fn cam_in(raw: &RawCamIn, what: &str) -> Result<CamIn, ScenarioError> {
    let only = |given: bool, key: &'static str, when: &'static str| {
        if given {
            return Err(CouplingsError::UnusedKey {
                what: what.to_string(),
                key,
                when,
            });
        }
        Ok(())
    };
    let needs = |setting: &'static str, needs: &'static str| CouplingsError::Needs {
        what: what.to_string(),
        setting,
        needs,
    };
    only(
        raw.start_mode != RawStartMode::RampIn && raw.ramp_distance.is_some(),
        "ramp_distance",
        "with start_mode = \"ramp-in\"",
    )?;
    only(
        raw.activation != RawActivation::AtPosition && raw.position.is_some(),
        "position",
        "with activation = \"at-position\"",
    )?;
    let start_mode = match raw.start_mode {
        RawStartMode::Absolute => CamInStartMode::Absolute,
        RawStartMode::Relative => CamInStartMode::Relative,
        RawStartMode::Bumpless => CamInStartMode::Bumpless,
        RawStartMode::RampIn => CamInStartMode::RampIn {
            distance: nonzero(raw.ramp_distance, &format!("{what} ramp_distance"))?
                .ok_or_else(|| needs("start_mode = \"ramp-in\"", "ramp_distance"))?,
        },
    };
    let activation = match raw.activation {
        RawActivation::Immediate => ActivationMode::Immediate,
        RawActivation::NextCycle => ActivationMode::NextCycle,
        RawActivation::AtPosition => ActivationMode::AtMasterPosition(
            raw.position
                .ok_or_else(|| needs("activation = \"at-position\"", "position"))?,
        ),
    };
    let sync_at = match (raw.sync_position, raw.start_distance) {
        (None, None) => None,
        (Some(position), Some(d)) => Some(SyncAt {
            position,
            start_distance: NonZeroU64::new(d).ok_or_else(|| ScenarioError::AtLeastOne {
                key: format!("{what} start_distance"),
                unit: "",
            })?,
            forward: true,
        }),
        _ => {
            return Err(CouplingsError::SyncTogether {
                what: what.to_string(),
            }
            .into());
        }
    };
    let scaling = |r: Option<[i32; 2]>, key: &str| match r {
        Some(r) => ratio(r, &format!("{what} {key}")),
        None => Ok(Zoom::ONE),
    };
    Ok(CamIn {
        master_offset: raw.master_offset,
        slave_offset: raw.slave_offset,
        master_scaling: scaling(raw.master_scaling, "master_scaling")?,
        slave_scaling: scaling(raw.slave_scaling, "slave_scaling")?,
        start_mode,
        activation,
        buffer_mode: match raw.buffer_mode {
            RawBufferMode::Aborting => BufferMode::Aborting,
            RawBufferMode::Buffered => BufferMode::Buffered,
        },
        blend: nonzero(raw.blend, &format!("{what} blend"))?.unwrap_or(DEFAULT_BLEND),
        sync_at,
        ramp_limits: None,
    })
}

/// Checks the `[[plcopen]]` steps and turns them into blocks.
pub(crate) fn steps(raw: &[RawStep], base: &Path) -> Result<Vec<PlcopenStep>, ScenarioError> {
    raw.iter()
        .enumerate()
        .map(|(i, s)| {
            let what = format!("[[plcopen]] {}", i + 1);
            let trigger = trigger(s.at_s, s.master_at_least, s.master_at_most, &what)?;
            let mut blocks = Vec::new();
            if let Some(r) = &s.cam_table_select {
                let table = match &r.table {
                    Some(t) => Some(ecam_design::load_table(t, base).map_err(|error| {
                        ScenarioError::Table {
                            place: format!("{what} MC_CamTableSelect table"),
                            error: Box::new(error),
                        }
                    })?),
                    None => None,
                };
                blocks.push(Block::CamTableSelect {
                    select: CamTableSelect {
                        periodic: r.periodic,
                        master_absolute: r.master_absolute,
                        slave_absolute: r.slave_absolute,
                        execution_mode: match r.execution_mode {
                            RawExecution::Immediate => ExecutionMode::Immediate,
                            RawExecution::Queued => ExecutionMode::Queued,
                        },
                    },
                    table,
                });
            }
            if let Some(r) = &s.cam_in {
                blocks.push(Block::CamIn(cam_in(r, &format!("{what} MC_CamIn"))?));
            }
            if let Some(r) = &s.cam_out {
                blocks.push(Block::CamOut(match r.mode {
                    RawCamOutMode::AtVelocity => CamOut::AtVelocity,
                    RawCamOutMode::Hold => CamOut::Hold,
                    RawCamOutMode::EndOfCycle => CamOut::EndOfCycle,
                }));
            }
            if let Some(r) = &s.gear_in {
                let w = format!("{what} MC_GearIn");
                blocks.push(Block::GearIn(GearIn {
                    ratio: ratio(r.ratio, &format!("{w} ratio"))?,
                    ramp: ramp(r.distance, r.acceleration, &w)?,
                }));
            }
            if let Some(r) = &s.gear_in_pos {
                let w = format!("{what} MC_GearInPos");
                blocks.push(Block::GearInPos(GearInPos {
                    ratio: ratio(r.ratio, &format!("{w} ratio"))?,
                    master_sync: r.master_sync,
                    slave_sync: r.slave_sync,
                    master_start_distance: nonzero(
                        r.master_start_distance,
                        &format!("{w} master_start_distance"),
                    )?,
                }));
            }
            if let Some(r) = &s.gear_out {
                blocks.push(Block::GearOut(GearOut {
                    ramp: ramp(r.distance, r.acceleration, &format!("{what} MC_GearOut"))?,
                }));
            }
            if let Some(r) = &s.phasing {
                blocks.push(Block::Phasing(Phasing {
                    shift: r.shift,
                    mode: match r.mode {
                        RawPhasingMode::Absolute => PhasingMode::Absolute,
                        RawPhasingMode::Relative => PhasingMode::Relative,
                    },
                    limits: limits(
                        r.velocity,
                        r.acceleration,
                        r.deceleration,
                        &format!("{what} MC_Phasing"),
                    )?,
                }));
            }
            if let Some(r) = &s.move_superimposed {
                blocks.push(Block::MoveSuperimposed(MoveSuperimposed {
                    distance: r.distance,
                    limits: limits(
                        r.velocity,
                        r.acceleration,
                        r.deceleration,
                        &format!("{what} MC_MoveSuperimposed"),
                    )?,
                }));
            }
            if let Some(r) = &s.halt_superimposed {
                if !(r.deceleration.is_finite() && r.deceleration > 0.0) {
                    return Err(CouplingsError::AboveZero {
                        key: format!("{what} MC_HaltSuperimposed deceleration"),
                        value: r.deceleration,
                    }
                    .into());
                }
                blocks.push(Block::HaltSuperimposed(r.deceleration));
            }
            if s.stop.is_some() {
                blocks.push(Block::Stop);
            }
            let got = blocks.len();
            match (blocks.pop(), got) {
                (Some(block), 1) => Ok(PlcopenStep { trigger, block }),
                _ => Err(CouplingsError::OneBlock { what, got }.into()),
            }
        })
        .collect()
}
