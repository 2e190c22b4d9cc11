//! `stickslip bench [SCENE]`: the spring method's reading against spring
//! stiffness, tied and free-ended, beside the stall force (weight method)
//! and the start-up force (Newton method) ([`crate::bench`]); printed as
//! text, JSON or CSV, and drawn as a figure ([`crate::plot::bench`]).
//!
//! Every argument is checked before anything runs: the options, that no
//! output (the table, the figure, the figure's CSV) is the scene or
//! another output, and that the figure's format and directory are usable.

use super::table_output::{TableFormat, TableOutput};
use super::{Failure, SceneOptions, Streams};
use crate::bench::{self, BenchOptions, SpringKinds, table};
use clap::Args;
use std::path::PathBuf;

/// Arguments of `bench`.
#[derive(Args)]
pub(crate) struct BenchArgs {
    /// Scene file (TOML); omitted: the built-in default scene. Its
    /// [spring], if any, gives the tied spring's damping and preload or
    /// the free end's gap; its stiffness is replaced.
    scene: Option<PathBuf>,
    /// Lowest spring stiffness (N/m).
    #[arg(long, value_name = "K", default_value_t = bench::DEFAULT_FROM, allow_negative_numbers = true)]
    from: f64,
    /// Highest spring stiffness (N/m).
    #[arg(long, value_name = "K", default_value_t = bench::DEFAULT_TO, allow_negative_numbers = true)]
    to: f64,
    /// Number of stiffnesses, log spaced from --from to --to.
    #[arg(long, value_name = "N", default_value_t = bench::DEFAULT_POINTS)]
    points: usize,
    /// Periods from rest within which a spring's orbit must lock; a case
    /// that locks into none is read over the 64 periods after them
    #[arg(long, value_name = "N", default_value_t = bench::DEFAULT_MAX_PERIODS)]
    max_periods: u64,
    /// Only the spring tied to the slider.
    #[arg(long, conflicts_with = "free")]
    tied: bool,
    /// Only the free-ended spring.
    #[arg(long)]
    free: bool,
    /// The table (one CSV row per stiffness and spring) and the figure
    /// of the spring force against stiffness.
    #[command(flatten)]
    out: TableOutput,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
}

pub(crate) fn bench(args: BenchArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    let options = BenchOptions {
        from: args.from,
        to: args.to,
        points: args.points,
        max_periods: args.max_periods,
        kinds: match (args.tied, args.free) {
            (true, _) => SpringKinds::Tied,
            (_, true) => SpringKinds::Free,
            _ => SpringKinds::Both,
        },
    };
    options.validate().map_err(|e| e.to_string())?;
    let mut scene = super::load_scene(args.scene.as_deref(), &args.set)?;
    args.out.check(args.scene.as_deref())?;
    args.options.apply(&mut scene, streams);
    let b = bench::bench(&scene, &options).map_err(|e| e.to_string())?;
    let text = match args.out.format() {
        TableFormat::Json => {
            let mut t = serde_json::to_string_pretty(&table::to_json(&b, &scene))
                .map_err(|e| e.to_string())?;
            t.push('\n');
            t
        }
        TableFormat::Csv => table::to_csv(&b, &scene),
        TableFormat::Text => table::to_text(&b),
    };
    args.out.figure("bench", |name| {
        crate::plot::bench::figure(&b, &scene, name).map_err(|e| e.to_string())
    })?;
    args.out.write(streams, &text)
}
