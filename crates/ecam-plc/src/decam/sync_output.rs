//! The sync output (offsets 4 bit 0, 8–12): one Y on exactly while the cam
//! runs and the master's place in the cycle (after zoom) lies inside the
//! window, both thresholds included.

use crate::device::Device;
use crate::devices::Devices;

/// Drives the sync Y, remembering which one it drove so a changed offset 8
/// (or a stop) turns the old one off.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SyncOutput {
    driven: Option<u16>,
}

impl SyncOutput {
    /// Nothing driven yet.
    pub const fn new() -> Self {
        Self { driven: None }
    }

    /// Sets output `Y[index]` to `on`, or releases it (`index = None`).
    /// A Y this instance drove before and no longer drives is turned off.
    pub fn drive(&mut self, devices: &mut Devices, index: Option<u16>, on: bool) {
        if let Some(old) = self.driven
            && Some(old) != index
        {
            // The index was range-checked when it was driven.
            let _ = devices.set_bit(Device::Y(old), false);
            self.driven = None;
        }
        if let Some(y) = index
            && devices.set_bit(Device::Y(y), on).is_ok()
        {
            self.driven = Some(y);
        }
    }

    /// Turns the driven output off and forgets it.
    pub fn release(&mut self, devices: &mut Devices) {
        self.drive(devices, None, false);
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)]
mod tests {
    use super::*;

    #[test]
    fn moving_the_output_turns_the_old_one_off() {
        let mut dev = Devices::new();
        let mut s = SyncOutput::new();
        s.drive(&mut dev, Some(7), true);
        assert!(dev.bit(Device::Y(7)).unwrap());
        s.drive(&mut dev, Some(6), true);
        assert!(!dev.bit(Device::Y(7)).unwrap());
        assert!(dev.bit(Device::Y(6)).unwrap());
        s.release(&mut dev);
        assert!(!dev.bit(Device::Y(6)).unwrap());
    }
}
