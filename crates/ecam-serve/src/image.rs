//! The PLC as clients see it: device memory as the last scan period left
//! it, with every write made since, and what the status and the live view
//! show. The scan side publishes it at the end of each scan period; the
//! servers only ever read this copy, so no request waits for a scan,
//! however long the program makes it (the FX serves its communication
//! between scans too, at END).
//!
//! A client's write goes into the copy at once (a read right after it sees
//! it) and is queued for the PLC, which takes it at the start of its next
//! scan period, as before: a write is seen by the next scan.

use ecam_plc::{Devices, Plc, WriteRefusal};

use crate::write::WriteBatch;

/// Device memory and run state as of the last scan period, plus the
/// writes made since.
#[derive(Clone, Debug, Default)]
pub struct Image {
    devices: Devices,
    now_us: u64,
    scans: u64,
    running_cams: Vec<u16>,
    /// The blocks the program's DECAMs name.
    cam_blocks: Vec<u16>,
    /// The master span of the table each running cam follows.
    spans: Vec<(u16, i64)>,
    fault: Option<String>,
    /// Writes applied here but not yet in the PLC.
    pending: Vec<WriteBatch>,
}

impl Image {
    /// The image of `plc` as it is now.
    pub fn of(plc: &Plc) -> Self {
        let mut image = Self::default();
        image.publish(plc);
        image
    }

    /// Device memory (the last scan period's, with the writes made since).
    pub fn devices(&self) -> &Devices {
        &self.devices
    }

    /// PLC (simulated) time at the end of the last scan period, µs.
    pub fn now_us(&self) -> u64 {
        self.now_us
    }

    /// Scans run so far.
    pub fn scans(&self) -> u64 {
        self.scans
    }

    /// True while a DECAM whose register block starts at `D{block}` was
    /// armed or following its cam at the end of the last scan period.
    pub fn cam_running(&self, block: u16) -> bool {
        self.running_cams.contains(&block)
    }

    /// The master span of the table the cam at `D{block}` follows, while
    /// it runs (see [`ecam_plc::Plc::cam_table_span`]).
    pub fn cam_table_span(&self, block: u16) -> Option<i64> {
        self.spans
            .iter()
            .find_map(|&(b, span)| (b == block).then_some(span))
    }

    /// Checks that a table of `points` points may be loaded into the block
    /// at `D{block}`, as [`ecam_plc::Plc::check_table_load`] does.
    ///
    /// # Errors
    /// The refusal, naming why.
    pub fn check_table_load(&self, block: u16, points: u16) -> Result<(), WriteRefusal> {
        ecam_plc::check_table_load(
            &self.devices,
            self.cam_blocks.iter().copied(),
            block,
            points,
        )
    }

    /// Checks client writes into data registers against the running cams,
    /// as [`ecam_plc::Plc::check_register_writes`] does.
    ///
    /// # Errors
    /// The refusal, naming the block and its error.
    pub fn check_register_writes(&self, writes: &[(u16, i16)]) -> Result<(), WriteRefusal> {
        ecam_plc::check_register_writes(&self.devices, self.running_cams.iter().copied(), writes)
    }

    /// What stopped the program (the watchdog), if anything did.
    pub fn fault(&self) -> Option<&str> {
        self.fault.as_deref()
    }

    /// A client's write: here at once, in the PLC at its next period.
    pub(crate) fn write(&mut self, batch: WriteBatch) {
        batch.apply(&mut self.devices);
        self.pending.push(batch);
    }

    /// Hands the writes made since the last period to `plc`, in order.
    pub(crate) fn deliver(&mut self, plc: &mut Plc) {
        for batch in self.pending.drain(..) {
            batch.apply(plc.devices_mut());
        }
    }

    /// Takes the end of a scan period from `plc`; writes made while it
    /// ran stay on top (and stay queued for the next period).
    pub(crate) fn publish(&mut self, plc: &Plc) {
        self.devices.clone_from(plc.devices());
        for batch in &self.pending {
            batch.apply(&mut self.devices);
        }
        self.now_us = plc.now_us();
        self.scans = plc.scans();
        self.running_cams.clear();
        self.running_cams.extend(plc.running_cams());
        self.cam_blocks.clear();
        self.cam_blocks.extend(plc.cam_blocks());
        self.spans.clear();
        self.spans.extend(
            self.running_cams
                .iter()
                .filter_map(|&b| plc.cam_table_span(b).map(|span| (b, span))),
        );
        self.fault = plc.fault().map(ToString::to_string);
    }
}
