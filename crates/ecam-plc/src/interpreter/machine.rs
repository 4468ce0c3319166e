//! What an instruction works on ([`Machine`]), what it remembers between
//! scans ([`Memory`]), and when an applied instruction runs ([`runs`]):
//! shared by every instruction family.

use crate::decam::Decam;
use crate::devices::Devices;
use crate::hardware::Hardware;
use crate::il::Exec;

/// What one instruction remembers between scans (edges, PLSY latch).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Memory {
    /// The previous input of an edge contact, or previous power flow of a
    /// pulse instruction (PLS/PLF, P forms, counter coil).
    pub previous: bool,
    /// PLSY: the pulse train was started and has not been re-armed yet.
    pub latched: bool,
}

/// Everything an instruction may touch.
pub(crate) struct Machine<'a> {
    /// Device memory.
    pub(crate) devices: &'a mut Devices,
    /// Pulse outputs, counters, wires.
    pub(crate) hardware: &'a mut Hardware,
    /// One E-cam instance per DECAM instruction, in program order.
    pub(crate) decams: &'a mut [Decam],
    /// Simulated time of this scan.
    pub(crate) now_us: u64,
}

/// Whether an applied instruction runs this scan: continuous forms while the
/// power flow is on, `P` forms in the scan it turns on.
pub(crate) fn runs(exec: Exec, power: bool, memory: &mut Memory) -> bool {
    let rising = power && !memory.previous;
    memory.previous = power;
    match exec {
        Exec::Continuous => power,
        Exec::Pulse => rising,
    }
}
