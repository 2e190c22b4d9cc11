//! A colour bar: the scale of a map's colours, drawn once above the
//! panels, in place of one legend entry per colour.
//!
//! Contract: the bar spans its range left to right in equal steps, one
//! per colour (the map's levels, so a level reads off the bar exactly);
//! ticks and labels are those of a linear axis over the range; its
//! description sits under the tick labels. It takes
//! [`height`] points and never overlaps the panels below it.

use super::axes::Axis;
use super::canvas::{Anchor, Canvas};
use super::font::{DIGIT_HEIGHT, text_width};
use super::marks::Role;
use super::style::{Rgb, Style};

/// The scale of a map's colours.
#[derive(Debug, Clone, PartialEq)]
pub struct ColorBar {
    /// Description with unit (quantity markup allowed).
    pub label: String,
    /// The values at the bar's two ends.
    pub range: (f64, f64),
    /// The colours, low to high, each an equal share of the range.
    pub colors: Vec<Rgb>,
}

/// Height (pt) of the bar, its ticks, labels and description.
pub(crate) fn height(style: &Style) -> f64 {
    let (f, t) = (style.font_pt, style.tick_pt());
    0.9 * f + 0.3 * f + 1.15 * t + 1.45 * f
}

/// Draws the bar with its top-left corner at `(x, y)` in `width` (pt).
pub(crate) fn draw(
    canvas: &mut Canvas,
    bar: &ColorBar,
    (x, y): (f64, f64),
    width: f64,
    style: &Style,
) {
    let (f, t) = (style.font_pt, style.tick_pt());
    let axis = Axis::linear(&bar.label, bar.range).with_ticks(5);
    let ticks = axis.tick_marks();
    let margin = ticks
        .iter()
        .map(|k| text_width(&k.label, t) / 2.0)
        .fold(f, f64::max);
    let (x0, w) = (x + margin, width - 2.0 * margin);
    let h = 0.9 * f;
    let n = bar.colors.len().max(1) as f64;
    for (i, c) in bar.colors.iter().enumerate() {
        let a = x0 + w * i as f64 / n;
        let b = x0 + w * (i + 1) as f64 / n;
        canvas.fill_rect(a, y, b - a + 0.3, h, *c);
    }
    let line = 0.6 * style.line_pt.min(1.5);
    canvas.frame(x0, y, w, h, Rgb(0, 0, 0), line);
    let tick_len = 0.3 * f;
    for k in ticks.iter().filter(|k| !k.label.is_empty()) {
        let fx = axis.fraction(k.value);
        if !(-1e-9..=1.0 + 1e-9).contains(&fx) {
            continue;
        }
        let px = x0 + fx * w;
        canvas.line((px, y + h), (px, y + h + tick_len), Rgb(0, 0, 0), line);
        canvas.text(
            &k.label,
            (px, y + h + tick_len + 0.15 * f + DIGIT_HEIGHT * t),
            t,
            Anchor::Middle,
            0.0,
            Role::TickLabel,
        );
    }
    canvas.text(
        &bar.label,
        (x0 + w / 2.0, y + h + tick_len + 1.15 * t + 1.05 * f),
        f,
        Anchor::Middle,
        0.0,
        Role::AxisLabel,
    );
}
