//! Series and panels: what is drawn, in data coordinates.
//!
//! Contract: a [`Series`] is a curve (one or more pieces, each a
//! polyline), a set of points, bands (filled spans) or areas (filled
//! polygons, drawn as one shape so that touching ones leave no seam); its
//! [`Look`] is
//! its identity in the legend. A [`Panel`] holds two axes, series drawn in
//! order (later on top) and notes. Drawing clips every curve to the axes
//! ([`clip_polyline`]), so a zoomed axis never draws outside its panel.

use super::axes::Axis;
use super::canvas::Anchor;
use super::style::Look;

/// What a series draws.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Polylines through the points of each piece, with markers at some
    /// points when the look has one.
    Curve,
    /// A marker at every point.
    Points,
    /// Filled spans: consecutive points of a piece are opposite corners.
    Bands,
    /// Filled polygons, one per piece, all filled as one shape (nonzero
    /// rule), so polygons sharing an edge show no seam between them.
    Areas,
}

impl Kind {
    /// The name in the SVG's `data-kind`.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Curve => "curve",
            Kind::Points => "points",
            Kind::Bands => "bands",
            Kind::Areas => "areas",
        }
    }
}

/// One series of a panel.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label (`None`: not in the legend).
    pub label: Option<String>,
    /// Pieces of the data: each is one polyline (so jumps can be gaps).
    pub pieces: Vec<Vec<(f64, f64)>>,
    /// Colour, dash pattern and marker.
    pub look: Look,
    /// Curve, points, bands or areas.
    pub kind: Kind,
}

impl Series {
    /// A connected curve.
    pub fn line(label: Option<&str>, points: Vec<(f64, f64)>, look: Look) -> Self {
        Series {
            label: label.map(str::to_owned),
            pieces: vec![points],
            look,
            kind: Kind::Curve,
        }
    }

    /// A horizontal line at `y` across `x0..x1`.
    pub fn hline(label: Option<&str>, y: f64, (x0, x1): (f64, f64), look: Look) -> Self {
        Self::line(label, vec![(x0, y), (x1, y)], look)
    }

    /// Markers at `points`.
    pub fn points(label: Option<&str>, points: Vec<(f64, f64)>, look: Look) -> Self {
        Series {
            label: label.map(str::to_owned),
            pieces: vec![points],
            look,
            kind: Kind::Points,
        }
    }

    /// Filled spans, each given by two opposite corners.
    pub fn bands(label: Option<&str>, spans: Vec<[(f64, f64); 2]>, look: Look) -> Self {
        Series {
            label: label.map(str::to_owned),
            pieces: spans.into_iter().map(|[a, b]| vec![a, b]).collect(),
            look,
            kind: Kind::Bands,
        }
    }

    /// Filled polygons, each given by its corners (all in the same
    /// orientation, so that touching ones add up).
    pub fn areas(label: Option<&str>, polygons: Vec<Vec<(f64, f64)>>, look: Look) -> Self {
        Series {
            label: label.map(str::to_owned),
            pieces: polygons,
            look,
            kind: Kind::Areas,
        }
    }
}

/// A text placed in data coordinates.
#[derive(Debug, Clone, PartialEq)]
pub struct Note {
    /// Anchor point (data coordinates, before the axis scale).
    pub at: (f64, f64),
    /// The text.
    pub text: String,
    /// Horizontal alignment at the anchor.
    pub anchor: Anchor,
}

/// A panel: axes, series, notes and an optional heading.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Heading above the plotting area, e.g. `(a) first period`.
    pub title: Option<String>,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// Series, drawn in order.
    pub series: Vec<Series>,
    /// Notes.
    pub notes: Vec<Note>,
}

impl Panel {
    /// A panel with the given axes and nothing in it.
    pub fn new(title: Option<&str>, x: Axis, y: Axis) -> Self {
        Panel {
            title: title.map(str::to_owned),
            x,
            y,
            series: Vec::new(),
            notes: Vec::new(),
        }
    }

    /// Adds a note at `at` (data coordinates).
    pub fn note(&mut self, at: (f64, f64), text: &str, anchor: Anchor) {
        self.notes.push(Note {
            at,
            text: text.to_owned(),
            anchor,
        });
    }
}

/// The parts of `points` inside the box `x` x `y`, as polylines: each
/// segment is clipped (Liang-Barsky) and runs of connected clipped segments
/// are joined.
pub(super) fn clip_polyline(
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
                if !(open && a == p) {
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
    out
}

fn clip_segment(
    p: (f64, f64),
    q: (f64, f64),
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    if !(p.0.is_finite() && p.1.is_finite() && q.0.is_finite() && q.1.is_finite()) {
        return None;
    }
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
}
