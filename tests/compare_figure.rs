//! The figure of `stickslip compare`, drawn by the plot kit: its panels
//! and data, and that neither the figure nor its data may overwrite an
//! input. Fixtures: tests/data/compare (generate.py).

use std::path::{Path, PathBuf};
mod common;

use common::in_process as cli;
use stickslip::plot::Preset;
use stickslip::{Scene, compare::CompareOptions};

const SCENE: &str = "examples/scenes/paper_default.toml";

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-cmpfig-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn the_figure_holds_every_drawn_point_in_its_data() {
    let files: Vec<PathBuf> = [500, 998, 1991, 5000]
        .iter()
        .map(|s| PathBuf::from(format!("tests/data/compare/fixed_{s}.csv")))
        .collect();
    let scene = Scene::from_path(Path::new(SCENE)).unwrap();
    let report = stickslip::compare::compare(&scene, &files, &CompareOptions::default()).unwrap();
    let figure = stickslip::plot::compare::figure(&report, None, "cmp").unwrap();
    let dir = scratch("data");
    let [svg, csv] = figure
        .write(&dir.join("cmp.svg"), &Preset::SingleColumn.style(), 300.0)
        .unwrap();
    assert!(std::fs::read_to_string(&svg).unwrap().starts_with("<svg"));
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .skip(1)
        .map(|l| l.split(',').collect())
        .collect();
    let count = |panel: &str, series: &str| {
        rows.iter()
            .filter(|r| r[0] == panel && (series.is_empty() || r[1] == series))
            .count()
    };
    // (a) the exact v_S at each of the first file's 1001 samples of
    // period 1 (T / (2 * 500) apart), at most 40 of them as markers.
    assert_eq!(count("a", "exact"), 1001);
    assert!((1..=40).contains(&count("a", "user")));
    // (b) the 1200 periods of each of the 4 files; (c) one point a file.
    assert_eq!(count("b", ""), 4 * 1200);
    assert_eq!(count("c", "fixed_500.csv"), 1);
    // Panel (c)'s points are the step-size parts of the report.
    for f in &report.files {
        let name = Path::new(&f.file).file_name().unwrap().to_str().unwrap();
        let row = rows.iter().find(|r| r[0] == "c" && r[1] == name).unwrap();
        let e: f64 = row[3].parse().unwrap();
        let split = f.v_inf_split.unwrap();
        approx::assert_relative_eq!(e, split.step_size_relative.abs(), max_relative = 1e-15);
    }
}

#[test]
fn a_figure_whose_data_would_overwrite_an_input_is_refused() {
    // The input lies where the figure's data would be written.
    let dir = scratch("refuse");
    let figure = dir.join("run.svg");
    let data = stickslip::plot::data_path(&figure);
    let original = std::fs::read("tests/data/compare/fixed_500.csv").unwrap();
    std::fs::write(&data, &original).unwrap();
    let (code, out, err) = cli(&[
        "compare",
        SCENE,
        data.to_str().unwrap(),
        "--figure",
        figure.to_str().unwrap(),
    ]);
    assert_eq!((code, out.as_str()), (3, ""), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert_eq!(std::fs::read(&data).unwrap(), original, "the input is kept");
    assert!(!figure.exists(), "nothing is written");
    // An extension that is no figure format is refused before running.
    let (code, _, err) = cli(&[
        "compare",
        SCENE,
        "tests/data/compare/fixed_500.csv",
        "--figure",
        dir.join("cmp.jpg").to_str().unwrap(),
    ]);
    assert_eq!(code, 3);
    assert!(
        err.contains("--figure") && err.contains(".svg, .pdf or .png"),
        "{err}"
    );
}

#[test]
fn files_are_told_apart_by_their_step_in_the_legend_and_named_in_the_caption() {
    let scene = Scene::from_path(Path::new(SCENE)).unwrap();
    let run = |names: &[&str]| {
        let files: Vec<PathBuf> = names
            .iter()
            .map(|n| PathBuf::from(format!("tests/data/compare/{n}")))
            .collect();
        let report =
            stickslip::compare::compare(&scene, &files, &CompareOptions::default()).unwrap();
        let figure = stickslip::plot::compare::figure(&report, None, "cmp").unwrap();
        let legend: Vec<String> = figure
            .plot
            .legend
            .iter()
            .map(|e| stickslip::plot::visible(&e.label))
            .collect();
        (report, figure, legend)
    };
    let (report, figure, legend) = run(&["fixed_500.csv", "fixed_5000.csv"]);
    // The fixtures' grid: S steps per harmonic period, n = 2, h = T / (2 S).
    for s in [500.0, 5000.0] {
        let h = report.signal.period / (2.0 * s);
        let shown = legend
            .iter()
            .filter_map(|l| l.strip_prefix("h = ")?.strip_suffix(" ns"))
            .filter_map(|v| v.parse::<f64>().ok())
            .any(|v| (v * 1e-9 / h - 1.0).abs() < 5e-3);
        assert!(shown, "h = {h:e} s in {legend:?}");
    }
    assert!(legend.iter().all(|l| !l.contains(".csv")), "{legend:?}");
    let caption = figure.plot.notes.join(" ");
    assert!(
        caption.contains("fixed_500.csv") && caption.contains("fixed_5000.csv"),
        "{caption}"
    );
    // Two files of one step are told apart by their place.
    let (_, _, legend) = run(&["fixed_500.csv", "fixed_500.csv"]);
    assert!(
        legend.iter().any(|l| l == "file 1") && legend.iter().any(|l| l == "file 2"),
        "{legend:?}"
    );
}
