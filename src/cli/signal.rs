//! `stickslip signal [SCENE]`: the rod signal exactly as simulated
//! (see [`crate::signal::description::SignalDescription`]), as text, JSON, or a MATLAB
//! or Python snippet that evaluates `x_R(t)`; with `--voltage`, the
//! actuator voltage that moves the rod along it
//! ([`crate::actuator::VoltageDescription`]), in the same four forms.

use super::{Failure, Streams, write_out};
use crate::actuator::VoltageDescription;
use crate::signal::description::SignalDescription;
use crate::simulation;
use clap::Args;
use std::path::PathBuf;

/// Arguments of `signal`.
#[derive(Args)]
pub(crate) struct SignalArgs {
    /// Scene file (TOML); omitted: the built-in default scene.
    scene: Option<PathBuf>,
    /// Print the voltage u(t) that moves the rod of [actuator] exactly
    /// along the signal (for a signal generator) instead of the signal;
    /// a scene's [voltage] as given.
    #[arg(long)]
    voltage: bool,
    /// Print one JSON object.
    #[arg(long, conflicts_with_all = ["matlab", "python"])]
    json: bool,
    /// Print a MATLAB snippet defining x_R = @(t) ... and v_R (with
    /// --voltage: u = @(t) ...).
    #[arg(long, conflicts_with = "python")]
    matlab: bool,
    /// Print a Python (numpy) snippet defining x_R(t) and v_R(t) (with
    /// --voltage: u(t)).
    #[arg(long)]
    python: bool,
    #[command(flatten)]
    set: super::SceneSet,
}

/// What `signal` prints.
enum Form {
    Text,
    Json,
    Matlab,
    Python,
}

/// A JSON value as printed: pretty, with a final line break.
fn json_text(value: &serde_json::Value) -> Result<String, Failure> {
    let mut t = serde_json::to_string_pretty(value).map_err(|e| e.to_string())?;
    t.push('\n');
    Ok(t)
}

pub(crate) fn signal(args: SignalArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    let (signal, motor) = simulation::build(&scene).map_err(|e| e.to_string())?;
    let form = match (args.json, args.matlab, args.python) {
        (true, _, _) => Form::Json,
        (_, true, _) => Form::Matlab,
        (_, _, true) => Form::Python,
        _ => Form::Text,
    };
    let text = if args.voltage {
        let d = match (&scene.voltage, &scene.actuator) {
            (Some(given), Some(actuator)) => VoltageDescription::given(given, &signal, actuator),
            _ => VoltageDescription::new(&scene.signal, &signal, scene.actuator.as_ref())
                .map_err(|e| e.to_string())?,
        };
        match form {
            Form::Text => d.to_text(),
            Form::Json => json_text(&d.to_json())?,
            Form::Matlab => d.to_matlab(),
            Form::Python => d.to_python(),
        }
    } else {
        let d = SignalDescription::new(&scene.signal, &signal, &motor);
        match form {
            Form::Text => d.to_text(),
            Form::Json => json_text(&d.to_json())?,
            Form::Matlab => d.to_matlab(),
            Form::Python => d.to_python(),
        }
    };
    write_out(streams, &text)
}
