//! Drives given as engineers give them (docs/model.md section 2): exactly
//! one of `kappa`, `sqrt_kappa`, `frequency` or `f_max`; what the scene
//! gives is held when the motor changes, written back as given, and the
//! sensitivities say which.
//!
//! Sources: the relation `f_0 = duty / sqrt(2 x_Rmax / (kappa a_0))`
//! (model 2) and `f_max = n f_0` (37); the scaling `f_0 ∝ sqrt(a_0) ∝
//! m_s^(-1/2)` at fixed `kappa`; central differences of the library's own
//! `v_inf`; the chain rule between the two held quantities.

use std::path::{Path, PathBuf};
use std::process::Command;
use stickslip::{Outcome, Scene, SignalSpec, motor::Motor, signal::Drive};

/// The paper's signal at a frequency: 9448.8 Hz is its `f_0` at
/// `kappa = 36` to five digits.
const BY_FREQUENCY: &str = "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nfrequency = 9448.8\n\
                            harmonics = 2\nsigma = true\n";

fn scene(text: &str) -> Scene {
    Scene::from_toml_str(text, "test").unwrap()
}

fn steady(scene: &Scene) -> stickslip::RunReport {
    match stickslip::run(scene, &stickslip::RunOptions::default()).unwrap() {
        Outcome::Steady(r) => *r,
        other => panic!("no steady state: {}", other.regime()),
    }
}

fn stickslip(args: &[&str]) -> (bool, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.success(),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-drive-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

#[test]
fn a_frequency_gives_the_signal_of_the_kappa_it_corresponds_to() {
    // kappa = 2 x_Rmax f_0^2 / (duty^2 a_0) inverts f_0 = duty / sqrt(2 x_Rmax / (kappa a_0)).
    for (kind, duty, extra) in [
        ("fourier", 1.0, "harmonics = 3\nsigma = true\n"),
        ("ideal", 0.5, ""),
    ] {
        let by_kappa = scene(&format!(
            "[signal]\nkind = \"{kind}\"\nstroke = 25e-6\nkappa = 36\nduty = {duty}\n{extra}"
        ));
        let motor = Motor::new(by_kappa.motor).unwrap();
        let f0 = duty / (2.0 * 25e-6 / (36.0 * motor.a_0())).sqrt();
        let built = by_kappa.build().unwrap();
        assert!((built.signal.f0() / f0 - 1.0).abs() < 1e-15, "{kind}");
        let by_frequency = scene(&format!(
            "[signal]\nkind = \"{kind}\"\nstroke = 25e-6\nfrequency = {f0:?}\nduty = {duty}\n{extra}"
        ));
        let shape = by_frequency.signal.shape().unwrap();
        assert!((shape.kappa(&motor) / 36.0 - 1.0).abs() < 1e-14, "{kind}");
        let other = by_frequency.build().unwrap();
        assert!((other.signal.period() / built.signal.period() - 1.0).abs() < 1e-15);
        // The same rod motion, to rounding.
        let t = built.signal.period();
        for i in 0..64 {
            let tau = t * i as f64 / 64.0;
            let (a, b) = (built.signal.position(tau), other.signal.position(tau));
            assert!(
                (a - b).abs() <= 1e-12 * 25e-6,
                "{kind} at {tau}: {a} vs {b}"
            );
        }
    }
}

#[test]
fn f_max_is_n_times_the_frequency() {
    let s = scene(&BY_FREQUENCY.replace("frequency = 9448.8", "f_max = 18897.6"));
    let motor = Motor::new(s.motor).unwrap();
    assert_eq!(s.signal.f0(&motor), 18897.6 / 2.0);
    let stickslip::scene::BuiltScene { signal, motor: _ } = s.build().unwrap();
    assert!((signal.f_max().unwrap() / 18897.6 - 1.0).abs() < 1e-15);
}

#[test]
fn the_resolved_scene_writes_the_drive_as_given() {
    for (given, written) in [
        ("frequency = 9448.8", "frequency = 9448.8"),
        ("f_max = 18897.6", "f_max = 18897.6"),
        ("kappa = 36", "kappa = 36.0"),
        ("sqrt_kappa = 6", "kappa = 36.0"),
    ] {
        let s = scene(&BY_FREQUENCY.replace("frequency = 9448.8", given));
        let toml = s.to_toml();
        assert!(toml.contains(&format!("\n{written}\n")), "{given}:\n{toml}");
        let drives = ["kappa =", "sqrt_kappa =", "frequency =", "f_max ="];
        let n = drives
            .iter()
            .filter(|d| toml.contains(&format!("\n{d}")))
            .count();
        assert_eq!(n, 1, "{given}:\n{toml}");
        assert_eq!(scene(&toml), s, "{given}: reads back equal");
    }
    // run --json: the scene key and f0 with the digits given.
    let path = temp("by_frequency.toml");
    std::fs::write(&path, BY_FREQUENCY).unwrap();
    let (ok, out, err) = stickslip(&["run", path.to_str().unwrap(), "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["scene"]["signal"]["frequency"], 9448.8);
    assert!(v["scene"]["signal"].get("kappa").is_none());
    assert_eq!(v["f0"], 9448.8);
}

/// The `f0` column of a sweep's rows, by `slider_mass`.
fn f0_by_mass(base: &str) -> Vec<(f64, f64)> {
    let scene = temp(&format!("base_{}.toml", base.len()));
    std::fs::write(&scene, base).unwrap();
    let sweep = temp(&format!("sweep_{}.toml", base.len()));
    std::fs::write(
        &sweep,
        format!(
            "base = {:?}\n[axes]\nslider_mass = [2e-3, 5e-3, 10e-3]\n[outputs]\nindicators = [\"v_inf\"]\n",
            scene.to_str().unwrap()
        ),
    )
    .unwrap();
    let out = temp(&format!("rows_{}.csv", base.len()));
    let _ = std::fs::remove_file(&out);
    let (header, rows) = sweep_rows(&sweep, &out);
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (m, f) = (col("slider_mass"), col("f0"));
    rows.iter()
        .map(|cells| (cells[m].parse().unwrap(), cells[f].parse().unwrap()))
        .collect()
}

/// Runs the sweep file `sweep` into `out` and returns its header and rows
/// (CSV cells; the `#` lines skipped).
fn sweep_rows(sweep: &Path, out: &Path) -> (Vec<String>, Vec<Vec<String>>) {
    let (ok, _, err) = stickslip(&[
        "sweep",
        sweep.to_str().unwrap(),
        "-q",
        "--no-timing",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let text = std::fs::read_to_string(out).unwrap();
    let mut lines = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .map(|l| l.split(',').map(str::to_owned).collect::<Vec<String>>());
    let header = lines.next().unwrap();
    (header, lines.collect())
}

#[test]
fn a_drive_given_by_frequency_keeps_it_through_a_slider_mass_sweep() {
    let rows = f0_by_mass(BY_FREQUENCY);
    assert_eq!(rows.len(), 3);
    for (m, f0) in rows {
        assert_eq!(f0, 9448.8, "slider_mass = {m}");
    }
}

#[test]
fn a_drive_given_by_kappa_retunes_with_the_slider_mass() {
    // f_0 ∝ sqrt(a_0) ∝ m_s^(-1/2) at fixed kappa (model 2).
    let rows = f0_by_mass(&BY_FREQUENCY.replace("frequency = 9448.8", "kappa = 36"));
    let (m0, f0) = rows[0];
    for (m, f) in &rows[1..] {
        let expected = f0 * (m0 / m).sqrt();
        assert!((f / expected - 1.0).abs() < 1e-14, "{m}: {f} vs {expected}");
    }
}

#[test]
fn a_frequency_axis_replaces_the_kappa_of_the_base() {
    let sweep = temp("frequency_axis.toml");
    std::fs::write(
        &sweep,
        "[axes]\nfrequency = [5000.5, 12000]\n[outputs]\nindicators = [\"v_inf\"]\n",
    )
    .unwrap();
    let out = temp("frequency_axis.csv");
    let _ = std::fs::remove_file(&out);
    let (header, rows) = sweep_rows(&sweep, &out);
    let (a, f) = (
        header.iter().position(|h| *h == "frequency").unwrap(),
        header.iter().position(|h| *h == "f0").unwrap(),
    );
    assert_eq!(rows.len(), 2);
    for row in rows {
        assert_eq!(row[a], row[f]);
    }
}

/// `v_inf` and its error estimate at `slider_mass = m`, the drive as
/// `scene` gives it.
fn v_inf_at(scene: &Scene, m: f64) -> (f64, f64) {
    let mut s = scene.clone();
    s.motor.slider_mass = m;
    let r = steady(&s);
    (r.indicators.v_inf, r.error.v_inf.unwrap())
}

#[test]
fn at_fixed_frequency_the_slider_mass_derivative_is_the_central_difference() {
    let s = scene(BY_FREQUENCY);
    let report = steady(&s);
    let sens = report.sensitivities(&s).unwrap();
    assert_eq!(sens.held_fixed, stickslip::signal::Held::Frequency);
    assert_eq!(sens.f0, 9448.8);
    let entry = |name: &str| {
        sens.entries
            .iter()
            .find(|e| e.parameter.to_string() == name)
            .unwrap_or_else(|| panic!("no {name}"))
            .derivative
            .value()
            .unwrap()
    };
    assert!(
        sens.entries
            .iter()
            .all(|e| e.parameter.to_string() != "signal.kappa")
    );
    let d = entry("motor.slider_mass");
    // Central differences D(h) = (v(m + h) - v(m - h)) / 2h at the same
    // frequency, extrapolated: R = (4 D(h) - D(2h)) / 3 removes the h^2
    // term. h = 2e-3 m_s: R's truncation (h^4, estimated from R at 2h) and
    // its rounding (bounded by the runs' own error estimates of v_inf,
    // about 1e-12 m/s, divided by h) both stay below 1e-6 of R.
    let m = s.motor.slider_mass;
    let h = 2e-3 * m;
    let difference = |h: f64| {
        let (up, e_up) = v_inf_at(&s, m + h);
        let (down, e_down) = v_inf_at(&s, m - h);
        ((up - down) / (2.0 * h), (e_up + e_down) / (2.0 * h))
    };
    let (d1, b1) = difference(h);
    let (d2, b2) = difference(2.0 * h);
    let (d4, _) = difference(4.0 * h);
    let r1 = (4.0 * d1 - d2) / 3.0;
    let r2 = (4.0 * d2 - d4) / 3.0;
    let truncation = (r2 - r1).abs() / 15.0;
    let rounding = (4.0 * b1 + b2) / 3.0;
    assert!(
        truncation + rounding < 1e-6 * r1.abs(),
        "the difference is not accurate enough to judge: truncation {truncation:e}, rounding {rounding:e}, R {r1:e}"
    );
    assert!(
        (d - r1).abs() <= 1e-6 * r1.abs(),
        "d v_inf / d m_s = {d:e} at fixed f_0 vs central difference {r1:e}"
    );
    // The measurement: -0.89 m/(s kg) at the fixed frequency.
    assert!((d + 0.888).abs() < 1e-3, "{d}");
}

#[test]
fn the_kappa_held_derivative_is_available_labelled_and_obeys_the_chain_rule() {
    let path = temp("chain.toml");
    std::fs::write(&path, BY_FREQUENCY).unwrap();
    let json = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["run", path.to_str().unwrap(), "--json", "--sensitivities"];
        args.extend_from_slice(extra);
        let (ok, out, err) = stickslip(&args);
        assert!(ok, "{err}");
        serde_json::from_str(&out).unwrap()
    };
    let at_f = json(&[]);
    let at_kappa = json(&["--sensitivities-at", "kappa"]);
    assert_eq!(at_f["held_fixed"], "frequency");
    assert_eq!(at_kappa["held_fixed"], "kappa");
    let value =
        |v: &serde_json::Value, key: &str| v["sensitivities"][key]["value"].as_f64().unwrap();
    assert!(at_kappa["sensitivities"].get("signal.frequency").is_none());
    assert!(at_f["sensitivities"].get("signal.kappa").is_none());
    // At fixed kappa, f_0 ∝ m_s^(-1/2): df_0/dm_s = -f_0 / (2 m_s), so
    // dv/dm_s|kappa = dv/dm_s|f_0 + dv/df_0 (-f_0 / (2 m_s)).
    let (f0, m) = (9448.8, 1.4e-3);
    let chain =
        value(&at_f, "motor.slider_mass") - value(&at_f, "signal.frequency") * f0 / (2.0 * m);
    let kappa_held = value(&at_kappa, "motor.slider_mass");
    assert!(
        (kappa_held / chain - 1.0).abs() < 1e-9,
        "{kappa_held} vs {chain}"
    );
    // The measurement: -106 m/(s kg) at fixed kappa.
    assert!((kappa_held + 106.1).abs() < 0.1, "{kappa_held}");
    // The text summary says what is held and at which frequency.
    let (ok, out, _) = stickslip(&["run", path.to_str().unwrap(), "--sensitivities"]);
    assert!(ok);
    assert!(
        out.contains("sensitivities held fixed: the drive frequency f0 = 9448.8"),
        "{out}"
    );
}

#[test]
fn sensitivities_at_kappa_of_a_harmonics_signal_is_refused_and_writes_nothing() {
    let out = temp("never.json");
    let (ok, _, err) = stickslip(&[
        "run",
        "examples/scenes/harmonics.toml",
        "--sensitivities",
        "--sensitivities-at",
        "kappa",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(!ok);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(err.contains("--sensitivities-at = kappa"), "{err}");
    assert!(!out.exists());
}

#[test]
fn a_drive_by_frequency_needs_no_static_friction() {
    // kappa = a_R / a_0 needs a_0 > 0; a frequency does not.
    let s = scene(&format!(
        "[motor]\nslider_mass = 1.4e-3\ncontact_force = 1\nmu_static = 0\nmu_dynamic = 0\n{BY_FREQUENCY}"
    ));
    let motor = Motor::new(s.motor).unwrap();
    let stickslip::scene::BuiltScene { signal, motor: _ } = s.build().unwrap();
    assert!((signal.f0() / 9448.8 - 1.0).abs() < 1e-15);
    assert!(
        matches!(s.signal, SignalSpec::Fourier { shape, .. } if shape.drive == Drive::Frequency(9448.8))
    );
    assert_eq!(s.signal.f0(&motor), 9448.8);
}
