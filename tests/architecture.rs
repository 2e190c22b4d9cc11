//! The shape of the tree (the data path of the crate docs in `src/lib.rs`):
//! every top-level module depends only on modules of lower layers, so
//! there is no import cycle; and no source file grows past 700 lines
//! unless it is listed below with the reason it is one idea.
//!
//! The dependencies are read from the source: every `crate::<module>` path
//! outside comments and `#[cfg(test)]` modules, including the names inside
//! `use crate::{...}` groups.

use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// The layers, bottom first: a module may use modules of lower layers only.
const LAYERS: &[&[&str]] = &[
    &[
        "error",
        "numerics",
        "interrupt",
        "symbol",
        "plural",
        "csv_text",
    ],
    &["output"],
    &["motor"],
    &["spring"],
    &["signal"],
    &["power"],
    &["actuator"],
    &["engine"],
    &["observer"],
    &["analysis"],
    &["sensitivity"],
    &["indicator"],
    &["scene"],
    &["provenance"],
    &["simulation"],
    &["report", "check", "compare"],
    &["export", "sweep", "characteristic", "optimize"],
    &["bench"],
    &["plot"],
    &["cli"],
];

/// Source files allowed over 700 lines, with the reason.
const LONG_FILES: &[(&str, &str)] = &[];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in fs::read_dir(dir).expect("src is readable") {
        let path = entry.expect("entry").path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// The top-level module a file belongs to (`None` for lib.rs and main.rs).
fn module_of(path: &Path) -> Option<String> {
    let rel = path.strip_prefix(src()).expect("inside src");
    let first = rel.components().next()?.as_os_str().to_str()?.to_owned();
    let name = first.trim_end_matches(".rs").to_owned();
    (name != "lib" && name != "main").then_some(name)
}

/// The code of a file without comments and without its test module.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    text.lines()
        .map(|line| match line.find("//") {
            Some(i) => &line[..i],
            None => line,
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every top-level module named after `crate::`.
fn used_modules(code: &str) -> BTreeSet<String> {
    let mut used = BTreeSet::new();
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // The first name of every top-level item of the group.
            let (mut depth, mut item_start) = (0usize, true);
            for (j, c) in group.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' if depth == 0 => break,
                    '}' => depth -= 1,
                    ',' if depth == 0 => item_start = true,
                    c if item_start && (c.is_alphanumeric() || c == '_') => {
                        used.insert(ident(&group[j..]));
                        item_start = false;
                    }
                    _ => {}
                }
            }
        } else {
            used.insert(ident(rest));
        }
    }
    used
}

fn layer_of(module: &str) -> Option<usize> {
    LAYERS.iter().position(|layer| layer.contains(&module))
}

#[test]
fn every_module_uses_only_lower_layers() {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut edges: BTreeMap<String, BTreeSet<(String, String)>> = BTreeMap::new();
    for file in &files {
        let Some(module) = module_of(file) else {
            continue;
        };
        let text = fs::read_to_string(file).expect("readable source");
        for used in used_modules(&code(&text)) {
            if used != module {
                let name = file.strip_prefix(src()).unwrap().display().to_string();
                edges
                    .entry(module.clone())
                    .or_default()
                    .insert((used, name));
            }
        }
    }
    assert!(
        edges.len() > 10,
        "the module graph was read ({} modules)",
        edges.len()
    );
    let mut wrong = Vec::new();
    for (module, uses) in &edges {
        let own = layer_of(module).unwrap_or_else(|| panic!("module {module} has no layer"));
        for (used, file) in uses {
            let theirs = layer_of(used)
                .unwrap_or_else(|| panic!("{file} uses crate::{used}, which is not a module"));
            if theirs >= own {
                wrong.push(format!("{file}: {module} uses {used}"));
            }
        }
    }
    assert!(
        wrong.is_empty(),
        "dependencies against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn every_top_level_module_has_a_layer() {
    let lib = fs::read_to_string(src().join("lib.rs")).expect("lib.rs");
    let declared: Vec<&str> = lib
        .lines()
        .filter_map(|l| {
            let l = l.trim_start_matches("pub ");
            l.strip_prefix("mod ")?.strip_suffix(';')
        })
        .collect();
    assert!(
        declared.len() > 10,
        "modules read from lib.rs: {declared:?}"
    );
    for module in declared {
        assert!(layer_of(module).is_some(), "module {module} has no layer");
    }
}

#[test]
fn no_source_file_is_longer_than_700_lines_without_a_reason() {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut long = Vec::new();
    for file in &files {
        let lines = fs::read_to_string(file).expect("readable").lines().count();
        let name = file.strip_prefix(src()).unwrap().display().to_string();
        if lines > 700 && !LONG_FILES.iter().any(|(f, _)| *f == name) {
            long.push(format!("{name}: {lines} lines"));
        }
    }
    assert!(
        long.is_empty(),
        "files over 700 lines:\n{}",
        long.join("\n")
    );
}

#[test]
fn the_reader_finds_paths_and_groups_but_not_comments() {
    // A hand-written sample: two paths, one group of three names, one
    // path in a comment that `code` drops.
    let sample =
        "use crate::a::X;\nuse crate::{b, c::Y, d::{e, f}};\n// crate::g\nlet _ = crate::h::z();";
    let found: Vec<String> = used_modules(&code(sample)).into_iter().collect();
    assert_eq!(found, ["a", "b", "c", "d", "h"]);
}

/// The names a public item is known by: every `pub struct`, `enum`,
/// `trait`, `type` and `union` of the tree (the crate warns on a `pub` item
/// no public path reaches, `unreachable_pub`, so each is public) and
/// every `pub use ... as NAME`, with the files that define them.
fn public_type_names() -> BTreeMap<String, Vec<String>> {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut names: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for path in files {
        if path.ends_with("main.rs") {
            continue;
        }
        let text = code(&fs::read_to_string(&path).expect("source is readable"));
        let rel = path
            .strip_prefix(src())
            .expect("inside src")
            .display()
            .to_string();
        for name in defined_names(&text) {
            names.entry(name).or_default().push(rel.clone());
        }
    }
    names
}

/// The type names `code` defines publicly (see [`public_type_names`]).
fn defined_names(code: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect()
    };
    let mut out = Vec::new();
    for line in code.lines() {
        let line = line.trim_start();
        for kind in ["struct", "enum", "trait", "type", "union"] {
            if let Some(rest) = line.strip_prefix(&format!("pub {kind} ")) {
                out.push(ident(rest));
            }
        }
        if line.starts_with("pub use ") {
            let mut rest = line;
            while let Some(i) = rest.find(" as ") {
                rest = &rest[i + 4..];
                out.push(ident(rest));
            }
        }
    }
    out
}

#[test]
fn every_public_type_name_is_defined_once() {
    let twice: Vec<String> = public_type_names()
        .into_iter()
        .filter(|(_, files)| files.len() > 1)
        .map(|(name, files)| format!("{name}: {}", files.join(", ")))
        .collect();
    assert!(
        twice.is_empty(),
        "public type names defined more than once:\n{}",
        twice.join("\n")
    );
}

#[test]
fn the_name_reader_sees_definitions_and_renames_but_not_crate_items() {
    let code = "pub struct A;\n    pub enum B {}\npub(crate) struct C;\n\
                pub use x::{D as E, F};\npub trait G {}\nstruct H;";
    assert_eq!(defined_names(code), ["A", "B", "E", "G"]);
}

/// The crate root's public names (`pub use` and `pub mod` of `src/lib.rs`).
fn root_names() -> (Vec<String>, Vec<String>) {
    let text = code(&fs::read_to_string(src().join("lib.rs")).expect("lib.rs is readable"));
    let (mut uses, mut mods) = (Vec::new(), Vec::new());
    for item in text.split(';') {
        let item = item.trim();
        let item = item
            .rsplit_once(")]")
            .map_or(item, |(_, rest)| rest.trim_start());
        if let Some(m) = item.strip_prefix("pub mod ") {
            mods.push(m.trim().to_owned());
        } else if let Some(u) = item.strip_prefix("pub use ") {
            let names = u.rsplit_once('{').map_or(u, |(_, group)| group);
            for name in names.trim_end_matches('}').split(',') {
                let name = name.rsplit("::").next().unwrap_or(name).trim();
                if !name.is_empty() {
                    uses.push(name.to_owned());
                }
            }
        }
    }
    (uses, mods)
}

/// The crate doc's section `## title`, up to the next section.
fn crate_doc_section(title: &str) -> String {
    let text = fs::read_to_string(src().join("lib.rs")).expect("lib.rs is readable");
    let doc: String = text
        .lines()
        .filter_map(|l| l.strip_prefix("//!"))
        .collect::<Vec<_>>()
        .join("\n");
    let start = doc
        .find(&format!("## {title}"))
        .unwrap_or_else(|| panic!("the crate doc has a section {title}"));
    let rest = &doc[start + 3 + title.len()..];
    rest[..rest.find("\n ## ").unwrap_or(rest.len())].to_owned()
}

#[test]
fn the_crate_root_names_only_what_its_docs_present() {
    let (uses, mods) = root_names();
    assert!(uses.contains(&"run".to_owned()) && mods.contains(&"engine".to_owned()));
    let front_door = crate_doc_section("The front door");
    let missing: Vec<&String> = uses
        .iter()
        .filter(|name| !front_door.contains(&format!("[`{name}`]")))
        .collect();
    assert!(
        missing.is_empty(),
        "root names not in the front door section: {missing:?}"
    );
    let data_path = crate_doc_section("The data path");
    let missing: Vec<&String> = mods
        .iter()
        .filter(|name| !data_path.contains(&format!("[`{name}`]")))
        .collect();
    assert!(
        missing.is_empty(),
        "namespaces not in the data path: {missing:?}"
    );
}

/// The public functions of `code` that return a tuple (`-> (A, B)`, or one
/// wrapped in `Option` or `Result`), with their names: a public result is
/// a named type whose fields say what each value is. `pub(crate)` and
/// `pub(super)` functions are not public. Signatures may span lines.
fn tuple_returning_functions(code: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("pub ") {
        let starts_word = i == 0 || !rest[..i].ends_with(|c: char| c.is_alphanumeric() || c == '_');
        rest = &rest[i + 4..];
        let mut item = rest.trim_start();
        for qualifier in ["const ", "async ", "unsafe ", "extern \"C\" "] {
            item = item.strip_prefix(qualifier).unwrap_or(item).trim_start();
        }
        let Some(item) = item.strip_prefix("fn ").filter(|_| starts_word) else {
            continue;
        };
        let name: String = item
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_')
            .collect();
        // The signature: up to the body or `;` outside brackets.
        let (mut depth, mut end, mut arrow) = (0i32, item.len(), None);
        let bytes = item.as_bytes();
        let mut k = 0;
        while k < bytes.len() {
            match bytes[k] {
                b'-' if bytes.get(k + 1) == Some(&b'>') => {
                    if depth == 0 && arrow.is_none() {
                        arrow = Some(k + 2);
                    }
                    k += 1;
                }
                b'(' | b'<' | b'[' => depth += 1,
                b')' | b'>' | b']' => depth -= 1,
                b'{' | b';' if depth == 0 => {
                    end = k;
                    break;
                }
                _ => {}
            }
            k += 1;
        }
        let Some(arrow) = arrow.filter(|a| *a <= end) else {
            continue;
        };
        let result = item[arrow..end].split(" where").next().unwrap_or("").trim();
        let inner = ["Option<", "Result<"]
            .iter()
            .find_map(|w| result.strip_prefix(w))
            .unwrap_or(result)
            .trim_start();
        let unit = inner
            .strip_prefix('(')
            .is_some_and(|r| r.trim_start().starts_with(')'));
        if inner.starts_with('(') && !unit {
            out.push(name);
        }
    }
    out
}

#[test]
fn no_public_function_returns_a_tuple() {
    let mut files = Vec::new();
    rust_files(&src(), &mut files);
    let mut found = Vec::new();
    for path in files {
        let text = code(&fs::read_to_string(&path).expect("source is readable"));
        let rel = path.strip_prefix(src()).expect("inside src").display();
        for name in tuple_returning_functions(&text) {
            found.push(format!("{rel}: {name}"));
        }
    }
    assert!(
        found.is_empty(),
        "public functions returning a tuple (return a named type):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_tuple_reader_sees_public_tuple_results_only() {
    // Planted: `a` returns a pair, `b` a wrapped pair over several lines,
    // `f` a pair under `const`; `c` is crate-private, `d` returns unit in a
    // `Result`, `e` a named type after a closure argument with an arrow,
    // `g` is not a function of its own (`republish`), `h` has no result.
    let code = "pub fn a(x: f64) -> (f64, f64) { (x, x) }\n\
                impl T {\n    pub fn b<F>(\n        &self,\n        f: F,\n    ) -> Option<(Vec<f64>, u32)>\n    where\n        F: Fn(f64) -> f64,\n    {\n    }\n}\n\
                pub(crate) fn c() -> (u8, u8) {}\n\
                pub fn d() -> Result<(), E> {}\n\
                pub fn e(f: impl Fn(f64) -> (f64, f64)) -> Named {}\n\
                pub const fn f() -> (u8, u8) {}\n\
                fn republish_g() -> (u8, u8) {}\n\
                pub fn h(x: (f64, f64)) {}\n";
    assert_eq!(tuple_returning_functions(code), ["a", "b", "f"]);
}
