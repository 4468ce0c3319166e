//! `ecam`: the command line of the ecam electronic cam system.
//!
//! Thin glue: every subcommand parses its arguments and calls into the
//! library crates. The output formats of `law`, `plc run`, `pmd run`,
//! `mc run` and `simulate` are contracts (see `docs/architecture.md`).

mod cmd;
mod generate;
mod logging;
mod paths;
mod progress;
mod serve;
mod signals;
mod values;

use clap::{ArgAction, Parser, Subcommand};

/// Electronic cam design, simulation and PLC / motion-processor emulation.
#[derive(Parser)]
#[command(name = "ecam", version, about)]
pub struct Cli {
    /// More log output on stderr: -v debug, -vv trace (RUST_LOG, if set, wins).
    #[arg(short, long, action = ArgAction::Count, global = true)]
    verbose: u8,
    /// Less log output on stderr: -q warnings and errors, -qq errors only.
    #[arg(short, long, action = ArgAction::Count, global = true, conflicts_with = "verbose")]
    quiet: u8,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Normalised motion laws: list them, or print one as CSV.
    Law(cmd::law::Args),
    /// Design cam tables: generate, summarise, plot.
    #[command(subcommand)]
    Table(cmd::table::Command),
    /// Run a scenario file through the engine in simulated time.
    Simulate(cmd::simulate::Args),
    /// The LX3V PLC face: run instruction-list programs.
    #[command(subcommand)]
    Plc(cmd::plc::Command),
    /// The motion-processor face: run command scripts.
    #[command(subcommand)]
    Pmd(cmd::pmd::Command),
    /// The motion-controller face (Normal / Periodic / Repeat cams): run scripts.
    #[command(subcommand)]
    Mc(cmd::mc::Command),
    /// Run the PLC in real time behind Modbus TCP and HTTP (API + designer page).
    Serve(cmd::serve::Args),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell).
    Completions(cmd::install::CompletionsArgs),
    /// Print the man page (roff), e.g. `ecam man > ecam.1`.
    Man(cmd::install::ManArgs),
    /// Cams on CiA 402 servo drives over EtherCAT (real or emulated).
    #[command(subcommand)]
    Ethercat(cmd::ethercat::Command),
}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    let extra: &[&str] = match &cli.command {
        Command::Serve(args) if args.trace_modbus => &["ecam::modbus::traffic=trace"],
        _ => &[],
    };
    // A server's log is read later, with times; a command's messages now.
    let timed = matches!(cli.command, Command::Serve(_) | Command::Ethercat(_));
    logging::init(cli.verbose, cli.quiet, extra, timed);
    let result = match cli.command {
        Command::Law(args) => cmd::law::run(args),
        Command::Table(command) => cmd::table::run(command),
        Command::Simulate(args) => cmd::simulate::run(args),
        Command::Plc(command) => cmd::plc::run(command),
        Command::Pmd(command) => cmd::pmd::run(command),
        Command::Mc(command) => cmd::mc::run(command),
        Command::Serve(args) => cmd::serve::run(args),
        Command::Completions(args) => cmd::install::completions(&args),
        Command::Man(args) => cmd::install::man(&args),
        Command::Ethercat(command) => cmd::ethercat::run(command),
    };
    exit_code(result)
}

/// The exit-code scheme (docs/cli.md): 0 done, 1 failed, 2 a usage mistake
/// (clap exits with 2 itself, before anything runs). A reader that closed
/// the pipe (`ecam law cycloid | head`) is not a failure: the command
/// stops quietly, as Unix tools do.
fn exit_code(result: anyhow::Result<()>) -> std::process::ExitCode {
    match result {
        Ok(()) => std::process::ExitCode::SUCCESS,
        Err(err)
            if err.chain().any(|e| {
                e.downcast_ref::<std::io::Error>()
                    .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
            }) =>
        {
            std::process::ExitCode::SUCCESS
        }
        Err(err) => {
            eprintln!("ecam: {err:#}");
            std::process::ExitCode::FAILURE
        }
    }
}
