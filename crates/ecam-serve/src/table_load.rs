//! `POST /api/table/load`: a whole point table written into a DECAM block
//! as one journalled write (its register image, as `ecam plc run --load`
//! writes it), so a table is never seen half-written.
//!
//! Body: `{"block": 2000, "points": [[0, 0], [100, 50], ...],
//! "while_running": "refuse" | "at-seam"}`. While the block's cam runs the
//! load is refused (409) unless `"at-seam"` asks for the running cam to
//! take the new table at its next seam (docs/plc.md, "Changing the table
//! while the cam runs"). A table goes only into a block the program's
//! DECAM names or into one clear of them all, never into D8000–D8511
//! ([`ecam_plc::Plc::check_table_load`]; docs/modbus.md, "Writes into cam
//! blocks").

use core::fmt;

use ecam_core::PointTable;
use ecam_plc::decam::offsets;
use ecam_plc::{Device, Devices};
use serde_json::Value;

use crate::WriteBatch;
use crate::state::{Shared, WriteError};

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
    // The image: offset 38 up to the block's end with this table (2..=512
    // points, checked above, so the count fits).
    let end = u32::from(block) + offsets::block_words(points as u16);
    for n in u32::from(block) + u32::from(offsets::SECTIONS)..end {
        let n = n as u16; // below D8512: the load checked it fits
        batch.word(n, scratch.word(n).unwrap_or(0) as u16);
    }
    Ok(TableLoad {
        block,
        points,
        while_running,
        batch,
    })
}

/// How a loaded table takes over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableSwitch {
    /// No cam runs at the block: the table is in place for the next start.
    Now,
    /// The block's cam runs: it takes the table at its next seam.
    AtSeam,
}

impl TableSwitch {
    /// The answer's `"switch"` value.
    pub fn name(self) -> &'static str {
        match self {
            Self::Now => "now",
            Self::AtSeam => "at-seam",
        }
    }
}

/// Why a checked table load was not written; nothing changed.
#[derive(Debug)]
pub enum TableLoadError {
    /// The block's cam runs and the request did not ask for `"at-seam"`.
    Running {
        /// The block.
        block: u16,
    },
    /// The target or the write was refused, or could not be made durable.
    Write(WriteError),
}

impl TableLoadError {
    /// The HTTP status: 409 while the cam runs, else as [`WriteError`].
    pub fn http_status(&self) -> u16 {
        match self {
            Self::Running { .. } => 409,
            Self::Write(err) => err.http_status(),
        }
    }

    /// The PLC error code behind the refusal, if any.
    pub fn code(&self) -> Option<u16> {
        match self {
            Self::Running { .. } => None,
            Self::Write(err) => err.code(),
        }
    }
}

impl fmt::Display for TableLoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Running { block } => write!(
                f,
                "the cam of the block at D{block} is running: send \"while_running\": \"at-seam\" to switch tables at its next seam"
            ),
            Self::Write(err) => write!(f, "{err}"),
        }
    }
}

impl std::error::Error for TableLoadError {}

impl Shared {
    /// Writes a checked table load as one durable write, if the program
    /// allows it: the block must be one the program names or clear of them
    /// (and below D8000), and a running cam takes a table only when
    /// `"at-seam"` was asked. Blocks the calling thread for the journal's
    /// sync to disk.
    ///
    /// # Errors
    /// [`TableLoadError`]; nothing was written.
    pub fn load_table(&self, load: &TableLoad) -> Result<TableSwitch, TableLoadError> {
        // 2..=512 points: parse_table_load checked.
        let points = u16::try_from(load.points).unwrap_or(u16::MAX);
        let running = self.image(|plc| {
            plc.check_table_load(load.block, points)
                .map(|()| plc.cam_running(load.block))
        });
        let running = running.map_err(|e| TableLoadError::Write(e.into()))?;
        if running && load.while_running == WhileRunning::Refuse {
            return Err(TableLoadError::Running { block: load.block });
        }
        self.write(&load.batch).map_err(TableLoadError::Write)?;
        Ok(if running {
            TableSwitch::AtSeam
        } else {
            TableSwitch::Now
        })
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;
    use crate::pdu::{Exception, Request};
    use crate::state::ServeInfo;

    /// A server whose program runs a cyclic cam from the block at D2000
    /// (a 2-point table, D2000..D2047) on a K1 time base.
    fn running_cam() -> Shared {
        let program =
            ecam_plc::Program::parse("LD M8000\nMOV K1 D2005\nDECAM K1 D2000 X0 Y0 Y4\n", "t.il")
                .unwrap();
        let mut plc = ecam_plc::Plc::new(program).unwrap();
        let table = PointTable::from_pairs(&[(0, 0), (1000, 100)]).unwrap();
        ecam_plc::decam::load_table(plc.devices_mut(), 2000, &table).unwrap();
        plc.scan();
        plc.hardware_tick(100);
        assert!(plc.cam_running(2000));
        let addr = "127.0.0.1:0".parse().unwrap();
        let info = ServeInfo {
            program: None,
            timing: ecam_plc::sim::Timing::default(),
            modbus: addr,
            http: addr,
            state_dir: None,
            limits: Default::default(),
        };
        Shared::new(plc, None, info, |_| {})
    }

    fn load(block: u16, at_seam: bool) -> TableLoad {
        let body = format!(
            r#"{{"block": {block}, "points": [[0, 0], [500, 100]], "while_running": "{}"}}"#,
            if at_seam { "at-seam" } else { "refuse" }
        );
        parse_table_load(body.as_bytes()).unwrap()
    }

    #[test]
    fn table_loads_go_to_the_programs_blocks_or_clear_of_them() {
        let shared = running_cam();
        let words = |s: &Shared| s.read(|d| (2038..2048).map(|n| d.word(n)).collect::<Vec<_>>());
        let before = words(&shared);
        let err = shared.load_table(&load(2000, false)).unwrap_err();
        assert_eq!(err.http_status(), 409);
        let err = shared.load_table(&load(2001, true)).unwrap_err();
        assert_eq!((err.http_status(), err.code()), (409, None));
        assert!(err.to_string().contains("D2000"), "{err}");
        let err = shared.load_table(&load(8000, true)).unwrap_err();
        assert_eq!(err.http_status(), 400);
        assert_eq!(words(&shared), before, "nothing written");
        assert_eq!(
            shared.load_table(&load(2000, true)).unwrap(),
            TableSwitch::AtSeam
        );
        assert_eq!(
            shared.load_table(&load(2048, false)).unwrap(),
            TableSwitch::Now
        );
    }

    #[test]
    fn a_modbus_write_that_breaks_the_running_table_is_exception_03() {
        let shared = running_cam();
        // Point 1's master (D2044) to 0: not above point 0's.
        let request = Request::WriteMultipleRegisters {
            address: 2044,
            values: vec![0, 0],
        };
        assert_eq!(
            crate::answer_request(&shared, &request),
            Err(Exception::IllegalDataValue)
        );
        assert_eq!(shared.read(|d| d.dword(2044)), Ok(1000));
        let mut batch = WriteBatch::new();
        batch.word(2044, 0);
        let err = shared.write(&batch).unwrap_err();
        assert_eq!((err.http_status(), err.code()), (409, Some(6782)));
    }

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
