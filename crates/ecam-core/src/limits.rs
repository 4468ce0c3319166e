//! The bounds on the work one request may ask for, shared by the command
//! line, parameter and scenario files, scripts and the HTTP API, so that no
//! input can make ecam allocate without limit or run for ever. Each is far
//! above any real cam and documented in `docs/cli.md` ("Limits").

/// Most points a sampled or generated table may have (`ecam law --points`,
/// the `function` generator). A DECAM table holds 512; a design table of a
/// million points is already far finer than any drive can follow.
pub const MAX_TABLE_POINTS: usize = 1_000_000;

/// Largest table file `ecam_core::io::read` reads (64 MiB): far above a
/// million points as text, so reading is bounded before parsing starts.
pub const MAX_TABLE_FILE_BYTES: u64 = 64 * 1024 * 1024;

/// Longest expression the `function` generator parses, in bytes.
pub const MAX_EXPRESSION_LEN: usize = 4_096;

/// The work one run may do in all, in the work units of
/// the work budget (`ecam_core::budget`): a command (`ecam plc run`, a script, a scenario, a
/// generator) or one design request of `ecam serve`. 10⁹ units are 10⁸
/// control cycles, or 10⁹ instructions or expression terms.
pub const MAX_RUN_WORK: u64 = 1_000_000_000;

/// Most control cycles one simulated run may take: `ecam plc run`'s
/// hardware ticks, a script's `Tick`s in total, a scenario's ticks (the
/// whole [`MAX_RUN_WORK`]). 10⁸ ticks are 2.8 hours of 100 µs cycles.
pub const MAX_SIMULATED_TICKS: u64 = MAX_RUN_WORK / CYCLE_WORK;

/// Work units one control cycle costs ([`crate::budget`]).
pub const CYCLE_WORK: u64 = 10;
/// Work units one instruction, or one expression term at one point, costs.
pub const STEP_WORK: u64 = 1;
