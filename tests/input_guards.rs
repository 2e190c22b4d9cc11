//! Guards on what a scene may ask for (issues 8 and 16): plausibility
//! warnings, work and memory limits, the wall-clock budget, messages that
//! point at the input, and the size of input files. One test per fixed
//! defect, named after its item.

use std::path::PathBuf;
use std::time::{Duration, Instant};
use stickslip::SignalSpec;
use stickslip::observer::MAX_LOGGED_EVENTS;
use stickslip::{Error, error::Num, error::ParamError, error::SceneError, error::SimulationError};
use stickslip::{
    Scene, scene::EngineKind, scene::MAX_FIXED_STEPS_PER_PERIOD, scene::MAX_INPUT_BYTES,
    scene::read_input,
};

fn parse(text: &str) -> Result<Scene, SceneError> {
    Scene::from_toml_str(text, "<string>")
}

fn temp_file(name: &str, bytes: &[u8]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-input-guards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join(name);
    std::fs::write(&path, bytes).unwrap();
    path
}

/// The scene the CLI fuzzer found running past 20 s: a
/// 966 MHz signal (stroke 0.23 um, kappa 3.7e7) whose slip-slip start-up
/// needs millions of periods of 42 harmonics each.
const SLOW_SCENE: &str = r#"
[motor]
slider_mass = 0.1257
contact_force = 19301.6
mu_static = 0.0751
mu_dynamic = 0.0102
[signal]
kind = "fourier"
harmonics = 42
kappa = 37087171.5
stroke = 2.29e-7
"#;

#[test]
fn plausibility_warnings_stroke_meant_as_micrometres() {
    let mut scene = Scene::default();
    // The paper's scene is plausible through and through.
    assert_eq!(scene.warnings(), vec![]);
    scene.signal = SignalSpec::fourier(25.0, 36.0, 2, true);
    let warnings: Vec<String> = scene.warnings().iter().map(|w| w.to_string()).collect();
    assert_eq!(
        warnings,
        ["signal.stroke = 25 m is above 1 mm; strokes are in metres (25 um = 2.5e-5 m)"]
    );
    // The run goes on: a warning is not an error.
    assert!(scene.validate().is_ok());
}

#[test]
fn plausibility_warnings_frequency_mass_force_friction() {
    let scene = parse(
        r#"
[motor]
slider_mass = 20.0
contact_force = 5000.0
mu_static = 3.0
mu_dynamic = 0.1
[signal]
kind = "harmonics"
frequency = 2e7
amplitudes = [1e-6]
phases = [0.0]
"#,
    )
    .unwrap();
    let fields: Vec<String> = scene.warnings().into_iter().map(|w| w.field).collect();
    assert_eq!(
        fields,
        [
            "motor.slider_mass",
            "motor.contact_force",
            "motor.mu_static",
            "signal.frequency"
        ]
    );
    // Just inside every bound: no warning.
    let scene = parse(
        r#"
[motor]
slider_mass = 10.0
contact_force = 1000.0
mu_static = 2.0
mu_dynamic = 2.0
[signal]
kind = "harmonics"
frequency = 1e7
amplitudes = [1e-3]
phases = [0.0]
"#,
    )
    .unwrap();
    assert_eq!(scene.warnings(), vec![]);
}

#[test]
fn plausibility_warnings_slow_scene_says_why() {
    let scene = parse(SLOW_SCENE).unwrap();
    let warnings: Vec<String> = scene.warnings().iter().map(|w| w.to_string()).collect();
    assert_eq!(warnings.len(), 3, "{warnings:#?}");
    assert!(warnings[0].starts_with("motor.contact_force = 19301.6 N is above 1 kN"));
    assert!(warnings[1].starts_with("signal.kappa = 37087171.5 is above 10000"));
    // f_0 = duty / t_1 with t_1 = sqrt(2 x_Rmax / (kappa a_0)),
    // a_0 = 0.0751 * 19301.6 / 0.1257 = 11531.8 m/s^2: 966 MHz.
    assert!(
        warnings[2].contains("gives the frequency f_0 = 966335874"),
        "{}",
        warnings[2]
    );
}

#[test]
fn work_limit_absurd_fixed_step_count_refused() {
    let mut scene = Scene::default();
    scene.run.engine = EngineKind::Fixed;
    scene.run.steps_per_harmonic = u32::MAX;
    let e = scene.validate().unwrap_err().to_string();
    assert!(
        e.starts_with("run.steps_per_harmonic = 4294967295: gives 8589934590 fixed steps"),
        "{e}"
    );
    // n = 2: 5e7 steps per harmonic are exactly the limit, and allowed.
    scene.run.steps_per_harmonic = u32::try_from(MAX_FIXED_STEPS_PER_PERIOD / 2).unwrap();
    assert!(scene.validate().is_ok());
    scene.run.steps_per_harmonic += 1;
    assert!(scene.validate().is_err());
    // The event engine takes no steps: the field is not its business.
    scene.run.engine = EngineKind::Event;
    assert!(scene.validate().is_ok());
}

#[test]
fn time_limit_stops_the_slow_scene_and_names_the_period() {
    let mut scene = parse(SLOW_SCENE).unwrap();
    scene.run.time_limit_s = Some(0.5);
    let clock = Instant::now();
    let result = stickslip::run(&scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report);
    let elapsed = clock.elapsed();
    match result {
        Err(Error::Simulation(SimulationError::TimeLimit { seconds, period })) => {
            assert_eq!(seconds, 0.5);
            // The start-up had begun: at least the fixed-point search ran.
            assert!(period > 0);
        }
        other => panic!("expected the time limit, got {other:?}"),
    }
    // The budget plus one period and the set-up; the unlimited run takes
    // over a minute (1e6 periods at about 80 us each).
    assert!(elapsed < Duration::from_secs(10), "{elapsed:?}");
}

#[test]
fn time_limit_field_is_read_validated_and_written() {
    let scene = parse("[run]\ntime_limit_s = 2.5\n").unwrap();
    assert_eq!(scene.run.time_limit_s, Some(2.5));
    assert_eq!(parse(&scene.to_toml()).unwrap(), scene);
    // Without it, the resolved scene does not mention it.
    assert!(!Scene::default().to_toml().contains("time_limit_s"));
    for (value, message) in [
        ("-1", "run.time_limit_s = -1: must be positive"),
        ("0", "run.time_limit_s = 0: must be positive"),
        ("nan", "run.time_limit_s = NaN: must be a finite number"),
    ] {
        let e = parse(&format!("[run]\ntime_limit_s = {value}\n"))
            .unwrap_err()
            .to_string();
        assert!(e.ends_with(message), "{e}");
    }
}

#[test]
fn event_log_is_bounded_and_says_how_much_it_left_out() {
    // kappa = 1e6: slip-slip, two reversals a period, and a start-up far
    // longer than the 60 000 periods allowed: 120 000 events.
    let mut scene = parse(
        r#"
[signal]
kind = "fourier"
harmonics = 2
sigma = true
kappa = 1e6
stroke = 25e-6
[run]
max_periods = 60000
[outputs]
indicators = ["v_inf"]
events = true
"#,
    )
    .unwrap();
    let report = stickslip::run(&scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    let log = report.event_log.as_ref().unwrap();
    assert_eq!(log.len(), MAX_LOGGED_EVENTS);
    let total = report.events().total();
    assert!(total > MAX_LOGGED_EVENTS as u64, "{total}");
    assert_eq!(log.len() as u64 + report.event_log_omitted, total);
    // A short log is complete.
    scene.run.max_periods = 100;
    let report = stickslip::run(&scene, &stickslip::RunOptions::default())
        .and_then(stickslip::Outcome::into_report)
        .unwrap();
    assert_eq!(report.event_log_omitted, 0);
    assert_eq!(
        report.event_log.as_ref().unwrap().len() as u64,
        report.events().total()
    );
}

#[test]
fn messages_tiny_mass_is_blamed_on_the_mass() {
    let e = parse(
        "[motor]\nslider_mass = 5e-324\ncontact_force = 1\nmu_static = 0.2\nmu_dynamic = 0.1\n",
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains(
            "motor.slider_mass = 5e-324: with motor.mu_static = 0.2 and \
             motor.contact_force = 1 gives the break-away acceleration a_0"
        ),
        "{e}"
    );
    // A force so large that mu_0 F_c overflows is blamed on the force.
    let e = parse(
        "[motor]\nslider_mass = 1\ncontact_force = 1e308\nmu_static = 10\nmu_dynamic = 0.1\n",
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("motor.contact_force = 1e308: with"), "{e}");
}

#[test]
fn messages_numbers_print_in_scientific_notation() {
    for (x, shown) in [
        (5e-324, "5e-324"),
        (1e300, "1e300"),
        (-2.5e-5, "-2.5e-5"),
        (1.5e9 + 0.5, "1.5000000005e9"),
        (0.2, "0.2"),
        (-3.0, "-3"),
        (4294967295.0, "4294967295"),
        (0.0, "0"),
        (f64::INFINITY, "inf"),
    ] {
        assert_eq!(Num(x).to_string(), shown);
    }
    let e = ParamError::positive("signal.stroke", -1e-300).unwrap_err();
    assert_eq!(e.to_string(), "signal.stroke = -1e-300: must be positive");
    // kappa = 1e-320 with the paper's a_0 = 124 m/s^2: a_R is subnormal and
    // T = sqrt(2 x_Rmax / a_R) overflows. The message once printed a_R
    // with 318 zeros.
    let scene = parse("[signal]\nkind = \"ideal\"\nstroke = 25e-6\nkappa = 1e-320\n").unwrap();
    let e = scene.build().unwrap_err().to_string();
    assert!(e.contains("e-318 m/s^2 gives the period T = inf s"), "{e}");
    assert!(!e.contains("00000000"), "{e}");
}

#[test]
fn messages_toml_syntax_error_names_the_key_and_shows_the_line() {
    let e = parse("[motor]\nslider_mass = = 1\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("motor.slider_mass: "), "{e}");
    assert!(
        e.contains("(line 2, column 15: `slider_mass = = 1`)"),
        "{e}"
    );
    let e = parse("[signal]\nkind = \"fourier\"\nharmonics 2\n")
        .unwrap_err()
        .to_string();
    assert!(e.contains("signal.harmonics: "), "{e}");
    assert!(e.contains("`harmonics 2`"), "{e}");
    assert_eq!(e.lines().count(), 1);
}

#[test]
fn input_size_large_file_refused_with_its_size() {
    // Newlines only: valid TOML (an empty scene) at any length.
    let limit = usize::try_from(MAX_INPUT_BYTES).unwrap();
    let at_limit = temp_file("at_limit.toml", &vec![b'\n'; limit]);
    assert_eq!(
        Scene::from_path(&at_limit).unwrap().signal,
        SignalSpec::paper_default()
    );
    let over = temp_file("over.toml", &vec![b'\n'; 50 << 20]);
    let e = Scene::from_path(&over).unwrap_err().to_string();
    assert!(
        e.ends_with(
            "the file holds 52428800 bytes; input files are limited to 1048576 bytes (1 MiB)"
        ),
        "{e}"
    );
    std::fs::remove_file(at_limit).unwrap();
    std::fs::remove_file(over).unwrap();
}

#[cfg(target_os = "linux")]
#[test]
fn input_size_endless_stream_refused() {
    let clock = Instant::now();
    let e = read_input(std::path::Path::new("/dev/zero")).unwrap_err();
    assert_eq!(e.kind(), std::io::ErrorKind::InvalidData);
    assert!(e.to_string().contains("more than 1048576 bytes"), "{e}");
    assert!(clock.elapsed() < Duration::from_secs(5));
}
