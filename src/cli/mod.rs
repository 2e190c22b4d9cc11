//! The command line, as a library function so that tests drive exactly the
//! code path of the binary: [`main_with`] parses the arguments, runs one
//! command and returns its exit status, writing only to the streams it is
//! given.
//!
//! Contract of every command:
//! * success exits 0; bad input or an internal error prints one line
//!   `stickslip: <reason>` on the error stream and exits 1; a usage error
//!   (unknown flag, missing argument) exits 2 with clap's usage text, whose
//!   first line says what was wrong;
//! * output files are written atomically (all or nothing).

mod check;
mod compare;
mod run;
mod signal;
mod sweep;

use clap::{Parser, Subcommand};
use std::io::Write;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "stickslip",
    version,
    about = "Event-driven simulator for piezoelectric inertia (stick-slip) drives"
)]
struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Subcommand)]
enum Command {
    /// Run a scene (default: the paper's motor, n = 2, sqrt(kappa) = 6, sigma on).
    Run(run::RunArgs),
    /// Print the built-in default scene as TOML.
    DefaultScene,
    /// Cross-check a scene: the event engine against the fixed-step
    /// reference at several resolutions, indicator by indicator.
    Check(check::CheckArgs),
    /// Run a sweep file's grid in parallel, one CSV or JSON-lines row per case.
    Sweep(sweep::SweepArgs),
    /// Join sweep outputs (shards) into one file, sorted by case.
    Merge(sweep::MergeArgs),
    /// Print the rod signal exactly as simulated (text, JSON, MATLAB, Python).
    Signal(signal::SignalArgs),
    /// Compare a user's fixed-step results (CSV, MAT) with the exact solution.
    Compare(compare::CompareArgs),
}

/// The output and error streams of one invocation.
pub struct Streams<'a> {
    /// Standard output: results.
    pub out: &'a mut dyn Write,
    /// Standard error: messages, warnings, progress.
    pub err: &'a mut dyn Write,
}

/// A command's failure: the one-line message printed as `stickslip: ...`.
type Failure = String;

/// Runs the command line `args` (the first item is the program name) and
/// returns the process exit status.
pub fn main_with<I, T>(args: I, streams: &mut Streams<'_>) -> u8
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let cli = match Cli::try_parse_from(args) {
        Ok(cli) => cli,
        Err(e) => {
            let text = e.render().ansi().to_string();
            let exit = e.exit_code();
            let target: &mut dyn Write = if e.use_stderr() {
                &mut *streams.err
            } else {
                &mut *streams.out
            };
            let _ = write!(target, "{text}");
            return u8::try_from(exit).unwrap_or(2);
        }
    };
    let outcome = match cli.command {
        None => run::run(run::RunArgs::default(), streams),
        Some(Command::Run(args)) => run::run(args, streams),
        Some(Command::DefaultScene) => {
            let text = crate::Scene::default().to_toml();
            write_out(streams, &text)
        }
        Some(Command::Check(args)) => check::check(args, streams),
        Some(Command::Sweep(args)) => sweep::sweep(args, streams),
        Some(Command::Merge(args)) => sweep::merge(args, streams),
        Some(Command::Signal(args)) => signal::signal(args, streams),
        Some(Command::Compare(args)) => return compare::compare(args, streams),
    };
    match outcome {
        Ok(()) => 0,
        Err(message) => {
            let _ = writeln!(streams.err, "stickslip: {}", message.replace('\n', " "));
            1
        }
    }
}

/// Writes a command's result to the output stream.
fn write_out(streams: &mut Streams<'_>, text: &str) -> Result<(), Failure> {
    streams
        .out
        .write_all(text.as_bytes())
        .and_then(|()| streams.out.flush())
        .map_err(|e| format!("cannot write to standard output: {e}"))
}

/// The binary's entry point: [`main_with`] on the process's arguments and
/// standard streams.
pub fn main() -> ExitCode {
    let stdout = std::io::stdout();
    let stderr = std::io::stderr();
    let mut out = stdout.lock();
    let mut err = stderr.lock();
    let mut streams = Streams {
        out: &mut out,
        err: &mut err,
    };
    ExitCode::from(main_with(std::env::args_os(), &mut streams))
}
