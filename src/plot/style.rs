//! Print presets and the look of series: the figure's printed size and
//! font size, and for each series a colour, a dash pattern and a marker.
//!
//! Contract: every text is drawn at [`Style::font_pt`] or
//! [`Style::tick_pt`], both at least [`MIN_FONT_PT`] at the printed size
//! (the SVG's user unit is the point, so `font-size` is in points). Series
//! are told apart by colour (the Okabe-Ito palette, safe for the common
//! colour-vision deficiencies) and, for greyscale print, by their dash
//! pattern or marker: [`Look::nth`] gives distinct (dash, marker) pairs for
//! the first 24 series (4 dashes times 6 markers).

use std::fmt;

/// Millimetres to points (1 pt = 1/72 in).
pub(crate) const PT_PER_MM: f64 = 72.0 / 25.4;

/// The smallest text size a journal accepts at the printed size.
pub(crate) const MIN_FONT_PT: f64 = 7.0;

/// A named print preset (`--style`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Preset {
    /// One journal column: 85 mm wide, 8 pt text.
    SingleColumn,
    /// The full page width of a two-column journal: 175 mm, 8 pt text.
    DoubleColumn,
    /// A presentation slide: 254 mm wide (a 16:9 slide of 10 in), 16 pt
    /// text; as tall as the panels need (`--height` to fix it).
    Slide,
}

impl Preset {
    /// Every preset, in the order of `--help`.
    pub const ALL: [Preset; 3] = [Preset::SingleColumn, Preset::DoubleColumn, Preset::Slide];

    /// The name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Preset::SingleColumn => "single-column",
            Preset::DoubleColumn => "double-column",
            Preset::Slide => "slide",
        }
    }

    /// The preset called `name`.
    pub fn from_name(name: &str) -> Option<Preset> {
        Preset::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The preset's style: its width and font; the height follows the
    /// figure ([`Style::height_mm`] `None`).
    pub fn style(self) -> Style {
        let (width_mm, height_mm, font_pt, line_pt) = match self {
            Preset::SingleColumn => (85.0, None, 8.0, 1.0),
            Preset::DoubleColumn => (175.0, None, 8.0, 1.0),
            Preset::Slide => (254.0, None, 16.0, 2.0),
        };
        Style {
            width_mm,
            height_mm,
            font_pt,
            line_pt,
            title: None,
        }
    }
}

impl fmt::Display for Preset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The printed size and text of one figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// Printed width (mm).
    pub width_mm: f64,
    /// Printed height (mm); `None`: as the figure's panels need.
    pub height_mm: Option<f64>,
    /// Text size (pt) of labels, legends and notes.
    pub font_pt: f64,
    /// Width (pt) of a data line.
    pub line_pt: f64,
    /// A title above the figure (journals typeset their own captions, so
    /// none by default).
    pub title: Option<String>,
}

impl Style {
    /// Tick labels: one point smaller than the other text, never below
    /// `MIN_FONT_PT`.
    pub fn tick_pt(&self) -> f64 {
        (self.font_pt - 1.0).max(MIN_FONT_PT)
    }

    /// Width in points.
    pub fn width_pt(&self) -> f64 {
        self.width_mm * PT_PER_MM
    }
}

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl fmt::Display for Rgb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// The Okabe-Ito palette, black first.
pub(crate) const PALETTE: [Rgb; 8] = [
    Rgb(0, 0, 0),       // black
    Rgb(0, 114, 178),   // blue
    Rgb(213, 94, 0),    // vermillion
    Rgb(0, 158, 115),   // bluish green
    Rgb(204, 121, 167), // reddish purple
    Rgb(230, 159, 0),   // orange
    Rgb(86, 180, 233),  // sky blue
    Rgb(240, 228, 66),  // yellow
];

/// Grey for reference lines, bands and grid lines.
pub(crate) const GREY: Rgb = Rgb(120, 120, 120);

/// Light grey for the grid.
pub(crate) const GRID: Rgb = Rgb(221, 221, 221);

/// Fill of bands (the stick band): light enough for data on top.
pub(crate) const BAND: Rgb = Rgb(214, 214, 214);

/// A line's dash pattern.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dash {
    /// Solid.
    Solid,
    /// Dashes.
    Dashed,
    /// Dots.
    Dotted,
    /// Dash and dot.
    DashDot,
    /// Long dashes, kept for reference lines.
    LongDash,
    /// No line: markers only.
    NoLine,
}

impl Dash {
    /// The name in the SVG's `data-dash`.
    pub fn name(self) -> &'static str {
        match self {
            Dash::Solid => "solid",
            Dash::Dashed => "dashed",
            Dash::Dotted => "dotted",
            Dash::DashDot => "dash-dot",
            Dash::LongDash => "long-dash",
            Dash::NoLine => "none",
        }
    }

    /// `stroke-dasharray` in multiples of the line width (`None`: solid).
    pub(crate) fn pattern(self) -> Option<&'static [f64]> {
        match self {
            Dash::Solid | Dash::NoLine => None,
            Dash::Dashed => Some(&[4.0, 2.5]),
            Dash::Dotted => Some(&[1.0, 1.8]),
            Dash::DashDot => Some(&[5.0, 2.0, 1.0, 2.0]),
            Dash::LongDash => Some(&[9.0, 3.0]),
        }
    }
}

/// A marker drawn at data points.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Marker {
    /// None.
    None,
    /// Filled circle.
    Circle,
    /// Filled square.
    Square,
    /// Filled triangle, point up.
    Triangle,
    /// Filled diamond.
    Diamond,
    /// Filled triangle, point down.
    TriangleDown,
    /// A plus sign (strokes).
    Plus,
    /// A diagonal cross (strokes): failed or unsettled cases.
    Cross,
}

impl Marker {
    /// The name in the SVG's `data-marker`.
    pub fn name(self) -> &'static str {
        match self {
            Marker::None => "none",
            Marker::Circle => "circle",
            Marker::Square => "square",
            Marker::Triangle => "triangle",
            Marker::Diamond => "diamond",
            Marker::TriangleDown => "triangle-down",
            Marker::Plus => "plus",
            Marker::Cross => "cross",
        }
    }
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Look {
    /// Colour.
    pub color: Rgb,
    /// Line pattern.
    pub dash: Dash,
    /// Marker.
    pub marker: Marker,
    /// Line width relative to [`Style::line_pt`].
    pub weight: f64,
}

impl Look {
    /// The look of the `i`-th series of a figure: colours in palette order;
    /// the first four series differ by their dash pattern alone, later
    /// ones add a marker (so every pair (dash, marker) differs for
    /// `i < 24`, 4 dashes times 6 markers).
    pub fn nth(i: usize) -> Look {
        const DASHES: [Dash; 4] = [Dash::Solid, Dash::Dashed, Dash::Dotted, Dash::DashDot];
        const MARKERS: [Marker; 6] = [
            Marker::None,
            Marker::Circle,
            Marker::Square,
            Marker::Triangle,
            Marker::Diamond,
            Marker::TriangleDown,
        ];
        Look {
            color: PALETTE[i % PALETTE.len()],
            dash: DASHES[i % DASHES.len()],
            marker: MARKERS[(i / DASHES.len()) % MARKERS.len()],
            weight: 1.0,
        }
    }

    /// The `i`-th series of points without lines: markers in turn.
    pub fn nth_points(i: usize) -> Look {
        const MARKERS: [Marker; 6] = [
            Marker::Circle,
            Marker::Square,
            Marker::Triangle,
            Marker::Diamond,
            Marker::TriangleDown,
            Marker::Plus,
        ];
        Look {
            color: PALETTE[i % PALETTE.len()],
            dash: Dash::NoLine,
            marker: MARKERS[i % MARKERS.len()],
            weight: 1.0,
        }
    }

    /// A solid line of colour `color`.
    pub fn line(color: Rgb, dash: Dash) -> Look {
        Look {
            color,
            dash,
            marker: Marker::None,
            weight: 1.0,
        }
    }

    /// A reference line (grey, long dashes).
    pub fn reference() -> Look {
        Look {
            weight: 0.8,
            ..Look::line(GREY, Dash::LongDash)
        }
    }

    /// The same look with `marker`.
    pub fn with_marker(mut self, marker: Marker) -> Look {
        self.marker = marker;
        self
    }

    /// The same look with line weight `weight`.
    pub fn weighted(mut self, weight: f64) -> Look {
        self.weight = weight;
        self
    }
}

#[cfg(test)]
mod tests {
    use super::Look;

    #[test]
    fn the_first_24_looks_differ_in_dash_or_marker() {
        // 4 dash patterns times 6 markers: the pairs repeat from i = 24 on.
        let pair = |i: usize| {
            let l = Look::nth(i);
            (format!("{:?}", l.dash), format!("{:?}", l.marker))
        };
        let pairs: Vec<_> = (0..24).map(pair).collect();
        for i in 0..24 {
            for j in 0..i {
                assert_ne!(pairs[i], pairs[j], "looks {j} and {i}");
            }
        }
        assert_eq!(pair(24), pairs[0]);
    }
}
