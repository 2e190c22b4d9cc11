//! A reviewer's reading of a drawing: what a journal's production desk
//! sends back, checked on the [`Marks`] of a figure (boxes from the shipped
//! fonts' metrics).
//!
//! Contract: [`review`] reports every
//!
//! * text whose box overlaps another text's box (tick labels included) or
//!   the stroke of a panel's frame ([`Check::TextOverlap`]);
//! * legend whose box is crossed by a data line or covers a data marker
//!   ([`Check::LegendOverData`]);
//! * text with characters set below 7 pt (`MIN_FONT_PT`) at the printed size
//!   ([`Check::TextTooSmall`]);
//! * legend taller than [`MAX_LEGEND_SHARE`] of the figure
//!   ([`Check::LegendTooTall`]);
//! * text showing an underscore, a raw column name or unfinished markup
//!   ([`Check::Underscore`]).
//!
//! An empty list is a figure the checks find nothing wrong with. Boxes
//! that only touch do not overlap; overlaps smaller than [`SLACK`] (far
//! below what print resolves) are not reported.

use super::marks::{Bounds, Marks, Role};
use super::style::MIN_FONT_PT;
use std::fmt;

/// The largest share of the figure's height a legend may take.
pub const MAX_LEGEND_SHARE: f64 = 0.25;

/// Overlaps of less than this (pt) are rounding, not a collision.
pub const SLACK: f64 = 0.05;

/// Which check a finding fails.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Check {
    /// A text overlaps another text or a panel's frame.
    TextOverlap,
    /// A legend lies over a data line or marker.
    LegendOverData,
    /// A text is smaller than the smallest print size.
    TextTooSmall,
    /// A legend takes more than its share of the height.
    LegendTooTall,
    /// A text shows an underscore.
    Underscore,
}

/// One thing wrong with a figure.
#[derive(Debug, Clone, PartialEq)]
pub struct Finding {
    /// The check it fails.
    pub check: Check,
    /// What and where, for a person.
    pub what: String,
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}: {}", self.check, self.what)
    }
}

fn shrunk(b: &Bounds) -> Bounds {
    Bounds {
        x0: b.x0 + SLACK,
        y0: b.y0 + SLACK,
        x1: b.x1 - SLACK,
        y1: b.y1 - SLACK,
    }
}

fn role(r: Role) -> &'static str {
    match r {
        Role::Title => "title",
        Role::Legend => "legend label",
        Role::Note => "note",
        Role::PanelTitle => "panel title",
        Role::AxisLabel => "axis label",
        Role::TickLabel => "tick label",
        Role::Annotation => "annotation",
    }
}

/// The four strokes of a frame as boxes.
fn edges((b, w): &(Bounds, f64)) -> [Bounds; 4] {
    let h = w / 2.0;
    [
        Bounds {
            x0: b.x0 - h,
            y0: b.y0 - h,
            x1: b.x1 + h,
            y1: b.y0 + h,
        },
        Bounds {
            x0: b.x0 - h,
            y0: b.y1 - h,
            x1: b.x1 + h,
            y1: b.y1 + h,
        },
        Bounds {
            x0: b.x0 - h,
            y0: b.y0 - h,
            x1: b.x0 + h,
            y1: b.y1 + h,
        },
        Bounds {
            x0: b.x1 - h,
            y0: b.y0 - h,
            x1: b.x1 + h,
            y1: b.y1 + h,
        },
    ]
}

/// Everything the checks find wrong with the drawing `marks`.
pub fn review(marks: &Marks) -> Vec<Finding> {
    let mut out = Vec::new();
    let mut find = |check, what: String| out.push(Finding { check, what });
    let texts = &marks.texts;
    for (i, a) in texts.iter().enumerate() {
        let sa = shrunk(&a.bounds);
        for b in &texts[..i] {
            if sa.overlaps(&shrunk(&b.bounds)) {
                find(
                    Check::TextOverlap,
                    format!(
                        "{} \"{}\" overlaps {} \"{}\"",
                        role(a.role),
                        a.text,
                        role(b.role),
                        b.text
                    ),
                );
            }
        }
        if marks.frames.iter().flat_map(edges).any(|e| sa.overlaps(&e)) {
            find(
                Check::TextOverlap,
                format!("{} \"{}\" overlaps a panel's frame", role(a.role), a.text),
            );
        }
        if a.smallest_pt < MIN_FONT_PT - 1e-9 {
            find(
                Check::TextTooSmall,
                format!(
                    "{} \"{}\" is set at {:.2} pt",
                    role(a.role),
                    a.text,
                    a.smallest_pt
                ),
            );
        }
        if a.text.contains('_') || a.text.contains('$') {
            find(
                Check::Underscore,
                format!(
                    "{} \"{}\" shows an underscore or markup",
                    role(a.role),
                    a.text
                ),
            );
        }
    }
    if let Some(legend) = &marks.legend {
        let inner = shrunk(legend);
        let crossed = marks
            .lines
            .iter()
            .any(|(points, _)| points.windows(2).any(|w| inner.crossed_by(w[0], w[1])));
        let covered = marks.markers.iter().any(|m| inner.overlaps(m));
        if crossed || covered {
            find(
                Check::LegendOverData,
                format!(
                    "the legend lies over a data {}",
                    if crossed { "line" } else { "marker" }
                ),
            );
        }
        let share = legend.height() / marks.height;
        if share > MAX_LEGEND_SHARE {
            find(
                Check::LegendTooTall,
                format!(
                    "the legend takes {:.0} % of the figure's height",
                    100.0 * share
                ),
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plot::{Anchor, Axis, Panel, Plot, Preset, Series, series::Note, style::Look};

    fn plot_with(notes: Vec<Note>) -> Plot {
        let mut p = Panel::new(
            None,
            Axis::linear("time (s)", (0.0, 1.0)),
            Axis::linear("speed (m/s)", (0.0, 1.0)),
        );
        p.series.push(Series::line(
            Some("data"),
            vec![(0.0, 0.0), (1.0, 1.0)],
            Look::nth(0),
        ));
        p.notes = notes;
        Plot::grid(vec![p], 1, 0.6)
    }

    fn checks(plot: &Plot) -> Vec<Check> {
        review(&plot.marks(&Preset::SingleColumn.style()))
            .into_iter()
            .map(|f| f.check)
            .collect()
    }

    #[test]
    fn a_clean_panel_has_no_findings() {
        assert_eq!(checks(&plot_with(Vec::new())), []);
    }

    #[test]
    fn a_note_planted_on_the_frame_is_an_overlap() {
        let planted = Note {
            at: (0.0, 0.5),
            text: "planted across the frame".to_owned(),
            anchor: Anchor::Middle,
        };
        assert!(checks(&plot_with(vec![planted])).contains(&Check::TextOverlap));
    }

    #[test]
    fn two_notes_planted_on_one_spot_overlap_each_other() {
        let note = |text: &str| Note {
            at: (0.5, 0.3),
            text: text.to_owned(),
            anchor: Anchor::Start,
        };
        let found =
            review(&plot_with(vec![note("one"), note("two")]).marks(&Preset::DoubleColumn.style()));
        assert!(
            found
                .iter()
                .any(|f| f.check == Check::TextOverlap && f.what.contains("\"two\"")),
            "{found:?}"
        );
    }

    #[test]
    fn an_underscore_and_a_tall_legend_are_found() {
        let mut p = Panel::new(
            None,
            Axis::linear("v_inf", (0.0, 1.0)),
            Axis::linear("$v_∞$ (m/s)", (0.0, 1.0)),
        );
        for i in 0..12 {
            p.series.push(Series::line(
                Some(&format!("a long legend entry number {i}")),
                vec![(0.0, 0.1), (1.0, 0.2)],
                Look::nth(i),
            ));
        }
        let found = checks(&Plot::grid(vec![p], 1, 0.3));
        assert!(found.contains(&Check::Underscore));
        assert!(found.contains(&Check::LegendTooTall));
        assert_eq!(found.iter().filter(|c| **c == Check::Underscore).count(), 1);
    }

    #[test]
    fn a_legend_box_crossed_by_a_line_covers_data() {
        let marks = Marks {
            width: 100.0,
            height: 100.0,
            lines: vec![(vec![(0.0, 5.0), (100.0, 5.0)], 1.0)],
            legend: Some(Bounds {
                x0: 10.0,
                y0: 0.0,
                x1: 50.0,
                y1: 10.0,
            }),
            ..Marks::default()
        };
        let found: Vec<Check> = review(&marks).into_iter().map(|f| f.check).collect();
        assert_eq!(found, [Check::LegendOverData]);
    }

    #[test]
    fn small_text_is_found() {
        let mut style = Preset::SingleColumn.style();
        style.font_pt = 6.0;
        let found = review(&plot_with(Vec::new()).marks(&style));
        assert!(found.iter().any(|f| f.check == Check::TextTooSmall));
    }
}
