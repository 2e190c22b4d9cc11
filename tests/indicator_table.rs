//! Every indicator of [`Indicator::ALL`] reaches every output with one
//! value and one unit: the JSON of `run --json` (value and
//! `error_estimate`), the text summary, the `check` table, a sweep row and
//! the axis label of a sweep figure. The expected values are
//! [`RunReport::value`] and [`RunReport::error`] of the same scene, so an
//! output that re-maps an indicator on its own is caught.
//!
//! The scene is `examples/scenes/harmonics.toml`: a harmonic series with an
//! actuator, so that every indicator (`velocity_per_power` included) is
//! available.

mod common;

use common::{ok, s, scratch, stickslip, write};
use std::fs;
use std::path::{Path, PathBuf};
use stickslip::{
    Indicator, Outcome, RunReport, Scene, check::check, report::to_json, report::to_text,
};

fn scene_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/harmonics.toml")
}

fn scene() -> Scene {
    Scene::from_path(&scene_path()).expect("the example scene reads")
}

fn report(scene: &Scene) -> (Outcome, RunReport) {
    let outcome =
        stickslip::run(scene, &stickslip::RunOptions::default()).expect("the example scene runs");
    let report = outcome.report().expect("a steady state").clone();
    (outcome, report)
}

#[test]
fn the_scene_asks_for_every_indicator() {
    let scene = scene();
    assert_eq!(scene.outputs.indicators, Indicator::ALL.to_vec());
}

#[test]
fn json_carries_every_value_and_estimate() {
    let scene = scene();
    let (outcome, r) = report(&scene);
    let json = to_json(&outcome, &scene);
    for i in Indicator::ALL {
        let value = r.value(i).unwrap_or_else(|| panic!("{i} has a value here"));
        assert_eq!(json[i.name()].as_f64(), Some(value), "JSON {i}");
        assert_eq!(
            json["error_estimate"][i.name()].as_f64(),
            r.error(i),
            "JSON error_estimate.{i}"
        );
    }
}

#[test]
fn the_text_summary_has_a_line_per_indicator_with_its_unit() {
    let scene = scene();
    let (outcome, _) = report(&scene);
    let text = to_text(&outcome);
    for i in Indicator::ALL {
        let line = text
            .lines()
            .find(|l| l.trim_start().starts_with(&format!("{} ", i.name())))
            .unwrap_or_else(|| panic!("no text line for {i}:\n{text}"));
        let unit = i.printed_unit();
        if unit != "1" {
            assert!(line.contains(unit), "the {i} line shows {unit}: {line}");
        }
    }
}

#[test]
fn check_has_a_row_per_indicator_with_the_run_value() {
    let scene = scene();
    let (_, r) = report(&scene);
    let table = check(&scene, &[20, 40]).expect("check runs");
    for i in Indicator::ALL {
        let row = table
            .rows
            .iter()
            .find(|row| row.name == i.name())
            .unwrap_or_else(|| panic!("no check row for {i}"));
        assert_eq!(row.unit, i.printed_unit(), "check unit of {i}");
        assert_eq!(Some(row.event), r.value(i), "check value of {i}");
        assert_eq!(row.event_error, r.error(i), "check estimate of {i}");
    }
}

#[test]
fn a_sweep_row_and_a_sweep_figure_show_every_indicator() {
    let scene = scene();
    let (_, r) = report(&scene);
    let dir = scratch("indicator_table", "sweep");
    let sweep = write(
        &dir,
        "one.toml",
        &format!(
            "base = {:?}\n[axes]\ncontact_force = [1.0]\n[outputs]\nformat = \"csv\"\n",
            scene_path().display().to_string()
        ),
    );
    let csv = dir.join("one.csv");
    ok(stickslip(&[
        "sweep",
        s(&sweep),
        "--no-timing",
        "-q",
        "-o",
        s(&csv),
    ]));
    let text = fs::read_to_string(&csv).expect("the sweep wrote its rows");
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().expect("header").split(',').collect();
    let row: Vec<&str> = lines.next().expect("one row").split(',').collect();
    for i in Indicator::ALL {
        let column = header
            .iter()
            .position(|h| *h == i.name())
            .unwrap_or_else(|| panic!("no sweep column {i}"));
        let cell: f64 = row[column].parse().expect("a number");
        assert_eq!(Some(cell), r.value(i), "sweep cell of {i}");

        let svg = dir.join(format!("{}.svg", i.name()));
        ok(stickslip(&[
            "plot",
            s(&csv),
            "--x",
            "contact_force",
            "--y",
            i.name(),
            "-o",
            s(&svg),
        ]));
        let figure = fs::read_to_string(&svg).expect("the figure was written");
        // The axis label is the indicator's entry in the table of symbols:
        // description, symbol (typeset) and unit.
        let label = stickslip::plot::visible(&i.symbol().label());
        assert!(label.contains(i.symbol().description));
        if i.unit() != "1" {
            assert!(label.ends_with(&format!("({})", i.unit())), "{label}");
        }
        let shown = common::svg_texts(&figure);
        assert!(
            shown.contains(&label),
            "the axis label of {i} is {label}; the figure shows {shown:?}"
        );
    }
}
