//! The drive check itself (formulas in the module documentation).

use alloc::vec::Vec;
use core::f64::consts::PI;
use core::fmt;

use super::motion::Motion;
use super::spec::{Drive, DriveError};

/// One of the drive's limits.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Limit {
    /// The motor's highest speed.
    Speed,
    /// The peak torque.
    PeakTorque,
    /// The continuous (RMS) torque.
    RmsTorque,
    /// The slave's highest jerk.
    Jerk,
}

impl Limit {
    /// How messages name it.
    pub const fn name(self) -> &'static str {
        match self {
            Self::Speed => "motor speed",
            Self::PeakTorque => "peak torque",
            Self::RmsTorque => "RMS torque",
            Self::Jerk => "jerk",
        }
    }
}

/// The highest master speed one limit allows.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct LimitSpeed {
    /// The limit.
    pub limit: Limit,
    /// Highest master speed, counts/s (`INFINITY`: this limit never binds;
    /// 0: no speed is safe, e.g. an impulse of torque where the cam's
    /// velocity steps).
    pub max_master_hz: f64,
    /// The same in machine cycles per minute.
    pub max_cycles_per_min: f64,
    /// Why it is 0, when it is.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reason: Option<&'static str>,
    /// Where (master) the reason is, when it is a point.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_master: Option<f64>,
}

/// What the motor does at one master speed.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct AtSpeed {
    /// Master speed, counts/s.
    pub master_hz: f64,
    /// Machine cycles per minute at that speed.
    pub cycles_per_min: f64,
    /// Peak motor speed, rpm.
    pub motor_speed_rpm: f64,
    /// Peak |motor torque|, N·m (`INFINITY` where the velocity steps).
    pub peak_torque: f64,
    /// Master position of the peak torque.
    pub peak_torque_at: f64,
    /// RMS motor torque over the cycle, N·m.
    pub rms_torque: f64,
    /// Peak |slave jerk|, pulses/s³ (`INFINITY` where the acceleration steps).
    pub peak_jerk: f64,
    /// Share of each limit used (1 = at the limit), in [`Limit`] order;
    /// jerk is `None` without a jerk limit.
    pub speed_use: f64,
    /// Peak torque / its limit.
    pub peak_torque_use: f64,
    /// RMS torque / its limit.
    pub rms_torque_use: f64,
    /// Peak jerk / its limit, when there is one.
    pub jerk_use: Option<f64>,
    /// True if every figure is within its limit.
    pub within_limits: bool,
}

/// The drive check's answer.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct DriveReport {
    /// Inertia at the motor, kg·m².
    pub inertia_at_motor: f64,
    /// Master counts per machine cycle (the cam's span).
    pub cycle_counts: f64,
    /// The figures at the master speed asked for.
    pub at_speed: Option<AtSpeed>,
    /// Every limit's highest master speed.
    pub limits: Vec<LimitSpeed>,
    /// The limit that binds first.
    pub binding: Limit,
    /// The highest master speed the cam allows, counts/s.
    pub max_master_hz: f64,
    /// The same in machine cycles per minute.
    pub max_cycles_per_min: f64,
}

/// Per-sample torque coefficients: `T = A·f² + B` N·m at master speed `f`.
struct Torque {
    master: f64,
    a: f64,
    b: f64,
}

/// Checks `motion` against `drive`, with the figures at `master_hz` when given.
///
/// # Errors
/// A drive that fails [`Drive::validate`]; a motion without span; a
/// master speed that is not a positive finite number.
pub fn check(
    motion: &Motion,
    drive: &Drive,
    master_hz: Option<f64>,
) -> Result<DriveReport, DriveError> {
    drive.validate()?;
    let span = motion.span();
    if !(span > 0.0 && span.is_finite()) {
        return Err(DriveError::NoMotion);
    }
    if let Some(f) = master_hz
        && !(f.is_finite() && f > 0.0)
    {
        return Err(DriveError::Value {
            key: "master speed",
            must: "a number above 0",
        });
    }
    let m = &drive.mechanics;
    let l = &drive.limits;
    let inertia = drive.inertia_at_motor();
    let per_pulse = 2.0 * PI / m.units_per_motor_rev; // rad of motor per slave pulse
    let peak_v = peak(motion, |k| k.v);
    let peak_j = peak(motion, |k| k.j);
    let moving = |v: f64| v.abs() > 1e-12 * peak_v;
    let torques: Vec<Torque> = motion
        .samples
        .iter()
        .map(|(master, k)| {
            let friction = if moving(k.v) {
                m.friction_torque * k.v.signum()
            } else {
                0.0
            };
            Torque {
                master: *master,
                a: inertia * per_pulse * k.a,
                b: (friction + m.load_torque) / m.gear_ratio,
            }
        })
        .collect();
    // Means over the cycle (trapezoids in master = in time at constant speed).
    let mean = |f: &dyn Fn(&Torque) -> f64| {
        let sum: f64 = torques
            .windows(2)
            .map(|w| (w[1].master - w[0].master) * 0.5 * (f(&w[0]) + f(&w[1])))
            .sum();
        sum / span
    };
    let (aa, ab, bb) = (
        mean(&|t| t.a * t.a),
        mean(&|t| t.a * t.b),
        mean(&|t| t.b * t.b),
    );
    let cycles = |f: f64| f * 60.0 / span;
    let step = motion.velocity_steps.first().copied();
    let jerk_step = motion.acceleration_steps.first().copied();

    let mut limits = Vec::new();
    let mut push = |limit, hz: f64, reason: Option<&'static str>, at_master: Option<f64>| {
        limits.push(LimitSpeed {
            limit,
            max_master_hz: hz,
            max_cycles_per_min: cycles(hz),
            reason,
            at_master,
        });
    };
    // Speed: 60·max|v|·f/U ≤ n_max.
    let speed_hz = if peak_v > 0.0 {
        l.max_speed * m.units_per_motor_rev / (60.0 * peak_v)
    } else {
        f64::INFINITY
    };
    push(Limit::Speed, speed_hz, None, None);
    // Peak torque: |A f² + B| ≤ T_peak at every sample.
    let static_over = torques.iter().find(|t| t.b.abs() > l.peak_torque);
    let (peak_hz, reason, at) = if let Some(at) = step {
        (
            0.0,
            Some("the cam's velocity steps here: an impulse of torque"),
            Some(at),
        )
    } else if let Some(t) = static_over {
        (
            0.0,
            Some("friction and load torque alone exceed the peak torque"),
            Some(t.master),
        )
    } else {
        let x = torques
            .iter()
            .map(|t| {
                if t.a > 0.0 {
                    (l.peak_torque - t.b) / t.a
                } else if t.a < 0.0 {
                    (l.peak_torque + t.b) / -t.a
                } else {
                    f64::INFINITY
                }
            })
            .fold(f64::INFINITY, f64::min);
        (libm::sqrt(x.max(0.0)), None, None)
    };
    push(Limit::PeakTorque, peak_hz, reason, at);
    // RMS torque: aa·x² + 2ab·x + bb ≤ T_rms², x = f².
    let limit2 = l.rms_torque * l.rms_torque;
    let (rms_hz, reason, at) = if let Some(at) = step {
        (
            0.0,
            Some("the cam's velocity steps here: an impulse of torque"),
            Some(at),
        )
    } else if bb > limit2 {
        (
            0.0,
            Some("friction and load torque alone exceed the RMS torque"),
            None,
        )
    } else if aa > 0.0 {
        let disc = (ab * ab - aa * (bb - limit2)).max(0.0);
        (
            libm::sqrt(((-ab + libm::sqrt(disc)) / aa).max(0.0)),
            None,
            None,
        )
    } else {
        (f64::INFINITY, None, None)
    };
    push(Limit::RmsTorque, rms_hz, reason, at);
    // Jerk: max|j|·f³ ≤ jerk_max.
    if let Some(max_jerk) = l.max_jerk {
        let (hz, reason, at) = if let Some(at) = jerk_step.or(step) {
            (
                0.0,
                Some("the cam's acceleration steps here: an impulse of jerk"),
                Some(at),
            )
        } else if peak_j > 0.0 {
            (libm::cbrt(max_jerk / peak_j), None, None)
        } else {
            (f64::INFINITY, None, None)
        };
        push(Limit::Jerk, hz, reason, at);
    }
    let first = limits
        .iter()
        .min_by(|a, b| a.max_master_hz.total_cmp(&b.max_master_hz))
        .copied();
    let (binding, max_hz) = first.map_or((Limit::Speed, f64::INFINITY), |f| {
        (f.limit, f.max_master_hz)
    });

    let at_speed = master_hz.map(|f| {
        let x = f * f;
        let (peak_torque, peak_torque_at) = if let Some(at) = step {
            (f64::INFINITY, at)
        } else {
            torques
                .iter()
                .map(|t| ((t.a * x + t.b).abs(), t.master))
                .fold((0.0, 0.0), |best, c| if c.0 > best.0 { c } else { best })
        };
        let rms_torque = if step.is_some() {
            f64::INFINITY
        } else {
            libm::sqrt((aa * x * x + 2.0 * ab * x + bb).max(0.0))
        };
        let peak_jerk = if jerk_step.or(step).is_some() {
            f64::INFINITY
        } else {
            peak_j * f * x
        };
        let motor_speed_rpm = 60.0 * peak_v * f / m.units_per_motor_rev;
        let speed_use = motor_speed_rpm / l.max_speed;
        let peak_torque_use = peak_torque / l.peak_torque;
        let rms_torque_use = rms_torque / l.rms_torque;
        let jerk_use = l.max_jerk.map(|j| peak_jerk / j);
        let within_limits = speed_use <= 1.0
            && peak_torque_use <= 1.0
            && rms_torque_use <= 1.0
            && jerk_use.is_none_or(|u| u <= 1.0);
        AtSpeed {
            master_hz: f,
            cycles_per_min: cycles(f),
            motor_speed_rpm,
            peak_torque,
            peak_torque_at,
            rms_torque,
            peak_jerk,
            speed_use,
            peak_torque_use,
            rms_torque_use,
            jerk_use,
            within_limits,
        }
    });
    Ok(DriveReport {
        inertia_at_motor: inertia,
        cycle_counts: span,
        at_speed,
        limits,
        binding,
        max_master_hz: max_hz,
        max_cycles_per_min: cycles(max_hz),
    })
}

fn peak(motion: &Motion, f: fn(&crate::Kinematics) -> f64) -> f64 {
    motion
        .samples
        .iter()
        .map(|(_, k)| f(k).abs())
        .filter(|x| x.is_finite())
        .fold(0.0, f64::max)
}

/// A number with four significant digits, for the report's text.
struct Sig(f64);

impl fmt::Display for Sig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        if x.is_infinite() {
            return f.write_str(if x > 0.0 { "∞" } else { "−∞" });
        }
        if x == 0.0 || !x.is_finite() {
            return f.write_str("0");
        }
        let digits = 3 - libm::floor(libm::log10(x.abs())) as i32;
        let text = alloc::format!("{:.*}", digits.clamp(0, 9) as usize, x);
        let text = if text.contains('.') {
            text.trim_end_matches('0').trim_end_matches('.').into()
        } else {
            text
        };
        f.write_str(&text)
    }
}

fn percent(share: f64) -> alloc::string::String {
    if share.is_finite() {
        alloc::format!("{:.0} %", share * 100.0)
    } else {
        "∞".into()
    }
}

impl fmt::Display for DriveReport {
    /// The lines `ecam table show --drive` prints.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "drive inertia:     {} kg·m² at the motor",
            Sig(self.inertia_at_motor)
        )?;
        if let Some(s) = &self.at_speed {
            writeln!(
                f,
                "at master speed:   {} counts/s = {} cycles/min{}",
                Sig(s.master_hz),
                Sig(s.cycles_per_min),
                if s.within_limits {
                    " (within the limits)"
                } else {
                    " (OVER A LIMIT)"
                }
            )?;
            writeln!(
                f,
                "  motor speed:     {} rpm peak ({} of the limit)",
                Sig(s.motor_speed_rpm),
                percent(s.speed_use)
            )?;
            writeln!(
                f,
                "  motor torque:    {} N·m peak at master {} ({} of the limit), {} N·m RMS ({} of the limit)",
                Sig(s.peak_torque),
                Sig(s.peak_torque_at),
                percent(s.peak_torque_use),
                Sig(s.rms_torque),
                percent(s.rms_torque_use)
            )?;
            match s.jerk_use {
                Some(u) => writeln!(
                    f,
                    "  slave jerk:      {} pulses/s³ peak ({} of the limit)",
                    Sig(s.peak_jerk),
                    percent(u)
                )?,
                None => writeln!(f, "  slave jerk:      {} pulses/s³ peak", Sig(s.peak_jerk))?,
            }
        }
        for l in &self.limits {
            let why = match (l.reason, l.at_master) {
                (Some(r), Some(m)) => alloc::format!(" ({r}: master {})", Sig(m)),
                (Some(r), None) => alloc::format!(" ({r})"),
                _ => alloc::string::String::new(),
            };
            writeln!(
                f,
                "  {:<16} allows {} counts/s = {} cycles/min{why}",
                alloc::format!("{}:", l.limit.name()),
                Sig(l.max_master_hz),
                Sig(l.max_cycles_per_min),
            )?;
        }
        write!(
            f,
            "fastest:           {} counts/s = {} cycles/min ({} binds first)",
            Sig(self.max_master_hz),
            Sig(self.max_cycles_per_min),
            self.binding.name()
        )
    }
}
