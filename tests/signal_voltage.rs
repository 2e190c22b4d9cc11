//! `stickslip signal --voltage`: the voltage that moves the rod of the
//! scene's `[actuator]` along the scene's signal (docs/interface.md,
//! `stickslip signal`), checked against what the command prints for the
//! signal itself (`stickslip signal --json`) and against closed forms:
//!
//! * the actuator equation (23) `M x'' + d x' + c x = alpha u` holds along
//!   the signal with `u` rebuilt from the printed harmonics;
//! * each amplitude is the paper's (31), the RMS its (33);
//! * the printed peak is the maximum of `|u|` to a dense sampling's
//!   resolution;
//! * text, JSON and the MATLAB snippet carry the same numbers, bit for bit
//!   (the Python snippet is evaluated by `python/tests`, where numpy is);
//! * the errors name their field.

mod common;

use common::{failure, ok, s, scratch, stickslip, write};
use serde_json::Value;
use std::f64::consts::PI;
use std::path::PathBuf;

/// Table 1: `M`, `d`, `c`, `alpha` of the default scene and of
/// `examples/scenes/harmonics.toml`.
const TABLE_1: [f64; 4] = [3.2e-3, 9.50, 24.6e6, 1.985];

/// A `harmonics` signal not shifted to its minimum (`x_R(0) != 0`), five
/// harmonics around the resonance `sqrt(c/M)/(2 pi) = 7.8 kHz` of its own
/// actuator (the fundamental below it, the others above).
const UNSHIFTED: &str = r#"
[signal]
kind = "harmonics"
frequency = 6000.0
amplitudes = [6e-6, 3e-6, 1.5e-6, 0.8e-6, 0.4e-6]
phases = [0.3, -1.2, 2.9, 0.0, -2.5]
shift_to_minimum = false

[actuator]
mass = 5.0e-3
damping = 20.0
stiffness = 1.2e7
transfer_factor = 3.1
capacitance = 1.0e-6
"#;

/// `M`, `d`, `c`, `alpha` of [`UNSHIFTED`].
const UNSHIFTED_ACTUATOR: [f64; 4] = [5.0e-3, 20.0, 1.2e7, 3.1];

/// A driven rod whose real actuator differs from `[actuator]`: the voltage
/// is designed for `[actuator]`.
const DRIVEN: &str = r#"
[signal]
kind = "fourier"
stroke = 20e-6
frequency = 4000.0
harmonics = 3
sigma = false

[actuator]
mass = 2.5e-3
damping = 12.0
stiffness = 3.0e7
transfer_factor = 2.2
capacitance = 1.0e-6
rod = "driven"

[actuator.real]
mass = 4.0e-3
stiffness = 2.0e7
"#;

/// `M`, `d`, `c`, `alpha` of [`DRIVEN`]'s `[actuator]`.
const DRIVEN_ACTUATOR: [f64; 4] = [2.5e-3, 12.0, 3.0e7, 2.2];

/// The scenes checked, each with the `[actuator]` it gives (the files
/// written to a scratch folder of their own for each test, `test`).
fn scenes(test: &str) -> Vec<(Vec<String>, [f64; 4])> {
    let dir = scratch("signal_voltage", test);
    let file = |name: &str, text: &str| -> Vec<String> {
        let p: PathBuf = write(&dir, name, text);
        vec![s(&p).to_owned()]
    };
    vec![
        (Vec::new(), TABLE_1),
        (vec!["examples/scenes/harmonics.toml".to_owned()], TABLE_1),
        (file("unshifted.toml", UNSHIFTED), UNSHIFTED_ACTUATOR),
        (file("driven.toml", DRIVEN), DRIVEN_ACTUATOR),
    ]
}

/// `stickslip signal SCENE EXTRA...`: its standard output (must succeed).
fn signal(scene: &[String], extra: &[&str]) -> String {
    let mut args = vec!["signal"];
    args.extend(scene.iter().map(String::as_str));
    args.extend_from_slice(extra);
    let o = stickslip(&args);
    ok(o.clone());
    String::from_utf8(o.stdout).expect("UTF-8")
}

fn json(text: &str) -> Value {
    serde_json::from_str(text).expect("one JSON object")
}

fn num(v: &Value) -> f64 {
    v.as_f64().expect("a number")
}

/// A series `c0 + sum_k a_k sin(k w t + phi_k)` as printed.
struct Series {
    period: f64,
    offset: f64,
    amplitudes: Vec<f64>,
    phases: Vec<f64>,
}

impl Series {
    fn from_json(v: &Value) -> Self {
        let h = v["harmonics"].as_array().expect("harmonics");
        for (i, item) in h.iter().enumerate() {
            assert_eq!(item["k"].as_u64(), Some(i as u64 + 1), "harmonics in order");
        }
        Self {
            period: num(&v["period"]),
            offset: num(&v["offset"]),
            amplitudes: h.iter().map(|x| num(&x["amplitude"])).collect(),
            phases: h.iter().map(|x| num(&x["phase"])).collect(),
        }
    }

    fn omega(&self) -> f64 {
        2.0 * PI / self.period
    }

    /// Value and first two derivatives at `t`.
    fn at(&self, t: f64) -> [f64; 3] {
        let w = self.omega();
        let mut r = [self.offset, 0.0, 0.0];
        for (i, (a, p)) in self.amplitudes.iter().zip(&self.phases).enumerate() {
            let kw = (i + 1) as f64 * w;
            let (sn, cs) = (kw * t + p).sin_cos();
            r[0] += a * sn;
            r[1] += a * kw * cs;
            r[2] -= a * kw * kw * sn;
        }
        r
    }

    /// `sum_k (k w)^j a_k`: a bound on the `j`-th derivative's magnitude.
    fn bound(&self, j: i32) -> f64 {
        let w = self.omega();
        self.amplitudes
            .iter()
            .enumerate()
            .map(|(i, a)| ((i + 1) as f64 * w).powi(j) * a)
            .sum()
    }
}

/// The number printed on the text line starting with `label`.
fn text_value(text: &str, label: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no line {label:?} in\n{text}"));
    line.trim_start()[label.len()..]
        .split_whitespace()
        .next()
        .and_then(|w| w.parse().ok())
        .unwrap_or_else(|| panic!("no number on {line:?}"))
}

/// The voltage rebuilt from `--voltage --json` satisfies (23) along the
/// signal rebuilt from `--json`, at 101 phases of a period: the residual
/// `M x'' + d x' + c x - alpha u` is at the rounding level of the terms
/// (bounded by their amplitude sums), while a wrong sign or factor of any
/// term leaves a residual of percents of them. The actuator is the
/// scene's `[actuator]` (not `[actuator.real]`), and the JSON states it.
#[test]
fn the_voltage_moves_the_designed_actuator_along_the_signal() {
    for (scene, [m, d, c, alpha]) in scenes("equation") {
        let x = Series::from_json(&json(&signal(&scene, &["--json"])));
        let v = json(&signal(&scene, &["--voltage", "--json"]));
        let u = Series::from_json(&v);
        assert_eq!(u.period, x.period, "{scene:?}: the signal's period");
        assert_eq!(num(&v["f0"]), 1.0 / x.period, "{scene:?}");
        let a = &v["actuator"];
        let printed = [
            num(&a["mass"]),
            num(&a["damping"]),
            num(&a["stiffness"]),
            num(&a["transfer_factor"]),
        ];
        assert_eq!(printed, [m, d, c, alpha], "{scene:?}: [actuator]");
        let scale = m * x.bound(2)
            + d * x.bound(1)
            + c * (x.offset.abs() + x.bound(0))
            + alpha * (u.offset.abs() + u.bound(0));
        for i in 0..101 {
            let t = x.period * i as f64 / 101.0;
            let [xr, vr, ar] = x.at(t);
            let residual = m * ar + d * vr + c * xr - alpha * u.at(t)[0];
            assert!(
                residual.abs() <= 1e-13 * scale,
                "{scene:?} at t = {t:e}: residual {residual:e} of terms up to {scale:e}"
            );
        }
    }
}

/// Each amplitude is the paper's (31), `u_k = (w_0 d_k k / alpha)
/// sqrt(d^2 + (k w_0 M - c / (k w_0))^2)`, with `d_k` from `--json`; the
/// offset is `c c0 / alpha` (the static part of (23)); the RMS is (33),
/// `sqrt(sum u_k^2 / 2)`; text and JSON print the same numbers.
#[test]
fn amplitudes_offset_and_rms_are_the_closed_forms() {
    for (scene, [m, d, c, alpha]) in scenes("closed_forms") {
        let x = Series::from_json(&json(&signal(&scene, &["--json"])));
        let v = json(&signal(&scene, &["--voltage", "--json"]));
        let u = Series::from_json(&v);
        let w0 = x.omega();
        for (i, (dk, uk)) in x.amplitudes.iter().zip(&u.amplitudes).enumerate() {
            let kw = (i + 1) as f64 * w0;
            let closed = kw * dk / alpha * d.hypot(kw * m - c / kw);
            assert!(
                (uk - closed).abs() <= 1e-14 * closed,
                "{scene:?} k = {}: {uk:e} against (31) {closed:e}",
                i + 1
            );
        }
        let offset = c * x.offset / alpha;
        assert!(
            (u.offset - offset).abs() <= 1e-15 * offset.abs(),
            "{scene:?}"
        );
        let rms = (0.5 * u.amplitudes.iter().map(|a| a * a).sum::<f64>()).sqrt();
        assert!((num(&v["rms"]) - rms).abs() <= 1e-15 * rms, "{scene:?}");

        let text = signal(&scene, &["--voltage"]);
        assert_eq!(text_value(&text, "RMS (33)"), num(&v["rms"]), "{scene:?}");
        assert_eq!(text_value(&text, "peak"), num(&v["peak"]), "{scene:?}");
        assert_eq!(text_value(&text, "u0 (offset)"), u.offset, "{scene:?}");
        assert_eq!(text_value(&text, "f0"), num(&v["f0"]), "{scene:?}");
        for (i, (a, p)) in u.amplitudes.iter().zip(&u.phases).enumerate() {
            let row = format!("{} ", i + 1);
            let line = text
                .lines()
                .find(|l| l.trim_start().starts_with(&row) && !l.contains('='))
                .unwrap_or_else(|| panic!("no row {row:?} in\n{text}"));
            let cells: Vec<f64> = line
                .split_whitespace()
                .skip(1)
                .map(|w| w.parse().expect("a number"))
                .collect();
            assert_eq!(cells, vec![*a, *p], "{scene:?}: {line}");
        }
        for (label, value) in [
            ("M (mass)", m),
            ("d (damping)", d),
            ("c (stiffness)", c),
            ("alpha", alpha),
        ] {
            assert_eq!(text_value(&text, label), value, "{scene:?}: {label}");
        }
    }
}

/// The printed peak is `max |u(t)|` (offset included): no sample of the
/// rebuilt `u` exceeds it beyond rounding, and it exceeds the largest of
/// 20000 samples by at most the sampling's resolution, `h^2 / 8` times a
/// bound on `|u''|` (between two samples the extremum lies within `h / 2`
/// of one, where `u' = 0`).
#[test]
fn the_peak_is_the_maximum_of_the_voltage() {
    for (scene, _) in scenes("peak") {
        let v = json(&signal(&scene, &["--voltage", "--json"]));
        let u = Series::from_json(&v);
        let peak = num(&v["peak"]);
        let n = 20000;
        let h = u.period / n as f64;
        let sampled = (0..n)
            .map(|i| u.at(i as f64 * h)[0].abs())
            .fold(0.0, f64::max);
        let rounding = 1e-14 * (u.offset.abs() + u.bound(0));
        let resolution = h * h / 8.0 * u.bound(2);
        assert!(
            sampled <= peak + rounding,
            "{scene:?}: a sample {sampled} above the peak {peak}"
        );
        assert!(
            peak <= sampled + resolution + rounding,
            "{scene:?}: peak {peak} above the samples' {sampled} by more than {resolution:e}"
        );
    }
}

/// `starts_at_rest` says what the signal does at `t = 0`: the shifted
/// signals (`fourier`, `harmonics` shifted to its minimum) are at rest
/// there, `x_R(0) = v_R(0) = 0` to rounding; the unshifted one is not,
/// and is still given its voltage.
#[test]
fn starts_at_rest_is_the_signal_at_rest_at_time_zero() {
    for (scene, _) in scenes("rest") {
        let x = Series::from_json(&json(&signal(&scene, &["--json"])));
        let v = json(&signal(&scene, &["--voltage", "--json"]));
        let [x0, v0, _] = x.at(0.0);
        let at_rest = x0.abs() <= 1e-14 * x.bound(0) && v0.abs() <= 1e-14 * x.bound(1);
        assert_eq!(v["starts_at_rest"].as_bool(), Some(at_rest), "{scene:?}");
        let text = signal(&scene, &["--voltage"]);
        let expected = if at_rest { "at rest" } else { "not at rest" };
        assert!(
            text.lines()
                .any(|l| l.contains("from t = 0") && l.contains(expected)),
            "{scene:?}:\n{text}"
        );
    }
}

/// The MATLAB snippet defines `u` from the same numbers as the JSON, bit
/// for bit (`T`, `u0`, `u_k`, `phi_u`, `u_peak`, `u_rms`).
#[test]
fn the_matlab_snippet_holds_the_json_numbers() {
    for (scene, _) in scenes("matlab") {
        let v = json(&signal(&scene, &["--voltage", "--json"]));
        let u = Series::from_json(&v);
        let snippet = signal(&scene, &["--voltage", "--matlab"]);
        let values = |name: &str| -> Vec<f64> {
            let line = snippet
                .lines()
                .find(|l| l.starts_with(&format!("{name} = ")))
                .unwrap_or_else(|| panic!("no {name} in\n{snippet}"));
            let rhs = &line[name.len() + 3..];
            let rhs =
                rhs[..rhs.find(';').expect("a statement")].trim_matches(|c| c == '[' || c == ']');
            rhs.split(',')
                .map(|w| w.trim().parse().expect("a number"))
                .collect()
        };
        assert_eq!(values("T"), vec![u.period], "{scene:?}");
        assert_eq!(values("u0"), vec![u.offset], "{scene:?}");
        assert_eq!(values("u_k"), u.amplitudes, "{scene:?}");
        assert_eq!(values("phi_u"), u.phases, "{scene:?}");
        assert_eq!(values("u_peak"), vec![num(&v["peak"])], "{scene:?}");
        assert_eq!(values("u_rms"), vec![num(&v["rms"])], "{scene:?}");
        assert!(snippet.contains("u = @(t) "), "{snippet}");
    }
}

/// No `[actuator]` is an error naming `actuator`, the ideal signal one
/// naming `signal.kind`, a voltage beyond floating point one naming
/// `actuator`: one line, exit 1, nothing on the output, whatever the form
/// asked.
#[test]
fn errors_name_the_field() {
    let table_1 = [
        "--set",
        "actuator.mass=3.2e-3",
        "--set",
        "actuator.damping=9.5",
        "--set",
        "actuator.stiffness=24.6e6",
        "--set",
        "actuator.transfer_factor=1.985",
        "--set",
        "actuator.capacitance=800e-9",
    ];
    let ideal: Vec<&str> = ["examples/scenes/ideal_discrete.toml"]
        .into_iter()
        .chain(table_1)
        .collect();
    let overflow = [
        "--set",
        "actuator.stiffness=1e308",
        "--set",
        "actuator.transfer_factor=1e-300",
    ];
    let cases: [(&[&str], &str); 4] = [
        (&["examples/scenes/stick_heavy.toml"], "actuator: "),
        (&["examples/scenes/ideal_stick_slip.toml"], "actuator: "),
        (&ideal, "signal.kind: "),
        (&overflow, "actuator: "),
    ];
    for (scene, field) in cases {
        for form in [None, Some("--json"), Some("--matlab"), Some("--python")] {
            let mut args = vec!["signal", "--voltage"];
            args.extend_from_slice(scene);
            args.extend(form);
            let o = stickslip(&args);
            assert_eq!(o.status.code(), Some(1), "{args:?}");
            assert!(o.stdout.is_empty(), "{args:?}");
            let err = failure(o);
            assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
            assert!(
                err.starts_with(&format!("stickslip: {field}")),
                "{args:?}: {err}"
            );
        }
    }
    // Without --voltage the same scenes print their signal.
    for scene in [
        "examples/scenes/stick_heavy.toml",
        "examples/scenes/ideal_stick_slip.toml",
    ] {
        ok(stickslip(&["signal", scene]));
    }
}
