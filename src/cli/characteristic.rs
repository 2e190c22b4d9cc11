//! `stickslip characteristic [SCENE]`: `v_inf` against the load force (or
//! an incline), with the stall force, the held band, the holding force,
//! the largest output power, the start-up force and the datasheet block
//! ([`crate::characteristic`]); printed as text, JSON or CSV, and drawn as
//! a figure with the plot kit ([`crate::plot::characteristic`]).
//!
//! Every argument is checked before anything runs: the options, that no
//! output (the table, the figure, the figure's CSV) is the scene or
//! another output, and that the figure's format and directory are usable.

use super::table_output::{TableFormat, TableOutput};
use super::{Failure, SceneOptions, Streams};
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
    /// The table (the summary, or the points as CSV) and the figure of
    /// the characteristic.
    #[command(flatten)]
    out: TableOutput,
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
    args.out.check(args.scene.as_deref())?;
    args.options.apply(&mut scene, streams);
    let c = characteristic::characteristic(&scene, &options).map_err(|e| e.to_string())?;
    let text = match args.out.format() {
        TableFormat::Json => {
            let mut t = serde_json::to_string_pretty(&table::to_json(&c, &scene))
                .map_err(|e| e.to_string())?;
            t.push('\n');
            t
        }
        TableFormat::Csv => table::to_csv(&c, &scene),
        TableFormat::Text => table::to_text(&c),
    };
    args.out.figure("characteristic", |name| {
        crate::plot::characteristic::figure(&c, &scene, name).map_err(|e| e.to_string())
    })?;
    args.out.write(streams, &text)
}
