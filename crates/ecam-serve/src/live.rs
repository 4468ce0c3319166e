//! What the designer page's live view shows of one running cam: samples of
//! a DECAM register block (docs/plc.md, "Register block") taken from the
//! shared PLC, with the speeds between two samples. The binary streams them
//! over a WebSocket (`GET /api/live`); this module decides what a sample
//! holds and how often one may be asked for.

use ecam_plc::decam::{flags, offsets};
use ecam_plc::{D_COUNT, Device};

use crate::image::Image;
use serde_json::{Value, json};

/// Samples per second when the client names none.
pub const DEFAULT_LIVE_RATE: u32 = 20;
/// Most samples per second a client may ask for: more than a screen shows,
/// and each sample locks the PLC for a moment.
pub const MAX_LIVE_RATE: u32 = 50;

/// Words of a DECAM block the live view reads (offsets 0–39 and the
/// first point; the last point is read when it lies within D8511).
const BLOCK_WORDS: u32 = offsets::block_words(1);

/// What `GET /api/live` was asked to stream.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LiveRequest {
    /// First register of the DECAM block (`D2000` → 2000).
    pub block: u16,
    /// Samples per second, 1..=[`MAX_LIVE_RATE`].
    pub rate: u32,
}

impl LiveRequest {
    /// Reads `block` (required; a number, `D2000` also accepted) and
    /// `rate` (optional) from a query string's values.
    ///
    /// # Errors
    /// A missing or bad block, a block whose registers run past D8511, a
    /// rate outside 1..=[`MAX_LIVE_RATE`].
    pub fn parse(block: Option<&str>, rate: Option<&str>) -> Result<Self, String> {
        let text = block.ok_or("name the cam's register block: /api/live?block=2000")?;
        let digits = text.trim().trim_start_matches(['D', 'd']);
        let block: u16 = digits.parse().map_err(|_| {
            format!(
                "block must be a D register number, not `{text}`",
                text = ecam_core::excerpt::excerpt(text)
            )
        })?;
        if u32::from(block) + BLOCK_WORDS > u32::from(D_COUNT) {
            return Err(format!(
                "block D{block} runs past D{}: a DECAM block needs 40 words and its table",
                D_COUNT - 1
            ));
        }
        let rate = match rate {
            None => DEFAULT_LIVE_RATE,
            Some(text) => text
                .trim()
                .parse::<u32>()
                .ok()
                .filter(|r| (1..=MAX_LIVE_RATE).contains(r))
                .ok_or_else(|| {
                    format!(
                        "rate must be 1..={MAX_LIVE_RATE} samples per second, not `{text}`",
                        text = ecam_core::excerpt::excerpt(text)
                    )
                })?,
        };
        Ok(Self { block, rate })
    }
}

/// One look at a cam's block.
#[derive(Clone, Debug, PartialEq)]
pub struct LiveSample {
    /// PLC (simulated) time, µs.
    pub time_us: u64,
    /// Scans run so far.
    pub scans: u64,
    /// True while the cam is armed or follows (as `POST /api/table/load` sees it).
    pub running: bool,
    /// The flag register (offset 1).
    pub flags: u16,
    /// The error register (offset 2).
    pub error: u16,
    /// Master position in the cycle before zoom, in master counts (offsets 27/28).
    pub master: i32,
    /// Master position in the cycle, after zoom (offsets 25/26): the table input.
    pub master_in_cycle: i32,
    /// The cycle length in the units of [`Self::master_in_cycle`]: the
    /// master span (last point's master − first's) of the table the cam
    /// follows while it runs (a table written into the block meanwhile
    /// waits for the next seam, and so does its span here); otherwise that
    /// of the block's table words, 0 when the point count (offset 38) is
    /// out of range.
    pub table_span: i64,
    /// Commanded slave position after zoom (offsets 19/20).
    pub slave: i32,
    /// The sync output's Y index (offset 8) and whether it is driven (offset 4 bit 0).
    pub sync_output: u16,
    /// Offset 4 bit 0.
    pub sync_enabled: bool,
    /// The sync output's state, when the index names a Y.
    pub sync_on: Option<bool>,
}

impl LiveSample {
    /// Reads block `block` of the PLC as clients see it. Registers that
    /// cannot be read (never, for a block [`LiveRequest::parse`] accepted)
    /// read as 0.
    pub fn read(plc: &Image, block: u16) -> Self {
        let d = plc.devices();
        let word = |offset: u16| {
            d.word(block.saturating_add(offset))
                .map_or(0, |w| u16::from_ne_bytes(w.to_ne_bytes()))
        };
        let dword = |offset: u16| d.dword(block.saturating_add(offset)).unwrap_or(0);
        let sync_output = word(offsets::SYNC_OUTPUT);
        let points = word(offsets::SECTIONS);
        let words_span = || {
            if !(2..=offsets::MAX_SECTIONS).contains(&points) {
                return 0;
            }
            // Point `points − 1` is below offset 40 + 4 × 512: fits u16.
            let last = offsets::block_words(points - 1) as u16;
            d.dword(block.saturating_add(last))
                .map_or(0, |last| i64::from(last) - i64::from(dword(offsets::TABLE)))
        };
        let table_span = plc.cam_table_span(block).unwrap_or_else(words_span);
        Self {
            time_us: plc.now_us(),
            scans: plc.scans(),
            running: plc.cam_running(block),
            flags: word(offsets::FLAGS),
            error: word(offsets::ERROR),
            master: dword(offsets::MASTER_RAW),
            master_in_cycle: dword(offsets::MASTER_ZOOMED),
            table_span,
            slave: dword(offsets::SLAVE_ZOOMED),
            sync_output,
            sync_enabled: word(offsets::CONTROL) & flags::CTL_SYNC_ENABLE != 0,
            sync_on: d.bit(Device::Y(sync_output)).ok(),
        }
    }

    /// The sample as the live view's JSON; speeds (counts per second of PLC
    /// time) from `previous`, `null` for the first sample or when no PLC
    /// time passed.
    pub fn to_json(&self, block: u16, previous: Option<&Self>) -> Value {
        let dt = previous
            .map(|p| self.time_us.saturating_sub(p.time_us))
            .filter(|&dt| dt > 0);
        let speed = |now: i32, then: Option<i32>| -> Option<f64> {
            let (then, dt) = (then?, dt?);
            // Positions wrap like D8140: the step between samples is the
            // wrapping difference.
            Some(f64::from(now.wrapping_sub(then)) * 1e6 / dt as f64)
        };
        // The master in the cycle falls back by one span at each seam: the
        // master's own travel is the step unwrapped by that span (a sample
        // period shorter than half a cycle is assumed, as for any sampled
        // angle). Forwards the cycle left is the previous sample's, going
        // backwards the one entered is this sample's: at a table switch the
        // two differ, and the other span would make a spike.
        let master_speed = previous.zip(dt).map(|(p, dt)| {
            let mut step = i64::from(self.master_in_cycle) - i64::from(p.master_in_cycle);
            if self.running && p.running {
                if p.table_span > 0 && step < -p.table_span / 2 {
                    step += p.table_span;
                } else if self.table_span > 0 && step > self.table_span / 2 {
                    step -= self.table_span;
                }
            }
            step as f64 * 1e6 / dt as f64
        });
        let mode = if self.flags & flags::CYCLIC != 0 {
            "cyclic"
        } else if self.flags & flags::NONCYCLIC != 0 {
            "noncyclic"
        } else {
            "stopped"
        };
        json!({
            "block": block,
            "time_us": self.time_us,
            "scans": self.scans,
            "running": self.running,
            "mode": mode,
            "flags": self.flags,
            "error": self.error,
            "master": self.master,
            "master_in_cycle": self.master_in_cycle,
            "slave": self.slave,
            "table_span": self.table_span,
            "master_velocity": master_speed,
            "slave_velocity": speed(self.slave, previous.map(|p| p.slave)),
            "in_sync": self.flags & flags::IN_SYNC_AREA != 0,
            "sync_output": {
                "device": format!("Y{:o}", self.sync_output),
                "enabled": self.sync_enabled,
                "on": self.sync_on,
            },
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_checked() {
        assert_eq!(
            LiveRequest::parse(Some("D2000"), None),
            Ok(LiveRequest {
                block: 2000,
                rate: DEFAULT_LIVE_RATE
            })
        );
        assert_eq!(
            LiveRequest::parse(Some("100"), Some("50")).map(|r| r.rate),
            Ok(50)
        );
        assert!(LiveRequest::parse(None, None).is_err());
        assert!(LiveRequest::parse(Some("x"), None).is_err());
        assert!(LiveRequest::parse(Some("8500"), None).is_err());
        assert!(LiveRequest::parse(Some("2000"), Some("0")).is_err());
        assert!(LiveRequest::parse(Some("2000"), Some("51")).is_err());
    }

    fn sample(time_us: u64, slave: i32, flags: u16) -> LiveSample {
        LiveSample {
            time_us,
            scans: 1,
            running: true,
            flags,
            error: 0,
            master: slave,
            master_in_cycle: slave,
            table_span: 0,
            slave,
            sync_output: 8,
            sync_enabled: true,
            sync_on: Some(true),
        }
    }

    #[test]
    fn speeds_come_from_the_previous_sample_and_wrap_like_the_counters() {
        let a = sample(1_000_000, i32::MAX - 9, flags::CYCLIC | flags::IN_SYNC_AREA);
        let b = sample(1_100_000, i32::MIN + 10, flags::CYCLIC);
        let first = a.to_json(2000, None);
        assert!(first["slave_velocity"].is_null());
        assert_eq!(first["mode"], "cyclic");
        assert_eq!(first["in_sync"], true);
        assert_eq!(first["sync_output"]["device"], "Y10");
        let second = b.to_json(2000, Some(&a));
        // 20 counts in 0.1 s across the wrap.
        assert_eq!(second["slave_velocity"], json!(200.0));
        assert_eq!(b.to_json(2000, Some(&b))["slave_velocity"], Value::Null);
    }

    #[test]
    fn the_master_speed_runs_on_across_the_seam() {
        let mut a = sample(1_000_000, 0, flags::CYCLIC);
        a.master_in_cycle = 3900;
        a.table_span = 4000;
        let mut b = a.clone();
        b.time_us = 1_050_000;
        b.master_in_cycle = 100; // 200 counts on, across the seam
        assert_eq!(b.to_json(2000, Some(&a))["master_velocity"], json!(4000.0));
        // Backwards across the seam.
        assert_eq!(a.to_json(2000, Some(&b))["master_velocity"], Value::Null);
        // A switch at the seam to a 2500-count table: forwards the span
        // unwrapped is the one left, backwards the one entered.
        let mut d = b.clone();
        d.table_span = 2500;
        assert_eq!(d.to_json(2000, Some(&a))["master_velocity"], json!(4000.0));
        let mut e = d.clone();
        e.time_us = 1_100_000;
        e.master_in_cycle = 2400;
        assert_eq!(e.to_json(2000, Some(&d))["master_velocity"], json!(-4000.0));
        let mut c = a.clone();
        c.time_us = 1_100_000;
        assert_eq!(c.to_json(2000, Some(&b))["master_velocity"], json!(-4000.0));
    }

    #[test]
    fn a_block_of_an_idle_plc_reads_stopped() {
        let plc = ecam_plc::Plc::new(ecam_plc::Program::parse("", "empty.il").unwrap()).unwrap();
        let s = LiveSample::read(&Image::of(&plc), 2000);
        assert!(!s.running);
        assert_eq!(s.to_json(2000, None)["mode"], "stopped");
    }
}
