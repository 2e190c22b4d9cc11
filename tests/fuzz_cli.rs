//! The command line fuzzed through the binary's own code path
//! ([`stickslip::cli::main_with`], which `src/main.rs` only calls).
//!
//! Seeded mutations of valid inputs: numbers set to 0, negative, 1e-300,
//! 5e-324, 1e300, nan and inf; wrong types; missing, duplicated and unknown
//! fields; huge arrays; garbage bytes and truncated files. For every case:
//! no panic, the exit status is 0 (a result) or 1 (one error line naming
//! the problem), a result holds no NaN, an error leaves no output file, and
//! no temporary file is ever left behind.
//!
//! The seed is fixed so that CI is reproducible; `STICKSLIP_FUZZ_SEED=<n>`
//! explores other inputs and `STICKSLIP_FUZZ_SCENES=<n>` sets the count.

use rand::rngs::StdRng;
use rand::{RngExt, SeedableRng};
use std::panic::AssertUnwindSafe;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use stickslip::cli::{Streams, main_with};
use toml::{Table, Value};

/// Mutated scene files per run.
const SCENES: usize = 10_000;

/// A case that takes longer than this is a hang, not a slow scene: every
/// run honours the time limit given to it (`--time-limit`, far below).
const HANG: Duration = Duration::from_secs(20);

fn seed() -> u64 {
    std::env::var("STICKSLIP_FUZZ_SEED")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(20_261_123)
}

fn count(default: usize) -> usize {
    std::env::var("STICKSLIP_FUZZ_SCENES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(default)
}

/// What one invocation did.
struct Outcome {
    status: u8,
    out: String,
    err: String,
    elapsed: Duration,
}

/// Runs the command line in-process; a panic fails the test with the input.
fn invoke(args: &[&str], input: &str) -> Outcome {
    let mut out = Vec::new();
    let mut err = Vec::new();
    let clock = Instant::now();
    let status = std::panic::catch_unwind(AssertUnwindSafe(|| {
        let mut streams = Streams {
            out: &mut out,
            err: &mut err,
        };
        let mut argv = vec!["stickslip"];
        argv.extend_from_slice(args);
        main_with(argv, &mut streams)
    }))
    .unwrap_or_else(|_| panic!("panic on {args:?} with input:\n{input}"));
    Outcome {
        status,
        out: String::from_utf8_lossy(&out).into_owned(),
        err: String::from_utf8_lossy(&err).into_owned(),
        elapsed: clock.elapsed(),
    }
}

/// A scratch directory of this test.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-fuzz-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The files in `dir`, sorted.
fn files(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// The error stream of a failed invocation: warnings, then exactly one
/// error line.
fn assert_one_error_line(o: &Outcome, input: &str) {
    let lines: Vec<&str> = o
        .err
        .lines()
        .filter(|l| !l.starts_with("stickslip: warning:"))
        .collect();
    assert!(
        lines.len() == 1 && lines[0].starts_with("stickslip: ") && lines[0].len() < 2000,
        "not one error line: {:?}\ninput:\n{input}",
        o.err
    );
}

/// No number in a JSON value is NaN or infinite (serde_json cannot even
/// write them; a `null` stands for a value that does not exist).
fn assert_finite(v: &serde_json::Value, input: &str) {
    match v {
        serde_json::Value::Number(n) => {
            assert!(n.as_f64().is_some_and(f64::is_finite), "{n} in\n{input}")
        }
        serde_json::Value::Array(a) => a.iter().for_each(|x| assert_finite(x, input)),
        serde_json::Value::Object(m) => m.values().for_each(|x| assert_finite(x, input)),
        _ => {}
    }
}

/// Special numbers every numeric field is tried with.
fn special_number(rng: &mut StdRng) -> Value {
    let floats = [
        0.0,
        -0.0,
        -1.0,
        -2.5e-6,
        1e-300,
        5e-324,
        -5e-324,
        1e300,
        -1e300,
        f64::NAN,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::MAX,
        f64::MIN_POSITIVE,
    ];
    let integers = [0, -1, 1, 4_294_967_295, 4_294_967_296, i64::MAX, i64::MIN];
    if rng.random_bool(0.7) {
        Value::Float(floats[rng.random_range(0..floats.len())])
    } else {
        Value::Integer(integers[rng.random_range(0..integers.len())])
    }
}

/// A value of a type the field does not have.
fn wrong_type(rng: &mut StdRng) -> Value {
    match rng.random_range(0..5) {
        0 => Value::String("25 um".into()),
        1 => Value::Boolean(true),
        2 => Value::Array(vec![Value::Integer(1), Value::String("x".into())]),
        3 => Value::Table(Table::new()),
        _ => Value::String(String::new()),
    }
}

/// A huge array: of numbers, of special numbers or of strings.
fn huge_array(rng: &mut StdRng) -> Value {
    let len = rng.random_range(1_000..20_000);
    let item = match rng.random_range(0..3) {
        0 => Value::Float(1e-6),
        1 => special_number(rng),
        _ => Value::String("v_inf".into()),
    };
    Value::Array(vec![item; len])
}

/// Every `(table, key)` path of a parsed file, top-level keys with an
/// empty table name.
fn paths(table: &Table) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for (k, v) in table {
        match v {
            Value::Table(t) => out.extend(t.keys().map(|kk| (k.clone(), kk.clone()))),
            _ => out.push((String::new(), k.clone())),
        }
    }
    out
}

fn slot<'a>(table: &'a mut Table, path: &(String, String)) -> &'a mut Table {
    if path.0.is_empty() {
        table
    } else {
        table
            .get_mut(&path.0)
            .and_then(Value::as_table_mut)
            .expect("path from paths()")
    }
}

/// One structural mutation of a parsed file.
fn mutate_table(rng: &mut StdRng, table: &mut Table) {
    let all = paths(table);
    if all.is_empty() {
        return;
    }
    let path = all[rng.random_range(0..all.len())].clone();
    let target = slot(table, &path);
    match rng.random_range(0..10) {
        0..=3 => {
            target.insert(path.1, special_number(rng));
        }
        4 => {
            target.insert(path.1, wrong_type(rng));
        }
        5 => {
            target.remove(&path.1);
        }
        6 => {
            target.insert("colour".into(), Value::Integer(1));
        }
        7 => {
            target.insert(path.1, huge_array(rng));
        }
        8 => {
            // A whole table missing, or an unknown one.
            if path.0.is_empty() || rng.random_bool(0.5) {
                table.insert("extras".into(), Value::Table(Table::new()));
            } else {
                table.remove(&path.0);
            }
        }
        _ => {
            // A number of the right kind far from the default.
            let scale = 10f64.powi(rng.random_range(-12..12));
            if let Some(Value::Float(x)) = target.get(&path.1).cloned() {
                target.insert(path.1, Value::Float(x * scale));
            }
        }
    }
}

/// Byte-level damage: a duplicated line, a truncation, garbage bytes.
fn damage_text(rng: &mut StdRng, text: &str) -> Vec<u8> {
    let mut bytes = text.as_bytes().to_vec();
    match rng.random_range(0..4) {
        0 => {
            // Duplicate a `key = value` line (a duplicated field).
            let lines: Vec<&str> = text.lines().collect();
            let keyed: Vec<usize> = (0..lines.len())
                .filter(|&i| lines[i].contains(" = "))
                .collect();
            if let Some(&i) = keyed.get(rng.random_range(0..keyed.len().max(1))) {
                let mut out: Vec<&str> = lines.clone();
                out.insert(i + 1, lines[i]);
                bytes = out.join("\n").into_bytes();
            }
        }
        1 => bytes.truncate(rng.random_range(0..=bytes.len())),
        2 => {
            for _ in 0..rng.random_range(1..8) {
                let at = rng.random_range(0..=bytes.len());
                bytes.insert(at, rng.random());
            }
        }
        _ => {
            bytes = (0..rng.random_range(0..4096))
                .map(|_| rng.random())
                .collect();
        }
    }
    bytes
}

/// The scenes users start from: the default and the examples.
fn base_scenes() -> Vec<String> {
    let mut out = vec![stickslip::Scene::default().to_toml()];
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let mut names: Vec<PathBuf> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    names.sort();
    for path in names {
        out.push(std::fs::read_to_string(&path).unwrap());
    }
    assert!(
        out.len() >= 5,
        "example scenes missing in {}",
        dir.display()
    );
    out
}

/// A mutated scene file.
fn mutated_scene(rng: &mut StdRng, bases: &[String]) -> Vec<u8> {
    let base = &bases[rng.random_range(0..bases.len())];
    let mut table: Table = base.parse().expect("example scenes parse");
    for _ in 0..rng.random_range(1..=3) {
        mutate_table(rng, &mut table);
    }
    let text = toml::to_string(&table).expect("a table serialises");
    if rng.random_bool(0.15) {
        damage_text(rng, &text)
    } else {
        text.into_bytes()
    }
}

#[test]
fn mutated_scenes_give_a_result_or_one_error_line() {
    let mut rng = StdRng::seed_from_u64(seed());
    let bases = base_scenes();
    let dir = scratch("scenes");
    let scene = dir.join("scene.toml");
    let output = dir.join("out.json");
    let (mut results, mut errors) = (0usize, 0usize);
    let mut slowest = (Duration::ZERO, String::new());
    for _ in 0..count(SCENES) {
        let bytes = mutated_scene(&mut rng, &bases);
        let input = String::from_utf8_lossy(&bytes)
            .chars()
            .take(3000)
            .collect::<String>();
        std::fs::write(&scene, &bytes).unwrap();
        let _ = std::fs::remove_file(&output);
        let o = invoke(
            &[
                "run",
                scene.to_str().unwrap(),
                "--json",
                "--quiet",
                "--time-limit",
                "0.5",
                "-o",
                output.to_str().unwrap(),
            ],
            &input,
        );
        assert!(o.elapsed < HANG, "took {:?} on\n{input}", o.elapsed);
        if o.elapsed > slowest.0 {
            slowest = (o.elapsed, input.clone());
        }
        match o.status {
            0 => {
                results += 1;
                let json = std::fs::read_to_string(&output)
                    .unwrap_or_else(|e| panic!("exit 0 without output ({e}) on\n{input}"));
                let value: serde_json::Value = serde_json::from_str(&json)
                    .unwrap_or_else(|e| panic!("output is not JSON ({e}) on\n{input}"));
                assert_finite(&value, &input);
                assert!(value.get("regime").is_some(), "no regime on\n{input}");
                assert!(o.out.is_empty(), "stdout used despite -o on\n{input}");
                assert_eq!(files(&dir), ["out.json", "scene.toml"], "on\n{input}");
            }
            1 => {
                errors += 1;
                assert_one_error_line(&o, &input);
                assert_eq!(files(&dir), ["scene.toml"], "on\n{input}");
            }
            s => panic!("exit status {s} ({}) on\n{input}", o.err),
        }
        // The input is never touched.
        assert_eq!(std::fs::read(&scene).unwrap(), bytes);
    }
    eprintln!(
        "{results} results, {errors} errors; slowest case {:?}",
        slowest.0
    );
    // Both kinds occur, or the mutations test nothing.
    assert!(
        results > 100 && errors > 100,
        "{results} results, {errors} errors"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Mutated sweep files and mutated merge inputs per run.
const SWEEPS: usize = 1_000;

/// A small sweep: four cases of the paper's motor, each run bounded by a
/// time limit in its base scene.
fn sweep_text(dir: &Path) -> String {
    let mut base: Table = stickslip::Scene::default().to_toml().parse().unwrap();
    let run = base
        .get_mut("run")
        .and_then(Value::as_table_mut)
        .expect("the default scene has a [run] table");
    run.insert("time_limit_s".into(), Value::Float(2.0));
    let base_path = dir.join("base.toml");
    std::fs::write(&base_path, toml::to_string(&base).unwrap()).unwrap();
    format!(
        "base = {:?}\n\n[axes]\nharmonics = [2, 3]\nsigma = [false, true]\n\n\
         [outputs]\nindicators = [\"v_inf\", \"startup_time\", \"smoothness\"]\nformat = \"csv\"\n",
        base_path.to_str().unwrap()
    )
}

/// Every cell of a sweep CSV (after its `#` header line) but the failure
/// text is a finite number, a boolean, a hash or empty: never NaN or inf.
fn assert_clean_csv(text: &str, input: &str) {
    let mut lines = text.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    for line in lines {
        for (cell, name) in line.split(',').zip(&header) {
            if *name == "failure" {
                continue;
            }
            let lower = cell.to_ascii_lowercase();
            assert!(
                !(lower == "nan" || lower.ends_with("inf") || lower.contains("nan")),
                "cell {cell:?} in\n{text}\nfrom\n{input}"
            );
        }
    }
}

/// No temporary or lock file is left in `dir`.
fn assert_no_leftovers(dir: &Path, input: &str) {
    for name in files(dir) {
        assert!(
            !name.ends_with(".tmp") && !name.ends_with(".lock"),
            "{name} left behind by\n{input}"
        );
    }
}

#[test]
fn mutated_sweeps_give_rows_or_one_error_line() {
    let mut rng = StdRng::seed_from_u64(seed() ^ 0x5eed);
    let dir = scratch("sweeps");
    let base = sweep_text(&dir);
    let file = dir.join("sweep.toml");
    let output = dir.join("out.csv");
    let (mut ok, mut errors) = (0usize, 0usize);
    for _ in 0..count(SWEEPS) {
        let mut table: Table = base.parse().unwrap();
        for _ in 0..rng.random_range(1..=2) {
            mutate_table(&mut rng, &mut table);
        }
        let text = toml::to_string(&table).unwrap();
        let bytes = if rng.random_bool(0.15) {
            damage_text(&mut rng, &text)
        } else {
            text.into_bytes()
        };
        let input = String::from_utf8_lossy(&bytes)
            .chars()
            .take(3000)
            .collect::<String>();
        std::fs::write(&file, &bytes).unwrap();
        let _ = std::fs::remove_file(&output);
        let o = invoke(
            &[
                "sweep",
                file.to_str().unwrap(),
                "-o",
                output.to_str().unwrap(),
                "--no-timing",
                "-q",
                "-j",
                "1",
            ],
            &input,
        );
        assert!(o.elapsed < HANG, "took {:?} on\n{input}", o.elapsed);
        match o.status {
            0 => {
                ok += 1;
                let csv = std::fs::read_to_string(&output)
                    .unwrap_or_else(|e| panic!("exit 0 without output ({e}) on\n{input}"));
                assert_clean_csv(&csv, &input);
            }
            1 => {
                errors += 1;
                assert_one_error_line(&o, &input);
                assert!(
                    !output.exists(),
                    "output left by a failed sweep of\n{input}"
                );
            }
            s => panic!("exit status {s} ({}) on\n{input}", o.err),
        }
        assert_no_leftovers(&dir, &input);
        assert_eq!(std::fs::read(&file).unwrap(), bytes, "input changed");
    }
    eprintln!("{ok} sweeps ran, {errors} refused");
    assert!(ok > 20 && errors > 100, "{ok} sweeps ran, {errors} refused");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Damages a sweep output the way a crash, an editor or another tool
/// might: a cell replaced, a line lost, doubled or cut, a column dropped,
/// garbage.
fn damage_shard(rng: &mut StdRng, text: &str) -> Vec<u8> {
    let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
    let body = 2..lines.len().max(3);
    match rng.random_range(0..6) {
        0 => {
            let cells = [
                "NaN",
                "nan",
                "inf",
                "-inf",
                "1e300",
                "",
                "x",
                "-1",
                "1000000000",
                "18446744073709551615",
                "0.5",
                "true",
            ];
            let i = rng.random_range(body.clone()).min(lines.len() - 1);
            let mut row: Vec<String> = lines[i].split(',').map(str::to_owned).collect();
            let j = rng.random_range(0..row.len());
            row[j] = cells[rng.random_range(0..cells.len())].to_owned();
            lines[i] = row.join(",");
        }
        1 => {
            let i = rng.random_range(0..lines.len());
            lines.remove(i);
        }
        2 => {
            let i = rng.random_range(0..lines.len());
            let copy = lines[i].clone();
            lines.insert(i, copy);
        }
        3 => {
            // A column dropped from every line after the comment.
            let j = rng.random_range(0..lines[1].split(',').count());
            for line in lines.iter_mut().skip(1) {
                let mut row: Vec<&str> = line.split(',').collect();
                if j < row.len() {
                    row.remove(j);
                }
                *line = row.join(",");
            }
        }
        4 => {
            let mut bytes = (lines.join("\n") + "\n").into_bytes();
            bytes.truncate(rng.random_range(0..=bytes.len()));
            return bytes;
        }
        _ => return damage_text(rng, text),
    }
    (lines.join("\n") + "\n").into_bytes()
}

#[test]
fn mutated_merge_inputs_merge_or_leave_everything_as_it_was() {
    let mut rng = StdRng::seed_from_u64(seed() ^ 0x3e63);
    let dir = scratch("merge");
    let file = dir.join("sweep.toml");
    std::fs::write(&file, sweep_text(&dir)).unwrap();
    let shards: Vec<String> = (1..=2)
        .map(|i| {
            let out = dir.join(format!("shard{i}.csv"));
            let shard = format!("{i}/2");
            let o = invoke(
                &[
                    "sweep",
                    file.to_str().unwrap(),
                    "--shard",
                    &shard,
                    "-o",
                    out.to_str().unwrap(),
                    "--no-timing",
                    "-q",
                ],
                "shard",
            );
            assert_eq!(o.status, 0, "{}", o.err);
            std::fs::read_to_string(out).unwrap()
        })
        .collect();
    let (a, b, merged) = (dir.join("a.csv"), dir.join("b.csv"), dir.join("m.csv"));
    let (mut ok, mut refused) = (0usize, 0usize);
    for round in 0..count(SWEEPS) {
        let first = if rng.random_bool(0.8) {
            damage_shard(&mut rng, &shards[0])
        } else {
            shards[0].clone().into_bytes()
        };
        let second = shards[1].clone().into_bytes();
        let input = String::from_utf8_lossy(&first)
            .chars()
            .take(3000)
            .collect::<String>();
        std::fs::write(&a, &first).unwrap();
        std::fs::write(&b, &second).unwrap();
        let _ = std::fs::remove_file(&merged);
        // Now and then the output is one of the inputs.
        let target = if round % 50 == 0 { &b } else { &merged };
        let o = invoke(
            &[
                "merge",
                "-o",
                target.to_str().unwrap(),
                a.to_str().unwrap(),
                b.to_str().unwrap(),
            ],
            &input,
        );
        match o.status {
            0 => {
                ok += 1;
                assert!(target == &merged, "merge over an input accepted");
                assert_clean_csv(&std::fs::read_to_string(&merged).unwrap(), &input);
            }
            1 => {
                refused += 1;
                assert_one_error_line(&o, &input);
                assert!(
                    !merged.exists(),
                    "output left by a refused merge of\n{input}"
                );
            }
            s => panic!("exit status {s} ({}) on\n{input}", o.err),
        }
        // The inputs are intact whatever happened.
        assert_eq!(std::fs::read(&a).unwrap(), first);
        assert_eq!(std::fs::read(&b).unwrap(), second);
        assert_no_leftovers(&dir, &input);
    }
    eprintln!("{ok} merges, {refused} refused");
    assert!(ok > 50 && refused > 100, "{ok} merges, {refused} refused");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A writer that fails like a closed pipe or a full disk.
struct Failing(std::io::ErrorKind);

impl std::io::Write for Failing {
    fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
        Err(std::io::Error::from(self.0))
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Err(std::io::Error::from(self.0))
    }
}

#[test]
fn output_faults_closed_pipe_full_disk_output_over_input() {
    let mut rng = StdRng::seed_from_u64(seed() ^ 0xfa17);
    let bases = base_scenes();
    let dir = scratch("faults");
    let scene = dir.join("scene.toml");
    for _ in 0..200 {
        let bytes = mutated_scene(&mut rng, &bases);
        let input = String::from_utf8_lossy(&bytes)
            .chars()
            .take(3000)
            .collect::<String>();
        std::fs::write(&scene, &bytes).unwrap();
        let path = scene.to_str().unwrap();
        // A closed pipe: the reader has gone, the command ends quietly
        // (exit 0) or reports the scene's own error (exit 1).
        for (kind, allowed) in [
            (std::io::ErrorKind::BrokenPipe, [0u8, 1]),
            (std::io::ErrorKind::StorageFull, [1, 1]),
        ] {
            let mut out = Failing(kind);
            let mut err = Vec::new();
            let status = std::panic::catch_unwind(AssertUnwindSafe(|| {
                let mut streams = Streams {
                    out: &mut out,
                    err: &mut err,
                };
                main_with(
                    [
                        "stickslip",
                        "run",
                        path,
                        "--json",
                        "-q",
                        "--time-limit",
                        "2",
                    ],
                    &mut streams,
                )
            }))
            .unwrap_or_else(|_| panic!("panic with {kind:?} on\n{input}"));
            assert!(
                allowed.contains(&status),
                "{kind:?}: exit {status} on\n{input}"
            );
            let err = String::from_utf8_lossy(&err).into_owned();
            let o = Outcome {
                status,
                out: String::new(),
                err,
                elapsed: Duration::ZERO,
            };
            if status == 1 {
                assert_one_error_line(&o, &input);
            }
        }
        // The output named as the input: refused, the input untouched.
        let o = invoke(&["run", path, "--json", "-q", "-o", path], &input);
        assert_eq!(o.status, 1, "output over input accepted:\n{input}");
        assert_one_error_line(&o, &input);
        assert_eq!(std::fs::read(&scene).unwrap(), bytes);
        assert_no_leftovers(&dir, &input);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn concurrent_sweeps_on_one_output_keep_every_row() {
    let dir = scratch("concurrent");
    let file = dir.join("sweep.toml");
    std::fs::write(&file, sweep_text(&dir)).unwrap();
    let output = dir.join("out.csv");
    let reference = {
        let out = dir.join("reference.csv");
        let o = invoke(
            &[
                "sweep",
                file.to_str().unwrap(),
                "-o",
                out.to_str().unwrap(),
                "--no-timing",
                "-q",
            ],
            "reference",
        );
        assert_eq!(o.status, 0, "{}", o.err);
        std::fs::read_to_string(out).unwrap()
    };
    for _ in 0..10 {
        let _ = std::fs::remove_file(&output);
        let statuses: Vec<(u8, String)> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..2)
                .map(|_| {
                    s.spawn(|| {
                        let o = invoke(
                            &[
                                "sweep",
                                file.to_str().unwrap(),
                                "-o",
                                output.to_str().unwrap(),
                                "--no-timing",
                                "-q",
                                "-j",
                                "1",
                            ],
                            "concurrent",
                        );
                        (o.status, o.err)
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        // Either both finished (one after the other) or the second was
        // refused naming the lock; in every case no row is lost.
        for (status, err) in &statuses {
            assert!(
                *status == 0 || (*status == 1 && err.contains("lock")),
                "{status}: {err}"
            );
        }
        assert!(statuses.iter().any(|(s, _)| *s == 0));
        assert_eq!(std::fs::read_to_string(&output).unwrap(), reference);
        assert_no_leftovers(&dir, "concurrent");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
