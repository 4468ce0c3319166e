//! Counters: the FX counter coil (`OUT Cn K<set value>`), its contact, and the
//! high-speed counters that count pulses on an X input.
//!
//! Counter kinds (FX family, with the LX3V's C231 on X0 that document 003's
//! example uses: "Enable high-speed counter C231 to receive high-speed pulse
//! from X0"):
//! - C0–C199: 16-bit up counters; one count per rising edge of the coil's
//!   power flow, stopping at the set value.
//! - C200–C255 except the high-speed ones: 32-bit counters, one count per
//!   rising edge of the coil's power flow, down while M8000+n (M8200..) is on.
//! - [`HIGH_SPEED_COUNTERS`]: one-phase high-speed counters; they count every
//!   pulse on their input while their coil is driven, down while M8000+n is on.
//!
//! The contact `LD Cn` is a latch, as on the FX3U: it is decided when the
//! counter counts and by RST, not by reading the value. A 16-bit counter's
//! contact turns on when a count reaches the set value and stays on until
//! RST; a 32-bit counter's turns on when a count up leaves the value at or
//! above the set value and off when a count down leaves it below (so the
//! ring wrap 2147483647 → −2147483648 while counting up keeps it on).
//! Writing the current value (MOV, `--set`) does not move the contact
//! until the next count. Before the first count or RST since power-up (a
//! retained counter restored by `ecam serve`), the contact reads as value ≥
//! set value; off while the coil has never run.

use crate::device::{C_32BIT_FIRST, C_COUNT, Device};
use crate::devices::Devices;
use crate::special::M_COUNTER_DIRECTION_BASE;

/// The supported high-speed counters and their inputs: (counter, X index).
pub const HIGH_SPEED_COUNTERS: [(u16, u16); 7] = [
    (231, 0),
    (235, 0),
    (236, 1),
    (237, 2),
    (238, 3),
    (239, 4),
    (240, 5),
];

/// Highest X index any high-speed counter reads, plus one.
const HIGH_SPEED_INPUTS: usize = 6;

/// High-speed counters reading X`input`.
pub(crate) fn counters_on_input(input: u16) -> impl Iterator<Item = u16> {
    HIGH_SPEED_COUNTERS
        .iter()
        .filter(move |(_, x)| *x == input)
        .map(|(c, _)| *c)
}

/// True for a supported high-speed counter.
fn is_high_speed(counter: u16) -> bool {
    HIGH_SPEED_COUNTERS.iter().any(|(c, _)| *c == counter)
}

/// Coil state and set values of C0..C255.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Counters {
    set_values: Vec<Option<i32>>,
    coils: Vec<bool>,
    /// The latched contacts; `None` until the first count or RST.
    contacts: Vec<Option<bool>>,
    last_input: [bool; HIGH_SPEED_INPUTS],
}

impl Default for Counters {
    fn default() -> Self {
        Self {
            set_values: vec![None; usize::from(C_COUNT)],
            coils: vec![false; usize::from(C_COUNT)],
            contacts: vec![None; usize::from(C_COUNT)],
            last_input: [false; HIGH_SPEED_INPUTS],
        }
    }
}

impl Counters {
    /// Executes the coil `OUT Cn set_value` with power flow `power`.
    pub fn drive_coil(&mut self, devices: &mut Devices, counter: u16, power: bool, set_value: i32) {
        let index = usize::from(counter);
        let (Some(sv), Some(coil)) = (self.set_values.get_mut(index), self.coils.get_mut(index))
        else {
            return;
        };
        *sv = Some(set_value);
        let rising = power && !*coil;
        *coil = power;
        if !rising || is_high_speed(counter) {
            return;
        }
        let value = devices.counter(counter).unwrap_or(0);
        if counter < C_32BIT_FIRST {
            // K0 counts as K1 (FX3U manual). At or past the set value the
            // count input is ignored and the contact (re)latches on.
            let target = set_value.max(1);
            let next = if value < target {
                value.saturating_add(1)
            } else {
                value
            };
            let _ = devices.set_counter(counter, next);
            if let Some(contact) = self.contacts.get_mut(index) {
                let was = contact.unwrap_or(false);
                *contact = Some(was || next >= target);
            }
        } else {
            self.count(devices, counter, 1);
        }
    }

    /// The counter's contact (see the module text): latched at counts and
    /// RST; before the first of them, value ≥ set value. A 16-bit counter
    /// with set value K0 behaves as with K1, as the FX3U manual says.
    pub fn contact(&self, devices: &Devices, counter: u16) -> bool {
        let index = usize::from(counter);
        if let Some(Some(latched)) = self.contacts.get(index) {
            return *latched;
        }
        match (self.set_values.get(index), devices.counter(counter)) {
            (Some(Some(sv)), Ok(value)) if counter < C_32BIT_FIRST => value >= (*sv).max(1),
            (Some(Some(sv)), Ok(value)) => value >= *sv,
            _ => false,
        }
    }

    /// RST Cn: the value to 0 and the contact off.
    pub fn reset(&mut self, devices: &mut Devices, counter: u16) {
        let _ = devices.set_counter(counter, 0);
        if let Some(contact) = self.contacts.get_mut(usize::from(counter)) {
            *contact = Some(false);
        }
    }

    /// Counts `pulses` on a 32-bit counter, up or down by its M8200+n flag,
    /// wrapping at 32 bits (FX ring counter), and moves its contact.
    fn count(&mut self, devices: &mut Devices, counter: u16, pulses: u32) {
        let down = M_COUNTER_DIRECTION_BASE
            .checked_add(counter)
            .and_then(|m| devices.m(m).ok())
            .unwrap_or(false);
        let before = self.contact(devices, counter);
        let value = devices.counter(counter).unwrap_or(0);
        let step = pulses as i32;
        let next = if down {
            value.wrapping_sub(step)
        } else {
            value.wrapping_add(step)
        };
        let _ = devices.set_counter(counter, next);
        let index = usize::from(counter);
        let set_value = self.set_values.get(index).copied().flatten();
        if let (Some(sv), Some(contact)) = (set_value, self.contacts.get_mut(index)) {
            *contact = Some(if down {
                before && next >= sv
            } else {
                before || next >= sv
            });
        }
    }

    /// True while a high-speed counter's coil is driven (it counts its input).
    pub fn is_counting(&self, counter: u16) -> bool {
        is_high_speed(counter)
            && self
                .coils
                .get(usize::from(counter))
                .copied()
                .unwrap_or(false)
    }

    /// `pulses` arrive on X`input`: every enabled high-speed counter on it counts them.
    pub fn feed(&mut self, devices: &mut Devices, input: u16, pulses: u32) {
        for counter in counters_on_input(input) {
            if self.is_counting(counter) {
                self.count(devices, counter, pulses);
            }
        }
    }

    /// Counts rising edges of X0..X5 set from outside.
    pub fn sample_inputs(&mut self, devices: &mut Devices) {
        for input in 0..HIGH_SPEED_INPUTS {
            let x = input as u16;
            let level = devices.bit(Device::X(x)).unwrap_or(false);
            let Some(last) = self.last_input.get_mut(input) else {
                continue;
            };
            let rising = level && !*last;
            *last = level;
            if rising {
                self.feed(devices, x, 1);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn high_speed_counter_counts_only_while_driven() {
        let mut devices = Devices::new();
        let mut counters = Counters::default();
        counters.feed(&mut devices, 0, 5);
        assert_eq!(devices.counter(231), Ok(0));
        counters.drive_coil(&mut devices, 231, true, 10);
        counters.feed(&mut devices, 0, 5);
        assert_eq!(devices.counter(231), Ok(5));
        assert!(!counters.contact(&devices, 231));
        counters.feed(&mut devices, 0, 5);
        assert!(counters.contact(&devices, 231));
        devices.set_m(8231, true).unwrap();
        counters.feed(&mut devices, 0, 7);
        assert_eq!(devices.counter(231), Ok(3));
        counters.drive_coil(&mut devices, 231, false, 10);
        counters.feed(&mut devices, 0, 5);
        assert_eq!(devices.counter(231), Ok(3));
    }

    #[test]
    fn sixteen_bit_counter_counts_edges_up_to_set_value() {
        let mut devices = Devices::new();
        let mut counters = Counters::default();
        for power in [true, true, false, true, false, true, false, true] {
            counters.drive_coil(&mut devices, 3, power, 3);
        }
        assert_eq!(devices.counter(3), Ok(3));
        assert!(counters.contact(&devices, 3));
    }

    #[test]
    fn a_16_bit_set_value_0_acts_as_1() {
        let mut devices = Devices::new();
        let mut counters = Counters::default();
        counters.drive_coil(&mut devices, 4, false, 0);
        assert!(!counters.contact(&devices, 4), "no count yet");
        counters.drive_coil(&mut devices, 4, true, 0);
        assert_eq!(devices.counter(4), Ok(1), "the first count");
        assert!(counters.contact(&devices, 4));
        counters.drive_coil(&mut devices, 4, false, 0);
        counters.drive_coil(&mut devices, 4, true, 0);
        assert_eq!(devices.counter(4), Ok(1), "and no further");
    }

    #[test]
    fn input_edges_count_once() {
        let mut devices = Devices::new();
        let mut counters = Counters::default();
        counters.drive_coil(&mut devices, 236, true, 0);
        devices.set_bit(Device::X(1), true).unwrap();
        counters.sample_inputs(&mut devices);
        counters.sample_inputs(&mut devices);
        assert_eq!(devices.counter(236), Ok(1));
    }
}
