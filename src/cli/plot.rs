//! `stickslip plot INPUT -o FILE`: a publication figure of a scene (TOML:
//! its motion over chosen periods, its start-up, or its event timeline) or
//! of a sweep output (CSV: `--x`, `--y`, `--series`, `--facet`, units and
//! labels), written
//! as SVG, PDF or PNG by the extension of `-o`, with its data as CSV
//! beside it (see [`crate::plot`], docs/interface.md).
//!
//! Every argument is checked before anything runs or is written: the
//! output's format, that its directory exists, that neither the figure
//! nor its CSV would overwrite the input, the sizes, and (for a sweep) the
//! columns; a failure is one line and creates nothing. The summary names
//! the files written and prints the figure's caption text (`caption:`
//! lines, the same as the CSV's `# caption:` lines).

use super::{Failure, SceneOptions, Streams, refuse_output_over_input, write_out};
use crate::plot::export::DPI_RANGE;
use crate::plot::motion::{self, Row};
use crate::plot::style::MIN_FONT_PT;
use crate::plot::sweep::{SweepSpec, sweep_figure};
use crate::plot::{Figure, Preset, Style};
use clap::{Args, ValueEnum};
use std::path::{Path, PathBuf};

/// Which figure of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum SceneFigure {
    /// Rod and slider over the chosen periods (--periods, --rows).
    Motion,
    /// Mean velocity per period of the start-up, with v_inf and p_0.99.
    Startup,
    /// The slider's modes and events over the start-up.
    Timeline,
    /// v_inf against the load force, with stall force and output power
    /// (`stickslip characteristic` has more options).
    Characteristic,
}

/// A row of the motion figure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
enum RowArg {
    Velocity,
    Displacement,
    Acceleration,
}

/// Arguments of `plot`.
#[derive(Args)]
pub(crate) struct PlotArgs {
    /// A scene file (.toml) or a sweep output (.csv).
    input: PathBuf,
    /// Output file: .svg, .pdf or .png; the data is written beside it as .csv.
    #[arg(short, long, value_name = "FILE")]
    output: PathBuf,
    /// Print preset: single-column (85 mm), double-column (175 mm) or slide;
    /// default: the figure's own.
    #[arg(long, value_parser = ["single-column", "double-column", "slide"])]
    style: Option<String>,
    /// Width in mm (overrides the preset).
    #[arg(long, value_name = "MM")]
    width: Option<f64>,
    /// Height in mm (default: as the panels need).
    #[arg(long, value_name = "MM")]
    height: Option<f64>,
    /// Text size in pt (at least 7).
    #[arg(long, value_name = "PT")]
    font_size: Option<f64>,
    /// PNG resolution in pixels per inch.
    #[arg(long, default_value_t = 300.0)]
    dpi: f64,
    /// A title above the figure (none by default: journals set captions).
    #[arg(long)]
    title: Option<String>,
    /// Scene: which figure.
    #[arg(long, value_enum, default_value = "motion")]
    figure: SceneFigure,
    /// Scene, motion: the columns, e.g. 1,2,last or 1-5 (last: the steady period).
    #[arg(long, default_value = "1,last")]
    periods: String,
    /// Scene, motion: the rows.
    #[arg(
        long,
        value_enum,
        value_delimiter = ',',
        default_value = "velocity,displacement,acceleration"
    )]
    rows: Vec<RowArg>,
    /// Sweep: the column on the x axis.
    #[arg(long)]
    x: Option<String>,
    /// Sweep: the column (indicator) on the y axis; several (repeated or
    /// comma-separated) of one unit share the axis, named in the legend.
    #[arg(long, value_delimiter = ',', value_name = "COLUMN")]
    y: Vec<String>,
    /// Sweep: one series per value of this column.
    #[arg(long)]
    series: Option<String>,
    /// Sweep: one panel per value of this column.
    #[arg(long)]
    facet: Option<String>,
    /// Sweep: logarithmic x axis.
    #[arg(long)]
    log_x: bool,
    /// Sweep: logarithmic y axis.
    #[arg(long)]
    log_y: bool,
    /// Sweep: a horizontal reference line at this y, in --y-unit if given
    /// (repeatable).
    #[arg(long, value_name = "Y", allow_negative_numbers = true)]
    ref_y: Vec<f64>,
    /// Sweep: a vertical reference line at this x, in --x-unit if given
    /// (repeatable).
    #[arg(long, value_name = "X", allow_negative_numbers = true)]
    ref_x: Vec<f64>,
    /// Sweep: the x axis in this unit (the column is in SI), e.g. ms, um,
    /// mm/s, mN, kHz; reference lines are given in it.
    #[arg(long, value_name = "UNIT")]
    x_unit: Option<String>,
    /// Sweep: the y axis in this unit, as --x-unit.
    #[arg(long, value_name = "UNIT")]
    y_unit: Option<String>,
    /// Sweep: name COLUMN by TEXT (its description and symbol) on axes,
    /// in legends and panel titles, e.g. 'v_inf=$v_∞$ at rest'
    /// (repeatable; $...$ is a quantity: italic, _x subscript).
    #[arg(long, value_name = "COLUMN=TEXT")]
    label: Vec<String>,
    #[command(flatten)]
    options: SceneOptions,
    #[command(flatten)]
    set: super::SceneSet,
}

/// A number in `[lo, hi]`, or a one-line error naming the flag.
fn within(flag: &str, value: f64, (lo, hi): (f64, f64), unit: &str) -> Result<f64, Failure> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(format!("{flag} {value}: must be from {lo} to {hi} {unit}"))
    }
}

/// The style from the preset (or the figure's own) and the explicit sizes.
fn style(args: &PlotArgs, default: Preset) -> Result<Style, Failure> {
    let preset = args
        .style
        .as_deref()
        .and_then(Preset::from_name)
        .unwrap_or(default);
    let mut style = preset.style();
    if let Some(w) = args.width {
        style.width_mm = within("--width", w, (20.0, 1000.0), "mm")?;
    }
    if let Some(h) = args.height {
        style.height_mm = Some(within("--height", h, (20.0, 1000.0), "mm")?);
    }
    if let Some(f) = args.font_size {
        style.font_pt = within("--font-size", f, (MIN_FONT_PT, 72.0), "pt")?;
    }
    style.title = args.title.clone();
    Ok(style)
}

/// Checks the output before any work: format, directory, not an input.
fn check_output(args: &PlotArgs) -> Result<(), Failure> {
    super::check_figure_path("-o", &args.output)?;
    let inputs: [&Path; 1] = [&args.input];
    refuse_output_over_input(&args.output, &inputs)?;
    refuse_output_over_input(&crate::plot::data_path(&args.output), &inputs)?;
    within("--dpi", args.dpi, DPI_RANGE, "pixels per inch")?;
    Ok(())
}

fn is_csv(path: &Path) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("csv"))
}

/// The figure's name: the output's file stem.
fn name_of(output: &Path) -> String {
    output
        .file_stem()
        .map_or("figure".to_owned(), |s| s.to_string_lossy().into_owned())
}

fn sweep_plot(args: &PlotArgs) -> Result<Figure, Failure> {
    let (Some(x), false) = (&args.x, args.y.is_empty()) else {
        return Err(format!(
            "{}: a sweep plot needs --x AXIS and --y INDICATOR",
            args.input.display()
        ));
    };
    let labels = args
        .label
        .iter()
        .map(|l| match l.split_once('=') {
            Some((column, text)) if !column.trim().is_empty() => {
                Ok((column.trim().to_owned(), text.to_owned()))
            }
            _ => Err(format!("--label {l}: expected COLUMN=TEXT")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    let spec = SweepSpec {
        x: x.clone(),
        y: args.y.clone(),
        labels,
        x_unit: args.x_unit.clone(),
        y_unit: args.y_unit.clone(),
        series: args.series.clone(),
        facet: args.facet.clone(),
        log_x: args.log_x,
        log_y: args.log_y,
        ref_y: args.ref_y.clone(),
        ref_x: args.ref_x.clone(),
    };
    sweep_figure(&args.input, &spec, &name_of(&args.output)).map_err(|e| e.to_string())
}

fn scene_plot(args: &PlotArgs, streams: &mut Streams<'_>) -> Result<Figure, Failure> {
    for (flag, given) in [
        ("--x", args.x.is_some()),
        ("--y", !args.y.is_empty()),
        ("--series", args.series.is_some()),
        ("--facet", args.facet.is_some()),
        ("--x-unit", args.x_unit.is_some()),
        ("--y-unit", args.y_unit.is_some()),
        ("--label", !args.label.is_empty()),
    ] {
        if given {
            return Err(format!(
                "{flag}: applies to a sweep output (.csv), and {} is a scene",
                args.input.display()
            ));
        }
    }
    let spans = motion::parse_periods(&args.periods)?;
    let mut scene = super::load_scene(Some(&args.input), &args.set)?;
    args.options.apply(&mut scene, streams);
    let name = name_of(&args.output);
    let rows: Vec<Row> = args
        .rows
        .iter()
        .map(|r| match r {
            RowArg::Velocity => Row::Velocity,
            RowArg::Displacement => Row::Displacement,
            RowArg::Acceleration => Row::Acceleration,
        })
        .collect();
    let figure = match args.figure {
        SceneFigure::Motion => motion::motion(&scene, &spans, &rows, &name),
        SceneFigure::Startup => motion::startup(&scene, &name),
        SceneFigure::Timeline => crate::plot::timeline::scene_timeline(&scene, &name),
        SceneFigure::Characteristic => {
            crate::plot::characteristic::scene_characteristic(&scene, &name)
        }
    };
    figure.map_err(|e| e.to_string())
}

pub(crate) fn plot(args: PlotArgs, streams: &mut Streams<'_>) -> Result<(), Failure> {
    check_output(&args)?;
    // Sizes are checked against a preset before any simulation runs.
    style(&args, Preset::SingleColumn)?;
    if args
        .input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("jsonl"))
    {
        return Err(format!(
            "{}: plot reads sweep outputs as CSV; run the sweep with -o NAME.csv",
            args.input.display()
        ));
    }
    let figure = if is_csv(&args.input) {
        if let Some(first) = args.set.set.first() {
            return Err(format!(
                "--set {}: applies to a scene, and {} is a sweep output",
                first.escape_debug(),
                args.input.display()
            ));
        }
        sweep_plot(&args)?
    } else {
        scene_plot(&args, streams)?
    };
    let style = style(&args, figure.preset)?;
    let [path, csv] = figure
        .write(&args.output, &style, args.dpi)
        .map_err(|e| e.to_string())?;
    // The caption's text (also the CSV's `# caption:` lines), for the
    // figure's caption in the paper.
    let mut summary = format!("wrote {} and {}\n", path.display(), csv.display());
    for note in &figure.plot.notes {
        summary.push_str(&format!("caption: {}\n", crate::plot::visible(note)));
    }
    write_out(streams, &summary)
}
