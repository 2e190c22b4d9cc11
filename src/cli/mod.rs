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
//! * output files are written atomically (all or nothing), and an output
//!   path that is one of the command's inputs is refused
//!   (`refuse_output_over_input`);
//! * results go to the output stream through one function that treats a
//!   closed pipe (`stickslip run --json | head -c 10`) as the end of the
//!   reader's interest: the command stops quietly with exit 0, as `cat` or
//!   `seq` do when their reader has gone; any other write failure (a full
//!   disk) is a one-line error with exit 1;
//! * values that are valid but implausible ([`crate::scene::Scene::warnings`]) print
//!   one line each, `stickslip: warning: ...`, on the error stream before
//!   the run, unless `--quiet`;
//! * `--time-limit SECONDS` (or the scene's `[run] time_limit_s`) bounds the
//!   wall-clock time of each simulation; a run that reaches it stops with a
//!   one-line error naming how far it got.
//! * a command stopped by SIGINT or SIGTERM exits 130 or 143 (see
//!   `crate::interrupt`, installed by [`main`]), leaving no partial or
//!   temporary file.

mod bench;
mod characteristic;
mod check;
mod compare;
mod optimize;
mod plot;
mod run;
mod signal;
mod sweep;
mod table_output;

use clap::{Args, Parser, Subcommand};
use std::io::Write;
use std::path::Path;
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
    /// Print the rod signal exactly as simulated, or with --voltage the
    /// actuator voltage that moves the rod along it (text, JSON, MATLAB,
    /// Python).
    Signal(signal::SignalArgs),
    /// Compare a user's fixed-step results (CSV, MAT) with the exact solution.
    Compare(compare::CompareArgs),
    /// Publication figure of a scene or a sweep output (SVG, PDF, PNG).
    Plot(plot::PlotArgs),
    /// The force-velocity characteristic: v_inf against the load, stall
    /// force, holding force, output power, datasheet block.
    Characteristic(characteristic::CharacteristicArgs),
    /// The spring method against stiffness, tied and free-ended, beside the
    /// stall force (weight method) and the start-up force (Newton method).
    Bench(bench::BenchArgs),
    /// The best rod signal of n harmonics at the scene's stroke and f_max,
    /// written as a runnable scene.
    Optimize(optimize::OptimizeArgs),
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
            // Plain text: the error stream may be a file or a pipe, where colour
            // codes would be noise.
            let text = e.render().to_string();
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
    // Ok: the exit status (0, or 130/143 for a sweep stopped by a signal).
    let outcome: Result<u8, Failure> = match cli.command {
        None => run::run(run::RunArgs::default(), streams).map(|()| 0),
        Some(Command::Run(args)) => run::run(args, streams).map(|()| 0),
        Some(Command::DefaultScene) => {
            let text = crate::scene::Scene::default().to_toml();
            write_out(streams, &text).map(|()| 0)
        }
        Some(Command::Check(args)) => check::check(args, streams).map(|()| 0),
        Some(Command::Sweep(args)) => sweep::sweep(args, streams),
        Some(Command::Merge(args)) => sweep::merge(args, streams).map(|()| 0),
        Some(Command::Signal(args)) => signal::signal(args, streams).map(|()| 0),
        Some(Command::Compare(args)) => return compare::compare(args, streams),
        Some(Command::Plot(args)) => plot::plot(args, streams).map(|()| 0),
        Some(Command::Characteristic(args)) => {
            characteristic::characteristic(args, streams).map(|()| 0)
        }
        Some(Command::Bench(args)) => bench::bench(args, streams).map(|()| 0),
        Some(Command::Optimize(args)) => optimize::optimize(args, streams).map(|()| 0),
    };
    match outcome {
        Ok(code) => code,
        Err(message) => {
            let _ = writeln!(streams.err, "stickslip: {}", one_line(&message));
            1
        }
    }
}

/// A message as one line: line breaks become spaces, and every other
/// control character (a carriage return quoted from a scene line) is
/// written escaped (`\r`), so that the message stays one line on any
/// terminal.
pub fn one_line(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    for c in message.chars() {
        match c {
            '\n' => out.push(' '),
            c if c.is_control() => out.extend(c.escape_debug()),
            c => out.push(c),
        }
    }
    out
}

/// Writes a command's result to the output stream. A reader that has gone
/// (broken pipe) ends the command quietly and successfully; any other
/// failure (`/dev/full`) is the command's error.
fn write_out(streams: &mut Streams<'_>, text: &str) -> Result<(), Failure> {
    match streams
        .out
        .write_all(text.as_bytes())
        .and_then(|()| streams.out.flush())
    {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(format!("cannot write to standard output: {e}"))
        }
        _ => Ok(()),
    }
}

/// `--set PATH=VALUE`, taken by every command that reads a scene (flatten
/// into its arguments with `#[command(flatten)]`).
#[derive(Args, Debug, Clone, Default)]
pub(crate) struct SceneSet {
    /// Set one scene field as if the file held it (repeatable, applied in
    /// order): PATH is the field's dotted path with 0-based indices
    /// (motor.slider_mass, signal.amplitudes[1]), VALUE a TOML value or a
    /// bare word (5e-3, true, fourier). Setting one of signal.kappa,
    /// sqrt_kappa, frequency, f_max replaces whichever the scene gave.
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub(crate) set: Vec<String>,
}

impl SceneSet {
    /// The overrides, parsed (`crate::scene::Override`).
    pub(crate) fn overrides(&self) -> Result<Vec<crate::scene::Override>, Failure> {
        self.set
            .iter()
            .map(|s| {
                s.parse()
                    .map_err(|e: crate::scene::OverrideError| e.to_string())
            })
            .collect()
    }
}

/// A scene file (`-`: standard input), or the built-in default scene, with
/// the `--set` overrides applied before it is checked.
pub(crate) fn load_scene(
    path: Option<&Path>,
    set: &SceneSet,
) -> Result<crate::scene::Scene, Failure> {
    let overrides = set.overrides()?;
    let scene = match path {
        Some(p) => crate::scene::Scene::from_path_with(p, &overrides),
        None if overrides.is_empty() => Ok(crate::scene::Scene::default()),
        None => crate::scene::Scene::from_toml_str_with(
            &crate::scene::Scene::default().to_toml(),
            "<default scene>",
            &overrides,
        ),
    };
    scene.map_err(|e| e.to_string())
}

/// Options every command that simulates a scene takes (flatten into its
/// arguments with `#[command(flatten)]`).
#[derive(Args, Debug, Clone, Copy, Default)]
pub(crate) struct SceneOptions {
    /// No warnings about implausible values (and no progress bar).
    #[arg(short, long)]
    pub(crate) quiet: bool,
    /// Wall-clock budget of each simulation, in seconds; overrides the
    /// scene's [run] time_limit_s.
    #[arg(
        long,
        value_name = "SECONDS",
        allow_negative_numbers = true,
        value_parser = parse_time_limit
    )]
    pub(crate) time_limit: Option<f64>,
}

impl SceneOptions {
    /// Applies the options to a loaded scene: `--time-limit` replaces its
    /// `run.time_limit_s`; unless `--quiet`, its warnings
    /// ([`crate::scene::Scene::warnings`]) are printed on the error stream, one
    /// line each.
    pub(crate) fn apply(&self, scene: &mut crate::scene::Scene, streams: &mut Streams<'_>) {
        // Long runs say how far they got, on an interactive terminal.
        crate::simulation::budget::show_progress(
            !self.quiet && std::io::IsTerminal::is_terminal(&std::io::stderr()),
        );
        if let Some(limit) = self.time_limit {
            scene.run.time_limit_s = Some(limit);
        }
        if !self.quiet {
            print_warnings(scene, streams);
        }
    }
}

/// Prints a scene's warnings ([`crate::scene::Scene::warnings`]) on the error
/// stream, one line each: `stickslip: warning: <field> = <value> ...`.
pub(crate) fn print_warnings(scene: &crate::scene::Scene, streams: &mut Streams<'_>) {
    for warning in scene.warnings() {
        let _ = writeln!(streams.err, "stickslip: warning: {warning}");
    }
}

/// `--time-limit`: a finite number of seconds above 0.
fn parse_time_limit(text: &str) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("\"{text}\" is not a number of seconds"))?;
    crate::error::ParamError::positive("--time-limit", value).map_err(|e| e.to_string())
}

/// Refuses to write `output` when it is one of `inputs`: the same file by
/// identity (device and inode, so that `./scene.toml`, an absolute path,
/// a hard link or a symbolic link to it all count), or the same path once
/// made absolute. An output that does not exist yet is no input. Call it
/// before any work is done.
pub(crate) fn refuse_output_over_input(output: &Path, inputs: &[&Path]) -> Result<(), Failure> {
    let absolute = |p: &Path| std::path::absolute(p).ok();
    for input in inputs {
        let same_file = same_file::is_same_file(output, input).unwrap_or(false);
        let same_path = absolute(output).is_some() && absolute(output) == absolute(input);
        if same_file || same_path {
            return Err(format!(
                "output {} is the input {}: refusing to overwrite an input; name another output",
                output.display(),
                input.display()
            ));
        }
    }
    Ok(())
}

/// Checks that a figure named by `flag` can be written: its extension picks
/// a format (`.svg`, `.pdf`, `.png`) and its directory exists.
pub(crate) fn check_figure_path(flag: &str, figure: &Path) -> Result<(), Failure> {
    crate::plot::ImageFormat::of(figure)
        .map_err(|e| e.to_string().replacen("-o ", &format!("{flag} "), 1))?;
    let dir = match figure.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if !dir.is_dir() {
        return Err(format!(
            "{flag} {}: the directory {} does not exist",
            figure.display(),
            dir.display()
        ));
    }
    Ok(())
}

/// Writes `figure` to `path` (format from the extension, CSV beside it) in
/// the preset `style` names, or the figure's own, at 300 dpi for PNG.
pub(crate) fn write_figure(
    figure: &crate::plot::Figure,
    style: Option<&str>,
    path: &Path,
) -> Result<(), Failure> {
    let preset = style
        .and_then(crate::plot::Preset::from_name)
        .unwrap_or(figure.preset);
    figure
        .write(path, &preset.style(), 300.0)
        .map(|_| ())
        .map_err(|e| e.to_string())
}

/// True if `path` has the extension `ext` (any case).
pub(crate) fn extension_is(path: &Path, ext: &str) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case(ext))
}

/// Checks that no output (`output`, `figure` and the figure's CSV) is the
/// input `scene` or another output, and that the figure can be written.
pub(crate) fn check_table_outputs(
    scene: Option<&Path>,
    output: Option<&Path>,
    figure: Option<&Path>,
) -> Result<(), Failure> {
    let inputs: Vec<&Path> = scene.into_iter().collect();
    let figure_csv = figure.map(crate::plot::data_path);
    let outputs: Vec<&Path> = [output, figure, figure_csv.as_deref()]
        .into_iter()
        .flatten()
        .collect();
    refuse_outputs(&outputs, &inputs)?;
    match figure {
        Some(figure) => check_figure_path("--figure", figure),
        None => Ok(()),
    }
}

/// Refuses every output that is one of `inputs`
/// ([`refuse_output_over_input`]) or names the same file as an earlier
/// output. Call it before any work is done.
pub(crate) fn refuse_outputs(outputs: &[&Path], inputs: &[&Path]) -> Result<(), Failure> {
    for (i, output) in outputs.iter().enumerate() {
        refuse_output_over_input(output, inputs)?;
        if let Some(other) = outputs[..i]
            .iter()
            .find(|o| refuse_output_over_input(output, &[o]).is_err())
        {
            return Err(format!(
                "{} is named as two outputs (also as {}): name another file for one of them",
                output.display(),
                other.display()
            ));
        }
    }
    Ok(())
}

/// The binary's entry point: [`main_with`] on the process's arguments and
/// standard streams.
pub fn main() -> ExitCode {
    // Without the handlers the signals keep their default action: the
    // commands still work, only an interrupted one may leave a temporary
    // file, so a failure here is not worth refusing to run.
    let _ = crate::interrupt::install();
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
