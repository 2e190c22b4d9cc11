//! The figure of `stickslip compare` ([`crate::compare`]).
//!
//! Panel (a): the slider velocity `v_S` of the first file with samples
//! (at most 40 of its samples, as markers) on the exact one over chosen
//! periods. Panel (b): the per-period
//! error `v_p,user - v_p` against the period `p`, for at most
//! [`MAX_SERIES`] files (with more, the files of the smallest and the
//! largest step and evenly spaced ones between; the note names them).
//! Panel (c), with two or more files with a step: the step-size part of
//! the `v_inf` error (relative, `abs(v_p,user(P) - v_p(P)) / abs(v_inf)`)
//! against the step `h` on logarithmic axes, with the fitted order line
//! when the fit is supported. A file is named in the legend by what
//! tells it from the others, its step (`h = 1 µs`), or by its place in
//! the command line (`file 2`) when it has no step or shares its step
//! with another; the file names are the user's, not the figure's, and go
//! to the notes (the caption), beside the exact `v_inf` and, for a file
//! that ends before the start-up is over, the split of its `v_inf` error.
//! The CSV beside the figure holds every drawn point: `panel, series, x,
//! y` in SI units (s, m/s, periods, 1), the series of a file named by its
//! file name.
//!
//! `reference_figure` (crate-private) makes the figure without files: the scene's own
//! fixed-step reference at two resolutions, exported as a user's program
//! would (`compare::reference`) and compared by the path the command
//! line takes after reading ([`crate::compare::compare_data`]).

use super::style::{Dash, Marker};
use super::{Axis, Cell, Csv, Figure, Look, Panel, Plot, PlotError, Preset, Series};
use crate::compare::{FileReport, Metric, Report};

/// Most files drawn in panel (b).
pub const MAX_SERIES: usize = 4;

/// Most of the user's samples marked in panel (a).
const USER_MARKERS: usize = 40;

/// The short name of a file (its name without directories).
fn short(file: &str) -> String {
    std::path::Path::new(file)
        .file_name()
        .map_or(file.to_owned(), |n| n.to_string_lossy().into_owned())
}

/// A step in the unit that suits it, to three significant digits.
fn step_text(h: f64) -> String {
    let (scale, unit) = if h < 1e-6 {
        (1e9, "ns")
    } else if h < 1e-3 {
        (1e6, "µs")
    } else if h < 1.0 {
        (1e3, "ms")
    } else {
        (1.0, "s")
    };
    let v = h * scale;
    let digits = if v >= 100.0 {
        0
    } else if v >= 10.0 {
        1
    } else {
        2
    };
    let text = format!("{v:.digits$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    };
    format!("$h$ = {text} {unit}")
}

/// The legend's name of each file of `report` (see the module doc).
fn labels(report: &Report) -> Vec<String> {
    let by_step: Vec<Option<String>> = report.files.iter().map(|f| f.step.map(step_text)).collect();
    by_step
        .iter()
        .enumerate()
        .map(|(i, s)| match s {
            Some(text) if by_step.iter().filter(|o| o.as_ref() == Some(text)).count() == 1 => {
                text.clone()
            }
            _ => format!("file {}", i + 1),
        })
        .collect()
}

/// The label of `file` (one of `report.files`).
fn label_of<'a>(report: &Report, labels: &'a [String], file: &FileReport) -> &'a str {
    let i = report
        .files
        .iter()
        .position(|f| std::ptr::eq(f, file))
        .unwrap_or(0);
    &labels[i]
}

/// The files of panel (b): all up to [`MAX_SERIES`], else the smallest and
/// largest step and evenly spaced ones between (by step, or file order).
fn chosen(report: &Report) -> Vec<&FileReport> {
    let mut files: Vec<&FileReport> = report
        .files
        .iter()
        .filter(|f| !f.period_errors.is_empty())
        .collect();
    if files.len() <= MAX_SERIES {
        return files;
    }
    files.sort_by(|a, b| {
        a.step
            .unwrap_or(f64::INFINITY)
            .total_cmp(&b.step.unwrap_or(f64::INFINITY))
    });
    let n = files.len();
    (0..MAX_SERIES)
        .map(|i| files[(i * (n - 1) + (MAX_SERIES - 1) / 2) / (MAX_SERIES - 1)])
        .collect()
}

/// A range around the values (or a unit range without any).
fn range(values: impl IntoIterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = super::min_max(values);
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    if hi > lo {
        super::padded(lo, hi, pad)
    } else {
        let w = if lo == 0.0 { 1e-12 } else { lo.abs() * 1e-3 };
        (lo - w, hi + w)
    }
}

/// The figure of `report`, panel (a) over periods `from..=to` (1-based;
/// `None`: the first period with samples), named `name`.
pub fn figure(
    report: &Report,
    periods: Option<(u64, u64)>,
    name: &str,
) -> Result<Figure, PlotError> {
    let period = report.signal.period;
    let labels = labels(report);
    let mut csv = Csv::new(
        &[
            &format!("stickslip compare: exact v_inf = {:e} m/s", report.v_inf),
            "panel a: x = t (s), y = v_S (m/s); panel b: x = period p, y = v_p,user - v_p (m/s); \
             panel c: x = step h (s), y = step-size part of the v_inf error, relative",
        ],
        &["panel", "series", "x", "y"],
    );
    let mut panels = Vec::new();
    let mut notes = Vec::new();
    if let Some(f) = report.files.iter().find(|f| !f.velocity.is_empty()) {
        let (a, b) = periods.unwrap_or_else(|| {
            let p = (f.velocity[0].0 / period).floor() as u64 + 1;
            (p, p)
        });
        let (t0, t1) = ((a - 1) as f64 * period, b as f64 * period);
        let pts: Vec<&(f64, f64, f64)> = f
            .velocity
            .iter()
            // A sample at an end, as written to a few digits, is in.
            .filter(|s| s.0 >= t0 - 1e-9 * period && s.0 <= t1 + 1e-9 * period)
            .collect();
        if pts.is_empty() {
            return Err(PlotError::Data {
                figure: name.to_owned(),
                reason: format!(
                    "--figure-periods {a}..{b}: {} has no samples in these periods",
                    f.file
                ),
            });
        }
        let y = range(pts.iter().flat_map(|s| [s.1, s.2]), 0.05);
        let x = (pts[0].0, pts[pts.len() - 1].0);
        let title = if a == b {
            format!("(a) slider velocity, period {a}")
        } else {
            format!("(a) slider velocity, periods {a}–{b}")
        };
        let mut panel = Panel::new(
            Some(&title),
            Axis::linear("time $t$ (ms)", (x.0 * 1e3, x.1 * 1e3)).scaled(1e3),
            Axis::linear("$v_S$ (m/s)", y),
        );
        let exact: Vec<(f64, f64)> = pts.iter().map(|s| (s.0, s.2)).collect();
        // The user's samples as markers on the exact curve, at most
        // USER_MARKERS of them (evenly picked) so that both stay visible.
        let every = pts.len().div_ceil(USER_MARKERS).max(1);
        let user: Vec<(f64, f64)> = pts.iter().step_by(every).map(|s| (s.0, s.1)).collect();
        for (series, points) in [("exact", &exact), ("user", &user)] {
            for (t, v) in points.iter() {
                csv.row(&[Cell::S("a"), Cell::S(series), Cell::F(*t), Cell::F(*v)]);
            }
        }
        panel.series.push(Series::line(
            Some("exact $v_S$"),
            exact,
            Look::nth(0).weighted(1.4),
        ));
        panel.series.push(Series::points(
            Some(&format!("$v_S$ samples, {}", label_of(report, &labels, f))),
            user,
            // In the colour of the file's line in panel (b).
            match chosen(report).iter().position(|s| std::ptr::eq(*s, f)) {
                Some(i) => Look {
                    color: Look::nth(i + 2).color,
                    ..Look::nth_points(1)
                },
                None => Look::nth_points(1),
            },
        ));
        panels.push(panel);
    }
    let shown = chosen(report);
    if !shown.is_empty() {
        let p_max = shown
            .iter()
            .flat_map(|f| f.period_errors.iter().map(|e| e.0))
            .max()
            .unwrap_or(1) as f64;
        let p_min = shown
            .iter()
            .flat_map(|f| f.period_errors.iter().map(|e| e.0))
            .min()
            .unwrap_or(1) as f64;
        let y = range(
            shown
                .iter()
                .flat_map(|f| f.period_errors.iter().map(|e| e.1 * 1e3))
                .chain([0.0]),
            0.05,
        );
        let mut panel = Panel::new(
            Some("(b) per-period error of $v_p$"),
            Axis::linear("period $p$", (p_min, p_max.max(p_min + 1.0))).integers(),
            Axis::linear("$v_{p,user} − v_p$ (mm/s)", y).scaled(1e3),
        );
        for (i, f) in shown.iter().enumerate() {
            let label = short(&f.file);
            let shown_as = label_of(report, &labels, f);
            let pts: Vec<(f64, f64)> = f.period_errors.iter().map(|e| (e.0 as f64, e.1)).collect();
            for (p, e) in &pts {
                csv.row(&[Cell::S("b"), Cell::S(&label), Cell::F(*p), Cell::F(*e)]);
            }
            panel
                .series
                .push(Series::line(Some(shown_as), pts, Look::nth(i + 2)));
        }
        let total = report
            .files
            .iter()
            .filter(|f| !f.period_errors.is_empty())
            .count();
        if total > shown.len() {
            notes.push(format!(
                "(b) shows {} of {total} files: the smallest and the largest step and evenly \
                 spaced ones between.",
                shown.len()
            ));
        }
        panels.push(panel);
    }
    let steps: Vec<(f64, f64, &str)> = report
        .files
        .iter()
        .filter_map(|f| {
            let e = f.judged(Metric::v_inf)?.relative;
            Some((f.step?, e, f.file.as_str()))
        })
        .filter(|(_, e, _)| *e > 0.0)
        .collect();
    if steps.len() >= 2 {
        let x = super::fitted("step $h$ (s)", steps.iter().map(|s| s.0), true, 0.1);
        let y_axis = super::fitted(
            "step-size part of the $v_∞$ error (relative)",
            steps.iter().map(|s| s.1),
            true,
            0.15,
        );
        let mut panel = Panel::new(Some("(c) $v_∞$ error against the step"), x.clone(), y_axis);
        for (h, e, file) in &steps {
            csv.row(&[
                Cell::S("c"),
                Cell::S(&short(file)),
                Cell::F(*h),
                Cell::F(*e),
            ]);
        }
        panel.series.push(Series::points(
            Some("$v_∞$ error, one point per file"),
            steps.iter().map(|s| (s.0, s.1)).collect(),
            Look::nth_points(0).with_marker(Marker::Circle),
        ));
        let fit = report
            .convergence
            .iter()
            .find(|(m, _)| *m == Metric::v_inf)
            .map(|(_, f)| f);
        if let Some((q, se)) = fit
            .filter(|f| f.supported)
            .and_then(|f| Some((f.order?, f.standard_error?)))
        {
            // The least-squares line through the points' logarithms.
            let n = steps.len() as f64;
            let mean_x = steps.iter().map(|s| s.0.ln()).sum::<f64>() / n;
            let mean_y = steps.iter().map(|s| s.1.ln()).sum::<f64>() / n;
            let (h0, h1) = (x.range.0, x.range.1);
            let line: Vec<(f64, f64)> = [h0, h1]
                .iter()
                .map(|h| (*h, (mean_y + q * (h.ln() - mean_x)).exp()))
                .collect();
            for (h, e) in &line {
                csv.row(&[Cell::S("c"), Cell::S("fit"), Cell::F(*h), Cell::F(*e)]);
            }
            panel.series.push(Series::line(
                Some(&format!("fitted order {q:.2} ± {se:.2}")),
                line,
                Look::line(super::style::GREY, Dash::Dashed),
            ));
        }
        panels.push(panel);
    }
    if panels.is_empty() {
        return Err(PlotError::Data {
            figure: name.to_owned(),
            reason: "no file has samples of v_S or a per-period series to draw".to_owned(),
        });
    }
    notes.push(format!(
        "Exact v∞ = {:.6} m/s, period T = {:.4e} s.",
        report.v_inf, period
    ));
    let files: Vec<String> = report
        .files
        .iter()
        .zip(&labels)
        .map(|(f, l)| format!("{}: {}", super::visible(l), short(&f.file)))
        .collect();
    notes.push(format!("Files: {}.", files.join("; ")));
    // Where the file ends before the start-up: the split of its error.
    let unfinished: Vec<String> = report
        .files
        .iter()
        .filter_map(|f| {
            let s = f.v_inf_split.as_ref().filter(|s| s.truncation_dominates)?;
            Some(format!(
                "{} ends at period {}: its v∞ error is the step-size part {:.2e} m/s plus the \
                 truncation part {:.2e} m/s (the start-up is not over).",
                short(&f.file),
                s.period,
                s.step_size,
                s.truncation
            ))
        })
        .collect();
    let more = unfinished.len().saturating_sub(2);
    notes.extend(unfinished.into_iter().take(2));
    if more > 0 {
        notes.push(format!(
            "{more} more files end before the start-up is over."
        ));
    }
    Ok(Figure {
        name: name.to_owned(),
        plot: Plot::grid(panels, 1, 0.55).with_notes(notes),
        csv: csv.finish(),
        preset: Preset::SingleColumn,
    })
}

/// The compare figure of the fixed-step reference on `scene` at each of
/// `steps` steps per period of the highest harmonic, over `periods`
/// periods, each exported as `reference_S.csv` (see the module doc).
pub(crate) fn reference_figure(
    scene: &crate::scene::Scene,
    steps: &[u32],
    periods: u64,
    name: &str,
) -> Result<Figure, PlotError> {
    let bad = |e: crate::compare::CompareError| PlotError::Data {
        figure: name.to_owned(),
        reason: e.to_string(),
    };
    let data = steps
        .iter()
        .map(|&s| {
            crate::compare::reference::export(scene, s, periods)
                .map(|d| (format!("reference_{s}.csv"), d))
        })
        .collect::<Result<Vec<_>, _>>()
        .map_err(bad)?;
    let report =
        crate::compare::compare_data(scene, &data, &crate::compare::CompareOptions::default())
            .map_err(bad)?;
    figure(&report, None, name)
}
