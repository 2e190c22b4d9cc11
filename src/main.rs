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
    },
    /// Print the built-in default scene as TOML.
    DefaultScene,
}

fn load(path: Option<&PathBuf>) -> Result<Scene, String> {
    match path {
        Some(p) => Scene::from_path(p).map_err(|e| e.to_string()),
        None => Ok(Scene::default()),
    }
}

fn run(scene: Option<PathBuf>, json: bool) -> Result<(), String> {
    let scene = load(scene.as_ref())?;
    let result = simulation::run(&scene).map_err(|e| e.to_string())?;
    if json {
        let text =
            serde_json::to_string_pretty(&report::to_json(&result)).map_err(|e| e.to_string())?;
        println!("{text}");
    } else {
        print!("{}", report::to_text(&result));
    }
    Ok(())
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let outcome = match cli.command {
        None => run(None, false),
        Some(Command::Run { scene, json }) => run(scene, json),
        Some(Command::DefaultScene) => {
            print!("{}", Scene::default().to_toml());
            Ok(())
        }
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("stickslip: {}", message.replace('\n', " "));
            ExitCode::FAILURE
        }
    }
}
