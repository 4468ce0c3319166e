//! Why the coupling sections of a scenario (`[modulo]`,
//! `[direction_guard]`, `[registration]`, `[cam_switches]`,
//! `[[plcopen]]`) do not describe a run. Each message names the key, as
//! [`crate::ScenarioError`]'s do; the keys the couplings share with the
//! rest of the file (triggers, seconds, tables, "at least 1") are
//! reported as the rest of the file reports them.

use core::fmt;

use ecam_engine::CouplingError;

/// A coupling section that does not describe a run.
#[derive(Debug)]
pub enum CouplingsError {
    /// The engine refuses a coupling's setting (`place` names the section
    /// or the step).
    Refused {
        /// The section or step.
        place: String,
        /// Why.
        error: CouplingError,
    },
    /// `[[plcopen]]` steps with `[cam]` keys that `MC_CamTableSelect` and
    /// `MC_CamIn` replace.
    PlcopenCamKeys,
    /// `[[plcopen]]` steps with `[start]` keys that `MC_CamIn` replaces.
    PlcopenStartKeys,
    /// `[[plcopen]]` steps with `[[switch]]` entries.
    PlcopenSwitch,
    /// `[modulo]` with a `[start] slave_align` it cannot place in a turn.
    ModuloAlign,
    /// A cam-switch compensation time outside ±1 s.
    Compensation {
        /// `on_compensation_s` or `off_compensation_s`.
        key: &'static str,
        /// The value given.
        seconds: f64,
    },
    /// A `[[cam_switches.track]]` number beyond the 32 tracks.
    Track {
        /// The number given.
        track: u8,
    },
    /// A time cam's `duration_s` outside 0 to an hour.
    TimeCamDuration {
        /// `[[cam_switches.switch]] N`.
        what: String,
        /// The value given.
        seconds: f64,
    },
    /// A cam switch with both or neither of `last_on` and `duration_s`.
    CamSwitchMode {
        /// `[[cam_switches.switch]] N`.
        what: String,
    },
    /// A ratio or scaling the engine cannot hold.
    Ratio {
        /// The step and key.
        what: String,
        /// The numerator given.
        num: i32,
        /// The denominator given.
        den: i32,
    },
    /// An acceleration or deceleration that is not a number above zero.
    AboveZero {
        /// The step and key.
        key: String,
        /// The value given.
        value: f64,
    },
    /// A gear ramp with both a distance and an acceleration.
    DistanceOrAcceleration {
        /// The step and block.
        what: String,
    },
    /// An `MC_CamIn` key its other inputs never read.
    UnusedKey {
        /// The step and block.
        what: String,
        /// The key.
        key: &'static str,
        /// When it is read.
        when: &'static str,
    },
    /// An `MC_CamIn` input without the key it needs.
    Needs {
        /// The step and block.
        what: String,
        /// The setting.
        setting: &'static str,
        /// The key it needs.
        needs: &'static str,
    },
    /// `sync_position` without `start_distance` or the other way round.
    SyncTogether {
        /// The step and block.
        what: String,
    },
    /// A `[[plcopen]]` step with no block or more than one.
    OneBlock {
        /// `[[plcopen]] N`.
        what: String,
        /// How many blocks it names.
        got: usize,
    },
}

impl fmt::Display for CouplingsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Refused { place, error } => write!(f, "{place}: {error}"),
            Self::PlcopenCamKeys => f.write_str(
                "with [[plcopen]] steps the cam is read as MC_CamTableSelect and MC_CamIn say: set kind, zooms and ramp-in there, not in [cam]; single_turn, max_master_step and [[sync]] are not offered with them",
            ),
            Self::PlcopenStartKeys => f.write_str(
                "with [[plcopen]] steps MC_CamIn starts the cam: [start] takes only master and slave (the positions at t = 0)",
            ),
            Self::PlcopenSwitch => f.write_str(
                "with [[plcopen]] steps a table change is MC_CamTableSelect then MC_CamIn (buffer_mode, activation, blend), not [[switch]]",
            ),
            Self::ModuloAlign => f.write_str(
                "[modulo] places an absolute cam in the turn its start mode picks: [start] slave_align must be \"absolute\" or \"offset\" (start = \"relative\" in [modulo] adds the table to the slave)",
            ),
            Self::Compensation { key, seconds } => write!(
                f,
                "[cam_switches] {key} = {seconds:?} s: must be between -1 and 1 seconds"
            ),
            Self::Track { track } => {
                write!(f, "[[cam_switches.track]] track = {track}: must be 0–31")
            }
            Self::TimeCamDuration { what, seconds } => write!(
                f,
                "{what}: duration_s = {seconds:?} must be 0 to 3600 seconds"
            ),
            Self::CamSwitchMode { what } => write!(
                f,
                "{what} needs exactly one of last_on (position cam) or duration_s (time cam)"
            ),
            Self::Ratio { what, num, den } => write!(
                f,
                "{what} = [{num}, {den}]: the numerator must be ±1 to ±65535, the denominator 1 to 65535"
            ),
            Self::AboveZero { key, value } => {
                write!(f, "{key} = {value:?}: must be a number above zero")
            }
            Self::DistanceOrAcceleration { what } => {
                write!(f, "{what}: give distance or acceleration, not both")
            }
            Self::UnusedKey { what, key, when } => write!(f, "{what} {key} only applies {when}"),
            Self::Needs {
                what,
                setting,
                needs,
            } => write!(f, "{what} {setting} needs {needs}"),
            Self::SyncTogether { what } => {
                write!(f, "{what}: sync_position and start_distance go together")
            }
            Self::OneBlock { what, got } => write!(
                f,
                "{what} needs exactly one block (MC_CamTableSelect, MC_CamIn, MC_CamOut, MC_GearIn, MC_GearInPos, MC_GearOut, MC_Phasing, MC_MoveSuperimposed, MC_HaltSuperimposed, MC_Stop); it has {got}"
            ),
        }
    }
}

impl std::error::Error for CouplingsError {}
