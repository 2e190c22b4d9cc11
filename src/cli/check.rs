//! `stickslip check [SCENE] [--steps ...]`: the event engine against the
//! fixed-step reference at several resolutions.

use super::{Failure, SceneOptions, Streams, write_out};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `check`.
#[derive(Args)]
pub(crate) struct CheckArgs {
    /// Scene file (TOML); omitted: the built-in default scene.
    scene: Option<PathBuf>,
    /// Resolutions: steps per period of the highest harmonic, comma separated.
    #[arg(
        long,
        value_delimiter = ',',
        value_parser = clap::value_parser!(u32).range(1..),
        default_values_t = crate::check::DEFAULT_STEPS
    )]
    steps: Vec<u32>,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
}

pub(crate) fn check(args: CheckArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let mut scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    for s in &args.steps {
        crate::scene::check_fixed_steps(&scene.signal, *s, "--steps").map_err(|e| e.to_string())?;
    }
    args.options.apply(&mut scene, streams);
    // The cross-check compares steady states: a scene without one (a
    // run-away, a start-up that does not converge) is reported as the
    // result it is, as `run` reports it.
    let mut event_scene = scene.clone();
    event_scene.run.engine = crate::scene::EngineKind::Event;
    let outcome = crate::simulation::simulate(&event_scene).map_err(|e| e.to_string())?;
    if outcome.report().is_none() {
        let text = format!(
            "{}no steady state to cross-check: the event engine's outcome is {}\n",
            crate::report::to_text(&outcome),
            outcome.regime()
        );
        return write_out(streams, &text);
    }
    let report = crate::check::check(&scene, &args.steps).map_err(|e| e.to_string())?;
    write_out(streams, &report.to_text())
}
