//! The drive file: the slave's mechanics and the drive's limits.

use core::fmt;

/// The slave axis' mechanics, as the motor sees them.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mechanics {
    /// Slave pulses (the cam's slave unit) per motor revolution.
    pub units_per_motor_rev: f64,
    /// Motor revolutions per revolution of the load shaft (a 5:1 gearbox is 5).
    #[serde(default = "one")]
    pub gear_ratio: f64,
    /// Load inertia at the load shaft, kg·m².
    pub load_inertia: f64,
    /// Motor (rotor, brake, coupling) inertia, kg·m².
    pub motor_inertia: f64,
    /// Friction torque at the load shaft, N·m, against the motion (none at rest).
    #[serde(default)]
    pub friction_torque: f64,
    /// Constant load torque at the load shaft, N·m (a weight on a vertical
    /// axis: positive resists positive motion).
    #[serde(default)]
    pub load_torque: f64,
}

fn one() -> f64 {
    1.0
}

/// The drive's (and motor's) limits.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DriveLimits {
    /// Highest motor speed, rpm.
    pub max_speed: f64,
    /// Peak torque, N·m at the motor.
    pub peak_torque: f64,
    /// Continuous (RMS) torque, N·m at the motor.
    pub rms_torque: f64,
    /// Highest slave jerk, pulses/s³, when the drive has one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub max_jerk: Option<f64>,
}

/// A drive file: `[mechanics]` and `[limits]`.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Drive {
    /// The slave's mechanics.
    pub mechanics: Mechanics,
    /// The drive's limits.
    pub limits: DriveLimits,
}

/// What is wrong with a drive or with the motion given to check.
#[derive(Clone, Debug, PartialEq)]
pub enum DriveError {
    /// A value that must be a positive finite number (or ≥ 0) is not.
    Value {
        /// Its key in the drive file.
        key: &'static str,
        /// What it must be.
        must: &'static str,
    },
    /// The motion has fewer than two samples or no master span.
    NoMotion,
}

impl fmt::Display for DriveError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Value { key, must } => write!(f, "drive: `{key}` must be {must}"),
            Self::NoMotion => {
                f.write_str("drive check: the cam has no motion to check (no master span)")
            }
        }
    }
}

impl core::error::Error for DriveError {}

impl Drive {
    /// Checks every value: positive where a ratio or a limit, at least 0
    /// for inertias and friction, a load inertia or a motor inertia above 0.
    ///
    /// # Errors
    /// [`DriveError::Value`] naming the first bad key.
    pub fn validate(&self) -> Result<(), DriveError> {
        let m = &self.mechanics;
        let l = &self.limits;
        let positive = "a number above 0";
        let non_negative = "a number of at least 0";
        let checks: [(&'static str, f64, bool); 9] = [
            ("units_per_motor_rev", m.units_per_motor_rev, true),
            ("gear_ratio", m.gear_ratio, true),
            ("load_inertia", m.load_inertia, false),
            ("motor_inertia", m.motor_inertia, false),
            ("friction_torque", m.friction_torque, false),
            ("max_speed", l.max_speed, true),
            ("peak_torque", l.peak_torque, true),
            ("rms_torque", l.rms_torque, true),
            ("max_jerk", l.max_jerk.unwrap_or(1.0), true),
        ];
        for (key, value, strictly) in checks {
            let ok = value.is_finite() && if strictly { value > 0.0 } else { value >= 0.0 };
            if !ok {
                let must = if strictly { positive } else { non_negative };
                return Err(DriveError::Value { key, must });
            }
        }
        if !m.load_torque.is_finite() {
            return Err(DriveError::Value {
                key: "load_torque",
                must: "a finite number",
            });
        }
        if m.load_inertia + m.motor_inertia <= 0.0 {
            return Err(DriveError::Value {
                key: "motor_inertia",
                must: "above 0 (or the load inertia): nothing would resist acceleration",
            });
        }
        Ok(())
    }

    /// Inertia at the motor, `J_m + J_L/i²`, kg·m².
    pub fn inertia_at_motor(&self) -> f64 {
        let m = &self.mechanics;
        m.motor_inertia + m.load_inertia / (m.gear_ratio * m.gear_ratio)
    }
}
