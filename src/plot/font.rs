//! The one font family every figure is set in: DejaVu Sans and DejaVu Sans
//! Oblique (for quantities, see `text`), shipped in `assets/fonts/` with
//! their licence (Bitstream Vera / DejaVu, free). Layout measures text with
//! their metrics, and PDF and PNG export load only these faces, so no
//! output depends on the fonts installed on the machine.

use std::sync::OnceLock;

/// The upright face.
pub(crate) const FONT_DATA: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The oblique face (quantities in italic).
pub(crate) const OBLIQUE_DATA: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans-Oblique.ttf");

/// The family name written into the SVG.
pub const FAMILY: &str = "DejaVu Sans";

/// Ascender height as a fraction of the font size, for placing text by its
/// visual middle (the digits' height in DejaVu Sans is 0.73 em).
pub(crate) const DIGIT_HEIGHT: f64 = 0.73;

fn face(italic: bool) -> &'static ttf_parser::Face<'static> {
    static UPRIGHT: OnceLock<ttf_parser::Face<'static>> = OnceLock::new();
    static OBLIQUE: OnceLock<ttf_parser::Face<'static>> = OnceLock::new();
    let (cell, data) = if italic {
        (&OBLIQUE, OBLIQUE_DATA)
    } else {
        (&UPRIGHT, FONT_DATA)
    };
    cell.get_or_init(|| {
        ttf_parser::Face::parse(data, 0).expect("the shipped font files are valid TrueType fonts")
    })
}

/// Width (pt) of plain `text` set at `size` pt in the upright or oblique
/// face: the sum of the glyphs' advances (characters the font lacks count
/// as a wide glyph).
pub(crate) fn advance(text: &str, size: f64, italic: bool) -> f64 {
    let face = face(italic);
    let em = f64::from(face.units_per_em());
    let units: f64 = text
        .chars()
        .map(|c| {
            face.glyph_index(c)
                .and_then(|g| face.glyph_hor_advance(g))
                .map_or(0.7 * em, f64::from)
        })
        .sum();
    units / em * size
}

/// The ink of plain `text` at `size` pt above (negative) and below
/// (positive) the baseline, from the glyphs' bounding boxes; `None` when
/// no glyph has ink (spaces). A glyph the font lacks counts as a box from
/// the baseline to the digits' height.
pub(crate) fn ink(text: &str, size: f64, italic: bool) -> Option<(f64, f64)> {
    let face = face(italic);
    let em = f64::from(face.units_per_em());
    text.chars()
        .filter_map(|c| match face.glyph_index(c) {
            Some(g) => face
                .glyph_bounding_box(g)
                .map(|b| (-f64::from(b.y_max) / em, -f64::from(b.y_min) / em)),
            None => Some((-DIGIT_HEIGHT, 0.0)),
        })
        .map(|(t, b)| (t * size, b * size))
        .reduce(|(a, b), (t, u)| (a.min(t), b.max(u)))
}

/// Width (pt) of `text` set at `size` pt. `text` may carry the quantity
/// markup of figure labels (`$v_∞$`): each run is measured in its face
/// and at its size, a script at its smaller size.
pub fn text_width(text: &str, size: f64) -> f64 {
    super::text::runs_width(&super::text::parse(text), size)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// DejaVu Sans digits are 0.636 em wide (its `hmtx` table): tick labels
    /// are laid out from this.
    #[test]
    fn digits_have_the_fonts_advance() {
        assert!((text_width("0000", 10.0) - 4.0 * 6.362).abs() < 0.01);
        assert!(text_width("κ", 10.0) > 0.0);
        // Rich text writes edge spaces as no-break spaces: same advance.
        assert_eq!(text_width("\u{a0}", 10.0), text_width(" ", 10.0));
    }

    #[test]
    fn descenders_reach_below_the_baseline_and_capitals_above() {
        let (top, bottom) = ink("Ag", 10.0, false).unwrap();
        assert!(top < -7.0 && bottom > 1.5, "{top} {bottom}");
        assert_eq!(ink("  ", 10.0, true), None);
    }
}
