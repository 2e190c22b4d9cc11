//! The SVG document: a writer of the few elements figures use, in points
//! (the document's user unit; its printed size is given in mm).
//!
//! Contract: numbers are written with at most two decimals (0.01 pt, far
//! below what print resolves), so the text is the same on every machine;
//! every text element carries its `font-size` in points; nothing is drawn
//! in the background colour (there is no background element: the page is
//! the background); markers are filled or stroked in the series' colour.

use super::font::FAMILY;
use super::marks::{Bounds, Marks, Role, TextMark};
use super::style::{Dash, Look, Marker, Rgb};
use super::text;
use std::fmt::Write as _;

/// Horizontal anchor of a text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// Text starts at the point.
    Start,
    /// Text is centred on the point.
    Middle,
    /// Text ends at the point.
    End,
}

impl Anchor {
    fn name(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// A number with at most two decimals, no trailing zeros, no `-0`.
pub(crate) fn num(x: f64) -> String {
    let r = (x * 100.0).round() / 100.0;
    let s = format!("{r:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_owned()
    } else {
        s.to_owned()
    }
}

/// Escapes text for XML.
pub(crate) fn escape(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// An SVG document being written, and the marks of what it holds.
#[derive(Default)]
pub(crate) struct Canvas {
    body: String,
    /// What was drawn where (see `marks`).
    pub(crate) marks: Marks,
    /// Inside a series' group: lines and markers are data.
    in_series: bool,
    /// Drawing the legend: everything drawn belongs to its box.
    in_legend: bool,
}

impl Canvas {
    /// Starts (`true`) or ends (`false`) the legend: what is drawn in
    /// between makes up the legend's box.
    pub(crate) fn legend_mode(&mut self, on: bool) {
        self.in_legend = on;
    }

    fn record(&mut self, b: Bounds) -> bool {
        if self.in_legend {
            self.marks.legend = Some(self.marks.legend.map_or(b, |l| l.union(b)));
            return false;
        }
        self.in_series
    }

    /// Opens a group for one series; [`Canvas::close`] ends it.
    pub(crate) fn open_series(&mut self, label: &str, look: &Look, kind: &str) {
        self.in_series = true;
        let _ = writeln!(
            self.body,
            r#"<g class="series" data-kind="{kind}" data-label="{}" data-color="{}" data-dash="{}" data-marker="{}">"#,
            escape(label),
            look.color,
            look.dash.name(),
            look.marker.name()
        );
    }

    /// Closes a group.
    pub(crate) fn close(&mut self) {
        self.in_series = false;
        self.body.push_str("</g>\n");
    }

    fn stroke_attrs(&self, color: Rgb, width: f64, dash: Dash) -> String {
        let mut s = format!(
            r#"fill="none" stroke="{color}" stroke-width="{}" stroke-linejoin="round""#,
            num(width)
        );
        if let Some(p) = dash.pattern() {
            let parts: Vec<String> = p.iter().map(|d| num(d * width.max(0.6))).collect();
            let _ = write!(s, r#" stroke-dasharray="{}""#, parts.join(" "));
        }
        if dash == Dash::Dotted {
            s.push_str(r#" stroke-linecap="round""#);
        }
        s
    }

    /// A polyline through `points` (pt).
    pub(crate) fn polyline(&mut self, points: &[(f64, f64)], color: Rgb, width: f64, dash: Dash) {
        if points.len() < 2 || dash == Dash::NoLine {
            return;
        }
        let (lo, hi) = super::min_max(points.iter().map(|p| p.0));
        let (top, bottom) = super::min_max(points.iter().map(|p| p.1));
        let h = width / 2.0;
        let b = Bounds {
            x0: lo - h,
            y0: top - h,
            x1: hi + h,
            y1: bottom + h,
        };
        if self.record(b) {
            self.marks.lines.push((points.to_vec(), width));
        }
        let attrs = self.stroke_attrs(color, width, dash);
        self.body.push_str("<path d=\"");
        for (i, (x, y)) in points.iter().enumerate() {
            let cmd = if i == 0 { 'M' } else { 'L' };
            let _ = write!(self.body, "{cmd}{} {}", num(*x), num(*y));
        }
        let _ = writeln!(self.body, "\" {attrs}/>");
    }

    /// A straight line.
    pub(crate) fn line(&mut self, a: (f64, f64), b: (f64, f64), color: Rgb, width: f64) {
        self.polyline(&[a, b], color, width, Dash::Solid);
    }

    /// An outlined rectangle (no fill).
    pub(crate) fn frame(&mut self, x: f64, y: f64, w: f64, h: f64, color: Rgb, width: f64) {
        let b = Bounds {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        };
        if !self.in_legend {
            self.marks.frames.push((b, width));
        }
        let _ = writeln!(
            self.body,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="none" stroke="{color}" stroke-width="{}"/>"#,
            num(x),
            num(y),
            num(w),
            num(h),
            num(width)
        );
    }

    /// A filled rectangle without outline (see [`Canvas::fill_rects`]).
    pub(crate) fn fill_rect(&mut self, x: f64, y: f64, w: f64, h: f64, color: Rgb) {
        self.fill_rects(&[[(x, y), (x + w, y + h)]], color);
    }

    /// Filled rectangles without outline, each given by its top-left and
    /// bottom-right corners, in one path with edges on whole pixels
    /// (`crispEdges`). Every edge is written by its coordinate (never as
    /// a position plus a size), so a rectangle that ends where the next
    /// begins shares that edge exactly, and touching rectangles of one
    /// colour are one shape to the renderer: a raster shows no seam.
    pub(crate) fn fill_rects(&mut self, rects: &[[(f64, f64); 2]], color: Rgb) {
        // The coordinates as written (two decimals).
        let snap = |v: f64| (v * 100.0).round() / 100.0;
        let rects: Vec<[f64; 4]> = rects
            .iter()
            .map(|[a, b]| [snap(a.0), snap(a.1), snap(b.0), snap(b.1)])
            .filter(|[x0, y0, x1, y1]| x0 < x1 && y0 < y1)
            .collect();
        if rects.is_empty() {
            return;
        }
        let (x0, x1) = super::min_max(rects.iter().flat_map(|r| [r[0], r[2]]));
        let (y0, y1) = super::min_max(rects.iter().flat_map(|r| [r[1], r[3]]));
        self.record(Bounds { x0, y0, x1, y1 });
        self.body.push_str("<path d=\"");
        for r in &rects {
            let [x0, y0, x1, y1] = r.map(num);
            let _ = write!(self.body, "M{x0} {y0}H{x1}V{y1}H{x0}Z");
        }
        let _ = writeln!(
            self.body,
            "\" fill=\"{color}\" shape-rendering=\"crispEdges\"/>"
        );
    }

    /// Filled polygons without outline, all in one path (nonzero rule):
    /// polygons of the same orientation that share an edge are one shape
    /// to the renderer, so no seam shows between them.
    pub(crate) fn fill_polygons(&mut self, polygons: &[Vec<(f64, f64)>], color: Rgb) {
        let polygons: Vec<&Vec<(f64, f64)>> = polygons.iter().filter(|p| p.len() >= 3).collect();
        if polygons.is_empty() {
            return;
        }
        let (x0, x1) = super::min_max(polygons.iter().flat_map(|p| p.iter().map(|q| q.0)));
        let (y0, y1) = super::min_max(polygons.iter().flat_map(|p| p.iter().map(|q| q.1)));
        self.record(Bounds { x0, y0, x1, y1 });
        self.body.push_str("<path d=\"");
        for polygon in polygons {
            for (i, (x, y)) in polygon.iter().enumerate() {
                let cmd = if i == 0 { 'M' } else { 'L' };
                let _ = write!(self.body, "{cmd}{} {}", num(*x), num(*y));
            }
            self.body.push('Z');
        }
        let _ = writeln!(self.body, "\" fill=\"{color}\"/>");
    }

    /// A marker of diameter `size` (pt) centred on `(x, y)`.
    pub(crate) fn marker(&mut self, marker: Marker, (x, y): (f64, f64), size: f64, color: Rgb) {
        let r = size / 2.0;
        if marker != Marker::None
            && self.record(Bounds {
                x0: x - r,
                y0: y - r,
                x1: x + r,
                y1: y + r,
            })
        {
            self.marks.markers.push(Bounds {
                x0: x - r,
                y0: y - r,
                x1: x + r,
                y1: y + r,
            });
        }
        let fill = format!(r#"fill="{color}""#);
        let stroke = format!(
            r#"fill="none" stroke="{color}" stroke-width="{}""#,
            num(size / 5.0)
        );
        let poly = |pts: &[(f64, f64)]| -> String {
            let d: Vec<String> = pts
                .iter()
                .map(|(dx, dy)| format!("{},{}", num(x + dx * r), num(y + dy * r)))
                .collect();
            d.join(" ")
        };
        let line = match marker {
            Marker::None => return,
            Marker::Circle => format!(
                r#"<circle cx="{}" cy="{}" r="{}" {fill}/>"#,
                num(x),
                num(y),
                num(r * 0.9)
            ),
            Marker::Square => format!(
                r#"<rect x="{}" y="{}" width="{}" height="{}" {fill}/>"#,
                num(x - r * 0.8),
                num(y - r * 0.8),
                num(r * 1.6),
                num(r * 1.6)
            ),
            Marker::Triangle => format!(
                r#"<polygon points="{}" {fill}/>"#,
                poly(&[(0.0, -1.1), (1.0, 0.65), (-1.0, 0.65)])
            ),
            Marker::TriangleDown => format!(
                r#"<polygon points="{}" {fill}/>"#,
                poly(&[(0.0, 1.1), (1.0, -0.65), (-1.0, -0.65)])
            ),
            Marker::Diamond => format!(
                r#"<polygon points="{}" {fill}/>"#,
                poly(&[(0.0, -1.1), (0.9, 0.0), (0.0, 1.1), (-0.9, 0.0)])
            ),
            Marker::Plus => format!(
                r#"<path d="M{} {}H{}M{} {}V{}" {stroke}/>"#,
                num(x - r),
                num(y),
                num(x + r),
                num(x),
                num(y - r),
                num(y + r)
            ),
            Marker::Cross => {
                let k = r * 0.8;
                format!(
                    r#"<path d="M{} {}L{} {}M{} {}L{} {}" {stroke}/>"#,
                    num(x - k),
                    num(y - k),
                    num(x + k),
                    num(y + k),
                    num(x - k),
                    num(y + k),
                    num(x + k),
                    num(y - k)
                )
            }
        };
        self.body.push_str(&line);
        self.body.push('\n');
    }

    /// A text (with the quantity markup of `text`) whose baseline starts
    /// (or ends, or is centred, by `anchor`) at `(x, y)`, rotated by
    /// `rotate` degrees about that point; `role` says what it is for.
    pub(crate) fn text(
        &mut self,
        text: &str,
        (x, y): (f64, f64),
        size: f64,
        anchor: Anchor,
        rotate: f64,
        role: Role,
    ) {
        if text::visible(text).trim().is_empty() {
            return;
        }
        self.record_text(text, (x, y), size, anchor, rotate, role);
        let transform = if rotate == 0.0 {
            String::new()
        } else {
            format!(
                r#" transform="rotate({} {} {})""#,
                num(rotate),
                num(x),
                num(y)
            )
        };
        let _ = writeln!(
            self.body,
            r#"<text x="{}" y="{}" font-size="{}" text-anchor="{}"{transform}>{}</text>"#,
            num(x),
            num(y),
            num(size),
            anchor.name(),
            text::svg_content(text, size)
        );
    }

    fn record_text(
        &mut self,
        markup: &str,
        (x, y): (f64, f64),
        size: f64,
        anchor: Anchor,
        rotate: f64,
        role: Role,
    ) {
        let runs = text::parse(markup);
        let w = text::runs_width(&runs, size);
        let (top, bottom) = text::runs_extent(&runs, size);
        let start = match anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -w / 2.0,
            Anchor::End => -w,
        };
        let (sin, cos) = rotate.to_radians().sin_cos();
        let corners = [
            (start, top),
            (start + w, top),
            (start, bottom),
            (start + w, bottom),
        ]
        .map(|(dx, dy)| (x + dx * cos - dy * sin, y + dx * sin + dy * cos));
        let (x0, x1) = super::min_max(corners.iter().map(|c| c.0));
        let (y0, y1) = super::min_max(corners.iter().map(|c| c.1));
        let bounds = Bounds { x0, y0, x1, y1 };
        let smallest_pt = runs
            .iter()
            .filter(|r| !r.text.trim().is_empty())
            .map(|r| text::run_size(r, size))
            .fold(f64::INFINITY, f64::min);
        self.record(bounds);
        self.marks.texts.push(TextMark {
            text: text::visible(markup),
            role,
            bounds,
            smallest_pt,
        });
    }

    /// The finished document: `width_mm` x `height_mm` printed, in points
    /// inside, with `metadata` (program version, figure name).
    pub(crate) fn finish(self, (width_mm, height_mm): (f64, f64), metadata: &str) -> String {
        let pt = super::style::PT_PER_MM;
        format!(
            concat!(
                r#"<svg xmlns="http://www.w3.org/2000/svg" version="1.1" width="{w}mm" height="{h}mm" viewBox="0 0 {vw} {vh}">"#,
                "\n<metadata>{meta}</metadata>\n",
                r##"<g font-family="{family}" fill="#000000">"##,
                "\n{body}</g>\n</svg>\n"
            ),
            w = num(width_mm),
            h = num(height_mm),
            vw = num(width_mm * pt),
            vh = num(height_mm * pt),
            meta = escape(metadata),
            family = FAMILY,
            body = self.body
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_have_two_decimals_and_no_negative_zero() {
        assert_eq!(num(1.0), "1");
        assert_eq!(num(1.256), "1.26");
        assert_eq!(num(-0.001), "0");
        assert_eq!(num(240.944), "240.94");
    }
}
