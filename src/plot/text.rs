//! Rich text in figures: quantities in italic with real subscripts and
//! superscripts, from a small markup that every label may use.
//!
//! Markup: text between two `$` is a quantity. Inside it, letters are set
//! in italic (the shipped DejaVu Sans Oblique), other characters upright;
//! `_x` or `_{…}` is a subscript and `^x` or `^{…}` a superscript, both
//! upright (descriptive indices: `$F_c$`, `$p_{0.99}$`, `$f_{max}$`).
//! Outside `$…$` every character stands for itself, so a label without
//! `$` is plain text. `$v_∞$ (m/s)` reads "v∞ (m/s)" with an italic v and
//! a lowered ∞.
//!
//! Contract: a script is set at [`script_size`] of its text's size, never
//! below the smallest print size ([`MIN_FONT_PT`]) nor above the text's
//! own size, and shifted by a fixed fraction of the text's size; widths
//! ([`runs_width`]) and ink extents ([`runs_extent`]) are measured from
//! the shipped fonts' metrics at the size and face each run is set in.
//! In the SVG, spaces at the edges of a run are written between the
//! `<tspan>`s at the text's size, where renderers keep them.

use super::canvas::escape;
use super::font;
use super::style::MIN_FONT_PT;
use std::fmt::Write as _;

/// Where a run sits relative to the baseline.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Shift {
    /// On the baseline.
    Base,
    /// Lowered (subscript).
    Sub,
    /// Raised (superscript).
    Super,
}

impl Shift {
    /// Baseline offset (pt, downward positive) at text size `size`.
    fn offset(self, size: f64) -> f64 {
        match self {
            Shift::Base => 0.0,
            Shift::Sub => 0.22 * size,
            Shift::Super => -0.38 * size,
        }
    }
}

/// A piece of text set in one face, size and baseline.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Run {
    /// The characters shown.
    pub text: String,
    /// Set in the oblique face.
    pub italic: bool,
    /// Baseline position.
    pub shift: Shift,
}

/// The size (pt) of a script in text of `size` pt.
pub(crate) fn script_size(size: f64) -> f64 {
    (0.7 * size).max(MIN_FONT_PT).min(size)
}

/// The runs of `markup`.
pub(crate) fn parse(markup: &str) -> Vec<Run> {
    let mut runs: Vec<Run> = Vec::new();
    let push = |runs: &mut Vec<Run>, c: char, italic: bool, shift: Shift| match runs.last_mut() {
        Some(r) if r.italic == italic && r.shift == shift => r.text.push(c),
        _ => runs.push(Run {
            text: c.to_string(),
            italic,
            shift,
        }),
    };
    let mut math = false;
    let mut chars = markup.chars().peekable();
    while let Some(c) = chars.next() {
        if c == '$' {
            math = !math;
            continue;
        }
        if math && (c == '_' || c == '^') {
            let shift = if c == '_' { Shift::Sub } else { Shift::Super };
            if chars.peek() == Some(&'{') {
                chars.next();
                for s in chars.by_ref() {
                    if s == '}' {
                        break;
                    }
                    push(&mut runs, s, false, shift);
                }
            } else if let Some(s) = chars.next() {
                push(&mut runs, s, false, shift);
            }
            continue;
        }
        // A combining mark (the hat of x̂) takes its letter's face.
        let combining = ('\u{300}'..='\u{36f}').contains(&c);
        let italic = match runs.last() {
            Some(r) if combining => r.italic,
            _ => math && c.is_alphabetic(),
        };
        push(&mut runs, c, italic, Shift::Base);
    }
    runs
}

/// The characters `markup` shows (what a reader sees, markup removed).
pub fn visible(markup: &str) -> String {
    parse(markup).into_iter().map(|r| r.text).collect()
}

/// The size (pt) a run of text at `size` is set at.
pub(crate) fn run_size(run: &Run, size: f64) -> f64 {
    if run.shift == Shift::Base {
        size
    } else {
        script_size(size)
    }
}

/// Width (pt) of the runs at text size `size`.
pub(crate) fn runs_width(runs: &[Run], size: f64) -> f64 {
    runs.iter()
        .map(|r| font::advance(&r.text, run_size(r, size), r.italic))
        .sum()
}

/// Ink extent of the runs above (negative) and below (positive) the
/// baseline, in pt: `(top, bottom)`.
pub(crate) fn runs_extent(runs: &[Run], size: f64) -> (f64, f64) {
    runs.iter()
        .filter_map(|r| {
            let s = run_size(r, size);
            let (top, bottom) = font::ink(&r.text, s, r.italic)?;
            let dy = r.shift.offset(size);
            Some((top + dy, bottom + dy))
        })
        .fold((0.0, 0.0), |(a, b), (t, u)| {
            (f64::min(a, t), f64::max(b, u))
        })
}

/// `n` spaces that XML keeps: one plain space, then no-break spaces (the
/// same advance in the shipped font).
fn spaces(n: usize) -> String {
    match n {
        0 => String::new(),
        n => format!(" {}", "\u{a0}".repeat(n - 1)),
    }
}

/// The SVG content of a `<text>` element of size `size` showing `markup`:
/// plain escaped text when it has no markup, otherwise `<tspan>`s with the
/// italic face, the script size and `dy` shifts back to the baseline.
pub(crate) fn svg_content(markup: &str, size: f64) -> String {
    let runs = parse(markup);
    if runs.iter().all(|r| !r.italic && r.shift == Shift::Base) {
        return escape(&visible(markup));
    }
    let num = super::canvas::num;
    let mut out = String::new();
    let mut offset = 0.0;
    for r in &runs {
        let target = r.shift.offset(size);
        let dy = target - offset;
        let plain = !r.italic && r.shift == Shift::Base && dy.abs() < 1e-9;
        if plain {
            out.push_str(&escape(&r.text));
            continue;
        }
        // Spaces at a run's edges are written between the `<tspan>`s, at
        // the text's own size (as they are measured): some renderers drop
        // a space at the edge of a shifted `<tspan>`.
        let core = r.text.trim_matches(' ');
        let lead = r.text.len() - r.text.trim_start_matches(' ').len();
        let trail = if core.is_empty() {
            0
        } else {
            r.text.len() - r.text.trim_end_matches(' ').len()
        };
        out.push_str(&spaces(lead));
        if !core.is_empty() {
            offset = target;
            out.push_str("<tspan");
            if r.italic {
                out.push_str(r#" font-style="italic""#);
            }
            if r.shift != Shift::Base {
                let _ = write!(out, r#" font-size="{}""#, num(run_size(r, size)));
            }
            if dy.abs() >= 1e-9 {
                let _ = write!(out, r#" dy="{}""#, num(dy));
            }
            let _ = write!(out, ">{}</tspan>", escape(core));
        }
        out.push_str(&spaces(trail));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantities_are_italic_with_upright_scripts() {
        let runs = parse("$v_∞$ (m/s)");
        assert_eq!(runs.len(), 3);
        assert!(runs[0].italic && runs[0].text == "v");
        assert!(runs[1].shift == Shift::Sub && runs[1].text == "∞" && !runs[1].italic);
        assert_eq!(runs[2].text, " (m/s)");
        assert_eq!(visible("$p_{0.99}$"), "p0.99");
        assert_eq!(visible("raw_name"), "raw_name");
        let hat = parse("$x̂_R$");
        assert!(hat[0].italic && hat[0].text == "x\u{302}", "{hat:?}");
    }

    #[test]
    fn a_subscript_is_narrower_than_the_same_text_on_the_line() {
        let sub = runs_width(&parse("$x_{max}$"), 16.0);
        let flat = runs_width(&parse("xmax"), 16.0);
        assert!(sub < flat, "{sub} >= {flat}");
    }

    #[test]
    fn scripts_are_never_below_the_smallest_print_size() {
        assert_eq!(script_size(8.0), MIN_FONT_PT);
        assert!((script_size(16.0) - 11.2).abs() < 1e-9);
        assert_eq!(script_size(6.0), 6.0);
    }

    #[test]
    fn svg_text_returns_to_the_baseline_after_a_script() {
        let s = svg_content("$F_c$ (N)", 8.0);
        assert!(s.contains(r#"<tspan font-style="italic">F</tspan>"#), "{s}");
        assert!(s.contains(r#"dy="1.76">c</tspan>"#), "{s}");
        assert!(
            s.contains(r#"c</tspan> <tspan dy="-1.76">(N)</tspan>"#),
            "{s}"
        );
    }
}
