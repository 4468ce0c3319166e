//! Integration tests of ecam-ethercat: the whole path from ethercrab to the
//! emulated drives and back.
#![allow(clippy::unwrap_used, clippy::expect_used)]

mod bring_up;
mod bus_master;
mod coe;
mod faults;
mod follow;
mod rotary_knife;
mod veth;

use std::sync::{Arc, Mutex};
use std::time::Duration;

use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment};
use ecam_ethercat::{Segment, SegmentConfig, Transport};

/// Lost cycles in a row a test line allows before it faults.
const LOST: u32 = 5;

/// Timing for tests that call `cycle` back to back (no real-time clock)
/// and lose replies on purpose (each lost one is waited for).
fn test_config() -> SegmentConfig {
    SegmentConfig {
        // Generous: a loaded CI host must not turn a slow reply into a
        // lost frame (only the tests that lose frames lose them).
        frame_timeout: Duration::from_millis(250),
        reply_timeout: Duration::from_millis(250),
        dc_static_sync_iterations: 50,
        ..SegmentConfig::for_cycle(Duration::from_millis(1))
    }
}

/// Timing for the tests that require every cycle answered (exactness over
/// thousands of cycles): a reply waited for 5 s, so that only a dead link,
/// not a busy shared host that stalls the test thread for a few hundred
/// milliseconds, loses a cycle. A reply that comes back is not held up.
fn exact_config() -> SegmentConfig {
    SegmentConfig {
        reply_timeout: Duration::from_secs(5),
        ..test_config()
    }
}

/// A segment of `drives` emulated drives brought to OP that answers every
/// cycle (the [`exact_config`] timing), and the handle to the emulation.
fn emulated(drives: usize, behaviour: DriveBehaviour) -> (Segment, Arc<Mutex<EmulatedSegment>>) {
    emulated_with(drives, behaviour, exact_config())
}

/// As [`emulated`], with this timing. The ESCs' watchdog is off: these
/// tests cycle without a real-time clock, and a loaded host may pause
/// them for longer than it.
fn emulated_with(
    drives: usize,
    behaviour: DriveBehaviour,
    config: SegmentConfig,
) -> (Segment, Arc<Mutex<EmulatedSegment>>) {
    let mut segment = EmulatedSegment::new(drives, behaviour);
    segment.set_watchdog(None);
    let emulation = Arc::new(Mutex::new(segment));
    let segment =
        Segment::bring_up(Transport::Emulated(Arc::clone(&emulation)), config).expect("bring-up");
    (segment, emulation)
}
