//! Every figure the project draws (`stickslip::plot::registry::ALL`), in
//! every preset, read as a journal's reviewer would (`plot::review`): no
//! text over another text, a tick label or a panel's frame; no legend over
//! data; no text below 7 pt printed; no legend taller than a quarter of
//! the figure; no underscore in any text. A figure added to the registry
//! is checked here without touching this file.

mod common;

use stickslip::plot::Preset;
use stickslip::plot::marks::Role;
use stickslip::plot::registry::ALL;
use stickslip::plot::review::{Check, review};

#[test]
fn every_figure_in_every_preset_passes_the_reviewers_checks() {
    let mut failures = Vec::new();
    for entry in ALL {
        for preset in Preset::ALL {
            let figure = entry
                .figure(preset)
                .unwrap_or_else(|e| panic!("{} ({preset}): {e}", entry.name));
            let marks = figure.marks(&preset.style());
            assert!(
                marks.texts.iter().any(|t| t.role == Role::TickLabel) && !marks.frames.is_empty(),
                "{} ({preset}): the marks hold no panel",
                entry.name
            );
            for finding in review(&marks) {
                failures.push(format!("{} ({preset}): {finding}", entry.name));
            }
        }
    }
    assert!(
        failures.is_empty(),
        "{} findings:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn the_marks_describe_the_svg_that_is_written() {
    // The texts the reviewer reads are the SVG's texts, one for one.
    for entry in ALL {
        let preset = Preset::SingleColumn;
        let figure = entry.figure(preset).unwrap();
        let svg = figure.svg(&preset.style());
        let marks = figure.marks(&preset.style());
        assert_eq!(
            svg.matches("<text ").count(),
            marks.texts.len(),
            "{}",
            entry.name
        );
        // Edge spaces of a rich text's runs are no-break spaces.
        let shown = common::svg_texts(&svg);
        let marked: Vec<String> = marks
            .texts
            .iter()
            .map(|t| t.text.replace('\u{a0}', " "))
            .collect();
        assert_eq!(shown, marked, "{}", entry.name);
    }
}

#[test]
fn a_text_moved_onto_another_in_a_registered_figure_is_found() {
    // A clean registered figure, then its first axis description planted
    // on its first tick label: the review must report that overlap.
    for name in [
        "work_precision",
        "compare_reference",
        "fig2_ideal_and_fourier",
    ] {
        let entry = ALL.iter().find(|e| e.name == name).expect(name);
        for preset in Preset::ALL {
            let mut marks = entry.figure(preset).unwrap().marks(&preset.style());
            assert_eq!(review(&marks), [], "{name} ({preset}) is clean");
            let tick = marks
                .texts
                .iter()
                .position(|t| t.role == Role::TickLabel)
                .unwrap();
            let label = marks
                .texts
                .iter()
                .position(|t| t.role == Role::AxisLabel)
                .unwrap();
            let (at, moved) = (marks.texts[tick].bounds, &mut marks.texts[label]);
            let (w, h) = (
                moved.bounds.x1 - moved.bounds.x0,
                moved.bounds.y1 - moved.bounds.y0,
            );
            moved.bounds.x0 = at.x0;
            moved.bounds.y0 = at.y0;
            moved.bounds.x1 = at.x0 + w;
            moved.bounds.y1 = at.y0 + h;
            let text = moved.text.clone();
            let found = review(&marks);
            assert!(
                found
                    .iter()
                    .any(|f| f.check == Check::TextOverlap && f.what.contains(&text)),
                "{name} ({preset}): {found:?}"
            );
        }
    }
}
