//! Fuzzing harnesses: one function per reader a client or a state
//! directory can feed, shared by the cargo-fuzz targets in `fuzz/` and by
//! the stable property tests in `tests/it/fuzz.rs`, so both exercise the
//! same code.
//!
//! Each takes arbitrary bytes and must return without panicking, whatever
//! the bytes; a panic is a bug in the reader.

use std::net::{Ipv4Addr, SocketAddr};
use std::path::PathBuf;
use std::sync::atomic::{AtomicU64, Ordering};

use ecam_plc::{Devices, Plc};

use crate::{
    JOURNAL_FILE, Journal, MbapHeader, SNAPSHOT_FILE, ServeInfo, Shared, WriteBatch,
    answer_request, encode_response, parse_device_names, parse_device_sets, parse_request,
};

/// Most bytes a response PDU may have: a Modbus TCP frame's length field
/// counts the unit id and at most 253 PDU bytes.
const MAX_RESPONSE_PDU: usize = 253;

/// A server with an empty program and no journal, as `ecam serve` without
/// a state directory runs.
fn server() -> Option<Shared> {
    let program = ecam_plc::Program::parse("END", "fuzz.il").ok()?;
    let plc = Plc::new(program).ok()?;
    let addr = SocketAddr::from((Ipv4Addr::LOCALHOST, 0));
    let info = ServeInfo {
        program: None,
        timing: ecam_plc::sim::Timing::default(),
        modbus: addr,
        http: addr,
        state_dir: None,
        limits: Default::default(),
    };
    Some(Shared::new(plc, None, info, |_| {}))
}

/// Feeds `data` to the Modbus TCP server's readers as a stream of frames,
/// as a connection delivers them: each [`MbapHeader::parse`]d, its PDU
/// [`parse_request`]ed and [`answer_request`]ed on a fresh [`Shared`], the
/// reply encoded ([`encode_response`]) and framed. The stream ends where
/// the connection would be closed (a header that is not Modbus TCP) or
/// where the bytes run out.
pub fn modbus_request(data: &[u8]) {
    let Some(shared) = server() else {
        return;
    };
    let mut rest = data;
    while let Some((header, after)) = rest.split_first_chunk::<{ MbapHeader::LEN }>() {
        let Some(header) = MbapHeader::parse(*header) else {
            return;
        };
        let Some((pdu, after)) = after.split_at_checked(header.pdu_len) else {
            return;
        };
        rest = after;
        let function = pdu.first().copied().unwrap_or(0);
        let reply = parse_request(pdu).and_then(|request| answer_request(&shared, &request));
        shared.stats.count_modbus_reply(&reply);
        let response = encode_response(function, &reply);
        assert!(
            !response.is_empty() && response.len() <= MAX_RESPONSE_PDU,
            "response PDU of {} bytes to {pdu:02x?}",
            response.len()
        );
        let _ = header.frame(&response);
    }
}

/// Feeds `data` to the HTTP device readers: the body of `POST
/// /api/devices` ([`parse_device_sets`]) and, as text, the `names` of
/// `GET /api/devices` ([`parse_device_names`]); a batch of writes they
/// accept is applied to fresh device memory.
pub fn device_json(data: &[u8]) {
    if let Ok((batch, _views)) = parse_device_sets(data) {
        batch.apply(&mut Devices::new());
    }
    if let Ok(names) = core::str::from_utf8(data) {
        let _ = parse_device_names(names);
    }
}

/// Feeds each line of `data` to the journal's line reader
/// ([`WriteBatch::parse_line`]); a line it accepts must be written back
/// ([`WriteBatch::to_line`]) as a line that reads as the same batch.
pub fn journal_line(data: &[u8]) {
    let Ok(text) = core::str::from_utf8(data) else {
        return;
    };
    for line in text.lines() {
        if let Ok(batch) = WriteBatch::parse_line(line) {
            let written = batch.to_line();
            let again = WriteBatch::parse_line(&written);
            assert_eq!(
                again.as_ref(),
                Ok(&batch),
                "{line:?} written as {written:?}"
            );
            batch.apply(&mut Devices::new());
        }
    }
}

/// Opens ([`Journal::open`]) a state directory holding `data`: the bytes
/// before the first NUL as the snapshot and those after it as the journal
/// (all of `data` as the journal when there is no NUL); restores what it
/// kept into fresh device memory. The directory is a fresh one under the
/// system's temporary directory, removed afterwards.
pub fn journal_open(data: &[u8]) {
    let dir = scratch_dir();
    let _ = std::fs::remove_dir_all(&dir);
    if std::fs::create_dir_all(&dir).is_err() {
        return;
    }
    let (snapshot, journal) = match data.iter().position(|&b| b == 0) {
        Some(at) => (data.get(..at), data.get(at.saturating_add(1)..)),
        None => (None, Some(data)),
    };
    let written = snapshot.is_none_or(|s| std::fs::write(dir.join(SNAPSHOT_FILE), s).is_ok())
        && journal.is_none_or(|j| std::fs::write(dir.join(JOURNAL_FILE), j).is_ok());
    if written && let Ok((journal, _recovery)) = Journal::open(&dir) {
        let _ = journal.records();
        journal.restore_into(&mut Devices::new());
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// A directory name no other harness call uses at the same time (the
/// stable tests run in parallel threads of one process).
fn scratch_dir() -> PathBuf {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    std::env::temp_dir().join(format!("ecam-fuzz-journal-{}-{n}", std::process::id()))
}
