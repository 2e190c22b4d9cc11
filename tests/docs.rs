//! The documentation matches the program, and the repository stands alone:
//!
//! * every key that `stickslip run --json` prints, at any depth, is
//!   documented in `docs/interface.md`;
//! * every field of the default scene is documented there;
//! * every section of `docs/model.md` that the code, tests, examples or
//!   README cite exists;
//! * nothing in the repository refers to files outside it.

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(relative: &str) -> String {
    let path = root().join(relative);
    fs::read_to_string(&path).unwrap_or_else(|e| panic!("cannot read {}: {e}", path.display()))
}

/// Runs the binary from the repository root; returns its standard output.
fn stickslip(args: &[&str]) -> String {
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(root())
        .output()
        .expect("the binary runs");
    assert!(
        out.status.success(),
        "stickslip {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).expect("UTF-8 output")
}

/// Every file below `dir` (recursively), sorted.
fn files_below(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    let mut pending = vec![dir.to_path_buf()];
    while let Some(d) = pending.pop() {
        let entries =
            fs::read_dir(&d).unwrap_or_else(|e| panic!("cannot list {}: {e}", d.display()));
        for entry in entries {
            let path = entry.expect("directory entry").path();
            if path.is_dir() {
                pending.push(path);
            } else {
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// A name is documented when it appears as a code span of its own,
/// `` `name` ``.
fn undocumented<'a>(names: impl IntoIterator<Item = &'a String>, doc: &str) -> Vec<String> {
    names
        .into_iter()
        .filter(|name| !doc.contains(&format!("`{name}`")))
        .cloned()
        .collect()
}

/// Object keys at every depth; array items are walked, their indices are
/// not keys.
fn json_keys(value: &serde_json::Value, keys: &mut BTreeSet<String>) {
    match value {
        serde_json::Value::Object(map) => {
            for (key, inner) in map {
                keys.insert(key.clone());
                json_keys(inner, keys);
            }
        }
        serde_json::Value::Array(items) => items.iter().for_each(|item| json_keys(item, keys)),
        _ => {}
    }
}

fn toml_keys(table: &toml::Table, keys: &mut BTreeSet<String>) {
    for (key, value) in table {
        keys.insert(key.clone());
        if let toml::Value::Table(inner) = value {
            toml_keys(inner, keys);
        }
    }
}

#[test]
fn every_json_key_is_documented() {
    let doc = read("docs/interface.md");
    let mut scenes: Vec<PathBuf> = files_below(&root().join("examples/scenes"))
        .into_iter()
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    assert!(
        scenes.iter().any(|p| p.ends_with("paper_default.toml")),
        "examples/scenes/paper_default.toml is missing"
    );
    // The default scene with every optional output switched on, so that
    // the keys shown only on request (v_inf_transient, event_log,
    // trajectory) are checked too.
    let all_outputs = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("docs_all_outputs.toml");
    let text = stickslip(&["default-scene"])
        .replace("verify_steady_state = false", "verify_steady_state = true")
        .replace("trajectory = false", "trajectory = true")
        .replace("events = false", "events = true");
    fs::write(&all_outputs, text).expect("temporary scene written");
    scenes.push(all_outputs);

    let mut keys = BTreeSet::new();
    for scene in &scenes {
        let scene = scene.to_str().expect("UTF-8 path");
        let output = stickslip(&["run", scene, "--json"]);
        let value: serde_json::Value = serde_json::from_str(&output)
            .unwrap_or_else(|e| panic!("{scene}: not one JSON object: {e}"));
        json_keys(&value, &mut keys);
    }
    // The keys of --sensitivities (the default scene's parameters).
    let output = stickslip(&["run", "--json", "--sensitivities"]);
    let value: serde_json::Value = serde_json::from_str(&output).expect("one JSON object");
    json_keys(&value, &mut keys);
    for expected in [
        "v_inf",
        "stick_to_slip",
        "v_inf_transient",
        "event_log",
        "mode",
        "sensitivities",
        "motor.extra_acceleration",
    ] {
        assert!(
            keys.contains(expected),
            "run --json printed no `{expected}`"
        );
    }
    let missing = undocumented(&keys, &doc);
    assert!(
        missing.is_empty(),
        "keys of run --json not documented in docs/interface.md: {missing:?}"
    );
}

#[test]
fn every_default_scene_field_is_documented() {
    let doc = read("docs/interface.md");
    let scene: toml::Table = stickslip(&["default-scene"])
        .parse()
        .expect("default-scene prints TOML");
    let mut keys = BTreeSet::new();
    toml_keys(&scene, &mut keys);
    for expected in ["motor", "slider_mass", "kind", "capacitance", "max_periods"] {
        assert!(
            keys.contains(expected),
            "default-scene printed no `{expected}`"
        );
    }
    let missing = undocumented(&keys, &doc);
    assert!(
        missing.is_empty(),
        "scene fields not documented in docs/interface.md: {missing:?}"
    );
}

/// The section numbers a text cites after the model page's path:
/// `section 7`, `sections 1 and 8`, `sections 3, 4`, `, section 8` and the
/// bare `7` of a table cell.
fn cited_sections(text: &str) -> Vec<u32> {
    let path = "docs/model.md";
    let mut cited = Vec::new();
    for (at, _) in text.match_indices(path) {
        let mut rest = text[at + path.len()..].trim_start_matches(',').trim_start();
        for word in ["sections", "section"] {
            if let Some(after) = rest.strip_prefix(word) {
                rest = after.trim_start();
                break;
            }
        }
        loop {
            let digits = rest.len() - rest.trim_start_matches(|c: char| c.is_ascii_digit()).len();
            if digits == 0 {
                break;
            }
            cited.push(rest[..digits].parse().expect("a section number"));
            rest = &rest[digits..];
            let next = [", ", " and ", "-", ", and "]
                .iter()
                .filter_map(|sep| rest.strip_prefix(sep))
                .find(|after| after.starts_with(|c: char| c.is_ascii_digit()));
            match next {
                Some(after) => rest = after,
                None => break,
            }
        }
    }
    cited
}

#[test]
fn cited_model_sections_exist() {
    let model = read("docs/model.md");
    let sections: BTreeSet<u32> = model
        .lines()
        .filter_map(|line| line.strip_prefix("## "))
        .filter_map(|heading| {
            let number = heading.split(['.', ' ']).next()?;
            number.parse().ok()
        })
        .collect();
    for n in 1..=9 {
        assert!(sections.contains(&n), "docs/model.md has no section {n}");
    }
    let mut files: Vec<PathBuf> = ["src", "tests", "examples"]
        .iter()
        .flat_map(|dir| files_below(&root().join(dir)))
        .collect();
    files.push(root().join("README.md"));
    let mut citations = 0;
    let mut dangling = Vec::new();
    for file in &files {
        let Ok(text) = fs::read_to_string(file) else {
            continue;
        };
        for n in cited_sections(&text) {
            citations += 1;
            if !sections.contains(&n) {
                dangling.push(format!("{}: section {n}", file.display()));
            }
        }
    }
    // The code cites the model page dozens of times; finding few means the
    // search is broken, not that all is well.
    assert!(
        citations >= 20,
        "only {citations} citations of docs/model.md found"
    );
    assert!(
        dangling.is_empty(),
        "citations of sections docs/model.md does not have: {dangling:?}"
    );
}

#[test]
fn citation_parser_reads_every_form() {
    let text = "docs/model.md section 7; docs/model.md sections 1 and 8; \
                docs/model.md sections 3, 4; docs/model.md, section 2; \
                docs/model.md 5: x; docs/model.md section 6, paper section 9; \
                docs/model.md section 4.2; docs/model.md (the model)";
    assert_eq!(cited_sections(text), vec![7, 1, 8, 3, 4, 2, 5, 6, 4]);
}

#[test]
fn nothing_refers_outside_the_repository() {
    // Spelled in pieces so that this file does not match itself.
    let needles = [concat!("..", "/shared"), concat!("/work", "/shared")];
    let mut files: Vec<PathBuf> = ["src", "tests", "examples", ".ci", "docs"]
        .iter()
        .flat_map(|dir| files_below(&root().join(dir)))
        .collect();
    files.extend(["README.md", "Cargo.toml"].map(|f| root().join(f)));
    let mut read_files = 0;
    let mut offending = Vec::new();
    for file in &files {
        let Ok(text) = fs::read_to_string(file) else {
            continue;
        };
        read_files += 1;
        for needle in needles {
            if text.contains(needle) {
                offending.push(format!("{} mentions {needle}", file.display()));
            }
        }
    }
    assert!(read_files >= 50, "only {read_files} files read");
    assert!(offending.is_empty(), "{offending:?}");
}
