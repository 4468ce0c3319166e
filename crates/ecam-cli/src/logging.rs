//! Log output on stderr with `tracing`: what the server (and any command)
//! tells its operator, at levels the operator picks.
//!
//! `RUST_LOG` (the `tracing-subscriber` filter syntax, e.g.
//! `RUST_LOG=ecam::modbus=debug`) wins when set; otherwise `-v`/`-q` move
//! the level from the default `info`: `-v` debug, `-vv` trace, `-q` warnings
//! and errors, `-qq` errors only. Errors that end a command are not logs:
//! `main` prints them as `ecam: …` whatever the level.

use tracing_subscriber::EnvFilter;

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
/// second call (tests) changes nothing.
pub fn init(verbose: u8, quiet: u8, extra: &[&str]) {
    let mut filter =
        EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new(level(verbose, quiet)));
    for directive in extra {
        if let Ok(directive) = directive.parse() {
            filter = filter.add_directive(directive);
        }
    }
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_ansi(std::io::IsTerminal::is_terminal(&std::io::stderr()))
        .try_init();
    // ethercrab's own log lines (target `ethercrab`).
    ecam_ethercat::log_bridge::install(tracing::level_filters::LevelFilter::current());
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
