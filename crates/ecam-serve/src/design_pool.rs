//! Where design requests (generators, laws, key points: the HTTP design
//! API) are computed: a fixed pool of [`DESIGN_WORKERS`] threads at the
//! lowest CPU priority, with at most [`DESIGN_QUEUE`] requests waiting.
//!
//! - **Bounded**: a request that finds the queue full is refused at once
//!   ([`Busy`], 503); what runs at once is the workers' count, so memory
//!   is at most that many answers (each bounded by the design API's own
//!   point limit, `ecam_design::MAX_DESIGN_POINTS`) plus the waiting
//!   bodies.
//! - **Cancelled**: each request gets a work budget
//!   ([`ecam_core::budget::Budget::per_run`]) that stops as soon as its
//!   [`Ticket`] is dropped: when the server gives up at the deadline, or
//!   when the client leaves (its request's future is dropped with it).
//!   A request given up while it waits is never started.
//! - **Never on the scan's time**: the workers run at nice 19, so the
//!   scan thread and the network threads (nice 0) take the CPU first; a
//!   burst of design work slows design answers, not the PLC.
//!
//! Sans-IO for the caller: [`DesignPool::submit`] hands the outcome to a
//! callback, which an async server turns into a future.

use std::collections::VecDeque;
use std::sync::atomic::{AtomicBool, AtomicU64, AtomicUsize, Ordering};
use std::sync::{Arc, Condvar, Mutex};

use ecam_core::budget::{Budget, OverBudget};
use serde_json::{Value, json};

use crate::limits::{DESIGN_QUEUE, DESIGN_WORKERS};
use crate::sync::lock;

type Job = Box<dyn FnOnce() + Send>;

/// Counters of the pool, for `GET /api/status`.
#[derive(Debug, Default)]
struct Counters {
    running: AtomicUsize,
    done: AtomicU64,
    cancelled: AtomicU64,
    refused: AtomicU64,
}

struct Pool {
    queue: Mutex<VecDeque<Job>>,
    work: Condvar,
    capacity: usize,
    workers: usize,
    counters: Counters,
}

/// The design requests' workers (see the module's documentation).
#[derive(Clone)]
pub struct DesignPool {
    pool: Arc<Pool>,
}

/// The queue is full: answer 503, try again later.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Busy;

impl std::fmt::Display for Busy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "the designer is busy ({DESIGN_WORKERS} requests computing, {DESIGN_QUEUE} waiting): try again in a moment"
        )
    }
}

impl std::error::Error for Busy {}

/// How a request ended.
#[derive(Debug, PartialEq)]
pub enum Outcome<T> {
    /// Its answer.
    Done(T),
    /// Given up (its ticket was dropped) before or while it ran.
    Cancelled,
}

/// A request in the pool: dropping it gives the request up (its work
/// stops at its next look at the budget, or never starts).
#[derive(Debug)]
pub struct Ticket {
    cancel: Arc<AtomicBool>,
}

impl Drop for Ticket {
    fn drop(&mut self) {
        self.cancel.store(true, Ordering::Relaxed);
    }
}

impl DesignPool {
    /// Starts [`DESIGN_WORKERS`] workers taking at most [`DESIGN_QUEUE`]
    /// waiting requests.
    ///
    /// # Errors
    /// A worker thread could not be started.
    pub fn start() -> std::io::Result<Self> {
        Self::with(DESIGN_WORKERS, DESIGN_QUEUE)
    }

    /// A pool of `workers` threads and `capacity` waiting requests.
    ///
    /// # Errors
    /// A worker thread could not be started.
    pub fn with(workers: usize, capacity: usize) -> std::io::Result<Self> {
        let pool = Arc::new(Pool {
            queue: Mutex::new(VecDeque::new()),
            work: Condvar::new(),
            capacity,
            workers,
            counters: Counters::default(),
        });
        for n in 0..workers {
            let pool = Arc::clone(&pool);
            std::thread::Builder::new()
                .name(format!("design-{n}"))
                .spawn(move || work(&pool))?;
        }
        Ok(Self { pool })
    }

    /// Queues `work`; `done` gets its outcome on a worker thread. `work`
    /// takes its budget: it must spend it as it goes (or at least
    /// [`Budget::check`] it) so that a given-up request stops.
    ///
    /// # Errors
    /// [`Busy`] when the queue is full (nothing queued, `done` dropped).
    pub fn submit<T: 'static>(
        &self,
        work: impl FnOnce(&mut Budget) -> T + Send + 'static,
        done: impl FnOnce(Outcome<T>) + Send + 'static,
    ) -> Result<Ticket, Busy> {
        let cancel = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&cancel);
        let pool = Arc::clone(&self.pool);
        let job: Job = Box::new(move || {
            let counters = &pool.counters;
            let mut budget = Budget::per_run().cancelled_by(flag);
            if budget.check() == Err(OverBudget::Cancelled) {
                counters.cancelled.fetch_add(1, Ordering::Relaxed);
                done(Outcome::Cancelled);
                return;
            }
            counters.running.fetch_add(1, Ordering::Relaxed);
            let out = work(&mut budget);
            counters.running.fetch_sub(1, Ordering::Relaxed);
            if budget.check() == Err(OverBudget::Cancelled) {
                counters.cancelled.fetch_add(1, Ordering::Relaxed);
                done(Outcome::Cancelled);
            } else {
                counters.done.fetch_add(1, Ordering::Relaxed);
                done(Outcome::Done(out));
            }
        });
        let mut queue = lock(&self.pool.queue);
        if queue.len() >= self.pool.capacity {
            self.pool.counters.refused.fetch_add(1, Ordering::Relaxed);
            return Err(Busy);
        }
        queue.push_back(job);
        self.pool.work.notify_one();
        Ok(Ticket { cancel })
    }

    /// For `GET /api/status`: workers, queue, and the requests done,
    /// cancelled and refused since the start.
    pub fn json(&self) -> Value {
        let c = &self.pool.counters;
        json!({
            "workers": self.pool.workers,
            "running": c.running.load(Ordering::Relaxed),
            "waiting": lock(&self.pool.queue).len(),
            "queue": self.pool.capacity,
            "done": c.done.load(Ordering::Relaxed),
            "cancelled": c.cancelled.load(Ordering::Relaxed),
            "refused_busy": c.refused.load(Ordering::Relaxed),
        })
    }
}

/// A worker: lowest priority, then requests one after the other.
fn work(pool: &Pool) {
    // Without it the work still runs, only at the scan's priority.
    let _ = thread_priority::set_current_thread_priority(thread_priority::ThreadPriority::Min);
    loop {
        let job = {
            let mut queue = lock(&pool.queue);
            loop {
                match queue.pop_front() {
                    Some(job) => break job,
                    None => {
                        queue = pool
                            .work
                            .wait(queue)
                            .unwrap_or_else(std::sync::PoisonError::into_inner);
                    }
                }
            }
        };
        job();
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::expect_used)]
mod tests {
    use std::sync::mpsc;
    use std::time::Duration;

    use super::*;

    const WAIT: Duration = Duration::from_secs(20);

    /// Work that spends its budget until it is given up.
    fn endless(budget: &mut Budget) -> u64 {
        while budget.spend(1).is_ok() {
            std::thread::sleep(Duration::from_millis(1));
        }
        budget.used()
    }

    /// The calling thread's nice value (Linux: field 19 of its stat).
    #[cfg(target_os = "linux")]
    fn nice() -> i64 {
        let stat = std::fs::read_to_string("/proc/thread-self/stat").unwrap();
        let after_name = &stat[stat.rfind(')').unwrap() + 2..];
        after_name.split(' ').nth(16).unwrap().parse().unwrap()
    }

    #[test]
    fn work_runs_at_the_lowest_priority_and_answers() {
        let pool = DesignPool::with(1, 2).unwrap();
        let (tx, rx) = mpsc::channel();
        #[cfg(target_os = "linux")]
        let probe = |_: &mut Budget| nice();
        #[cfg(not(target_os = "linux"))]
        let probe = |_: &mut Budget| 19;
        let _ticket = pool
            .submit(probe, move |out| tx.send(out).unwrap())
            .unwrap();
        assert_eq!(rx.recv_timeout(WAIT).unwrap(), Outcome::Done(19));
        assert_eq!(pool.json()["done"], 1);
    }

    #[test]
    fn a_dropped_ticket_stops_the_work_and_a_full_queue_refuses() {
        let pool = DesignPool::with(1, 1).unwrap();
        let (tx, rx) = mpsc::channel();
        let first_tx = tx.clone();
        let first = pool
            .submit(endless, move |out| first_tx.send(out).unwrap())
            .unwrap();
        // Wait until it runs, then fill the queue.
        while pool.json()["running"] != 1 {
            std::thread::sleep(Duration::from_millis(5));
        }
        let second_tx = tx.clone();
        let second = pool
            .submit(endless, move |out| second_tx.send(out).unwrap())
            .unwrap();
        assert_eq!(pool.submit(endless, |_| {}).unwrap_err(), Busy);
        // Given up while waiting: never started.
        drop(second);
        drop(first);
        let outcomes = [
            rx.recv_timeout(WAIT).unwrap(),
            rx.recv_timeout(WAIT).unwrap(),
        ];
        assert_eq!(outcomes, [Outcome::Cancelled, Outcome::Cancelled]);
        let status = pool.json();
        assert_eq!(
            (status["cancelled"].clone(), status["refused_busy"].clone()),
            (json!(2), json!(1))
        );
        assert_eq!(status["running"], 0);
    }
}
