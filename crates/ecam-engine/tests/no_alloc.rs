//! `tick` allocates nothing: a counting global allocator watches this
//! thread while axes of every mode run, start, stop and fault.
//!
//! Its own test binary: a `#[global_allocator]` replaces the allocator of
//! the whole binary it is linked into, so it stays out of `tests/it`.
#![allow(unsafe_code)] // the GlobalAlloc wrapper below; test-only
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::num::{NonZeroU32, NonZeroU64};
use std::sync::atomic::{AtomicUsize, Ordering};

use ecam_core::PointTable;
use ecam_engine::{
    AxisConfig, CamAxis, Compare, Coupling, MasterAlign, MissedActivation, OffsetChange,
    RampDirection, RampIn, RampInLimits, SlaveAlign, StartMode, StopKind, SwitchAt, SyncWindow,
    TickInput, Zoom,
};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    static WATCHING: Cell<bool> = const { Cell::new(false) };
}

fn note() {
    if WATCHING.try_with(Cell::get).unwrap_or(false) {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
    }
}

// SAFETY: every call is forwarded unchanged to the system allocator; the
// wrapper only counts.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc(layout) }
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        note();
        // SAFETY: same contract as the caller's.
        unsafe { System.alloc_zeroed(layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        note();
        // SAFETY: same contract as the caller's.
        unsafe { System.realloc(ptr, layout, new_size) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as the caller's.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn configs() -> Vec<AxisConfig> {
    let windows = [
        SyncWindow::new(100, 900),
        SyncWindow::new(0, 50),
        SyncWindow::OFF,
        SyncWindow::new(500, 400),
    ];
    let base = AxisConfig {
        sync_windows: windows,
        max_frequency_hz: 50_000,
        ..AxisConfig::default()
    };
    vec![
        base,
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            master_zoom: Zoom::new(7, 3).unwrap(),
            slave_zoom: Zoom::new(5, 2).unwrap(),
            slave_align: SlaveAlign::Relative,
            ..base
        },
        AxisConfig {
            coupling: Coupling::OneShot { repeats: 2 },
            start: StartMode::AfterDelay {
                counts: 300,
                after_edge: true,
            },
            master_align: MasterAlign::StartAt(0),
            ..base
        },
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            single_turn: NonZeroU64::new(1000),
            slave_align: SlaveAlign::NearestEquivalent,
            start: StartMode::AtMasterPosition {
                position: 2500,
                after_edge: false,
            },
            ..base
        },
        AxisConfig {
            coupling: Coupling::Normal,
            start: StartMode::Breakpoint {
                compare: Compare::AtLeast,
                value: 40,
            },
            ramp_in: NonZeroU64::new(500).map(|distance| RampIn { distance }),
            ..base
        },
    ]
}

#[test]
fn tick_allocates_nothing() {
    let table = PointTable::from_pairs(&[(0, 0), (250, 900), (600, 100), (1000, 1400)]).unwrap();
    let mut axes: Vec<CamAxis<PointTable>> = configs()
        .into_iter()
        .map(|c| CamAxis::new(table.clone(), c).unwrap())
        .collect();
    let mut masters: Vec<i64> = (0..3000).map(|i| (i * 37) % 7919 - 1000).collect();
    masters.extend((0..500).map(|i| i64::from(i) * 1_000_000_007));
    masters.push(i64::MAX);
    masters.push(i64::MIN);
    let mut outputs = 0i64;

    // The counter sees this thread's allocations...
    WATCHING.with(|w| w.set(true));
    drop(std::hint::black_box(Box::new(7u64)));
    WATCHING.with(|w| w.set(false));
    assert_eq!(ALLOCATIONS.swap(0, Ordering::SeqCst), 1);

    // ...and none while the axes run.
    WATCHING.with(|w| w.set(true));
    for (n, axis) in axes.iter_mut().enumerate() {
        // Every other axis ramps in under limits, in one direction.
        if n % 2 == 1 {
            axis.set_ramp_in_limits(Some(RampInLimits {
                max_jerk: NonZeroU64::new(1_000_000_000),
                max_velocity: NonZeroU32::new(100_000).unwrap(),
                max_acceleration: NonZeroU64::new(10_000_000).unwrap(),
                direction: RampDirection::Positive,
            }));
            axis.set_missed_activation(MissedActivation::NextPass);
        }
        axis.arm().ok();
        for (i, &master) in masters.iter().enumerate() {
            let input = TickInput {
                master,
                master_fraction: 0,
                start_input: i % 40 > 20,
                watch: master,
                dt_us: 100,
                output_enabled: i % 997 != 0,
            };
            let out = axis.tick(&input);
            outputs = outputs.wrapping_add(out.pulses);
            match i % 701 {
                5 => axis.stop(StopKind::EndOfCycle),
                300 => axis.stop(StopKind::Immediate),
                // Out of the cam at velocity, then a decelerating stop.
                250 => {
                    axis.cam_out_at_velocity().ok();
                }
                270 => {
                    axis.stop_decelerating(NonZeroU64::new(1_000_000).unwrap())
                        .ok();
                }
                301 | 320 => {
                    axis.arm().ok();
                }
                500 => {
                    axis.change_offsets(OffsetChange {
                        master: 37,
                        slave: -250,
                        distance: NonZeroU64::new(400).unwrap(),
                    })
                    .ok();
                }
                // Table switches: the new table is built (and the old one
                // taken back) outside the watch; only ticks are watched.
                100 | 200 | 400 => {
                    WATCHING.with(|w| w.set(false));
                    let at = match i % 701 {
                        100 => SwitchAt::Now {
                            blend: NonZeroU64::new(300),
                        },
                        200 => SwitchAt::MasterPosition {
                            position: master.saturating_add(50),
                            blend: NonZeroU64::new(200),
                        },
                        _ => SwitchAt::Now { blend: None },
                    };
                    axis.switch_curve(table.clone(), at).ok();
                    drop(axis.take_retired_curve());
                    WATCHING.with(|w| w.set(true));
                }
                _ => {}
            }
        }
    }
    WATCHING.with(|w| w.set(false));

    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
    // Keep the results alive so nothing is optimised away.
    std::hint::black_box(outputs);
}
