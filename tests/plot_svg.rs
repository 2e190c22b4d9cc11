//! Read from the SVG text of every figure family in
//! every preset: the smallest text at the printed size is at least 7 pt;
//! nothing is drawn in the background colour (white) or invisibly; no two
//! labelled series share both colour-free attributes (dash pattern and
//! marker), and bands (which have neither) differ in lightness, so every
//! figure reads in greyscale; the program version is in the metadata.

#[path = "common/grid.rs"]
mod grid;

use grid::grid;
use stickslip::SignalSpec;
use stickslip::motor::Motor;
use stickslip::plot::motion::{self, Row, Span};
use stickslip::plot::performance::figures6_7;
use stickslip::plot::sweep::{SweepSpec, sweep_figure};
use stickslip::plot::{Figure, PRODUCER, Preset, scaling, signals, timeline};

const PT_PER_MM: f64 = 72.0 / 25.4;

/// A sweep output with a failed case and a run-away one (a `regime`
/// column), as another tool might write it.
pub const SWEEP_CSV: &str = "# stickslip_version = 0.1.0, base_scene_hash = 0\n\
case,level,harmonics,sigma,v_inf,regime,failure\n\
0,3,2,false,0.03,slip-slip,\n\
1,3,3,false,0.02,slip-slip,\n\
2,3,4,false,,run-away,\n\
3,6,2,false,0.07,stick-slip,\n\
4,6,3,false,,,time limit reached\n\
5,6,4,false,0.05,slip-slip,\n";

/// Every figure family.
fn figures() -> Vec<Figure> {
    let motor = Motor::default();
    let scene = stickslip::Scene::default();
    let mut fig8 = scene.clone();
    fig8.signal = SignalSpec::fourier(25e-6, 1.0, 2, false);
    let mut stick = scene.clone();
    stick.signal = SignalSpec::fourier(25e-6, 0.36, 5, true);
    let [six, seven] = figures6_7(&grid()).unwrap();
    let dir = std::env::temp_dir().join(format!("stickslip-plot-svg-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("sweep.csv");
    std::fs::write(&csv, SWEEP_CSV).unwrap();
    let spec = SweepSpec {
        x: "harmonics".into(),
        y: vec!["v_inf".into()],
        series: Some("level".into()),
        ref_y: vec![0.06],
        ..SweepSpec::default()
    };
    let sweep = sweep_figure(&csv, &spec, "sweep").unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    vec![
        signals::figure2(&motor).unwrap(),
        signals::figure3(&motor).unwrap(),
        signals::figure4(&motor).unwrap(),
        signals::figure5(&motor).unwrap(),
        six,
        seven,
        motion::figure8(&fig8).unwrap(),
        scaling::figure9(&motor).unwrap(),
        scaling::stroke_scaling(&scene).unwrap(),
        timeline::event_timeline(&scene).unwrap(),
        motion::motion(
            &stick,
            &[Span::Periods(1, 1), Span::Periods(2, 3), Span::Steady],
            &[Row::Velocity, Row::Displacement, Row::Acceleration],
            "motion",
        )
        .unwrap(),
        motion::startup(&stick, "startup").unwrap(),
        timeline::scene_timeline(&stick, "timeline").unwrap(),
        sweep,
        stickslip::plot::characteristic::scene_characteristic(&stick, "characteristic").unwrap(),
        stickslip::plot::driven::figure(
            &stickslip::plot::driven::runs(&scene).unwrap(),
            Preset::DoubleColumn,
        )
        .unwrap(),
    ]
}

fn mm(attr: &str) -> f64 {
    attr.strip_suffix("mm")
        .expect("size in mm")
        .parse()
        .unwrap()
}

/// Relative luminance of `#rrggbb` (sRGB weights, linear enough for a
/// greyscale check).
fn lightness(color: &str) -> f64 {
    let c = |i: usize| f64::from(u8::from_str_radix(&color[i..i + 2], 16).unwrap()) / 255.0;
    0.2126 * c(1) + 0.7152 * c(3) + 0.0722 * c(5)
}

/// A horizontal text lies on the page: its extent from the shipped font's
/// metrics, by its anchor, inside `[0, width]` (user units).
fn on_the_page(node: &roxmltree::Node<'_, '_>, width: f64, what: &str) {
    if node.attribute("transform").is_some() {
        return;
    }
    let x: f64 = node.attribute("x").unwrap().parse().unwrap();
    let size: f64 = node.attribute("font-size").unwrap().parse().unwrap();
    let text = node.text().unwrap_or("");
    let w = stickslip::plot::text_width(text, size);
    let (left, right) = match node.attribute("text-anchor").unwrap_or("start") {
        "middle" => (x - w / 2.0, x + w / 2.0),
        "end" => (x - w, x),
        _ => (x, x + w),
    };
    assert!(
        left >= -0.5 && right <= width + 0.5,
        "{what}: \"{text}\" runs off the page ({left:.1} .. {right:.1} of {width:.1})"
    );
}

/// A series' kind, dash pattern, marker and colour, as the SVG states
/// them.
type Look = (String, String, String, String);

/// Checks one SVG; `what` names it in failures.
fn check(svg: &str, what: &str) {
    let doc = roxmltree::Document::parse(svg).unwrap_or_else(|e| panic!("{what}: {e}"));
    let root = doc.root_element();
    let width_mm = mm(root.attribute("width").unwrap());
    let view: Vec<f64> = root
        .attribute("viewBox")
        .unwrap()
        .split(' ')
        .map(|v| v.parse().unwrap())
        .collect();
    // Points per user unit at the printed size.
    let scale = width_mm * PT_PER_MM / view[2];
    let mut texts = 0;
    let mut smallest = f64::INFINITY;
    let mut looks: std::collections::BTreeMap<String, Look> = Default::default();
    for node in doc.descendants().filter(|n| n.is_element()) {
        if let Some(size) = node.attribute("font-size") {
            smallest = smallest.min(size.parse::<f64>().unwrap() * scale);
        }
        if node.tag_name().name() == "text" {
            texts += 1;
            on_the_page(&node, view[2], what);
            assert!(
                node.ancestors().any(|a| a.attribute("font-size").is_some()),
                "{what}: text without a size"
            );
        }
        for attr in ["fill", "stroke"] {
            let v = node.attribute(attr).unwrap_or("none").to_ascii_lowercase();
            assert!(
                !matches!(
                    v.as_str(),
                    "#ffffff" | "#fff" | "white" | "rgb(255,255,255)"
                ),
                "{what}: a <{}> drawn in the background colour",
                node.tag_name().name()
            );
        }
        for attr in ["opacity", "stroke-opacity", "fill-opacity", "stroke-width"] {
            if let Some(v) = node.attribute(attr) {
                assert!(v.parse::<f64>().unwrap() > 0.0, "{what}: {attr}={v}");
            }
        }
        assert_ne!(node.attribute("visibility"), Some("hidden"), "{what}");
        if node.attribute("class") == Some("series") {
            let label = node.attribute("data-label").unwrap().to_owned();
            if label.is_empty() {
                continue;
            }
            let look = (
                node.attribute("data-kind").unwrap().to_owned(),
                node.attribute("data-dash").unwrap().to_owned(),
                node.attribute("data-marker").unwrap().to_owned(),
                node.attribute("data-color").unwrap().to_owned(),
            );
            if let Some(previous) = looks.insert(label.clone(), look.clone()) {
                assert_eq!(previous, look, "{what}: series {label} drawn two ways");
            }
        }
    }
    assert!(texts > 0, "{what}: no text");
    // The viewBox is written to 0.01 pt, so the printed scale is exact to
    // about 3e-5 (a script set at exactly 7 pt may print at 6.9999 pt).
    assert!(
        smallest >= 7.0 * (1.0 - 1e-4),
        "{what}: text of {smallest:.2} pt"
    );
    let all: Vec<(&String, &Look)> = looks.iter().collect();
    for (i, (la, a)) in all.iter().enumerate() {
        for (lb, b) in &all[i + 1..] {
            if a.0 == "bands" && b.0 == "bands" {
                let (x, y) = (lightness(&a.3), lightness(&b.3));
                assert!(
                    (x - y).abs() >= 0.15,
                    "{what}: bands {la} and {lb} differ by colour alone"
                );
            } else if a.0 != "bands" && b.0 != "bands" {
                assert!(
                    (&a.1, &a.2) != (&b.1, &b.2),
                    "{what}: series {la} and {lb} share dash {} and marker {}",
                    a.1,
                    a.2
                );
            }
        }
    }
    let meta = doc
        .descendants()
        .find(|n| n.tag_name().name() == "metadata")
        .and_then(|n| n.text())
        .unwrap_or("");
    assert!(
        meta.contains(PRODUCER),
        "{what}: no version in the metadata"
    );
}

#[test]
fn every_figure_in_every_preset_reads_in_print_and_greyscale() {
    let figures = figures();
    for f in &figures {
        for preset in Preset::ALL {
            let style = preset.style();
            let svg = f.svg(&style);
            check(&svg, &format!("{} ({preset})", f.name));
            let root = roxmltree::Document::parse(&svg).unwrap();
            let width = mm(root.root_element().attribute("width").unwrap());
            assert_eq!(
                width, style.width_mm,
                "{} is printed at the preset's width",
                f.name
            );
        }
    }
}

/// No title unless asked for: the preset's figure has no text of the
/// title, the titled one does, once.
#[test]
fn a_title_only_when_asked_for() {
    let f = signals::figure3(&Motor::default()).unwrap();
    let mut style = Preset::SingleColumn.style();
    assert!(!f.svg(&style).contains("Figure 3"));
    style.title = Some("Figure 3: amplitudes".into());
    assert_eq!(f.svg(&style).matches("Figure 3: amplitudes").count(), 1);
}

/// Explicit sizes: `--width`, `--height` and `--font-size` reach the SVG.
#[test]
fn explicit_sizes_are_the_printed_sizes() {
    let f = signals::figure5(&Motor::default()).unwrap();
    let mut style = Preset::DoubleColumn.style();
    style.width_mm = 120.0;
    style.height_mm = Some(70.0);
    style.font_pt = 9.0;
    let svg = f.svg(&style);
    let doc = roxmltree::Document::parse(&svg).unwrap();
    let root = doc.root_element();
    assert_eq!(mm(root.attribute("width").unwrap()), 120.0);
    assert_eq!(mm(root.attribute("height").unwrap()), 70.0);
    let largest = doc
        .descendants()
        .filter_map(|n| n.attribute("font-size"))
        .map(|s| s.parse::<f64>().unwrap())
        .fold(0.0, f64::max);
    assert_eq!(largest, 9.0);
    check(&svg, "figure 5 at 120 x 70 mm, 9 pt");
}

/// The rectangles `(x0, y0, x1, y1)` of a filled path written as
/// `M x0 y0 H x1 V y1 H x0 Z` subpaths.
fn rects(d: &str) -> Vec<[f64; 4]> {
    d.split('M')
        .filter(|s| !s.is_empty())
        .map(|s| {
            let v: Vec<f64> = s
                .trim_end_matches('Z')
                .split(['H', 'V', ' '])
                .map(|n| n.parse().unwrap())
                .collect();
            assert_eq!(v.len(), 5, "a rectangle: {s}");
            [v[0], v[1], v[2], v[3]]
        })
        .collect()
}

/// The raster of modes (one row per period) covers its panel without a
/// gap: rows written one below the other share their edges exactly (the
/// same number in the SVG), and so do the segments within a row, so no
/// renderer leaves a line of background between them at any resolution.
#[test]
fn raster_rows_and_segments_share_their_edges_exactly() {
    let scene = stickslip::Scene::default();
    let f = timeline::event_timeline(&scene).unwrap();
    for preset in Preset::ALL {
        let svg = f.svg(&preset.style());
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let mut all: Vec<[f64; 4]> = Vec::new();
        for g in doc.descendants().filter(|n| {
            n.attribute("data-kind") == Some("bands")
                && n.attribute("data-label")
                    .is_some_and(|l| l.starts_with("raster"))
        }) {
            // The legend's swatch of a mode is a single rectangle.
            for path in g.children().filter(|n| n.tag_name().name() == "path") {
                let found = rects(path.attribute("d").unwrap());
                if found.len() > 1 {
                    all.extend(found);
                }
            }
        }
        assert!(all.len() > 400, "{preset}: {} rectangles", all.len());
        let left = all.iter().map(|r| r[0]).fold(f64::INFINITY, f64::min);
        let right = all.iter().map(|r| r[2]).fold(f64::NEG_INFINITY, f64::max);
        let mut rows: std::collections::BTreeMap<(u64, u64), Vec<[f64; 2]>> = Default::default();
        for r in &all {
            rows.entry((r[1].to_bits(), r[3].to_bits()))
                .or_default()
                .push([r[0], r[2]]);
        }
        let mut bottom_of_previous: Option<f64> = None;
        for ((top, bottom), mut spans) in rows {
            let (top, bottom) = (f64::from_bits(top), f64::from_bits(bottom));
            if let Some(b) = bottom_of_previous {
                assert_eq!(top, b, "{preset}: a gap or overlap between rows at {b}");
            }
            bottom_of_previous = Some(bottom);
            spans.sort_by(|a, b| a[0].total_cmp(&b[0]));
            assert_eq!(spans[0][0], left, "{preset}: row at {top} starts late");
            assert_eq!(spans[spans.len() - 1][1], right, "{preset}: row at {top}");
            for w in spans.windows(2) {
                assert_eq!(w[0][1], w[1][0], "{preset}: gap in the row at {top}");
            }
        }
    }
}
