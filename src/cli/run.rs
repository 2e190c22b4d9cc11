//! `stickslip run [SCENE] [--json] [-o FILE]`: one run of a scene, printed
//! as a summary or as one JSON object (keys in `docs/interface.md`).

use super::{Failure, SceneOptions, Streams, refuse_outputs, write_out};
use crate::motor::Motor;
use crate::signal::{Held, SignalSpec};
use crate::{report, simulation};
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
    /// Also report the exact derivatives of v_inf with respect to the
    /// motor's and the signal's parameters (docs/model.md section 14).
    #[arg(long)]
    sensitivities: bool,
    /// With --sensitivities: what the derivatives hold of the drive, its
    /// frequency f0 or kappa (default: what the scene gives).
    #[arg(long, value_name = "frequency|kappa", requires = "sensitivities")]
    sensitivities_at: Option<HeldArg>,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
    /// Exact trajectory export (`--trajectory`, `--times`, `--sample-rate`,
    /// `--periods`, `--periods-series`; docs/interface.md).
    #[command(flatten)]
    export: ExportArgs,
}

/// The values of `--sensitivities-at`.
#[derive(Clone, Copy, clap::ValueEnum)]
pub(crate) enum HeldArg {
    /// The drive frequency f0 (the period).
    Frequency,
    /// kappa = a_R / a_0 (the period follows a_0).
    Kappa,
}

impl From<HeldArg> for Held {
    fn from(h: HeldArg) -> Held {
        match h {
            HeldArg::Frequency => Held::Frequency,
            HeldArg::Kappa => Held::Kappa,
        }
    }
}

/// Flags of the exact trajectory export (implemented in [`crate::export`]).
#[derive(Args, Default)]
pub(crate) struct ExportArgs {
    /// Write x_R, v_R, a_R, x_S, v_S, mode at the sample times to FILE
    /// (CSV, or JSON lines for .jsonl).
    #[arg(long, value_name = "FILE")]
    trajectory: Option<PathBuf>,
    /// Sample times for --trajectory: one per line, or a CSV/MAT column t.
    #[arg(long, value_name = "FILE")]
    times: Option<PathBuf>,
    /// Sample rate for --trajectory (Hz), over --periods.
    #[arg(long, value_name = "HZ", allow_negative_numbers = true)]
    sample_rate: Option<f64>,
    /// Periods A..B sampled with --sample-rate (default 1..1).
    #[arg(long, value_name = "A..B", value_parser = super::compare::parse_range)]
    periods: Option<(u64, u64)>,
    /// Write the per-period series p, v_p, x_p, stick time, events of the
    /// start-up to FILE (CSV, or JSON lines for .jsonl).
    #[arg(long, value_name = "FILE")]
    periods_series: Option<PathBuf>,
}

pub(crate) fn run(args: RunArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let e = args.export;
    // No output may be an input (the scene, the sample times) or another
    // output of the same run.
    let inputs: Vec<&Path> = args
        .scene
        .iter()
        .chain(&e.times)
        .map(PathBuf::as_path)
        .collect();
    let outputs: Vec<&Path> = [&args.output, &e.trajectory, &e.periods_series]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    refuse_outputs(&outputs, &inputs)?;
    let mut scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    args.options.apply(&mut scene, streams);
    // The scene whose derivatives are taken: the drive as given, or given
    // the other way (the same signal) to hold the other quantity.
    let held = args.sensitivities_at.map(Held::from);
    let mut at = scene.clone();
    if let Some(held) = held {
        if held == Held::Kappa && matches!(scene.signal, SignalSpec::Harmonics { .. }) {
            return Err(
                "--sensitivities-at = kappa: the signal (kind = \"harmonics\") is given by its \
                 frequency and has no kappa"
                    .to_owned(),
            );
        }
        let motor = Motor::new(scene.motor).map_err(|e| e.to_string())?;
        at.signal = scene.signal.holding(held, &motor);
    }
    let held = at.signal.held();
    let f0 = Motor::new(at.motor).map_or(f64::NAN, |m| at.signal.f0(&m));
    let request = crate::export::TrajectoryRequest {
        trajectory: e.trajectory,
        times: e.times,
        sample_rate: e.sample_rate,
        periods: e.periods,
        periods_series: e.periods_series,
    };
    if request.any() {
        crate::export::write_requested(&scene, &request)?;
    }
    if args.sensitivities && scene.run.engine != crate::scene::EngineKind::Event {
        return Err(
            "--sensitivities needs run.engine = \"event\": the derivatives are those of the exact \
             event-driven steady state"
                .to_owned(),
        );
    }
    if args.sensitivities && scene.spring.is_some() {
        return Err(
            "--sensitivities: with a spring ([spring]) v_inf does not apply, and the \
             sensitivities are those of v_inf"
                .to_owned(),
        );
    }
    let outcome = simulation::simulate(&scene).map_err(|e| e.to_string())?;
    if args.sensitivities && matches!(scene.rod, crate::actuator::RodModel::Driven(_)) {
        // A driven rod: the real actuator's parameters, the voltage held.
        let sensitivities = match outcome.report() {
            Some(r) => r.actuator_sensitivities(&scene).map_err(|e| e.to_string()),
            None => Err(format!("no periodic steady state ({})", outcome.regime())),
        };
        let text = if args.json {
            let mut value = report::to_json(&outcome, &scene);
            report::add_actuator_sensitivities_json(&mut value, &sensitivities);
            let mut text = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
            text.push('\n');
            text
        } else {
            let mut text = report::to_text(&outcome);
            text.push_str(&report::actuator_sensitivities_text(&sensitivities));
            text
        };
        return match args.output {
            Some(path) => crate::output::write_atomically(&path, text.as_bytes())
                .map_err(|e| format!("cannot write {}: {e}", path.display())),
            None => write_out(streams, &text),
        };
    }
    let sensitivities = args.sensitivities.then(|| match outcome.report() {
        Some(r) => r.sensitivities(&at).map_err(|e| e.to_string()),
        None => Err(format!("no periodic steady state ({})", outcome.regime())),
    });
    let text = if args.json {
        let mut value = report::to_json(&outcome, &scene);
        if let Some(s) = &sensitivities {
            report::add_sensitivities_json(&mut value, s, held);
        }
        let mut text = serde_json::to_string_pretty(&value).map_err(|e| e.to_string())?;
        text.push('\n');
        text
    } else {
        let mut text = report::to_text(&outcome);
        if let Some(s) = &sensitivities {
            text.push_str(&report::sensitivities_text(s, held, f0));
        }
        text
    };
    match args.output {
        Some(path) => crate::output::write_atomically(&path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => write_out(streams, &text),
    }
}
