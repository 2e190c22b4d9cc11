//! Any sweep output as a figure: an indicator (`--y`) against an axis
//! (`--x`), one series per value of `--series`, one panel per value of
//! `--facet`, optional log axes and reference lines.
//!
//! Contract: the CSV is a sweep output (docs/interface.md section 5: `#`
//! comment lines, a header, one row per case), ours or another tool's with
//! the same columns. Every named column must exist (an unknown one is an
//! error listing the columns). A row whose `--y` cell is empty is never
//! dropped: it is drawn as a marker on the panel's bottom edge at its x,
//! by reason — `failure` text (failed), a `regime` that is not a steady
//! one (`run-away`, `not_converged`), or no value — and so is a value a
//! log axis cannot show. A series whose x values repeat (other axes vary)
//! is drawn as points, not as a line zig-zagging between them.

use super::layout::fitted;
use super::style::{Dash, GREY, Look, Marker, PALETTE};
use super::{Axis, Cell, Csv, Figure, Panel, Plot, PlotError, Preset, Series};
use crate::indicator::Indicator;
use crate::symbol::symbol;
use std::collections::HashMap;
use std::path::Path;

/// What to plot from a sweep output.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SweepSpec {
    /// Column on the horizontal axis.
    pub x: String,
    /// Column on the vertical axis.
    pub y: String,
    /// Column whose values make the series.
    pub series: Option<String>,
    /// Column whose values make the panels.
    pub facet: Option<String>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Horizontal reference lines at these y values.
    pub ref_y: Vec<f64>,
    /// Vertical reference lines at these x values.
    pub ref_x: Vec<f64>,
}

/// Regimes with a steady state (docs/interface.md, `regime`).
const STEADY_REGIMES: [&str; 3] = ["stuck", "stick-slip", "slip-slip"];

/// Units of the documented columns the table of symbols does not name,
/// for axis labels.
fn unit(column: &str) -> Option<&'static str> {
    if let Ok(indicator) = column.parse::<Indicator>() {
        return Some(indicator.unit()).filter(|u| *u != "1");
    }
    Some(match column {
        "error_v_inf" => "m/s",
        "period" | "wall_time_s" => "s",
        "apparent_power" => "VA",
        "stroke" => "m",
        "contact_force" => "N",
        "slider_mass" => "kg",
        "extra_acceleration" => "m/s²",
        _ => return None,
    })
}

/// A column's name as words (another tool's column, not in the table of
/// symbols): underscores become spaces.
fn words(column: &str) -> String {
    column.replace('_', " ")
}

/// The axis label of a column: description, symbol and unit from the
/// table of symbols, or the column's name in words and its unit.
fn axis_label(column: &str) -> String {
    if let Some(s) = symbol(column) {
        return s.label();
    }
    match unit(column) {
        Some(u) => format!("{} ({u})", words(column)),
        None => words(column),
    }
}

/// How a series or facet of `column` = `value` is named: "with" or
/// "without" for a switch, the symbol (or the column in words) and the
/// value otherwise.
fn value_label(column: &str, value: &str) -> String {
    let sym = symbol(column);
    let what = sym.map_or_else(|| words(column), |s| s.description.to_owned());
    match value {
        "true" if !what.is_empty() => format!("with {what}"),
        "false" if !what.is_empty() => format!("without {what}"),
        _ => format!(
            "{} = {value}",
            sym.map_or_else(|| words(column), |s| s.quantity.to_owned())
        ),
    }
}

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

/// One row as plotted.
struct Row {
    x: f64,
    y: Result<f64, Flag>,
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
    check_references(spec)?;
    let file = std::fs::File::open(path)
        .map_err(|e| PlotError::Argument(format!("{}: {e}", path.display())))?;
    sweep_figure_from(
        std::io::BufReader::new(file),
        &path.display().to_string(),
        spec,
        name,
    )
}

/// Reference lines are finite, and positive on a log axis.
fn check_references(spec: &SweepSpec) -> Result<(), PlotError> {
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
    Ok(())
}

/// Draws the sweep output read from `input` (named `path` in messages)
/// as `spec` says.
pub fn sweep_figure_from(
    input: impl std::io::Read,
    path: &str,
    spec: &SweepSpec,
    name: &str,
) -> Result<Figure, PlotError> {
    check_references(spec)?;
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_reader(input);
    let bad_csv = |e: csv::Error| PlotError::Argument(format!("{}: not a sweep CSV: {e}", path));
    let headers = reader.headers().map_err(bad_csv)?.clone();
    let ix = column_index(&headers, &spec.x, "--x", path)?;
    let iy = column_index(&headers, &spec.y, "--y", path)?;
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
        let y = match number(iy, &spec.y)? {
            Some(v) if spec.log_y && v <= 0.0 => Err(Flag::OffLogAxis),
            Some(v) => Ok(v),
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
        };
        if spec.log_x && x <= 0.0 {
            return Err(PlotError::Argument(format!(
                "--log-x: {}: data row {line}: {} = {x} is not positive",
                path, spec.x
            )));
        }
        rows.push(Row {
            x,
            y,
            series: is.map(|i| cell(i).to_owned()).unwrap_or_default(),
            facet: ifacet.map(|i| cell(i).to_owned()).unwrap_or_default(),
        });
    }
    if rows.is_empty() {
        return Err(PlotError::Argument(format!("{}: no data rows", path)));
    }
    draw(rows, spec, name, path)
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

fn draw(rows: Vec<Row>, spec: &SweepSpec, name: &str, path: &str) -> Result<Figure, PlotError> {
    let facets = distinct(rows.iter().map(|r| r.facet.as_str()));
    let series = distinct(rows.iter().map(|r| r.series.as_str()));
    let mut flags: Vec<Flag> = rows.iter().filter_map(|r| r.y.clone().err()).collect();
    flags.sort();
    flags.dedup();
    let mut x_axis = fitted(
        &axis_label(&spec.x),
        rows.iter().map(|r| r.x).chain(spec.ref_x.iter().copied()),
        spec.log_x,
        0.04,
    );
    if rows.iter().all(|r| r.x.fract() == 0.0) {
        x_axis = x_axis.integers();
    }
    let ys = rows
        .iter()
        .filter_map(|r| r.y.as_ref().ok().copied())
        .chain(spec.ref_y.iter().copied());
    let mut y_axis = fitted(&axis_label(&spec.y), ys, spec.log_y, 0.06);
    if rows.iter().all(|r| r.y.is_err()) && spec.ref_y.is_empty() {
        y_axis = if spec.log_y {
            Axis::log(&y_axis.label, (1.0, 10.0))
        } else {
            Axis::linear(&y_axis.label, (0.0, 1.0))
        };
    }
    let bottom = y_axis.range.0;
    let mut csv = Csv::new(
        &[
            &format!("Sweep plot of {}: {} against {}.", path, spec.y, spec.x),
            "status: ok, or why the row has no point (failed; its regime without a steady state, e.g. run-away; no value; off the log axis); such rows are drawn on the bottom edge.",
        ],
        &["facet", "series", "x", "y", "status"],
    );
    for r in &rows {
        let (y, status) = match &r.y {
            Ok(v) => (Cell::F(*v), "ok".to_owned()),
            Err(f) => (Cell::S(""), f.label()),
        };
        csv.row(&[
            Cell::S(&r.facet),
            Cell::S(&r.series),
            Cell::F(r.x),
            y,
            Cell::S(&status),
        ]);
    }
    let mut panels = Vec::new();
    let mut points_only = false;
    for facet in &facets {
        let title = spec.facet.as_ref().map(|f| value_label(f, facet));
        let mut panel = Panel::new(title.as_deref(), x_axis.clone(), y_axis.clone());
        for &ry in &spec.ref_y {
            panel.series.push(Series::hline(
                Some("reference"),
                ry,
                x_axis.range,
                Look::reference(),
            ));
        }
        for &rx in &spec.ref_x {
            panel.series.push(Series::line(
                Some("reference"),
                vec![(rx, y_axis.range.0), (rx, y_axis.range.1)],
                Look::reference(),
            ));
        }
        for (i, s) in series.iter().enumerate() {
            let mut pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| &r.facet == facet && &r.series == s)
                .filter_map(|r| r.y.as_ref().ok().map(|y| (r.x, *y)))
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let repeated = pts.windows(2).any(|w| w[0].0 == w[1].0);
            points_only |= repeated;
            let label = match &spec.series {
                Some(col) => value_label(col, s),
                None => symbol(&spec.y).map_or_else(|| words(&spec.y), |s| s.quantity.to_owned()),
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
                panel.series.push(Series::points(
                    Some(&label),
                    pts,
                    Look {
                        dash: Dash::NoLine,
                        ..look
                    },
                ));
            } else {
                panel.series.push(Series::line(Some(&label), pts, look));
            }
        }
        for (k, flag) in flags.iter().enumerate() {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| &r.facet == facet && r.y.as_ref().err() == Some(flag))
                .map(|r| (r.x, bottom))
                .collect();
            let count = rows
                .iter()
                .filter(|r| r.y.as_ref().err() == Some(flag))
                .count();
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
