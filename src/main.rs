//! `stickslip`: command-line front end. Parses arguments and calls the
//! library; with no arguments it runs the paper's default scene.

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;
use stickslip::{Scene, report, simulation};

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
    Run {
        /// Scene file (TOML); omitted: the built-in default scene.
        scene: Option<PathBuf>,
        /// Print one JSON object instead of the summary.
        #[arg(long)]
        json: bool,
        /// Write the output to this file (atomically, only after the run
        /// succeeded) instead of standard output.
        #[arg(long, short)]
        output: Option<PathBuf>,
    },
    /// Print the built-in default scene as TOML.
    DefaultScene,
    /// Cross-check a scene: the event engine against the fixed-step
    /// reference at several resolutions, indicator by indicator.
    Check {
        /// Scene file (TOML); omitted: the built-in default scene.
        scene: Option<PathBuf>,
        /// Resolutions: steps per period of the highest harmonic, comma separated.
        #[arg(
            long,
            value_delimiter = ',',
            value_parser = clap::value_parser!(u32).range(1..),
            default_values_t = stickslip::check::DEFAULT_STEPS
        )]
        steps: Vec<u32>,
    },
    /// Run a sweep file's grid in parallel, one CSV or JSON-lines row per case.
    Sweep {
        /// Sweep file (TOML).
        file: PathBuf,
        /// Output file; rows already in it are kept and not rerun. Default:
        /// <sweep name>.csv (or .jsonl), <sweep name>.<i>-of-<N>.csv for a shard.
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Run only shard i of N (i from 1): the cases with index % N == i - 1.
        #[arg(long, value_name = "i/N")]
        shard: Option<stickslip::sweep::Shard>,
        /// Leave out the wall_time_s column: the same sweep then writes the same bytes.
        #[arg(long)]
        no_timing: bool,
        /// No progress bar.
        #[arg(short, long)]
        quiet: bool,
        /// Worker threads (default: every available CPU).
        #[arg(short, long)]
        jobs: Option<usize>,
    },
    /// Join sweep outputs (shards) into one file, sorted by case.
    Merge {
        /// The merged file (written atomically).
        output: PathBuf,
        /// Sweep outputs with the same columns.
        #[arg(required = true)]
        inputs: Vec<PathBuf>,
    },
}

fn load(path: Option<&PathBuf>) -> Result<Scene, String> {
    match path {
        Some(p) => Scene::from_path(p).map_err(|e| e.to_string()),
        None => Ok(Scene::default()),
    }
}

fn run(scene: Option<PathBuf>, json: bool, output: Option<PathBuf>) -> Result<(), String> {
    let scene = load(scene.as_ref())?;
    let result = simulation::run(&scene).map_err(|e| e.to_string())?;
    let text = if json {
        let mut text =
            serde_json::to_string_pretty(&report::to_json(&result)).map_err(|e| e.to_string())?;
        text.push('\n');
        text
    } else {
        report::to_text(&result)
    };
    match output {
        Some(path) => stickslip::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => {
            print!("{text}");
            Ok(())
        }
    }
}

fn sweep(
    file: PathBuf,
    output: Option<PathBuf>,
    shard: Option<stickslip::sweep::Shard>,
    timing: bool,
    progress: bool,
    jobs: Option<usize>,
) -> Result<(), String> {
    use stickslip::sweep;
    if let Some(jobs) = jobs {
        rayon::ThreadPoolBuilder::new()
            .num_threads(jobs)
            .build_global()
            .map_err(|e| e.to_string())?;
    }
    let sweep = sweep::load(&file).map_err(|e| e.to_string())?;
    let output = output.unwrap_or_else(|| sweep.default_output(shard));
    let options = sweep::Options {
        shard,
        timing,
        progress,
        ..sweep::Options::new(&output)
    };
    let s = sweep::execute(&sweep, &options).map_err(|e| e.to_string())?;
    eprintln!(
        "stickslip: {} cases{}: {} already written, {} run, {} failed; {} rows in {}",
        s.cases,
        shard.map_or(String::new(), |sh| format!(
            " in shard {sh} (of {})",
            sweep.len()
        )),
        s.skipped,
        s.ran,
        s.failed,
        s.rows,
        output.display()
    );
    if s.failed > 0 {
        eprintln!("stickslip: warning: see the failure column for why cases failed");
    }
    Ok(())
}

fn check(scene: Option<PathBuf>, steps: &[u32]) -> Result<(), String> {
    let scene = load(scene.as_ref())?;
    let report = stickslip::check::check(&scene, steps).map_err(|e| e.to_string())?;
    print!("{}", report.to_text());
    Ok(())
}

fn merge(output: PathBuf, inputs: Vec<PathBuf>) -> Result<(), String> {
    let s = stickslip::sweep::merge(&output, &inputs).map_err(|e| e.to_string())?;
    eprintln!("stickslip: {} rows in {}", s.rows, output.display());
    if !s.missing.is_empty() {
        eprintln!(
            "stickslip: warning: {} cases missing below the last one: {:?}",
            s.missing.len(),
            s.missing
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        None => run(None, false, None),
        Some(Command::Run {
            scene,
            json,
            output,
        }) => run(scene, json, output),
        Some(Command::DefaultScene) => {
            print!("{}", Scene::default().to_toml());
            Ok(())
        }
        Some(Command::Sweep {
            file,
            output,
            shard,
            no_timing,
            quiet,
            jobs,
        }) => sweep(file, output, shard, !no_timing, !quiet, jobs),
        Some(Command::Merge { output, inputs }) => merge(output, inputs),
        Some(Command::Check { scene, steps }) => check(scene, &steps),
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("stickslip: {}", message.replace('\n', " "));
            ExitCode::FAILURE
        }
    }
}
