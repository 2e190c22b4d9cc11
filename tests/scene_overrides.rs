//! Scenes as users pass them on the command line: from standard input
//! (`-`), and with single fields overridden (`--set PATH=VALUE`,
//! docs/interface.md section 2), checked as if the file held them.

mod common;

use common::{failure, ok, s, scratch, stickslip, write};
use std::io::Write;
use std::process::{Command, Stdio};

/// The binary with `input` on its standard input.
fn stickslip_with_stdin(args: &[&str], input: &str) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(input.as_bytes())
        .unwrap();
    child.wait_with_output().unwrap()
}

fn json(o: &std::process::Output) -> serde_json::Value {
    serde_json::from_slice(&o.stdout).expect("JSON on standard output")
}

/// `--set` gives the same run as a file that holds the value: the same
/// resolved scene (its fingerprint) and the same numbers, to the bit.
#[test]
fn an_override_runs_as_the_file_that_holds_it() {
    let dir = scratch("overrides", "as_file");
    let mut scene = stickslip::Scene::default();
    scene.motor.slider_mass = 5e-3;
    scene.signal = stickslip::SignalSpec::fourier(25e-6, 9.0, 2, true);
    scene.outputs.indicators = vec![stickslip::Indicator::VInf];
    let edited = write(&dir, "edited.toml", &scene.to_toml());
    let mut base = stickslip::Scene::default();
    base.outputs.indicators = vec![stickslip::Indicator::VInf];
    let base = write(&dir, "base.toml", &base.to_toml());
    let from_file = stickslip(&["run", s(&edited), "--json", "-q"]);
    let overridden = stickslip(&[
        "run",
        s(&base),
        "--json",
        "-q",
        "--set",
        "motor.slider_mass=5e-3",
        "--set",
        "signal.sqrt_kappa=3",
    ]);
    ok(from_file.clone());
    ok(overridden.clone());
    let (a, b) = (json(&from_file), json(&overridden));
    assert_eq!(a["scene_hash"], b["scene_hash"]);
    assert_eq!(a["v_inf"], b["v_inf"]);
    assert_eq!(b["scene"]["motor"]["slider_mass"], 5e-3);
}

/// A scene on standard input (`-`) runs as the same scene from a file.
#[test]
fn a_scene_on_standard_input_runs_as_from_a_file() {
    let text = stickslip::Scene::default().to_toml();
    let dir = scratch("overrides", "stdin");
    let file = write(&dir, "scene.toml", &text);
    let from_stdin = stickslip_with_stdin(&["run", "-", "--json", "-q"], &text);
    let from_file = stickslip(&["run", s(&file), "--json", "-q"]);
    ok(from_stdin.clone());
    assert_eq!(
        json(&from_stdin)["scene_hash"],
        json(&from_file)["scene_hash"]
    );
    assert_eq!(json(&from_stdin)["v_inf"], json(&from_file)["v_inf"]);
    // A bad scene on standard input is named as such.
    let mut bad = stickslip::Scene::default();
    bad.motor.slider_mass = -1.0;
    let err = failure(stickslip_with_stdin(&["run", "-"], &bad.to_toml()));
    assert!(
        err.contains("<stdin>") && err.contains("slider_mass"),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
}

/// `f_0` grows with `sqrt(kappa)` at a fixed stroke and motor
/// (`kappa = a_R / a_0` with `a_R = (2 pi f_0)^2 x`, docs/model.md
/// section 2): `signal --set signal.sqrt_kappa=3` halves the default's
/// `f_0` (`sqrt(kappa) = 6`). Setting `sqrt_kappa` on a scene that gives
/// `kappa` replaces it rather than giving both.
#[test]
fn the_signal_command_takes_overrides_and_one_drive_field_replaces_the_other() {
    let default = stickslip(&["signal", "--json"]);
    let halved = stickslip(&["signal", "--json", "--set", "signal.sqrt_kappa=3"]);
    let f = |o: &std::process::Output| json(o)["f0"].as_f64().expect("f0");
    let ratio = f(&default) / f(&halved);
    assert!((ratio - 2.0).abs() < 1e-12, "{ratio}");
    // The default scene is written with `kappa`.
    assert!(
        stickslip::Scene::default()
            .to_toml()
            .contains("kappa = 36.0")
    );
}

/// Every command that reads a scene applies the overrides before it
/// checks the scene: an override that breaks it is the one-line error of
/// a file that holds the value, naming the override, and nothing is
/// written.
#[test]
fn every_command_that_reads_a_scene_checks_its_overrides() {
    let dir = scratch("overrides", "every_command");
    let sweep = write(&dir, "grid.toml", "[axes]\nsigma = [false, true]\n");
    let out = dir.join("out");
    let figure = dir.join("figure.svg");
    let data = "tests/data/compare/fixed_1119.csv";
    let bad = ["--set", "motor.slider_mass=-1"];
    let commands: Vec<Vec<&str>> = vec![
        vec!["run", "-o", s(&out)],
        vec!["check"],
        vec!["signal"],
        vec!["characteristic", "-o", s(&out)],
        vec!["optimize", "-o", s(&out)],
        vec![
            "plot",
            "examples/scenes/paper_default.toml",
            "-o",
            s(&figure),
        ],
        vec!["compare", "examples/scenes/paper_default.toml", data],
        vec!["sweep", s(&sweep), "-o", s(&out)],
    ];
    for mut args in commands {
        args.extend(bad);
        let o = stickslip(&args);
        let err = failure(o.clone());
        assert!(
            err.contains("--set motor.slider_mass=-1")
                && err.contains("motor.slider_mass = -1: must be positive"),
            "{args:?}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}");
        assert!(!out.exists() && !figure.exists(), "{args:?}");
    }
}

/// The sweep's base scene takes the overrides before the axes: each row's
/// scene is the one a base file holding the value gives.
#[test]
fn a_sweep_applies_overrides_to_its_base_scene() {
    let dir = scratch("overrides", "sweep");
    let mut base = stickslip::Scene::default();
    base.motor.slider_mass = 2e-3;
    let base_file = write(&dir, "base.toml", &base.to_toml());
    let with_base = write(
        &dir,
        "with_base.toml",
        "base = \"base.toml\"\n[axes]\nsigma = [false, true]\n[outputs]\nindicators = [\"v_inf\"]\n",
    );
    let without = write(
        &dir,
        "without.toml",
        "[axes]\nsigma = [false, true]\n[outputs]\nindicators = [\"v_inf\"]\n",
    );
    assert!(base_file.exists());
    let (a, b) = (dir.join("a.csv"), dir.join("b.csv"));
    ok(stickslip(&[
        "sweep",
        s(&with_base),
        "-q",
        "--no-timing",
        "-o",
        s(&a),
    ]));
    ok(stickslip(&[
        "sweep",
        s(&without),
        "-q",
        "--no-timing",
        "-o",
        s(&b),
        "--set",
        "motor.slider_mass=2e-3",
    ]));
    let rows = |p: &std::path::Path| -> Vec<String> {
        std::fs::read_to_string(p)
            .unwrap()
            .lines()
            .skip(1)
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(rows(&a), rows(&b));
    assert_eq!(rows(&a).len(), 3);
}

/// Malformed overrides and overrides that do not fit the scene: one line
/// naming the override and what is wrong, exit 1, nothing written.
#[test]
fn malformed_overrides_are_one_line_errors() {
    let dir = scratch("overrides", "malformed");
    let out = dir.join("out.json");
    for (given, says) in [
        ("motor.slider_mass", "expected PATH=VALUE"),
        ("motor.slider_mas=1", "unknown field `slider_mas`"),
        (
            "signal.amplitudes[0]=1",
            "signal.amplitudes is not in the scene",
        ),
        (
            "motor.slider_mass.x=1",
            "motor.slider_mass is a number, not a table",
        ),
        ("motor.slider_mass=abc", "invalid type: string \"abc\""),
        ("motor.slider_mass=nan", "motor.slider_mass"),
        ("motor.x\r=1\n", "unknown field `x`"),
    ] {
        let o = stickslip(&["run", "-o", s(&out), "--set", given]);
        assert_eq!(o.status.code(), Some(1), "{given}");
        let err = failure(o);
        assert!(err.contains(says), "{given:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{given:?}: {err}");
        assert!(!err.contains('\r'));
        assert!(!out.exists());
    }
}

/// Messages show the value given and stay one line: the unit hint of an
/// implausible stroke reads the value given in micrometres (its decimal
/// exponent lowered by 6), a duty too short for floating point is refused
/// naming it (never `NaN`), and a carriage return quoted from a scene line
/// is written escaped.
#[test]
fn messages_show_the_value_given_and_stay_one_line() {
    let o = stickslip(&["run", "--set", "signal.stroke=0.0026"]);
    let err = ok(o);
    assert!(
        err.contains("signal.stroke = 0.0026 m is above 1 mm")
            && err.contains("(0.0026 um = 2.6e-9 m)"),
        "{err}"
    );
    let err = ok(stickslip(&["run", "--set", "signal.stroke=25"]));
    assert!(err.contains("(25 um = 2.5e-5 m)"), "{err}");
    for duty in ["1e-300", "1e-60"] {
        let set = format!("signal.duty={duty}");
        let err = failure(stickslip(&["run", "--set", &set]));
        assert!(
            err.contains(&format!("signal.duty = {duty}")) && !err.contains("NaN"),
            "{err}"
        );
        assert_eq!(err.lines().count(), 1, "{err}");
    }
    let dir = scratch("overrides", "carriage_return");
    let scene = write(
        &dir,
        "cr.toml",
        "[motor]\nslider_mas = -1.0 # a comment\r with a carriage return\n",
    );
    let o = stickslip(&["run", s(&scene)]);
    let err = failure(o);
    assert!(!err.contains('\r') && err.contains("\\r"), "{err:?}");
    assert_eq!(err.lines().count(), 1, "{err:?}");
}

/// `--set signal.frequency` (or `f_max`) on a scene that gives `kappa`
/// replaces it: the run has that `f_0` (`f_max = n f_0`, docs/model.md
/// section 2), not the error of a scene that gives two drives.
#[test]
fn a_frequency_set_on_the_command_line_replaces_the_scene_s_kappa() {
    assert!(
        stickslip::Scene::default()
            .to_toml()
            .contains("kappa = 36.0")
    );
    let f0 = |args: &[&str]| {
        let o = stickslip(args);
        let v = json(&o);
        assert!(o.status.success(), "{args:?}");
        (v["f0"].as_f64().unwrap(), v["f_max"].as_f64().unwrap())
    };
    let (f_0, f_max) = f0(&["run", "--json", "-q", "--set", "signal.frequency=9000"]);
    assert_eq!(f_0, 9000.0);
    assert_eq!(f_max, 2.0 * 9000.0);
    let (f_0, f_max) = f0(&["run", "--json", "-q", "--set", "signal.f_max=2e4"]);
    assert_eq!(f_max, 2e4);
    assert!((f_0 - 1e4).abs() <= 1e-9, "{f_0}");
}
