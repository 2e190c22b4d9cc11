//! `stickslip compare SCENE DATA...`: a user's fixed-step results against
//! the exact solution (see [`crate::compare`]). Exit status: 0 when every
//! file passes the tolerance, 1 when one fails, 3 for bad input or an
//! internal error (one line `stickslip: <reason>`), 2 for usage errors.

use super::{Streams, refuse_outputs};
use crate::compare::read::{LengthUnit, ReadOptions, TimeUnit};
use crate::compare::{self, CompareOptions, Metric};
use clap::Args;
use std::path::{Path, PathBuf};

/// Exit status of bad input or an internal error in `compare`.
pub(crate) const EXIT_BAD_INPUT: u8 = 3;

/// Arguments of `compare`.
#[derive(Args)]
#[command(
    after_help = "Exit status: 0 every file passes, 1 a file fails the tolerance, \
                        2 usage error, 3 bad input or internal error."
)]
pub(crate) struct CompareArgs {
    /// Scene file (TOML) the data were computed for (`-`: standard input).
    scene: PathBuf,
    #[command(flatten)]
    set: super::SceneSet,
    /// The user's results: CSV files (columns t, x_S/x, v_S/v, x_R; p, v_p)
    /// or MATLAB Level 5 MAT-files (.mat: variables of the same names,
    /// structs, Simulink's "Structure with time").
    #[arg(required = true)]
    data: Vec<PathBuf>,
    /// Unit of the times in the files.
    #[arg(long, value_enum, default_value = "s")]
    time_unit: TimeUnit,
    /// Unit of the lengths in the files (velocities: length unit / time unit).
    #[arg(long, value_enum, default_value = "m")]
    length_unit: LengthUnit,
    /// Name of the time column or variable.
    #[arg(long, value_name = "NAME")]
    var_t: Option<String>,
    /// Name of the slider position column or variable.
    #[arg(long = "var-x-s", value_name = "NAME")]
    var_x_s: Option<String>,
    /// Name of the slider velocity column or variable.
    #[arg(long = "var-v-s", value_name = "NAME")]
    var_v_s: Option<String>,
    /// Name of the rod position column or variable.
    #[arg(long = "var-x-r", value_name = "NAME")]
    var_x_r: Option<String>,
    /// Name of the period index column or variable.
    #[arg(long, value_name = "NAME")]
    var_p: Option<String>,
    /// Name of the per-period mean velocity column or variable.
    #[arg(long, value_name = "NAME")]
    var_v_p: Option<String>,
    /// Tolerance of the verdict on the chosen metric's relative error.
    #[arg(long, default_value_t = compare::DEFAULT_TOLERANCE)]
    tolerance: f64,
    /// The error the verdict judges.
    #[arg(long, value_enum, default_value = "v_inf")]
    metric: Metric,
    /// Largest rod deviation accepted as the scene's, relative to the stroke.
    #[arg(long, default_value_t = compare::rod::DEFAULT_ROD_TOLERANCE)]
    rod_tolerance: f64,
    /// |v_R - v_S| below this, relative to max |v_R|, counts as stick.
    #[arg(long, default_value_t = compare::DEFAULT_STICK_TOLERANCE)]
    stick_tolerance: f64,
    /// Print one JSON object instead of the text report.
    #[arg(long)]
    json: bool,
    /// Draw the comparison: .svg, .pdf or .png, with its data as CSV
    /// beside it.
    #[arg(long, value_name = "FILE")]
    figure: Option<PathBuf>,
    /// Print preset of the figure (default: single-column).
    #[arg(long, value_parser = ["single-column", "double-column", "slide"])]
    style: Option<String>,
    /// Periods A..B shown in the figure's velocity panel (default: the
    /// first period with samples).
    #[arg(long, value_name = "A..B", value_parser = parse_range)]
    figure_periods: Option<(u64, u64)>,
}

/// `A..B` with `1 <= A <= B`.
pub(crate) fn parse_range(text: &str) -> Result<(u64, u64), String> {
    let (a, b) = text
        .split_once("..")
        .ok_or_else(|| format!("`{text}` is not a range A..B"))?;
    let a: u64 = a
        .trim()
        .parse()
        .map_err(|_| format!("`{a}` is not a period index"))?;
    let b: u64 = b
        .trim()
        .parse()
        .map_err(|_| format!("`{b}` is not a period index"))?;
    if a < 1 || b < a {
        return Err(format!("`{text}`: need 1 <= A <= B"));
    }
    Ok((a, b))
}

pub(crate) fn compare(args: CompareArgs, streams: &mut Streams<'_>) -> u8 {
    match run(args, streams) {
        Ok(pass) => u8::from(!pass),
        Err(message) => {
            let _ = writeln!(streams.err, "stickslip: {}", super::one_line(&message));
            EXIT_BAD_INPUT
        }
    }
}

/// Checks, before anything runs, that the figure can be written and that
/// neither it nor its data is an input.
fn check_figure(args: &CompareArgs) -> Result<(), String> {
    let Some(figure) = &args.figure else {
        return Ok(());
    };
    super::check_figure_path("--figure", figure)?;
    let data = crate::plot::data_path(figure);
    let mut inputs: Vec<&Path> = vec![args.scene.as_path()];
    inputs.extend(args.data.iter().map(PathBuf::as_path));
    refuse_outputs(&[figure.as_path(), data.as_path()], &inputs)
}

fn run(args: CompareArgs, streams: &mut Streams<'_>) -> Result<bool, String> {
    let scene = super::load_scene(Some(&args.scene), &args.set)?;
    check_figure(&args)?;
    let for_positive = |option: &str, value: f64| {
        if value > 0.0 && value.is_finite() {
            Ok(value)
        } else {
            Err(format!("{option} = {value}: must be a positive number"))
        }
    };
    let options = CompareOptions {
        read: ReadOptions {
            time_unit: args.time_unit,
            length_unit: args.length_unit,
            names: [
                args.var_t,
                args.var_x_s,
                args.var_v_s,
                args.var_x_r,
                args.var_p,
                args.var_v_p,
            ],
        },
        tolerance: for_positive("--tolerance", args.tolerance)?,
        metric: args.metric,
        rod_tolerance: for_positive("--rod-tolerance", args.rod_tolerance)?,
        stick_tolerance: for_positive("--stick-tolerance", args.stick_tolerance)?,
    };
    let report = compare::compare(&scene, &args.data, &options).map_err(|e| e.to_string())?;
    if let Some(path) = &args.figure {
        let name = path
            .file_stem()
            .map_or("compare".to_owned(), |s| s.to_string_lossy().into_owned());
        let figure = crate::plot::compare::figure(&report, args.figure_periods, &name)
            .map_err(|e| e.to_string())?;
        super::write_figure(&figure, args.style.as_deref(), path)?;
    }
    let text = if args.json {
        let mut t = serde_json::to_string_pretty(&report.to_json()).map_err(|e| e.to_string())?;
        t.push('\n');
        t
    } else {
        report.to_text()
    };
    super::write_out(streams, &text)?;
    Ok(report.pass)
}
