//! Print-ready files: the PDF of each preset is one
//! page of the preset's width (read with lopdf, an independent PDF
//! parser), its text set in the embedded DejaVu Sans and its producer the
//! program version; the PNG has the pixel size `width / 25.4 in × dpi`;
//! and states its resolution; the same figure gives the same bytes; a
//! raster of touching rectangles renders without a seam.

use lopdf::{Document, Object};
use stickslip::motor::Motor;
use stickslip::plot::{ImageFormat, PRODUCER, Preset, scaling, signals, timeline};

const PT_PER_MM: f64 = 72.0 / 25.4;

fn number(o: &Object) -> f64 {
    match o {
        Object::Integer(i) => *i as f64,
        Object::Real(r) => f64::from(*r),
        other => panic!("not a number: {other:?}"),
    }
}

/// Width and height (pt) of the only page.
fn page_size(doc: &Document) -> (f64, f64) {
    let pages = doc.get_pages();
    assert_eq!(pages.len(), 1, "one page");
    let id = *pages.values().next().unwrap();
    let page = doc.get_object(id).unwrap().as_dict().unwrap();
    let b: Vec<f64> = page
        .get(b"MediaBox")
        .unwrap()
        .as_array()
        .unwrap()
        .iter()
        .map(number)
        .collect();
    (b[2] - b[0], b[3] - b[1])
}

/// The base names of the embedded fonts (font descriptors with a font
/// file).
fn embedded_fonts(doc: &Document) -> Vec<String> {
    doc.objects
        .values()
        .filter_map(|o| o.as_dict().ok())
        .filter(|d| d.has(b"FontFile2") || d.has(b"FontFile3") || d.has(b"FontFile"))
        .map(|d| {
            String::from_utf8_lossy(d.get(b"FontName").unwrap().as_name().unwrap()).into_owned()
        })
        .collect()
}

fn producer(doc: &Document) -> String {
    let info = doc.trailer.get(b"Info").unwrap().as_reference().unwrap();
    let dict = doc.get_object(info).unwrap().as_dict().unwrap();
    match dict.get(b"Producer").unwrap() {
        Object::String(bytes, _) => String::from_utf8_lossy(bytes).into_owned(),
        other => panic!("producer {other:?}"),
    }
}

#[test]
fn pdf_pages_have_the_presets_width_and_embedded_text() {
    let f = signals::figure3(&Motor::default()).unwrap();
    for preset in Preset::ALL {
        let style = preset.style();
        let bytes = f.encode(ImageFormat::Pdf, &style, 300.0).unwrap();
        assert_eq!(
            bytes,
            f.encode(ImageFormat::Pdf, &style, 300.0).unwrap(),
            "{preset}: same bytes"
        );
        let doc = Document::load_mem(&bytes).unwrap();
        let (w, h) = page_size(&doc);
        assert!(
            (w - style.width_mm * PT_PER_MM).abs() < 0.05,
            "{preset}: page width {w} pt"
        );
        assert!(h > 0.2 * w && h < 2.0 * w, "{preset}: page height {h} pt");
        let fonts = embedded_fonts(&doc);
        assert!(!fonts.is_empty(), "{preset}: no embedded font");
        assert!(
            fonts.iter().all(|n| n.contains("DejaVuSans")),
            "{preset}: {fonts:?}"
        );
        assert_eq!(producer(&doc), PRODUCER);
    }
}

#[test]
fn png_has_the_requested_pixel_size() {
    let f = scaling::figure9(&Motor::default()).unwrap();
    for (preset, dpi) in [
        (Preset::SingleColumn, 300.0),
        (Preset::DoubleColumn, 150.0),
        (Preset::Slide, 96.0),
    ] {
        let style = preset.style();
        let bytes = f.encode(ImageFormat::Png, &style, dpi).unwrap();
        assert_eq!(&bytes[1..4], b"PNG");
        let width = u32::from_be_bytes(bytes[16..20].try_into().unwrap());
        let height = u32::from_be_bytes(bytes[20..24].try_into().unwrap());
        let expected = (style.width_mm / 25.4 * dpi).round() as u32;
        assert_eq!(width, expected, "{preset} at {dpi} dpi");
        assert!(height > width / 5, "{preset}: height {height}");
        // The pHYs chunk: pixels per metre, unit metre.
        let at = bytes
            .windows(4)
            .position(|w| w == b"pHYs")
            .expect("a pHYs chunk")
            + 4;
        let per_metre = u32::from_be_bytes(bytes[at..at + 4].try_into().unwrap());
        assert_eq!(per_metre, (dpi / 0.0254).round() as u32, "{preset}");
        assert_eq!(bytes[at + 8], 1, "unit: metre");
        let software = format!("Software\0{PRODUCER}");
        assert!(
            bytes
                .windows(software.len())
                .any(|w| w == software.as_bytes()),
            "{preset}: version"
        );
        assert_eq!(
            bytes,
            f.encode(ImageFormat::Png, &style, dpi).unwrap(),
            "{preset}: same bytes"
        );
    }
}

#[test]
fn the_format_follows_the_extension() {
    use std::path::Path;
    assert_eq!(
        ImageFormat::of(Path::new("a.svg")).unwrap(),
        ImageFormat::Svg
    );
    assert_eq!(
        ImageFormat::of(Path::new("a.PDF")).unwrap(),
        ImageFormat::Pdf
    );
    assert_eq!(
        ImageFormat::of(Path::new("dir/a.png")).unwrap(),
        ImageFormat::Png
    );
    let e = ImageFormat::of(Path::new("a.jpg")).unwrap_err().to_string();
    assert!(
        e.contains("a.jpg") && e.contains(".svg, .pdf or .png"),
        "{e}"
    );
}

/// The bounding box (user units) of the event timeline's raster: the
/// `M x0 y0 H x1 V y1 H x0 Z` rectangles of its mode bands (the legend's
/// swatches are single rectangles and left out).
fn raster_box(svg: &str) -> [f64; 4] {
    let doc = roxmltree::Document::parse(svg).unwrap();
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    for g in doc.descendants().filter(|n| {
        n.attribute("data-kind") == Some("bands")
            && n.attribute("data-label")
                .is_some_and(|l| l.starts_with("raster"))
    }) {
        for path in g.children().filter(|n| n.tag_name().name() == "path") {
            let d = path.attribute("d").unwrap();
            if d.matches('M').count() < 2 {
                continue;
            }
            for r in d.split('M').filter(|r| !r.is_empty()) {
                let v: Vec<f64> = r
                    .trim_end_matches('Z')
                    .split(['H', 'V', ' '])
                    .map(|n| n.parse().unwrap())
                    .collect();
                b = [
                    b[0].min(v[0]),
                    b[1].min(v[1]),
                    b[2].max(v[2]),
                    b[3].max(v[3]),
                ];
            }
        }
    }
    assert!(b[0] < b[2] && b[1] < b[3], "a raster");
    b
}

/// The event timeline's raster of modes (hundreds of rows, each a few
/// pixels high, every row and segment a rectangle touching the next) has
/// no pixel of the white page inside it, rendered at print resolutions in
/// every preset.
#[test]
fn raster_renders_without_a_seam() {
    let f = timeline::event_timeline(&stickslip::Scene::default()).unwrap();
    for preset in Preset::ALL {
        let style = preset.style();
        let svg = f.svg(&style);
        let view_width: f64 = svg
            .split("viewBox=\"0 0 ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .unwrap()
            .parse()
            .unwrap();
        let raster = raster_box(&svg);
        for dpi in [254.0, 300.0, 600.0] {
            let bytes = f.encode(ImageFormat::Png, &style, dpi).unwrap();
            let mut reader = png::Decoder::new(&bytes[..]).read_info().unwrap();
            let mut pixels = vec![0; reader.output_buffer_size()];
            let info = reader.next_frame(&mut pixels).unwrap();
            let channels = info.color_type.samples();
            let scale = f64::from(info.width) / view_width;
            // Two pixels inside the raster's edges (the frame's antialiasing).
            let px = |v: f64| (v * scale).round() as usize;
            let (x0, y0, x1, y1) = (
                px(raster[0]) + 2,
                px(raster[1]) + 2,
                px(raster[2]) - 2,
                px(raster[3]) - 2,
            );
            assert!(
                y1 > y0 + 100,
                "{preset} at {dpi} dpi: the raster is {} rows",
                y1 - y0
            );
            let mut white_rows = Vec::new();
            for y in y0..y1 {
                let row = &pixels[y * info.line_size..(y + 1) * info.line_size];
                let white = (x0..x1)
                    .filter(|x| row[x * channels..x * channels + 3] == [255, 255, 255])
                    .count();
                if white > 0 {
                    white_rows.push((y, white));
                }
            }
            assert!(
                white_rows.is_empty(),
                "{preset} at {dpi} dpi: white pixels in rows (row, count) {white_rows:?}"
            );
        }
    }
}
