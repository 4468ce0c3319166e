//! What a script prints: one JSON object per `Get…` command.

use core::fmt;

use ecam_engine::EngineError;

/// The answer to a `Get…` command; [`Report::to_json`] (and `Display`) give
/// the line `ecam mc run` prints.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Report {
    /// A number read from an axis: `GetCommandPosition` (pulses) or
    /// `GetSingleTurn` (counts per turn, 0 when the axis is not
    /// single-turn).
    Value {
        /// The command, e.g. `GetCommandPosition`.
        cmd: &'static str,
        /// The axis.
        axis: usize,
        /// The value.
        value: i64,
    },
    /// `GetECAMStatus`: whether an E-CAM drives the axis, and why the last
    /// one stopped by itself, if it did.
    ECamStatus {
        /// The slave axis.
        axis: usize,
        /// An E-CAM drives it.
        running: bool,
        /// The engine fault that stopped its last E-CAM, if any.
        fault: Option<EngineError>,
    },
}

impl Report {
    /// The command that printed this.
    pub fn cmd(&self) -> &'static str {
        match self {
            Self::Value { cmd, .. } => cmd,
            Self::ECamStatus { .. } => "GetECAMStatus",
        }
    }

    /// The axis it is about.
    pub fn axis(&self) -> usize {
        match self {
            Self::Value { axis, .. } | Self::ECamStatus { axis, .. } => *axis,
        }
    }

    /// The number read, for [`Report::Value`].
    pub fn value(&self) -> Option<i64> {
        match self {
            Self::Value { value, .. } => Some(*value),
            Self::ECamStatus { .. } => None,
        }
    }

    /// The report as one JSON object, keys in this order:
    /// `{"cmd":"GetCommandPosition","axis":1,"value":1500}` or
    /// `{"cmd":"GetECAMStatus","axis":1,"running":false,"fault":"…"}`
    /// (`"fault":null` when none).
    pub fn to_json(&self) -> String {
        let text = |s: &str| serde_json::Value::from(s).to_string();
        match self {
            Self::Value { cmd, axis, value } => {
                format!(r#"{{"cmd":{},"axis":{axis},"value":{value}}}"#, text(cmd))
            }
            Self::ECamStatus {
                axis,
                running,
                fault,
            } => {
                let fault = fault
                    .as_ref()
                    .map_or_else(|| "null".to_owned(), |f| text(&f.to_string()));
                format!(
                    r#"{{"cmd":"GetECAMStatus","axis":{axis},"running":{running},"fault":{fault}}}"#
                )
            }
        }
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.to_json())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_lines() {
        let r = Report::Value {
            cmd: "GetCommandPosition",
            axis: 1,
            value: -2000,
        };
        assert_eq!(
            r.to_json(),
            r#"{"cmd":"GetCommandPosition","axis":1,"value":-2000}"#
        );
        let s = Report::ECamStatus {
            axis: 1,
            running: true,
            fault: None,
        };
        assert_eq!(
            s.to_string(),
            r#"{"cmd":"GetECAMStatus","axis":1,"running":true,"fault":null}"#
        );
        let f = Report::ECamStatus {
            axis: 1,
            running: false,
            fault: Some(EngineError::MasterStep),
        };
        let json: serde_json::Value = serde_json::from_str(&f.to_json()).unwrap_or_default();
        assert!(json["fault"].as_str().is_some_and(|m| !m.is_empty()), "{f}");
    }
}
