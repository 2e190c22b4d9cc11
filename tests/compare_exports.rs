//! `stickslip compare` on the exports users make, from the independent
//! fixed-step generator (tests/data/compare/generate.py, its docstring
//! says how each file is laid out): the trajectories alone of the S = 500
//! run stopped after 300 periods, before its start-up ends (CSV, and the
//! same samples as Simulink's "Structure with time" in a MAT-file written
//! by scipy's savemat), and its first period as Simulink's "Array", as a
//! matrix with named columns and as a Scope's "Structure with time".
//!
//! The expected numbers come from elsewhere: the user's `v_p` of period
//! 300 is the generator's own (fixed_500.csv, the same run, whose `v_p`
//! the generator took from `x_S` at its grid points); the exact `v_p` of
//! period 300 and `v_inf` come from `stickslip run` (`--periods-series`,
//! `--json`).

mod common;

use common::in_process as cli;
use stickslip::{
    Scene, compare::Column as CompareColumn, compare::CompareOptions,
    compare::UserData as CompareData,
};

const DIR: &str = "tests/data/compare";
const SCENE: &str = "examples/scenes/paper_default.toml";
/// The export's last period (generate.py EXPORT_PERIODS).
const LAST: usize = 300;

fn file(name: &str) -> String {
    format!("{DIR}/{name}")
}

fn report(args: &[&str]) -> (u8, serde_json::Value) {
    let mut all = vec!["compare", SCENE];
    all.extend_from_slice(args);
    all.push("--json");
    let (code, out, err) = cli(&all);
    assert!(code <= 1, "compare failed: {err}");
    (code, serde_json::from_str(&out).unwrap())
}

fn scratch(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-exports-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Column `name` of a CSV with a header (empty cells skipped).
fn column(path: &std::path::Path, name: &str) -> Vec<f64> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let j = header.iter().position(|h| *h == name).unwrap();
    lines
        .filter_map(|l| l.split(',').nth(j).filter(|c| !c.is_empty()))
        .map(|c| c.parse().unwrap())
        .collect()
}

/// Exact `v_inf` and exact `v_p` of period `LAST`, from `stickslip run`.
fn exact() -> (f64, f64) {
    let series = scratch("series").join("series.csv");
    let (code, out, err) = cli(&[
        "run",
        SCENE,
        "--json",
        "--periods-series",
        series.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let v_inf = serde_json::from_str::<serde_json::Value>(&out).unwrap()["v_inf"]
        .as_f64()
        .unwrap();
    (v_inf, column(&series, "v_p")[LAST - 1])
}

#[test]
fn a_trajectory_only_export_of_an_unfinished_start_up_splits_its_v_inf_error() {
    let (v_inf, exact_v_p) = exact();
    let user_v_p = column(std::path::Path::new(&file("fixed_500.csv")), "v_p")[LAST - 1];
    let (code, r) = report(&[&file("trajectory_500.csv")]);
    let f = &r["files"][0];
    assert_eq!(f["periods"], LAST as u64);
    // Both parts, and their sum, as computed directly.
    let total = f["errors"]["v_inf"]["absolute"].as_f64().unwrap();
    let direct = (user_v_p - v_inf).abs();
    assert!(
        (total - direct).abs() <= 0.01 * direct,
        "{total} vs {direct}"
    );
    let split = &f["v_inf_split"];
    assert_eq!(split["period"], LAST as u64);
    let step_size = split["step_size"].as_f64().unwrap();
    let direct = user_v_p - exact_v_p;
    assert!(
        (step_size - direct).abs() <= 0.01 * direct.abs(),
        "step-size part {step_size} vs {direct}"
    );
    let truncation = split["truncation"].as_f64().unwrap();
    let direct = exact_v_p - v_inf;
    assert!(
        (truncation - direct).abs() <= 0.01 * direct.abs(),
        "truncation part {truncation} vs {direct}"
    );
    // The start-up is not over at period 300 (p_0.99 = 388): truncation
    // dominates, is said so, and the verdict judges the step-size part,
    // which passes the default 1e-3 where the total (3e-2) would not.
    assert_eq!(split["truncation_dominates"], true);
    let warnings = f["warnings"].as_array().unwrap();
    assert!(
        warnings[0]
            .as_str()
            .unwrap()
            .contains("truncation dominates")
    );
    assert!(f["errors"]["v_inf"]["relative"].as_f64().unwrap() > 1e-3);
    assert_eq!((code, &f["pass"]), (0, &serde_json::json!(true)));
    // Most period ends fall between samples (every 13th of 1000 steps a
    // period); the estimate of their error is stated, far below the
    // step-size part.
    let ends = &f["period_ends"];
    assert!(ends["interpolated"].as_u64().unwrap() > 200);
    assert!(ends["max_v_p_error"].as_f64().unwrap() < 0.01 * step_size.abs());
}

#[test]
fn a_simulink_structure_with_time_reads_like_the_csv_export() {
    // The same samples: x_S and v_S as two "To Workspace" structs found by
    // their variable names, the time from their own `time`.
    let (_, csv) = report(&[&file("trajectory_500.csv")]);
    let (_, mat) = report(&[&file("simulink_500.mat")]);
    let (a, b) = (&csv["files"][0], &mat["files"][0]);
    assert_eq!(a["samples"], b["samples"]);
    assert_eq!(a["periods"], b["periods"]);
    for key in ["step_size", "truncation"] {
        let (x, y) = (
            a["v_inf_split"][key].as_f64().unwrap(),
            b["v_inf_split"][key].as_f64().unwrap(),
        );
        // The CSV holds 15 digits, the MAT-file every bit.
        assert!((x - y).abs() <= 1e-6 * x.abs(), "{key}: {x} vs {y}");
    }
    assert_eq!(a["events"]["matched"], b["events"]["matched"]);
}

#[test]
fn an_array_a_matrix_with_named_columns_and_a_scope_structure_are_read() {
    // Period 1 of the S = 500 run: its v_p is fixed_500.csv's first.
    let direct = column(std::path::Path::new(&file("fixed_500.csv")), "v_p")[0];
    let mat = file("simulink_array.mat");
    // The matrix with column headers: found by name.
    let (_, named) = report(&[&mat]);
    // The array: columns named by --var-*.
    let (_, array) = report(&[
        &mat,
        "--var-t",
        "simout(:,1)",
        "--var-x-s",
        "simout(:,2)",
        "--var-v-s",
        "simout(:,3)",
    ]);
    // A Scope's "Structure with time": signals found by their labels,
    // the time by their struct's.
    let (_, scope) = report(&[&file("simulink_scope.mat")]);
    for r in [&named, &array, &scope] {
        let f = &r["files"][0];
        assert_eq!(f["periods"], 1);
        let v = f["v_inf"].as_f64().unwrap();
        assert!((v - direct).abs() <= 1e-9 * direct, "{v} vs {direct}");
    }
}

#[test]
fn event_times_of_the_exact_trajectory_at_a_users_times_are_below_a_tenth_of_a_step() {
    // The exact trajectory sampled at the export's own times.
    let exact = scratch("events").join("exact.csv");
    let (code, _, err) = cli(&[
        "run",
        SCENE,
        "--trajectory",
        exact.to_str().unwrap(),
        "--times",
        &file("trajectory_500.csv"),
    ]);
    assert_eq!(code, 0, "{err}");
    let (_, r) = report(&[exact.to_str().unwrap()]);
    let f = &r["files"][0];
    let e = &f["events"];
    // Two reversals a period over 300 periods, the first before a sample.
    assert!(e["exact"].as_u64().unwrap() >= 2 * LAST as u64 - 2);
    assert_eq!((&e["missed"], &e["spurious"]), (&0.into(), &0.into()));
    let step = f["step"].as_f64().unwrap();
    let max = e["max_time_error"].as_f64().unwrap();
    assert!(max < 0.1 * step, "{max} s against the step {step} s");
}

#[test]
fn the_analysis_takes_arrays_without_a_file() {
    // The export's arrays handed over directly give the file's report.
    let path = std::path::Path::new(DIR).join("trajectory_500.csv");
    let data = CompareData {
        t: Some(CompareColumn::new("t", column(&path, "t"))),
        x_s: Some(CompareColumn::new("x_S", column(&path, "x_S"))),
        v_s: Some(CompareColumn::new("v_S", column(&path, "v_S"))),
        ..Default::default()
    };
    let scene = Scene::from_path(std::path::Path::new(SCENE)).unwrap();
    let options = CompareOptions::default();
    let from_arrays =
        stickslip::compare::compare_data(&scene, &[("arrays".to_owned(), data)], &options).unwrap();
    let from_file = stickslip::compare::compare(&scene, &[path], &options).unwrap();
    let (a, b) = (&from_arrays.files[0], &from_file.files[0]);
    assert_eq!(a.v_inf_split, b.v_inf_split);
    assert_eq!(a.errors, b.errors);
    // Arrays are validated as files are.
    let bad = CompareData {
        t: Some(CompareColumn::new("t", vec![0.0, 1e-6, 1e-6])),
        v_s: Some(CompareColumn::new("v_S", vec![0.0, 0.1, 0.2])),
        ..Default::default()
    };
    let e = stickslip::compare::compare_data(&scene, &[("arrays".to_owned(), bad)], &options)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("column t, element 3") && e.contains("repeats"),
        "{e}"
    );
}

#[test]
fn found_nothing_lists_what_was_found_and_the_flags_that_map_it() {
    let (code, _, err) = cli(&[
        "compare",
        SCENE,
        &file("simulink_array.mat"),
        "--var-x-s",
        "position",
    ]);
    assert_eq!(code, 3);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("column position: no such variable; found simout(:,1), simout(:,2)"),
        "{err}"
    );
    let dir = scratch("nothing");
    let path = dir.join("scope.csv");
    std::fs::write(&path, "time_s,pos\n0,0\n1e-6,1e-9\n").unwrap();
    let (code, _, err) = cli(&["compare", SCENE, path.to_str().unwrap()]);
    assert_eq!(code, 3);
    assert!(
        err.contains("found time_s, pos") && err.contains("--var-t, --var-x-s"),
        "{err}"
    );
}

#[test]
fn a_damaged_mat_file_is_one_line_and_exit_3() {
    let bytes = std::fs::read(file("simulink_500.mat")).unwrap();
    let dir = scratch("damaged");
    for (name, damaged) in [
        ("truncated.mat", bytes[..5000].to_vec()),
        ("garbled.mat", {
            let mut b = bytes.clone();
            for i in (300..b.len()).step_by(101) {
                b[i] ^= 0x5a;
            }
            b
        }),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, damaged).unwrap();
        let (code, out, err) = cli(&["compare", SCENE, path.to_str().unwrap()]);
        assert_eq!((code, out.as_str()), (3, ""), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("a damaged MAT-file"), "{err}");
    }
}
