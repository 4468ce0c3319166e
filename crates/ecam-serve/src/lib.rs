//! # ecam-serve: the PLC behind Modbus TCP and HTTP, without the sockets
//!
//! Everything `ecam serve` decides, as plain functions and types the
//! binary wires to its listeners: the Modbus PDU codec ([`parse_request`],
//! [`encode_response`]) and MBAP framing ([`MbapHeader`]), the address map
//! (the **contract** in `docs/architecture.md`: [`coil_range`],
//! [`register_range`]), device writes and their one-line text form
//! ([`WriteBatch`]), the durable journal of a state directory
//! ([`Journal`]; its files carry checksums, so damage stops the start with
//! file and line, [`Damage`], or is stepped over, [`OnDamage`]), which devices a restart keeps ([`is_kept`],
//! [`LatchedImage`]), device names as JSON for the HTTP API
//! ([`parse_device_names`], [`devices_to_json`], [`parse_device_sets`]),
//! the PLC shared by the scan loop and the servers ([`Shared`]), paced
//! by the wall clock ([`scan_loop`]) and timed by the watchdog
//! ([`ThreadCpuTime`]), the copy of it clients read and write so that no
//! request waits for a scan ([`Image`]), what the designer's live view
//! samples of a DECAM block ([`LiveRequest`], [`LiveSample`]), and what
//! keeps clients from holding the server: every cap and deadline
//! ([`Limits`]), who makes room at a full cap ([`Connections`]), and where
//! design requests run ([`DesignPool`]).
//!
//! Without features it has no async runtime and prints nothing: the
//! binary owns stderr and hears what the operator should through
//! [`Event`]. The feature `net` adds the sockets and async tasks (`net`:
//! the Modbus TCP listener, the HTTP router and the live view on tokio and
//! axum); the feature `ethercat` adds `serve --ethercat`'s fieldbus adapter
//! (`ethercat`: the PLC's pulse outputs on CiA 402 drives over
//! ecam-ethercat's cycle driver). The scan loop and the latched-value saver block the
//! thread they run on; the design pool runs its own worker threads. Use it to serve the PLC over another transport, or
//! to test what a client sees without a network; to run PLC programs in
//! simulated time, use `ecam_plc::sim` directly. `docs/modbus.md` describes
//! the server as a user sees it.
//!
//! ```
//! use ecam_plc::{Plc, Program, sim::Timing};
//! use ecam_serve::{Response, ServeInfo, Shared, answer_request, encode_response, parse_request};
//!
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let plc = Plc::new(Program::parse("", "empty.il")?)?;
//! let addr = "127.0.0.1:0".parse()?;
//! let info = ServeInfo {
//!     program: None,
//!     timing: Timing::default(),
//!     modbus: addr,
//!     http: addr,
//!     state_dir: None,
//!     limits: Default::default(),
//! };
//! let shared = Shared::new(plc, None, info, |event| eprintln!("{event:?}"));
//!
//! // 0x10 Write Multiple Registers: D100 = 0x0C6F, D101 = 0, so DD100 = 3183
//! // (32-bit values low word first).
//! let pdu = [0x10, 0, 100, 0, 2, 4, 0x0C, 0x6F, 0x00, 0x00];
//! let request = parse_request(&pdu)?;
//! let reply = answer_request(&shared, &request);
//! assert_eq!(reply, Ok(Response::Written { address: 100, quantity: 2 }));
//! assert_eq!(encode_response(pdu[0], &reply), [0x10, 0, 100, 0, 2]);
//! assert_eq!(shared.read(|devices| devices.dword(100)), Ok(3183));
//!
//! // Y outputs are the program's: writing coil 12000 (Y0) is exception 02.
//! let reply = answer_request(&shared, &parse_request(&[0x05, 0x2E, 0xE0, 0xFF, 0x00])?);
//! assert_eq!(encode_response(0x05, &reply), [0x85, 0x02]);
//! # Ok(())
//! # }
//! ```
#![cfg_attr(test, allow(clippy::unwrap_used, clippy::expect_used))]

mod answer;
mod bus;
mod bus_request;
mod clock;
mod connections;
mod design_pool;
mod device_json;
#[cfg(feature = "ethercat")]
pub mod ethercat;
#[doc(hidden)]
pub mod fuzz;
mod image;
mod journal;
mod limits;
mod live;
mod map;
mod mbap;
#[cfg(feature = "net")]
pub mod net;
mod pdu;
mod periodic_save;
mod retain;
mod scan_time;
mod state;
mod state_error;
mod state_file;
mod state_report;
mod sync;
mod table_load;
mod web_guard;
mod write;

pub use answer::answer_request;
pub use bus::{
    BUS_REGISTER_BASE, BusCommand, BusFace, BusLineState, BusSnapshot, BusSource, DRIVE_WORDS,
    DriveView, ENABLE_COIL, FAULT_COIL, HEADER_WORDS,
};
pub use bus_request::{BusRequestError, DEFAULT_FAULT_CODE, parse_bus_command};
pub use clock::{BusTicks, MAX_LAG, Step, next_step, scan_loop, scan_on_bus_ticks, scan_period};
pub use connections::{Activity, Busy as RequestBusy, Caps, Connections, Kind, Registration};
pub use design_pool::{Busy, DesignPool, Outcome, Ticket};
pub use device_json::{
    MAX_DEVICE_NAMES, devices_to_json, parse_device_names, parse_device_sets, parse_json_body,
};
pub use image::Image;
pub use journal::{
    COMPACT_AFTER, COMPACT_AFTER_BYTES, DAMAGED_SUFFIX, JOURNAL_FILE, Journal, OnDamage, Recovery,
    SNAPSHOT_FILE,
};
pub use limits::{
    BODY, DEFAULT_DESIGN_DEADLINE, DEFAULT_IDLE, DEFAULT_MAX_CONNECTIONS, DESIGN_QUEUE,
    DESIGN_WORKERS, LIVE_IDLE, LIVE_SEND, Limits, MAX_BODY_BYTES, MAX_LIVE_VIEWS, PARTIAL,
};
pub use live::{DEFAULT_LIVE_RATE, LiveRequest, LiveSample, MAX_LIVE_RATE};
pub use map::{
    CoilArea, CoilRange, RegisterRange, X_COIL_BASE, Y_COIL_BASE, coil_range, register_range,
    writable_coil_range,
};
pub use mbap::MbapHeader;
pub use pdu::{
    Exception, MAX_READ_BITS, MAX_READ_REGISTERS, MAX_WRITE_BITS, MAX_WRITE_REGISTERS, Request,
    Response, encode_response, parse_request,
};
pub use periodic_save::save_latched_periodically;
pub use retain::{LatchedImage, Overridden, SAVE_PERIOD, is_kept, overridden};
pub use scan_time::ThreadCpuTime;
pub use state::{Closer, Event, ServeInfo, Shared, Stats, WriteError};
pub use state_error::{Damage, JournalError};
pub use state_file::{Dropped, SNAPSHOT_HEADER};
pub use state_report::{Notice, NoticeLevel, open_notices, restore_notices};
pub use table_load::{TableLoad, TableLoadError, TableSwitch, WhileRunning, parse_table_load};
pub use web_guard::{Access, MIN_TOKEN_LEN, Refusal, RequestFacts, TokenError, read_token};
pub use write::{LineError, Slot, WriteBatch};
