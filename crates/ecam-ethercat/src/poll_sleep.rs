//! A wait for futures that run inside the link's polling loop, shared by
//! the segment's bring-up and the drives' start-up SDOs (its own file, so
//! neither imports the other for it).

use std::time::{Duration, Instant};

/// Waits `period` inside a future driven by [`crate::link::run`] (which polls
/// about every millisecond), without a timer of async-io's.
pub(crate) async fn async_io_free_sleep(period: Duration) {
    let until = Instant::now() + period;
    std::future::poll_fn(|_| {
        if Instant::now() >= until {
            std::task::Poll::Ready(())
        } else {
            std::task::Poll::Pending
        }
    })
    .await;
}
