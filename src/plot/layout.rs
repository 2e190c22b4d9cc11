//! Layout: a figure's panels in a grid under an optional title, the legend
//! and note lines, sized for print, and drawn into an SVG.
//!
//! Contract: the figure is [`Style::width_mm`] wide; its height is
//! [`Style::height_mm`] when given, otherwise what the panels need at the
//! plot's aspect ratio (taller where a y-axis description at the smallest
//! print size needs it). Gutters are measured with the font's metrics, so
//! tick labels and axis descriptions never overlap the plotting area or
//! each other's panels. Every text is set at [`Style::font_pt`] or
//! [`Style::tick_pt`].

use super::axes::Axis;
use super::canvas::{Anchor, Canvas};
use super::colorbar::{self, ColorBar};
use super::font::{DIGIT_HEIGHT, text_width};
use super::legend::{self, LegendEntry, legend_of, marker_size};
use super::marks::{Marks, Role};
use super::series::{Kind, Panel, clip_polyline};
use super::style::{GRID, MIN_FONT_PT, Rgb, Style};

/// A figure's drawing: panels, their arrangement, and the legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Plot {
    /// Panels, row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Height of a plotting area over its width.
    pub aspect: f64,
    /// Legend entries (by default those of the panels' labelled series).
    pub legend: Vec<LegendEntry>,
    /// The caption's text (what the legend cannot say): not drawn, written
    /// as `# caption:` lines at the head of the figure's CSV
    /// ([`super::Figure::data`]).
    pub notes: Vec<String>,
    /// The scale of a map's colours, drawn above the panels.
    pub colorbar: Option<ColorBar>,
}

impl Plot {
    /// Panels in `columns` columns with the legend of their series.
    pub fn grid(panels: Vec<Panel>, columns: usize, aspect: f64) -> Self {
        let legend = legend_of(&panels);
        Plot {
            panels,
            columns: columns.max(1),
            aspect,
            legend,
            notes: Vec::new(),
            colorbar: None,
        }
    }

    /// The same plot with a colour bar above its panels.
    pub fn with_colorbar(mut self, bar: ColorBar) -> Self {
        self.colorbar = Some(bar);
        self
    }

    /// The same plot with caption lines (written to the CSV, not drawn).
    pub fn with_notes(mut self, notes: Vec<String>) -> Self {
        self.notes = notes;
        self
    }

    /// Draws the plot at `style`; `metadata` goes into the SVG's
    /// `<metadata>`.
    pub fn render(&self, style: &Style, metadata: &str) -> String {
        let (canvas, size) = self.draw(style);
        canvas.finish(size, metadata)
    }

    /// What [`Plot::render`] puts where at `style`: text boxes, frames,
    /// data and the legend's box (see `marks`).
    pub fn marks(&self, style: &Style) -> Marks {
        let (canvas, (w, h)) = self.draw(style);
        let pt = super::style::PT_PER_MM;
        Marks {
            width: w * pt,
            height: h * pt,
            ..canvas.marks
        }
    }

    /// The drawing and its printed size (mm).
    fn draw(&self, style: &Style) -> (Canvas, (f64, f64)) {
        let f = style.font_pt;
        let width = style.width_pt();
        let pad = 0.5 * f;
        let inner = width - 2.0 * pad;
        let mut canvas = Canvas::default();
        let mut y = pad;
        if let Some(title) = &style.title {
            canvas.text(
                title,
                (width / 2.0, y + DIGIT_HEIGHT * f * 1.15),
                f * 1.15,
                Anchor::Middle,
                0.0,
                Role::Title,
            );
            y += 1.6 * f;
        }
        if !self.legend.is_empty() {
            legend::draw(&mut canvas, &self.legend, (pad, y), inner, style);
            y += legend::height(&self.legend, inner, style) + 0.2 * f;
        }
        if let Some(bar) = &self.colorbar {
            colorbar::draw(&mut canvas, bar, (pad, y + 0.2 * f), inner, style);
            y += colorbar::height(style) + 0.4 * f;
        }
        let mut gutters: Vec<Gutter> = self.panels.iter().map(|p| Gutter::of(p, style)).collect();
        // The plot's columns, fewer when its panels would be narrower than
        // their x-axis descriptions (a wide figure set in one column).
        let needed = self
            .panels
            .iter()
            .map(|p| text_width(&p.x.label, f) / TEXT_FIT)
            .fold(8.0 * f, f64::max);
        let mut columns = self.columns.min(self.panels.len().max(1));
        let (left, right, plot_w) = loop {
            let cell_w = inner / columns as f64;
            // One left gutter per column and one top/bottom per row, so
            // that the plotting areas line up.
            let left: Vec<f64> = (0..columns)
                .map(|c| column_max(&gutters, columns, c, |g| g.left))
                .collect();
            let right: Vec<f64> = (0..columns)
                .map(|c| column_max(&gutters, columns, c, |g| g.right))
                .collect();
            let plot_w = (0..columns)
                .map(|c| cell_w - left[c] - right[c])
                .fold(f64::INFINITY, f64::min)
                .max(f);
            if plot_w >= needed || columns == 1 {
                break (left, right, plot_w);
            }
            columns -= 1;
        };
        let rows = self.panels.len().div_ceil(columns).max(1);
        let cell_w = inner / columns as f64;
        // Panel titles wrap within their panel; the row's top gutter holds
        // the most lines.
        let title_width = |c: usize| TEXT_FIT * (plot_w + right[c]);
        for (i, (g, panel)) in gutters.iter_mut().zip(&self.panels).enumerate() {
            if let Some(title) = &panel.title {
                let lines = wrap(title, title_width(i % columns), f).len();
                g.top = 0.25 * f + 1.25 * f * lines as f64;
            }
        }
        let row_max = |r: usize, f: fn(&Gutter) -> f64| {
            gutters
                .iter()
                .skip(r * columns)
                .take(columns)
                .map(f)
                .fold(0.0, f64::max)
        };
        let fixed: f64 = (0..rows)
            .map(|r| row_max(r, |g| g.top) + row_max(r, |g| g.bottom))
            .sum();
        // A panel is at least as tall as its y-axis description at the
        // smallest print size, so that descriptions of panels one above
        // the other never run into each other.
        let y_label_min = self
            .panels
            .iter()
            .map(|p| text_width(&p.y.label, MIN_FONT_PT.min(f)) / TEXT_FIT)
            .fold(0.0, f64::max);
        let plot_h = match style.height_mm {
            Some(h) => ((h * super::style::PT_PER_MM - y - pad - fixed) / rows as f64).max(f),
            None => (plot_w * self.aspect).max(y_label_min),
        };
        for (i, panel) in self.panels.iter().enumerate() {
            let (r, c) = (i / columns, i % columns);
            let top: f64 = y
                + (0..r)
                    .map(|k| row_max(k, |g| g.top) + plot_h + row_max(k, |g| g.bottom))
                    .sum::<f64>()
                + row_max(r, |g| g.top);
            let x0 = pad + c as f64 * cell_w + left[c];
            draw_panel(
                &mut canvas,
                panel,
                Rect {
                    x: x0,
                    y: top,
                    w: plot_w,
                    h: plot_h,
                },
                style,
                left[c],
                title_width(c),
            );
        }
        let height = y
            + (0..rows)
                .map(|r| row_max(r, |g| g.top) + plot_h + row_max(r, |g| g.bottom))
                .sum::<f64>()
            + pad;
        let height_mm = style.height_mm.unwrap_or(height / super::style::PT_PER_MM);
        (canvas, (style.width_mm, height_mm))
    }
}

/// Renderers that hint glyph advances to whole pixels set text a few per
/// cent wider than its metrics: wrapped text fills this much of its width.
const TEXT_FIT: f64 = 0.94;

/// `text` broken at spaces into lines no wider than `width` (pt) at
/// `size` pt (a single word wider than that stays whole).
fn wrap(text: &str, width: f64, size: f64) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() {
            word.to_owned()
        } else {
            format!("{line} {word}")
        };
        if !line.is_empty() && text_width(&candidate, size) > width {
            lines.push(std::mem::replace(&mut line, word.to_owned()));
        } else {
            line = candidate;
        }
    }
    lines.push(line);
    lines
}

fn column_max(gutters: &[Gutter], columns: usize, c: usize, f: fn(&Gutter) -> f64) -> f64 {
    gutters
        .iter()
        .skip(c)
        .step_by(columns)
        .map(f)
        .fold(0.0, f64::max)
}

/// The plotting area of a panel (pt).
#[derive(Debug, Clone, Copy)]
struct Rect {
    x: f64,
    y: f64,
    w: f64,
    h: f64,
}

impl Rect {
    fn at(&self, fx: f64, fy: f64) -> (f64, f64) {
        (self.x + fx * self.w, self.y + (1.0 - fy) * self.h)
    }
}

/// Space around a panel's plotting area (pt).
#[derive(Debug, Clone, Copy)]
struct Gutter {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
}

impl Gutter {
    fn of(panel: &Panel, style: &Style) -> Self {
        let (f, t) = (style.font_pt, style.tick_pt());
        let tick_len = 0.3 * f;
        let y_labels = panel
            .y
            .tick_marks()
            .iter()
            .map(|k| text_width(&k.label, t))
            .fold(0.0, f64::max);
        let x_ticks = panel.x.tick_marks();
        let last_x = x_ticks
            .iter()
            .rev()
            .find(|k| !k.label.is_empty())
            .map_or(0.0, |k| text_width(&k.label, t) / 2.0);
        Gutter {
            // The y description (baseline 0.95 f in, a subscript reaching
            // about 1.35 f) keeps 0.15 f clear of the tick labels.
            left: 1.5 * f + y_labels + tick_len + 0.25 * f,
            right: last_x.max(0.6 * f),
            top: if panel.title.is_some() {
                1.5 * f
            } else {
                0.7 * f
            },
            bottom: tick_len + 1.15 * t + 1.45 * f,
        }
    }
}

/// Where data point `(x, y)` lies in the panel as fractions of its axes.
fn fractions(panel: &Panel, (x, y): (f64, f64)) -> (f64, f64) {
    (
        panel.x.fraction(x * panel.x.scale),
        panel.y.fraction(y * panel.y.scale),
    )
}

fn draw_panel(
    canvas: &mut Canvas,
    panel: &Panel,
    area: Rect,
    style: &Style,
    left_gutter: f64,
    title_width: f64,
) {
    let (f, t) = (style.font_pt, style.tick_pt());
    let tick_len = 0.3 * f;
    let axis_pt = 0.6 * style.line_pt.min(1.5);
    // As many tick labels as fit side by side (x) or one above the other
    // (y) at this size.
    // Neighbouring labels of a log or phase axis at least this far apart
    // (pt) beyond their half widths (x) or their height (y).
    let x_apart = |shown: &[&super::axes::Tick]| {
        shown.windows(2).all(|w| {
            let d = area.w * (panel.x.fraction(w[1].value) - panel.x.fraction(w[0].value)).abs();
            d >= (text_width(&w[0].label, t) + text_width(&w[1].label, t)) / 2.0 + 0.4 * f
        })
    };
    let y_apart = |shown: &[&super::axes::Tick]| {
        shown.windows(2).all(|w| {
            area.h * (panel.y.fraction(w[1].value) - panel.y.fraction(w[0].value)).abs() >= 1.2 * t
        })
    };
    let x_ticks = fitting_ticks(
        &panel.x,
        |labels| {
            let widest = labels.iter().map(|l| text_width(l, t)).fold(0.0, f64::max);
            (widest + 0.8 * f) * labels.len() as f64 <= area.w
        },
        x_apart,
    );
    let y_ticks = fitting_ticks(
        &panel.y,
        |labels| 1.6 * t * labels.len() as f64 <= area.h,
        y_apart,
    );
    // Grid lines at labelled ticks, under the data.
    let inside = |v: f64| (-1e-9..=1.0 + 1e-9).contains(&v);
    for k in x_ticks.iter().filter(|k| !k.label.is_empty()) {
        let fx = panel.x.fraction(k.value);
        if inside(fx) && fx > 1e-6 && fx < 1.0 - 1e-6 {
            canvas.line(area.at(fx, 0.0), area.at(fx, 1.0), GRID, 0.4 * axis_pt);
        }
    }
    for k in y_ticks.iter().filter(|k| !k.label.is_empty()) {
        let fy = panel.y.fraction(k.value);
        if inside(fy) && fy > 1e-6 && fy < 1.0 - 1e-6 {
            canvas.line(area.at(0.0, fy), area.at(1.0, fy), GRID, 0.4 * axis_pt);
        }
    }
    draw_series(canvas, panel, area, style);
    canvas.frame(area.x, area.y, area.w, area.h, Rgb(0, 0, 0), axis_pt);
    for k in &x_ticks {
        let fx = panel.x.fraction(k.value);
        if !inside(fx) {
            continue;
        }
        let (px, py) = area.at(fx, 0.0);
        let len = if k.label.is_empty() {
            tick_len * 0.55
        } else {
            tick_len
        };
        canvas.line((px, py), (px, py + len), Rgb(0, 0, 0), axis_pt);
        if !k.label.is_empty() {
            canvas.text(
                &k.label,
                (px, py + tick_len + 0.15 * f + DIGIT_HEIGHT * t),
                t,
                Anchor::Middle,
                0.0,
                Role::TickLabel,
            );
        }
    }
    for k in &y_ticks {
        let fy = panel.y.fraction(k.value);
        if !inside(fy) {
            continue;
        }
        let (px, py) = area.at(0.0, fy);
        let len = if k.label.is_empty() {
            tick_len * 0.55
        } else {
            tick_len
        };
        canvas.line((px - len, py), (px, py), Rgb(0, 0, 0), axis_pt);
        if !k.label.is_empty() {
            canvas.text(
                &k.label,
                (px - tick_len - 0.2 * f, py + 0.5 * DIGIT_HEIGHT * t),
                t,
                Anchor::End,
                0.0,
                Role::TickLabel,
            );
        }
    }
    let x_label_y = area.y + area.h + tick_len + 1.15 * t + 1.05 * f;
    canvas.text(
        &panel.x.label,
        (area.x + area.w / 2.0, x_label_y),
        f,
        Anchor::Middle,
        0.0,
        Role::AxisLabel,
    );
    let y_label_x = area.x - left_gutter + 0.95 * f;
    // A description longer than the panel is tall is set smaller, down to
    // the smallest print size, rather than run into the panel above.
    let fit = TEXT_FIT * area.h / text_width(&panel.y.label, f).max(1e-9);
    let y_size = (f * fit.min(1.0)).max(MIN_FONT_PT.min(f));
    canvas.text(
        &panel.y.label,
        (y_label_x, area.y + area.h / 2.0),
        (y_size * 100.0).floor() / 100.0,
        Anchor::Middle,
        -90.0,
        Role::AxisLabel,
    );
    if let Some(title) = &panel.title {
        let lines = wrap(title, title_width, f);
        for (k, line) in lines.iter().enumerate() {
            let above = (lines.len() - 1 - k) as f64 * 1.25 * f;
            canvas.text(
                line,
                (area.x, area.y - 0.45 * f - above),
                f,
                Anchor::Start,
                0.0,
                Role::PanelTitle,
            );
        }
    }
    for note in &panel.notes {
        let (fx, fy) = fractions(panel, note.at);
        if inside(fx) && inside(fy) {
            let (px, py) = area.at(fx, fy);
            // A note that would run out of the panel is set against its
            // anchor's other side, so it never covers a neighbour.
            let w = text_width(&note.text, f);
            let anchor = match note.anchor {
                Anchor::Start if px + w > area.x + area.w => Anchor::End,
                Anchor::End if px - w < area.x => Anchor::Start,
                a => a,
            };
            canvas.text(&note.text, (px, py), f, anchor, 0.0, Role::Annotation);
        }
    }
}

/// The axis's ticks with the most labels, up to its wish, that `fits`
/// (given the labels); at least two labels on a linear axis. A
/// logarithmic or phase axis keeps its ticks and labels fewer of them
/// until `apart` (given the labelled ticks) holds: all of them, then (log)
/// only the powers of ten, then every k-th of those.
fn fitting_ticks(
    axis: &Axis,
    fits: impl Fn(&[&str]) -> bool,
    apart: impl Fn(&[&super::axes::Tick]) -> bool,
) -> Vec<super::axes::Tick> {
    let labelled = |ticks: &[super::axes::Tick]| -> Vec<String> {
        ticks
            .iter()
            .filter(|k| !k.label.is_empty())
            .map(|k| k.label.clone())
            .collect()
    };
    if axis.log || axis.pi {
        let ticks = axis.tick_marks();
        let decade = |v: f64| {
            let m = v / 10f64.powf(v.log10().floor());
            (m - 1.0).abs() < 1e-9
        };
        let keep = |t: &super::axes::Tick, powers: bool| {
            !t.label.is_empty() && (!powers || decade(t.value))
        };
        let count = ticks.iter().filter(|t| !t.label.is_empty()).count().max(1);
        let mut candidates: Vec<(bool, usize)> = vec![(false, 1)];
        if axis.log {
            candidates.extend((1..=count).map(|k| (true, k)));
        } else {
            candidates.extend((2..=count).map(|k| (false, k)));
        }
        for (powers, every) in candidates {
            let mut k = 0;
            let thinned: Vec<super::axes::Tick> = ticks
                .iter()
                .map(|t| {
                    let mut t = t.clone();
                    if keep(&t, powers) {
                        if k % every != 0 {
                            t.label.clear();
                        }
                        k += 1;
                    } else {
                        t.label.clear();
                    }
                    t
                })
                .collect();
            let shown: Vec<&super::axes::Tick> =
                thinned.iter().filter(|t| !t.label.is_empty()).collect();
            if shown.len() <= 2 || apart(&shown) {
                return thinned;
            }
        }
        return ticks;
    }
    let mut wanted = axis.ticks;
    loop {
        let ticks = axis.clone().with_ticks(wanted).tick_marks();
        let labels = labelled(&ticks);
        let refs: Vec<&str> = labels.iter().map(String::as_str).collect();
        if wanted <= 2 || fits(&refs) {
            return ticks;
        }
        wanted -= 1;
    }
}

/// Markers on a curve of many points: about this many per piece.
const MARKERS_PER_CURVE: usize = 9;

fn draw_series(canvas: &mut Canvas, panel: &Panel, area: Rect, style: &Style) {
    let size = marker_size(style);
    let in_unit = |(fx, fy): (f64, f64)| {
        (-1e-9..=1.0 + 1e-9).contains(&fx) && (-1e-9..=1.0 + 1e-9).contains(&fy)
    };
    for (index, s) in panel.series.iter().enumerate() {
        let label = s.label.as_deref().unwrap_or("");
        canvas.open_series(label, &s.look, s.kind.name());
        let width = style.line_pt * s.look.weight;
        // Bands and areas are filled as one shape per series, so touching
        // pieces show no seam.
        let (mut rects, mut polygons) = (Vec::new(), Vec::new());
        for piece in &s.pieces {
            let frac: Vec<(f64, f64)> = piece.iter().map(|&p| fractions(panel, p)).collect();
            match s.kind {
                Kind::Bands => {
                    if let [a, b] = frac[..] {
                        let clamp = |v: f64| {
                            if v.is_finite() {
                                v.clamp(0.0, 1.0)
                            } else {
                                0.0
                            }
                        };
                        let (x0, y0) = area.at(clamp(a.0.min(b.0)), clamp(a.1.max(b.1)));
                        let (x1, y1) = area.at(clamp(a.0.max(b.0)), clamp(a.1.min(b.1)));
                        rects.push([(x0, y0), (x1, y1)]);
                    }
                }
                Kind::Areas => {
                    let clamp =
                        |(fx, fy): (f64, f64)| area.at(fx.clamp(0.0, 1.0), fy.clamp(0.0, 1.0));
                    polygons.push(frac.iter().map(|&p| clamp(p)).collect::<Vec<_>>());
                }
                Kind::Points => {
                    for p in frac.iter().filter(|p| in_unit(**p)) {
                        canvas.marker(s.look.marker, area.at(p.0, p.1), size, s.look.color);
                    }
                }
                Kind::Curve => {
                    for part in clip_polyline(&frac, (0.0, 1.0), (0.0, 1.0)) {
                        let pts: Vec<(f64, f64)> = part.iter().map(|p| area.at(p.0, p.1)).collect();
                        canvas.polyline(&pts, s.look.color, width, s.look.dash);
                    }
                    let inside: Vec<(f64, f64)> =
                        frac.iter().copied().filter(|p| in_unit(*p)).collect();
                    for p in marker_points(&inside, index) {
                        canvas.marker(s.look.marker, area.at(p.0, p.1), size, s.look.color);
                    }
                }
            }
        }
        canvas.fill_rects(&rects, s.look.color);
        canvas.fill_polygons(&polygons, s.look.color);
        canvas.close();
    }
}

/// The points of a curve that carry its marker: all of a short curve;
/// about [`MARKERS_PER_CURVE`] evenly spread ones of a long one, shifted
/// by the series' index so that markers of overlapping curves do not
/// hide each other.
fn marker_points(points: &[(f64, f64)], index: usize) -> Vec<(f64, f64)> {
    if points.len() <= 2 * MARKERS_PER_CURVE {
        return points.to_vec();
    }
    let step = points.len() as f64 / MARKERS_PER_CURVE as f64;
    let shift = (index % 3) as f64 / 3.0 + 0.5 / 3.0;
    (0..MARKERS_PER_CURVE)
        .map(|k| points[(((k as f64 + shift) * step) as usize).min(points.len() - 1)])
        .collect()
}

/// An axis over the values, padded by `frac` of the span on both ends
/// (linear) or to whole factors (log).
pub fn fitted(label: &str, values: impl IntoIterator<Item = f64>, log: bool, frac: f64) -> Axis {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if log {
        let k = (hi / lo).powf(frac);
        Axis::log(label, (lo / k, hi * k))
    } else {
        let pad = (hi - lo) * frac;
        Axis::linear(label, (lo - pad, hi + pad))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_wrap_at_spaces_within_the_width() {
        let lines = wrap(
            "one two three four five six",
            text_width("one two three", 8.0),
            8.0,
        );
        assert_eq!(lines, ["one two three", "four five six"]);
        assert_eq!(wrap("unbreakable", 1.0, 8.0), ["unbreakable"]);
    }
}
