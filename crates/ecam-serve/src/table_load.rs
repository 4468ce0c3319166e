//! `POST /api/table/load`: a whole point table written into a DECAM block
//! as one journalled write (its register image, as `ecam plc run --load`
//! writes it), so a table is never seen half-written.
//!
//! Body: `{"block": 2000, "points": [[0, 0], [100, 50], ...],
//! "while_running": "refuse" | "at-seam"}`. While the block's cam runs the
//! load is refused (409) unless `"at-seam"` asks for the running cam to
//! take the new table at its next seam (docs/plc.md, "Changing the table
//! while the cam runs").

use ecam_core::PointTable;
use ecam_plc::{Device, Devices};
use serde_json::Value;

use crate::WriteBatch;

/// What to do when the block's cam is running.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WhileRunning {
    /// Refuse the load (the default).
    Refuse,
    /// Write it; the running cam takes it at its next seam.
    AtSeam,
}

/// A checked table load: the block, how many points, the writes.
#[derive(Clone, Debug)]
pub struct TableLoad {
    /// First register of the DECAM block.
    pub block: u16,
    /// Points in the table.
    pub points: usize,
    /// What to do if the block's cam runs.
    pub while_running: WhileRunning,
    /// The register image, as one batch.
    pub batch: WriteBatch,
}

/// Parses and checks a load request; nothing is written.
///
/// # Errors
/// A message naming what is wrong: not JSON, no `block` D register, no
/// `points`, a table the core refuses, or the DECAM checks (6782, 6783).
pub fn parse_table_load(body: &[u8]) -> Result<TableLoad, String> {
    let value = crate::device_json::parse_json_body(body)?;
    let block =
        match value.get("block") {
            Some(Value::Number(n)) => n
                .as_u64()
                .and_then(|n| u16::try_from(n).ok())
                .filter(|&n| Device::D(n).check().is_ok())
                .ok_or_else(|| format!("\"block\" {n} is not a D register number (0-8511)"))?,
            Some(Value::String(s)) => match Device::parse(s.trim()) {
                Ok(Device::D(n)) => n,
                _ => {
                    return Err(format!(
                        "\"block\" `{s}` is not a D register, e.g. \"D2000\""
                    ));
                }
            },
            _ => return Err(
                "the body needs \"block\", e.g. {\"block\": 2000, \"points\": [[0, 0], [100, 50]]}"
                    .into(),
            ),
        };
    let pairs = value
        .get("points")
        .and_then(Value::as_array)
        .ok_or("the body needs \"points\": [[master, slave], ...]")?
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let pair = p.as_array().filter(|a| a.len() == 2);
            let whole = |v: Option<&Value>| v.and_then(Value::as_i64);
            match pair {
                Some(a) => match (whole(a.first()), whole(a.get(1))) {
                    (Some(m), Some(s)) => Ok((m, s)),
                    _ => Err(format!("point {i}: master and slave must be whole numbers")),
                },
                None => Err(format!("point {i}: expected [master, slave]")),
            }
        })
        .collect::<Result<Vec<_>, _>>()?;
    let while_running = match value.get("while_running").and_then(Value::as_str) {
        None | Some("refuse") => WhileRunning::Refuse,
        Some("at-seam") => WhileRunning::AtSeam,
        Some(other) => {
            return Err(format!(
                "\"while_running\" `{other}`: expected \"refuse\" or \"at-seam\""
            ));
        }
    };
    let table = PointTable::from_pairs(&pairs).map_err(|e| e.to_string())?;
    // The DECAM face's one writer of the image checks and lays it out; its
    // words go into one batch.
    let mut scratch = Devices::new();
    let points =
        ecam_plc::decam::load_table(&mut scratch, block, &table).map_err(|e| e.to_string())?;
    let mut batch = WriteBatch::new();
    let first = block.saturating_add(ecam_plc::decam::offsets::SECTIONS);
    let words = 2 + usize::from(ecam_plc::decam::offsets::WORDS_PER_SECTION) * points;
    for i in 0..words {
        let n = first.saturating_add(i as u16);
        batch.word(n, scratch.word(n).unwrap_or(0) as u16);
    }
    Ok(TableLoad {
        block,
        points,
        while_running,
        batch,
    })
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn a_table_becomes_one_batch_of_its_image() {
        let load =
            parse_table_load(br#"{"block": 2000, "points": [[0, 0], [100000, -5]]}"#).unwrap();
        assert_eq!((load.block, load.points), (2000, 2));
        assert_eq!(load.while_running, WhileRunning::Refuse);
        let mut dev = Devices::new();
        load.batch.apply(&mut dev);
        assert_eq!(dev.word(2038), Ok(2));
        assert_eq!(dev.word(2039), Ok(40));
        assert_eq!(dev.dword(2044), Ok(100_000));
        assert_eq!(dev.dword(2046), Ok(-5));
    }

    #[test]
    fn bad_loads_say_what_is_wrong() {
        for (body, needle) in [
            (&br#"{"points": [[0,0],[1,1]]}"#[..], "block"),
            (br#"{"block": "M0", "points": [[0,0],[1,1]]}"#, "D register"),
            (br#"{"block": 2000}"#, "points"),
            (br#"{"block": 2000, "points": [[0,0]]}"#, "6783"),
            (br#"{"block": 2000, "points": [[5,0],[1,1]]}"#, "6782"),
            (br#"{"block": 8400, "points": [[0,0],[1,1],[2,2],[3,3],[4,4],[5,5],[6,6],[7,7],[8,8],[9,9],[10,10],[11,11],[12,12],[13,13],[14,14],[15,15],[16,16],[17,17],[18,18],[19,19],[20,20],[21,21],[22,22],[23,23],[24,24],[25,25],[26,26],[27,27],[28,28]]}"#, "D8512"),
            (br#"{"block": 2000, "points": [[0,0],[1,"a"]]}"#, "whole numbers"),
            (br#"{"block": 2000, "points": [[0,0],[1,1]], "while_running": "now"}"#, "at-seam"),
        ] {
            let err = parse_table_load(body).unwrap_err();
            assert!(err.contains(needle), "{}: {err}", String::from_utf8_lossy(body));
        }
    }
}
