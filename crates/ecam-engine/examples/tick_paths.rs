//! The ecam half of `scripts/bench-side-by-side`'s `tick-worst-instr`:
//! drives one axis through the paths of `tick` that cost most (a master
//! jump needing a table search, a seam, a table switch with a blend, a
//! ramp-in, stops, the first tick after engaging, faults, a master between
//! whole counts) and through a
//! stretch of steady ticks, calling every tick it measures through one
//! function, `instr_probe`, that does nothing else. Run under
//! `valgrind --tool=callgrind --collect-atstart=no
//! --toggle-collect='*instr_probe*' --dump-after='*instr_probe*'
//! --combine-dumps=yes`, each call becomes one dump holding that tick's
//! instructions and nothing else; the binary prints the path of each call,
//! in call order, one per line (`probe PATH`), so the script can pair the
//! two. Instruction counts are what noise cannot reach: the same binary
//! gives the same counts on a loaded machine. See docs/engine.md,
//! "Benchmarks".
//!
//! `--only SCENARIO` runs one scenario and `--probe N` measures only its
//! `N`th tick (to profile one tick: `callgrind_annotate` on a run without
//! the dumps). `--half-counts` gives every tick a master fraction of half
//! a count, as a coarse master's estimate does (every tick between whole
//! counts; the harness does not pass it: see docs/engine.md, "The
//! one-tick transitions").
//!
//! Without valgrind it runs the same ticks natively (a quick check that
//! every scenario does what its name says: each prints the state it ends
//! in after `end PATH`).

use std::hint::black_box;
use std::num::{NonZeroU32, NonZeroU64};
use std::sync::atomic::{AtomicUsize, Ordering};

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, AxisState, CamAxis, OffsetChange, RampDirection, RampIn, RampInLimits, SlaveAlign,
    StartMode, StopKind, SwitchAt, TickInput, TickOutput, Zoom,
};

#[path = "../benches/common/mod.rs"]
mod common;

/// Probes so far; `--probe N` measures only the `N`th (counted from 0),
/// so that a profile shows that one tick alone.
static PROBES: AtomicUsize = AtomicUsize::new(0);

fn only_probe() -> Option<usize> {
    std::env::args()
        .skip_while(|a| a != "--probe")
        .nth(1)
        .and_then(|n| n.parse().ok())
}

/// `--half-counts`: every tick half a count past the master's count.
fn half_counts() -> bool {
    static HALF: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    *HALF.get_or_init(|| std::env::args().any(|a| a == "--half-counts"))
}

/// Steady ticks measured for the reference mean.
const STEADY_TICKS: usize = 2000;

/// One measured tick. Kept out of line and free of anything but the tick,
/// so that its instructions are the tick's own (plus a call's frame).
#[inline(never)]
fn instr_probe(axis: &mut CamAxis<PointTable>, input: &TickInput) -> TickOutput {
    *axis.tick_in_place(black_box(input))
}

/// Runs ticks of one axis, measuring those it is asked to.
struct Driver {
    axis: CamAxis<PointTable>,
    master: i64,
    /// Master counts per tick.
    speed: i64,
}

impl Driver {
    fn new(config: AxisConfig) -> Result<Self, String> {
        let axis = CamAxis::new(table()?, config).map_err(|e| format!("axis: {e}"))?;
        Ok(Self {
            axis,
            master: 0,
            speed: common::MASTER_PER_TICK,
        })
    }

    fn input(&self) -> TickInput {
        TickInput {
            master_fraction: if half_counts() { 1 << 31 } else { 0 },
            ..TickInput::at(self.master, common::DT_US)
        }
    }

    /// One tick at the next master, not measured.
    fn run(&mut self) -> TickOutput {
        self.master += self.speed;
        let out = self.axis.tick(&self.input());
        // Anything a switch retired is dropped here, outside the tick.
        drop(self.axis.take_retired_curve());
        out
    }

    /// `n` unmeasured ticks.
    fn run_for(&mut self, n: usize) {
        for _ in 0..n {
            let _ = self.run();
        }
    }

    /// One measured tick at `input`.
    fn probe_at(&mut self, path: &str, input: &TickInput) -> TickOutput {
        let index = PROBES.fetch_add(1, Ordering::Relaxed);
        let out = if only_probe().is_none_or(|only| only == index) {
            println!("probe {path}");
            instr_probe(&mut self.axis, input)
        } else {
            *self.axis.tick_in_place(input)
        };
        drop(self.axis.take_retired_curve());
        out
    }

    /// One measured tick at the next master.
    fn probe(&mut self, path: &str) -> TickOutput {
        self.master += self.speed;
        let input = self.input();
        self.probe_at(path, &input)
    }

    /// Measured ticks while `more` holds for the last output, at most `limit`.
    fn probe_while(&mut self, path: &str, limit: usize, more: impl Fn(&TickOutput) -> bool) {
        for _ in 0..limit {
            let out = self.probe(path);
            if !more(&out) {
                return;
            }
        }
    }

    fn end(&self, path: &str) {
        println!("end {path} {:?}", self.axis.state());
    }
}

/// The benchmark's table (513 points, a stroke): the scenario of `tick-1`.
fn table() -> Result<PointTable, String> {
    common::stroke_table().ok_or_else(|| "benchmark table".to_string())
}

/// A second table for the switches: the benchmark's periodic cam.
fn other_table() -> Result<PointTable, String> {
    common::periodic_table().ok_or_else(|| "periodic table".to_string())
}

fn nonzero(n: u64) -> NonZeroU64 {
    NonZeroU64::new(n).unwrap_or(NonZeroU64::MIN)
}

/// An engaged axis of the `tick-1` scenario, settled for `warm` ticks.
fn engaged(config: AxisConfig, warm: usize) -> Result<Driver, String> {
    let mut d = Driver::new(config)?;
    d.axis.arm().map_err(|e| format!("arm: {e}"))?;
    d.run_for(warm.max(1));
    Ok(d)
}

/// Master counts per table cycle in the `tick-1` scenario (zoom 7/3).
fn cycle_counts() -> i64 {
    let span = (common::POINTS as i64 - 1) * common::STEP;
    span * 3 / 7
}

fn steady() -> Result<(), String> {
    let mut d = engaged(common::config(0), 1000)?;
    for _ in 0..STEADY_TICKS {
        d.probe("steady");
    }
    d.end("steady");
    Ok(())
}

fn fractions() -> Result<(), String> {
    // A settled cam followed between whole counts (an exact time base or
    // a coarse master's estimate): quarter, half and three-quarter counts.
    let mut d = engaged(common::config(0), 1000)?;
    for i in 0..200u32 {
        d.master += d.speed;
        let input = TickInput {
            master_fraction: 0x4000_0000u32.wrapping_mul(i % 3 + 1),
            ..d.input()
        };
        d.probe_at("between whole counts", &input);
    }
    d.end("between whole counts");
    Ok(())
}

fn seam() -> Result<(), String> {
    let mut d = engaged(common::config(0), 10)?;
    for _ in 0..3 {
        // Up to a few ticks before the next seam, then across it.
        let next = (d.master / cycle_counts() + 1) * cycle_counts();
        while d.master + 4 * d.speed < next {
            d.run();
        }
        d.probe_while("seam", 8, |_| true);
    }
    d.end("seam");
    Ok(())
}

fn jumps() -> Result<(), String> {
    let mut d = engaged(common::config(0), 10)?;
    // Jumps to far sections, forwards and backwards (no step limit set),
    // each a fresh search; then a few ticks to settle.
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    for _ in 0..64 {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        d.master += (x % (2 * cycle_counts() as u64)) as i64 - cycle_counts();
        d.probe_while("master jump (table search)", 2, |_| true);
    }
    d.end("master jump (table search)");
    Ok(())
}

fn first_ticks() -> Result<(), String> {
    // Immediate start: the tick after arm engages.
    let mut d = Driver::new(common::config(0))?;
    d.run_for(5);
    for _ in 0..8 {
        d.axis.arm().map_err(|e| format!("arm: {e}"))?;
        d.probe_while("first tick after engaging", 2, |_| true);
        d.axis.stop(StopKind::Immediate);
        d.run();
    }
    d.end("first tick after engaging");
    // Engaging at a master position the tick passes, nearest equivalent.
    let config = AxisConfig {
        slave_align: ecam_engine::SlaveAlign::NearestEquivalent,
        ..common::config(0)
    };
    let mut d = Driver::new(config)?;
    for _ in 0..8 {
        let position = d.master + 5 * d.speed + 3;
        let config = AxisConfig {
            start: StartMode::AtMasterPosition {
                position,
                after_edge: false,
            },
            ..config
        };
        d.axis
            .set_config(config)
            .map_err(|e| format!("config: {e}"))?;
        d.axis.arm().map_err(|e| format!("arm: {e}"))?;
        d.probe_while("engage at a master position", 8, |o| !o.events.engaged);
        d.probe("engage at a master position");
        d.axis.stop(StopKind::Immediate);
        d.run();
    }
    d.end("engage at a master position");
    Ok(())
}

fn ramp_ins() -> Result<(), String> {
    let config = AxisConfig {
        ramp_in: Some(RampIn {
            distance: nonzero(1300),
        }),
        ..common::config(0)
    };
    let mut d = Driver::new(config)?;
    d.run_for(5);
    d.axis.arm().map_err(|e| format!("arm: {e}"))?;
    d.probe_while("ramp-in", 200, |o| !o.following);
    d.end("ramp-in");

    // A relative slave: the cam is fitted to it, so the ramp has no gap
    // and catches up the cam's velocity only.
    let mut d = limited_ramp_in(common::config(0), -5000)?;
    d.probe_while("ramp-in under limits", 400, |o| !o.following);
    d.end("ramp-in under limits");

    // The slave ahead of the cam (the output offset kept, not fitted to
    // the slave): the cam is behind, so the positive direction adds whole
    // strokes to it, and the ramp closes a gap.
    let offset = AxisConfig {
        slave_align: SlaveAlign::Offset(0),
        ..common::config(0)
    };
    let mut d = limited_ramp_in(offset, 40_000)?;
    d.probe_while("ramp-in under limits, strokes added", 400, |o| !o.following);
    d.end("ramp-in under limits, strokes added");
    Ok(())
}

/// An axis of `config` armed for a ramp-in under velocity, acceleration
/// and jerk limits, positive direction only, from slave `slave`, the
/// master running for 20 ticks first (so its speed is known).
fn limited_ramp_in(config: AxisConfig, slave: i64) -> Result<Driver, String> {
    let mut d = Driver::new(config)?;
    d.axis.set_ramp_in_limits(Some(RampInLimits {
        max_velocity: NonZeroU32::new(2_000_000).unwrap_or(NonZeroU32::MIN),
        max_acceleration: nonzero(400_000_000),
        direction: RampDirection::Positive,
        max_jerk: Some(nonzero(100_000_000_000)),
    }));
    d.run_for(20);
    d.axis
        .set_slave_position(slave)
        .map_err(|e| format!("slave: {e}"))?;
    d.axis.arm().map_err(|e| format!("arm: {e}"))?;
    Ok(d)
}

fn switches() -> Result<(), String> {
    let mut d = engaged(common::config(0), 50)?;
    for blend in [None, Some(nonzero(1300))] {
        d.axis
            .switch_curve(other_table()?, SwitchAt::Now { blend })
            .map_err(|e| format!("switch: {e}"))?;
        d.probe_while("table switch now, blended", 200, |o| !o.following);
        d.run_for(5);
        d.axis
            .switch_curve(
                table()?,
                SwitchAt::MasterPosition {
                    position: d.master + 3 * d.speed + 5,
                    blend,
                },
            )
            .map_err(|e| format!("switch: {e}"))?;
        d.probe_while("table switch at a position, blended", 200, |o| {
            !o.events.table_switched
        });
        d.probe_while("table switch at a position, blended", 200, |o| !o.following);
        d.run_for(5);
    }
    d.end("table switch");
    // At the seam, blended: queued, then across the seam.
    let mut d = engaged(common::config(0), 10)?;
    for _ in 0..2 {
        d.axis
            .switch_curve(
                table()?,
                SwitchAt::NextSeam {
                    blend: Some(nonzero(1300)),
                },
            )
            .map_err(|e| format!("switch: {e}"))?;
        let next = (d.master / cycle_counts() + 1) * cycle_counts();
        while d.master + 4 * d.speed < next {
            d.run();
        }
        d.probe_while("table switch at the seam, blended", 300, |o| {
            !o.events.table_switched
        });
        d.probe_while("table switch at the seam, blended", 300, |o| !o.following);
        d.run_for(5);
    }
    d.end("table switch at the seam, blended");
    Ok(())
}

fn changes() -> Result<(), String> {
    let mut d = engaged(common::config(0), 50)?;
    d.axis
        .change_offsets(OffsetChange {
            master: 700,
            slave: -300,
            distance: nonzero(1300),
        })
        .map_err(|e| format!("offsets: {e}"))?;
    d.probe_while("offset change", 300, |o| !o.following);
    d.run_for(5);
    d.axis
        .change_slave_scaling(Zoom::new(3, 2).unwrap_or_default(), nonzero(1300))
        .map_err(|e| format!("scaling: {e}"))?;
    d.probe_while("slave scaling change", 300, |o| !o.following);
    d.run_for(5);
    d.axis
        .change_master_scaling(Zoom::new(5, 2).unwrap_or_default(), Some(nonzero(1300)))
        .map_err(|e| format!("scaling: {e}"))?;
    d.probe_while("master scaling change", 300, |o| !o.following);
    d.end("changes");
    Ok(())
}

fn stops() -> Result<(), String> {
    // End of cycle, asked for near its end: the ticks to the seam.
    let mut d = engaged(common::config(0), 10)?;
    let next = (d.master / cycle_counts() + 1) * cycle_counts();
    while d.master + 40 * d.speed < next {
        d.run();
    }
    d.axis.stop(StopKind::EndOfCycle);
    d.probe_while("end-of-cycle stop", 100, |o| o.state != AxisState::Finished);
    d.end("end-of-cycle stop");
    // Immediate: the tick that reports it.
    let mut d = engaged(common::config(0), 10)?;
    d.axis.stop(StopKind::Immediate);
    d.probe("immediate stop");
    d.end("immediate stop");
    // Cam-out at velocity, then a decelerating halt to rest.
    let mut d = engaged(common::config(0), 10)?;
    d.axis
        .cam_out_at_velocity()
        .map_err(|e| format!("cam out: {e}"))?;
    d.probe_while("cam-out at velocity", 5, |_| true);
    d.axis
        .stop_decelerating(nonzero(5_000_000))
        .map_err(|e| format!("halt: {e}"))?;
    d.probe_while("decelerating halt", 500, |o| o.state == AxisState::Velocity);
    d.end("decelerating halt");
    Ok(())
}

fn faults() -> Result<(), String> {
    let config = AxisConfig {
        max_master_step: Some(nonzero(100)),
        ..common::config(0)
    };
    let mut d = engaged(config, 10)?;
    d.master += 5000;
    d.probe("fault (master step)");
    d.end("fault (master step)");
    let mut d = engaged(common::config(0), 10)?;
    d.master += d.speed;
    let input = TickInput {
        output_enabled: false,
        ..d.input()
    };
    d.probe_at("output inhibit", &input);
    d.end("output inhibit");
    Ok(())
}

/// One scenario: drives its axes and measures the ticks of its path.
type Scenario = fn() -> Result<(), String>;

/// The scenarios, by name.
const SCENARIOS: [(&str, Scenario); 10] = [
    ("steady", steady),
    ("fractions", fractions),
    ("seam", seam),
    ("jumps", jumps),
    ("first_ticks", first_ticks),
    ("ramp_ins", ramp_ins),
    ("switches", switches),
    ("changes", changes),
    ("stops", stops),
    ("faults", faults),
];

fn main() -> Result<(), String> {
    // `--only NAME` runs one scenario (for profiling it alone).
    let only = std::env::args().skip_while(|a| a != "--only").nth(1);
    for (name, scenario) in SCENARIOS {
        if only.as_deref().is_none_or(|o| o == name) {
            scenario()?;
        }
    }
    Ok(())
}
