//! Print-ready files: SVG as drawn, PDF through svg2pdf and PNG through
//! resvg, the format chosen by the output's extension.
//!
//! Contract: PDF and PNG are rendered with only the shipped fonts
//! (`src/plot/font.rs`, DejaVu Sans and its oblique face) loaded, so their bytes do not depend on the machine's
//! fonts; the PDF embeds a subset of it (its text stays text) on a page of
//! the figure's printed size, with the program version in its information
//! dictionary; the PNG is `width_mm / 25.4 × dpi` pixels wide, on white,
//! with its resolution stated (`pHYs`) so that it prints at that size, and
//! the program version as its `Software` text.
//! The same SVG gives the same bytes (for PDF, the fonts' objects in a
//! fixed order: upright face first).

use super::PlotError;
use super::font::{FAMILY, FONT_DATA, OBLIQUE_DATA};
use pdf_writer::{Content, Finish, Name, Pdf, Rect, Ref, TextStr};
use resvg::{tiny_skia, usvg};
use std::collections::HashMap;
use std::path::Path;

/// An output format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// SVG text.
    Svg,
    /// A one-page PDF.
    Pdf,
    /// A PNG image.
    Png,
}

impl ImageFormat {
    /// The format named by `path`'s extension (`svg`, `pdf`, `png`, any
    /// case).
    pub fn of(path: &Path) -> Result<ImageFormat, PlotError> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        match ext.as_deref() {
            Some("svg") => Ok(ImageFormat::Svg),
            Some("pdf") => Ok(ImageFormat::Pdf),
            Some("png") => Ok(ImageFormat::Png),
            _ => Err(PlotError::Argument(format!(
                "-o {}: the extension must be .svg, .pdf or .png",
                path.display()
            ))),
        }
    }
}

/// The lowest and highest `--dpi` accepted.
pub(crate) const DPI_RANGE: (f64, f64) = (10.0, 2400.0);

fn tree(svg: &str) -> Result<usvg::Tree, PlotError> {
    let mut options = usvg::Options {
        font_family: FAMILY.to_owned(),
        ..usvg::Options::default()
    };
    let db = options.fontdb_mut();
    db.load_font_data(FONT_DATA.to_vec());
    db.load_font_data(OBLIQUE_DATA.to_vec());
    db.set_sans_serif_family(FAMILY);
    usvg::Tree::from_str(svg, &options)
        .map_err(|e| PlotError::Export(format!("reading the SVG: {e}")))
}

/// The figure as PDF: one page of the SVG's printed size, text embedded,
/// `producer` and `title` in the information dictionary.
pub(crate) fn pdf(svg: &str, producer: &str, title: &str) -> Result<Vec<u8>, PlotError> {
    let tree = tree(svg)?;
    // svg2pdf writes the fonts a figure uses, and lists them in its
    // resources, in the order of hash maps, which differs from run to run;
    // with both shipped faces in one figure the bytes would too. Of the
    // four orders, the one with the upright face first and the resources
    // sorted by name is kept: each conversion has one chance in four of it
    // (not finding it in 128 tries has odds of 1e-16).
    let mut tries = 0;
    let (chunk, svg_ref) = loop {
        let (chunk, svg_ref) = svg2pdf::to_chunk(&tree, svg2pdf::ConversionOptions::default())
            .map_err(|e| PlotError::Export(format!("converting to PDF: {e}")))?;
        tries += 1;
        let bytes = chunk.as_bytes();
        if (upright_font_first(bytes) && fonts_listed_in_order(bytes)) || tries == 128 {
            break (chunk, svg_ref);
        }
    };
    let mut alloc = Ref::new(1);
    let catalog = alloc.bump();
    let pages = alloc.bump();
    let page = alloc.bump();
    let content_ref = alloc.bump();
    let info = alloc.bump();
    let mut map = HashMap::new();
    let chunk = chunk.renumber(|old| *map.entry(old).or_insert_with(|| alloc.bump()));
    let svg_ref = map[&svg_ref];
    // usvg sizes the tree in CSS pixels (96 per inch); the page is in
    // points (72 per inch).
    let to_pt = 72.0 / 96.0;
    let (w, h) = (tree.size().width() * to_pt, tree.size().height() * to_pt);
    let mut pdf = Pdf::new();
    pdf.catalog(catalog).pages(pages);
    pdf.pages(pages).kids([page]).count(1);
    let name = Name(b"S1");
    let mut p = pdf.page(page);
    p.media_box(Rect::new(0.0, 0.0, w, h));
    p.parent(pages);
    p.contents(content_ref);
    p.resources().x_objects().pair(name, svg_ref);
    p.finish();
    let mut content = Content::new();
    content.transform([w, 0.0, 0.0, h, 0.0, 0.0]).x_object(name);
    pdf.stream(content_ref, &content.finish());
    pdf.extend(&chunk);
    pdf.document_info(info)
        .producer(TextStr(producer))
        .creator(TextStr(producer))
        .title(TextStr(title));
    Ok(pdf.finish())
}

/// True unless the oblique face's font objects come before the upright
/// face's (or only one face is used).
fn upright_font_first(pdf: &[u8]) -> bool {
    let find = |needle: &[u8], from: usize| {
        pdf[from..]
            .windows(needle.len())
            .position(|w| w == needle)
            .map(|i| i + from)
    };
    let Some(oblique) = find(b"DejaVuSans-Oblique", 0) else {
        return true;
    };
    // The first mention of the upright face: "DejaVuSans" not followed by
    // "-Oblique".
    let mut at = 0;
    while let Some(i) = find(b"DejaVuSans", at) {
        if !pdf[i..].starts_with(b"DejaVuSans-Oblique") {
            return i < oblique;
        }
        at = i + 1;
    }
    true
}

/// True if every `/Font << ... >>` resource dictionary lists its fonts in
/// ascending name order.
fn fonts_listed_in_order(pdf: &[u8]) -> bool {
    let text = String::from_utf8_lossy(pdf);
    text.split("/Font <<").skip(1).all(|rest| {
        let dict = rest.split(">>").next().unwrap_or("");
        let names: Vec<&str> = dict
            .split_whitespace()
            .filter(|w| w.starts_with('/'))
            .collect();
        names.windows(2).all(|w| w[0] <= w[1])
    })
}

/// The figure as PNG at `dpi` pixels per inch, on white, `producer` in
/// its `Software` text.
pub(crate) fn png(svg: &str, dpi: f64, producer: &str) -> Result<Vec<u8>, PlotError> {
    let tree = tree(svg)?;
    let scale = dpi / 96.0;
    let size = tree.size();
    let w = (f64::from(size.width()) * scale).round() as u32;
    let h = (f64::from(size.height()) * scale).round() as u32;
    let mut pixmap = tiny_skia::Pixmap::new(w, h).ok_or_else(|| {
        PlotError::Export(format!("a {w} x {h} pixel image is too large or empty"))
    })?;
    pixmap.fill(tiny_skia::Color::WHITE);
    let (sx, sy) = (w as f32 / size.width(), h as f32 / size.height());
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(sx, sy),
        &mut pixmap.as_mut(),
    );
    // On an opaque white page the premultiplied pixels are the plain ones.
    let mut bytes = Vec::new();
    let encoding = |e: png::EncodingError| PlotError::Export(format!("encoding the PNG: {e}"));
    {
        let mut encoder = png::Encoder::new(&mut bytes, w, h);
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        // The resolution, so that the image prints at the figure's size.
        let per_metre = (dpi / 0.0254).round() as u32;
        encoder.set_pixel_dims(Some(png::PixelDimensions {
            xppu: per_metre,
            yppu: per_metre,
            unit: png::Unit::Meter,
        }));
        encoder
            .add_text_chunk("Software".to_owned(), producer.to_owned())
            .map_err(encoding)?;
        let mut writer = encoder.write_header().map_err(encoding)?;
        writer.write_image_data(pixmap.data()).map_err(encoding)?;
    }
    Ok(bytes)
}
