//! Figures: the paper's figures 2-9 and two new ones (the stroke scaling
//! law (38), (39), (42) on log-log axes and an event timeline of the
//! start-up), each as an SVG with its data as CSV beside it.
//!
//! `cargo run --release --example paper_figures` writes them all to
//! `plots/`. One file per figure family:
//!
//! * [`signals`]: figure 2 (ideal signals (11) and their partial sums (8)),
//!   figure 3 (harmonic amplitudes with and without sigma factors (15)),
//!   figure 4 (rod signals for `n = 2` and 5) and figure 5 (signals of
//!   equal `f_max` (37));
//! * [`performance`]: figures 6 and 7, the indicators of section 7 against
//!   `n` at several `f_max` levels, from a grid of runs the caller provides;
//! * [`velocity`]: figure 8, rod and slider velocity in the first and a
//!   steady-state period, drawn from the exact segments;
//! * [`scaling`]: figure 9 (`f_max ∝ 1/sqrt(x_hat)` (37) against
//!   `f_allowed ∝ 1/x_hat` (43)) and the stroke scaling law;
//! * [`timeline`]: the slider's modes over the start-up.
//!
//! # Output contract
//!
//! A [`Figure`] holds the SVG text and the CSV text; nothing in either
//! depends on the clock, the thread count or the machine's fonts, so the
//! same inputs give the same bytes. CSV numbers are written with `{:e}`
//! (Rust's shortest representation that reads back to the same `f64`), SI
//! units, one header line after `#` comment lines that say what the columns
//! are. [`Figure::write_to`] replaces each file atomically (temporary file
//! and rename).
//!
//! # Drawing
//!
//! plotters' SVG backend without fonts: text stays `<text>` and the viewer
//! picks the font. Text extents are therefore estimated
//! (`text_width`, generous for DejaVu Sans and Arial) and legends are
//! laid out here, outside the plotting areas, so that no text can cover
//! data. Lines are clipped to the axes here as well
//! (`clip_polyline`), so that a zoomed axis (figure 2's acceleration
//! band) never draws outside its panel.

pub mod performance;
pub mod scaling;
pub mod signals;
pub mod timeline;
pub mod velocity;

use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use thiserror::Error;

/// A finished figure: SVG and CSV text under one file stem.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Figure {
    /// File stem: the figure is written as `NAME.svg` and `NAME.csv`.
    pub name: String,
    /// The SVG document.
    pub svg: String,
    /// The data drawn, as CSV.
    pub csv: String,
}

impl Figure {
    /// Writes `NAME.svg` and `NAME.csv` into `dir` (created if missing),
    /// each through a temporary file and a rename, so that a reader never
    /// sees a half-written file. Returns the two paths.
    pub fn write_to(&self, dir: &Path) -> Result<[PathBuf; 2], PlotError> {
        std::fs::create_dir_all(dir).map_err(|source| PlotError::Io {
            path: dir.display().to_string(),
            source,
        })?;
        let svg = dir.join(format!("{}.svg", self.name));
        let csv = dir.join(format!("{}.csv", self.name));
        write_atomically(&svg, self.svg.as_bytes())?;
        write_atomically(&csv, self.csv.as_bytes())?;
        Ok([svg, csv])
    }
}

fn write_atomically(path: &Path, bytes: &[u8]) -> Result<(), PlotError> {
    crate::output::write_atomically(path, bytes).map_err(|source| PlotError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// What can go wrong while making a figure.
#[derive(Debug, Error)]
pub enum PlotError {
    /// plotters refused to draw.
    #[error("drawing figure {figure}: {message}")]
    Drawing {
        /// The figure's name.
        figure: String,
        /// plotters' message.
        message: String,
    },
    /// A simulation behind the figure failed.
    #[error("simulating for figure {figure}: {source}")]
    Simulation {
        /// The figure's name.
        figure: String,
        /// The simulator's error.
        #[source]
        source: crate::Error,
    },
    /// The data handed in cannot make the figure.
    #[error("figure {figure}: {reason}")]
    Data {
        /// The figure's name.
        figure: String,
        /// What is wrong with the data.
        reason: String,
    },
    /// A file could not be written.
    #[error("writing {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
}

impl PlotError {
    fn simulation(figure: &str) -> impl FnOnce(crate::Error) -> PlotError + '_ {
        move |source| PlotError::Simulation {
            figure: figure.to_owned(),
            source,
        }
    }
}

// ---------------------------------------------------------------- CSV ----

/// A CSV table built row by row: `#` comment lines, a header, then rows of
/// cells. Numbers are written with `{:e}`, so the text is exact and the
/// same on every run.
#[derive(Debug, Clone, Default)]
pub(crate) struct Csv {
    text: String,
    columns: usize,
}

/// One CSV cell.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Cell<'a> {
    /// A number, written with `{:e}`.
    F(f64),
    /// An integer.
    I(i64),
    /// A word (no commas, quotes or line breaks).
    S(&'a str),
}

impl Csv {
    /// A table with comment lines (each written after `# `) and a header.
    pub(crate) fn new(comments: &[&str], header: &[&str]) -> Self {
        let mut text = String::new();
        for c in comments {
            text.push_str("# ");
            text.push_str(c);
            text.push('\n');
        }
        text.push_str(&header.join(","));
        text.push('\n');
        Csv {
            text,
            columns: header.len(),
        }
    }

    /// Appends a row; it must have one cell per column.
    pub(crate) fn row(&mut self, cells: &[Cell<'_>]) {
        debug_assert_eq!(cells.len(), self.columns, "one cell per column");
        for (i, cell) in cells.iter().enumerate() {
            if i > 0 {
                self.text.push(',');
            }
            match cell {
                Cell::F(x) => write!(self.text, "{x:e}"),
                Cell::I(i) => write!(self.text, "{i}"),
                Cell::S(s) => {
                    debug_assert!(!s.contains([',', '"', '\n']), "plain CSV words only");
                    write!(self.text, "{s}")
                }
            }
            .expect("writing to a String cannot fail");
        }
        self.text.push('\n');
    }

    /// The CSV text.
    pub(crate) fn finish(self) -> String {
        self.text
    }
}

// -------------------------------------------------------------- style ----

/// Colours: the Okabe-Ito palette (distinguishable with the common colour
/// vision deficiencies), then black.
pub(crate) const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),   // blue
    RGBColor(213, 94, 0),    // vermillion
    RGBColor(0, 158, 115),   // bluish green
    RGBColor(204, 121, 167), // reddish purple
    RGBColor(230, 159, 0),   // orange
    RGBColor(86, 180, 233),  // sky blue
    RGBColor(120, 120, 120), // grey
    RGBColor(0, 0, 0),       // black
];

/// Light grey for reference lines and bands.
pub(crate) const REFERENCE: RGBColor = RGBColor(110, 110, 110);

/// Font sizes in plotters units (the SVG's `font-size` is 1/1.24 of these).
pub(crate) mod size {
    /// Figure title.
    pub const TITLE: f64 = 24.0;
    /// Panel title.
    pub const PANEL: f64 = 19.0;
    /// Axis description.
    pub const AXIS: f64 = 18.0;
    /// Tick labels.
    pub const TICK: f64 = 16.0;
    /// Legend entries and annotations.
    pub const LEGEND: f64 = 17.0;
}

/// A sans-serif text style of the given plotters size.
pub(crate) fn font(size: f64) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

/// Estimated width in pixels of `text` at plotters size `size`: 0.58 em per
/// character of the rendered font, generous for DejaVu Sans and Arial.
pub(crate) fn text_width(text: &str, size: f64) -> i32 {
    (text.chars().count() as f64 * 0.58 * size / 1.24).ceil() as i32
}

/// Line height in pixels for plotters size `size`.
pub(crate) fn line_height(size: f64) -> i32 {
    (1.45 * size / 1.24).ceil() as i32
}

/// The drawing area figures are drawn on.
pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The result of drawing into an SVG string.
pub(crate) type DrawResult = Result<(), DrawingAreaErrorKind<std::io::Error>>;

/// Renders an SVG of `width` x `height` pixels with `draw`, on white.
pub(crate) fn render(
    figure: &str,
    (width, height): (u32, u32),
    draw: impl FnOnce(&Area<'_>) -> DrawResult,
) -> Result<String, PlotError> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        let result = root
            .fill(&WHITE)
            .and_then(|()| draw(&root))
            .and_then(|()| root.present());
        result.map_err(|e| PlotError::Drawing {
            figure: figure.to_owned(),
            message: e.to_string(),
        })?;
    }
    Ok(svg)
}

/// A figure of panels side by side under a title and one shared legend,
/// with its CSV data.
pub(crate) fn side_by_side(
    name: &str,
    size: (u32, u32),
    title: &str,
    panels: &[Panel],
    csv: Csv,
) -> Result<Figure, PlotError> {
    let legend = legend_of(&panels.iter().collect::<Vec<_>>());
    let svg = render(name, size, |root| {
        let body = titled(root, title)?;
        let body = with_legend_on_top(&body, &legend)?;
        for (a, p) in body.split_evenly((1, panels.len())).iter().zip(panels) {
            draw_panel(a, p)?;
        }
        Ok(())
    })?;
    Ok(Figure {
        name: name.to_owned(),
        svg,
        csv: csv.finish(),
    })
}

/// Splits a title strip of the figure title's height off the top of `area`
/// and writes `title` centred in it; returns the rest.
pub(crate) fn titled<'a>(
    area: &Area<'a>,
    title: &str,
) -> Result<Area<'a>, DrawingAreaErrorKind<std::io::Error>> {
    let h = line_height(size::TITLE) + 10;
    let (top, rest) = area.split_vertically(h);
    let (w, _) = top.dim_in_pixel();
    top.draw_text(
        title,
        &font(size::TITLE).pos(Pos::new(HPos::Center, VPos::Center)),
        (w as i32 / 2, h / 2 + 2),
    )?;
    Ok(rest)
}

// ------------------------------------------------------------- series ----

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Mark {
    /// A solid line of the given width.
    Line(u32),
    /// A dashed line: width, dash length, gap (pixels).
    Dashed(u32, u32, u32),
    /// A solid line with a filled circle at each point.
    LinePoints(u32),
    /// A line with hollow squares at each point.
    LineSquares(u32),
    /// Filled circles of the given radius, no line.
    Points(u32),
    /// Filled rectangles: consecutive point pairs are opposite corners.
    Rects,
}

/// One series of a panel.
#[derive(Debug, Clone)]
pub(crate) struct Series {
    /// Legend label (`None`: not in the legend).
    pub label: Option<String>,
    /// Pieces of the curve: each is drawn as one polyline (so jumps can be
    /// drawn as gaps or as vertical lines, as the caller chooses).
    pub pieces: Vec<Vec<(f64, f64)>>,
    /// Colour.
    pub color: RGBColor,
    /// Line style.
    pub mark: Mark,
}

impl Series {
    /// A connected curve.
    pub(crate) fn line(
        label: Option<&str>,
        points: Vec<(f64, f64)>,
        color: RGBColor,
        mark: Mark,
    ) -> Self {
        Series {
            label: label.map(str::to_owned),
            pieces: vec![points],
            color,
            mark,
        }
    }

    /// A horizontal line at `y` across `x0..x1`.
    pub(crate) fn hline(
        label: Option<&str>,
        y: f64,
        (x0, x1): (f64, f64),
        color: RGBColor,
        mark: Mark,
    ) -> Self {
        Self::line(label, vec![(x0, y), (x1, y)], color, mark)
    }
}

/// A text label placed in data coordinates.
#[derive(Clone)]
pub(crate) struct Note {
    /// Anchor point (data coordinates).
    pub at: (f64, f64),
    /// The text.
    pub text: String,
    /// Horizontal alignment at the anchor.
    pub h: HPos,
    /// Vertical alignment at the anchor.
    pub v: VPos,
}

/// One axis of a panel.
#[derive(Debug, Clone)]
pub(crate) struct Axis {
    /// Description with unit, e.g. `t (ms)`.
    pub label: String,
    /// Range shown.
    pub range: (f64, f64),
    /// Logarithmic.
    pub log: bool,
    /// Multiply data by this before drawing (e.g. 1e3 for s -> ms). The
    /// range is in drawn units.
    pub scale: f64,
    /// Number of tick labels wanted (plotters picks round values).
    pub ticks: usize,
}

impl Axis {
    /// A linear axis with data drawn unscaled.
    pub(crate) fn linear(label: &str, range: (f64, f64)) -> Self {
        Axis {
            label: label.to_owned(),
            range,
            log: false,
            scale: 1.0,
            ticks: 6,
        }
    }

    /// A logarithmic axis.
    pub(crate) fn log(label: &str, range: (f64, f64)) -> Self {
        Axis {
            log: true,
            ..Self::linear(label, range)
        }
    }

    /// The same axis drawing data times `scale`.
    pub(crate) fn scaled(mut self, scale: f64) -> Self {
        self.scale = scale;
        self
    }

    /// The same axis with about `n` tick labels.
    pub(crate) fn ticks(mut self, n: usize) -> Self {
        self.ticks = n;
        self
    }
}

/// A panel: axes, series, notes and an optional title.
#[derive(Clone)]
pub(crate) struct Panel {
    /// Title above the plotting area.
    pub title: Option<String>,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Series, drawn in order (later ones on top).
    pub series: Vec<Series>,
    /// Text notes.
    pub notes: Vec<Note>,
    /// Width of the area for y tick labels and description (pixels).
    pub y_label_area: u32,
}

impl Panel {
    /// A panel with the given axes and nothing in it.
    pub(crate) fn new(title: Option<&str>, x: Axis, y: Axis) -> Self {
        Panel {
            title: title.map(str::to_owned),
            x,
            y,
            series: Vec::new(),
            notes: Vec::new(),
            y_label_area: 78,
        }
    }
}

/// Formats a tick value compactly: no trailing zeros, scientific notation
/// with a Unicode exponent outside `[1e-3, 1e5)`.
pub(crate) fn tick_label(v: f64) -> String {
    if v == 0.0 {
        return "0".to_owned();
    }
    let a = v.abs();
    if (1e-3..1e5).contains(&a) {
        let s = format!("{v:.6}");
        let s = s.trim_end_matches('0').trim_end_matches('.');
        return s.replace('-', "−");
    }
    let exp = a.log10().floor() as i32;
    let mantissa = v / 10f64.powi(exp);
    let sup = superscript(exp);
    if (mantissa.abs() - 1.0).abs() < 1e-9 {
        format!("{}10{sup}", if mantissa < 0.0 { "−" } else { "" })
    } else {
        let m = format!("{mantissa:.2}");
        let m = m.trim_end_matches('0').trim_end_matches('.');
        format!("{}×10{sup}", m.replace('-', "−"))
    }
}

/// Tick labels of a logarithmic axis: powers of ten, and on axes of at
/// most three decades also 2 and 5 times them; the other ticks plotters
/// offers (3, 4, 6, ... times) stay unlabelled. Written plainly when the
/// whole axis lies in `[0.01, 10000]`, with a power of ten otherwise.
fn log_tick_label(v: f64, (lo, hi): (f64, f64)) -> String {
    let decade = v.abs().log10().floor();
    let mantissa = v / 10f64.powf(decade);
    let close = |m: f64| (mantissa - m).abs() < 1e-6;
    let short_axis = (hi / lo).log10() <= 3.01;
    if !(close(1.0) || close(10.0) || (short_axis && (close(2.0) || close(5.0)))) {
        return String::new();
    }
    if lo >= 0.999e-2 && hi <= 1.001e4 {
        let s = format!("{v:.4}");
        return s.trim_end_matches('0').trim_end_matches('.').to_owned();
    }
    let e = if close(10.0) { decade + 1.0 } else { decade } as i32;
    let m = mantissa.round() as i64 % 10;
    if m == 1 || close(10.0) {
        format!("10{}", superscript(e))
    } else {
        format!("{m}×10{}", superscript(e))
    }
}

/// An integer in superscript digits, for exponents in axis labels.
pub fn superscript(e: i32) -> String {
    e.to_string()
        .chars()
        .map(|c| match c {
            '-' => '⁻',
            '0' => '⁰',
            '1' => '¹',
            '2' => '²',
            '3' => '³',
            '4' => '⁴',
            '5' => '⁵',
            '6' => '⁶',
            '7' => '⁷',
            '8' => '⁸',
            _ => '⁹',
        })
        .collect()
}

/// The parts of `points` inside the box `x` x `y`, as polylines: each
/// segment is clipped (Liang-Barsky) and runs of connected clipped segments
/// are joined.
pub(crate) fn clip_polyline(
    points: &[(f64, f64)],
    x: (f64, f64),
    y: (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    for w in points.windows(2) {
        let (p, q) = (w[0], w[1]);
        match clip_segment(p, q, x, y) {
            Some((a, b)) => {
                let continues = open && a == p;
                if !continues {
                    out.push(vec![a]);
                }
                if let Some(last) = out.last_mut() {
                    last.push(b);
                }
                open = b == q;
            }
            None => open = false,
        }
    }
    if points.len() == 1 {
        let p = points[0];
        if p.0 >= x.0 && p.0 <= x.1 && p.1 >= y.0 && p.1 <= y.1 {
            out.push(vec![p]);
        }
    }
    out
}

fn clip_segment(
    p: (f64, f64),
    q: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (q.0 - p.0, q.1 - p.1);
    let mut t0: f64 = 0.0;
    let mut t1: f64 = 1.0;
    for (den, num) in [
        (-dx, p.0 - x0),
        (dx, x1 - p.0),
        (-dy, p.1 - y0),
        (dy, y1 - p.1),
    ] {
        if den == 0.0 {
            if num < 0.0 {
                return None;
            }
        } else {
            let t = num / den;
            if den < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            p
        } else if t == 1.0 {
            q
        } else {
            (p.0 + t * dx, p.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

/// Draws a panel into `area`.
pub(crate) fn draw_panel(area: &Area<'_>, panel: &Panel) -> DrawResult {
    let (x0, x1) = panel.x.range;
    let (y0, y1) = panel.y.range;
    match (panel.x.log, panel.y.log) {
        (false, false) => draw_panel_in(area, panel, x0..x1, y0..y1),
        (true, false) => draw_panel_in(area, panel, (x0..x1).log_scale(), y0..y1),
        (false, true) => draw_panel_in(area, panel, x0..x1, (y0..y1).log_scale()),
        (true, true) => draw_panel_in(area, panel, (x0..x1).log_scale(), (y0..y1).log_scale()),
    }
}

fn draw_panel_in<X, Y>(area: &Area<'_>, panel: &Panel, x_spec: X, y_spec: Y) -> DrawResult
where
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let mut builder = ChartBuilder::on(area);
    builder
        .margin_top(8)
        .margin_right(18)
        .margin_left(4)
        .x_label_area_size(52)
        .y_label_area_size(panel.y_label_area);
    if let Some(title) = &panel.title {
        builder.caption(title, font(size::PANEL));
    }
    let mut chart = builder.build_cartesian_2d(x_spec, y_spec)?;
    // Ticks are multiples of a round step computed in floating point: snap
    // a tick that should be 0 (1e-17 and the like) to 0.
    let snap = |v: f64, (lo, hi): (f64, f64)| if v.abs() < 1e-9 * (hi - lo) { 0.0 } else { v };
    let x_fmt = |v: &f64| {
        if panel.x.log {
            log_tick_label(*v, panel.x.range)
        } else {
            tick_label(snap(*v, panel.x.range))
        }
    };
    let y_fmt = |v: &f64| {
        if panel.y.log {
            log_tick_label(*v, panel.y.range)
        } else {
            tick_label(snap(*v, panel.y.range))
        }
    };
    chart
        .configure_mesh()
        .x_desc(panel.x.label.as_str())
        .y_desc(panel.y.label.as_str())
        .x_labels(panel.x.ticks)
        .y_labels(panel.y.ticks)
        .x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(font(size::TICK))
        .axis_desc_style(font(size::AXIS))
        .light_line_style(WHITE)
        .bold_line_style(RGBColor(225, 225, 225))
        .axis_style(BLACK)
        .draw()?;

    let (sx, sy) = (panel.x.scale, panel.y.scale);
    let (xr, yr) = (panel.x.range, panel.y.range);
    for s in &panel.series {
        for piece in &s.pieces {
            let scaled: Vec<(f64, f64)> = piece.iter().map(|(x, y)| (x * sx, y * sy)).collect();
            match s.mark {
                Mark::Rects => {
                    let style = s.color.filled();
                    chart.draw_series(scaled.chunks_exact(2).map(|c| {
                        let clamp = |(x, y): (f64, f64)| (x.clamp(xr.0, xr.1), y.clamp(yr.0, yr.1));
                        Rectangle::new([clamp(c[0]), clamp(c[1])], style)
                    }))?;
                }
                Mark::Points(_) => {}
                Mark::Line(w) | Mark::LinePoints(w) | Mark::LineSquares(w) => {
                    for part in clip_polyline(&scaled, xr, yr) {
                        chart.draw_series(LineSeries::new(part, s.color.stroke_width(w)))?;
                    }
                }
                Mark::Dashed(w, dash, gap) => {
                    for part in clip_polyline(&scaled, xr, yr) {
                        chart.draw_series(DashedLineSeries::new(
                            part,
                            dash,
                            gap,
                            s.color.stroke_width(w),
                        ))?;
                    }
                }
            }
            let inside = |p: &&(f64, f64)| p.0 >= xr.0 && p.0 <= xr.1 && p.1 >= yr.0 && p.1 <= yr.1;
            match s.mark {
                Mark::LinePoints(_) => {
                    chart.draw_series(
                        scaled
                            .iter()
                            .filter(inside)
                            .map(|p| Circle::new(*p, 4, s.color.filled())),
                    )?;
                }
                Mark::Points(r) => {
                    chart.draw_series(
                        scaled
                            .iter()
                            .filter(inside)
                            .map(|p| Circle::new(*p, r, s.color.filled())),
                    )?;
                }
                Mark::LineSquares(_) => {
                    chart.draw_series(scaled.iter().filter(inside).map(|p| {
                        EmptyElement::at(*p)
                            + Rectangle::new([(-4, -4), (4, 4)], WHITE.filled())
                            + Rectangle::new([(-4, -4), (4, 4)], s.color.stroke_width(2))
                    }))?;
                }
                _ => {}
            }
        }
    }
    for note in &panel.notes {
        let style = font(size::LEGEND).pos(Pos::new(note.h, note.v));
        chart.draw_series(std::iter::once(Text::new(
            note.text.clone(),
            (note.at.0 * sx, note.at.1 * sy),
            style,
        )))?;
    }
    Ok(())
}

// ------------------------------------------------------------- legend ----

/// One legend entry: the series' colour and mark and its label.
#[derive(Debug, Clone)]
pub(crate) struct LegendEntry {
    /// Label text.
    pub label: String,
    /// Colour.
    pub color: RGBColor,
    /// Mark shown beside the label.
    pub mark: Mark,
}

impl LegendEntry {
    /// An entry.
    pub(crate) fn new(label: &str, color: RGBColor, mark: Mark) -> Self {
        LegendEntry {
            label: label.to_owned(),
            color,
            mark,
        }
    }
}

/// The legend entries of panels' labelled series, each label once, in
/// order of first appearance.
pub(crate) fn legend_of(panels: &[&Panel]) -> Vec<LegendEntry> {
    let mut entries: Vec<LegendEntry> = Vec::new();
    for p in panels {
        for s in &p.series {
            if let Some(label) = &s.label
                && !entries.iter().any(|e| &e.label == label)
            {
                entries.push(LegendEntry::new(label, s.color, s.mark));
            }
        }
    }
    entries
}

const SWATCH: i32 = 34;
const ENTRY_GAP: i32 = 26;

fn entry_width(e: &LegendEntry) -> i32 {
    SWATCH + 8 + text_width(&e.label, size::LEGEND)
}

/// Lays entries out in rows no wider than `width`: returns the rows as
/// index ranges.
fn legend_rows(entries: &[LegendEntry], width: i32) -> Vec<std::ops::Range<usize>> {
    let mut rows = Vec::new();
    let mut start = 0;
    let mut used = 0;
    for (i, e) in entries.iter().enumerate() {
        let w = entry_width(e);
        if i > start && used + ENTRY_GAP + w > width {
            rows.push(start..i);
            start = i;
            used = 0;
        }
        used += if i > start { ENTRY_GAP + w } else { w };
    }
    if start < entries.len() {
        rows.push(start..entries.len());
    }
    rows
}

/// Height in pixels a horizontal legend of `entries` needs in `width`.
pub(crate) fn legend_height(entries: &[LegendEntry], width: u32) -> u32 {
    let rows = legend_rows(entries, width as i32 - 20).len() as i32;
    (rows * line_height(size::LEGEND) + 10).max(0) as u32
}

/// Splits a legend strip off the top of `area`, draws the entries in
/// centred rows and returns the rest of the area.
pub(crate) fn with_legend_on_top<'a>(
    area: &Area<'a>,
    entries: &[LegendEntry],
) -> Result<Area<'a>, DrawingAreaErrorKind<std::io::Error>> {
    if entries.is_empty() {
        return Ok(area.clone());
    }
    let (w, _) = area.dim_in_pixel();
    let h = legend_height(entries, w);
    let (top, rest) = area.split_vertically(h);
    draw_legend(&top, entries)?;
    Ok(rest)
}

/// Draws a legend in `area`: entries in centred rows, top down.
pub(crate) fn draw_legend(area: &Area<'_>, entries: &[LegendEntry]) -> DrawResult {
    let (w, _) = area.dim_in_pixel();
    let lh = line_height(size::LEGEND);
    let rows = legend_rows(entries, w as i32 - 20);
    let row_width = |row: &std::ops::Range<usize>| {
        entries[row.clone()].iter().map(entry_width).sum::<i32>()
            + ENTRY_GAP * (row.len() as i32 - 1)
    };
    // One row is centred; several rows form a left-aligned, centred block.
    let block = rows.iter().map(row_width).max().unwrap_or(0);
    for (r, row) in rows.into_iter().enumerate() {
        let mut x = (w as i32 - block) / 2;
        let y = 5 + r as i32 * lh + lh / 2;
        for e in &entries[row] {
            draw_legend_entry(area, e, (x, y))?;
            x += entry_width(e) + ENTRY_GAP;
        }
    }
    Ok(())
}

/// Draws one legend entry with its swatch's left end at `(x, y)` (pixels,
/// `y` the text's middle).
pub(crate) fn draw_legend_entry(
    area: &Area<'_>,
    e: &LegendEntry,
    (x, y): (i32, i32),
) -> DrawResult {
    draw_swatch(area, e, (x, y))?;
    area.draw_text(
        &e.label,
        &font(size::LEGEND).pos(Pos::new(HPos::Left, VPos::Center)),
        (x + SWATCH + 8, y),
    )
}

fn draw_swatch(area: &Area<'_>, e: &LegendEntry, (x, y): (i32, i32)) -> DrawResult {
    let line = |w: u32| PathElement::new(vec![(x, y), (x + SWATCH, y)], e.color.stroke_width(w));
    match e.mark {
        Mark::Line(w) => area.draw(&line(w.max(2))),
        Mark::Dashed(w, _, _) => {
            for k in 0..3 {
                let a = x + k * 13;
                area.draw(&PathElement::new(
                    vec![(a, y), (a + 8, y)],
                    e.color.stroke_width(w.max(2)),
                ))?;
            }
            Ok(())
        }
        Mark::LinePoints(w) => {
            area.draw(&line(w.max(2)))?;
            area.draw(&Circle::new((x + SWATCH / 2, y), 4, e.color.filled()))
        }
        Mark::LineSquares(w) => {
            area.draw(&line(w.max(2)))?;
            let c = (x + SWATCH / 2, y);
            area.draw(&Rectangle::new(
                [(c.0 - 4, c.1 - 4), (c.0 + 4, c.1 + 4)],
                WHITE.filled(),
            ))?;
            area.draw(&Rectangle::new(
                [(c.0 - 4, c.1 - 4), (c.0 + 4, c.1 + 4)],
                e.color.stroke_width(2),
            ))
        }
        Mark::Points(r) => area.draw(&Circle::new((x + SWATCH / 2, y), r, e.color.filled())),
        Mark::Rects => area.draw(&Rectangle::new(
            [(x + 4, y - 7), (x + SWATCH - 4, y + 7)],
            e.color.filled(),
        )),
    }
}

/// Least-squares slope of `ln y` against `ln x` (the exponent of a power
/// law `y ∝ x^s`).
pub(crate) fn loglog_slope(points: &[(f64, f64)]) -> f64 {
    let n = points.len() as f64;
    let (mx, my) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        (a + x.ln() / n, b + y.ln() / n)
    });
    let (sxy, sxx) = points.iter().fold((0.0, 0.0), |(a, b), (x, y)| {
        let dx = x.ln() - mx;
        (a + dx * (y.ln() - my), b + dx * dx)
    });
    sxy / sxx
}

/// `n` evenly spaced values from `a` to `b`, both included.
pub(crate) fn linspace(a: f64, b: f64, n: usize) -> impl Iterator<Item = f64> {
    let step = (b - a) / (n - 1) as f64;
    (0..n).map(move |i| if i + 1 == n { b } else { a + step * i as f64 })
}

/// A range padded by `frac` of its width on both ends.
pub(crate) fn padded(lo: f64, hi: f64, frac: f64) -> (f64, f64) {
    let pad = (hi - lo) * frac;
    (lo - pad, hi + pad)
}

/// Smallest and largest of some values.
pub(crate) fn min_max(values: impl IntoIterator<Item = f64>) -> (f64, f64) {
    values
        .into_iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
            (lo.min(v), hi.max(v))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_inside_parts_and_joins_them() {
        let pts = [(0.0, 0.0), (1.0, 2.0), (2.0, 0.0), (3.0, 0.5)];
        let parts = clip_polyline(&pts, (0.0, 3.0), (-1.0, 1.0));
        assert_eq!(parts.len(), 2);
        assert_eq!(parts[0], vec![(0.0, 0.0), (0.5, 1.0)]);
        assert_eq!(parts[1], vec![(1.5, 1.0), (2.0, 0.0), (3.0, 0.5)]);
    }

    #[test]
    fn slope_of_a_power_law() {
        let pts: Vec<(f64, f64)> = [1e-9, 1e-6, 1e-3]
            .iter()
            .map(|x: &f64| (*x, 3.0 * x.sqrt()))
            .collect();
        assert!((loglog_slope(&pts) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn tick_labels_are_compact() {
        assert_eq!(tick_label(0.25), "0.25");
        assert_eq!(tick_label(-3.0), "−3");
        assert_eq!(tick_label(1e-6), "10⁻⁶");
        assert_eq!(tick_label(2.5e6), "2.5×10⁶");
        assert_eq!(log_tick_label(1e-3, (1e-9, 1e-3)), "10⁻³");
        assert_eq!(log_tick_label(100.0, (1.0, 1e3)), "100");
        assert_eq!(log_tick_label(2e-3, (1e-9, 1e-3)), "");
        assert_eq!(log_tick_label(3e-3, (1e-9, 1e-3)), "");
        assert_eq!(log_tick_label(2.0, (1.0, 100.0)), "2");
        assert_eq!(log_tick_label(0.05, (0.01, 1.0)), "0.05");
        assert_eq!(log_tick_label(5e-5, (1e-5, 1e-3)), "5×10⁻⁵");
        assert_eq!(log_tick_label(3.0, (1.0, 100.0)), "");
    }
}
