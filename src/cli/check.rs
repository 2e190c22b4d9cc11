//! `stickslip check [SCENE] [--steps ...]`: the event engine against the
//! fixed-step reference at several resolutions.

use super::run::load;
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
}

pub(crate) fn check(args: CheckArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let mut scene = load(args.scene.as_deref())?;
    for s in &args.steps {
        crate::scene::check_fixed_steps(&scene.signal, *s, "--steps").map_err(|e| e.to_string())?;
    }
    args.options.apply(&mut scene, streams);
    let report = crate::check::check(&scene, &args.steps).map_err(|e| e.to_string())?;
    write_out(streams, &report.to_text())
}
