//! Every outcome is a result, with its provenance, and every indicator has
//! one definition: `stickslip run --json` for a run-away, a stuck and a
//! not-converged slider (exit 0, a `regime`, what is known); the version,
//! resolved scene and fingerprint in the JSON; stable event names; the
//! cost split into set-up and simulation; `run.verify_steady_state`
//! changing nothing but adding the cross-check; and the same indicator
//! values from `run --json`, `check` and a sweep row.

mod common;

use common::{stickslip, write};

use serde_json::Value;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

fn dir(name: &str) -> PathBuf {
    common::scratch("outcomes", name)
}

fn run_json(scene: &Path) -> Value {
    let o = stickslip(&["run", scene.to_str().unwrap(), "--json"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8(o.stdout).unwrap();
    assert!(!text.contains("NaN"), "{text}");
    serde_json::from_str(&text).unwrap()
}

fn run_text(scene: &Path) -> String {
    let o = stickslip(&["run", scene.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8(o.stdout).unwrap()
}

/// The paper's motor with a load of 1.5 a_d (a_d = 112 m/s^2, docs/model.md
/// section 6): sliding friction cannot hold it, the slider runs away.
const RUN_AWAY: &str = "[motor]\nslider_mass = 1.4e-3\ncontact_force = 1.0\nmu_static = 0.1736\n\
mu_dynamic = 0.1568\nextra_acceleration = 168.0\n";

#[test]
fn a_run_away_is_a_result() {
    let d = dir("runaway");
    let scene = write(&d, "runaway.toml", RUN_AWAY);
    let v = run_json(&scene);
    assert_eq!(v["regime"], "run-away");
    assert_eq!(v["direction"], "forward");
    // Outside the rod's velocity range, moving forwards: faster than the
    // rod's mean velocity (0) by far.
    assert!(v["final_velocity"].as_f64().unwrap() > 0.0, "{v}");
    assert!(v["periods_simulated"].as_u64().unwrap() >= 1);
    assert!(v["last_v_p"].is_f64());
    for name in ["v_inf", "smoothness", "durability", "friction_energy"] {
        assert!(v[name].is_null(), "{name} of a run-away");
    }
    let text = run_text(&scene);
    assert!(
        text.contains("run-away") && text.contains("keeps accelerating"),
        "{text}"
    );
}

/// The scene that was once listed as bad input (a load of -200 m/s^2
/// against a_d = 112 m/s^2): a run-away backwards is a result, exit 0.
#[test]
fn the_run_away_load_scene_is_a_result() {
    let v = run_json(Path::new("tests/data/runaway_load.toml"));
    assert_eq!(v["regime"], "run-away");
    assert_eq!(v["direction"], "backward");
    assert!(v["final_velocity"].as_f64().unwrap() < 0.0);
}

/// `check` of a scene without a steady state reports the outcome (exit
/// 0) instead of failing: there is nothing to cross-check.
#[test]
fn check_of_a_run_away_is_a_result() {
    let o = stickslip(&["check", "tests/data/runaway_load.toml", "--steps", "50"]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(text.contains("run-away (backward)"), "{text}");
    assert!(text.contains("no steady state to cross-check"), "{text}");
}

/// A rod acceleration far inside the stick band (kappa = 1e-4, as in
/// tests/engine.rs): the slider follows the rod, stuck, and its v_inf is 0
/// within its error estimate (it follows a periodic rod).
#[test]
fn a_stuck_slider_is_a_result() {
    let d = dir("stuck");
    let scene = write(
        &d,
        "stuck.toml",
        "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 1e-4\nharmonics = 5\nsigma = true\n",
    );
    let v = run_json(&scene);
    assert_eq!(v["regime"], "stuck");
    let e = v["error_estimate"]["v_inf"].as_f64().unwrap();
    assert!(v["v_inf"].as_f64().unwrap().abs() <= e, "{v}");
    // No start-up time for a v_inf that is not larger than its error.
    assert!(v["startup_time"].is_null());
}

/// A start-up that cannot reach its limit in 3 periods (the fixed-step
/// engine's steady state is always decided by the start-up).
#[test]
fn a_start_up_that_does_not_converge_is_a_result() {
    let d = dir("notconv");
    let scene = write(
        &d,
        "short.toml",
        "[run]\nmax_periods = 3\nengine = \"fixed\"\nsteps_per_harmonic = 50\n",
    );
    let v = run_json(&scene);
    assert_eq!(v["regime"], "not_converged");
    assert_eq!(v["periods_simulated"].as_u64(), Some(3));
    assert!(v["v_inf"].is_null());
    let bounds = v["v_inf_bounds"].as_array().unwrap();
    assert_eq!(bounds.len(), 2);
    assert!(
        bounds.iter().any(|b| b.as_f64() == v["last_v_p"].as_f64()),
        "{v}"
    );
    assert!(run_text(&scene).contains("not converged"));
}

/// Version, resolved scene and fingerprint, stable event names, and the
/// cost split into set-up and simulation.
#[test]
fn json_is_traceable() {
    let d = dir("trace");
    let scene = write(
        &d,
        "log.toml",
        "[outputs]\nevents = true\nindicators = [\"v_inf\"]\n",
    );
    let v = run_json(&scene);
    assert_eq!(v["stickslip_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(v["scene_hash"].as_str().unwrap().len(), 16);
    // The resolved scene reads back to the same scene (same fingerprint).
    let scene_toml = toml::to_string(&v["scene"]).unwrap();
    let again = stickslip::Scene::from_toml_str(&scene_toml, "<json>").unwrap();
    assert_eq!(
        stickslip::provenance::scene_hash(&again),
        v["scene_hash"].as_str().unwrap()
    );
    let kinds = [
        "stick_to_slip",
        "slip_to_stick",
        "reversal",
        "grazing",
        "jump",
        "contact_start",
        "contact_end",
    ];
    let log = v["event_log"].as_array().unwrap();
    assert!(!log.is_empty());
    for e in log {
        assert!(kinds.contains(&e["kind"].as_str().unwrap()), "{e}");
    }
    let (wall, setup, sim) = (
        v["wall_time_s"].as_f64().unwrap(),
        v["setup_time_s"].as_f64().unwrap(),
        v["simulation_time_s"].as_f64().unwrap(),
    );
    assert!(
        setup > 0.0 && sim > 0.0 && wall >= setup + sim,
        "{wall} {setup} {sim}"
    );
}

/// `run.verify_steady_state = true` adds the cross-check and changes no
/// other reported value; the cost keys (times, work, periods simulated)
/// grow with the longer start-up.
#[test]
fn verification_changes_no_reported_value() {
    let d = dir("verify");
    let base = "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 1.0\nharmonics = 3\nsigma = false\n\
                [outputs]\nevents = true\n";
    let plain = run_json(&write(&d, "plain.toml", base));
    let checked = run_json(&write(
        &d,
        "checked.toml",
        &format!("{base}[run]\nverify_steady_state = true\n"),
    ));
    assert_eq!(checked["steady_state_check"]["agrees"], true);
    assert!(checked["v_inf_transient"].is_f64());
    let strip = |v: &Value| {
        let mut m = v.as_object().unwrap().clone();
        for key in [
            "wall_time_s",
            "setup_time_s",
            "simulation_time_s",
            "work",
            "periods_simulated",
            "v_inf_transient",
            "steady_state_check",
            "scene",
            "scene_hash",
        ] {
            m.remove(key);
        }
        m
    };
    assert_eq!(strip(&plain), strip(&checked));
    assert!(plain.get("v_inf_transient").is_none());
}

/// Row of a CSV file by column name.
fn csv_row(path: &Path) -> HashMap<String, String> {
    // The first line is the `# stickslip_version = ...` header comment.
    let mut reader = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .unwrap();
    let headers = reader.headers().unwrap().clone();
    let record = reader.records().next().unwrap().unwrap();
    headers
        .iter()
        .zip(record.iter())
        .map(|(h, v)| (h.to_owned(), v.to_owned()))
        .collect()
}

/// The event engine's value of an indicator in `check`'s table: the line
/// `  event <value> ± <error>` after the header `<name> (<unit>)`.
fn check_value(text: &str, name: &str) -> (f64, String) {
    let mut lines = text.lines();
    let header = lines
        .find(|l| l.starts_with(&format!("{name} (")))
        .unwrap_or_else(|| panic!("no {name} in check:\n{text}"));
    let rest = header[name.len() + 2..].split(", order").next().unwrap();
    let unit = rest.strip_suffix(')').unwrap().to_owned();
    let event = lines.find(|l| l.trim_start().starts_with("event")).unwrap();
    (
        event.split_whitespace().nth(1).unwrap().parse().unwrap(),
        unit,
    )
}

/// One scene (the paper's motor and actuator, n = 4 with sigma at
/// kappa = 0.5: stick phases in every period, so every indicator is
/// non-trivial) through
/// `run --json`, `check` and a one-case sweep: each indicator has the same
/// value everywhere (check prints 16 digits), and friction energy the same
/// unit, J per period.
#[test]
fn one_definition_per_indicator() {
    let d = dir("definitions");
    let scene_text = "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nkappa = 0.5\nharmonics = 4\nsigma = true\n\
                      [actuator]\nmass = 3.2e-3\ndamping = 9.50\nstiffness = 24.6e6\n\
                      transfer_factor = 1.985\ncapacitance = 800e-9\n";
    let scene = write(&d, "scene.toml", scene_text);
    let v = run_json(&scene);
    let o = stickslip(&["check", scene.to_str().unwrap(), "--steps", "500"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let check = String::from_utf8(o.stdout).unwrap();
    let sweep = write(
        &d,
        "sweep.toml",
        "base = \"scene.toml\"\n[axes]\nkappa = [0.5]\n",
    );
    let out = d.join("rows.csv");
    let o = stickslip(&[
        "sweep",
        sweep.to_str().unwrap(),
        "--quiet",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let row = csv_row(&out);
    let names = [
        "v_inf",
        "startup_time",
        "smoothness",
        "durability",
        "friction_energy",
        "stiction_fraction",
        "stiction_fraction_steady",
        "velocity_per_power",
    ];
    let run_text = run_text(&scene);
    for name in names {
        let from_run = v[name].as_f64().unwrap_or_else(|| panic!("{name} in run"));
        let (from_check, unit) = check_value(&check, name);
        let from_sweep: f64 = row[name]
            .parse()
            .unwrap_or_else(|_| panic!("{name} in sweep"));
        let scale = from_run.abs().max(1e-300);
        assert!(
            (from_check - from_run).abs() <= 1e-15 * scale,
            "{name}: check {from_check} run {from_run}"
        );
        assert_eq!(from_sweep, from_run, "{name}: sweep");
        if name == "friction_energy" {
            assert_eq!(unit, "J (per period)");
            assert!(run_text.contains("J (per period)"));
        }
    }
    assert!(v["stiction_fraction"].as_f64().unwrap() > 0.0);
}
