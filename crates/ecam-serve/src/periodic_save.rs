//! The thread that keeps latched values saved while the server runs (what
//! is saved: [`retain`](crate::retain)). Its own file because it drives
//! the shared state, which itself uses the retention rules: kept beside
//! them it would make the two import each other.

use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use crate::retain::{LatchedImage, SAVE_PERIOD};
use crate::state::{Event, Shared};

/// Saves the latched values every [`SAVE_PERIOD`] until `stop` is set
/// (the caller saves once more after the scan loop has stopped), on the
/// calling thread. A failing save is reported once as
/// [`Event::LatchedSaveFailing`], and [`Event::LatchedSavesResumed`] when
/// saves work again.
pub fn save_latched_periodically(shared: &Shared, stop: &AtomicBool) {
    let mut image = LatchedImage::new();
    let mut next = Instant::now() + SAVE_PERIOD;
    let mut failing = false;
    while !stop.load(Ordering::Relaxed) {
        let now = Instant::now();
        if now < next {
            // Short naps keep `stop` responsive.
            std::thread::sleep((next - now).min(Duration::from_millis(50)));
            continue;
        }
        next = now + SAVE_PERIOD;
        match shared.save_latched(&mut image) {
            Ok(_) if failing => {
                failing = false;
                shared.report(Event::LatchedSavesResumed);
            }
            Ok(_) => {}
            Err(err) if !failing => {
                failing = true;
                shared.report(Event::LatchedSaveFailing(err));
            }
            Err(_) => {}
        }
    }
}
