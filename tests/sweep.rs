//! Sweeps (`src/sweep/`): sharding and merging, rerun skipping, the
//! `level` axis, case order, and bad sweep files. Small grids of the
//! paper's motor, so that the whole file runs in seconds.

mod common;

use common::{failure, ok, s, stickslip, write};

use std::fs;
use std::path::{Path, PathBuf};
use stickslip::Scene;
use stickslip::sweep::{self, AxisValue, Shard, Sweep, SweepAxis};

/// 2 levels x 3 n x 2 sigma = 12 cases of the default scene's motor.
/// A fresh directory for one test.
fn dir(name: &str) -> PathBuf {
    common::scratch("sweep", name)
}

const SMALL: &str = r#"
[axes]
level = [3, 6]
harmonics = [2, 3, 4]
sigma = [false, true]
"#;

/// A CSV row of [`SMALL`] (v_inf is the sixth column) with another v_inf.
/// `line` of a sweep CSV whose columns are `case`, three axes,
/// `scene_hash`, `regime`, `v_inf`, ... with another `v_inf`.
fn with_v_inf(line: &str, v_inf: &str) -> String {
    let mut fields: Vec<&str> = line.split(',').collect();
    fields[6] = v_inf;
    fields.join(",")
}

/// The timing columns, left out with `--no-timing`.
const TIMING: [&str; 3] = ["wall_time_s", "setup_time_s", "simulation_time_s"];

/// CSV rows as header-keyed maps, without the timing columns.
fn rows_without_timing(path: &Path) -> Vec<Vec<(String, String)>> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .unwrap();
    let header = reader.headers().unwrap().clone();
    reader
        .records()
        .map(|r| {
            header
                .iter()
                .zip(r.unwrap().iter())
                .filter(|(k, _)| !TIMING.contains(k))
                .map(|(k, v)| (k.to_owned(), v.to_owned()))
                .collect()
        })
        .collect()
}

/// "A sweep split into 3 shards and merged equals the unsharded
/// sweep row for row" — byte for byte without timing, every column but the
/// wall time with it, in CSV and JSON lines.
#[test]
fn three_shards_merged_equal_the_unsharded_sweep() {
    let d = dir("shards");
    let file = write(&d, "small.toml", SMALL);
    for (ext, timing) in [("csv", false), ("jsonl", false), ("csv", true)] {
        let timing_flag: &[&str] = if timing { &[] } else { &["--no-timing"] };
        let whole = d.join(format!("whole-{timing}.{ext}"));
        let mut args = vec!["sweep", s(&file), "-q", "-o", s(&whole)];
        args.extend(timing_flag);
        ok(stickslip(&args));
        let mut shards = Vec::new();
        for i in 1..=3 {
            let out = d.join(format!("shard{i}-{timing}.{ext}"));
            let shard = format!("{i}/3");
            let mut args = vec!["sweep", s(&file), "-q", "--shard", &shard, "-o", s(&out)];
            args.extend(timing_flag);
            let err = ok(stickslip(&args));
            assert!(err.contains("4 cases in shard"), "{err}");
            shards.push(out);
        }
        let merged = d.join(format!("merged-{timing}.{ext}"));
        // Inputs in any order.
        let args = vec![
            "merge",
            "-o",
            s(&merged),
            s(&shards[2]),
            s(&shards[0]),
            s(&shards[1]),
        ];
        ok(stickslip(&args));
        let (a, b) = (
            fs::read_to_string(&whole).unwrap(),
            fs::read_to_string(&merged).unwrap(),
        );
        if timing {
            assert_eq!(rows_without_timing(&whole), rows_without_timing(&merged));
            assert_eq!(rows_without_timing(&whole).len(), 12);
        } else {
            assert_eq!(a, b, "{ext}");
            // A header line, the column names (CSV), then the rows.
            let rows = if ext == "csv" {
                a.lines().count() - 2
            } else {
                a.lines().count() - 1
            };
            assert_eq!(rows, 12);
        }
        if ext == "jsonl" {
            for (i, line) in a.lines().skip(1).enumerate() {
                let v: serde_json::Value = serde_json::from_str(line).unwrap();
                assert_eq!(v["case"], i);
                assert!(v["v_inf"].as_f64().unwrap() > 0.0);
                assert!(v["failure"].is_null());
            }
        }
    }
}

/// Without timing the same sweep writes the same bytes, run to run.
#[test]
fn a_sweep_without_timing_is_byte_identical_run_to_run() {
    let d = dir("identical");
    let file = write(&d, "small.toml", SMALL);
    let (a, b) = (d.join("a.csv"), d.join("b.csv"));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-o",
        s(&a),
    ]));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-j",
        "1",
        "-o",
        s(&b),
    ]));
    assert_eq!(fs::read(&a).unwrap(), fs::read(&b).unwrap());
}

/// A rerun keeps the rows already written (complete lines only) and runs
/// the missing cases: deleting rows and cutting the last line gives the
/// same file back; a kept row is not recomputed.
#[test]
fn a_rerun_runs_only_the_missing_cases() {
    let d = dir("rerun");
    let file = write(&d, "small.toml", SMALL);
    let out = d.join("out.csv");
    let args = ["sweep", s(&file), "-q", "--no-timing", "-o", s(&out)];
    ok(stickslip(&args));
    let full = fs::read_to_string(&out).unwrap();
    let lines: Vec<&str> = full.lines().collect();
    assert_eq!(lines.len(), 14);

    // Drop cases 2, 5 and 6; cut the last row (case 11) in the middle.
    let mut damaged: Vec<&str> = lines
        .iter()
        .enumerate()
        .filter(|(i, _)| ![4, 7, 8].contains(i))
        .map(|(_, l)| *l)
        .collect();
    let last = damaged.pop().unwrap();
    let damaged = format!("{}\n{}", damaged.join("\n"), &last[..last.len() / 2]);
    fs::write(&out, damaged).unwrap();
    let err = ok(stickslip(&args));
    assert!(err.contains("8 already written, 4 run"), "{err}");
    assert_eq!(fs::read_to_string(&out).unwrap(), full);

    // The library on one thread, from an empty file, writes the same.
    fs::write(&out, "").unwrap();
    let options = sweep::SweepOptions {
        timing: false,
        progress: false,
        jobs: Some(1),
        ..sweep::SweepOptions::new(&out)
    };
    let summary = sweep::execute(&sweep::load(&file).unwrap(), &options).unwrap();
    assert_eq!((summary.ran, summary.skipped, summary.rows), (12, 0, 12));
    assert_eq!(fs::read_to_string(&out).unwrap(), full);

    // Nothing missing: nothing runs, and a kept row is kept as it is.
    let edited = full.replacen(lines[2], &with_v_inf(lines[2], "9.5"), 1);
    assert_ne!(edited, full);
    fs::write(&out, &edited).unwrap();
    let err = ok(stickslip(&args));
    assert!(err.contains("12 already written, 0 run"), "{err}");
    assert_eq!(fs::read_to_string(&out).unwrap(), edited);

    // An output with other columns (here: timing) is refused, untouched.
    let err = failure(stickslip(&["sweep", s(&file), "-q", "-o", s(&out)]));
    assert!(
        err.contains("has no columns wall_time_s, setup_time_s, simulation_time_s compared with"),
        "{err}"
    );
    assert_eq!(fs::read_to_string(&out).unwrap(), edited);

    // Another axis value (level 6 -> 7): the six rows of level 6 are
    // dropped and rerun, the six of level 3 kept (the edited one too).
    let other = write(&d, "other.toml", &SMALL.replace("[3, 6]", "[3, 7]"));
    let err = ok(stickslip(&[
        "sweep",
        s(&other),
        "-q",
        "--no-timing",
        "-o",
        s(&out),
    ]));
    assert!(
        err.contains("6 rows of") && err.contains("6 already written, 6 run"),
        "{err}"
    );
    let now = fs::read_to_string(&out).unwrap();
    assert_eq!(now.lines().nth(2), edited.lines().nth(2));
    assert!(now.lines().nth(8).unwrap().starts_with("6,7,2,false,"));
}

/// The `level` axis sets `sqrt(kappa) = level / n` (37): each case is the
/// scene written by hand with that `sqrt_kappa`.
#[test]
fn level_axis_sets_sqrt_kappa_to_level_over_n() {
    let sweep = Sweep::from_toml_str(SMALL, "<string>", Path::new(".")).unwrap();
    let cases = sweep.cases();
    assert_eq!(cases.len(), 12);
    // sqrt(kappa) by hand: level 3 over n = 2, 3, 4, then level 6.
    let by_hand = [1.5, 1.5, 1.0, 1.0, 0.75, 0.75, 3.0, 3.0, 2.0, 2.0, 1.5, 1.5];
    for (case, sqrt_kappa) in cases.iter().zip(by_hand) {
        let n = case
            .value(SweepAxis::Harmonics)
            .and_then(AxisValue::as_f64)
            .unwrap();
        let sigma = case
            .value(SweepAxis::Sigma)
            .and_then(AxisValue::as_bool)
            .unwrap();
        let manual = format!(
            "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nsqrt_kappa = {sqrt_kappa}\nharmonics = {n}\nsigma = {sigma}\n"
        );
        let scene = Scene {
            signal: Scene::from_toml_str(&manual, "<manual>").unwrap().signal,
            ..Scene::default()
        };
        assert_eq!(case.scene, scene, "case {}", case.index);
    }
    // Case order: level slowest, then n, then sigma fastest.
    let order: Vec<String> = cases.iter().take(4).map(|c| c.describe()).collect();
    assert_eq!(
        order,
        [
            "level = 3, harmonics = 2, sigma = false",
            "level = 3, harmonics = 2, sigma = true",
            "level = 3, harmonics = 3, sigma = false",
            "level = 3, harmonics = 3, sigma = true",
        ]
    );
    // Without a harmonics axis, n comes from the base scene (n = 2).
    let sweep = Sweep::from_toml_str("[axes]\nlevel = [12]\n", "<string>", Path::new(".")).unwrap();
    assert_eq!(
        sweep.cases()[0].scene,
        Scene::default(),
        "level 12 / n 2 = 6"
    );
}

/// `run_cases` returns the results in case order, whatever finishes first,
/// and equal to single runs.
#[test]
fn run_cases_returns_results_in_case_order() {
    let sweep = Sweep::from_toml_str(SMALL, "<string>", Path::new(".")).unwrap();
    let mut cases = sweep.cases();
    cases.reverse();
    let results = sweep::run_cases(&cases, false);
    for (case, result) in cases.iter().zip(&results) {
        let r = result.as_ref().unwrap();
        assert_eq!(r.index, case.index);
        assert_eq!(r.values, case.values);
        let single = sweep::run_case(case).unwrap();
        let (a, b) = (r.report.indicators.v_inf, single.report.indicators.v_inf);
        assert!(
            (a - b).abs() <= 1e-15 * b.abs(),
            "case {}: {a} vs {b}",
            case.index
        );
    }
}

#[test]
fn shards_parse_one_based() {
    let shard: Shard = "2/3".parse().unwrap();
    assert_eq!((shard.index, shard.count), (2, 3));
    assert_eq!(
        (0..9).filter(|c| shard.contains(*c)).collect::<Vec<_>>(),
        [1, 4, 7]
    );
    for bad in ["0/3", "4/3", "1/0", "a/3", "3", "-1/3"] {
        assert!(bad.parse::<Shard>().is_err(), "{bad}");
    }
    let err = failure(stickslip(&["sweep", "x.toml", "--shard", "0/3"]));
    assert!(err.contains("1 <= i <= N"), "{err}");
}

/// Bad sweep files: a one-line error naming the sweep field and value, a
/// non-zero exit, and no output file.
#[test]
fn bad_sweep_files_are_refused_before_anything_runs() {
    let d = dir("bad");
    write(
        &d,
        "ideal.toml",
        "[signal]\nkind = \"ideal\"\nstroke = 25e-6\nkappa = 1.0\n",
    );
    write(
        &d,
        "no_actuator.toml",
        "[motor]\nslider_mass = 1.4e-3\ncontact_force = 1.0\nmu_static = 0.1736\nmu_dynamic = 0.1568\n",
    );
    let cases: &[(&str, &str)] = &[
        (
            "[axes]\nlevel = [3, 6, -3]\n",
            "axes.level[2] = -3: must be positive",
        ),
        (
            "[axes]\nlevel = [3]\nharmonics = [2, 0]\n",
            "axes.harmonics[1] = 0: must be an integer from 1 to",
        ),
        (
            "[axes]\nsqrt_kappa = [1, nan]\n",
            "axes.sqrt_kappa[1] = NaN: must be a finite number",
        ),
        (
            "[axes]\nduty = [0.5, 1.5]\n",
            "axes.duty[1] = 1.5: must lie in (0, 1]",
        ),
        (
            "[axes]\nmu_static = [-0.1]\n",
            "axes.mu_static[0] = -0.1: must not be negative",
        ),
        (
            "[axes]\nharmonics = [2, 3, 2]\n",
            "axes.harmonics[2] = 2: repeats axes.harmonics[0]",
        ),
        (
            "[axes]\nsigma = [true, false, true]\n",
            "axes.sigma[2]: true repeats axes.sigma[0]",
        ),
        ("[axes]\nsigma = []\n", "axes.sigma: is empty"),
        (
            "[axes]\nlevel = [3]\nkappa = [1]\n",
            "at most one of axes.level, axes.sqrt_kappa, axes.kappa, axes.frequency and axes.f_max",
        ),
        (
            "[axes]\nmu_dynamic = [0.1, 0.2]\n",
            "case 1 (mu_dynamic = 0.2): motor.mu_dynamic = 0.2: must not exceed motor.mu_static = 0.1736",
        ),
        ("[axes]\nlevels = [3]\n", "unknown field `levels`"),
        (
            "[axes]\nharmonics = [2.5]\n",
            "axes.harmonics[0]: invalid type: floating point `2.5`, expected i64 (line 2, column 14: `harmonics = [2.5]`)",
        ),
        ("bases = \"x\"\n", "unknown field `bases`"),
        (
            "base = \"ideal.toml\"\n[axes]\nharmonics = [2]\n",
            "axes.harmonics: needs a base signal with kind = \"fourier\"",
        ),
        (
            "base = \"missing.toml\"\n",
            "base scene: cannot read scene file",
        ),
        (
            "[outputs]\nindicators = [\"speed\"]\n",
            "unknown indicator \"speed\"",
        ),
        ("[outputs]\nformat = \"xml\"\n", "unknown variant `xml`"),
        (
            "base = \"no_actuator.toml\"\n[outputs]\nindicators = [\"velocity_per_power\"]\n",
            "outputs.indicators: velocity_per_power needs an [actuator] table",
        ),
    ];
    for (i, (text, expected)) in cases.iter().enumerate() {
        let file = write(&d, &format!("bad{i}.toml"), text);
        let out = d.join(format!("bad{i}.csv"));
        let err = failure(stickslip(&["sweep", s(&file), "-q", "-o", s(&out)]));
        assert!(err.contains(expected), "{text:?}: {err}");
        assert!(
            err.contains(&format!("bad{i}.toml")),
            "names the file: {err}"
        );
        assert_eq!(err.trim().lines().count(), 1, "one line: {err}");
        assert!(!out.exists(), "{text:?} left an output");
    }
}

/// `merge` refuses inputs that do not fit together, naming the file.
#[test]
fn merge_refuses_mismatched_inputs() {
    let d = dir("merge");
    let file = write(&d, "small.toml", SMALL);
    let (a, b, c) = (d.join("a.csv"), d.join("b.csv"), d.join("c.jsonl"));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "--shard",
        "1/2",
        "-o",
        s(&a),
    ]));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--shard",
        "2/2",
        "-o",
        s(&b),
    ]));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "--shard",
        "2/2",
        "-o",
        s(&c),
    ]));
    let out = d.join("out.csv");
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&a), s(&b)]));
    assert!(
        err.contains(
            "b.csv: has the extra columns wall_time_s, setup_time_s, simulation_time_s compared with"
        ),
        "{err}"
    );
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&a), s(&c)]));
    assert!(err.contains("c.jsonl") && err.contains("jsonl"), "{err}");
    // The same case with different content.
    let text = fs::read_to_string(&a).unwrap();
    let line = text.lines().nth(2).unwrap();
    let changed = write(
        &d,
        "changed.csv",
        &text.replacen(line, &with_v_inf(line, "9.5"), 1),
    );
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&a), s(&changed)]));
    assert!(
        err.contains("changed.csv: line 3: case 0 is also in") && err.contains("a.csv line 3"),
        "{err}"
    );
    // The same input twice.
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&a), s(&a)]));
    assert!(err.contains("a.csv: is given twice"), "{err}");
    assert!(!out.exists());
    // The old syntax (output first, no -o) is a usage error.
    let o = stickslip(&["merge", s(&out), s(&a)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(!out.exists());
    // A missing shard is refused, naming the cases no input holds (the
    // sweep's number of cases is in the first line of every shard), and
    // nothing is written; --allow-partial merges what is there and lists
    // them.
    // SMALL has 2 x 3 x 2 = 12 cases; shard 1/2 holds the even ones.
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&a)]));
    assert!(
        err.contains(
            "not written: 6 of the sweep's 12 cases are in no input ([1, 3, 5, 7, 9, 11])"
        ) && err.contains("--allow-partial"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(!out.exists());
    let err = ok(stickslip(&[
        "merge",
        "-o",
        s(&out),
        s(&a),
        "--allow-partial",
    ]));
    assert!(
        err.contains("6 cases of the sweep are in no input") && err.contains("[1, 3, 5, 7, 9, 11]"),
        "{err}"
    );
    assert_eq!(fs::read_to_string(&out).unwrap().lines().count(), 2 + 6);
}

/// A run-away is a physical outcome: its row has the regime `run-away`,
/// the velocity of its last period and no indicators, and no failure. A
/// case whose run fails (here: its time limit runs out) is written with
/// the reason in `failure` and the other result columns empty. Neither
/// stops the sweep, and neither is rerun.
#[test]
fn a_run_away_is_a_row_and_a_failing_case_is_written_with_its_reason() {
    let d = dir("failure");
    // The paper's motor with a time limit of 0.2 s per run.
    let base = Scene::default().to_toml().replace(
        "verify_steady_state = false",
        "verify_steady_state = false\ntime_limit_s = 0.2",
    );
    assert!(base.contains("time_limit_s"));
    write(&d, "base.toml", &base);
    // g_t = 500 m/s^2 > a_d = 112 m/s^2 (docs/model.md section 6): sliding
    // friction cannot hold the slider. kappa = 1e9: the start-up from rest
    // takes of the order of kappa periods, far beyond 0.2 s.
    let file = write(
        &d,
        "f.toml",
        "base = \"base.toml\"\n[axes]\nkappa = [36, 1e9]\nextra_acceleration = [0, 500]\n[outputs]\nindicators = [\"v_inf\", \"startup_time\"]\n",
    );
    let out = d.join("f.csv");
    let args = ["sweep", s(&file), "-q", "--no-timing", "-o", s(&out)];
    let err = ok(stickslip(&args));
    assert!(err.contains("4 run, 2 failed"), "{err}");
    let rows = rows_without_timing(&out);
    let get =
        |row: &[(String, String)], key: &str| row.iter().find(|(k, _)| k == key).unwrap().1.clone();
    // Case 0: the paper's default.
    assert!(get(&rows[0], "v_inf").parse::<f64>().unwrap() > 0.29);
    assert_eq!(get(&rows[0], "regime"), "slip-slip");
    assert_eq!(get(&rows[0], "failure"), "");
    // Case 1: kappa = 36 with the load: a run-away, forward (g_t > 0).
    assert_eq!(get(&rows[1], "regime"), "run-away");
    assert_eq!(get(&rows[1], "v_inf"), "");
    assert_eq!(get(&rows[1], "failure"), "");
    assert!(get(&rows[1], "last_v_p").parse::<f64>().unwrap() > 0.0);
    // Cases 2 and 3: kappa = 1e9, with and without the load (which would
    // run away only once the slider leaves the rod's huge velocity range):
    // the time limit.
    for row in &rows[2..] {
        assert_eq!(get(row, "regime"), "");
        assert_eq!(get(row, "v_inf"), "");
        assert!(get(row, "failure").contains("time limit"), "{rows:?}");
    }
    let err = ok(stickslip(&args));
    assert!(err.contains("4 already written, 0 run"), "{err}");
}
