//! Every figure the project draws (`stickslip::plot::registry::ALL`), in
//! every preset, read as a journal's reviewer would (`plot::review`): no
//! text over another text, a tick label or a panel's frame; no legend over
//! data; no text below 7 pt printed; no legend taller than a quarter of
//! the figure; no underscore in any text. A figure added to the registry
//! is checked here without touching this file.

use stickslip::plot::Preset;
use stickslip::plot::marks::Role;
use stickslip::plot::registry::ALL;
use stickslip::plot::review::review;

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
        let doc = roxmltree::Document::parse(&svg).unwrap();
        let shown: Vec<String> = doc
            .descendants()
            .filter(|n| n.has_tag_name("text"))
            .map(|n| {
                n.descendants()
                    .filter(|d| d.is_text())
                    .filter_map(|d| d.text())
                    .collect::<String>()
                    // Edge spaces of a rich text's runs are no-break spaces.
                    .replace('\u{a0}', " ")
            })
            .collect();
        let marked: Vec<String> = marks
            .texts
            .iter()
            .map(|t| t.text.replace('\u{a0}', " "))
            .collect();
        assert_eq!(shown, marked, "{}", entry.name);
    }
}
