//! The PLC shared by the scan loop and the Modbus and HTTP servers.
//!
//! One lock guards the PLC (program, device memory, hardware): the scan
//! side holds it for a scan period's work. Clients never take it: they
//! read and write the [`Image`] the scan side publishes after each period,
//! behind its own lock held for a copy at most, so a request is answered at
//! once however long the program makes a scan. Writes go through the
//! journal's lock, which is taken first and held until the write is in the
//! image, so the journal's order is the order writes reach device memory.
//!
//! The library prints nothing: what a server operator should hear about
//! (a new operation error, a refused write, a failed save) is handed to the
//! [`Event`] sink the binary gives [`Shared::new`].

use std::collections::HashSet;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};

use ecam_plc::Devices;
use ecam_plc::Plc;
use ecam_plc::WriteRefusal;
use ecam_plc::sim::Timing;
use serde_json::{Value, json};

use crate::connections::Connections;
use crate::design_pool::DesignPool;
use crate::image::Image;
use crate::journal::{Journal, JournalError};
use crate::limits::Limits;
use crate::pdu::{Exception, Response};
use crate::retain::LatchedImage;
pub(crate) use crate::sync::lock;
use crate::write::WriteBatch;

/// How the server was started (for `GET /api/status`).
#[derive(Clone, Debug)]
pub struct ServeInfo {
    /// The program file, if one was loaded.
    pub program: Option<String>,
    /// Scan period and hardware tick.
    pub timing: Timing,
    /// Bound Modbus TCP address.
    pub modbus: SocketAddr,
    /// Bound HTTP address.
    pub http: SocketAddr,
    /// The state directory, if writes are kept.
    pub state_dir: Option<PathBuf>,
    /// Caps and deadlines of the connections.
    pub limits: Limits,
}

/// How the server closes a connection the registry chose to make room
/// (see [`Connections`]): the listener's own way to end that task.
pub type Closer = Arc<dyn Fn() + Send + Sync>;

/// Counters the servers and the scan loop update.
#[derive(Debug, Default)]
pub struct Stats {
    /// Whether the scan loop is running.
    pub scanning: AtomicBool,
    /// How far the PLC's simulated time is behind the wall clock, µs.
    pub lag_us: AtomicU64,
    /// Wall-clock time the scan loop gave up catching up on, µs.
    pub skipped_us: AtomicU64,
    /// Operation errors raised by scans.
    pub operation_errors: AtomicU64,
    /// Modbus connections accepted.
    pub modbus_connections: AtomicU64,
    /// Modbus requests answered (responses and exceptions).
    pub modbus_requests: AtomicU64,
    /// Modbus exception responses sent.
    pub modbus_exceptions: AtomicU64,
    /// Connections closed for a malformed MBAP header.
    pub modbus_garbage: AtomicU64,
    /// The last operation error (`file:line: message`).
    pub last_operation_error: Mutex<Option<String>>,
    /// Operation errors already on stderr, by line and code (each once).
    pub reported_errors: Mutex<HashSet<(usize, u16)>>,
    /// Latched-value saves done (each compares the latched devices with
    /// what is kept and journals the differences, if any).
    pub latched_saves: AtomicU64,
    /// The fault that stopped the program has been reported.
    pub fault_reported: AtomicBool,
}

impl Stats {
    /// Counts one Modbus answer: a response, or an exception.
    pub fn count_modbus_reply(&self, reply: &Result<Response, Exception>) {
        self.modbus_requests.fetch_add(1, Ordering::Relaxed);
        if reply.is_err() {
            self.modbus_exceptions.fetch_add(1, Ordering::Relaxed);
        }
    }
}

/// Something the server's operator should hear about, handed to the sink
/// given to [`Shared::new`] as it happens (the binary prints it on stderr).
#[derive(Debug)]
pub enum Event {
    /// A scan raised an operation error not reported before (each distinct
    /// line and code once): `file:line: message (D8067=code)`.
    OperationError(String),
    /// A Modbus write could not be made durable; it was refused with
    /// exception 04 and not applied.
    WriteRefused(JournalError),
    /// Folding the journal into the snapshot failed after a durable append;
    /// the write stands and the compaction is tried again on the next one.
    CompactionFailed(JournalError),
    /// A periodic save of latched values failed (reported once until saves
    /// work again); it is retried every [`SAVE_PERIOD`](crate::SAVE_PERIOD).
    LatchedSaveFailing(JournalError),
    /// Periodic saves of latched values work again after failing.
    LatchedSavesResumed,
    /// The watchdog stopped the program: `file:line: message (D8061=code,
    /// M8061=1)`; it stays stopped until the server is restarted.
    ProgramStopped(String),
}

/// A client's write that was not made; device memory is as it was.
#[derive(Debug)]
pub enum WriteError {
    /// The program's cams refuse it: it would leave a running cam's table
    /// invalid, or a table load aims where no table may go.
    Refused(WriteRefusal),
    /// The journal could not be written (`--state`), so the write was not
    /// applied either.
    Journal(JournalError),
}

impl WriteError {
    /// The Modbus exception a client gets: 03 (illegal data value) for a
    /// write the cams refuse, 04 (server device failure) for one that
    /// could not be made durable.
    pub fn exception(&self) -> Exception {
        match self {
            Self::Refused(_) => Exception::IllegalDataValue,
            Self::Journal(_) => Exception::ServerDeviceFailure,
        }
    }

    /// The HTTP status a client gets: 409 (conflict with the running
    /// program) for a refusal, except 400 for a table load into the
    /// special registers (never right); 500 when it could not be made
    /// durable.
    pub fn http_status(&self) -> u16 {
        match self {
            Self::Refused(WriteRefusal::SpecialRegisters { .. }) => 400,
            Self::Refused(_) => 409,
            Self::Journal(_) => 500,
        }
    }

    /// The PLC error code behind a refusal, if any (6781, 6782, 6783).
    pub fn code(&self) -> Option<u16> {
        match self {
            Self::Refused(refusal) => refusal.code(),
            Self::Journal(_) => None,
        }
    }
}

impl core::fmt::Display for WriteError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            Self::Refused(refusal) => write!(f, "{refusal}"),
            Self::Journal(err) => write!(f, "not written: {err}"),
        }
    }
}

impl std::error::Error for WriteError {}

impl From<WriteRefusal> for WriteError {
    fn from(refusal: WriteRefusal) -> Self {
        Self::Refused(refusal)
    }
}

impl From<JournalError> for WriteError {
    fn from(err: JournalError) -> Self {
        Self::Journal(err)
    }
}

/// Everything the server threads share.
pub struct Shared {
    plc: Mutex<Plc>,
    image: Mutex<Image>,
    journal: Mutex<Option<Journal>>,
    /// How the server was started.
    pub info: ServeInfo,
    /// Counters.
    pub stats: Stats,
    /// The drives on a fieldbus, when the server runs them (`--ethercat`);
    /// set once at start.
    pub bus: std::sync::OnceLock<crate::bus::BusFace>,
    /// The open connections, within `info.limits`.
    pub connections: Arc<Connections<Closer>>,
    /// Where design requests are computed; started by the first one.
    design: OnceLock<Option<DesignPool>>,
    events: Box<dyn Fn(Event) + Send + Sync>,
}

impl Shared {
    /// Shares `plc` (with any kept values already restored) and `journal`;
    /// `events` hears what the operator should (see [`Event`]). From now
    /// on the watchdog times scans by the scan thread's CPU time
    /// ([`ThreadCpuTime`](crate::ThreadCpuTime)).
    pub fn new(
        mut plc: Plc,
        journal: Option<Journal>,
        info: ServeInfo,
        events: impl Fn(Event) + Send + Sync + 'static,
    ) -> Self {
        plc.set_scan_timer(Box::new(crate::scan_time::ThreadCpuTime::default()));
        Self {
            image: Mutex::new(Image::of(&plc)),
            plc: Mutex::new(plc),
            journal: Mutex::new(journal),
            connections: Arc::new(Connections::new(info.limits.caps())),
            info,
            stats: Stats::default(),
            bus: std::sync::OnceLock::new(),
            design: OnceLock::new(),
            events: Box::new(events),
        }
    }

    /// The design requests' pool, started on first use; `None` when its
    /// threads could not be started (design requests are then refused).
    pub fn design(&self) -> Option<&DesignPool> {
        self.design
            .get_or_init(|| DesignPool::start().ok())
            .as_ref()
    }

    /// Hands `event` to the sink given to [`Self::new`].
    pub(crate) fn report(&self, event: Event) {
        (self.events)(event);
    }

    /// Appends `batch` to `journal`, reporting a failed compaction.
    fn append(&self, journal: &mut Journal, batch: &WriteBatch) -> Result<(), JournalError> {
        let appended = journal.append(batch);
        if let Some(err) = journal.take_compaction_failure() {
            self.report(Event::CompactionFailed(err));
        }
        appended
    }

    /// Runs `f` with the PLC locked: the scan side only (the scan loop, a
    /// fieldbus cycle); it waits while a scan runs. Clients use
    /// [`Self::read`], [`Self::image`] and [`Self::write`].
    pub fn with_plc<T>(&self, f: impl FnOnce(&mut Plc) -> T) -> T {
        f(&mut lock(&self.plc))
    }

    /// Reads device memory as clients see it (the [`Image`]).
    pub fn read<T>(&self, f: impl FnOnce(&Devices) -> T) -> T {
        f(lock(&self.image).devices())
    }

    /// Reads the PLC as clients see it.
    pub fn image<T>(&self, f: impl FnOnce(&Image) -> T) -> T {
        f(&lock(&self.image))
    }

    /// The scan side's exchange with the clients around one scan period:
    /// `f` runs with the PLC locked, after the writes made since the last
    /// period were handed to it, and the image is published after it.
    pub(crate) fn exchange<T>(&self, f: impl FnOnce(&mut Plc) -> T) -> T {
        let mut plc = lock(&self.plc);
        lock(&self.image).deliver(&mut plc);
        let out = f(&mut plc);
        lock(&self.image).publish(&plc);
        out
    }

    /// Checks `batch` against the program's running cams (as clients see
    /// them, in the [`Image`]), makes it durable (when there is a state
    /// directory), then applies it to device memory as clients see it; the
    /// PLC takes it at the start of its next scan period. Never waits for a
    /// scan. Once this returns `Ok` the write may be
    /// acknowledged.
    ///
    /// # Errors
    /// [`WriteError::Refused`] when it would leave a running cam's table
    /// invalid ([`ecam_plc::check_register_writes`]); [`WriteError::Journal`]
    /// when the journal could not be written. Either way nothing was
    /// applied.
    pub fn write(&self, batch: &WriteBatch) -> Result<(), WriteError> {
        let mut journal = lock(&self.journal);
        let words: Vec<(u16, i16)> = batch.words().collect();
        if !words.is_empty() {
            lock(&self.image).check_register_writes(&words)?;
        }
        if let Some(journal) = journal.as_mut() {
            self.append(journal, batch)?;
        }
        lock(&self.image).write(batch.clone());
        Ok(())
    }

    /// Saves the latched devices' values that differ from what a restart
    /// would restore, as one journal record (see [`LatchedImage`]); returns
    /// how many were saved. The journal's lock is held throughout, so no
    /// client write falls between the copy and the record; the image's
    /// only for the copy into `image` (the PLC's not at all).
    ///
    /// # Errors
    /// The record could not be written; it is tried again next time.
    pub fn save_latched(&self, image: &mut LatchedImage) -> Result<usize, JournalError> {
        let mut journal = lock(&self.journal);
        let Some(journal) = journal.as_mut() else {
            return Ok(0);
        };
        image.capture(lock(&self.image).devices());
        let changes = image.changes(journal.persisted());
        self.append(journal, &changes)?;
        self.stats.latched_saves.fetch_add(1, Ordering::Relaxed);
        Ok(changes.writes().len())
    }

    /// The body of `GET /api/status`.
    pub fn status(&self) -> Value {
        let (scans, now_us, operation_error, fault, scan_times, watchdog) = self.image(|image| {
            let word = |n: u16| image.devices().word(n).unwrap_or(0);
            let [current, shortest, longest] = ecam_plc::special::D_SCAN_TIME.map(word);
            (
                image.scans(),
                image.now_us(),
                word(ecam_plc::special::D_OPERATION_ERROR),
                image.fault().map(str::to_string),
                json!({"last_ms": f64::from(current) / 10.0, "min_ms": f64::from(shortest) / 10.0,
                       "max_ms": f64::from(longest) / 10.0}),
                ecam_plc::watchdog::limit_us(word(ecam_plc::special::D_WATCHDOG)) / 1000,
            )
        });
        let (kept, records, read_only) = lock(&self.journal).as_ref().map_or((0, 0, None), |j| {
            (
                j.persisted().len(),
                j.records(),
                j.read_only().map(ToString::to_string),
            )
        });
        let load = |a: &AtomicU64| a.load(Ordering::Relaxed);
        let s = &self.stats;
        json!({
            "running": s.scanning.load(Ordering::Relaxed),
            "program": self.info.program,
            "scan_us": self.info.timing.scan_us,
            "tick_us": self.info.timing.tick_us,
            "scans": scans,
            "sim_time_us": now_us,
            "lag_us": load(&s.lag_us),
            "skipped_us": load(&s.skipped_us),
            "operation_errors": load(&s.operation_errors),
            "last_operation_error": *lock(&s.last_operation_error),
            "D8067": operation_error,
            "plc": {
                "state": if fault.is_some() { "stopped" } else { "run" },
                "fault": fault,
                "watchdog_ms": watchdog,
                "scan_time": scan_times,
            },
            "modbus": {
                "address": self.info.modbus.to_string(),
                "connections": load(&s.modbus_connections),
                "requests": load(&s.modbus_requests),
                "exceptions": load(&s.modbus_exceptions),
                "closed_malformed": load(&s.modbus_garbage),
            },
            "http": self.info.http.to_string(),
            "connections": self.connections.json(),
            "design": self.design.get().and_then(Option::as_ref).map(DesignPool::json),
            "limits": self.info.limits.json(),
            "ethercat": self.bus.get().map(|b| {
                let s = b.snapshot();
                json!({"state": s.state, "drives": s.drives.len(), "cycles": s.cycles})
            }),
            "state": {
                "dir": self.info.state_dir.as_ref().map(|d| d.display().to_string()),
                "kept_values": kept,
                "journal_records": records,
                "latched_saves": load(&s.latched_saves),
                "read_only": read_only,
            },
        })
    }
}
