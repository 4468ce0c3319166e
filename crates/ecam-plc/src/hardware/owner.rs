//! Who drives a pulse output: one instruction at a time.
//!
//! The FX family (and the LX3V after it) lets only one pulse instruction
//! drive an output. An instruction that becomes active while another keeps
//! the output busy does not run; it takes the output once the other has
//! released it, if its own power flow is still on. [`super::Hardware`] keeps
//! the owner of each output and refuses pulses from anyone else.

/// The identity of an instruction that drives a pulse output.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OutputOwner {
    /// A PLSY/DPLSY instruction, by the index of its statement in the program.
    PulseTrain(usize),
    /// A DECAM instance, by its instance number (each
    /// [`crate::decam::Decam`] gets its own when it is created).
    Cam(u64),
}
