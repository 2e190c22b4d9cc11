//! What a drawing put where: every text's box (from the shipped fonts'
//! metrics), every panel frame, every data line and marker, and the
//! legend's box, in points on the page (y downwards), as the SVG is
//! written.
//!
//! Contract: the canvas records a mark for every element it writes, so
//! the marks of [`super::Figure::marks`] describe exactly the SVG of
//! [`super::Figure::svg`] at the same style: a text's box spans its
//! runs' advances horizontally and their glyphs' ink vertically, turned
//! with the text; data lines and markers are those of the panels (a
//! legend's swatches are part of the legend's box, not data); grid lines
//! and ticks are neither.

/// An axis-aligned box on the page (pt, y downwards).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounds {
    /// Left edge.
    pub x0: f64,
    /// Top edge.
    pub y0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y1: f64,
}

impl Bounds {
    /// The smallest box holding both.
    pub fn union(self, o: Bounds) -> Bounds {
        Bounds {
            x0: self.x0.min(o.x0),
            y0: self.y0.min(o.y0),
            x1: self.x1.max(o.x1),
            y1: self.y1.max(o.y1),
        }
    }

    /// True if the two boxes share an area (touching edges do not).
    pub fn overlaps(&self, o: &Bounds) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// True if the segment from `a` to `b` passes through the box's
    /// inside.
    pub fn crossed_by(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        // Liang-Barsky clipping of the segment against the open box.
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let mut t0: f64 = 0.0;
        let mut t1: f64 = 1.0;
        for (p, q) in [
            (-dx, a.0 - self.x0),
            (dx, self.x1 - a.0),
            (-dy, a.1 - self.y0),
            (dy, self.y1 - a.1),
        ] {
            if p == 0.0 {
                if q <= 0.0 {
                    return false;
                }
            } else {
                let t = q / p;
                if p < 0.0 {
                    t0 = t0.max(t);
                } else {
                    t1 = t1.min(t);
                }
            }
        }
        t0 < t1
    }

    /// Height.
    pub fn height(&self) -> f64 {
        self.y1 - self.y0
    }
}

/// What a text is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The figure's title (only when the style has one).
    Title,
    /// A legend entry's label.
    Legend,
    /// A line of text under the legend.
    Note,
    /// A panel's heading.
    PanelTitle,
    /// An axis description.
    AxisLabel,
    /// A tick label.
    TickLabel,
    /// A text placed in a panel at data coordinates.
    Annotation,
}

/// One text as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct TextMark {
    /// The characters a reader sees (markup removed).
    pub text: String,
    /// What it is for.
    pub role: Role,
    /// Its box.
    pub bounds: Bounds,
    /// The smallest size (pt) any of its characters is set at.
    pub smallest_pt: f64,
}

/// Everything a drawing put on its page.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Marks {
    /// Page width (pt).
    pub width: f64,
    /// Page height (pt).
    pub height: f64,
    /// Every text.
    pub texts: Vec<TextMark>,
    /// Every panel's frame (the outline of its plotting area) and its
    /// stroke width (pt).
    pub frames: Vec<(Bounds, f64)>,
    /// Every data polyline (panels only) and its stroke width (pt).
    pub lines: Vec<(Vec<(f64, f64)>, f64)>,
    /// Every data marker's box (panels only).
    pub markers: Vec<Bounds>,
    /// The legend's box (swatches and labels), if there is a legend.
    pub legend: Option<Bounds>,
}
