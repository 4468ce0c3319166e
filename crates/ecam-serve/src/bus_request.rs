//! What a client asks of the drive line over HTTP (`POST
//! /api/ethercat/COMMAND` and its JSON body), read into a [`BusCommand`]
//! here, sans-IO, so that the listener only passes the route's word, the
//! body and the line's transport.

use core::fmt;

use ecam_core::excerpt::excerpt;
use serde_json::Value;

use crate::bus::BusCommand;

/// The error code of an injected fault when the body gives none (0x7500,
/// a communication error, what a drive reports when its bus goes quiet).
pub const DEFAULT_FAULT_CODE: u16 = 0x7500;

/// A command the line does not take; nothing was queued.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum BusRequestError {
    /// No command of this name.
    UnknownCommand(String),
    /// `fault` on drives that are not emulated.
    NotEmulated,
    /// `fault` without a drive number, or with a code past 16 bits.
    FaultBody,
}

impl BusRequestError {
    /// The HTTP status: 404 for an unknown command, 409 for a fault on
    /// real drives, 400 for a fault body that does not read.
    pub fn http_status(&self) -> u16 {
        match self {
            Self::UnknownCommand(_) => 404,
            Self::NotEmulated => 409,
            Self::FaultBody => 400,
        }
    }
}

impl fmt::Display for BusRequestError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::UnknownCommand(name) => write!(
                f,
                "no command `{}`: enable, disable, reset or fault",
                excerpt(name)
            ),
            Self::NotEmulated => {
                f.write_str("faults can only be injected into emulated drives (--emulated N)")
            }
            Self::FaultBody => {
                f.write_str("give {\"drive\": N} and optionally {\"code\": 0..65535}")
            }
        }
    }
}

impl std::error::Error for BusRequestError {}

/// The command `name` (`enable`, `disable`, `reset`, `fault`) with its
/// `body` (`{"drive": N, "code": C}` for a fault), for a line whose
/// snapshot names `transport` (faults go only to emulated drives).
///
/// # Errors
/// An unknown name, a fault on real drives, or a fault body that does
/// not read.
pub fn parse_bus_command(
    name: &str,
    body: &Value,
    transport: &str,
) -> Result<BusCommand, BusRequestError> {
    match name {
        "enable" => Ok(BusCommand::Enable),
        "disable" => Ok(BusCommand::Disable),
        "reset" => Ok(BusCommand::Reset),
        "fault" if !transport.starts_with("emulated") => Err(BusRequestError::NotEmulated),
        "fault" => {
            let drive = body
                .get("drive")
                .and_then(Value::as_u64)
                .and_then(|d| usize::try_from(d).ok());
            let code = match body.get("code") {
                None => Some(DEFAULT_FAULT_CODE),
                Some(code) => code.as_u64().and_then(|c| u16::try_from(c).ok()),
            };
            match (drive, code) {
                (Some(drive), Some(code)) => Ok(BusCommand::EmulateFault { drive, code }),
                _ => Err(BusRequestError::FaultBody),
            }
        }
        other => Err(BusRequestError::UnknownCommand(other.to_string())),
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn commands_and_faults_read() {
        let none = json!({});
        assert_eq!(
            parse_bus_command("enable", &none, "raw eth0"),
            Ok(BusCommand::Enable)
        );
        assert_eq!(
            parse_bus_command("reset", &none, "emulated"),
            Ok(BusCommand::Reset)
        );
        assert_eq!(
            parse_bus_command("fault", &json!({"drive": 1}), "emulated (2 drives)"),
            Ok(BusCommand::EmulateFault {
                drive: 1,
                code: DEFAULT_FAULT_CODE
            })
        );
        assert_eq!(
            parse_bus_command("fault", &json!({"drive": 0, "code": 29456}), "emulated"),
            Ok(BusCommand::EmulateFault {
                drive: 0,
                code: 29456
            })
        );
    }

    #[test]
    fn refusals_say_why_with_their_status() {
        let e = parse_bus_command("fault", &json!({"drive": 1}), "raw eth0").unwrap_err();
        assert_eq!((e.http_status(), e), (409, BusRequestError::NotEmulated));
        for body in [
            json!({}),
            json!({"drive": 1, "code": 70000}),
            json!({"drive": -1}),
        ] {
            let e = parse_bus_command("fault", &body, "emulated").unwrap_err();
            assert_eq!(e.http_status(), 400, "{body}");
        }
        let long = "x".repeat(10_000);
        let e = parse_bus_command(&long, &json!({}), "emulated").unwrap_err();
        assert_eq!(e.http_status(), 404);
        assert!(e.to_string().len() < 120, "{e}");
    }
}
