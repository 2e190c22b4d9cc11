//! `stickslip run [SCENE] [--json] [-o FILE]`: one run of a scene, printed
//! as a summary or as one JSON object (keys in `docs/interface.md`).

use super::{Failure, SceneOptions, Streams, refuse_output_over_input, write_out};
use crate::{Scene, report, simulation};
use clap::Args;
use std::path::{Path, PathBuf};

/// Arguments of `run`.
#[derive(Args, Default)]
pub(crate) struct RunArgs {
    /// Scene file (TOML); omitted: the built-in default scene.
    scene: Option<PathBuf>,
    /// Print one JSON object instead of the summary.
    #[arg(long)]
    json: bool,
    /// Write the output to this file (atomically, only after the run
    /// succeeded) instead of standard output.
    #[arg(long, short)]
    output: Option<PathBuf>,
    #[command(flatten)]
    options: SceneOptions,
}

/// A scene file, or the built-in default scene.
pub(crate) fn load(path: Option<&Path>) -> Result<Scene, Failure> {
    match path {
        Some(p) => Scene::from_path(p).map_err(|e| e.to_string()),
        None => Ok(Scene::default()),
    }
}

pub(crate) fn run(args: RunArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    if let (Some(output), Some(scene)) = (&args.output, &args.scene) {
        refuse_output_over_input(output, &[scene])?;
    }
    let mut scene = load(args.scene.as_deref())?;
    args.options.apply(&mut scene, streams);
    let outcome = simulation::simulate(&scene).map_err(|e| e.to_string())?;
    let text = if args.json {
        let mut text = serde_json::to_string_pretty(&report::to_json(&outcome, &scene))
            .map_err(|e| e.to_string())?;
        text.push('\n');
        text
    } else {
        report::to_text(&outcome)
    };
    match args.output {
        Some(path) => crate::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => write_out(streams, &text),
    }
}
