//! The start register (offset 5) and its timing rule.
//!
//! Document 003 section 4.1.2 / 5.1(3): to restart, or to change between
//! cyclic and noncyclic, the register must be off (0) for at least 100 µs
//! first. The gate remembers since when the register (or the DECAM
//! instruction's power flow) has been off; a start value seen after a
//! shorter off time, or written straight over the other mode, is refused
//! until the register goes back to 0.

/// The mode the start register asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CamMode {
    /// Start register 1.
    Cyclic,
    /// Start register 2.
    Noncyclic,
}

impl CamMode {
    /// Decodes offset 5: 1 cyclic, 2 noncyclic, anything else stop.
    pub fn from_register(value: u16) -> Option<Self> {
        match value {
            1 => Some(Self::Cyclic),
            2 => Some(Self::Noncyclic),
            _ => None,
        }
    }
}

/// Minimum off time before a start, in µs.
pub const RESTART_OFF_US: u64 = 100;

/// What the gate tells the cam to do this tick.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GateAction {
    /// Nothing changes.
    Hold,
    /// Stop immediately (the register went to stop, or switched modes).
    Stop,
    /// Start in this mode (if the register block is valid).
    Start(CamMode),
}

/// Tracks the start register across ticks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct StartGate {
    /// The mode accepted and not yet stopped.
    active: Option<CamMode>,
    /// Since when the register has been off; `None` after a refused start
    /// until the register is off again. Power-up counts as off long ago.
    off_since: Option<u64>,
    /// A start is waiting for something other than time (a valid block, the
    /// stop flag M8145… released): it is taken as soon as it can be.
    pending: bool,
}

impl Default for StartGate {
    fn default() -> Self {
        Self::new()
    }
}

impl StartGate {
    /// A gate at power-up: off since long ago.
    pub const fn new() -> Self {
        Self {
            active: None,
            off_since: Some(0),
            pending: false,
        }
    }

    /// The accepted mode.
    pub const fn active(&self) -> Option<CamMode> {
        self.active
    }

    /// The instruction lost power flow (counts as the register off).
    pub fn power_off(&mut self, now_us: u64) {
        self.active = None;
        self.pending = false;
        if self.off_since.is_none() {
            self.off_since = Some(now_us);
        }
    }

    /// Reads the register value at `now_us`.
    pub fn observe(&mut self, register: u16, now_us: u64) -> GateAction {
        let wanted = CamMode::from_register(register);
        match (self.active, wanted) {
            (active, None) => {
                self.active = None;
                self.pending = false;
                if self.off_since.is_none() {
                    self.off_since = Some(now_us);
                }
                if active.is_some() {
                    GateAction::Stop
                } else {
                    GateAction::Hold
                }
            }
            (Some(a), Some(w)) if a == w => GateAction::Hold,
            (Some(_), Some(_)) => {
                // Mode switch without the 100 µs off time: stop, and refuse
                // the new mode until the register has been off again.
                self.active = None;
                self.off_since = None;
                GateAction::Stop
            }
            (None, Some(w)) => match self.off_since {
                Some(t) if self.pending || t == 0 || now_us.saturating_sub(t) >= RESTART_OFF_US => {
                    self.pending = true;
                    GateAction::Start(w)
                }
                _ => {
                    self.off_since = None;
                    GateAction::Hold
                }
            },
        }
    }

    /// The start returned by [`StartGate::observe`] was carried out.
    pub fn started(&mut self, mode: CamMode) {
        self.active = Some(mode);
        self.off_since = None;
        self.pending = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn starts_after_power_up() {
        let mut g = StartGate::new();
        assert_eq!(g.observe(1, 0), GateAction::Start(CamMode::Cyclic));
        g.started(CamMode::Cyclic);
        assert_eq!(g.observe(1, 100), GateAction::Hold);
        assert_eq!(g.observe(7, 200), GateAction::Stop);
    }

    #[test]
    fn restart_needs_100_us_off() {
        let mut g = StartGate::new();
        g.started(CamMode::Cyclic);
        assert_eq!(g.observe(0, 1000), GateAction::Stop);
        // Back on after 50 µs: refused, and stays refused while on.
        assert_eq!(g.observe(1, 1050), GateAction::Hold);
        assert_eq!(g.observe(1, 2000), GateAction::Hold);
        assert_eq!(g.observe(0, 2100), GateAction::Hold);
        assert_eq!(g.observe(1, 2200), GateAction::Start(CamMode::Cyclic));
    }

    #[test]
    fn switching_modes_directly_is_refused() {
        let mut g = StartGate::new();
        g.started(CamMode::Cyclic);
        assert_eq!(g.observe(2, 1000), GateAction::Stop);
        assert_eq!(g.observe(2, 5000), GateAction::Hold);
        assert_eq!(g.observe(0, 5100), GateAction::Hold);
        assert_eq!(g.observe(2, 5200), GateAction::Start(CamMode::Noncyclic));
    }

    #[test]
    fn a_pending_start_waits_without_losing_the_gap() {
        let mut g = StartGate::new();
        assert_eq!(g.observe(0, 500), GateAction::Hold);
        assert_eq!(g.observe(1, 1000), GateAction::Start(CamMode::Cyclic));
        // Not carried out (bad block); later ticks still offer it.
        assert_eq!(g.observe(1, 1010), GateAction::Start(CamMode::Cyclic));
    }
}
