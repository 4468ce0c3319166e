//! clap value parsers for flags that name devices, wires and definitions:
//! a malformed one is a usage error (exit 2) before anything runs, as
//! clap reports it; only what the run itself meets (a file, the program)
//! fails with exit 1.

use std::path::PathBuf;

use ecam_plc::{Devices, View};

/// `--set DEV=VALUE`: the device and the value, checked to fit it.
pub fn set(text: &str) -> Result<(View, String), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| "expected DEV=VALUE, e.g. D100=3183".to_string())?;
    let view = View::parse(name.trim()).map_err(|e| e.to_string())?;
    // Written once into scratch memory: a value that does not fit is
    // refused here, not after the program has been read.
    view.write(&mut Devices::new(), value)
        .map_err(|e| e.to_string())?;
    Ok((view, value.trim().to_string()))
}

/// `--dump DEV[:COUNT]`: the devices to print, in order.
pub fn dump(text: &str) -> Result<Vec<View>, String> {
    let (name, count) = match text.split_once(':') {
        Some((name, count)) => {
            let count = count
                .parse::<u16>()
                .ok()
                .filter(|&c| c >= 1)
                .ok_or("COUNT must be a whole number from 1 to 65535")?;
            (name, count)
        }
        None => (text, 1),
    };
    let first = View::parse(name.trim()).map_err(|e| e.to_string())?;
    (0..count)
        .map(|k| first.nth(k).map_err(|e| e.to_string()))
        .collect()
}

/// `--trace-dev DEV`.
pub fn device(text: &str) -> Result<View, String> {
    View::parse(text.trim()).map_err(|e| e.to_string())
}

/// `--wire Yn:Xm`.
pub fn wire(text: &str) -> Result<ecam_plc::Wire, String> {
    ecam_plc::Wire::parse(text).map_err(|e| e.to_string())
}

/// `--load Dn=FILE`: the DECAM block's first register and the table file.
pub fn load(text: &str) -> Result<(u16, PathBuf), String> {
    let (block, file) = text
        .split_once('=')
        .ok_or("expected Dn=FILE, e.g. D2000=table.csv")?;
    let block = ecam_plc::decam::block_at(block).map_err(|e| e.to_string())?;
    Ok((block, PathBuf::from(file.trim())))
}

/// `--define NAME=VALUE` of a motion-processor script.
pub fn define(text: &str) -> Result<(String, i64), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or("expected NAME=VALUE, e.g. cam_table_0=120")?;
    let number = ecam_core::script_line::parse_number(value.trim())
        .map_err(|e| format!("`{}`: {e}", value.trim()))?;
    Ok((name.trim().to_string(), number))
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn malformed_values_are_refused_with_the_reason() {
        assert!(set("D100=3183").is_ok());
        assert!(set("D100=99999").unwrap_err().contains("99999"));
        assert!(set("D100").unwrap_err().contains("DEV=VALUE"));
        assert_eq!(dump("D2019:2").unwrap().len(), 2);
        assert!(dump("D2019:0").is_err());
        assert!(wire("Y1-X0").is_err());
        assert_eq!(load("D2000=t.csv").unwrap().0, 2000);
        assert!(load("M10=t.csv").unwrap_err().contains("data register"));
        assert_eq!(define("a=0x10").unwrap(), ("a".into(), 16));
    }
}
