//! A driven rod's voltage given directly in a `[voltage]` table
//! (docs/model.md section 16, docs/interface.md `[voltage]`):
//!
//! * the table is read, checked field by field and written back as given;
//! * the rod's reference motion is the `[actuator]`'s response, the closed
//!   form `alpha u_k / |c - M (k w)^2 + i d k w|` with the phase lag
//!   `atan2(d k w, c - M (k w)^2)` and the offset `alpha u_0 / c`;
//! * the rod starts at rest at `x_R = 0` and its free oscillation, excited
//!   at `t = 0`, is the closed form of a damped oscillator; without the
//!   reaction it decays and the rod settles onto the response;
//! * the voltage `stickslip signal --voltage` prints for the driven
//!   example, given back as `[voltage]`, reproduces the designed run: the
//!   same physics reached two ways;
//! * a sweep over a `[voltage]` scene varies the motor only.

mod common;

use common::{failure, ok, s, scratch, stickslip, write};
use serde_json::Value;
use std::f64::consts::PI;
use stickslip::actuator::{DrivenRod, DrivenSpec, GivenVoltage, RodModel};
use stickslip::engine::{DrivenEngine, EventOptions, PeriodEngine, PeriodStart};
use stickslip::error::SceneError;
use stickslip::signal::Signal;
use stickslip::{Indicator, Scene, SignalSpec};

/// Table 1's actuator, `M`, `d`, `c`, `alpha`.
const TABLE_1: [f64; 4] = [3.2e-3, 9.50, 24.6e6, 1.985];

/// Table 1's `[actuator]`, the rod model left to `[voltage]`.
const ACTUATOR: &str = r#"
[actuator]
mass = 3.2e-3
damping = 9.50
stiffness = 24.6e6
transfer_factor = 1.985
capacitance = 800e-9
"#;

/// One harmonic, 80 V at 6 kHz (below the resonance
/// `sqrt(c/M) / (2 pi) = 13.95 kHz`) with a phase and an offset, so that
/// the response does not start at rest.
const ONE_HARMONIC: [f64; 4] = [6000.0, 80.0, 0.7, 15.0];

fn one_harmonic(reaction: bool) -> String {
    let [f, u, phi, u0] = ONE_HARMONIC;
    format!(
        "[voltage]\nfrequency = {f:?}\namplitudes = [{u:?}]\nphases = [{phi:?}]\n\
         offset = {u0:?}\n{ACTUATOR}reaction = {reaction}\n"
    )
}

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, "<test>")
}

/// The response's closed form for [`ONE_HARMONIC`]: amplitude, phase of
/// `sin(w t + phase)` and offset (m, rad, m).
fn closed_form_response() -> (f64, f64, f64) {
    let [m, d, c, alpha] = TABLE_1;
    let [f, u, phi, u0] = ONE_HARMONIC;
    let w = 2.0 * PI * f;
    let (re, im) = (c - m * w * w, d * w);
    (alpha * u / re.hypot(im), phi - im.atan2(re), alpha * u0 / c)
}

#[test]
fn a_voltage_table_drives_the_rod_and_writes_back_as_given() {
    let text = format!(
        "[voltage]\nfrequency = 9450.0\namplitudes = [120.0, 30.0]\nphases = [0.0, 1.2]\n\
         offset = 4.5\n{ACTUATOR}"
    );
    let scene = parse(&text).expect("a valid scene");
    // [voltage] makes the rod driven, with the reaction (its default).
    assert_eq!(scene.rod, RodModel::Driven(DrivenSpec::default()));
    let given = GivenVoltage {
        frequency: 9450.0,
        amplitudes: vec![120.0, 30.0],
        phases: vec![0.0, 1.2],
        offset: 4.5,
    };
    assert_eq!(scene.voltage.as_ref(), Some(&given));
    assert!(matches!(scene.signal, SignalSpec::Response { .. }));
    let written = scene.to_toml();
    assert!(written.contains("[voltage]") && !written.contains("[signal]"));
    assert_eq!(parse(&written).expect("written back"), scene);
    // The same scene built programmatically.
    let mut built = Scene {
        outputs: scene.outputs.clone(),
        ..Scene::default()
    };
    built.set_voltage(given).expect("an actuator");
    assert_eq!(built, scene);
}

#[test]
fn each_refusal_is_one_line_naming_its_field() {
    let good = "[voltage]\nfrequency = 9450.0\namplitudes = [120.0, 30.0]\nphases = [0.0, 1.2]\n\
                offset = 0.0\n"
        .to_owned();
    let with = |from: &str, to: &str| good.replace(from, to) + ACTUATOR;
    let signal = "[signal]\nkind = \"fourier\"\nstroke = 25e-6\nsqrt_kappa = 6.0\nharmonics = 2\n";
    let cases = [
        (good.clone(), "voltage", "[actuator]"),
        (
            format!("{good}{ACTUATOR}rod = \"prescribed\"\n"),
            "actuator.rod",
            "[voltage]",
        ),
        (format!("{good}{signal}{ACTUATOR}"), "voltage", "[signal]"),
        (with("9450.0", "0.0"), "voltage.frequency", "= 0"),
        (with("9450.0", "inf"), "voltage.frequency", "inf"),
        (
            with("[0.0, 1.2]", "[0.0]"),
            "voltage.phases",
            "has 1 entries",
        ),
        (
            with("[120.0, 30.0]", "[]").replace("[0.0, 1.2]", "[]"),
            "voltage.amplitudes",
            "= 0",
        ),
        (
            with("[120.0, 30.0]", "[120.0, -30.0]"),
            "voltage.amplitudes[1]",
            "-30",
        ),
        (
            with("[120.0, 30.0]", "[0.0, 0.0]"),
            "voltage.amplitudes",
            "zero",
        ),
        (with("[0.0, 1.2]", "[nan, 1.2]"), "voltage.phases[0]", "NaN"),
        (
            with("offset = 0.0", "offset = -inf"),
            "voltage.offset",
            "inf",
        ),
    ];
    for (text, field, value) in &cases {
        let e = parse(text).expect_err(field);
        let message = e.to_string();
        assert!(matches!(e, SceneError::Param { .. }), "{field}: {message}");
        assert!(message.contains(&format!(" {field}")), "{message}");
        assert!(message.contains(value), "{field}: {message}");
        assert!(!message.contains('\n'), "{message}");
    }
    // On the command line: a non-zero exit, the one line, nothing run.
    let dir = scratch("driven_voltage", "refusals");
    let path = write(&dir, "prescribed.toml", &cases[1].0);
    let o = stickslip(&["run", s(&path)]);
    assert!(o.stdout.is_empty());
    let err = failure(o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("actuator.rod"), "{err}");
}

/// The signal of a single-harmonic voltage is the closed form of the
/// friction-free actuator's response (amplitude to 1e-14, phase to 1e-13,
/// offset to 1e-15), and `signal --voltage` prints the voltage as given,
/// bit for bit.
#[test]
fn the_signal_is_the_closed_form_response_to_one_harmonic() {
    let scene = parse(&one_harmonic(true)).expect("a valid scene");
    let built = scene.build().expect("built");
    let Signal::Fourier(f) = &built.signal else {
        panic!("a series");
    };
    let (amplitude, phase, offset) = closed_form_response();
    assert_eq!(f.amplitudes().len(), 1);
    let a = f.amplitudes()[0];
    assert!(
        (a - amplitude).abs() <= 1e-14 * amplitude,
        "{a:e} against {amplitude:e}"
    );
    let lag = (f.phases()[0] - phase).rem_euclid(2.0 * PI);
    assert!(
        lag.min(2.0 * PI - lag) <= 1e-13,
        "phase {} against {phase}",
        f.phases()[0]
    );
    assert!(
        (f.offset() - offset).abs() <= 1e-15 * offset,
        "{}",
        f.offset()
    );

    let dir = scratch("driven_voltage", "printed");
    let path = write(&dir, "one.toml", &one_harmonic(true));
    let o = stickslip(&["signal", s(&path), "--voltage", "--json"]);
    let v: Value = serde_json::from_slice(&o.stdout).expect("JSON");
    ok(o);
    let [freq, u, phi, u0] = ONE_HARMONIC;
    assert_eq!(v["f0"].as_f64(), Some(freq));
    assert_eq!(v["offset"].as_f64(), Some(u0));
    assert_eq!(v["harmonics"][0]["amplitude"].as_f64(), Some(u));
    assert_eq!(v["harmonics"][0]["phase"].as_f64(), Some(phi));
    assert_eq!(v["given"].as_bool(), Some(true));
    assert_eq!(v["starts_at_rest"].as_bool(), Some(false));
}

/// The rod starts at rest at `x_R = 0` although the response does not:
/// without the reaction, after the first period from rest the rod is the
/// response plus the free oscillation started with minus the response's
/// state, the closed form
/// `h = e^{-sigma t} (y_0 cos nu t + (y_1 + sigma y_0) / nu sin nu t)`,
/// `nu^2 = c / M - sigma^2`, `sigma = d / (2 M)`, position and velocity
/// to 1e-12 of the amplitude (the transient itself is above 1e-2 of it);
/// in the steady state it has decayed, and the reported deviation from
/// the response is below 1e-12 of the amplitude.
#[test]
fn without_the_reaction_the_rod_settles_from_rest_onto_the_response() {
    let scene = parse(&one_harmonic(false)).expect("a valid scene");
    let built = scene.build().expect("built");
    let (RodModel::Driven(spec), Some(design), Some(given)) =
        (&scene.rod, &scene.actuator, &scene.voltage)
    else {
        panic!("a driven rod with its voltage");
    };
    let rod = DrivenRod::new(spec, design, given.voltage(), &built.motor).expect("a rod");
    let options = EventOptions::default();
    let mut engine = DrivenEngine::new(
        &built.signal,
        &rod,
        &built.motor,
        options.velocity_tolerance,
        options.max_events_per_period,
    );
    let start = PeriodStart {
        velocity: 0.0,
        mode: None,
    };
    engine.run_period(1, start, &mut ()).expect("a period");
    let end = engine.state().expect("a state");

    let [m, d, c, _] = TABLE_1;
    let (amplitude, phase, offset) = closed_form_response();
    let w = 2.0 * PI * ONE_HARMONIC[0];
    let response = |t: f64| {
        let (sn, cs) = (w * t + phase).sin_cos();
        [offset + amplitude * sn, amplitude * w * cs]
    };
    let (sigma, period) = (d / (2.0 * m), 1.0 / ONE_HARMONIC[0]);
    let nu = (c / m - sigma * sigma).sqrt();
    let [x0, v0] = response(0.0);
    let (y0, y1) = (-x0, -v0);
    let decay = (-sigma * period).exp();
    let (sn, cs) = (nu * period).sin_cos();
    let h = decay * (y0 * cs + (y1 + sigma * y0) / nu * sn);
    let dh = decay * (y1 * cs - (sigma * y1 + c / m * y0) / nu * sn);
    let [xp, vp] = response(period);
    assert!(
        h.abs() > 1e-2 * amplitude,
        "the transient is visible: {h:e}"
    );
    assert!(
        (end.rod_x - (xp + h)).abs() <= 1e-12 * amplitude,
        "x {:e} against {:e}",
        end.rod_x,
        xp + h
    );
    assert!(
        (end.rod_v - (vp + dh)).abs() <= 1e-12 * amplitude * w,
        "v {:e} against {:e}",
        end.rod_v,
        vp + dh
    );

    let report = common::run(&scene);
    let drive = report.drive.expect("a driven rod's profile");
    assert!(
        drive.rod_deviation_max <= 1e-12 * amplitude,
        "deviation {:e} of an amplitude {amplitude:e}",
        drive.rod_deviation_max
    );
}

/// The voltage `signal --voltage --json` prints for
/// `examples/scenes/driven_rod.toml`, given as `[voltage]` in place of its
/// `[signal]` (the `[actuator]` and `[actuator.real]` kept), runs to the
/// designed run's indicators and drive profile within 1e-12 relative
/// (1e-15 of the scale where a value is zero): the response to the
/// designed voltage is the designed signal, which starts at rest. The
/// `[voltage]` table ending the text output is the same scene.
#[test]
fn the_designed_voltage_given_directly_reproduces_the_designed_run() {
    let example = "examples/scenes/driven_rod.toml";
    let o = stickslip(&["signal", example, "--voltage", "--json"]);
    let v: Value = serde_json::from_slice(&o.stdout).expect("JSON");
    ok(o);
    let list = |key: &str| -> String {
        let items: Vec<String> = v["harmonics"]
            .as_array()
            .expect("harmonics")
            .iter()
            .map(|h| format!("{:?}", h[key].as_f64().expect("a number")))
            .collect();
        items.join(", ")
    };
    let table = format!(
        "[voltage]\nfrequency = {:?}\namplitudes = [{}]\nphases = [{}]\noffset = {:?}\n",
        v["f0"].as_f64().expect("f0"),
        list("amplitude"),
        list("phase"),
        v["offset"].as_f64().expect("offset"),
    );
    let text = std::fs::read_to_string(example).expect("the example");
    let at = text.find("[actuator]").expect("an [actuator] table");
    assert!(text[..at].contains("[signal]"), "the [signal] comes first");
    let given = format!("{}\n{table}", &text[at..]);
    let scene = parse(&given).expect("the given scene");

    let o = stickslip(&["signal", example, "--voltage"]);
    let printed = String::from_utf8(o.stdout.clone()).expect("UTF-8");
    ok(o);
    let from_text = &printed[printed.find("[voltage]").expect("a [voltage] table")..];
    let pasted = parse(&format!("{}\n{from_text}", &text[at..])).expect("the pasted scene");
    assert_eq!(pasted, scene, "text and JSON give the same voltage");

    let designed = common::run(&Scene::from_path(std::path::Path::new(example)).expect("example"));
    let direct = common::run(&scene);
    let close = |what: &str, x: f64, y: f64, scale: f64| {
        let d = (x - y).abs();
        assert!(
            d <= 1e-12 * scale || d <= 1e-15,
            "{what}: designed {x:e}, given {y:e}"
        );
    };
    let mut compared = 0;
    for indicator in Indicator::ALL {
        let (a, b) = (designed.value(indicator), direct.value(indicator));
        assert_eq!(a.is_some(), b.is_some(), "{indicator}");
        if let (Some(x), Some(y)) = (a, b) {
            let scale = match indicator {
                Indicator::StictionFraction => 1.0,
                _ => x.abs(),
            };
            close(indicator.name(), x, y, scale);
            compared += 1;
        }
    }
    assert!(compared >= 5, "only {compared} indicators compared");
    let (a, b) = (
        designed.drive.expect("a profile"),
        direct.drive.expect("a profile"),
    );
    for (what, x, y) in [
        (
            "rod_deviation_max",
            a.rod_deviation_max,
            b.rod_deviation_max,
        ),
        (
            "rod_deviation_rms",
            a.rod_deviation_rms,
            b.rod_deviation_rms,
        ),
        ("voltage_peak", a.voltage_peak, b.voltage_peak),
        ("voltage_rms", a.voltage_rms, b.voltage_rms),
        ("current_peak", a.current_peak, b.current_peak),
        ("current_rms", a.current_rms, b.current_rms),
    ] {
        close(what, x, y, x.abs());
    }
}

/// A sweep over a `[voltage]` scene varies the motor, each case keeping
/// the voltage and its response, and refuses the signal's axes, which
/// have nothing to vary, naming the axis.
#[test]
fn a_sweep_over_a_voltage_scene_varies_the_motor_only() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
    let base = "base = \"driven_voltage.toml\"\n[axes]\n";
    let sweep = stickslip::sweep::Sweep::from_toml_str(
        &format!("{base}slider_mass = [1.0e-3, 2.0e-3]\n"),
        "<test>",
        &dir,
    )
    .expect("a motor axis");
    let cases = sweep.cases();
    assert_eq!(cases.len(), 2);
    for case in &cases {
        assert_eq!(case.scene.voltage, sweep.base().voltage);
        assert_eq!(case.scene.signal, sweep.base().signal);
        case.scene.validate().expect("a valid case");
    }
    assert_eq!(cases[1].scene.motor.slider_mass, 2.0e-3);
    for axis in ["stroke = [1e-5]", "frequency = [8000.0]", "kappa = [4.0]"] {
        let e = stickslip::sweep::Sweep::from_toml_str(&format!("{base}{axis}\n"), "<test>", &dir)
            .expect_err(axis)
            .to_string();
        let name = axis.split(' ').next().expect("a name");
        assert!(
            e.contains(&format!("axes.{name}")) && e.contains("[voltage]"),
            "{e}"
        );
    }
}
