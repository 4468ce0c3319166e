//! Sync outputs (document 003 registers 8–12, function register 4 bit 0):
//! a signal that is on while the master's place in the cycle lies inside a
//! window.

/// One sync window on the master position in the cycle (after master zoom).
///
/// Document 003: "lower threshold ≤ master axis position ≤ higher
/// threshold", so both bounds are inclusive. A window whose `low > high`
/// is never active.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SyncWindow {
    /// Lower bound, inclusive (registers 9/10).
    pub low: i64,
    /// Upper bound, inclusive (registers 11/12).
    pub high: i64,
    /// The enable bit (function register 4, bit 0).
    pub enabled: bool,
}

impl SyncWindow {
    /// A disabled window.
    pub const OFF: SyncWindow = SyncWindow {
        low: 0,
        high: 0,
        enabled: false,
    };

    /// An enabled window `[low, high]`.
    pub const fn new(low: i64, high: i64) -> Self {
        Self {
            low,
            high,
            enabled: true,
        }
    }

    /// Whether `master_in_cycle` lies inside this enabled window.
    pub const fn contains(&self, master_in_cycle: i64) -> bool {
        self.enabled && self.low <= master_in_cycle && master_in_cycle <= self.high
    }
}

/// Bit `i` set when window `i` holds `master_in_cycle`.
#[inline]
pub(crate) fn active_windows(windows: &[SyncWindow; 4], master_in_cycle: i64) -> u8 {
    // Without short-circuits: four compares and no branches every tick.
    let mut bits = 0u8;
    for (i, w) in windows.iter().enumerate() {
        let inside = w.enabled & (w.low <= master_in_cycle) & (master_in_cycle <= w.high);
        bits |= u8::from(inside) << i;
    }
    bits
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn document_003_example_window_is_inclusive() {
        // Section 4.1.3: sync on between master 20000 and 30000.
        let windows = [
            SyncWindow::new(20000, 30000),
            SyncWindow::OFF,
            SyncWindow {
                low: 0,
                high: 100,
                enabled: false,
            },
            SyncWindow::new(29000, 40000),
        ];
        assert_eq!(active_windows(&windows, 19999), 0);
        assert_eq!(active_windows(&windows, 20000), 1);
        assert_eq!(active_windows(&windows, 30000), 0b1001);
        assert_eq!(active_windows(&windows, 30001), 0b1000);
        assert_eq!(active_windows(&windows, 50), 0);
    }
}
