//! `stickslip signal [SCENE]`: the rod signal exactly as simulated
//! (see [`crate::signal::description::SignalDescription`]), as text, JSON, or a MATLAB
//! or Python snippet that evaluates `x_R(t)`.

use super::{Failure, Streams, write_out};
use crate::signal::description::SignalDescription;
use crate::simulation;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `signal`.
#[derive(Args)]
pub(crate) struct SignalArgs {
    /// Scene file (TOML); omitted: the built-in default scene.
    scene: Option<PathBuf>,
    /// Print one JSON object.
    #[arg(long, conflicts_with_all = ["matlab", "python"])]
    json: bool,
    /// Print a MATLAB snippet defining x_R = @(t) ... and v_R.
    #[arg(long, conflicts_with = "python")]
    matlab: bool,
    /// Print a Python (numpy) snippet defining x_R(t) and v_R(t).
    #[arg(long)]
    python: bool,
    #[command(flatten)]
    set: super::SceneSet,
}

pub(crate) fn signal(args: SignalArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    let (signal, motor) = simulation::build(&scene).map_err(|e| e.to_string())?;
    let d = SignalDescription::new(&scene.signal, &signal, &motor);
    let text = if args.json {
        let mut t = serde_json::to_string_pretty(&d.to_json()).map_err(|e| e.to_string())?;
        t.push('\n');
        t
    } else if args.matlab {
        d.to_matlab()
    } else if args.python {
        d.to_python()
    } else {
        d.to_text()
    };
    write_out(streams, &text)
}
