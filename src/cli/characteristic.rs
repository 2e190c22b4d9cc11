//! `stickslip characteristic [SCENE]`: `v_inf` against the load force (or
//! an incline), with the stall force, the held band, the holding force,
//! the largest output power, the start-up force and the datasheet block
//! ([`crate::characteristic`]); printed as text, JSON or CSV, and drawn as
//! a figure with the plot kit ([`crate::plot::characteristic`]).
//!
//! Every argument is checked before anything runs: the options, that no
//! output (the table, the figure, the figure's CSV) is the scene or
//! another output, and that the figure's format and directory are usable.

use super::{Failure, SceneOptions, Streams, write_out};
use crate::characteristic::{self, CharacteristicOptions, LoadAxis, table};
use clap::{Args, ValueEnum};
use std::path::PathBuf;

/// The load.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum LoadArg {
    /// A force F (N) against forward motion.
    Force,
    /// The slider's weight on an incline of angle theta (degrees).
    Incline,
}

/// Arguments of `characteristic`.
#[derive(Args)]
pub(crate) struct CharacteristicArgs {
    /// Scene file (TOML); omitted: the built-in default scene.
    scene: Option<PathBuf>,
    /// Print one JSON object instead of the summary.
    #[arg(long, conflicts_with = "csv")]
    json: bool,
    /// Print the points as CSV instead of the summary.
    #[arg(long)]
    csv: bool,
    /// Write the output to this file (atomically, only after success);
    /// a name ending in .json or .csv chooses that format.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Also draw the characteristic: .svg, .pdf or .png, with its data as
    /// .csv beside it.
    #[arg(long, value_name = "FILE")]
    figure: Option<PathBuf>,
    /// Print preset of the figure (default: single-column).
    #[arg(long, value_parser = ["single-column", "double-column", "slide"])]
    style: Option<String>,
    /// The load: a force, or the slider's weight on an incline.
    #[arg(long, value_enum, default_value = "force")]
    load: LoadArg,
    /// Low end of the range (N, or degrees on an incline); default: the
    /// whole range, -mu_0 F_c (or -90 degrees).
    #[arg(long, allow_negative_numbers = true, value_name = "X")]
    from: Option<f64>,
    /// High end of the range; default mu_0 F_c (or 90 degrees).
    #[arg(long, allow_negative_numbers = true, value_name = "X")]
    to: Option<f64>,
    /// Sampling tolerance: largest chord error relative to the range of v_inf.
    #[arg(long, default_value_t = 1e-3, allow_negative_numbers = true)]
    tolerance: f64,
    /// Largest number of evaluations of the sampled curve.
    #[arg(long, default_value_t = 400)]
    max_evaluations: u64,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
}

/// The format of the table.
#[derive(Clone, Copy, PartialEq, Eq)]
enum TableFormat {
    Text,
    Json,
    Csv,
}

pub(crate) fn characteristic(
    args: CharacteristicArgs,
    streams: &mut Streams<'_>,
) -> Result<(), Failure> {
    let axis = match args.load {
        LoadArg::Force => LoadAxis::Force,
        LoadArg::Incline => LoadAxis::Incline,
    };
    let mut scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    let holding = scene.motor.mu_static * scene.motor.contact_force;
    let (lo, hi) = axis.default_range(holding);
    let options = CharacteristicOptions {
        axis,
        range: (args.from.is_some() || args.to.is_some())
            .then(|| (args.from.unwrap_or(lo), args.to.unwrap_or(hi))),
        tolerance: args.tolerance,
        max_evaluations: args.max_evaluations,
    };
    options.validate().map_err(|e| e.to_string())?;
    super::check_table_outputs(
        args.scene.as_deref(),
        args.output.as_deref(),
        args.figure.as_deref(),
    )?;
    args.options.apply(&mut scene, streams);
    let c = characteristic::characteristic(&scene, &options).map_err(|e| e.to_string())?;
    let format = if args.json
        || args
            .output
            .as_deref()
            .is_some_and(|o| !args.csv && super::extension_is(o, "json"))
    {
        TableFormat::Json
    } else if args.csv
        || args
            .output
            .as_deref()
            .is_some_and(|o| super::extension_is(o, "csv"))
    {
        TableFormat::Csv
    } else {
        TableFormat::Text
    };
    let text = match format {
        TableFormat::Json => {
            let mut t = serde_json::to_string_pretty(&table::to_json(&c, &scene))
                .map_err(|e| e.to_string())?;
            t.push('\n');
            t
        }
        TableFormat::Csv => table::to_csv(&c, &scene),
        TableFormat::Text => table::to_text(&c),
    };
    if let Some(path) = &args.figure {
        let name = path.file_stem().map_or("characteristic".to_owned(), |s| {
            s.to_string_lossy().into_owned()
        });
        let figure =
            crate::plot::characteristic::figure(&c, &scene, &name).map_err(|e| e.to_string())?;
        super::write_figure(&figure, args.style.as_deref(), path)?;
    }
    match &args.output {
        Some(path) => crate::output::write_atomically(path, text.as_bytes())
            .map_err(|e| format!("cannot write {}: {e}", path.display())),
        None => write_out(streams, &text),
    }
}
