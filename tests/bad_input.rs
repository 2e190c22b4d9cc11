//! The folder `tests/bad_input/` holds bad scene files and, in
//! `expected.txt`, the error each must produce; `tests/bad_input/sweeps/`
//! the same for sweep files. Every one makes the CLI exit non-zero with
//! that error on one line of stderr, and writes no output file, not even a
//! partial one.

use std::path::Path;
use std::process::Command;

#[test]
fn every_bad_scene_gives_its_error_and_no_output() {
    check_folder("tests/bad_input", &["run"], &["--json", "--output"]);
}

#[test]
fn every_bad_sweep_gives_its_error_and_no_output() {
    check_folder(
        "tests/bad_input/sweeps",
        &["sweep"],
        &["-q", "--no-timing", "-o"],
    );
}

/// Runs `stickslip COMMAND FILE OPTIONS OUTPUT` for every file listed in
/// the folder's `expected.txt`.
fn check_folder(folder: &str, command: &[&str], options: &[&str]) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join(folder);
    let expected = std::fs::read_to_string(dir.join("expected.txt")).unwrap();
    let cases: Vec<(&str, &str)> = expected
        .lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| l.split_once(" | ").expect("file | error"))
        .collect();
    // Every file in the folder is listed, and every listed file exists.
    let mut files: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".toml"))
        .collect();
    files.sort();
    let mut listed: Vec<String> = cases.iter().map(|(f, _)| f.to_string()).collect();
    listed.sort();
    assert_eq!(files, listed);

    let out_dir = std::env::temp_dir().join(format!(
        "stickslip-bad-input-{}-{}",
        std::process::id(),
        folder.replace('/', "-")
    ));
    std::fs::create_dir_all(&out_dir).unwrap();
    for (file, error) in cases {
        let output = out_dir.join(format!("{file}.out.csv"));
        let o = Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args(command)
            .arg(dir.join(file))
            .args(options)
            .arg(&output)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{file} was accepted");
        assert_eq!(stderr.trim_end().lines().count(), 1, "{file}: {stderr}");
        assert!(
            stderr.contains(error),
            "{file}: expected «{error}», got «{stderr}»"
        );
        assert!(!output.exists(), "{file}: an output file was written");
        assert!(o.stdout.is_empty(), "{file}: output on stdout");
    }
    std::fs::remove_dir_all(&out_dir).unwrap();
}
