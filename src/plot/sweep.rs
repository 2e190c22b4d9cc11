//! Any sweep output as a figure: one or more indicators (`--y`) against
//! an axis (`--x`), one series per value of `--series`, one panel per
//! value of `--facet`, optional log axes, reference lines, display units
//! and names given to columns.
//!
//! Contract: the CSV is a sweep output (docs/interface.md section 5: `#`
//! comment lines, a header, one row per case), ours or another tool's with
//! the same columns, its values in SI. Every named column must exist (an
//! unknown one is an error listing the columns). Columns are named from
//! the table of symbols (`src/symbol.rs`) unless [`SweepSpec::labels`]
//! names them; a switch's series or panels read "with …"/"without …",
//! numbers have at most four significant digits. An axis is drawn in SI
//! or in the display unit asked for ([`UNITS`]), which must measure what
//! its column measures (a ratio takes none; an undocumented column is
//! taken to be in SI); the drawn values, and the CSV written beside the
//! figure (its header names the unit), are the SI values times the
//! unit's factor. Several `--y` columns (each once) share one unit and one
//! axis, each named in the legend by its description and symbol; with
//! `--series` their legend entries are the pairs (symbol, value), at most
//! as many as the palette has colours. A row
//! whose `--y` cell is empty is never dropped: it is drawn as a marker on
//! the panel's bottom edge at its x, by reason — `failure` text (failed),
//! a `regime` that is not a steady one (`run-away`, `not_converged`), or
//! no value — and so is a value a log axis cannot show. A series whose x
//! values repeat (other axes vary) is drawn as points, not as a line
//! zig-zagging between them.

mod names;

use super::layout::fitted;
use super::style::{Dash, GREY, Look, Marker, PALETTE};
use super::{Axis, Cell, Csv, Figure, Panel, Plot, PlotError, Preset, Series};
use names::{Names, display_unit, number, si_unit};
pub use names::{UNITS, Unit};
use std::collections::HashMap;
use std::path::Path;

/// What to plot from a sweep output.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepSpec {
    /// Column on the horizontal axis.
    pub x: String,
    /// Columns on the vertical axis: one, or several of one unit (drawn
    /// on one axis, told apart by the legend).
    pub y: Vec<String>,
    /// Column whose values make the series.
    pub series: Option<String>,
    /// Column whose values make the panels.
    pub facet: Option<String>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Horizontal reference lines at these y values (in the y axis's
    /// display unit).
    pub ref_y: Vec<f64>,
    /// Vertical reference lines at these x values (in the x axis's
    /// display unit).
    pub ref_x: Vec<f64>,
    /// Names given to columns (column, text in the quantity markup): they
    /// replace the table of symbols' description and symbol wherever the
    /// column is named (axis, legend, panel title); units stay.
    pub labels: Vec<(String, String)>,
    /// The x axis's display unit (`ms`, `µm`, `mm/s`; see [`UNITS`]); the
    /// column holds SI values.
    pub x_unit: Option<String>,
    /// The y axis's display unit, as `x_unit`.
    pub y_unit: Option<String>,
}

/// Regimes with a steady state (docs/interface.md, `regime`).
const STEADY_REGIMES: [&str; 3] = ["stuck", "stick-slip", "slip-slip"];

/// Why a row has no point on the plot.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord)]
enum Flag {
    Failed,
    Unsettled(String),
    NoValue,
    OffLogAxis,
}

impl Flag {
    fn label(&self) -> String {
        match self {
            Flag::Failed => "failed".to_owned(),
            Flag::Unsettled(r) => r.clone(),
            Flag::NoValue => "no value".to_owned(),
            Flag::OffLogAxis => "≤ 0, off the log axis".to_owned(),
        }
    }

    fn look(&self, i: usize) -> Look {
        let marker = match self {
            Flag::Failed => Marker::Cross,
            Flag::Unsettled(_) => [Marker::Plus, Marker::TriangleDown, Marker::Diamond][i % 3],
            Flag::NoValue => Marker::Square,
            Flag::OffLogAxis => Marker::Triangle,
        };
        Look {
            color: if *self == Flag::Failed {
                PALETTE[2]
            } else {
                GREY
            },
            dash: Dash::NoLine,
            marker,
            weight: 1.0,
        }
    }
}

/// One row as plotted: x and each `--y` value in drawn units.
struct Row {
    x: f64,
    ys: Vec<Result<f64, Flag>>,
    series: String,
    facet: String,
}

fn column_index(
    headers: &csv::StringRecord,
    name: &str,
    flag: &str,
    path: &str,
) -> Result<usize, PlotError> {
    headers.iter().position(|h| h == name).ok_or_else(|| {
        let names: Vec<&str> = headers.iter().collect();
        PlotError::Argument(format!(
            "{flag} {name}: no such column in {}; its columns are {}",
            path,
            names.join(", ")
        ))
    })
}

/// Reads the sweep output at `path` and draws it as `spec` says.
pub fn sweep_figure(path: &Path, spec: &SweepSpec, name: &str) -> Result<Figure, PlotError> {
    check_spec(spec)?;
    let file = std::fs::File::open(path)
        .map_err(|e| PlotError::Argument(format!("{}: {e}", path.display())))?;
    sweep_figure_from(
        std::io::BufReader::new(file),
        &path.display().to_string(),
        spec,
        name,
    )
}

/// What can be checked before the data is read: at least one `--y`,
/// several of one unit, units that fit their columns, labels in closed
/// markup, and reference lines finite (and positive on a log axis).
fn check_spec(spec: &SweepSpec) -> Result<Axes, PlotError> {
    if spec.y.is_empty() {
        return Err(PlotError::Argument(
            "--y: a sweep plot needs at least one column".to_owned(),
        ));
    }
    let repeated = spec
        .y
        .iter()
        .enumerate()
        .find(|(i, c)| spec.y[..*i].contains(c));
    if let Some((_, twice)) = repeated {
        return Err(PlotError::Argument(format!(
            "--y {}: names {twice} twice",
            spec.y.join(",")
        )));
    }
    let units: Vec<Option<&str>> = spec.y.iter().map(|c| si_unit(c)).collect();
    if units.iter().any(|u| *u != units[0]) {
        let each: Vec<String> = spec
            .y
            .iter()
            .zip(&units)
            .map(|(c, u)| format!("{c} in {}", u.unwrap_or("an unknown unit")))
            .collect();
        return Err(PlotError::Argument(format!(
            "--y {}: columns on one axis share a unit, and these are {}",
            spec.y.join(","),
            each.join(", ")
        )));
    }
    for (column, text) in &spec.labels {
        if text.trim().is_empty() || text.matches('$').count() % 2 != 0 {
            return Err(PlotError::Argument(format!(
                "--label {column}={text}: the text must be non-empty with each $ closed"
            )));
        }
    }
    for (log, flag, refs) in [
        (spec.log_x, "--ref-x", &spec.ref_x),
        (spec.log_y, "--ref-y", &spec.ref_y),
    ] {
        if let Some(v) = refs.iter().find(|v| !v.is_finite() || (log && **v <= 0.0)) {
            return Err(PlotError::Argument(format!(
                "{flag} {v}: a reference line must be finite, and positive on a log axis (--log-x, --log-y)"
            )));
        }
    }
    let (x_scale, x_unit) = display_unit(
        "--x-unit",
        spec.x_unit.as_deref(),
        std::slice::from_ref(&spec.x),
    )?;
    let (y_scale, y_unit) = display_unit("--y-unit", spec.y_unit.as_deref(), &spec.y)?;
    Ok(Axes {
        x_scale,
        x_unit,
        y_scale,
        y_unit,
    })
}

/// The factors from SI to drawn values and the units shown.
struct Axes {
    x_scale: f64,
    x_unit: Option<&'static str>,
    y_scale: f64,
    y_unit: Option<&'static str>,
}

/// Draws the sweep output read from `input` (named `path` in messages)
/// as `spec` says.
pub fn sweep_figure_from(
    input: impl std::io::Read,
    path: &str,
    spec: &SweepSpec,
    name: &str,
) -> Result<Figure, PlotError> {
    let axes = check_spec(spec)?;
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(input);
    let bad_csv = |e: csv::Error| PlotError::Argument(format!("{}: not a sweep CSV: {e}", path));
    let headers = reader.headers().map_err(bad_csv)?.clone();
    let ix = column_index(&headers, &spec.x, "--x", path)?;
    let iys = spec
        .y
        .iter()
        .map(|y| column_index(&headers, y, "--y", path))
        .collect::<Result<Vec<_>, _>>()?;
    let is = spec
        .series
        .as_deref()
        .map(|s| column_index(&headers, s, "--series", path))
        .transpose()?;
    let ifacet = spec
        .facet
        .as_deref()
        .map(|s| column_index(&headers, s, "--facet", path))
        .transpose()?;
    for (column, _) in &spec.labels {
        column_index(&headers, column, "--label", path)?;
    }
    let ifail = headers.iter().position(|h| h == "failure");
    let iregime = headers.iter().position(|h| h == "regime");
    let mut rows = Vec::new();
    let mut record = csv::StringRecord::new();
    let mut line = 0usize;
    while reader.read_record(&mut record).map_err(bad_csv)? {
        line += 1;
        let cell = |i: usize| record.get(i).unwrap_or("").trim();
        let number = |i: usize, column: &str| -> Result<Option<f64>, PlotError> {
            let text = cell(i);
            if text.is_empty() {
                return Ok(None);
            }
            match text {
                "true" => return Ok(Some(1.0)),
                "false" => return Ok(Some(0.0)),
                _ => {}
            }
            match text.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(Some(v)),
                _ => Err(PlotError::Argument(format!(
                    "{}: data row {line}: column {column} = \"{text}\" is not a number",
                    path
                ))),
            }
        };
        let Some(x) = number(ix, &spec.x)? else {
            return Err(PlotError::Argument(format!(
                "{}: data row {line}: column {} (--x) is empty",
                path, spec.x
            )));
        };
        let mut ys = Vec::with_capacity(iys.len());
        for (&iy, column) in iys.iter().zip(&spec.y) {
            ys.push(match number(iy, column)? {
                Some(v) if spec.log_y && v <= 0.0 => Err(Flag::OffLogAxis),
                Some(v) => Ok(v * axes.y_scale),
                None => Err(if ifail.is_some_and(|i| !cell(i).is_empty()) {
                    Flag::Failed
                } else if let Some(r) = iregime
                    .map(cell)
                    .filter(|r| !r.is_empty() && !STEADY_REGIMES.contains(r))
                {
                    Flag::Unsettled(r.to_owned())
                } else {
                    Flag::NoValue
                }),
            });
        }
        if spec.log_x && x <= 0.0 {
            return Err(PlotError::Argument(format!(
                "--log-x: {}: data row {line}: {} = {x} is not positive",
                path, spec.x
            )));
        }
        rows.push(Row {
            x: x * axes.x_scale,
            ys,
            series: is.map(|i| cell(i).to_owned()).unwrap_or_default(),
            facet: ifacet.map(|i| cell(i).to_owned()).unwrap_or_default(),
        });
    }
    if rows.is_empty() {
        return Err(PlotError::Argument(format!("{}: no data rows", path)));
    }
    draw(rows, spec, &axes, name, path)
}

/// Distinct values in order: numerically when all are numbers, else in
/// order of first appearance.
fn distinct<'a>(values: impl Iterator<Item = &'a str>) -> Vec<String> {
    let mut seen: Vec<String> = Vec::new();
    let mut index: HashMap<&str, ()> = HashMap::new();
    for v in values {
        if index.insert(v, ()).is_none() {
            seen.push(v.to_owned());
        }
    }
    if seen.iter().all(|v| v.parse::<f64>().is_ok()) {
        seen.sort_by(|a, b| {
            a.parse::<f64>()
                .unwrap_or(0.0)
                .total_cmp(&b.parse::<f64>().unwrap_or(0.0))
        });
    }
    seen
}

/// The legend entry of reference lines at `values` of `columns` drawn in
/// `unit`: the quantity and its values (`$v_∞$ = 0.06 m/s`).
fn reference_label(
    names: &Names,
    columns: &[String],
    values: &[f64],
    unit: Option<&str>,
) -> String {
    let what = match columns {
        [one] => names.short(one),
        _ => "reference".to_owned(),
    };
    let values: Vec<String> = values.iter().map(|v| number(*v)).collect();
    let unit = unit.map_or(String::new(), |u| format!(" {u}"));
    format!("{what} = {}{unit}", values.join(", "))
}

fn draw(
    rows: Vec<Row>,
    spec: &SweepSpec,
    axes: &Axes,
    name: &str,
    path: &str,
) -> Result<Figure, PlotError> {
    let names = Names {
        labels: &spec.labels,
    };
    let facets = distinct(rows.iter().map(|r| r.facet.as_str()));
    let series = distinct(rows.iter().map(|r| r.series.as_str()));
    if let Some(col) = spec.series.as_deref()
        && spec.y.len() > 1
        && spec.y.len() * series.len() > PALETTE.len()
    {
        return Err(PlotError::Argument(format!(
            "--series {col}: {} --y columns times {} values make {} legend entries, more than {} told apart by colour; use --facet {col}, or one --y",
            spec.y.len(),
            series.len(),
            spec.y.len() * series.len(),
            PALETTE.len()
        )));
    }
    let mut flags: Vec<Flag> = rows
        .iter()
        .flat_map(|r| r.ys.iter().filter_map(|y| y.clone().err()))
        .collect();
    flags.sort();
    flags.dedup();
    let mut x_axis = fitted(
        &names.axis(std::slice::from_ref(&spec.x), axes.x_unit),
        rows.iter().map(|r| r.x).chain(spec.ref_x.iter().copied()),
        spec.log_x,
        0.04,
    );
    if rows.iter().all(|r| r.x.fract() == 0.0) {
        x_axis = x_axis.integers();
    }
    let ys = rows
        .iter()
        .flat_map(|r| r.ys.iter().filter_map(|y| y.as_ref().ok().copied()))
        .chain(spec.ref_y.iter().copied());
    let mut y_axis = fitted(&names.axis(&spec.y, axes.y_unit), ys, spec.log_y, 0.06);
    if rows.iter().all(|r| r.ys.iter().all(Result::is_err)) && spec.ref_y.is_empty() {
        y_axis = if spec.log_y {
            Axis::log(&y_axis.label, (1.0, 10.0))
        } else {
            Axis::linear(&y_axis.label, (0.0, 1.0))
        };
    }
    let bottom = y_axis.range.0;
    let header = |axis: &str, unit: Option<&str>| match unit {
        Some(u) => format!("{axis} ({u})"),
        None => axis.to_owned(),
    };
    let in_unit = |unit: Option<&str>| unit.map_or(String::new(), |u| format!(" in {u}"));
    let mut csv = Csv::new(
        &[
            &format!(
                "Sweep plot of {}: {}{} against {}{}.",
                path,
                spec.y.join(", "),
                in_unit(axes.y_unit),
                spec.x,
                in_unit(axes.x_unit)
            ),
            "status: ok, or why the row has no point (failed; its regime without a steady state, e.g. run-away; no value; off the log axis); such rows are drawn on the bottom edge.",
        ],
        &[
            "facet",
            "series",
            "y_column",
            &header("x", axes.x_unit),
            &header("y", axes.y_unit),
            "status",
        ],
    );
    for r in &rows {
        for (column, y) in spec.y.iter().zip(&r.ys) {
            let (y, status) = match y {
                Ok(v) => (Cell::F(*v), "ok".to_owned()),
                Err(f) => (Cell::S(""), f.label()),
            };
            csv.row(&[
                Cell::S(&r.facet),
                Cell::S(&r.series),
                Cell::S(column),
                Cell::F(r.x),
                y,
                Cell::S(&status),
            ]);
        }
    }
    let mut panels = Vec::new();
    let mut points_only = false;
    for facet in &facets {
        let title = spec.facet.as_ref().map(|f| names.value(f, facet));
        let mut panel = Panel::new(title.as_deref(), x_axis.clone(), y_axis.clone());
        if !spec.ref_y.is_empty() {
            let label = reference_label(&names, &spec.y, &spec.ref_y, axes.y_unit);
            for &ry in &spec.ref_y {
                panel.series.push(Series::hline(
                    Some(&label),
                    ry,
                    x_axis.range,
                    Look::reference(),
                ));
            }
        }
        if !spec.ref_x.is_empty() {
            let label = reference_label(
                &names,
                std::slice::from_ref(&spec.x),
                &spec.ref_x,
                axes.x_unit,
            );
            for &rx in &spec.ref_x {
                panel.series.push(Series::line(
                    Some(&label),
                    vec![(rx, y_axis.range.0), (rx, y_axis.range.1)],
                    Look {
                        dash: Dash::Dotted,
                        ..Look::reference()
                    },
                ));
            }
        }
        for (k, column) in spec.y.iter().enumerate() {
            for (j, s) in series.iter().enumerate() {
                let i = k * series.len() + j;
                let mut pts: Vec<(f64, f64)> = rows
                    .iter()
                    .filter(|r| &r.facet == facet && &r.series == s)
                    .filter_map(|r| r.ys[k].as_ref().ok().map(|y| (r.x, *y)))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let repeated = pts.windows(2).any(|w| w[0].0 == w[1].0);
                points_only |= repeated;
                let label = match (&spec.series, spec.y.len()) {
                    (Some(col), 1) => names.value(col, s),
                    (Some(col), _) => format!("{}, {}", names.short(column), names.value(col, s)),
                    (None, 1) => names.short(column),
                    (None, _) => names.long(column),
                };
                let mut look = Look::nth(i);
                if (repeated || pts.len() <= 40) && look.marker == Marker::None {
                    look.marker = [
                        Marker::Circle,
                        Marker::Square,
                        Marker::Triangle,
                        Marker::Diamond,
                    ][i % 4];
                }
                if repeated {
                    // Points only: the markers, not the dashes, tell the
                    // series apart (six shapes before one repeats).
                    panel
                        .series
                        .push(Series::points(Some(&label), pts, Look::nth_points(i)));
                } else {
                    panel.series.push(Series::line(Some(&label), pts, look));
                }
            }
        }
        for (k, flag) in flags.iter().enumerate() {
            // A row flagged in several `--y` columns is one marker.
            let flagged = |r: &Row| r.ys.iter().any(|y| y.as_ref().err() == Some(flag));
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| &r.facet == facet && flagged(r))
                .map(|r| (r.x, bottom))
                .collect();
            pts.dedup();
            let count = rows.iter().filter(|r| flagged(r)).count();
            let label = format!("{} ({count}, at the bottom)", flag.label());
            panel
                .series
                .push(Series::points(Some(&label), pts, flag.look(k)));
        }
        panels.push(panel);
    }
    let columns = facets.len().min(3);
    let mut notes = Vec::new();
    if points_only {
        notes.push("several rows share an x value (other axes vary): drawn as points".to_owned());
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(panels, columns, 0.68).with_notes(notes),
        csv: csv.finish(),
        preset: if columns > 1 {
            Preset::DoubleColumn
        } else {
            Preset::SingleColumn
        },
    })
}
