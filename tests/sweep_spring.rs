//! Sweeps of the spring against the slider (docs/model.md section 17;
//! docs/interface.md sections 4 and 5): the `spring.*` axes, the columns
//! of the spring's reading, and the refusals. Each case is a run of a few
//! milliseconds, so the whole file runs in about a second.

mod common;

use common::{failure, ok, s, scratch, stickslip, write};
use std::path::{Path, PathBuf};
use stickslip::characteristic::reference_forces;
use stickslip::spring::{Spring, SpringEnd};
use stickslip::{Indicator, Scene};

/// The columns of the spring's reading and their error estimates
/// (docs/interface.md section 5).
const SPRING_COLUMNS: [&str; 14] = [
    "spring_force_mean",
    "spring_force_max",
    "spring_force_min",
    "spring_position_mean",
    "contact_fraction",
    "orbit_periods",
    "spring_reading_periods",
    "spring_force_mean_range_low",
    "spring_force_mean_range_high",
    "error_spring_force_mean",
    "error_spring_force_max",
    "error_spring_force_min",
    "error_spring_position_mean",
    "error_contact_fraction",
];

/// The default scene (the paper's motor and signal) with `spring`, asking
/// only for the friction energy, and at most `max_periods` periods.
fn spring_scene(spring: Spring, max_periods: u64) -> Scene {
    let mut scene = Scene {
        spring: Some(spring),
        ..Scene::default()
    };
    scene.outputs.indicators = vec![Indicator::FrictionEnergy];
    scene.run.max_periods = max_periods;
    scene
}

fn tied(stiffness: f64) -> Spring {
    Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Tied { preload: 0.0 },
    }
}

fn free(stiffness: f64) -> Spring {
    Spring {
        stiffness,
        damping: 0.0,
        end: SpringEnd::Free { gap: 0.0 },
    }
}

/// A sweep file over `axes` (TOML lines under `[axes]`) of the scene
/// `base`, written beside it.
fn sweep_file(dir: &Path, name: &str, base: &Scene, axes: &str) -> PathBuf {
    write(dir, &format!("{name}_base.toml"), &base.to_toml());
    write(
        dir,
        &format!("{name}.toml"),
        &format!("base = \"{name}_base.toml\"\n[axes]\n{axes}"),
    )
}

/// The rows of a sweep CSV as (column, cell) pairs.
fn csv_rows(path: &Path) -> Vec<Vec<(String, String)>> {
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
                .map(|(k, v)| (k.to_owned(), v.to_owned()))
                .collect()
        })
        .collect()
}

fn cell<'a>(row: &'a [(String, String)], column: &str) -> &'a str {
    row.iter()
        .find(|(k, _)| k == column)
        .map(|(_, v)| v.as_str())
        .unwrap_or_else(|| panic!("no column {column}"))
}

/// A numeric CSV cell as the JSON value it stands for: empty is `null`,
/// a number is read by Rust's exact parser (bit for bit).
fn as_json(cell: &str) -> serde_json::Value {
    if cell.is_empty() {
        serde_json::Value::Null
    } else if let Ok(n) = cell.parse::<u64>() {
        serde_json::json!(n)
    } else {
        serde_json::json!(cell.parse::<f64>().expect("a number"))
    }
}

/// `stickslip run --json` of `scene`, written to `dir`.
fn run_json(dir: &Path, name: &str, scene: &Scene) -> serde_json::Value {
    let path = write(dir, name, &scene.to_toml());
    let out = stickslip(&["run", s(&path), "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// The same number, to the bit (integers and floats alike), or both absent.
fn same(a: &serde_json::Value, b: &serde_json::Value) -> bool {
    match (a.as_f64(), b.as_f64()) {
        (Some(x), Some(y)) => x.to_bits() == y.to_bits(),
        _ => a == b,
    }
}

/// Independent source: a single `stickslip run --json` of the scene with
/// the case's stiffness (and gap) written into its `[spring]`. Every row
/// of a `spring.stiffness` sweep holds, bit for bit, that run's
/// fingerprint, regime and spring reading with its error estimates: a
/// tied spring that locks into an orbit (`orbit_periods` 1, no range, an
/// estimate of each figure) and a stiff free end that locks into none
/// within 300 periods (the reading over the next 64 periods and the range
/// of a single period's mean, `tests/spring_engine.rs`; no estimate).
#[test]
fn each_row_of_a_stiffness_sweep_is_the_single_run_at_that_stiffness() {
    let d = scratch("sweep_spring", "single_runs");
    let sweeps = [
        (
            "tied",
            spring_scene(tied(1e3), 1_000_000),
            "spring.stiffness = [10, 1e3, 1e5]\n",
        ),
        (
            "free",
            spring_scene(free(1e4), 300),
            "spring.stiffness = [1e4, 1e6]\nspring.gap = [0, 1e-6]\n",
        ),
    ];
    let (mut locked, mut unlocked) = (0, 0);
    for (name, base, axes) in sweeps {
        let file = sweep_file(&d, name, &base, axes);
        let out = d.join(format!("{name}.csv"));
        ok(stickslip(&[
            "sweep",
            s(&file),
            "-q",
            "--no-timing",
            "-o",
            s(&out),
        ]));
        for (i, row) in csv_rows(&out).iter().enumerate() {
            for (column, value) in row {
                assert!(
                    !["NaN", "inf", "-inf"].contains(&value.as_str()),
                    "{name} row {i}: {column} = {value}"
                );
            }
            let k: f64 = cell(row, "spring.stiffness").parse().unwrap();
            let mut scene = base.clone();
            let spring = scene.spring.as_mut().unwrap();
            spring.stiffness = k;
            if let SpringEnd::Free { gap } = &mut spring.end {
                *gap = cell(row, "spring.gap").parse().unwrap();
            }
            let json = run_json(&d, &format!("{name}_{i}.toml"), &scene);
            for key in ["scene_hash", "regime"] {
                assert_eq!(Some(cell(row, key)), json[key].as_str(), "{name} k = {k}");
            }
            for key in [
                "friction_energy",
                "spring_force_mean",
                "spring_force_max",
                "spring_force_min",
                "spring_position_mean",
                "contact_fraction",
                "orbit_periods",
                "spring_reading_periods",
                "periods_simulated",
                "last_v_p",
                "f0",
                "period",
            ] {
                assert!(
                    same(&as_json(cell(row, key)), &json[key]),
                    "{name} k = {k}: {key}: sweep {} against run {}",
                    cell(row, key),
                    json[key]
                );
            }
            let range = &json["spring_force_mean_range"];
            for (j, key) in [
                "spring_force_mean_range_low",
                "spring_force_mean_range_high",
            ]
            .into_iter()
            .enumerate()
            {
                assert!(
                    same(&as_json(cell(row, key)), &range[j]),
                    "{name} k = {k}: {key}: sweep {} against run {range}",
                    cell(row, key)
                );
            }
            // Each figure's error estimate: `error_estimate` of the run
            // (empty and null where no orbit locked).
            for key in [
                "spring_force_mean",
                "spring_force_max",
                "spring_force_min",
                "spring_position_mean",
                "contact_fraction",
            ] {
                let column = format!("error_{key}");
                let estimate = &json["error_estimate"][key];
                assert!(
                    same(&as_json(cell(row, &column)), estimate),
                    "{name} k = {k}: {column}: sweep {} against run {estimate}",
                    cell(row, &column)
                );
                assert_eq!(
                    estimate.is_null(),
                    json["orbit_periods"].is_null(),
                    "{name} k = {k}: {key}'s estimate {estimate}"
                );
            }
            // v_inf does not apply against a spring, nor its error.
            assert_eq!(cell(row, "error_v_inf"), "", "{name} k = {k}");
            match json["orbit_periods"].as_u64() {
                Some(_) => locked += 1,
                None => unlocked += 1,
            }
        }
    }
    assert!(
        locked >= 3 && unlocked >= 2,
        "{locked} locked, {unlocked} not"
    );
}

/// Without a `[spring]` a sweep writes none of the spring's columns, and
/// a rerun of a spring sweep reads every cell of its rows back (CSV and
/// JSON lines): it keeps them all and runs nothing.
#[test]
fn the_spring_columns_come_only_with_a_spring_and_read_back() {
    let d = scratch("sweep_spring", "columns");
    let plain = write(&d, "plain.toml", "[axes]\nlevel = [6]\n");
    let out = d.join("plain.csv");
    ok(stickslip(&["sweep", s(&plain), "-q", "-o", s(&out)]));
    let row = &csv_rows(&out)[0];
    for column in SPRING_COLUMNS {
        assert!(
            row.iter().all(|(k, _)| k != column),
            "{column} without a spring"
        );
    }
    assert_ne!(
        cell(row, "error_v_inf"),
        "",
        "v_inf's error without a spring"
    );

    let file = sweep_file(
        &d,
        "free",
        &spring_scene(free(1e4), 300),
        "spring.stiffness = [1e4, 1e6]\n",
    );
    for ext in ["csv", "jsonl"] {
        let out = d.join(format!("free.{ext}"));
        let args = ["sweep", s(&file), "-q", "--no-timing", "-o", s(&out)];
        ok(stickslip(&args));
        let first = std::fs::read_to_string(&out).unwrap();
        for column in SPRING_COLUMNS {
            assert!(first.contains(column), "{ext}: {column}");
        }
        let err = ok(stickslip(&args));
        assert!(err.contains("2 already written, 0 run"), "{ext}: {err}");
        assert_eq!(std::fs::read_to_string(&out).unwrap(), first, "{ext}");
    }
}

/// Soft-spring limit (module docs of `stickslip::bench`; docs/model.md
/// section 17): a tied spring's mean force balances the mean friction,
/// and as `k -> 0` the slider sees a constant load that must hold it, so
/// the mean force tends to the stall force (the weight method,
/// `characteristic::reference_forces` of the scene without the spring)
/// from above, its excess falling with the stiffness (first order in `k`:
/// the independent reference's `1.75e-7` of the stall force at 1 kN/m,
/// so below `1e-8` at 10 N/m).
#[test]
fn a_tied_springs_mean_force_falls_to_the_stall_force_with_the_stiffness() {
    let d = scratch("sweep_spring", "stall");
    let stall = reference_forces(&Scene::default()).unwrap().stall.force;
    let file = sweep_file(
        &d,
        "tied",
        &spring_scene(tied(1e3), 1_000_000),
        "spring.stiffness = [1e4, 1e3, 100, 10]\n",
    );
    let out = d.join("tied.csv");
    ok(stickslip(&["sweep", s(&file), "-q", "-o", s(&out)]));
    let excess: Vec<(f64, f64)> = csv_rows(&out)
        .iter()
        .map(|row| {
            let k: f64 = cell(row, "spring.stiffness").parse().unwrap();
            let mean: f64 = cell(row, "spring_force_mean").parse().unwrap();
            (k, (mean - stall) / stall)
        })
        .collect();
    assert_eq!(excess.len(), 4);
    for pair in excess.windows(2) {
        let ((k0, e0), (k1, e1)) = (pair[0], pair[1]);
        assert!(k1 < k0 && 0.0 < e1 && e1 < e0, "{excess:?}");
    }
    assert!(excess[3].1 < 1e-8, "{excess:?}");
}

/// Bad spring axes are refused before anything runs, in one line naming
/// the sweep file, the axis and (where one is at fault) the value, and
/// leave no output: as the `[spring]` table refuses `gap` on a tied
/// spring and `preload` or damping on a free end.
#[test]
fn bad_spring_axes_are_refused_in_one_line_naming_the_field() {
    let d = scratch("sweep_spring", "refused");
    write(
        &d,
        "tied_base.toml",
        &spring_scene(tied(1e3), 1000).to_toml(),
    );
    write(
        &d,
        "free_base.toml",
        &spring_scene(free(1e4), 1000).to_toml(),
    );
    let cases: &[(&str, &str)] = &[
        (
            "[axes]\nspring.stiffness = [1e3]\n",
            "axes.spring.stiffness: the base scene has no [spring]",
        ),
        (
            "base = \"tied_base.toml\"\n[axes]\nspring.gap = [0]\n",
            "axes.spring.gap: applies to a free end (spring.tied = false)",
        ),
        (
            "base = \"tied_base.toml\"\n[axes]\nspring.stiffness = [10, -100]\n",
            "axes.spring.stiffness[1] = -100: must be positive",
        ),
        (
            "base = \"tied_base.toml\"\n[axes.spring]\nstiffness = [10, nan]\n",
            "axes.spring.stiffness[1] = NaN: must be a finite number",
        ),
        (
            "base = \"tied_base.toml\"\n[axes]\nspring.damping = [-0.1]\n",
            "axes.spring.damping[0] = -0.1: must not be negative",
        ),
        (
            "base = \"free_base.toml\"\n[axes]\nspring.preload = [0.01]\n",
            "axes.spring.preload: applies to a tied spring (spring.tied = true)",
        ),
        (
            "base = \"free_base.toml\"\n[axes]\nspring.gap = [0, -1e-6]\n",
            "axes.spring.gap[1] = -1e-6: must not be negative",
        ),
        (
            "base = \"free_base.toml\"\n[axes]\nspring.damping = [0, 0.1]\n",
            "case 1 (spring.damping = 0.1): spring.damping = 0.1: must be 0 for a free-ended spring",
        ),
        (
            "base = \"tied_base.toml\"\n[axes]\nspring.tied = [false]\n",
            "axes.spring.tied: unknown field `tied`",
        ),
        (
            "base = \"tied_base.toml\"\n[outputs]\nindicators = [\"v_inf\"]\n",
            "outputs.indicators: assumes net travel",
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
