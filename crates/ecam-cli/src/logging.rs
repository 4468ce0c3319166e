//! Log output on stderr with `tracing`: what the server (and any command)
//! tells its operator, at levels the operator picks.
//!
//! `RUST_LOG` (the `tracing-subscriber` filter syntax, e.g.
//! `RUST_LOG=ecam::modbus=debug`) wins when set; otherwise `-v`/`-q` move
//! the level from the default `info`: `-v` debug, `-vv` trace, `-q` warnings
//! and errors, `-qq` errors only. Every command logs: what it reads and
//! runs at `debug` (`-v`), what it reports beside its output (a generator's
//! extra results) at `info` (`-q` hides it), warnings (a PLC program's
//! operation errors) at `warn`. Errors that end a command are not logs:
//! `main` prints them as `ecam: …` whatever the level.

use tracing::Level;
use tracing_subscriber::EnvFilter;
use tracing_subscriber::fmt::FmtContext;
use tracing_subscriber::fmt::format::{self, FormatEvent, FormatFields};
use tracing_subscriber::registry::LookupSpan;

/// The level `-v`/`-q` ask for, counted from `info`.
pub fn level(verbose: u8, quiet: u8) -> &'static str {
    match i16::from(verbose) - i16::from(quiet) {
        i16::MIN..=-2 => "error",
        -1 => "warn",
        0 => "info",
        1 => "debug",
        _ => "trace",
    }
}

/// Installs the stderr subscriber; `extra` adds filter directives (such as
/// `ecam serve --trace-modbus`'s) to `RUST_LOG` or the flags' level. A
/// server's log (`timed`) carries times, levels and targets; a command's
/// messages are plain lines (`warning:` before a warning). A second call
/// (tests) changes nothing.
pub fn init(verbose: u8, quiet: u8, extra: &[&str], timed: bool) {
    let mut filter =
        EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new(level(verbose, quiet)));
    for directive in extra {
        if let Ok(directive) = directive.parse() {
            filter = filter.add_directive(directive);
        }
    }
    let ansi = std::io::IsTerminal::is_terminal(&std::io::stderr());
    let builder = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(ansi);
    let _ = if timed {
        builder.try_init()
    } else {
        builder.event_format(Plain).try_init()
    };
    // ethercrab's own log lines (target `ethercrab`).
    ecam_ethercat::log_bridge::install(tracing::level_filters::LevelFilter::current());
}

/// A command's message as a plain line: the text alone at `info`, after
/// `ecam: warning:` / `ecam: error:` / `debug:` / `trace:` otherwise.
struct Plain;

impl<S, N> FormatEvent<S, N> for Plain
where
    S: tracing::Subscriber + for<'a> LookupSpan<'a>,
    N: for<'a> FormatFields<'a> + 'static,
{
    fn format_event(
        &self,
        ctx: &FmtContext<'_, S, N>,
        mut writer: format::Writer<'_>,
        event: &tracing::Event<'_>,
    ) -> std::fmt::Result {
        let prefix = match *event.metadata().level() {
            Level::ERROR => "ecam: error: ",
            Level::WARN => "ecam: warning: ",
            Level::INFO => "",
            Level::DEBUG => "debug: ",
            Level::TRACE => "trace: ",
        };
        write!(writer, "{prefix}")?;
        ctx.field_format().format_fields(writer.by_ref(), event)?;
        writeln!(writer)
    }
}

#[cfg(test)]
mod tests {
    use super::level;

    #[test]
    fn flags_move_the_level_from_info() {
        assert_eq!(level(0, 0), "info");
        assert_eq!(level(1, 0), "debug");
        assert_eq!(level(3, 0), "trace");
        assert_eq!(level(0, 1), "warn");
        assert_eq!(level(0, 5), "error");
    }
}
