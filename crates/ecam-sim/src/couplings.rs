//! The scenario sections of the couplings beyond the documents: `[modulo]`,
//! `[direction_guard]`, `[registration]` (with the marks on the material),
//! `[cam_switches]`; the PLCopen steps are in `steps.rs`. Every key is in
//! `docs/simulate.md`.
//!
//! A scenario with any of these (or a `[[plcopen]]` step) runs on a slave
//! axis ([`ecam_engine::SlaveAxis`]) instead of a plain cam axis.

use std::num::NonZeroU64;
use std::path::Path;

use ecam_engine::{
    AxisConfig, CamSwitch, DigitalCamSwitch, DirectionGuard, GuardDirection, GuardResume,
    LatchSource, MasterFilter, ModuloAxis, ModuloStart, RegistrationConfig, SlaveAlign,
    SlaveConfig, SwitchDirection, SwitchMode, TRACKS, TrackOptions,
};
use serde::Deserialize;

use crate::couplings_error::CouplingsError;
use crate::error::ScenarioError;
use crate::steps::{PlcopenStep, RawStep};

/// `[modulo]`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawModulo {
    modulo: u64,
    #[serde(default)]
    start: RawModuloStart,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawModuloStart {
    #[default]
    Absolute,
    Relative,
    EndlessPositive,
    EndlessNegative,
    Nearest,
}

/// `[direction_guard]`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawGuard {
    #[serde(default)]
    allow: RawAllow,
    #[serde(default)]
    resume: RawResume,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawAllow {
    #[default]
    Forward,
    Backward,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawResume {
    #[default]
    AtOnce,
    AtReversalPoint,
}

/// `[registration]`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawRegistration {
    #[serde(default)]
    source: RawSource,
    cycle: u64,
    expected: i64,
    window: u64,
    max_correction: u64,
    ramp: u64,
    marks: RawMarks,
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawSource {
    #[default]
    Master,
    Slave,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawMarks {
    first: i64,
    spacing: u64,
    #[serde(default)]
    missing: Vec<u64>,
}

/// `[cam_switches]`.
#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawCamSwitches {
    #[serde(default)]
    axis: RawSwitchAxis,
    modulo: Option<u64>,
    #[serde(default)]
    switch: Vec<RawSwitch>,
    #[serde(default)]
    track: Vec<RawTrack>,
}

#[derive(Deserialize, Debug, Default, Clone, Copy, PartialEq, Eq)]
#[serde(rename_all = "kebab-case")]
enum RawSwitchAxis {
    #[default]
    Master,
    Slave,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawSwitch {
    track: u8,
    first_on: i64,
    last_on: Option<i64>,
    duration_s: Option<f64>,
    #[serde(default)]
    direction: RawSwitchDirection,
}

#[derive(Deserialize, Debug, Default, Clone, Copy)]
#[serde(rename_all = "kebab-case")]
enum RawSwitchDirection {
    #[default]
    Both,
    Positive,
    Negative,
}

#[derive(Deserialize, Debug)]
#[serde(deny_unknown_fields)]
struct RawTrack {
    track: u8,
    #[serde(default)]
    on_compensation_s: f64,
    #[serde(default)]
    off_compensation_s: f64,
    #[serde(default)]
    hysteresis: u64,
}

/// Print marks on the material: one every `spacing` from `first` (master
/// counts for a master latch, slave pulses for a slave latch), but for
/// the `missing` ones (0 is the first mark).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Marks {
    /// The first mark.
    pub first: i64,
    /// Between two marks.
    pub spacing: NonZeroU64,
    /// Marks not printed, by number.
    pub missing: Vec<u64>,
}

impl Marks {
    /// The marks passed going from `from` to `to` (forwards only; a
    /// touch probe latches on the mark's leading edge): their positions.
    pub fn passed(&self, from: i64, to: i64) -> impl Iterator<Item = i64> + '_ {
        let spacing = i128::from(self.spacing.get());
        let first = i128::from(self.first);
        // The first mark number beyond `from` and the last at or before `to`.
        let begin = (i128::from(from) - first).div_euclid(spacing) + 1;
        let end = (i128::from(to) - first).div_euclid(spacing);
        let begin = begin.max(0);
        (begin..=end)
            .take(64)
            .filter(|&i| u64::try_from(i).is_ok_and(|i| !self.missing.contains(&i)))
            .filter_map(move |i| i64::try_from(first + i * spacing).ok())
    }
}

/// Which position the cam switches compare.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SwitchAxis {
    /// The master the slave sees.
    Master,
    /// The commanded slave.
    Slave,
}

/// `[cam_switches]`: the cams, their tracks' options, the axis they watch.
#[derive(Clone, Debug, PartialEq)]
pub struct CamSwitches {
    /// The position they compare.
    pub axis: SwitchAxis,
    /// The cams.
    pub switches: Vec<CamSwitch>,
    /// The group, with its modulo and track options.
    pub group: DigitalCamSwitch,
}

/// Everything a slave axis needs beyond the cam.
#[derive(Default)]
pub struct Couplings {
    /// Modulo, direction guard, registration (the ceiling and the master
    /// filter come from `[cam]`).
    pub slave: SlaveConfig,
    /// The print marks registration latches.
    pub marks: Option<Marks>,
    /// Cam switches, if any.
    pub cam_switches: Option<CamSwitches>,
    /// PLCopen steps, in the order they are requested.
    pub steps: Vec<PlcopenStep>,
}

/// The coupling sections of a scenario as written.
pub(crate) struct RawCouplings<'a> {
    pub(crate) modulo: Option<&'a RawModulo>,
    pub(crate) guard: Option<&'a RawGuard>,
    pub(crate) registration: Option<&'a RawRegistration>,
    pub(crate) cam_switches: Option<&'a RawCamSwitches>,
    pub(crate) steps: &'a [RawStep],
}

/// With `[[plcopen]]` steps the cam is driven by `MC_CamTableSelect` and
/// `MC_CamIn`: refuses the `[cam]`, `[start]` and `[[switch]]` keys they
/// replace, which would otherwise be silently ignored.
pub(crate) fn plcopen_reads_no_cam_keys(
    cam: bool,
    start: bool,
    switch: bool,
) -> Result<(), CouplingsError> {
    if cam {
        return Err(CouplingsError::PlcopenCamKeys);
    }
    if start {
        return Err(CouplingsError::PlcopenStartKeys);
    }
    if switch {
        return Err(CouplingsError::PlcopenSwitch);
    }
    Ok(())
}

/// Turns the coupling sections into [`Couplings`] (`None` when there are
/// none) and sets what the cam needs for them in `config`.
pub(crate) fn assemble(
    raw: RawCouplings<'_>,
    config: &mut AxisConfig,
    base: &Path,
) -> Result<Option<Couplings>, ScenarioError> {
    if raw.modulo.is_none()
        && raw.guard.is_none()
        && raw.registration.is_none()
        && raw.cam_switches.is_none()
        && raw.steps.is_empty()
    {
        return Ok(None);
    }
    let modulo = raw.modulo.map(modulo).transpose()?;
    if let Some(axis) = modulo
        && raw.steps.is_empty()
    {
        config.slave_align = match config.slave_align {
            SlaveAlign::Absolute => SlaveAlign::Modulo { axis, offset: 0 },
            SlaveAlign::Offset(offset) => SlaveAlign::Modulo { axis, offset },
            _ => return Err(CouplingsError::ModuloAlign.into()),
        };
    }
    let (registration, marks) = match raw.registration.map(registration).transpose()? {
        Some((config, marks)) => (Some(config), Some(marks)),
        None => (None, None),
    };
    let slave = SlaveConfig {
        max_frequency_hz: config.max_frequency_hz,
        master_filter: config.master_filter,
        modulo,
        guard: raw.guard.map(guard),
        registration,
    };
    // The slave axis tracks the master and hands the cam its fraction.
    config.master_filter = MasterFilter::Direct;
    Ok(Some(Couplings {
        slave,
        marks,
        cam_switches: raw.cam_switches.map(cam_switches).transpose()?,
        steps: crate::steps::steps(raw.steps, base)?,
    }))
}

/// The engine refused the setting of `place`.
fn refused(place: &str) -> impl FnOnce(ecam_engine::CouplingError) -> CouplingsError + '_ {
    move |error| CouplingsError::Refused {
        place: place.to_string(),
        error,
    }
}

pub(crate) fn modulo(raw: &RawModulo) -> Result<ModuloAxis, CouplingsError> {
    let start = match raw.start {
        RawModuloStart::Absolute => ModuloStart::Absolute,
        RawModuloStart::Relative => ModuloStart::Relative,
        RawModuloStart::EndlessPositive => ModuloStart::EndlessPositive,
        RawModuloStart::EndlessNegative => ModuloStart::EndlessNegative,
        RawModuloStart::Nearest => ModuloStart::Nearest,
    };
    ModuloAxis::new(raw.modulo, start).map_err(refused("[modulo] modulo"))
}

pub(crate) fn guard(raw: &RawGuard) -> DirectionGuard {
    DirectionGuard {
        direction: match raw.allow {
            RawAllow::Forward => GuardDirection::Forward,
            RawAllow::Backward => GuardDirection::Backward,
        },
        resume: match raw.resume {
            RawResume::AtOnce => GuardResume::AtOnce,
            RawResume::AtReversalPoint => GuardResume::AtReversalPoint,
        },
    }
}

pub(crate) fn registration(
    raw: &RawRegistration,
) -> Result<(RegistrationConfig, Marks), ScenarioError> {
    let nz = |v: u64, key: &str| {
        NonZeroU64::new(v).ok_or_else(|| ScenarioError::AtLeastOne {
            key: format!("[registration] {key}"),
            unit: "",
        })
    };
    let config = RegistrationConfig {
        source: match raw.source {
            RawSource::Master => LatchSource::Master,
            RawSource::Slave => LatchSource::Slave,
        },
        cycle: nz(raw.cycle, "cycle")?,
        expected: raw.expected,
        window: raw.window,
        max_correction: raw.max_correction,
        ramp: nz(raw.ramp, "ramp")?,
    };
    config.check().map_err(refused("[registration]"))?;
    let marks = Marks {
        first: raw.marks.first,
        spacing: nz(raw.marks.spacing, "marks.spacing")?,
        missing: raw.marks.missing.clone(),
    };
    Ok((config, marks))
}

pub(crate) fn cam_switches(raw: &RawCamSwitches) -> Result<CamSwitches, ScenarioError> {
    let mut options = [TrackOptions::default(); TRACKS];
    let micros = |seconds: f64, key: &'static str| -> Result<i32, CouplingsError> {
        if !(-1.0..=1.0).contains(&seconds) {
            return Err(CouplingsError::Compensation { key, seconds });
        }
        Ok((seconds * 1e6).round() as i32)
    };
    for t in &raw.track {
        let slot = options
            .get_mut(usize::from(t.track))
            .ok_or(CouplingsError::Track { track: t.track })?;
        *slot = TrackOptions {
            on_compensation_us: micros(t.on_compensation_s, "on_compensation_s")?,
            off_compensation_us: micros(t.off_compensation_s, "off_compensation_s")?,
            hysteresis: t.hysteresis,
        };
    }
    let switches = raw
        .switch
        .iter()
        .enumerate()
        .map(|(i, s)| -> Result<CamSwitch, CouplingsError> {
            let what = format!("[[cam_switches.switch]] {}", i + 1);
            let mode = match (s.last_on, s.duration_s) {
                (Some(last_on), None) => SwitchMode::Position { last_on },
                (None, Some(d)) if (0.0..=3600.0).contains(&d) => SwitchMode::Time {
                    duration_us: (d * 1e6).round() as u64,
                },
                (None, Some(seconds)) => {
                    return Err(CouplingsError::TimeCamDuration { what, seconds });
                }
                _ => return Err(CouplingsError::CamSwitchMode { what }),
            };
            Ok(CamSwitch {
                track: s.track,
                first_on: s.first_on,
                mode,
                direction: match s.direction {
                    RawSwitchDirection::Both => SwitchDirection::Both,
                    RawSwitchDirection::Positive => SwitchDirection::Positive,
                    RawSwitchDirection::Negative => SwitchDirection::Negative,
                },
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    DigitalCamSwitch::check(&switches).map_err(refused("[cam_switches]"))?;
    let modulo = match raw.modulo {
        Some(m) => Some(NonZeroU64::new(m).ok_or_else(|| ScenarioError::AtLeastOne {
            key: "[cam_switches] modulo".to_string(),
            unit: "",
        })?),
        None => None,
    };
    Ok(CamSwitches {
        axis: match raw.axis {
            RawSwitchAxis::Master => SwitchAxis::Master,
            RawSwitchAxis::Slave => SwitchAxis::Slave,
        },
        switches,
        group: DigitalCamSwitch::new(modulo, options),
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn marks_passed_skip_the_missing_ones() {
        let marks = Marks {
            first: 100,
            spacing: NonZeroU64::new(1000).unwrap(),
            missing: vec![2],
        };
        let got: Vec<i64> = marks.passed(0, 3100).collect();
        assert_eq!(got, [100, 1100, 3100]);
        assert_eq!(marks.passed(100, 1099).count(), 0);
        assert_eq!(marks.passed(3100, 0).count(), 0);
    }
}
