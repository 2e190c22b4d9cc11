//! Sweeps lose nothing and never serve stale rows: resume keyed by the
//! resolved scene and the program version, SIGINT/SIGTERM with every
//! finished row on disk, one writer per output, merges that refuse rather
//! than guess.

mod common;

use common::{failure, ok, s, stickslip, write};

use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A fresh directory for one test.
fn dir(name: &str) -> PathBuf {
    common::scratch("sweep_integrity", name)
}

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

/// 2 levels x 3 n = 6 cases of the default scene's motor.
const SMALL: &str = "[axes]\nlevel = [3, 6]\nharmonics = [2, 3, 4]\n";

/// Sixteen cases of a fraction of a second each: `kappa = 1e6` needs a
/// start-up of the order of `kappa` periods, which the start-up time makes
/// every case simulate (a `v_inf`-only case skips it).
const SLOW: &str = "[axes]\nkappa = [1e6]\nharmonics = [2]\nmu_static = [0.180, 0.181, 0.182, 0.183, 0.184, 0.185, 0.186, 0.187, 0.188, 0.189, 0.190, 0.191, 0.192, 0.193, 0.194, 0.195]\n[outputs]\nindicators = [\"v_inf\", \"startup_time\"]\n";

fn spawn(args: &[&str]) -> Child {
    Command::new(BIN)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts")
}

fn signal(child: &Child, name: &str) {
    let status = Command::new("kill")
        .args([format!("-{name}"), child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
}

/// Waits until `ready` holds, at most `limit`.
fn wait_for(limit: Duration, mut ready: impl FnMut() -> bool) {
    let start = Instant::now();
    while !ready() {
        assert!(start.elapsed() < limit, "timed out");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The rows (complete lines after the header lines) of a CSV output.
fn rows(path: &Path) -> usize {
    let text = fs::read_to_string(path).unwrap_or_default();
    text.lines().count().saturating_sub(2) - usize::from(!text.is_empty() && !text.ends_with('\n'))
}

/// Every file in `dir`, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A column of a CSV output, by name.
fn column(path: &Path, name: &str) -> Vec<String> {
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .unwrap();
    let at = reader.headers().unwrap().iter().position(|h| h == name);
    let at = at.unwrap_or_else(|| panic!("no column {name}"));
    reader
        .records()
        .map(|r| r.unwrap()[at].to_owned())
        .collect()
}

/// Changing the base scene (not an axis) makes every row stale: the rerun
/// says so, recomputes them, and equals a fresh run of the changed sweep;
/// `v_inf` changes with the slider mass. A row written by another program
/// version is recomputed too.
#[test]
fn a_changed_base_scene_recomputes_the_stale_rows() {
    let d = dir("stale");
    let base = d.join("base.toml");
    let default = String::from_utf8(stickslip(&["default-scene"]).stdout).unwrap();
    fs::write(&base, &default).unwrap();
    let file = write(&d, "grid.toml", &format!("base = \"base.toml\"\n{SMALL}"));
    let out = d.join("out.csv");
    let args = ["sweep", s(&file), "-q", "--no-timing", "-o", s(&out)];
    ok(stickslip(&args));
    let before = column(&out, "v_inf");
    let hashes = column(&out, "scene_hash");

    // A heavier slider: same axis values, other scenes.
    fs::write(
        &base,
        default.replace("slider_mass = 0.0014", "slider_mass = 0.0028"),
    )
    .unwrap();
    let err = ok(stickslip(&args));
    assert!(
        err.contains("6 rows of") && err.contains("recomputed"),
        "{err}"
    );
    assert!(err.contains("0 already written, 6 run"), "{err}");
    let after = column(&out, "v_inf");
    for (a, b) in before.iter().zip(&after) {
        assert_ne!(a, b, "a stale v_inf was kept");
    }
    assert!(
        column(&out, "scene_hash")
            .iter()
            .zip(&hashes)
            .all(|(a, b)| a != b)
    );
    let fresh = d.join("fresh.csv");
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-o",
        s(&fresh),
    ]));
    assert_eq!(fs::read(&out).unwrap(), fs::read(&fresh).unwrap());

    // Another program version in the header: every row is recomputed.
    let text = fs::read_to_string(&out).unwrap();
    let version = text.lines().next().unwrap().to_owned();
    assert!(version.starts_with("# stickslip_version = "), "{version}");
    fs::write(
        &out,
        text.replacen("stickslip_version = ", "stickslip_version = 0.0.0-old", 1),
    )
    .unwrap();
    let err = ok(stickslip(&args));
    assert!(
        err.contains("written by stickslip 0.0.0-old") && err.contains("its 6 rows are recomputed"),
        "{err}"
    );
    assert_eq!(fs::read(&out).unwrap(), fs::read(&fresh).unwrap());
}

/// SIGINT (and SIGTERM) during a sweep: the finished rows are on disk as
/// whole lines, the message says how many, the exit status is 130 (143),
/// no temporary or lock file remains, and a rerun completes the file to
/// the bytes of an uninterrupted run.
#[test]
fn an_interrupted_sweep_keeps_its_rows_and_a_rerun_completes_it() {
    let d = dir("interrupt");
    let file = write(&d, "slow.toml", SLOW);
    let whole = d.join("whole.csv");
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-j",
        "1",
        "-o",
        s(&whole),
    ]));
    assert_eq!(rows(&whole), 16);

    for (name, status) in [("INT", 130), ("TERM", 143)] {
        let out = d.join(format!("out-{name}.csv"));
        let args = [
            "sweep",
            s(&file),
            "-q",
            "--no-timing",
            "-j",
            "1",
            "-o",
            s(&out),
        ];
        let child = spawn(&args);
        wait_for(Duration::from_secs(60), || rows(&out) >= 3);
        signal(&child, name);
        let o = child.wait_with_output().unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(status), "{err}");
        let on_disk = rows(&out);
        assert!((3..16).contains(&on_disk), "{on_disk} rows: {err}");
        assert!(
            err.contains(&format!("stopped by SIG{name}: {on_disk} rows are in")),
            "{err}"
        );
        // Whole lines only, each one of the uninterrupted run.
        let text = fs::read_to_string(&out).unwrap();
        assert!(text.ends_with('\n'));
        let reference = fs::read_to_string(&whole).unwrap();
        assert!(text.lines().all(|l| reference.lines().any(|r| r == l)));
        assert!(
            !listing(&d)
                .iter()
                .any(|n| n.ends_with(".tmp") || n.ends_with(".lock"))
        );

        let err = ok(stickslip(&args));
        assert!(err.contains(&format!("{on_disk} already written")), "{err}");
        assert_eq!(fs::read(&out).unwrap(), fs::read(&whole).unwrap());
    }
}

/// Ctrl-C on `run` and `check`: exit 130, no output and no temporary file.
#[test]
fn an_interrupted_run_or_check_leaves_no_file() {
    let d = dir("interrupt_run");
    // kappa = 1e7: the start-up from rest takes of the order of kappa
    // periods (docs/interface.md, plausibility warnings), many seconds.
    let scene = write(
        &d,
        "slow.toml",
        "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 1e7\nharmonics = 2\nsigma = true\n\n[run]\nmax_periods = 100000000\n",
    );
    let out = d.join("out.json");
    for args in [
        vec!["run", s(&scene), "--json", "-o", s(&out)],
        vec!["check", s(&scene)],
    ] {
        let child = spawn(&args);
        std::thread::sleep(Duration::from_millis(300));
        signal(&child, "INT");
        let o = child.wait_with_output().unwrap();
        assert_eq!(o.status.code(), Some(130), "{args:?}");
        assert_eq!(listing(&d), ["slow.toml"], "{args:?}");
    }
}

/// A refused merge writes nothing and leaves every input byte for byte as
/// it was; an output that is one of the inputs (by another path, or a
/// link) is refused.
#[test]
fn a_refused_merge_leaves_every_input_intact() {
    let d = dir("merge_intact");
    let file = write(&d, "small.toml", SMALL);
    let (a, b) = (d.join("a.csv"), d.join("b.csv"));
    for (shard, out) in [("1/2", &a), ("2/2", &b)] {
        ok(stickslip(&[
            "sweep",
            s(&file),
            "-q",
            "--no-timing",
            "--shard",
            shard,
            "-o",
            s(out),
        ]));
    }
    let timed = d.join("timed.csv");
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--shard",
        "2/2",
        "-o",
        s(&timed),
    ]));
    let text_b = fs::read_to_string(&b).unwrap();
    let truncated = write(&d, "truncated.csv", &text_b[..text_b.len() - 5]);
    let mut fields: Vec<String> = text_b
        .lines()
        .nth(2)
        .unwrap()
        .split(',')
        .map(str::to_owned)
        .collect();
    fields[2] = "NaN".into();
    let nan = write(
        &d,
        "nan.csv",
        &text_b.replacen(text_b.lines().nth(2).unwrap(), &fields.join(","), 1),
    );
    let link = d.join("link.csv");
    fs::hard_link(&a, &link).unwrap();
    let dotted = format!("{}/./a.csv", d.display());

    let inputs = [&a, &b, &timed, &truncated, &nan];
    let before: Vec<Vec<u8>> = inputs.iter().map(|p| fs::read(p).unwrap()).collect();
    let out = d.join("out.csv");
    let refusals: [(Vec<&str>, &str); 7] = [
        (
            vec!["-o", s(&a), s(&a), s(&b)],
            "the output is also an input",
        ),
        (
            vec!["-o", &dotted, s(&a), s(&b)],
            "the output is also an input",
        ),
        (
            vec!["-o", s(&link), s(&a), s(&b)],
            "the output is also an input",
        ),
        (
            vec!["-o", s(&out), s(&a), s(&timed)],
            "timed.csv: has the extra columns wall_time_s",
        ),
        (
            vec!["-o", s(&out), s(&a), s(&truncated)],
            "truncated.csv: line 5: the row is truncated",
        ),
        (
            vec!["-o", s(&out), s(&a), s(&nan)],
            "nan.csv: line 3: harmonics = \"NaN\"",
        ),
        (
            vec!["-o", s(&out), s(&a), s(&b), s(&a)],
            "a.csv: is given twice",
        ),
    ];
    for (args, expected) in refusals {
        let mut all = vec!["merge"];
        all.extend(args);
        let err = failure(stickslip(&all));
        assert!(err.contains(expected), "{all:?}: {err}");
        assert!(!out.exists(), "{all:?} wrote an output");
        for (p, bytes) in inputs.iter().zip(&before) {
            assert_eq!(&fs::read(p).unwrap(), bytes, "{} changed", p.display());
        }
    }
    // The good merge still works.
    ok(stickslip(&["merge", "-o", s(&out), s(&a), s(&b)]));
    assert_eq!(rows(&out), 6);
}

/// A `case` of 1000000000 or 18446744073709551615 made merge
/// allocate by case index. Cases are keys: such a row is refused (no sweep
/// has that many cases) at once, and a real gap of ten million cases is
/// counted, not listed.
#[test]
fn merge_refuses_huge_case_indices_without_allocating_by_index() {
    let d = dir("huge_case");
    let file = write(
        &d,
        "small.toml",
        "[axes]\nlevel = [3]\n[outputs]\nindicators = [\"v_inf\"]\n",
    );
    let a = d.join("a.csv");
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-o",
        s(&a),
    ]));
    let text = fs::read_to_string(&a).unwrap();
    let row = text.lines().nth(2).unwrap();
    let out = d.join("out.csv");
    for case in ["1000000000", "18446744073709551615"] {
        let big = write(
            &d,
            "big.csv",
            &text.replacen(row, &row.replacen('0', case, 1), 1),
        );
        let start = Instant::now();
        let err = failure(stickslip(&["merge", "-o", s(&out), s(&big)]));
        assert!(
            err.contains(&format!(
                "big.csv: line 3: case = \"{case}\": must be a case index below 10000000"
            )),
            "{err}"
        );
        assert!(start.elapsed() < Duration::from_secs(5));
        assert!(!out.exists());
    }
    let far = write(
        &d,
        "far.csv",
        &text.replacen(row, &row.replacen('0', "9999999", 1), 1),
    );
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&far)]));
    assert!(
        err.contains("9999999 of the sweep's 10000000 cases are in no input ([0, 1, 2, 3, 4, 5, 6, 7, 8, 9, ...])"),
        "{err}"
    );
    assert!(!out.exists());
    let err = ok(stickslip(&[
        "merge",
        "-o",
        s(&out),
        s(&far),
        "--allow-partial",
    ]));
    assert!(
        err.contains(
            "9999999 cases of the sweep are in no input: [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, ...]"
        ),
        "{err}"
    );
}

/// A 10^7-case grid aborted at 3.9 GiB. The grid is made case by
/// case: loading it and running a shard of five cases fits in 1 GiB of
/// address space and a few seconds.
#[test]
fn a_ten_million_case_grid_runs_a_shard_in_bounded_memory() {
    let d = dir("big_grid");
    let list = |n: usize, f: &dyn Fn(usize) -> f64| {
        (0..n)
            .map(|i| format!("{:?}", f(i)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let text = format!(
        "[axes]\nmu_static = [{}]\ncontact_force = [{}]\nslider_mass = [{}]\nextra_acceleration = [{}]\n[outputs]\nindicators = [\"v_inf\"]\n",
        list(100, &|i| 0.2 + i as f64 * 1e-4),
        list(100, &|i| 1.0 + i as f64 * 0.01),
        list(100, &|i| 1e-3 + i as f64 * 1e-6),
        list(10, &|i| i as f64 * 0.01),
    );
    let file = write(&d, "big.toml", &text);
    let out = d.join("big.csv");
    let start = Instant::now();
    let o = Command::new("sh")
        .arg("-c")
        .arg(format!(
            "ulimit -v 1048576 && exec '{BIN}' sweep '{}' -q --no-timing --shard 1/2000000 -o '{}'",
            s(&file),
            s(&out)
        ))
        .output()
        .unwrap();
    let err = ok(o);
    assert!(
        err.contains("5 cases in shard 1/2000000 (of 10000000)"),
        "{err}"
    );
    assert!(start.elapsed() < Duration::from_secs(60));
    assert_eq!(
        column(&out, "case"),
        ["0", "2000000", "4000000", "6000000", "8000000"]
    );
    // One more axis value is past the documented limit, refused with the count.
    let file = write(&d, "bigger.toml", &text.replace("[0.0, ", "[0.0, 0.005, "));
    let err = failure(stickslip(&["sweep", s(&file), "-q", "-o", s(&out)]));
    assert!(
        err.contains("11000000 cases, more than the 10000000"),
        "{err}"
    );
}

/// Two sweeps on one output lost rows. The second is refused
/// while the first runs; the first completes every row. A lock file left
/// by a process that is gone does not block.
#[test]
fn a_second_sweep_on_the_same_output_is_refused_while_the_first_runs() {
    let d = dir("two_writers");
    let file = write(&d, "slow.toml", SLOW);
    let out = d.join("out.csv");
    let lock = d.join("out.csv.lock");
    let args = [
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-j",
        "1",
        "-o",
        s(&out),
    ];
    let first = spawn(&args);
    wait_for(Duration::from_secs(60), || rows(&out) >= 1);
    let err = failure(stickslip(&args));
    assert!(
        err.contains(&format!(
            "another stickslip sweep (process {}) is writing it",
            first.id()
        )),
        "{err}"
    );
    let o = first.wait_with_output().unwrap();
    assert!(o.status.success());
    assert_eq!(rows(&out), 16);
    assert!(!lock.exists());

    // A stale lock file (its process is gone, its lock released).
    fs::write(&lock, "4194304").unwrap();
    let err = ok(stickslip(&args));
    assert!(err.contains("16 already written, 0 run"), "{err}");
    assert!(!lock.exists());
}

/// A JSON-lines sweep could not resume from its own output ("row
/// of case 0 has another level"). Values read back bit-identical, so the
/// rerun keeps the row.
#[test]
fn a_jsonl_sweep_resumes_from_its_own_output() {
    let d = dir("jsonl_resume");
    let kappa = 15.270401784289755_f64;
    let file = write(
        &d,
        "k.toml",
        "[axes]\nkappa = [15.270401784289755]\n[outputs]\nformat = \"jsonl\"\nindicators = [\"v_inf\"]\n",
    );
    let out = d.join("k.jsonl");
    let args = ["sweep", s(&file), "-q", "--no-timing", "-o", s(&out)];
    ok(stickslip(&args));
    let text = fs::read_to_string(&out).unwrap();
    let row: serde_json::Value = serde_json::from_str(text.lines().nth(1).unwrap()).unwrap();
    assert_eq!(row["kappa"].as_f64().unwrap().to_bits(), kappa.to_bits());
    let err = ok(stickslip(&args));
    assert!(err.contains("1 already written, 0 run"), "{err}");
    assert_eq!(fs::read_to_string(&out).unwrap(), text);
}

/// Merge copied NaN cells. A cell a sweep cannot write is
/// refused, naming the file, line and column; nothing is written.
#[test]
fn merge_refuses_nan_cells() {
    let d = dir("nan");
    let file = write(&d, "small.toml", SMALL);
    let (csv, jsonl) = (d.join("a.csv"), d.join("a.jsonl"));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-o",
        s(&csv),
    ]));
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-o",
        s(&jsonl),
    ]));
    let out = d.join("out.csv");
    let text = fs::read_to_string(&csv).unwrap();
    let row = text.lines().nth(3).unwrap();
    let bad = write(
        &d,
        "bad.csv",
        &text.replacen(row, &row.replacen(",0,", ",NaN,", 1), 1),
    );
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&bad)]));
    assert!(
        err.contains(
            "bad.csv: line 4: stiction_fraction = \"NaN\": must be a finite number or nothing"
        ),
        "{err}"
    );
    // JSON has no NaN; a string in a number column is refused the same way.
    let text = fs::read_to_string(&jsonl).unwrap();
    let bad = write(
        &d,
        "bad.jsonl",
        &text.replacen("\"period\":", "\"period\":\"NaN\",\"x\":", 1),
    );
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&bad)]));
    assert!(
        err.contains("bad.jsonl: line 2: unknown column \"x\""),
        "{err}"
    );
    let mut first: serde_json::Map<String, serde_json::Value> =
        serde_json::from_str(text.lines().nth(1).unwrap()).unwrap();
    first.insert("events_total".into(), "NaN".into());
    let text = text.replacen(
        text.lines().nth(1).unwrap(),
        &serde_json::Value::Object(first).to_string(),
        1,
    );
    let bad = write(&d, "bad2.jsonl", &text);
    let err = failure(stickslip(&["merge", "-o", s(&out), s(&bad)]));
    assert!(
        err.contains(
            "bad2.jsonl: line 2: events_total = \"NaN\": must be a whole number or nothing"
        ),
        "{err}"
    );
    assert!(!out.exists());
}

/// `sweep -j 4096` hung on a two-case sweep. Workers are capped
/// at the cases and the CPUs, and the pool is local: the command runs
/// in-process several times with different `-j` (a global pool can be
/// built only once).
#[test]
fn jobs_beyond_the_cases_and_cpus_do_not_hang() {
    let d = dir("jobs");
    let file = write(
        &d,
        "two.toml",
        "[axes]\nlevel = [3, 6]\n[outputs]\nindicators = [\"v_inf\"]\n",
    );
    let out = d.join("two.csv");
    let start = Instant::now();
    ok(stickslip(&[
        "sweep",
        s(&file),
        "-q",
        "--no-timing",
        "-j",
        "4096",
        "-o",
        s(&out),
    ]));
    assert!(start.elapsed() < Duration::from_secs(30));
    let reference = fs::read(&out).unwrap();
    for jobs in ["4096", "1", "3"] {
        fs::remove_file(&out).unwrap();
        let (mut o, mut e) = (Vec::new(), Vec::new());
        let mut streams = stickslip::cli::Streams {
            out: &mut o,
            err: &mut e,
        };
        let args = [
            "stickslip",
            "sweep",
            s(&file),
            "-q",
            "--no-timing",
            "-j",
            jobs,
            "-o",
            s(&out),
        ];
        let code = stickslip::cli::main_with(args, &mut streams);
        assert_eq!(code, 0, "-j {jobs}: {}", String::from_utf8_lossy(&e));
        assert_eq!(fs::read(&out).unwrap(), reference);
    }
    let err =
        String::from_utf8_lossy(&stickslip(&["sweep", s(&file), "-j", "0"]).stderr).into_owned();
    assert!(err.contains("-j"), "{err}");
}
