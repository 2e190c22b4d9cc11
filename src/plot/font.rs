//! The one font every figure is set in: DejaVu Sans, shipped in
//! `assets/fonts/` with its licence (Bitstream Vera / DejaVu, free). Layout
//! measures text with its metrics, and PDF and PNG export load only this
//! font, so no output depends on the fonts installed on the machine.

use std::sync::OnceLock;

/// The font file.
pub(crate) const FONT_DATA: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");

/// The family name written into the SVG.
pub const FAMILY: &str = "DejaVu Sans";

/// Ascender height as a fraction of the font size, for placing text by its
/// visual middle (the digits' height in DejaVu Sans is 0.73 em).
pub(crate) const DIGIT_HEIGHT: f64 = 0.73;

fn face() -> &'static ttf_parser::Face<'static> {
    static FACE: OnceLock<ttf_parser::Face<'static>> = OnceLock::new();
    FACE.get_or_init(|| {
        ttf_parser::Face::parse(FONT_DATA, 0)
            .expect("the shipped font file is a valid TrueType font")
    })
}

/// Width (pt) of `text` set at `size` pt: the sum of the glyphs' advances
/// (characters the font lacks count as a wide glyph).
pub fn text_width(text: &str, size: f64) -> f64 {
    let face = face();
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

#[cfg(test)]
mod tests {
    use super::*;

    /// DejaVu Sans digits are 0.636 em wide (its `hmtx` table): tick labels
    /// are laid out from this.
    #[test]
    fn digits_have_the_fonts_advance() {
        assert!((text_width("0000", 10.0) - 4.0 * 6.362).abs() < 0.01);
        assert!(text_width("κ", 10.0) > 0.0);
    }
}
