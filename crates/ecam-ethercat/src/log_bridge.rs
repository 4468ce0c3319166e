//! ethercrab logs through the `log` crate; ecam's operator reads
//! `tracing` on stderr. This bridge hands every ethercrab record to
//! `tracing` under the target `ethercrab` (the module it came from as a
//! field), so `RUST_LOG=ethercrab=debug` shows the master's own account of
//! a bring-up or a lost frame.
//!
//! The bridge is installed with the level the subscriber lets through, so
//! a disabled level costs ethercrab one comparison.

use log::{Level, LevelFilter, Log, Metadata, Record};

struct Bridge;

impl Log for Bridge {
    fn enabled(&self, metadata: &Metadata<'_>) -> bool {
        metadata.level() <= log::max_level()
    }

    fn log(&self, record: &Record<'_>) {
        let module = record.target();
        let message = record.args();
        match record.level() {
            Level::Error => tracing::error!(target: "ethercrab", module, "{message}"),
            Level::Warn => tracing::warn!(target: "ethercrab", module, "{message}"),
            Level::Info => tracing::info!(target: "ethercrab", module, "{message}"),
            Level::Debug => tracing::debug!(target: "ethercrab", module, "{message}"),
            Level::Trace => tracing::trace!(target: "ethercrab", module, "{message}"),
        }
    }

    fn flush(&self) {}
}

static BRIDGE: Bridge = Bridge;

/// Routes `log` records (ethercrab's) into `tracing`, up to `level`
/// (`tracing::level_filters::LevelFilter::current()` after the subscriber
/// is installed). A second call only changes the level.
pub fn install(level: tracing::level_filters::LevelFilter) {
    let _ = log::set_logger(&BRIDGE);
    log::set_max_level(match level {
        tracing::level_filters::LevelFilter::OFF => LevelFilter::Off,
        tracing::level_filters::LevelFilter::ERROR => LevelFilter::Error,
        tracing::level_filters::LevelFilter::WARN => LevelFilter::Warn,
        tracing::level_filters::LevelFilter::INFO => LevelFilter::Info,
        tracing::level_filters::LevelFilter::DEBUG => LevelFilter::Debug,
        _ => LevelFilter::Trace,
    });
}
