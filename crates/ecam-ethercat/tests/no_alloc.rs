//! The real-time cycle allocates nothing: a counting global allocator
//! watches this thread while a cam line cycles on emulated drives (frames
//! sent and received on this thread, replies lost now and then, a drive
//! fault and the quick stop it brings), the distributed-clock lock steps
//! and the status image is published — issue 24's "no allocation in the
//! cycle", measured as the engine's `tick` is.
//!
//! Its own test binary: a `#[global_allocator]` replaces the allocator of
//! the whole binary it is linked into, so it stays out of `tests/it`.
#![allow(unsafe_code)] // the GlobalAlloc wrapper below; test-only
#![allow(missing_docs, clippy::unwrap_used, clippy::expect_used)]

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Duration;

use ecam_core::PointTable;
use ecam_engine::{AxisConfig, CamAxis, Coupling, SlaveAlign};
use ecam_ethercat::dc::Sync0Lock;
use ecam_ethercat::emulation::{DriveBehaviour, EmulatedSegment, Impairment};
use ecam_ethercat::line::{CamDrive, CamLine, LineState, Master};
use ecam_ethercat::monitor::{DriveCell, LineCounters, LineMonitor};
use ecam_ethercat::{Segment, SegmentConfig, Transport};

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

fn axis() -> CamAxis<PointTable> {
    let table = PointTable::from_pairs(&[(0, 0), (250, 900), (600, 100), (1000, 1400)]).unwrap();
    CamAxis::new(
        table,
        AxisConfig {
            coupling: Coupling::Repeat { min_stroke: 1 },
            slave_align: SlaveAlign::Relative,
            ..AxisConfig::default()
        },
    )
    .unwrap()
}

#[test]
fn the_cycle_allocates_nothing() {
    let mut emulation = EmulatedSegment::new(4, DriveBehaviour::default());
    emulation.set_watchdog(None);
    let emulation = Arc::new(Mutex::new(emulation));
    let config = SegmentConfig {
        reply_timeout: Duration::from_millis(100),
        frame_timeout: Duration::from_millis(250),
        dc_static_sync_iterations: 20,
        ..SegmentConfig::for_cycle(Duration::from_millis(1))
    };
    let segment = Segment::bring_up(Transport::Emulated(Arc::clone(&emulation)), config).unwrap();
    let axes = (0..4)
        .map(|drive| CamDrive {
            axis: axis(),
            drive,
            master: if drive == 3 {
                Master::DriveActual { position: 0 }
            } else {
                Master::Virtual
            },
        })
        .collect();
    let mut line = CamLine::new(segment, axes, 50, Duration::from_millis(30)).unwrap();
    line.virtual_speed = 13;
    let monitor = LineMonitor::new(4);
    let mut lock = Sync0Lock::new(config.cycle, config.sync0_shift);
    let mut counters = LineCounters::default();
    line.start().unwrap();
    for _ in 0..50 {
        line.cycle().unwrap();
    }
    assert_eq!(line.state(), LineState::Running);

    let mut run = |line: &mut CamLine<PointTable>, cycles: usize| {
        for _ in 0..cycles {
            let report = line.cycle().unwrap();
            counters.cycles += 1;
            if report.bus.frame_lost {
                counters.lost_cycles += 1;
            } else {
                std::hint::black_box(lock.step(report.bus.dc_system_time, true));
            }
            let cells = line
                .segment()
                .drives()
                .iter()
                .zip(line.segment().al_states())
                .map(|(d, al)| DriveCell {
                    state: d.state(),
                    al_state: *al,
                    actual: d.actual(),
                    missed: d.missed_cycles(),
                    ..DriveCell::default()
                });
            monitor.publish(line.state(), &counters, cells, line.faults(), 0);
            // Between cycles: the faulted drive's emergency is read.
            line.acyclic_step(Duration::from_millis(20));
        }
    };

    // The counter sees this thread's allocations...
    WATCHING.with(|w| w.set(true));
    drop(std::hint::black_box(Box::new(7u64)));
    WATCHING.with(|w| w.set(false));
    assert_eq!(ALLOCATIONS.swap(0, Ordering::SeqCst), 1);

    // ...and none while the line runs, loses replies, faults and stops.
    emulation.lock().unwrap().impair(Impairment {
        drop_every: 37,
        ..Impairment::default()
    });
    WATCHING.with(|w| w.set(true));
    run(&mut line, 2000);
    WATCHING.with(|w| w.set(false));
    emulation
        .lock()
        .unwrap()
        .esc_mut(2)
        .unwrap()
        .drive_mut()
        .inject_fault(0x2310);
    WATCHING.with(|w| w.set(true));
    run(&mut line, 200);
    WATCHING.with(|w| w.set(false));
    assert_eq!(line.state(), LineState::Faulted);
    assert!(counters.lost_cycles > 40, "{counters:?}");
    assert!(
        line.faults().iter().any(|f| f.emergency.is_some()),
        "{:?}",
        line.faults()
    );

    assert_eq!(ALLOCATIONS.load(Ordering::SeqCst), 0);
}
