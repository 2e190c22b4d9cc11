//! The legend: one entry per labelled series (each label once), laid out
//! in rows above the panels so that no text covers data.
//!
//! Contract: an entry shows the series' own look (dash pattern, marker,
//! colour, or a filled swatch for bands) beside its label; rows are
//! filled left to right and never wider than the figure.

use super::canvas::{Anchor, Canvas};
use super::font::{DIGIT_HEIGHT, text_width};
use super::marks::Role;
use super::series::{Kind, Panel};
use super::style::{Look, Style};

/// One legend entry.
#[derive(Debug, Clone, PartialEq)]
pub struct LegendEntry {
    /// Label text.
    pub label: String,
    /// The series' look.
    pub look: Look,
    /// The series' kind (bands show a filled swatch).
    pub kind: Kind,
}

/// The entries of the panels' labelled series, each label once, in order
/// of first appearance.
pub(super) fn legend_of(panels: &[Panel]) -> Vec<LegendEntry> {
    let mut entries: Vec<LegendEntry> = Vec::new();
    for p in panels {
        for s in &p.series {
            if let Some(label) = &s.label
                && !entries.iter().any(|e| &e.label == label)
            {
                entries.push(LegendEntry {
                    label: label.clone(),
                    look: s.look,
                    kind: s.kind,
                });
            }
        }
    }
    entries
}

/// Geometry of a legend at one font size.
struct Metrics {
    swatch: f64,
    gap: f64,
    entry_gap: f64,
    row: f64,
    font: f64,
}

impl Metrics {
    fn of(style: &Style) -> Self {
        let f = style.font_pt;
        Metrics {
            swatch: 2.6 * f,
            gap: 0.4 * f,
            entry_gap: 1.2 * f,
            row: 1.3 * f,
            font: f,
        }
    }

    fn entry_width(&self, e: &LegendEntry) -> f64 {
        self.swatch + self.gap + text_width(&e.label, self.font)
    }
}

/// Splits entries into rows no wider than `width` (pt).
fn rows(entries: &[LegendEntry], width: f64, m: &Metrics) -> Vec<std::ops::Range<usize>> {
    let mut rows = Vec::new();
    let mut start = 0;
    let mut used = 0.0;
    for (i, e) in entries.iter().enumerate() {
        let w = m.entry_width(e);
        if i > start && used + m.entry_gap + w > width {
            rows.push(start..i);
            start = i;
            used = 0.0;
        }
        used += if i > start { m.entry_gap + w } else { w };
    }
    if start < entries.len() {
        rows.push(start..entries.len());
    }
    rows
}

/// Height (pt) the legend needs in `width`.
pub(crate) fn height(entries: &[LegendEntry], width: f64, style: &Style) -> f64 {
    let m = Metrics::of(style);
    rows(entries, width, &m).len() as f64 * m.row
}

/// Draws the legend with its top-left corner at `(x, y)` in `width`.
pub(crate) fn draw(
    canvas: &mut Canvas,
    entries: &[LegendEntry],
    (x, y): (f64, f64),
    width: f64,
    style: &Style,
) {
    let m = Metrics::of(style);
    canvas.legend_mode(true);
    for (r, row) in rows(entries, width, &m).into_iter().enumerate() {
        let mid = y + (r as f64 + 0.5) * m.row;
        let mut at = x;
        for e in &entries[row] {
            canvas.open_series(&e.label, &e.look, e.kind.name());
            swatch(canvas, e, (at, mid), &m, style);
            canvas.close();
            canvas.text(
                &e.label,
                (at + m.swatch + m.gap, mid + 0.5 * DIGIT_HEIGHT * m.font),
                m.font,
                Anchor::Start,
                0.0,
                Role::Legend,
            );
            at += m.entry_width(e) + m.entry_gap;
        }
    }
    canvas.legend_mode(false);
}

fn swatch(canvas: &mut Canvas, e: &LegendEntry, (x, y): (f64, f64), m: &Metrics, style: &Style) {
    let look = e.look;
    match e.kind {
        Kind::Bands | Kind::Areas => {
            let h = 0.8 * m.font;
            canvas.fill_rect(x, y - h / 2.0, m.swatch, h, look.color);
        }
        Kind::Curve | Kind::Points => {
            if e.kind == Kind::Curve {
                canvas.polyline(
                    &[(x, y), (x + m.swatch, y)],
                    look.color,
                    style.line_pt * look.weight,
                    look.dash,
                );
            }
            canvas.marker(
                look.marker,
                (x + m.swatch / 2.0, y),
                marker_size(style),
                look.color,
            );
        }
    }
}

/// Marker diameter (pt) at a style.
pub(crate) fn marker_size(style: &Style) -> f64 {
    (0.55 * style.font_pt).max(3.5)
}
